//! Tangential contact: the coupled exact solver against closed forms (model.md section 13).

use contactwave::analytic::friction::ClippedShear;
use contactwave::excitation::{Excitation, ToneBurst, Window};
use contactwave::law::registry::{build_law, build_tangential};
use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use contactwave::material::Material;
use contactwave::solver::coupled::{CoupledHalfSpace, CoupledSolver};
use contactwave::solver::halfspace::{ExactSolver, HalfSpace, HalfSpaceSettings};
use contactwave::solver::Solver;
use std::sync::Arc;

const AL: Material = Material::ALUMINIUM;

fn problem(
    p0: f64,
    comp: CompressionSpec,
    trac: TractionSpec,
    tang: TangentialSpec,
    q0: f64,
    normal: Arc<dyn Excitation>,
    shear: Arc<dyn Excitation>,
) -> CoupledHalfSpace {
    let law = build_law(p0, &comp, &trac, "<test>", "interface").unwrap();
    let tl = build_tangential(&tang, q0, &law, "<test>", "interface").unwrap();
    let zt = AL.density * 3100.0;
    CoupledHalfSpace {
        normal: HalfSpace::new(AL, Some(AL), Arc::new(law), normal),
        z1t: zt,
        z2t: zt,
        tangential: Arc::new(tl),
        shear_incident: shear,
        oblique: None,
    }
}

fn silent(f: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(0.0, f, 10.0, Window::Rectangular))
}

#[test]
fn rigid_stick_clipping_matches_closed_form() {
    let f = 1e6;
    let (a, p0, mu) = (5e6, 10e6, 0.3);
    let burst = Arc::new(ToneBurst::new(a, f, 10.0, Window::Rectangular));
    let p = problem(
        p0,
        CompressionSpec::Rigid,
        TractionSpec::Free,
        TangentialSpec::Coulomb {
            friction: mu,
            stiffness: None,
        },
        0.0,
        silent(f),
        burst.clone(),
    );
    let solver = CoupledSolver {
        settings: HalfSpaceSettings {
            samples_per_period: 1000,
            ..Default::default()
        },
    };
    let t0 = std::time::Instant::now();
    let out = solver.solve(&p).unwrap();
    eprintln!(
        "solve {:?}, {} samples, {} slip events",
        t0.elapsed(),
        out.shear.t.len(),
        out.slip_events
    );
    let c = mu * p0;
    let mut err: f64 = 0.0;
    for (i, &t) in out.shear.t.iter().enumerate() {
        let s = burst.stress(t).clamp(-c, c);
        err = err.max((out.shear.transmitted_stress[i] - s).abs());
    }
    eprintln!("max |tau_tr - clip| = {err:e}");
    assert!(err < 1e-9 * a);
    // harmonics over the burst's 10 whole periods
    let dt = out.shear.dt;
    let n_per = (1.0 / (f * dt)).round() as usize;
    for n in [1usize, 3, 5, 7] {
        let (mut cs, mut sn) = (0.0, 0.0);
        for k in 0..10 * n_per {
            let t = k as f64 * dt;
            let w = 2.0 * std::f64::consts::PI * f * n as f64 * t;
            let v = out.shear.transmitted_stress[k];
            cs += v * w.cos();
            sn += v * w.sin();
        }
        let amp = 2.0 * (cs * cs + sn * sn).sqrt() / (10 * n_per) as f64;
        let exact = ClippedShear {
            amplitude: a,
            omega: 2.0 * std::f64::consts::PI * f,
            z1: 1.0,
            z2: 1.0,
            limit: c,
        }
        .transmitted_harmonic(n)
        .abs();
        eprintln!("n = {n}: {amp:e} vs {exact:e}: {:e}", amp / exact - 1.0);
        assert!((amp / exact - 1.0).abs() < 1e-4);
    }
    eprintln!(
        "closure {:e}, friction {:e}",
        out.closure_error(),
        out.friction_dissipation
    );
    assert!(out.closure_error() < 1e-6);
}

#[test]
fn no_shear_reproduces_the_normal_solver() {
    let f = 1e6;
    let burst: Arc<dyn Excitation> = Arc::new(ToneBurst::new(
        1.6e6,
        f,
        15.0,
        Window::HannRamps {
            ramp_fraction: 0.25,
        },
    ));
    let trac = TractionSpec::Rccm {
        stiffness: 2e13,
        energy: 0.1,
        viscosity: 0.0,
    };
    let p = problem(
        0.82e6,
        CompressionSpec::Rigid,
        trac,
        TangentialSpec::Rccm {
            stiffness: 1e13,
            friction: 0.5,
        },
        0.0,
        burst,
        silent(f),
    );
    let reference = ExactSolver::default().solve(&p.normal).unwrap();
    let out = CoupledSolver::default().solve(&p).unwrap();
    let n = reference.t.len().min(out.normal.t.len());
    let scale = reference
        .reflected_stress
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let mut err: f64 = 0.0;
    for i in 0..n {
        err = err.max((reference.reflected_stress[i] - out.normal.reflected_stress[i]).abs());
    }
    eprintln!(
        "len {} vs {}, max diff {:e} (scale {scale:e}); beta {} vs {}; closure {:e}",
        reference.t.len(),
        out.normal.t.len(),
        err,
        reference.beta.last().unwrap(),
        out.normal.beta.last().unwrap(),
        out.closure_error()
    );
    assert!(err < 1e-6 * scale);
}

fn hann(a: f64, f: f64, cycles: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(
        a,
        f,
        cycles,
        Window::HannRamps {
            ramp_fraction: 0.25,
        },
    ))
}

/// name, p0, compression, traction, tangential, q0, normal and shear amplitudes
type Case = (
    &'static str,
    f64,
    CompressionSpec,
    TractionSpec,
    TangentialSpec,
    f64,
    f64,
    f64,
);

#[test]
fn energy_audit_closes_on_combined_loading() {
    let f = 1e6;
    let cases: Vec<Case> = vec![
        (
            "rccm full, damaging, normal + shear",
            0.82e6,
            CompressionSpec::Rigid,
            TractionSpec::Rccm {
                stiffness: 2e13,
                energy: 0.1,
                viscosity: 0.0,
            },
            TangentialSpec::Rccm {
                stiffness: 1e13,
                friction: 0.4,
            },
            0.0,
            3e6,
            2e6,
        ),
        (
            "rccm full, viscous",
            0.82e6,
            CompressionSpec::Rigid,
            TractionSpec::Rccm {
                stiffness: 2e13,
                energy: 0.1,
                viscosity: 1e-7,
            },
            TangentialSpec::Rccm {
                stiffness: 1e13,
                friction: 0.4,
            },
            0.0,
            3e6,
            2e6,
        ),
        (
            "power law + elastic-stick coulomb, static shear",
            5e6,
            CompressionSpec::Power { c: 4e9, m: 0.5 },
            TractionSpec::Free,
            TangentialSpec::Coulomb {
                friction: 0.5,
                stiffness: Some(5e12),
            },
            1e6,
            4e6,
            2e6,
        ),
        (
            "linear compression + rigid coulomb, clapping",
            1e6,
            CompressionSpec::Linear { stiffness: 1e13 },
            TractionSpec::Free,
            TangentialSpec::Coulomb {
                friction: 0.6,
                stiffness: None,
            },
            0.2e6,
            3e6,
            1e6,
        ),
        (
            "linear tangential spring",
            1e6,
            CompressionSpec::Rigid,
            TractionSpec::Free,
            TangentialSpec::Linear { stiffness: 1e13 },
            0.5e6,
            0.5e6,
            1e6,
        ),
    ];
    for (name, p0, comp, trac, tang, q0, sn, st) in cases {
        let p = problem(
            p0,
            comp,
            trac,
            tang,
            q0,
            hann(sn, f, 15.0),
            hann(st, f, 15.0),
        );
        let t0 = std::time::Instant::now();
        let out = CoupledSolver::default().solve(&p).unwrap();
        eprintln!(
            "{name}: {:?}, closure {:e}, friction {:e}, damage {:e}, beta {}, slip events {}, events {}, n {}",
            t0.elapsed(),
            out.closure_error(),
            out.friction_dissipation,
            out.normal.energy.damage,
            out.normal.beta.last().unwrap(),
            out.slip_events,
            out.normal.events,
            out.normal.t.len()
        );
        assert!(out.closure_error() < 1e-5, "{name}");
        assert!(out.friction_dissipation >= 0.0);
        // beta never increases
        assert!(
            out.normal.beta.windows(2).all(|w| w[1] <= w[0] + 1e-15),
            "{name}"
        );
    }
}

#[test]
fn every_tangential_validation_case_passes() {
    let cases = contactwave::study::validation::shear::run_all().unwrap();
    assert!(cases.len() >= 11);
    for c in &cases {
        assert!(c.passed(), "{c:?}");
    }
}

#[test]
fn static_shear_alone_keeps_the_interface_at_rest() {
    // a pre-stressed interface with no wave stays in equilibrium for every branch that can
    // carry q0: a spring (linear), a sticking slider (coulomb, |q0| < mu p0)
    let f = 1e6;
    for (tang, q0) in [
        (TangentialSpec::Linear { stiffness: 1e13 }, 0.5e6),
        (
            TangentialSpec::Coulomb {
                friction: 0.5,
                stiffness: Some(5e12),
            },
            1e6,
        ),
        (
            TangentialSpec::Coulomb {
                friction: 0.5,
                stiffness: None,
            },
            -1e6,
        ),
    ] {
        let p = problem(
            5e6,
            CompressionSpec::Linear { stiffness: 1e13 },
            TractionSpec::Free,
            tang.clone(),
            q0,
            silent(f),
            silent(f),
        );
        let out = CoupledSolver::default().solve(&p).unwrap();
        let drift = out.shear.gap.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert_eq!(drift, 0.0, "{tang:?}");
        assert!(out
            .shear
            .contact_stress
            .iter()
            .all(|&t| (t - q0).abs() < 1e-9 * q0.abs()));
    }
}

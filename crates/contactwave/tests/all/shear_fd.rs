//! Tangential contact on the bar-stack FD scheme (issue 11, item 4): the coupled FD
//! solver against the coupled exact solver and closed forms (model.md section 13).

use contactwave::analysis::velocity_bands;
use contactwave::excitation::{Excitation, ToneBurst, Window};
use contactwave::law::registry::{build_law, build_tangential};
use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use contactwave::material::Material;
use contactwave::solver::bar_stack::InterfaceScheme;
use contactwave::solver::coupled::{CoupledHalfSpace, CoupledOutput, CoupledSolver};
use contactwave::solver::half_space::{HalfSpace, HalfSpaceOutput, HalfSpaceSettings};
use contactwave::solver::half_space_fd::FdSolver;
use contactwave::solver::half_space_fd_shear::FdCoupledSolver;
use contactwave::solver::Solver;
use std::sync::Arc;

const AL: Material = Material::ALUMINIUM;
/// Shear wave speed of aluminium, m/s (until `Material` carries a shear modulus).
const CT_AL: f64 = 3100.0;

#[allow(clippy::too_many_arguments)]
fn problem(
    p0: f64,
    comp: CompressionSpec,
    trac: TractionSpec,
    tang: TangentialSpec,
    q0: f64,
    normal: Arc<dyn Excitation>,
    shear: Arc<dyn Excitation>,
    wall: bool,
) -> CoupledHalfSpace {
    let law = build_law(p0, &comp, &trac, "<test>", "interface").unwrap();
    let tl = build_tangential(&tang, q0, &law, "<test>", "interface").unwrap();
    let zt = AL.density * CT_AL;
    CoupledHalfSpace {
        normal: HalfSpace::new(AL, (!wall).then_some(AL), Arc::new(law), normal),
        z1t: zt,
        z2t: if wall { f64::INFINITY } else { zt },
        tangential: Arc::new(tl),
        shear_incident: shear,
        oblique: None,
    }
}

fn silent(f: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(0.0, f, 10.0, Window::Rectangular))
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

fn exact(p: &CoupledHalfSpace, spp: usize, tail: f64) -> CoupledOutput {
    CoupledSolver {
        settings: HalfSpaceSettings {
            samples_per_period: spp,
            tail_periods: Some(tail),
            summary_only: false,
        },
    }
    .solve(p)
    .unwrap()
}

fn fd(p: &CoupledHalfSpace, spp: usize, tail: f64) -> CoupledOutput {
    FdCoupledSolver {
        samples_per_period: spp,
        tail_periods: Some(tail),
        interface_scheme: InterfaceScheme::Average,
    }
    .solve(p)
    .unwrap()
}

/// Harmonic amplitudes A1, A3 (m/s) of the reflected and transmitted particle velocities.
fn harmonics(o: &HalfSpaceOutput, f0: f64) -> [f64; 4] {
    let r = velocity_bands(&o.reflected_displacement, o.dt, f0, None);
    let t = velocity_bands(&o.transmitted_displacement, o.dt, f0, None);
    [r.harmonic[1], r.harmonic[3], t.harmonic[1], t.harmonic[3]]
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// (a) Rigid-stick Coulomb between identical half-spaces under a shear burst: the
/// transmitted shear stress is the incident one clipped at mu p0, in the FD as in the
/// exact solver.
#[test]
fn rigid_stick_clipping_fd_matches_exact() {
    let f = 1e6;
    let (a, p0, mu) = (5e6, 10e6, 0.3);
    let burst = Arc::new(ToneBurst::new(a, f, 10.0, Window::Rectangular));
    let p = problem(
        p0,
        CompressionSpec::Rigid(Default::default()),
        TractionSpec::Free(Default::default()),
        TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
            friction: mu,
            stiffness: None,
        }),
        0.0,
        silent(f),
        burst.clone(),
        false,
    );
    let spp = 400;
    let t0 = std::time::Instant::now();
    let out = fd(&p, spp, 5.0);
    let t_fd = t0.elapsed();
    let t0 = std::time::Instant::now();
    let ex = exact(&p, spp, 5.0);
    let t_ex = t0.elapsed();
    let c = mu * p0;
    // sample by sample, the FD transmitted stress is the clipped incident
    let err = out
        .shear
        .t
        .iter()
        .zip(&out.shear.transmitted_stress)
        .fold(0.0f64, |m, (&t, &s)| {
            m.max((s - burst.stress(t).clamp(-c, c)).abs())
        });
    let n = out.shear.t.len().min(ex.shear.t.len());
    let diff = max_diff(
        &out.shear.transmitted_stress[..n],
        &ex.shear.transmitted_stress[..n],
    );
    eprintln!(
        "clipping: FD {t_fd:?}, exact {t_ex:?}; max |tau_tr - clip| = {err:e} Pa, \
         max |FD - exact| = {diff:e} Pa; slip events {} vs {}",
        out.slip_events, ex.slip_events
    );
    // the switches are placed to within a step: within a step's change of the burst
    let step_change = 2.0 * std::f64::consts::PI * a / spp as f64;
    assert!(err < step_change, "{err:e}");
    assert!(diff < step_change, "{diff:e}");
    // harmonics of the reflected and transmitted velocities (the exact solver's match the
    // clipped sine's Fourier series: tests/all/shear.rs)
    let h_fd = harmonics(&out.shear, f);
    let h_ex = harmonics(&ex.shear, f);
    for i in 0..4 {
        let rel = h_fd[i] / h_ex[i] - 1.0;
        eprintln!(
            "clipping harmonic {i}: FD {:e}, exact {:e}: {rel:e}",
            h_fd[i], h_ex[i]
        );
        assert!(rel.abs() < 1e-3);
    }
    // slips forward and back each half period: at least two switches per period
    assert!(out.slip_events >= 20);
    assert!(out.friction_dissipation > 0.0);
}

/// (b) Full RCCM with damage under normal and shear bursts: the FD and the exact solver
/// agree to 1% on the reflected and transmitted shear harmonics A1, A3 and on beta_end.
#[test]
fn full_rccm_fd_matches_exact_to_one_percent() {
    let f = 1e6;
    let p = problem(
        0.82e6,
        CompressionSpec::Rigid(Default::default()),
        TractionSpec::Rccm(contactwave::law::traction::rccm::Spec {
            stiffness: 2e13,
            energy: 0.1,
            viscosity: 0.0,
        }),
        TangentialSpec::Rccm(contactwave::law::tangential::rccm::Spec {
            stiffness: 1e13,
            friction: 0.4,
        }),
        0.0,
        hann(3e6, f, 15.0),
        hann(2e6, f, 15.0),
        false,
    );
    let spp = 1000;
    let tail = 20.0;
    let t0 = std::time::Instant::now();
    let out = fd(&p, spp, tail);
    let t_fd = t0.elapsed();
    let t0 = std::time::Instant::now();
    let ex = exact(&p, spp, tail);
    let t_ex = t0.elapsed();
    let (b_fd, b_ex) = (
        *out.normal.beta.last().unwrap(),
        *ex.normal.beta.last().unwrap(),
    );
    eprintln!(
        "full RCCM, spp {spp}: FD {t_fd:?} ({} samples), exact {t_ex:?} ({} samples); \
         beta_end {b_fd} vs {b_ex} ({:e})",
        out.shear.t.len(),
        ex.shear.t.len(),
        b_fd / b_ex - 1.0
    );
    assert!(b_ex < 0.9, "the case must damage: beta_end = {b_ex}");
    assert!((b_fd / b_ex - 1.0).abs() < 0.01);
    let h_fd = harmonics(&out.shear, f);
    let h_ex = harmonics(&ex.shear, f);
    let names = [
        "reflected A1",
        "reflected A3",
        "transmitted A1",
        "transmitted A3",
    ];
    for i in 0..4 {
        let rel = h_fd[i] / h_ex[i] - 1.0;
        eprintln!(
            "shear {}: FD {:e}, exact {:e}: {rel:e}",
            names[i], h_fd[i], h_ex[i]
        );
        assert!(rel.abs() < 0.01, "{}: {rel:e}", names[i]);
    }
    let n_fd = harmonics(&out.normal, f);
    let n_ex = harmonics(&ex.normal, f);
    for i in 0..4 {
        eprintln!(
            "normal {}: FD {:e}, exact {:e}: {:e}",
            names[i],
            n_fd[i],
            n_ex[i],
            n_fd[i] / n_ex[i] - 1.0
        );
    }
    // the shear A3 is a real nonlinearity, not noise
    assert!(h_ex[1] > 1e-3 * h_ex[0]);
}

/// (c) The FD energy audit closes to the time discretisation error, and converges.
#[test]
fn fd_energy_audit_closes() {
    let f = 1e6;
    let cases: Vec<(&str, CoupledHalfSpace)> = vec![
        (
            "full RCCM",
            problem(
                0.82e6,
                CompressionSpec::Rigid(Default::default()),
                TractionSpec::Rccm(contactwave::law::traction::rccm::Spec {
                    stiffness: 2e13,
                    energy: 0.1,
                    viscosity: 0.0,
                }),
                TangentialSpec::Rccm(contactwave::law::tangential::rccm::Spec {
                    stiffness: 1e13,
                    friction: 0.4,
                }),
                0.0,
                hann(3e6, f, 15.0),
                hann(2e6, f, 15.0),
                false,
            ),
        ),
        (
            "power law + elastic-stick coulomb, static shear",
            problem(
                5e6,
                CompressionSpec::Power(contactwave::law::compression::power::Spec {
                    c: 4e9,
                    m: 0.5,
                }),
                TractionSpec::Free(Default::default()),
                TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
                    friction: 0.3,
                    stiffness: Some(5e12),
                }),
                1e6,
                hann(4e6, f, 15.0),
                hann(4e6, f, 15.0),
                false,
            ),
        ),
    ];
    for (name, p) in cases {
        let mut errs = vec![];
        for spp in [250, 1000] {
            let out = fd(&p, spp, 20.0);
            let e = out.closure_error();
            eprintln!(
                "{name}, spp {spp}: closure {e:e}, friction {:e}, damage {:e}, incident {:e}",
                out.friction_dissipation,
                out.normal.energy.damage,
                out.incident_energy()
            );
            assert!(out.friction_dissipation >= 0.0);
            errs.push(e);
        }
        assert!(errs[1] < 5e-3, "{name}: {errs:?}");
        assert!(errs[1] < errs[0], "{name}: {errs:?}");
        // and the FD matches the exact solver on the shear harmonics
        let (out, ex) = (fd(&p, 1000, 20.0), exact(&p, 1000, 20.0));
        let (h_fd, h_ex) = (harmonics(&out.shear, f), harmonics(&ex.shear, f));
        for i in 0..4 {
            let rel = h_fd[i] / h_ex[i] - 1.0;
            eprintln!(
                "{name}: shear harmonic {i}: {rel:e}; slip events {} vs {}",
                out.slip_events, ex.slip_events
            );
            assert!(rel.abs() < 0.01, "{name}: {i}: {rel:e}");
        }
        assert!(out.friction_dissipation > 0.0, "{name}: the case must slip");
    }
}

/// (d) mu = 0 is free sliding (the shear wave is reflected completely) and a very large mu
/// is bonded (transmitted completely), in the FD as in the exact solver.
#[test]
fn friction_limits_free_and_bonded() {
    let f = 1e6;
    let a = 2e6;
    for (mu, transmit) in [(0.0, false), (1e3, true)] {
        let p = problem(
            1e6,
            CompressionSpec::Linear(contactwave::law::compression::linear::Spec {
                stiffness: 1e13,
            }),
            TractionSpec::Free(Default::default()),
            TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
                friction: mu,
                stiffness: None,
            }),
            0.0,
            silent(f),
            hann(a, f, 10.0),
            false,
        );
        let out = fd(&p, 200, 5.0);
        let ex = exact(&p, 200, 5.0);
        let inc = &out.shear.incident_stress;
        let (tr, rf) = (&out.shear.transmitted_stress, &out.shear.reflected_stress);
        if transmit {
            // bonded: tau_tr = tau_inc and nothing reflected, exactly in the displacements
            // (Courant 1), to the centred difference's O((omega dt)^2 / 6) in the stresses
            let u_inc = &out.shear.incident_displacement;
            let u_max = max_abs(u_inc);
            let d_tr = max_diff(&out.shear.transmitted_displacement, u_inc);
            let d_rf = max_abs(&out.shear.reflected_displacement);
            eprintln!(
                "bonded: displacement errors {:e}, {:e}; stress {:e}",
                d_tr / u_max,
                d_rf / u_max,
                max_diff(tr, inc) / a
            );
            assert!(d_tr < 1e-9 * u_max && d_rf < 1e-9 * u_max);
            let wdt = 2.0 * std::f64::consts::PI / 200.0;
            assert!(max_diff(tr, inc) < 0.2 * wdt * wdt * a);
            assert!(max_abs(rf) < 0.2 * wdt * wdt * a);
            assert_eq!(out.slip_events, 0);
            assert!(out.slip_state.iter().all(|s| *s == 0.0));
        } else {
            // free: tau = 0, total reflection (reflected = -incident)
            assert!(max_abs(tr) < 1e-9 * a, "mu {mu}: {:e}", max_abs(tr));
            let neg: Vec<f64> = inc.iter().map(|v| -v).collect();
            assert!(max_diff(rf, &neg) < 1e-9 * a);
        }
        let n = out.shear.t.len().min(ex.shear.t.len());
        let d = max_diff(
            &out.shear.transmitted_stress[..n],
            &ex.shear.transmitted_stress[..n],
        );
        eprintln!("mu {mu}: max |FD - exact| transmitted shear {d:e} Pa");
        assert!(d < 1e-3 * a);
    }
}

/// With no shear wave and no tangential coupling, the coupled FD's normal histories are
/// those of the normal-only FD solver.
#[test]
fn no_shear_reproduces_the_normal_fd() {
    let f = 1e6;
    let p = problem(
        0.82e6,
        CompressionSpec::Rigid(Default::default()),
        TractionSpec::Rccm(contactwave::law::traction::rccm::Spec {
            stiffness: 2e13,
            energy: 0.1,
            viscosity: 1e-8,
        }),
        TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
            friction: 0.5,
            stiffness: None,
        }),
        0.0,
        hann(1.6e6, f, 15.0),
        silent(f),
        false,
    );
    let spp = 300;
    let reference = FdSolver {
        samples_per_period: spp,
        tail_periods: Some(10.0),
        interface_scheme: InterfaceScheme::Average,
    }
    .solve(&p.normal)
    .unwrap();
    let out = fd(&p, spp, 10.0);
    let n = reference.t.len().min(out.normal.t.len());
    assert!(n > 20 * spp);
    let scale = max_abs(&reference.reflected_stress);
    let d_stress = max_diff(
        &reference.reflected_stress[..n],
        &out.normal.reflected_stress[..n],
    );
    let d_disp = max_diff(
        &reference.reflected_displacement[..n],
        &out.normal.reflected_displacement[..n],
    );
    let d_beta = max_diff(&reference.beta[..n], &out.normal.beta[..n]);
    eprintln!("stress {d_stress:e} (scale {scale:e}), displacement {d_disp:e}, beta {d_beta:e}");
    assert!(d_stress < 1e-9 * scale);
    assert!(d_disp < 1e-9 * max_abs(&reference.reflected_displacement));
    assert!(d_beta < 1e-12);
    // and the shear field stays at rest
    assert!(max_abs(&out.shear.transmitted_stress) == 0.0);
}

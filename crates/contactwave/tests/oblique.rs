//! Oblique incidence (model.md section 14): the exact coupled solver with the plane-wave
//! compliances against the closed-form coefficients of a spring interface and of a
//! welded one (Zoeppritz), the normal-incidence solvers at theta = 0, and the energy audit.

use contactwave::analytic::oblique::{coefficients, Bond, Elastic, Geometry, WaveType};
use contactwave::excitation::{Excitation, ToneBurst, Window};
use contactwave::law::registry::{build_law, build_tangential};
use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use contactwave::material::Material;
use contactwave::solver::coupled::{CoupledHalfSpace, CoupledOutput, CoupledSolver};
use contactwave::solver::halfspace::HalfSpaceSettings;
use contactwave::solver::Solver;
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;
use std::sync::Arc;

const AL: Material = Material::ALUMINIUM;
const STEEL: Material = Material::STEEL;
const F0: f64 = 1e6;

fn elastic(m: &Material) -> Elastic {
    Elastic {
        density: m.density,
        cp: m.wave_speed(),
        cs: m.shear_wave_speed().unwrap(),
    }
}

/// Linear springs K_N (compression and traction alike: a linear interface) and K_T.
fn springs(
    wave: WaveType,
    deg: f64,
    counterpart: Option<Material>,
    kn: f64,
    kt: f64,
) -> (CoupledHalfSpace, Geometry, Arc<dyn Excitation>) {
    let p0 = 50e6;
    let law = build_law(
        p0,
        &CompressionSpec::Linear { stiffness: kn },
        &TractionSpec::Linear { stiffness: kn },
        "<test>",
        "interface",
    )
    .unwrap();
    let tl = build_tangential(
        &TangentialSpec::Linear { stiffness: kt },
        0.0,
        &law,
        "<test>",
        "interface",
    )
    .unwrap();
    let e2 = counterpart.as_ref().map(elastic);
    let g = Geometry::new(&elastic(&AL), e2.as_ref(), wave, deg.to_radians()).unwrap();
    let burst: Arc<dyn Excitation> = Arc::new(ToneBurst::new(1e6, F0, 8.0, Window::Hann));
    let p = CoupledHalfSpace::oblique(
        AL,
        counterpart,
        Arc::new(law),
        Arc::new(tl),
        &g,
        burst.clone(),
    );
    (p, g, burst)
}

fn run(p: &CoupledHalfSpace, spp: usize, tail: f64) -> CoupledOutput {
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

/// Fourier sums at f0 of the outgoing waves' particle velocities over the incident's:
/// `[R_P, R_SV, T_P, T_SV]`.
fn measured(out: &CoupledOutput, g: &Geometry, burst: &dyn Excitation) -> [Complex64; 4] {
    let w = 2.0 * PI * F0;
    let rw = Geometry::traction_to_waves(&g.reflected);
    let tw = g.transmitted.map(|t| Geometry::traction_to_waves(&t));
    let mut acc = [Complex64::new(0.0, 0.0); 5];
    for (k, &t) in out.normal.t.iter().enumerate() {
        let e = Complex64::from_polar(1.0, -w * t);
        let winc = -burst.stress(t) / g.incident.impedance;
        acc[4] += e * winc;
        let r = [
            out.normal.reflected_stress[k],
            out.shear.reflected_stress[k],
        ];
        let s = [
            out.normal.transmitted_stress[k],
            out.shear.transmitted_stress[k],
        ];
        for j in 0..2 {
            acc[j] += e * (rw[j][0] * r[0] + rw[j][1] * r[1]);
            if let Some(m) = &tw {
                acc[2 + j] += e * (m[j][0] * s[0] + m[j][1] * s[1]);
            }
        }
    }
    [
        acc[0] / acc[4],
        acc[1] / acc[4],
        acc[2] / acc[4],
        acc[3] / acc[4],
    ]
}

fn max_err(a: &[Complex64; 4], b: &[Complex64; 4]) -> f64 {
    (0..4).map(|k| (a[k] - b[k]).norm()).fold(0.0, f64::max)
}

#[test]
fn spring_interface_matches_closed_form() {
    // omega Z / K of order 1: strong, frequency-dependent mode conversion
    let (kn, kt) = (2e14, 1e14);
    for (wave, deg, cp) in [
        (WaveType::P, 22.5, Some(STEEL)),
        (WaveType::P, 45.0, Some(STEEL)),
        (WaveType::Sv, 20.0, Some(STEEL)),
        (WaveType::P, 30.0, None),
        (WaveType::Sv, 25.0, None),
    ] {
        let (p, g, burst) = springs(wave, deg, cp, kn, kt);
        let out = run(&p, 200, 40.0);
        let m = measured(&out, &g, &*burst);
        let c = coefficients(
            &g,
            Bond::Springs {
                normal: kn,
                tangential: kt,
            },
            2.0 * PI * F0,
        );
        let err = max_err(&m, &c);
        eprintln!(
            "{} {deg} deg {}: |R_P| {:.6} |R_SV| {:.6} |T_P| {:.6} |T_SV| {:.6}; max error {err:.2e}; closure {:.1e}",
            wave.name(),
            if cp.is_some() { "Al/steel" } else { "Al/wall" },
            c[0].norm(),
            c[1].norm(),
            c[2].norm(),
            c[3].norm(),
            out.closure_error()
        );
        assert!(err < 1e-6, "{err}");
        // mode conversion is there
        assert!(c[1].norm() > 0.05 && c[0].norm() > 0.05);
        // elastic interface: the energy audit closes, and the wave energies add up to
        // the component fluxes (P and SV carry no cross flux)
        assert!(out.closure_error() < 1e-9, "{}", out.closure_error());
        let n = &out.normal.energy;
        let s = &out.shear.energy;
        let waves: f64 = out.wave_energy.iter().sum();
        let comps = n.reflected + s.reflected + n.transmitted + s.transmitted;
        assert!((waves - comps).abs() < 1e-9 * comps, "{waves} {comps}");
    }
}

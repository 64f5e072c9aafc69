//! Oblique incidence (model.md section 14): the exact coupled solver with the plane-wave
//! compliances against the closed-form coefficients of a spring interface and of a
//! welded one (Zoeppritz), the normal-incidence solvers at theta = 0, and the energy audit.

use contactwave::analytic::oblique::{coefficients, Bond, Elastic, Geometry, WaveType};
use contactwave::excitation::{Excitation, ToneBurst, Window};
use contactwave::law::registry::{build_law, build_tangential};
use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use contactwave::material::Material;
use contactwave::solver::coupled::{CoupledHalfSpace, CoupledOutput, CoupledSolver};
use contactwave::solver::half_space::HalfSpaceSettings;
use contactwave::solver::Solver;
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;
use std::sync::Arc;

const AL: Material = Material::ALUMINIUM;
const STEEL: Material = Material::STEEL;
const F0: f64 = 1e6;

/// A preset as a scenario gives it to a half-space: the P-wave modulus of its E and nu.
fn half_space(m: Material) -> Material {
    m.half_space(m.poisson_ratio().unwrap())
}

fn elastic(m: &Material) -> Elastic {
    Elastic {
        density: m.density,
        cp: m.wave_speed(),
        cs: m.shear_wave_speed().unwrap(),
    }
}

/// Closed-form coefficients of linear springs `kn`, `kt` (Pa/m) at `F0`.
fn spring_coefficients(
    g: &Geometry,
    kn: f64,
    kt: f64,
) -> contactwave::analytic::oblique::Coefficients {
    let bond = Bond::Springs {
        normal: kn,
        tangential: kt,
    };
    coefficients(g, bond, 2.0 * PI * F0)
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
        &CompressionSpec::Linear(contactwave::law::compression::linear::Spec { stiffness: kn }),
        &TractionSpec::Linear(contactwave::law::traction::linear::Spec { stiffness: kn }),
        "<test>",
        "interface",
    )
    .unwrap();
    let tl = build_tangential(
        &TangentialSpec::Linear(contactwave::law::tangential::linear::Spec { stiffness: kt }),
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
/// `[R_P, R_SV, T_P, T_SV]` (the library's measurement, `transfer_at`).
fn measured(out: &CoupledOutput, g: &Geometry, burst: &dyn Excitation) -> [Complex64; 4] {
    contactwave::model::half_space::oblique::transfer_at(out, g, burst, F0)
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
        let c = spring_coefficients(&g, kn, kt);
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

#[test]
fn stiff_springs_give_the_zoeppritz_coefficients() {
    // K >> omega Z: the welded limit, error O(omega Z / K)
    let k = 1e20;
    for (wave, deg) in [
        (WaveType::P, 22.5),
        (WaveType::P, 45.0),
        (WaveType::Sv, 20.0),
    ] {
        let (p, g, burst) = springs(wave, deg, Some(STEEL), k, k);
        let out = run(&p, 200, 10.0);
        let m = measured(&out, &g, &*burst);
        let z = coefficients(&g, Bond::Welded, 2.0 * PI * F0);
        let err = max_err(&m, &z);
        eprintln!(
            "{} {deg} deg welded: R_P {:.6} R_SV {:.6} T_P {:.6} T_SV {:.6}; max error {err:.2e}",
            wave.name(),
            z[0],
            z[1],
            z[2],
            z[3]
        );
        assert!(err < 1e-4, "{err}");
    }
}

/// The same interface at normal incidence through the normal-incidence path.
fn normal_incidence(wave: WaveType) -> (CoupledHalfSpace, CoupledHalfSpace) {
    let (oblique, _, burst) = springs(wave, 0.0, Some(STEEL), 2e14, 1e14);
    let silent: Arc<dyn Excitation> = Arc::new(ToneBurst::new(0.0, F0, 1.0, Window::Rectangular));
    let (n, s) = match wave {
        WaveType::P => (burst, silent),
        WaveType::Sv => (silent, burst),
    };
    let mut normal = oblique.clone();
    normal.normal = contactwave::solver::half_space::HalfSpace::new(
        AL,
        Some(STEEL),
        normal.normal.law.clone(),
        n,
    );
    normal.z1t = AL.shear_impedance().unwrap();
    normal.z2t = STEEL.shear_impedance().unwrap();
    normal.shear_incident = s;
    normal.oblique = None;
    (oblique, normal)
}

#[test]
fn zero_angle_is_the_normal_incidence_solver() {
    for wave in [WaveType::P, WaveType::Sv] {
        let (o, n) = normal_incidence(wave);
        let (a, b) = (run(&o, 200, 20.0), run(&n, 200, 20.0));
        assert_eq!(a.normal.t.len(), b.normal.t.len());
        let mut err: f64 = 0.0;
        for (x, y) in [
            (&a.normal.reflected_stress, &b.normal.reflected_stress),
            (&a.shear.reflected_stress, &b.shear.reflected_stress),
            (&a.normal.transmitted_stress, &b.normal.transmitted_stress),
            (&a.shear.transmitted_stress, &b.shear.transmitted_stress),
            (&a.normal.gap, &b.normal.gap),
            (&a.shear.gap, &b.shear.gap),
        ] {
            let scale = y.iter().fold(1e-30f64, |m, v| m.max(v.abs()));
            for (u, v) in x.iter().zip(y.iter()) {
                err = err.max((u - v).abs() / scale);
            }
        }
        eprintln!("{} at 0 deg vs normal incidence: {err:.1e}", wave.name());
        assert!(err < 1e-12, "{err}");
    }
}

/// Nonlinear interfaces at 30 degrees between aluminium and steel: clapping, stick-slip
/// and damage with the coupled constraint stresses; the energy audit closes.
#[test]
fn energy_audit_closes_with_clapping_friction_and_damage() {
    let cases: Vec<(&str, CompressionSpec, TractionSpec, TangentialSpec)> = vec![
        (
            "Signorini + Coulomb (rigid stick)",
            CompressionSpec::Rigid(Default::default()),
            TractionSpec::Free(Default::default()),
            TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
                friction: 0.3,
                stiffness: None,
            }),
        ),
        (
            "linear + Coulomb (elastic stick)",
            CompressionSpec::Linear(contactwave::law::compression::linear::Spec {
                stiffness: 5e14,
            }),
            TractionSpec::Free(Default::default()),
            TangentialSpec::Coulomb(contactwave::law::tangential::coulomb::Spec {
                friction: 0.3,
                stiffness: Some(2e14),
            }),
        ),
        (
            "Signorini + RCCM (damage, friction)",
            CompressionSpec::Rigid(Default::default()),
            TractionSpec::Rccm(contactwave::law::traction::rccm::Spec {
                stiffness: 1e14,
                energy: 0.02,
                viscosity: 0.0,
            }),
            TangentialSpec::Rccm(contactwave::law::tangential::rccm::Spec {
                stiffness: 5e13,
                friction: 0.3,
            }),
        ),
    ];
    for (name, comp, trac, tang) in cases {
        for wave in [WaveType::P, WaveType::Sv] {
            let p0 = 2e6;
            let law = build_law(p0, &comp, &trac, "<test>", "interface").unwrap();
            let tl = build_tangential(&tang, 0.0, &law, "<test>", "interface").unwrap();
            let g = Geometry::new(
                &elastic(&AL),
                Some(&elastic(&STEEL)),
                wave,
                20f64.to_radians(),
            )
            .unwrap();
            let burst: Arc<dyn Excitation> = Arc::new(ToneBurst::new(
                3e6,
                F0,
                6.0,
                Window::HannRamps {
                    ramp_fraction: 0.25,
                },
            ));
            let p =
                CoupledHalfSpace::oblique(AL, Some(STEEL), Arc::new(law), Arc::new(tl), &g, burst);
            let out = run(&p, 400, 10.0);
            let err = out.closure_error();
            eprintln!(
                "{name}, {}: closure {err:.1e}, events {}, slip events {}, friction {:.3e} J/m^2, damage {:.3e}",
                wave.name(),
                out.normal.events,
                out.slip_events,
                out.friction_dissipation,
                out.normal.energy.damage
            );
            assert!(out.normal.events > 0, "the interface must open");
            assert!(out.slip_events > 0, "the interface must slip");
            if name.contains("RCCM") {
                assert!(out.normal.energy.damage > 0.0);
            }
            assert!(err < 1e-6, "{err}");
        }
    }
}

#[test]
fn scenario_refuses_angles_beyond_the_critical_one() {
    use contactwave::scenario::Scenario;
    let text = |deg: f64| {
        format!(
            "[medium]\nmaterial = \"aluminium\"\n[interface]\nstatic_pressure = 1e6\n\
             [shear_incident]\nangle = {deg:?}\nfrequency = 1e6\ncycles = 5\namplitude = 1e6\n"
        )
    };
    let al = half_space(AL);
    let crit = (al.shear_wave_speed().unwrap() / al.wave_speed())
        .asin()
        .to_degrees();
    let ok = Scenario::from_toml_str(&text(crit - 0.1), "s.toml").unwrap();
    assert!(ok.oblique.is_some());
    let e = Scenario::from_toml_str(&text(crit + 0.1), "s.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("field `shear_incident.angle`"), "{e}");
    assert!(e.contains(&format!("{crit:.6}")), "{e}");
    assert!(e.contains("reflected P wave"), "{e}");
    let e = Scenario::from_toml_str(&text(90.0), "s.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("[0, 90)"), "{e}");
}

/// The outgoing waves are analysed by the scenario's method: pulse inversion cancels a
/// linear interface's second harmonic in every wave (the band peak's leakage floor does
/// not), and on a clapping-free power-law contact with friction it agrees with the
/// plateau fit, a different extraction.
#[test]
fn each_wave_is_analysed_by_the_scenario_method() {
    use contactwave::scenario::Scenario;
    use contactwave::simulate_summary;
    let text = |interface: &str, method: &str| {
        format!(
            "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\n\
             material = \"steel\"\n[interface]\n{interface}\n[incident]\nangle = 30.0\n\
             frequency = 1e6\ncycles = 10\namplitude = 1e6\n[solver]\nsamples_per_period = 50\n\
             [analysis]\nmethod = \"{method}\"\n"
        )
    };
    let waves = [
        "reflected_P",
        "reflected_SV",
        "transmitted_P",
        "transmitted_SV",
    ];
    let linear = "static_pressure = 1e6\ncompression = { law = \"linear\", stiffness = 5e13 }\n\
                  traction = { law = \"linear\", stiffness = 5e13 }\n\
                  tangential = { law = \"linear\", stiffness = 2e13 }";
    let sum = |i: &str, m: &str| {
        simulate_summary(&Scenario::from_toml_str(&text(i, m), "s.toml").unwrap()).unwrap()
    };
    let pi = sum(linear, "pulse_inversion");
    let bp = sum(linear, "band_peak");
    for w in waves {
        let a1 = pi.get(&format!("{w}_A1_over_Ainc")).unwrap();
        assert!(a1 > 0.01, "{w}: {a1}");
        assert!(pi.get(&format!("{w}_A2_over_A1")).unwrap() < 1e-9, "{w}");
        // the band peak reads the fundamental's leakage as a second harmonic
        assert!(bp.get(&format!("{w}_A2_over_A1")).unwrap() > 1e-4, "{w}");
        let a1_bp = bp.get(&format!("{w}_A1_over_Ainc")).unwrap();
        assert!((a1 / a1_bp - 1.0).abs() < 1e-9, "{w}: {a1} {a1_bp}");
    }
    let rough = "static_pressure = 0.3e6\n\
                 compression = { law = \"power\", c = 1.81e10, m = 0.35 }\n\
                 tangential = { law = \"coulomb\", friction = 0.3 }";
    let pi = sum(rough, "pulse_inversion");
    let fit = sum(rough, "plateau_fit");
    let (a, b) = (
        pi.get("reflected_P_A2_over_A1").unwrap(),
        fit.get("reflected_P_A2_over_A1").unwrap(),
    );
    assert!(a > 1e-3 && (a / b - 1.0).abs() < 0.05, "{a} {b}");
}

/// The summary of an oblique run names its waves and components and normalises them all by
/// the incident wave (issue 24 item 5): `amplitude` and `A_inc` are the incident wave's
/// stress and particle velocity amplitude (what xi refers to), the incident burst's own
/// `incident_A1_over_Ainc` is its window's band peak (about 1, not the normal traction
/// component's 1.14), each outgoing wave's `A1/A_inc` is its closed-form coefficient, and
/// the interface components are `reflected_normal_*` / `reflected_tangential_*` /
/// `transmitted_tangential_*` over the same `A_inc`: the closed-form normal and tangential
/// particle velocities of the reflected field (linear springs, P at 45 degrees,
/// aluminium/steel, plateau fit). The old component keys are gone.
#[test]
fn oblique_summary_keys_name_the_wave_and_the_component() {
    use contactwave::scenario::Scenario;
    let (kn, kt) = (5e13, 2e13);
    let text = format!(
        "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\n\
         material = \"steel\"\n[interface]\nstatic_pressure = 50e6\n\
         compression = {{ law = \"linear\", stiffness = {kn:e} }}\n\
         traction = {{ law = \"linear\", stiffness = {kn:e} }}\n\
         tangential = {{ law = \"linear\", stiffness = {kt:e} }}\n[incident]\nangle = 45.0\n\
         frequency = 1e6\ncycles = 20\namplitude = 1e6\n[solver]\nsamples_per_period = 200\n\
         [analysis]\nmethod = \"plateau_fit\"\n"
    );
    let s = Scenario::from_toml_str(&text, "s.toml").unwrap();
    let sum = contactwave::simulate(&s).unwrap().summary;
    let get = |k: &str| sum.get(k).unwrap_or_else(|| panic!("{k} missing"));
    let (al, steel) = (half_space(AL), half_space(STEEL));
    let a_inc = 1e6 / (al.density * al.wave_speed());
    assert_eq!(get("amplitude"), 1e6);
    assert!((get("A_inc") / a_inc - 1.0).abs() < 1e-12);
    assert!((get("incident_A1_over_Ainc") - 1.0).abs() < 0.01);
    let g = Geometry::new(
        &elastic(&al),
        Some(&elastic(&steel)),
        WaveType::P,
        45f64.to_radians(),
    )
    .unwrap();
    let c = spring_coefficients(&g, kn, kt);
    let close = |k: &str, exact: f64| {
        let v = get(k);
        assert!((v / exact - 1.0).abs() < 1e-3, "{k}: {v} vs {exact}");
    };
    for (k, w) in [
        "reflected_P",
        "reflected_SV",
        "transmitted_P",
        "transmitted_SV",
    ]
    .iter()
    .enumerate()
    {
        close(&format!("{w}_A1_over_Ainc"), c[k].norm());
    }
    // the reflected field's particle velocity at the interface, per unit incident w
    let [rp, rs] = g.reflected;
    let [tp, ts] = g.transmitted.unwrap();
    let comp = |i: usize| (c[0] * rp.polarisation[i] + c[1] * rs.polarisation[i]).norm();
    close("reflected_normal_A1_over_Ainc", comp(0));
    close("reflected_tangential_A1_over_Ainc", comp(1));
    let tr = (c[2] * tp.polarisation[1] + c[3] * ts.polarisation[1]).norm();
    close("transmitted_tangential_A1_over_Ainc", tr);
    for gone in [
        "A1_over_Ainc",
        "A2_over_A1",
        "beta_star",
        "shear_A1_over_Ainc",
        "shear_tr_A1_over_Ainc",
        "shear_A_inc",
        "shear_amplitude",
        "wave_amplitude",
        "wave_A_inc",
    ] {
        assert!(sum.get(gone).is_none(), "{gone}");
    }
}

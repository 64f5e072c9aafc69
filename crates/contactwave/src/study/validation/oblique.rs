//! Validation cases of oblique incidence (model.md section 14.6), run by `contactwave
//! validate` after the tangential cases: the spring interface's reflection and
//! transmission coefficients (P and SV, mode conversion) against the closed form, the
//! welded (Zoeppritz) limit of stiff springs, the closed form against Aki & Richards'
//! explicit coefficients, theta = 0 against the normal-incidence solver, and the energy
//! audit with clapping and friction.

use super::ValidationCase;
use crate::analytic::oblique::{aki_richards_p, coefficients, Bond, Elastic, Geometry};
use crate::error::{Error, Result};
use crate::model::half_space::oblique::transfer_at;
use crate::model::half_space::shear::coupled_problem;
use crate::scenario::Scenario;
use crate::solver::coupled::{CoupledOutput, CoupledSolver};
use crate::solver::half_space::HalfSpaceSettings;
use crate::solver::Solver;

const F0: f64 = 1e6;

/// Aluminium on `counterpart` (`None`: rigid wall) with linear springs K_N, K_T, p0 = 50
/// MPa, an 8-cycle Hann burst of 1 MPa at 1 MHz, `key` (`incident` or `shear_incident`)
/// at `deg` degrees, 200 samples per period and 40 periods of tail.
fn spring_case(
    key: &str,
    deg: f64,
    counterpart: Option<&str>,
    kn: f64,
    kt: f64,
) -> Result<Scenario> {
    let cp = match counterpart {
        Some(m) => format!("[counterpart]\nkind = \"medium\"\nmaterial = \"{m}\"\n"),
        None => String::new(),
    };
    Scenario::from_toml_str(
        &format!(
            "[medium]\nmaterial = \"aluminium\"\n{cp}\
             [interface]\nstatic_pressure = 50e6\n\
             compression = {{ law = \"linear\", stiffness = {kn:?} }}\n\
             traction = {{ law = \"linear\", stiffness = {kn:?} }}\n\
             tangential = {{ law = \"linear\", stiffness = {kt:?} }}\n\
             [{key}]\nangle = {deg:?}\nfrequency = 1e6\ncycles = 8\nwindow = \"hann\"\namplitude = 1e6\n\
             [solver]\nsamples_per_period = 200\ntail_periods = 40\n"
        ),
        "<validation>",
    )
}

fn solve(s: &Scenario) -> Result<CoupledOutput> {
    let sh = s
        .shear
        .as_ref()
        .ok_or_else(|| Error::invalid("<validation>", "shear", "none", "an oblique scenario"))?;
    CoupledSolver {
        settings: HalfSpaceSettings {
            samples_per_period: s.spec.solver.samples_per_period(),
            tail_periods: s.spec.solver.tail_periods,
            summary_only: false,
        },
    }
    .solve(&coupled_problem(s, sh))
}

/// Largest complex error of the measured coefficients against the closed form.
fn coefficient_error(s: &Scenario, bond: Bond) -> Result<(f64, CoupledOutput)> {
    let o = s
        .oblique
        .as_ref()
        .ok_or_else(|| Error::invalid("<validation>", "angle", 0, "an oblique scenario"))?;
    let out = solve(s)?;
    let m = transfer_at(&out, &o.geometry, &*o.burst, F0);
    let c = coefficients(&o.geometry, bond, 2.0 * std::f64::consts::PI * F0);
    let err = (0..4).map(|k| (m[k] - c[k]).norm()).fold(0.0, f64::max);
    Ok((err, out))
}

/// Every oblique case, in a stable order.
pub fn run_all() -> Result<Vec<ValidationCase>> {
    let mut v = Vec::new();
    let (kn, kt) = (2e14, 1e14);
    for (key, deg, cp, label) in [
        (
            "incident",
            22.5,
            Some("steel"),
            "P 22.5 deg, aluminium/steel",
        ),
        ("incident", 45.0, Some("steel"), "P 45 deg, aluminium/steel"),
        (
            "shear_incident",
            20.0,
            Some("steel"),
            "SV 20 deg, aluminium/steel",
        ),
        ("incident", 30.0, None, "P 30 deg, aluminium/rigid wall"),
    ] {
        let s = spring_case(key, deg, cp, kn, kt)?;
        let (err, out) = coefficient_error(
            &s,
            Bond::Springs {
                normal: kn,
                tangential: kt,
            },
        )?;
        v.push(ValidationCase::new(
            format!("oblique springs, {label}: max |R, T - closed form| (P and SV)"),
            0.0,
            err,
            1e-6,
        ));
        if deg == 45.0 {
            v.push(ValidationCase::new(
                format!("oblique springs, {label}: energy closure"),
                0.0,
                out.closure_error(),
                1e-9,
            ));
            let n = &out.normal.energy;
            let sh = &out.shear.energy;
            let comps = n.reflected + sh.reflected + n.transmitted + sh.transmitted;
            v.push(ValidationCase::new(
                format!("oblique springs, {label}: sum of P and SV wave energies = flux"),
                comps,
                out.wave_energy.iter().sum(),
                1e-9,
            ));
        }
    }
    // stiff springs: the welded interface (Zoeppritz)
    for (key, deg, label) in [
        ("incident", 45.0, "P 45 deg"),
        ("shear_incident", 20.0, "SV 20 deg"),
    ] {
        let s = spring_case(key, deg, Some("steel"), 1e20, 1e20)?;
        let (err, _) = coefficient_error(&s, Bond::Welded)?;
        v.push(ValidationCase::new(
            format!("oblique, K = 1e20 Pa/m, {label}, aluminium/steel: max |R, T - Zoeppritz|"),
            0.0,
            err,
            1e-4,
        ));
    }
    // the Zoeppritz system against Aki & Richards' explicit coefficients
    let al = Elastic {
        density: 2710.0,
        cp: (71e9f64 / 2710.0).sqrt(),
        cs: (71e9 / (2.0 * 1.33) / 2710.0f64).sqrt(),
    };
    let st = Elastic {
        density: 7850.0,
        cp: (210e9f64 / 7850.0).sqrt(),
        cs: (210e9 / (2.0 * 1.3) / 7850.0f64).sqrt(),
    };
    let deg = 30.0f64;
    let g = Geometry::new(
        &al,
        Some(&st),
        crate::analytic::oblique::WaveType::P,
        deg.to_radians(),
    )
    .map_err(|c| Error::invalid("<validation>", "angle", c.angle_deg, "below critical"))?;
    let z = coefficients(&g, Bond::Welded, 2.0 * std::f64::consts::PI * F0);
    let ar = aki_richards_p(&al, &st, deg.to_radians());
    let err = (0..4)
        .map(|k| (z[k].norm() - ar[k].abs()).abs())
        .fold(0.0, f64::max);
    v.push(ValidationCase::new(
        "Zoeppritz system vs Aki & Richards eq. 5.40, P 30 deg: max ||R|, |T| difference|",
        0.0,
        err,
        1e-12,
    ));
    // theta = 0: the plane-wave problem is the normal-incidence one; a small angle runs
    // the coupled path (off-diagonal compliances) and departs from it by O(theta)
    for key in ["incident", "shear_incident"] {
        let zero = spring_case(key, 0.0, Some("steel"), kn, kt)?;
        let normal = solve(&zero)?;
        let sh = zero.shear.as_ref().map(|x| x.tangential.clone());
        let e = |m: &crate::material::Material| Elastic {
            density: m.density,
            cp: m.wave_speed(),
            cs: m.shear_wave_speed().unwrap_or(f64::NAN),
        };
        let wave = if key == "incident" {
            crate::analytic::oblique::WaveType::P
        } else {
            crate::analytic::oblique::WaveType::Sv
        };
        let cp = zero.counterpart.as_ref().map(e);
        for deg in [0.0f64, 1e-3] {
            let g = Geometry::new(&e(&zero.medium), cp.as_ref(), wave, deg.to_radians()).map_err(
                |c| Error::invalid("<validation>", "angle", c.angle_deg, "below critical"),
            )?;
            let burst = match wave {
                crate::analytic::oblique::WaveType::P => zero.incident.clone(),
                _ => zero
                    .shear
                    .as_ref()
                    .map(|x| x.incident.clone())
                    .unwrap_or(zero.incident.clone()),
            };
            let p = crate::solver::coupled::CoupledHalfSpace::oblique(
                zero.medium,
                zero.counterpart,
                zero.law.clone(),
                sh.clone().ok_or_else(|| {
                    Error::invalid("<validation>", "shear", "none", "a tangential law")
                })?,
                &g,
                burst,
            );
            let settings = HalfSpaceSettings {
                samples_per_period: 200,
                tail_periods: Some(40.0),
                summary_only: false,
            };
            let a = CoupledSolver { settings }.solve(&p)?;
            let pairs = [
                (&a.normal.reflected_stress, &normal.normal.reflected_stress),
                (&a.shear.reflected_stress, &normal.shear.reflected_stress),
                (
                    &a.normal.transmitted_stress,
                    &normal.normal.transmitted_stress,
                ),
                (
                    &a.shear.transmitted_stress,
                    &normal.shear.transmitted_stress,
                ),
            ];
            let scale = pairs
                .iter()
                .flat_map(|(_, y)| y.iter())
                .fold(1e-30f64, |m, v| m.max(v.abs()));
            let mut err: f64 = 0.0;
            for (x, y) in pairs {
                for (u, w) in x.iter().zip(y.iter()) {
                    err = err.max((u - w).abs() / scale);
                }
            }
            let (name, tol) = if deg == 0.0 {
                (
                    format!(
                        "oblique solver at 0 deg = normal-incidence solver ({key}): max difference / peak"
                    ),
                    1e-12,
                )
            } else {
                (
                    format!(
                        "oblique solver at 1e-3 deg (coupled path) vs normal incidence ({key}): max difference / peak"
                    ),
                    1e-4,
                )
            };
            v.push(ValidationCase::new(name, 0.0, err, tol));
        }
    }
    // clapping and friction: the audit closes
    let s = Scenario::from_toml_str(
        "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\nmaterial = \"steel\"\n\
         [interface]\nstatic_pressure = 2e6\ntangential = { law = \"coulomb\", friction = 0.3 }\n\
         [incident]\nangle = 30.0\nfrequency = 1e6\ncycles = 6\namplitude = 3e6\n\
         [solver]\nsamples_per_period = 400\ntail_periods = 10\n",
        "<validation>",
    )?;
    let out = solve(&s)?;
    v.push(ValidationCase::new(
        "oblique P 30 deg, Signorini + Coulomb, aluminium/steel: energy closure",
        0.0,
        out.closure_error(),
        1e-6,
    ));
    Ok(v)
}

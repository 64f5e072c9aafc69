//! Validation cases of tangential contact (model.md section 13.5), run by
//! `contactwave validate` after the normal cases: the rigid-stick clipping closed form
//! (harmonics and dissipation), the bonded and free limits of friction, no harmonics below
//! the slip threshold, odd harmonics only for a symmetric frictional response, the
//! dissipated energy against the area of the friction loop, the full RCCM law without
//! shear against the normal solver, and the coupled energy audit.

use super::ValidationCase;
use crate::analysis::projection::period_harmonics;
use crate::analytic::friction::ClippedShear;
use crate::error::{Error, Result};
use crate::model::half_space::shear::ShearResult;
use crate::scenario::Scenario;
use crate::{simulate, simulate_summary};

/// Aluminium half-spaces, p0 (Pa), the given tangential law and a shear burst of
/// amplitude `a` (Pa) at 1 MHz: `cycles` cycles with `window`, `spp` samples per period.
fn shear_case(
    p0: f64,
    tangential: &str,
    a: f64,
    cycles: usize,
    window: &str,
    spp: usize,
) -> Result<Scenario> {
    Scenario::from_toml_str(
        &format!(
            "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\nmaterial = \"aluminium\"\n\
             [interface]\nstatic_pressure = {p0:?}\ntangential = {tangential}\n\
             [shear_incident]\nfrequency = 1e6\ncycles = {cycles}\nwindow = \"{window}\"\namplitude = {a:?}\n\
             [solver]\nsamples_per_period = {spp}\n"
        ),
        "<validation>",
    )
}

fn shear_of(s: &Scenario) -> Result<(ShearResult, f64)> {
    let r = simulate(s)?;
    let z1t = s.shear.as_ref().map_or(f64::NAN, |sh| sh.z1t);
    r.shear
        .map(|sh| (sh, z1t))
        .ok_or_else(|| Error::invalid("<validation>", "shear", "none", "a shear scenario"))
}

const F0: f64 = 1e6;
const CYCLES: usize = 10;

fn clipped(p0: f64, mu: f64, a: f64, z: f64) -> ClippedShear {
    ClippedShear {
        amplitude: a,
        omega: 2.0 * std::f64::consts::PI * F0,
        z1: z,
        z2: z,
        limit: mu * p0,
    }
}

/// Rigid-stick Coulomb friction between identical aluminium half-spaces, p0 = 10 MPa,
/// mu = 0.3, a 10-cycle rectangular shear burst of 5 MPa (mu p0 / tau_inc = 0.6): the
/// transmitted shear stress's harmonics 1, 3, 5 over the burst's whole periods against
/// the clipped-sine closed form (1e-4), the friction dissipation per cycle against its
/// closed form, and the energy dissipated against the area of the `tau - [u]_T` loop.
pub fn clipping() -> Result<Vec<ValidationCase>> {
    let (p0, mu, a) = (10e6, 0.3, 5e6);
    let s = shear_case(
        p0,
        "{ law = \"coulomb\", friction = 0.3 }",
        a,
        CYCLES,
        "rectangular",
        1000,
    )?;
    let (r, z) = shear_of(&s)?;
    let o = &r.interface;
    let cf = clipped(p0, mu, a, z);
    let h = period_harmonics(&o.transmitted_stress, o.dt, F0, 0, CYCLES, 5)
        .unwrap_or_else(|| vec![f64::NAN; 6]);
    let mut v = Vec::new();
    for n in [1usize, 3, 5] {
        v.push(ValidationCase::new(
            format!("Coulomb clipping (mu p0/tau = 0.6): transmitted shear harmonic {n}, Pa"),
            cf.transmitted_harmonic(n).abs(),
            h[n],
            1e-4,
        ));
    }
    v.push(ValidationCase::new(
        "Coulomb clipping: even harmonic 2 / harmonic 1 (symmetric friction: 0)",
        0.0,
        h[2] / h[1],
        1e-9,
    ));
    v.push(ValidationCase::new(
        "Coulomb clipping: friction dissipation per cycle, J/m^2",
        cf.dissipation_per_cycle(),
        r.friction_dissipation / CYCLES as f64,
        1e-6,
    ));
    // the loop area: int tau d[u]_T over the run (trapezoid on the samples)
    let area: f64 = o
        .gap
        .windows(2)
        .zip(o.contact_stress.windows(2))
        .map(|(g, t)| 0.5 * (t[0] + t[1]) * (g[1] - g[0]))
        .sum();
    v.push(ValidationCase::new(
        "Coulomb clipping: dissipated energy = area of the friction loop, J/m^2",
        area,
        r.friction_dissipation,
        1e-4,
    ));
    Ok(v)
}

/// Limits of friction: a very large mu transmits the shear wave as a bonded interface
/// (`tau_tr = tau_inc` between identical media), mu = 0 reflects it completely (free).
pub fn limits() -> Result<Vec<ValidationCase>> {
    let a = 5e6;
    let mut v = Vec::new();
    for (mu, name, tr_factor) in [
        (1e6, "mu -> inf is bonded", 1.0),
        (0.0, "mu = 0 is free", 0.0),
    ] {
        let s = shear_case(
            10e6,
            &format!("{{ law = \"coulomb\", friction = {mu:?} }}"),
            a,
            CYCLES,
            "hann_ramps",
            200,
        )?;
        let (r, _) = shear_of(&s)?;
        let o = &r.interface;
        let err = o
            .transmitted_stress
            .iter()
            .zip(&o.incident_stress)
            .map(|(tr, inc)| (tr - tr_factor * inc).abs())
            .fold(0.0f64, f64::max);
        v.push(ValidationCase::new(
            format!("Coulomb {name}: max |tau_tr - {tr_factor} tau_inc| / A"),
            0.0,
            err / a,
            1e-9,
        ));
    }
    Ok(v)
}

/// No harmonics below the slip threshold: mu p0 / tau_inc = 1.2 (Hann-ramp burst), the
/// transmitted shear wave is the incident one: its A3/A1 (band peak) equals the analysis
/// floor, the same analysis applied to the incident burst (the linear response).
pub fn below_threshold() -> Result<ValidationCase> {
    let s = shear_case(
        20e6,
        "{ law = \"coulomb\", friction = 0.3 }",
        5e6,
        15,
        "hann_ramps",
        200,
    )?;
    let (r, _) = shear_of(&s)?;
    let o = &r.interface;
    let floor = crate::analysis::velocity_bands(&o.incident_displacement, o.dt, F0, None);
    let tr = &r.transmitted_bands;
    Ok(ValidationCase::new(
        "Coulomb below the slip threshold (mu p0/tau = 1.2): transmitted shear A3/A1 = floor",
        floor.harmonic[3] / floor.harmonic[1],
        tr.harmonic[3] / tr.harmonic[1],
        1e-6,
    ))
}

/// The full RCCM law with C_T = 0 and no shear wave reproduces the normal-only RCCM
/// results (the coupled solver against the normal solver; thesis chapter 3 case,
/// 1.6 MPa: damaging).
pub fn rccm_without_shear() -> Result<Vec<ValidationCase>> {
    let base = "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
                traction = { law = \"rccm\", stiffness = 2e13, energy = 0.1 }\n";
    let inc = "[incident]\nfrequency = 1e6\ncycles = 15\namplitude = 1.6e6\n";
    let normal = Scenario::from_toml_str(&format!("{base}{inc}"), "<validation>")?;
    let full = Scenario::from_toml_str(
        &format!("{base}tangential = {{ law = \"rccm\", stiffness = 0.0, friction = 0.3 }}\n{inc}"),
        "<validation>",
    )?;
    let (a, b) = (simulate_summary(&normal)?, simulate_summary(&full)?);
    let mut v = Vec::new();
    for key in ["A2_over_Ainc", "beta_end"] {
        v.push(ValidationCase::new(
            format!("full RCCM, C_T = 0, no shear = normal RCCM: {key}"),
            a.get(key).unwrap_or(f64::NAN),
            b.get(key).unwrap_or(f64::NAN),
            1e-9,
        ));
    }
    Ok(v)
}

/// Energy audit of the coupled solver on the full RCCM law hit by a longitudinal and a
/// shear burst (damage and friction both active): relative closure error.
pub fn coupled_energy() -> Result<ValidationCase> {
    let s = Scenario::from_toml_str(
        "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\nmaterial = \"aluminium\"\n\
         [interface]\nstatic_pressure = 0.82e6\ntraction = { law = \"rccm\", stiffness = 2e13, energy = 0.1 }\n\
         tangential = { law = \"rccm\", stiffness = 1e13, friction = 0.4 }\n\
         [incident]\nfrequency = 1e6\ncycles = 15\namplitude = 3e6\n\
         [shear_incident]\nfrequency = 1e6\ncycles = 15\namplitude = 2e6\ndelay = 2e-6\n",
        "<validation>",
    )?;
    let sm = simulate_summary(&s)?;
    Ok(ValidationCase::new(
        "full RCCM, normal + shear bursts: energy audit closure (friction, damage)",
        0.0,
        sm.get("energy_closure_error").unwrap_or(f64::NAN),
        1e-6,
    ))
}

/// Cross-validation of the two solvers with shear: the FD scheme with a shear field
/// against the coupled exact solver on the full RCCM law hit by a longitudinal and a
/// shear burst (damage and friction), 1000 samples per period: the transmitted shear
/// wave's A3/A_inc and beta_end (1%).
pub fn fd_vs_exact() -> Result<Vec<ValidationCase>> {
    let base = "[medium]\nmaterial = \"aluminium\"\n[counterpart]\nkind = \"medium\"\nmaterial = \"aluminium\"\n\
         [interface]\nstatic_pressure = 0.82e6\ntraction = { law = \"rccm\", stiffness = 2e13, energy = 0.1 }\n\
         tangential = { law = \"rccm\", stiffness = 1e13, friction = 0.4 }\n\
         [incident]\nfrequency = 1e6\ncycles = 15\namplitude = 3e6\n\
         [shear_incident]\nfrequency = 1e6\ncycles = 15\namplitude = 2e6\n";
    let run = |method: &str| -> Result<crate::analysis::Summary> {
        let s = Scenario::from_toml_str(
            &format!(
                "{base}[solver]\nmethod = \"{method}\"\nsamples_per_period = 1000\ntail_periods = 20\n"
            ),
            "<validation>",
        )?;
        simulate_summary(&s)
    };
    let (ex, fd) = (run("exact")?, run("fd")?);
    let mut v = Vec::new();
    for key in ["shear_tr_A3_over_Ainc", "shear_A1_over_Ainc", "beta_end"] {
        v.push(ValidationCase::new(
            format!("FD vs exact, full RCCM with normal + shear bursts: {key}"),
            ex.get(key).unwrap_or(f64::NAN),
            fd.get(key).unwrap_or(f64::NAN),
            0.01,
        ));
    }
    Ok(v)
}

/// The bar stack's transverse field (model.md section 9.7) against the exact coupled
/// solver: rigid-stick clipping between two aluminium bars with transparent ends (the
/// half-spaces of [`clipping`], 500 samples per period in both): the transmitted shear
/// wave's A3/A1 and the frictional dissipation (1e-3).
pub fn bar_stack_vs_exact() -> Result<Vec<ValidationCase>> {
    let law = "{ law = \"coulomb\", friction = 0.3 }";
    let stack = format!(
        "[model]\nkind = \"bar_stack\"\narea = 1.0\nstatic_force = 10e6\n\
         first_end = \"transparent\"\nlast_end = \"transparent\"\nsamples_per_period = 500\n\
         [[segment]]\nname = \"a\"\nlength = 0.01\nmaterial = \"aluminium\"\n\
         [[segment]]\nname = \"b\"\nlength = 0.01\nmaterial = \"aluminium\"\n\
         [[interface]]\nbetween = [\"a\", \"b\"]\ntangential = {law}\n\
         [shear_incident]\nfrequency = 1e6\ncycles = {CYCLES}\nwindow = \"rectangular\"\namplitude = 5e6\n"
    );
    let table = crate::scenario::parse_toml(&stack, "<validation>")?;
    let bs = crate::scenario::bar_stack::BarStackScenario::from_table(
        table,
        std::path::Path::new("<validation>"),
    )?;
    let fd = crate::simulate_bar_stack(&bs)?.summary;
    let ex = simulate_summary(&shear_case(10e6, law, 5e6, CYCLES, "rectangular", 500)?)?;
    Ok(["shear_tr_A3_over_A1", "friction_dissipation"]
        .into_iter()
        .map(|key| {
            ValidationCase::new(
                format!("bar stack vs exact, Coulomb clipping (two aluminium bars): {key}"),
                ex.get(key).unwrap_or(f64::NAN),
                fd.get(key).unwrap_or(f64::NAN),
                1e-3,
            )
        })
        .collect())
}

/// Every tangential case, in a stable order.
pub fn run_all() -> Result<Vec<ValidationCase>> {
    let mut v = clipping()?;
    v.extend(limits()?);
    v.push(below_threshold()?);
    v.extend(rccm_without_shear()?);
    v.push(coupled_energy()?);
    v.extend(fd_vs_exact()?);
    v.extend(bar_stack_vs_exact()?);
    Ok(v)
}

//! Validation cases of the 2D solver's numerical dispersion at the scenarios' default
//! resolution (docs/model.md section 15.4): the phase velocity at 3 f0 measured in the
//! time domain along z, the Bloch-wave analysis of the scheme
//! ([`crate::solver::solid_2d::dispersion`]) against it, and the analysis' largest error
//! over every direction of travel.

use super::ValidationCase;
use super::ALUMINIUM;
use crate::error::Result;
use crate::excitation::{Excitation, ToneBurst, Window};
use crate::law::compression::Rigid;
use crate::law::point::PointLaw;
use crate::law::tangential::Free as Sliding;
use crate::law::traction::Free;
use crate::scenario::solid_2d::{DEFAULT_ORDER, DISPERSION_BUDGET, PHASE_STEP};
use crate::solver::solid_2d::dispersion::{element_size_for, phase_error, Branch};
use crate::solver::solid_2d::{Elastic, Solid2d, WaveType};
use std::f64::consts::PI;
use std::sync::Arc;

/// The law type of the (crack-free) runs.
type Signorini = PointLaw<Rigid, Free, Sliding>;

/// The analysed frequency: 3 f0 of a 5 MHz burst, Hz.
pub const FREQUENCY: f64 = 15e6;

/// The scenarios' default element size for `material` at [`FREQUENCY`], m.
pub fn default_element_size(material: &Elastic) -> Result<f64> {
    default_element_size_at(material, FREQUENCY)
}

/// The scenarios' default element size (m) for `material` and a highest analysed
/// harmonic at `frequency` (Hz).
pub fn default_element_size_at(material: &Elastic, frequency: f64) -> Result<f64> {
    let dt = PHASE_STEP / (2.0 * PI * frequency);
    element_size_for(
        DEFAULT_ORDER,
        dt,
        &[*material],
        WaveType::PSv,
        frequency,
        DISPERSION_BUDGET,
    )
    .ok_or_else(|| failed("no default element size"))
}

fn failed(what: &str) -> crate::error::Error {
    crate::error::Error::Numerical {
        time: 0.0,
        message: format!("2D dispersion validation: {what}"),
        state: String::new(),
    }
}

fn speed(material: &Elastic, branch: Branch) -> f64 {
    if branch == Branch::P {
        material.p_speed
    } else {
        material.s_speed
    }
}

/// The relative phase velocity error `c_num / c - 1` of a plane wave of `branch` at
/// [`FREQUENCY`] travelling along z in aluminium at the scenarios' default resolution
/// (order, element size and step bound), measured in the time domain, and the time step
/// of the run (s): the phase at 15 MHz between two receivers about 30 wavelengths apart
/// (a whole number of elements, so at the same place in their elements) of a 12-cycle
/// Hann burst from a surface traction in a periodic strip one element wide.
pub fn time_domain(branch: Branch) -> Result<(f64, f64)> {
    let f = FREQUENCY;
    let c = speed(&ALUMINIUM, branch);
    let lambda = c / f;
    let h = default_element_size(&ALUMINIUM)?;
    let w = 2.0 * PI * f;
    let depth = (50.0 * lambda / h).ceil() * h;
    let (z1, z2) = (2.0 * lambda, 32.0 * lambda);
    let signal: Arc<dyn Excitation> = Arc::new(ToneBurst::new(1e6, f, 12.0, Window::Hann));
    let problem = |receivers: Vec<[f64; 2]>| Solid2d::<Signorini> {
        order: DEFAULT_ORDER,
        courant: 0.9,
        max_time_step: PHASE_STEP / w,
        receivers,
        crack_every: 1000,
        ..Solid2d::periodic_strip(
            ALUMINIUM,
            branch.wave(),
            h,
            depth,
            (branch == Branch::P, signal.clone()),
            (z2 + 14.0 * lambda) / c,
        )
    };
    // the node nearest z1, and the node a whole number of elements below it near z2
    let probe = problem(vec![[0.0, z1]]).plan("<validation>")?;
    let za = probe
        .mesh
        .z
        .iter()
        .copied()
        .min_by(|a, b| (a - z1).abs().total_cmp(&(b - z1).abs()))
        .unwrap_or(z1);
    let dz = ((z2 - za) / h).round() * h;
    drop(probe);
    let plan = problem(vec![[0.0, za], [0.0, za + dz]]).plan("<validation>")?;
    let out = plan.run()?;
    let comp = usize::from(branch == Branch::P);
    let phase = |x: &[f64]| {
        let (mut re, mut im) = (0.0, 0.0);
        for (k, &t) in out.time.iter().enumerate() {
            re += x[k] * (w * t).cos();
            im -= x[k] * (w * t).sin();
        }
        im.atan2(re)
    };
    let expected = w * dz / c;
    let mut d = phase(out.trace(0, comp)) - phase(out.trace(1, comp)) - expected;
    d -= (d / (2.0 * PI)).round() * 2.0 * PI;
    Ok((expected / (expected + d) - 1.0, out.dt))
}

/// The Bloch analysis' error of `branch` in `material` with the default order and
/// elements of `h` (m), time step `dt` (s), at `angle` (rad from z).
pub fn bloch(material: &Elastic, h: f64, branch: Branch, dt: f64, angle: f64) -> Result<f64> {
    phase_error(DEFAULT_ORDER, h, dt, material, branch, angle, FREQUENCY)
}

/// The error of largest magnitude over the directions 0 to 90 degrees (1 degree apart;
/// the square elements make the rest alike) and the direction, degrees.
pub fn worst_direction(material: &Elastic, branch: Branch, dt: f64) -> Result<(f64, f64)> {
    let h = default_element_size(material)?;
    let mut worst = (0.0f64, 0.0);
    for deg in 0..=90 {
        let e = bloch(material, h, branch, dt, f64::from(deg).to_radians())?;
        if e.abs() > worst.0.abs() {
            worst = (e, f64::from(deg));
        }
    }
    Ok(worst)
}

/// The cases: per wave type, the time-domain error along z, the Bloch analysis against
/// it, and the largest error over the directions.
pub fn run_all() -> Result<Vec<ValidationCase>> {
    let mut v = Vec::new();
    for branch in [Branch::P, Branch::Sv, Branch::Sh] {
        let label = format!("{branch:?}").to_uppercase();
        let c = speed(&ALUMINIUM, branch);
        let (e, dt) = time_domain(branch)?;
        v.push(ValidationCase::new(
            format!(
                "2D: {label} phase velocity error at 3 f0 (15 MHz) along z, default resolution"
            ),
            0.0,
            e,
            1e-3,
        ));
        v.push(ValidationCase::new(
            format!(
                "2D: {label} phase velocity (m/s) at 3 f0 along z: Bloch analysis vs time domain"
            ),
            c * (1.0
                + bloch(
                    &ALUMINIUM,
                    default_element_size(&ALUMINIUM)?,
                    branch,
                    dt,
                    0.0,
                )?),
            c * (1.0 + e),
            1e-5,
        ));
        let (worst, deg) = worst_direction(&ALUMINIUM, branch, dt)?;
        v.push(ValidationCase::new(
            format!(
                "2D: {label} largest phase velocity error at 3 f0 over directions (at {deg} deg), default resolution, Bloch analysis"
            ),
            0.0,
            worst,
            1e-3,
        ));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The time domain and the Bloch analysis agree along z (the analysis is the scheme),
    /// and both are within 1e-3 at the default resolution.
    #[test]
    fn time_domain_matches_the_bloch_analysis() {
        for branch in [Branch::P, Branch::Sv, Branch::Sh] {
            let (e, dt) = time_domain(branch).unwrap();
            let h = default_element_size(&ALUMINIUM).unwrap();
            let b = bloch(&ALUMINIUM, h, branch, dt, 0.0).unwrap();
            eprintln!("{branch:?}: time domain {e:.4e}, Bloch {b:.4e}");
            assert!(e.abs() < 1e-3 && e != 0.0, "{e:e}");
            assert!((e - b).abs() < 1e-5, "{e:e} {b:e}");
        }
    }

    /// At the default resolution every direction of every wave is within 1e-3, for
    /// Poisson's ratios 0.25 to 0.45 (the element size follows c_S; P is finer).
    #[test]
    fn default_resolution_within_1e_3_in_every_direction() {
        let w = 2.0 * PI * FREQUENCY;
        for nu in [0.25f64, 0.34, 0.4, 0.45] {
            let cs = 3000.0;
            let m = Elastic {
                density: 2700.0,
                p_speed: cs * ((2.0 - 2.0 * nu) / (1.0 - 2.0 * nu)).sqrt(),
                s_speed: cs,
            };
            for branch in [Branch::P, Branch::Sv, Branch::Sh] {
                let (e, deg) = worst_direction(&m, branch, PHASE_STEP / w).unwrap();
                eprintln!("nu {nu}, {branch:?}: worst {e:.3e} at {deg} deg");
                assert!(e.abs() < 1e-3, "nu {nu} {branch:?}: {e:e} at {deg}");
            }
        }
    }
}

//! Validation steps for the run settings: the time step, the simulated time and the
//! analysis settings.

use super::spec::{AnalysisSpec, ModelSpec, DEFAULT_HAMMER_DURATION, DEFAULT_INCIDENT_SPP};
use super::{inv, pos};
use crate::error::Result;
use crate::excitation::Excitation;
use crate::solver::bar_stack::Segment;
use std::sync::Arc;

/// The time step, s: `model.cell_size` (default: the shortest segment / 4) over the
/// largest wave speed; with incident waves (longitudinal, shear or both) at most a period
/// of their highest frequency over `model.samples_per_period`, adjusted so that the first
/// segment is meshed at Courant number 1; `model.time_step` overrides it within the
/// stability limit.
pub(super) fn time_step(
    m: &ModelSpec,
    segments: &[Segment],
    waves: &[&Arc<dyn Excitation>],
    file: &str,
) -> Result<f64> {
    let shortest = segments
        .iter()
        .map(|s| s.length)
        .fold(f64::INFINITY, f64::min);
    let dx = m.cell_size.unwrap_or(shortest / 4.0);
    pos(file, "model.cell_size", dx)?;
    let cmax = segments
        .iter()
        .map(|s| s.material.wave_speed())
        .fold(0.0, f64::max);
    let mut dt = dx / cmax;
    let highest = waves
        .iter()
        .map(|w| w.highest_frequency())
        .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.max(f))));
    if let Some(highest) = highest {
        let spp = m.samples_per_period.unwrap_or(DEFAULT_INCIDENT_SPP);
        if !crate::scenario::spec::SAMPLES_PER_PERIOD.contains(&spp) {
            return Err(inv(
                file,
                "model.samples_per_period",
                spp,
                "must lie in [16, 100000]",
            ));
        }
        let d = dt.min(1.0 / (highest * spp as f64));
        // the first segment at Courant number 1: its transparent end then absorbs the
        // outgoing wave exactly
        let c0 = segments[0].material.wave_speed();
        let cells0 = (segments[0].length / (c0 * d) * (1.0 - 1e-12))
            .ceil()
            .max(1.0);
        dt = segments[0].length / (c0 * cells0);
    }
    if let Some(ts) = m.time_step {
        // explicit scheme: a segment needs one cell of size >= c dt (Courant <= 1)
        let (limit, name) = segments
            .iter()
            .map(|s| (s.length / s.material.wave_speed(), s.name.as_str()))
            .fold((f64::INFINITY, ""), |a, b| if b.0 < a.0 { b } else { a });
        if !(ts.is_finite() && ts > 0.0 && ts <= limit) {
            return Err(inv(
                file,
                "model.time_step",
                ts,
                &format!(
                    "in (0, {limit:.4e}] s: above it segment `{name}` cannot hold one cell \
                     at Courant number <= 1 (stability limit of the explicit scheme)"
                ),
            ));
        }
        dt = ts;
    }
    Ok(dt)
}

/// The simulated time, s: `model.duration`, or by default, with incident waves, the
/// longest burst, four travel times of the stack (at the shear wave speeds with a
/// transverse field, `shear`) and 100 periods of the lowest fundamental, and
/// [`DEFAULT_HAMMER_DURATION`] otherwise; at most 5e8 time steps of `dt`.
pub(super) fn duration(
    m: &ModelSpec,
    segments: &[Segment],
    waves: &[&Arc<dyn Excitation>],
    shear: bool,
    dt: f64,
    file: &str,
) -> Result<f64> {
    let travel: f64 = segments
        .iter()
        .map(|s| {
            let c = match s.material.shear_wave_speed() {
                Some(ct) if shear => ct,
                _ => s.material.wave_speed(),
            };
            s.length / c
        })
        .sum();
    let duration = match (m.duration, waves.first()) {
        (Some(d), _) => {
            pos(file, "model.duration", d)?;
            d
        }
        (None, Some(_)) => {
            let burst = waves.iter().map(|w| w.duration()).fold(0.0, f64::max);
            let f0 = waves
                .iter()
                .map(|w| w.fundamental())
                .fold(f64::INFINITY, f64::min);
            burst + 4.0 * travel + 100.0 / f0
        }
        (None, None) => DEFAULT_HAMMER_DURATION,
    };
    let steps = duration / dt;
    if steps > 5e8 {
        return Err(inv(
            file,
            "model.duration",
            duration,
            &format!("too many time steps ({steps:.2e}); raise model.cell_size"),
        ));
    }
    Ok(duration)
}

/// The analysis settings: the band searched for the first mode must be `0 < min < max`.
pub(super) fn validate_analysis(a: &AnalysisSpec, file: &str) -> Result<()> {
    if !(a.first_mode_min > 0.0 && a.first_mode_max > a.first_mode_min) {
        return Err(inv(
            file,
            "analysis.first_mode_max",
            a.first_mode_max,
            "must exceed analysis.first_mode_min > 0",
        ));
    }
    Ok(())
}

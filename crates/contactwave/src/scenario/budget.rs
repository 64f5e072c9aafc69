//! Size estimates of scenarios, checked against the memory budget ([`crate::budget`])
//! before a solver allocates: time samples x recorded series of a half-space run, mesh
//! nodes and time steps x recorded series of a bar stack.

use super::spec::IncidentKind;
use super::Scenario;
use crate::budget::{self, BYTES_PER_SAMPLE};
use crate::error::Result;

/// Series a half-space solve records per time sample when only the summary is wanted
/// (`t`, `beta`, reflected displacement) and their padded transforms (band analysis).
const HALF_SPACE_SUMMARY_SERIES: f64 = 5.0;
/// Series of a full half-space run per interface sample: ten recorded histories, the
/// columns of `timeseries.csv`, two padded spectra.
const HALF_SPACE_FULL_SERIES: f64 = 14.0;
/// Series per probe sample: five histories and their columns in `probe.csv`.
const PROBE_SERIES: f64 = 6.0;

/// Number of interface time samples of a half-space run, at most (the automatic tail
/// may stop earlier).
pub fn half_space_samples(s: &Scenario) -> f64 {
    let dt = half_space_dt(s);
    let period = 1.0 / s.incident.fundamental();
    let tail = s.spec.solver.tail_periods.unwrap_or(400.0) * period;
    (duration(s) + tail) / dt + 1.0
}

/// Longest incident wave (longitudinal or shear), s.
fn duration(s: &Scenario) -> f64 {
    let d = s.incident.duration();
    s.shear
        .as_ref()
        .map_or(d, |sh| d.max(sh.incident.duration()))
}

/// Whether the shear wave sets the run's length.
fn shear_is_longer(s: &Scenario) -> bool {
    s.shear
        .as_ref()
        .is_some_and(|sh| sh.incident.duration() > s.incident.duration())
}

/// Time step of a half-space run, s.
fn half_space_dt(s: &Scenario) -> f64 {
    let f = s.incident.highest_frequency();
    let f = s
        .shear
        .as_ref()
        .map_or(f, |sh| f.max(sh.incident.highest_frequency()));
    1.0 / (f * s.spec.solver.samples_per_period() as f64)
}

/// Series recorded per sample: the coupled (shear) solver keeps every history of both
/// components.
fn series(s: &Scenario, normal: f64) -> f64 {
    if s.shear.is_some() {
        normal.max(HALF_SPACE_FULL_SERIES) + 16.0
    } else {
        normal
    }
}

/// Number of probe samples of a full half-space run: the delay window from the incident
/// wave's arrival at the probe to the reflected wave's, plus the interface record.
pub fn probe_samples(s: &Scenario) -> f64 {
    let delay = s.probe_x.abs() / s.medium.wave_speed();
    2.0 * delay / half_space_dt(s) + half_space_samples(s)
}

/// Refuse a half-space scenario whose solve needs more memory than the budget (the
/// summary-only solve of a sweep point; a full run adds [`check_half_space_run`]). The
/// error names the key that sets the length: the burst (`incident.cycles`, the file of
/// `incident.path`) or the tail (`solver.tail_periods`).
pub fn check_half_space(s: &Scenario) -> Result<()> {
    let n = half_space_samples(s);
    check_samples(s, n, series(s, HALF_SPACE_SUMMARY_SERIES))
}

/// Refuse a full half-space run (interface histories, probe series, spectra, files) that
/// needs more memory than the budget.
pub fn check_half_space_run(s: &Scenario) -> Result<()> {
    let n = half_space_samples(s);
    check_samples(s, n, series(s, HALF_SPACE_FULL_SERIES))?;
    let m = probe_samples(s);
    let dt = half_space_dt(s);
    budget::check(
        &s.file,
        "probe.x",
        s.probe_x,
        (n * HALF_SPACE_FULL_SERIES + m * PROBE_SERIES) * BYTES_PER_SAMPLE,
        &format!(
            "{m:.2e} probe samples: the wave travels 2 |x| / c = {:.3e} s between the incident and the reflected wave at dt = {dt:.3e} s",
            2.0 * s.probe_x.abs() / s.medium.wave_speed()
        ),
    )
}

fn check_samples(s: &Scenario, n: f64, series: f64) -> Result<()> {
    let dt = half_space_dt(s);
    let f0 = s.incident.fundamental();
    let burst_periods = duration(s) * f0;
    let tail_periods = s.spec.solver.tail_periods.unwrap_or(400.0);
    let spp = s.spec.solver.samples_per_period();
    let (inc, prefix) = match (&s.spec.shear_incident, shear_is_longer(s)) {
        (Some(sh), true) => (sh, "shear_incident"),
        _ => (&s.spec.incident, "incident"),
    };
    let (field, value) = if burst_periods >= tail_periods {
        match inc.kind {
            IncidentKind::File => (
                format!("{prefix}.path"),
                inc.path.clone().unwrap_or_default().to_string(),
            ),
            _ => (
                format!("{prefix}.cycles"),
                inc.cycles
                    .map_or_else(|| "15".to_string(), |c| c.to_string()),
            ),
        }
    } else {
        ("solver.tail_periods".to_string(), format!("{tail_periods}"))
    };
    budget::check(
        &s.file,
        &field,
        value,
        n * series * BYTES_PER_SAMPLE,
        &format!(
            "{n:.2e} time samples of {series} series: {burst_periods:.3e} burst and {tail_periods} tail periods at {spp} samples per period, dt = {dt:.3e} s"
        ),
    )
}

/// Refuse a bar stack whose mesh or recorded histories need more memory than the budget:
/// `nodes` mesh nodes (about ten arrays of `f64` each), `steps` time steps of
/// `series` recorded series each.
pub fn check_bar_stack(
    file: &str,
    nodes: f64,
    cell_field: &str,
    cell_value: f64,
    steps: f64,
    series: f64,
    duration: f64,
) -> Result<()> {
    budget::check(
        file,
        cell_field,
        cell_value,
        nodes * 10.0 * 8.0,
        &format!("a mesh of {nodes:.3e} nodes"),
    )?;
    budget::check(
        file,
        "model.duration",
        duration,
        (steps + 1.0) * series * BYTES_PER_SAMPLE,
        &format!("{steps:.3e} time steps of {series} recorded series"),
    )
}

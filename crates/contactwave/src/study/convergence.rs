//! Convergence study of a solver in time and space (thesis section 2.3.5, eqs. 2.42-2.43;
//! Figure 22).
//!
//! The second-harmonic efficiency `A2/A_inc(xi)` is computed over a grid of load ratios
//! for a series of resolutions (samples per period of the highest input frequency; with
//! the FD solver every segment runs at Courant number 1, so `dx = c dt` refines with `dt`).
//! For each resolution the thesis' error is
//!
//! ```text
//! vect_error(xi) = (A2/A_inc(xi) - A2/A_inc(xi)|ref) / A2/A_inc(xi)|ref     (2.42)
//! Error          = || vect_error ||_2 / Nb_xi                                 (2.43)
//! ```
//!
//! with the finest resolution as the reference (as in the thesis) and, since contactwave
//! has an exact solver, also against the exact solver's curve. The observed order is the
//! least-squares slope of `log Error` against `log dt`.
//!
//! ```
//! use contactwave::study::convergence::{run_convergence, ConvergenceSpec};
//! let base = contactwave::scenario::parse_toml(
//!     "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.01e6\n\
//!      [incident]\nfrequency = 1e6\ncycles = 15\nxi = 0.5\n[solver]\ntail_periods = 20\n",
//!     "doc.toml",
//! ).unwrap();
//! let spec = ConvergenceSpec {
//!     xi: vec![0.3, 0.6],
//!     samples_per_period: vec![100, 200, 400],
//!     ..ConvergenceSpec::default()
//! };
//! let r = run_convergence(&base, std::path::Path::new("doc.toml"), &spec, &|_, _| {}).unwrap();
//! // first order in time at a clapping interface: the error halves when dt halves
//! assert!(r.levels[0].error_exact > r.levels[1].error_exact);
//! assert!(r.order_exact > 0.5);
//! ```

use crate::error::{Error, Result};
use crate::run::{Executor, Progress};
use crate::scenario::{set_dotted, Scenario};
use std::path::Path;

/// Which solver the study refines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConvergenceMethod {
    /// The finite-difference bar-stack scheme (the thesis' method).
    Fd,
    /// The exact half-space solver (its sampling: event location is exact).
    Exact,
}

/// What to compute.
#[derive(Debug, Clone)]
pub struct ConvergenceSpec {
    /// Load ratios, dimensionless (the thesis uses xi in ]0, 1]).
    pub xi: Vec<f64>,
    /// Resolutions: samples per period of the highest input frequency, each > 8.
    pub samples_per_period: Vec<usize>,
    /// Solver refined.
    pub method: ConvergenceMethod,
    /// Harmonic studied (2 in the thesis).
    pub harmonic: usize,
}

impl Default for ConvergenceSpec {
    fn default() -> Self {
        ConvergenceSpec {
            xi: (1..=10).map(|k| 0.1 * k as f64).collect(),
            samples_per_period: vec![125, 250, 500, 1000, 2000, 4000],
            method: ConvergenceMethod::Fd,
            harmonic: 2,
        }
    }
}

/// One resolution of the study.
#[derive(Debug, Clone)]
pub struct ConvergenceLevel {
    /// Samples per period of the highest input frequency.
    pub samples_per_period: usize,
    /// Time step, s.
    pub dt: f64,
    /// Space step in medium 1, m (`c dt` for the FD solver; NaN for the exact solver).
    pub dx: f64,
    /// `A_n/A_inc` at each xi.
    pub efficiency: Vec<f64>,
    /// Eq. 2.43 against the finest resolution (fraction, not percent; 0 for the finest).
    pub error_finest: f64,
    /// Eq. 2.43 against the exact solver at its default resolution (fraction).
    pub error_exact: f64,
}

/// Result of [`run_convergence`].
#[derive(Debug, Clone)]
pub struct ConvergenceResult {
    /// Load ratios.
    pub xi: Vec<f64>,
    /// Harmonic studied.
    pub harmonic: usize,
    /// Resolutions, coarsest first.
    pub levels: Vec<ConvergenceLevel>,
    /// `A_n/A_inc` of the exact solver at its default resolution, at each xi.
    pub exact: Vec<f64>,
    /// Observed order against the exact solver (slope of log error over log dt).
    pub order_exact: f64,
    /// Observed order against the finest level (all levels but the finest).
    pub order_finest: f64,
}

fn invalid(file: &str, field: &str, value: String, allowed: &str) -> Error {
    Error::invalid(file, field, value, allowed)
}

/// Check the spec against the base scenario file `file`.
fn check(spec: &ConvergenceSpec, file: &str) -> Result<()> {
    if spec.xi.is_empty() || spec.xi.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        return Err(invalid(
            file,
            "--xi",
            format!("{:?}", spec.xi),
            "one or more load ratios > 0",
        ));
    }
    if spec.samples_per_period.len() < 3 || spec.samples_per_period.iter().any(|&n| n < 8) {
        return Err(invalid(
            file,
            "--spp",
            format!("{:?}", spec.samples_per_period),
            "three or more resolutions, each >= 8 samples per period",
        ));
    }
    if !(1..=5).contains(&spec.harmonic) {
        return Err(invalid(
            file,
            "--harmonic",
            spec.harmonic.to_string(),
            "1 to 5",
        ));
    }
    Ok(())
}

/// The scenario of the base table at load ratio `xi`, `spp` samples per period and solver
/// `method` (`None`: the base's own solver settings).
fn variant(
    base: &toml::Table,
    path: &Path,
    xi: f64,
    spp: Option<usize>,
    method: Option<&str>,
) -> Result<Scenario> {
    let mut t = base.clone();
    set_dotted(&mut t, "incident.xi", toml::Value::Float(xi))?;
    if let Some(n) = spp {
        set_dotted(
            &mut t,
            "solver.samples_per_period",
            toml::Value::Integer(n as i64),
        )?;
    }
    if let Some(m) = method {
        set_dotted(&mut t, "solver.method", toml::Value::String(m.into()))?;
    }
    Scenario::from_table(t, path)
}

/// Eq. 2.43: `||(a - r)/r||_2 / Nb` over the points where the reference is above
/// [`NOISE_FLOOR`] times its largest value (at xi = 1 a unilateral contact does not clap
/// and `A2` is numerical noise, whose relative error means nothing).
pub fn thesis_error(a: &[f64], reference: &[f64]) -> f64 {
    let floor = NOISE_FLOOR
        * reference
            .iter()
            .filter(|r| r.is_finite())
            .fold(0.0f64, |m, r| m.max(r.abs()));
    let (mut s, mut n) = (0.0, 0usize);
    for (x, r) in a.iter().zip(reference) {
        if r.abs() > floor && r.abs() > 0.0 && x.is_finite() {
            s += ((x - r) / r).powi(2);
            n += 1;
        }
    }
    if n == 0 {
        f64::NAN
    } else {
        s.sqrt() / n as f64
    }
}

/// Reference values below this fraction of the largest one are left out of eq. 2.43.
pub const NOISE_FLOOR: f64 = 1e-3;

/// Least-squares slope of log y against log x over the finite, positive pairs.
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| **a > 0.0 && **b > 0.0 && a.is_finite() && b.is_finite())
        .map(|(a, b)| (a.ln(), b.ln()))
        .collect();
    if pts.len() < 2 {
        return f64::NAN;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    if sxx > 0.0 {
        sxy / sxx
    } else {
        f64::NAN
    }
}

/// Run the study on a base half-space scenario table that came from `path`. Runs in
/// parallel (the [`Executor`]); `progress(done, total)` is called after each run.
pub fn run_convergence(
    base: &toml::Table,
    path: &Path,
    spec: &ConvergenceSpec,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<ConvergenceResult> {
    let file = path.display().to_string();
    check(spec, &file)?;
    let mut spps = spec.samples_per_period.clone();
    spps.sort_unstable();
    spps.dedup();
    if spps.len() < 3 {
        return Err(invalid(
            &file,
            "--spp",
            format!("{:?}", spec.samples_per_period),
            "three or more distinct resolutions",
        ));
    }
    let method = match spec.method {
        ConvergenceMethod::Fd => "fd",
        ConvergenceMethod::Exact => "exact",
    };
    // validate every scenario first (a bad base fails before any run)
    let mut jobs: Vec<(Option<usize>, usize, Scenario)> = Vec::new();
    // the exact reference records as long a tail as the FD runs (the band analysis of a
    // record depends slightly on its length)
    let mut exact_base = base.clone();
    let has_tail = base
        .get("solver")
        .and_then(|s| s.get("tail_periods"))
        .is_some();
    if !has_tail {
        set_dotted(
            &mut exact_base,
            "solver.tail_periods",
            toml::Value::Float(100.0),
        )?;
    }
    for (i, &xi) in spec.xi.iter().enumerate() {
        jobs.push((
            None,
            i,
            variant(&exact_base, path, xi, None, Some("exact"))?,
        ));
        for (l, &n) in spps.iter().enumerate() {
            jobs.push((Some(l), i, variant(base, path, xi, Some(n), Some(method))?));
        }
    }
    let key = format!("A{}_over_Ainc", spec.harmonic);
    let observer = Progress {
        report: progress,
        cancel: None,
    };
    let values: Vec<f64> = Executor::new()
        .map(
            &jobs,
            |(_, _, s)| crate::simulate_summary(s).map(|sum| sum.get(&key).unwrap_or(f64::NAN)),
            &observer,
        )?
        .into_iter()
        .map(|r| r.and_then(|r| r.ok()).unwrap_or(f64::NAN))
        .collect();
    let nx = spec.xi.len();
    let mut exact = vec![f64::NAN; nx];
    let mut eff = vec![vec![f64::NAN; nx]; spps.len()];
    for ((level, i, _), v) in jobs.iter().zip(&values) {
        match level {
            None => exact[*i] = *v,
            Some(l) => eff[*l][*i] = *v,
        }
    }
    let first = &jobs[1].2;
    let f_hi = first.incident.highest_frequency();
    let c1 = first.medium.wave_speed();
    let finest = eff[spps.len() - 1].clone();
    let levels: Vec<ConvergenceLevel> = spps
        .iter()
        .zip(eff)
        .map(|(&n, e)| {
            let dt = 1.0 / (f_hi * n as f64);
            ConvergenceLevel {
                samples_per_period: n,
                dt,
                dx: if spec.method == ConvergenceMethod::Fd {
                    c1 * dt
                } else {
                    f64::NAN
                },
                error_finest: thesis_error(&e, &finest),
                error_exact: thesis_error(&e, &exact),
                efficiency: e,
            }
        })
        .collect();
    let dts: Vec<f64> = levels.iter().map(|l| l.dt).collect();
    let order_exact = loglog_slope(
        &dts,
        &levels.iter().map(|l| l.error_exact).collect::<Vec<_>>(),
    );
    let k = levels.len() - 1;
    let order_finest = loglog_slope(
        &dts[..k],
        &levels[..k]
            .iter()
            .map(|l| l.error_finest)
            .collect::<Vec<_>>(),
    );
    Ok(ConvergenceResult {
        xi: spec.xi.clone(),
        harmonic: spec.harmonic,
        levels,
        exact,
        order_exact,
        order_finest,
    })
}

impl ConvergenceResult {
    /// `convergence.csv`: one row per resolution (errors as fractions and percent).
    pub fn levels_csv(&self) -> String {
        let mut s = String::from(
            "samples_per_period,dt_s,dx_m,error_vs_finest,error_vs_exact,error_vs_finest_percent,error_vs_exact_percent\n",
        );
        for l in &self.levels {
            s.push_str(&format!(
                "{},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                l.samples_per_period,
                l.dt,
                l.dx,
                l.error_finest,
                l.error_exact,
                100.0 * l.error_finest,
                100.0 * l.error_exact
            ));
        }
        s
    }

    /// `efficiency.csv`: `xi`, then `A_n/A_inc` per resolution, then the exact solver's.
    pub fn curves_csv(&self) -> String {
        let mut s = String::from("xi");
        for l in &self.levels {
            s.push_str(&format!(",spp_{}", l.samples_per_period));
        }
        s.push_str(",exact\n");
        for (i, xi) in self.xi.iter().enumerate() {
            s.push_str(&format!("{xi}"));
            for l in &self.levels {
                s.push_str(&format!(",{:e}", l.efficiency[i]));
            }
            s.push_str(&format!(",{:e}\n", self.exact[i]));
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_error_and_slope() {
        // a uniform 1% error on 4 points: ||0.01 * ones(4)|| / 4 = 0.02 / 4
        let r = [1.0, 2.0, 3.0, 4.0];
        let a: Vec<f64> = r.iter().map(|x| x * 1.01).collect();
        assert!((thesis_error(&a, &r) - 0.005).abs() < 1e-12);
        // zero references are skipped
        assert!((thesis_error(&[1.0, 5.0], &[1.0, 0.0]) - 0.0).abs() < 1e-15);
        let x = [1.0, 2.0, 4.0, 8.0];
        let y: Vec<f64> = x.iter().map(|v: &f64| 3.0 * v.powi(2)).collect();
        assert!((loglog_slope(&x, &y) - 2.0).abs() < 1e-12);
    }
}

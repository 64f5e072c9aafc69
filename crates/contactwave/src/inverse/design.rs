//! Experiment design: rank candidate values of a condition (e.g. `incident.frequency`) by
//! the information the control curve would carry on the unknowns, at their nominal values
//! (the starting values of the identification file).
//!
//! For a candidate, the sensitivity matrix `S[i][j] = (d model_i / d z_j) / sigma_i` (rows:
//! control values x observed keys; `z`: scaled parameters;
//! `sigma_i = relative_noise |y_i| + absolute_noise` of `[fit]`, `y_i` the nominal model
//! value) is built by central differences. Ranked by `log10 det(S^T S)` (D-optimality),
//! ties broken by the smallest singular value of `S` (E-optimality).

use super::model::{toml_number, Model};
use super::sensitivity::svd_right;
use super::spec::Scale;
use crate::error::{Error, Result};
use crate::run::Executor;
use serde_json::json;

/// One ranked candidate.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignCandidate {
    /// Value of the design key (its unit).
    pub value: f64,
    /// `log10 det(S^T S)` (`-inf` when singular).
    pub log10_det: f64,
    /// Smallest singular value of `S`.
    pub min_singular: f64,
    /// All singular values of `S`, descending.
    pub singular_values: Vec<f64>,
    /// Rank, 1 = most informative.
    pub rank: usize,
}

/// The design ranking.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignReport {
    /// Design key, e.g. `incident.frequency`.
    pub key: String,
    /// Control variable and its values per candidate experiment.
    pub control: String,
    /// Control values used.
    pub control_values: Vec<f64>,
    /// Candidates in rank order.
    pub candidates: Vec<DesignCandidate>,
    /// Forward runs done.
    pub forward_runs: usize,
    /// Wall time, s.
    pub wall_seconds: f64,
}

/// Rank the `[design]` candidates of a spec.
pub fn design(model: &Model) -> Result<DesignReport> {
    let t0 = std::time::Instant::now();
    let spec = model.spec;
    let d = spec.design.as_ref().ok_or_else(|| {
        Error::invalid(
            spec.file.display().to_string(),
            "design",
            "(missing)",
            "a [design] table with the candidate values (e.g. frequencies = [0.5e6, 1e6])",
        )
    })?;
    let control = spec.measured.control().to_string();
    let cidx = 0;
    let control_values: Vec<f64> = match &d.control_values {
        Some(v) => v.clone(),
        None => {
            let mut v: Vec<f64> = spec.measured.rows.iter().map(|r| r[cidx]).collect();
            v.sort_by(f64::total_cmp);
            v.dedup();
            v
        }
    };
    // the design key must be settable
    {
        let mut t = spec.base_table.clone();
        crate::scenario::set_dotted(&mut t, &d.key, toml_number(&d.key, d.values[0]))
            .map_err(|e| e.in_file(&spec.file.display().to_string()))?;
    }
    let params = &spec.parameters;
    let nominal: Vec<f64> = params.iter().map(|p| p.initial).collect();
    let z0: Vec<f64> = params.iter().map(|p| p.to_scaled(p.initial)).collect();
    let fit = &spec.fit;
    let mut cands: Vec<DesignCandidate> = d
        .values
        .iter()
        .map(|&value| {
            // rows: control values; columns of S: parameters
            let rows: Vec<Vec<f64>> = Executor::new()
                .try_map(&control_values, |&c| {
                    let extra = vec![(control.clone(), c), (d.key.clone(), value)];
                    let run = |vals: &[f64]| -> Result<Vec<f64>> {
                        let s = model.run_with(0, vals, &extra)?;
                        Ok(spec
                            .measured
                            .observed
                            .iter()
                            .map(|o| s.get(&o.key).unwrap_or(f64::NAN))
                            .collect())
                    };
                    let y0 = run(&nominal)?;
                    let mut cols = Vec::with_capacity(params.len());
                    for (j, p) in params.iter().enumerate() {
                        let (lo, hi) = p.scaled_bounds();
                        let h = match p.scale {
                            Scale::Log => 1e-2,
                            Scale::Linear => 1e-3 * (hi - lo),
                        };
                        let (a, b) = ((z0[j] - h).max(lo), (z0[j] + h).min(hi));
                        let mut va = nominal.clone();
                        let mut vb = nominal.clone();
                        va[j] = p.from_scaled(a);
                        vb[j] = p.from_scaled(b);
                        let ya = run(&va)?;
                        let yb = run(&vb)?;
                        cols.push(
                            ya.iter()
                                .zip(&yb)
                                .zip(&y0)
                                .map(|((ya, yb), y)| {
                                    let sigma = (fit.relative_noise * y.abs() + fit.absolute_noise)
                                        .max(1e-300);
                                    (yb - ya) / (b - a) / sigma
                                })
                                .collect::<Vec<f64>>(),
                        );
                    }
                    // one S row per observed key
                    let nobs = y0.len();
                    Ok((0..nobs)
                        .map(|k| cols.iter().map(|c| c[k]).collect::<Vec<f64>>())
                        .collect::<Vec<Vec<f64>>>())
                })?
                .into_iter()
                .flatten()
                .collect();
            let (sv, _) = svd_right(&rows);
            let log10_det = sv.iter().map(|s| 2.0 * s.log10()).sum::<f64>();
            Ok(DesignCandidate {
                value,
                log10_det: if log10_det.is_nan() {
                    f64::NEG_INFINITY
                } else {
                    log10_det
                },
                min_singular: sv.last().copied().unwrap_or(0.0),
                singular_values: sv,
                rank: 0,
            })
        })
        .collect::<Result<_>>()?;
    cands.sort_by(|a, b| {
        b.log10_det
            .total_cmp(&a.log10_det)
            .then(b.min_singular.total_cmp(&a.min_singular))
    });
    for (i, c) in cands.iter_mut().enumerate() {
        c.rank = i + 1;
    }
    Ok(DesignReport {
        key: d.key.clone(),
        control,
        control_values,
        candidates: cands,
        forward_runs: model.forward_runs(),
        wall_seconds: t0.elapsed().as_secs_f64(),
    })
}

impl DesignReport {
    /// `design.json`.
    pub fn to_json(&self) -> serde_json::Value {
        let fin = |x: f64| if x.is_finite() { json!(x) } else { json!(null) };
        json!({
            "key": self.key,
            "control": self.control,
            "control_values": self.control_values,
            "forward_runs": self.forward_runs,
            "wall_seconds": self.wall_seconds,
            "candidates": self.candidates.iter().map(|c| json!({
                "rank": c.rank,
                "value": c.value,
                "log10_det": fin(c.log10_det),
                "min_singular_value": fin(c.min_singular),
                "singular_values": c.singular_values.iter().map(|&s| fin(s)).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        })
    }

    /// `design.csv`: rank, value, log10_det, min_singular_value.
    pub fn to_csv(&self) -> String {
        let mut s = format!("rank,{},log10_det,min_singular_value\n", self.key);
        for c in &self.candidates {
            s.push_str(&format!(
                "{},{},{},{}\n",
                c.rank, c.value, c.log10_det, c.min_singular
            ));
        }
        s
    }

    /// A plain-text table.
    pub fn table(&self) -> String {
        let mut s = format!(
            "{:>4} | {:>14} | {:>12} | {:>18}\n",
            "rank", self.key, "log10 det", "min singular value"
        );
        s.push_str(&"-".repeat(58));
        s.push('\n');
        for c in &self.candidates {
            s.push_str(&format!(
                "{:>4} | {:>14.6e} | {:>12.4} | {:>18.6e}\n",
                c.rank, c.value, c.log10_det, c.min_singular
            ));
        }
        s
    }
}

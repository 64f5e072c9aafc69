//! The result of an identification: estimates, intervals, identifiability, the fitted
//! curve, and their JSON and CSV forms (`crate::output::identify` renders its files).

use super::estimate::Estimate;
use super::identifiability::Identifiability;
use super::spec::{Measured, Parameter, Scale};

use serde_json::json;

/// A finished identification.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// The unknowns.
    pub parameters: Vec<Parameter>,
    /// The estimate.
    pub estimate: Estimate,
    /// Identifiability at the estimate.
    pub identifiability: Identifiability,
    /// The data.
    pub measured: Measured,
    /// Model values at the estimate, `[row][observed]`.
    pub fitted: Vec<Vec<f64>>,
    /// Forward runs done.
    pub forward_runs: usize,
    /// Forward runs that failed numerically or gave a non-finite observed value (the fit
    /// gave those parameter points a prohibitive cost and went on).
    pub failed_runs: usize,
    /// The first failed forward run, `row N: MESSAGE`.
    pub first_failure: Option<String>,
    /// Wall time, s.
    pub wall_seconds: f64,
}

fn fin(x: f64) -> serde_json::Value {
    if x.is_finite() {
        json!(x)
    } else {
        json!(null)
    }
}

impl Identification {
    /// Estimate of a parameter by key.
    pub fn estimate_of(&self, key: &str) -> Option<f64> {
        let j = self.parameters.iter().position(|p| p.key == key)?;
        Some(self.estimate.values[j])
    }

    /// Linearised 95% interval of a parameter by key (`None` if not identifiable).
    pub fn interval_of(&self, key: &str) -> Option<(f64, f64)> {
        let j = self.parameters.iter().position(|p| p.key == key)?;
        self.identifiability.intervals[j]
    }

    /// Whether a parameter was identified.
    pub fn identified(&self, key: &str) -> bool {
        self.parameters
            .iter()
            .position(|p| p.key == key)
            .is_some_and(|j| self.identifiability.verdicts[j].identified)
    }

    /// Norm of the weighted residual vector at the optimum, `sqrt(SSR)`.
    pub fn residual_norm(&self) -> f64 {
        self.estimate.cost.max(0.0).sqrt()
    }

    /// One line per parameter: `key: verdict`.
    pub fn verdict_lines(&self) -> Vec<String> {
        self.parameters
            .iter()
            .zip(&self.identifiability.verdicts)
            .map(|(p, v)| format!("{}: {}", p.key, v.text))
            .collect()
    }

    /// The `identification.json` object.
    pub fn to_json(&self) -> serde_json::Value {
        let id = &self.identifiability;
        let mut estimates = serde_json::Map::new();
        let mut intervals = serde_json::Map::new();
        let mut boot = serde_json::Map::new();
        let mut verdicts = serde_json::Map::new();
        let mut identified = serde_json::Map::new();
        let mut std_errors = serde_json::Map::new();
        let mut bound = serde_json::Map::new();
        for (j, p) in self.parameters.iter().enumerate() {
            estimates.insert(p.key.clone(), fin(self.estimate.values[j]));
            let iv = |x: Option<(f64, f64)>| match x {
                Some((a, b)) => json!([fin(a), fin(b)]),
                None => json!([null, null]),
            };
            intervals.insert(p.key.clone(), iv(id.intervals[j]));
            boot.insert(p.key.clone(), iv(id.bootstrap_intervals[j]));
            verdicts.insert(p.key.clone(), json!(id.verdicts[j].text));
            identified.insert(p.key.clone(), json!(id.verdicts[j].identified));
            std_errors.insert(p.key.clone(), fin(id.std_errors[j]));
            bound.insert(
                p.key.clone(),
                json!([fin(id.bound_delta_chi2[j].0), fin(id.bound_delta_chi2[j].1)]),
            );
        }
        let mut out = json!({
            "parameters": self.parameters.iter().map(|p| json!({
                "key": p.key,
                "bounds": [p.lower, p.upper],
                "scale": match p.scale { Scale::Log => "log", Scale::Linear => "linear" },
                "initial": p.initial,
            })).collect::<Vec<_>>(),
            "estimates": estimates,
            "intervals": intervals,
            "bootstrap_intervals": boot,
            "bootstrap_resamples": id.bootstrap_resamples,
            "verdicts": verdicts,
            "identified": identified,
            "std_errors_scaled": std_errors,
            "bound_delta_chi2": bound,
            "residual_norm": fin(self.residual_norm()),
            "cost": fin(self.estimate.cost),
            "residual_variance": fin(id.residual_variance),
            "data_points": self.measured.len(),
            "residuals": self.measured.residual_count(),
            "forward_runs": self.forward_runs,
            "wall_seconds": self.wall_seconds,
            "global_stage": {
                "estimate_scaled": self.estimate.global_z,
                "cost": fin(self.estimate.global_cost),
            },
            "local_iterations": self.estimate.local_iterations,
            "jacobian_svd": {
                "scaled_space": "log10 of log parameters, the value of linear ones",
                "singular_values": id.singular_values.iter().map(|&s| fin(s)).collect::<Vec<_>>(),
                "right_singular_vectors": id.singular_vectors,
                "condition_number": fin(id.condition_number),
                "parameter_order": self.parameters.iter().map(|p| p.key.clone()).collect::<Vec<_>>(),
            },
        });
        // only when some forward run failed (the keys are absent otherwise)
        if self.failed_runs > 0 {
            out["failed_forward_runs"] = json!(self.failed_runs);
            out["first_failure"] = json!(self.first_failure);
        }
        out
    }

    /// `fit.csv`: conditions, then measured, fitted and sigma per observed key.
    pub fn fit_csv(&self) -> String {
        let m = &self.measured;
        let mut h: Vec<String> = m.conditions.clone();
        for o in &m.observed {
            h.push(o.key.clone());
            h.push(format!("fitted_{}", o.key));
            h.push(format!("sigma_{}", o.key));
        }
        let mut s = h.join(",");
        s.push('\n');
        for (i, row) in m.rows.iter().enumerate() {
            let mut cells: Vec<String> = row.iter().map(|v| v.to_string()).collect();
            for (k, o) in m.observed.iter().enumerate() {
                cells.push(o.values[i].to_string());
                cells.push(self.fitted[i][k].to_string());
                cells.push(o.sigma[i].to_string());
            }
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }
}

//! Identifiability at the optimum, reported rather than assumed.
//!
//! - `J`: Jacobian of the weighted residuals `(model - y)/sigma` with respect to the scaled
//!   parameters (log10 for log parameters), by central finite differences (one-sided at a
//!   bound).
//! - Its singular values and right singular vectors (eigen-decomposition of `J^T J` by
//!   Jacobi rotations) and its condition number `s_max / s_min`.
//! - Linearised 95% intervals: covariance `s^2 (J^T J)^-1`, `s^2 = SSR / (n - p)`, Student
//!   t quantile; directions with `s_k < 1e-6 s_max` count as unconstrained.
//! - Bound check: the cost with one parameter moved to each of its bounds (others at the
//!   optimum); a side where `delta chi^2 = (cost_bound - cost) / s^2 < 3.84` is not
//!   constrained by the data.
//! - Bootstrap: rows resampled with replacement, local refit (Nelder-Mead) from the
//!   optimum; 2.5% and 97.5% percentiles.
//!
//! Verdict: a parameter is identified when its linearised interval is finite, lies inside
//! its bounds, spans less than a decade on each side (log) or half the range (linear),
//! and both bounds are rejected by the data; otherwise it is not identifiable and no
//! interval is given.
//!
//! The Jacobian and its singular value decomposition come from `sensitivity`; the
//! refits from the estimation.

use super::estimate::{refine, Estimate, LeastSquares};
use super::model::Model;
use super::spec::Scale;
use crate::error::{Error, Result};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

// The Jacobian and its SVD live below the estimation and this module (both need them);
// re-exported here, where they were defined before.
pub use super::sensitivity::{jacobian, svd_right, symmetric_eigen};

/// `delta chi^2` of a 95% one-parameter interval.
const CHI2_95: f64 = 3.841;
/// Singular values below this fraction of the largest are treated as zero.
const SINGULAR_FLOOR: f64 = 1e-6;

/// Verdict on one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Identified (a finite interval inside the bounds).
    pub identified: bool,
    /// Plain-language verdict, e.g. `identified, 95% CI [1.9e13, 2.1e13]`.
    pub text: String,
}

/// The identifiability analysis at the optimum.
#[derive(Debug, Clone, PartialEq)]
pub struct Identifiability {
    /// Jacobian of the weighted residuals w.r.t. the scaled parameters, `[residual][param]`.
    pub jacobian: Vec<Vec<f64>>,
    /// Singular values of `J`, descending.
    pub singular_values: Vec<f64>,
    /// Right singular vectors: `singular_vectors[k][j]` = component `j` of vector `k`.
    pub singular_vectors: Vec<Vec<f64>>,
    /// `s_max / s_min` (infinite when `s_min = 0`).
    pub condition_number: f64,
    /// Residual variance `s^2 = SSR / (n - p)` (1 when n = p).
    pub residual_variance: f64,
    /// Standard errors in the scaled space (infinite when unconstrained).
    pub std_errors: Vec<f64>,
    /// Linearised 95% intervals in the keys' units (`None`: not identifiable).
    pub intervals: Vec<Option<(f64, f64)>>,
    /// Bootstrap 95% intervals in the keys' units (`None`: no bootstrap, or not identifiable).
    pub bootstrap_intervals: Vec<Option<(f64, f64)>>,
    /// Number of bootstrap refits done.
    pub bootstrap_resamples: usize,
    /// `delta chi^2` with the parameter at its (lower, upper) bound.
    pub bound_delta_chi2: Vec<(f64, f64)>,
    /// Verdicts.
    pub verdicts: Vec<Verdict>,
}

pub use crate::numeric::t975;

/// The whole analysis at the estimate.
pub fn analyse(
    model: &Model,
    est: &Estimate,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Identifiability> {
    let spec = model.spec;
    let params = &spec.parameters;
    let p = params.len();
    let rows: Vec<usize> = (0..spec.measured.len()).collect();
    let n = spec.measured.residual_count();
    let z = &est.z;
    let jac = jacobian(model, z, &rows)?;
    let (sv, vecs) = svd_right(&jac);
    let smax = sv.first().copied().unwrap_or(0.0);
    let smin = sv.last().copied().unwrap_or(0.0);
    let condition_number = if smin > 0.0 {
        smax / smin
    } else {
        f64::INFINITY
    };
    let dof = n.saturating_sub(p);
    let s2 = if dof > 0 {
        (est.cost / dof as f64).max(1e-300)
    } else {
        1.0
    };
    // covariance s^2 V diag(1/s_k^2) V^T
    let mut std_errors = vec![0.0; p];
    for (jp, se) in std_errors.iter_mut().enumerate() {
        let mut var = 0.0;
        for (k, &s) in sv.iter().enumerate() {
            let vk = vecs[k][jp];
            if vk == 0.0 {
                continue;
            }
            if !(s > SINGULAR_FLOOR * smax) {
                if vk.abs() > 1e-3 {
                    var = f64::INFINITY;
                }
                continue;
            }
            var += vk * vk / (s * s);
        }
        *se = (s2 * var).sqrt();
    }
    let t = t975(dof.max(1));
    // bound check
    let ls = LeastSquares::new(model, rows.clone());
    let bound_delta_chi2: Vec<(f64, f64)> = (0..p)
        .map(|j| {
            let (lo, hi) = params[j].scaled_bounds();
            let mut d = [0.0; 2];
            for (k, b) in [lo, hi].into_iter().enumerate() {
                let mut zb = z.clone();
                zb[j] = b;
                d[k] = if (b - z[j]).abs() < 1e-12 * (hi - lo) {
                    0.0
                } else {
                    (ls.evaluate(&zb)? - est.cost) / s2
                };
            }
            Ok((d[0], d[1]))
        })
        .collect::<Result<_>>()?;
    // bootstrap
    let mut boot: Vec<Vec<f64>> = Vec::new();
    if spec.fit.bootstrap > 0 && spec.measured.len() >= 2 {
        progress(&format!(
            "bootstrap: {} resamples, local refits from the optimum",
            spec.fit.bootstrap
        ));
        let mut rng = StdRng::seed_from_u64(spec.fit.seed.wrapping_add(0x5eed));
        let m = spec.measured.len();
        let samples: Vec<Vec<usize>> = (0..spec.fit.bootstrap)
            .map(|_| (0..m).map(|_| rng.random_range(0..m)).collect())
            .collect();
        boot = samples
            .into_iter()
            .map(|rs| refine(model, rs, z, 0.02, spec.fit.bootstrap_iterations, 1e-3).map(|r| r.0))
            .collect::<Result<_>>()?;
    }
    let mut intervals = Vec::with_capacity(p);
    let mut bootstrap_intervals = Vec::with_capacity(p);
    let mut verdicts = Vec::with_capacity(p);
    for (j, par) in params.iter().enumerate() {
        let (lo, hi) = par.scaled_bounds();
        let half = t * std_errors[j];
        let (a, b) = (z[j] - half, z[j] + half);
        let max_half = match par.scale {
            Scale::Log => 1.0,
            Scale::Linear => 0.5 * (hi - lo),
        };
        let (dl, du) = bound_delta_chi2[j];
        let flat_low = dl < CHI2_95;
        let flat_high = du < CHI2_95;
        let finite = half.is_finite();
        let inside = finite && a >= lo && b <= hi;
        let narrow = finite && half <= max_half;
        let identified = finite && inside && narrow && !flat_low && !flat_high;
        let value = est.values[j];
        let boot_ci = if boot.len() >= 5 && identified {
            let mut v: Vec<f64> = boot.iter().map(|b| b[j]).collect();
            v.sort_by(f64::total_cmp);
            let q = |f: f64| v[((f * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)];
            Some((par.from_scaled(q(0.025)), par.from_scaled(q(0.975))))
        } else {
            None
        };
        let text = if identified {
            let (ca, cb) = (par.from_scaled(a), par.from_scaled(b));
            intervals.push(Some((ca, cb)));
            format!("identified, 95% CI [{ca:.4e}, {cb:.4e}]")
        } else {
            intervals.push(None);
            if flat_low && flat_high {
                "not identifiable from these data (the curve does not depend on it)".to_string()
            } else if flat_low || flat_high {
                // the curve is flat between one bound and the estimate
                let (limit, bound_name, bound) = if flat_low {
                    ("an upper", "lower", par.lower)
                } else {
                    ("a lower", "upper", par.upper)
                };
                let flat = if (value - bound).abs() <= 1e-6 * bound.abs() {
                    format!(
                        "the best fit lies at the {bound_name} bound {bound:.4e}: the curve is flat towards it"
                    )
                } else if flat_low {
                    format!(
                        "the curve does not change between the lower bound {bound:.4e} and the estimate {value:.4e}"
                    )
                } else {
                    format!(
                        "the curve does not change between the estimate {value:.4e} and the upper bound {bound:.4e}"
                    )
                };
                format!("not identifiable from these data: only {limit} limit ({flat})")
            } else if !finite {
                "not identifiable from these data (zero sensitivity along a combination of \
                 parameters: correlated with another parameter)"
                    .to_string()
            } else {
                "not identifiable from these data (the 95% interval is wider than the \
                 bounds or than a decade: weak sensitivity or correlation)"
                    .to_string()
            }
        };
        bootstrap_intervals.push(boot_ci);
        verdicts.push(Verdict { identified, text });
    }
    if !s2.is_finite() {
        return Err(Error::numerical(0.0, "residual variance not finite", ""));
    }
    Ok(Identifiability {
        jacobian: jac,
        singular_values: sv,
        singular_vectors: vecs,
        condition_number,
        residual_variance: s2,
        std_errors,
        intervals,
        bootstrap_intervals,
        bootstrap_resamples: boot.len(),
        bound_delta_chi2,
        verdicts,
    })
}

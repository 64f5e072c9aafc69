//! The estimation: an argmin problem (weighted least squares in the scaled parameter space),
//! a global stage (argmin `ParticleSwarm`) and a local refinement (argmin `NelderMead`),
//! run by argmin's `Executor`. The swarm's particles are evaluated in parallel (argmin's
//! `rayon` feature) and so are the rows of each curve.

use super::model::Model;
use super::sensitivity::{jacobian, svd_right};
use crate::error::{Error, Result};
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use argmin::solver::particleswarm::ParticleSwarm;
use rand::rngs::StdRng;
use rand::SeedableRng;
use std::sync::{Arc, Mutex};

/// Cost given to a parameter point whose forward run failed numerically.
const FAILED_COST: f64 = 1e30;

/// The argmin problem: `sum r_i^2` of the weighted residuals over `rows` (a row may repeat:
/// bootstrap resamples), with a quadratic penalty outside the bounds (Nelder-Mead is
/// unbounded; the point is clamped into the bounds for the forward runs).
pub struct LeastSquares<'m, 'a> {
    /// The forward model.
    pub model: &'m Model<'a>,
    /// Rows of the data used (with repetitions).
    pub rows: Vec<usize>,
    /// The first error of a cost evaluation under argmin (which unwraps some of them):
    /// kept here, the cost made infinite, and every later evaluation skipped; the caller
    /// returns it after the executor ([`LeastSquares::solved`]).
    failure: Arc<Mutex<Option<Error>>>,
}

impl<'m, 'a> LeastSquares<'m, 'a> {
    /// The problem over `rows` of `model`.
    pub fn new(model: &'m Model<'a>, rows: Vec<usize>) -> Self {
        LeastSquares {
            model,
            rows,
            failure: Arc::default(),
        }
    }

    /// A handle on the failure slot, to read after the executor has taken the problem.
    fn failures(&self) -> Arc<Mutex<Option<Error>>> {
        self.failure.clone()
    }

    /// `result`, unless a cost evaluation failed meanwhile: then that error.
    fn solved<T>(
        failure: &Mutex<Option<Error>>,
        result: std::result::Result<T, argmin::core::Error>,
    ) -> Result<T> {
        if let Some(e) = failure.lock().ok().and_then(|mut f| f.take()) {
            return Err(e);
        }
        result.map_err(argmin_err)
    }

    /// Sum of squared weighted residuals at scaled coordinates `z` (bounds penalty
    /// included); `Err` only for errors other than numerical failures.
    pub fn evaluate(&self, z: &[f64]) -> Result<f64> {
        let mut penalty = 0.0;
        let zc: Vec<f64> = self
            .model
            .spec
            .parameters
            .iter()
            .zip(z)
            .map(|(p, &z)| {
                let (lo, hi) = p.scaled_bounds();
                let c = z.clamp(lo, hi);
                let d = (z - c) / (hi - lo);
                penalty += d * d;
                c
            })
            .collect();
        // forward-run each distinct row once
        let mut unique = self.rows.clone();
        unique.sort_unstable();
        unique.dedup();
        let curves = match self.model.curves_at(&zc, &unique) {
            Ok(c) => c,
            Err(Error::Numerical { .. }) => return Ok(FAILED_COST),
            Err(e) => return Err(e),
        };
        let r = self.model.weigh(&curves, &unique);
        let nobs = self.model.spec.measured.observed.len();
        let mut sum = 0.0;
        for &i in &self.rows {
            let k = unique.binary_search(&i).unwrap_or(0);
            for x in &r[k * nobs..(k + 1) * nobs] {
                sum += if x.is_finite() { x * x } else { FAILED_COST };
            }
        }
        Ok(sum + 1e3 * penalty * (1.0 + sum))
    }
}

impl CostFunction for LeastSquares<'_, '_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, z: &Self::Param) -> std::result::Result<f64, argmin::core::Error> {
        // argmin's Nelder-Mead unwraps the costs of its first simplex: an error is kept
        // for the caller instead, and the search runs out on infinite costs
        let failed = |f: &Mutex<Option<Error>>| f.lock().map(|f| f.is_some()).unwrap_or(true);
        if failed(&self.failure) {
            return Ok(f64::INFINITY);
        }
        match self.evaluate(z) {
            Ok(c) => Ok(c),
            Err(e) => {
                if let Ok(mut f) = self.failure.lock() {
                    f.get_or_insert(e);
                }
                Ok(f64::INFINITY)
            }
        }
    }
}

/// Result of the estimation (scaled coordinates: log10 for log parameters).
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Optimum, scaled coordinates.
    pub z: Vec<f64>,
    /// Optimum, parameter values (SI units of the keys).
    pub values: Vec<f64>,
    /// Sum of squared weighted residuals at the optimum.
    pub cost: f64,
    /// Best point of the global stage (scaled) and its cost.
    pub global_z: Vec<f64>,
    /// Cost of the global stage's best point.
    pub global_cost: f64,
    /// Iterations of the local stage.
    pub local_iterations: u64,
}

fn argmin_err(e: argmin::core::Error) -> Error {
    // an interruption inside a cost evaluation stays an interruption (exit 130,
    // KeyboardInterrupt), not a numerical failure
    if crate::interrupt::requested() {
        return Error::Interrupted;
    }
    Error::numerical(0.0, format!("optimiser: {e}"), "identification")
}

/// Local refinement (Nelder-Mead) from `z0` on `rows`, initial simplex steps `step`
/// (fractions of each scaled range), at most `iters` iterations, stopping when the
/// standard deviation of the simplex costs falls below `tolerance`. Returns (z, cost, iters).
pub fn refine(
    model: &Model,
    rows: Vec<usize>,
    z0: &[f64],
    step: f64,
    iters: u64,
    tolerance: f64,
) -> Result<(Vec<f64>, f64, u64)> {
    let params = &model.spec.parameters;
    let mut simplex = vec![z0.to_vec()];
    for (j, p) in params.iter().enumerate() {
        let (lo, hi) = p.scaled_bounds();
        let h = step * (hi - lo);
        let mut v = z0.to_vec();
        v[j] = if z0[j] + h <= hi {
            z0[j] + h
        } else {
            z0[j] - h
        };
        simplex.push(v);
    }
    refine_simplex(model, rows, z0, simplex, iters, tolerance)
}

/// Local refinement with a simplex aligned on the right singular vectors of the Jacobian
/// at `z0`, each edge as long as the 1-sigma change along it (clamped to [1e-3, 0.2] of
/// the smallest scaled range): Nelder-Mead then walks along valleys of correlated
/// parameters (e.g. C and m of a power law) instead of zig-zagging across them.
pub fn refine_aligned(
    model: &Model,
    rows: Vec<usize>,
    z0: &[f64],
    iters: u64,
    tolerance: f64,
) -> Result<(Vec<f64>, f64, u64)> {
    let params = &model.spec.parameters;
    let mut unique = rows.clone();
    unique.sort_unstable();
    unique.dedup();
    let jac = match jacobian(model, z0, &unique) {
        Ok(j) => j,
        Err(Error::Numerical { .. }) => return refine(model, rows, z0, 0.01, iters, tolerance),
        Err(e) => return Err(e),
    };
    let (sv, vecs) = svd_right(&jac);
    let range = params
        .iter()
        .map(|p| {
            let (lo, hi) = p.scaled_bounds();
            hi - lo
        })
        .fold(f64::INFINITY, f64::min);
    let mut simplex = vec![z0.to_vec()];
    for (s, v) in sv.iter().zip(&vecs) {
        let h = if *s > 0.0 { 1.0 / s } else { f64::INFINITY };
        let h = h.clamp(1e-3 * range, 0.2 * range);
        simplex.push(z0.iter().zip(v).map(|(z, v)| z + h * v).collect());
    }
    refine_simplex(model, rows, z0, simplex, iters, tolerance)
}

/// Nelder-Mead from the given simplex (its first vertex `z0`).
fn refine_simplex(
    model: &Model,
    rows: Vec<usize>,
    z0: &[f64],
    simplex: Vec<Vec<f64>>,
    iters: u64,
    tolerance: f64,
) -> Result<(Vec<f64>, f64, u64)> {
    let params = &model.spec.parameters;
    let problem = LeastSquares::new(model, rows);
    let c0 = problem.evaluate(z0)?;
    if iters == 0 {
        return Ok((z0.to_vec(), c0, 0));
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(tolerance)
        .map_err(argmin_err)?;
    let failure = problem.failures();
    let res = LeastSquares::solved(
        &failure,
        Executor::new(problem, solver)
            .configure(|s| s.max_iters(iters))
            .run(),
    )?;
    let st = res.state();
    let z = st.get_best_param().cloned().unwrap_or_else(|| z0.to_vec());
    let cost = st.get_best_cost();
    let z: Vec<f64> = params
        .iter()
        .zip(z)
        .map(|(p, z)| {
            let (lo, hi) = p.scaled_bounds();
            z.clamp(lo, hi)
        })
        .collect();
    if cost <= c0 {
        Ok((z, cost, st.get_iter()))
    } else {
        Ok((z0.to_vec(), c0, st.get_iter()))
    }
}

/// Global (particle swarm) then local (Nelder-Mead, restarted once) minimisation of the
/// weighted least squares over every row.
pub fn estimate(model: &Model, progress: &(dyn Fn(&str) + Sync)) -> Result<Estimate> {
    let spec = model.spec;
    let fit = &spec.fit;
    let rows: Vec<usize> = (0..spec.measured.len()).collect();
    let z_init: Vec<f64> = spec
        .parameters
        .iter()
        .map(|p| p.to_scaled(p.initial))
        .collect();
    let init_cost = LeastSquares::new(model, rows.clone()).evaluate(&z_init)?;
    let (mut global_z, mut global_cost) = (z_init.clone(), init_cost);
    // starting points of the local stage: the best particles of the swarm
    let mut starts: Vec<(Vec<f64>, f64)> = vec![(z_init.clone(), init_cost)];
    if fit.particles >= 2 && fit.iterations > 0 {
        let (lo, hi): (Vec<f64>, Vec<f64>) =
            spec.parameters.iter().map(|p| p.scaled_bounds()).unzip();
        let pso = ParticleSwarm::new((lo, hi), fit.particles)
            .with_rng_generator(StdRng::seed_from_u64(fit.seed));
        let problem = LeastSquares::new(model, rows.clone());
        let failure = problem.failures();
        let res = LeastSquares::solved(
            &failure,
            Executor::new(problem, pso)
                .configure(|s| s.max_iters(fit.iterations))
                .run(),
        )?;
        let st = res.state();
        if let Some(best) = st.get_best_param()
            && st.get_best_cost() < global_cost
        {
            global_z = best.position.clone();
            global_cost = st.get_best_cost();
        }
        if let Some(pop) = st.get_population() {
            starts.extend(pop.iter().map(|p| (p.position.clone(), p.cost)));
        }
        starts.push((global_z.clone(), global_cost));
        progress(&format!(
            "global stage (particle swarm, {} particles x {} iterations): cost {:.6e}",
            fit.particles, fit.iterations, global_cost
        ));
    }
    starts.sort_by(|a, b| a.1.total_cmp(&b.1));
    // distinct starts: at least 5% of the scaled range apart in some coordinate
    let mut chosen: Vec<Vec<f64>> = Vec::new();
    for (z, _) in starts {
        let distinct = chosen.iter().all(|c| {
            c.iter().zip(&z).zip(&spec.parameters).any(|((a, b), p)| {
                let (lo, hi) = p.scaled_bounds();
                (a - b).abs() > 0.05 * (hi - lo)
            })
        });
        if distinct {
            chosen.push(z);
        }
        if chosen.len() >= fit.local_starts.max(1) {
            break;
        }
    }
    let mut best: Option<(Vec<f64>, f64, u64)> = None;
    let mut iters = 0;
    for z0 in &chosen {
        let (z1, _, i1) = refine(model, rows.clone(), z0, 0.05, fit.local_iterations, 1e-6)?;
        let (z2, c2, i2) =
            refine_aligned(model, rows.clone(), &z1, fit.local_iterations / 2, 1e-6)?;
        iters += i1 + i2;
        if best.as_ref().is_none_or(|b| c2 < b.1) {
            best = Some((z2, c2, i1 + i2));
        }
    }
    let (z, cost, _) = best.unwrap_or((global_z.clone(), global_cost, 0));
    progress(&format!(
        "local stage (Nelder-Mead from {} starts, {} iterations): cost {:.6e}",
        chosen.len(),
        iters,
        cost
    ));
    Ok(Estimate {
        values: model.values(&z),
        z,
        cost,
        global_z,
        global_cost,
        local_iterations: iters,
    })
}

//! Local sensitivity of the forward model: the [`jacobian`] of the weighted residuals with
//! respect to the scaled parameters, and its singular values and right singular vectors
//! ([`svd_right`], by [`symmetric_eigen`] of `J^T J`).
//!
//! Shared by the estimation (the aligned Nelder-Mead simplex), the identifiability analysis
//! and the experiment design; it sits below all three and uses only the forward model.

use super::model::Model;
use super::spec::Scale;
use crate::error::Result;
use crate::run::Executor;

/// Eigen-decomposition of a symmetric matrix by cyclic Jacobi rotations: (eigenvalues
/// descending, eigenvectors as rows in the same order).
pub fn symmetric_eigen(a: &[Vec<f64>]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut m: Vec<Vec<f64>> = a.to_vec();
    let mut v: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| m[i][j] * m[i][j])
            .sum();
        let diag: f64 = (0..n).map(|i| m[i][i] * m[i][i]).sum();
        if off <= 1e-30 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if m[p][q] == 0.0 {
                    continue;
                }
                let theta = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (mkp, mkq) = (m[k][p], m[k][q]);
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for k in 0..n {
                    let (mpk, mqk) = (m[p][k], m[q][k]);
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k][p], v[k][q]);
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| m[j][j].total_cmp(&m[i][i]));
    let values = order.iter().map(|&i| m[i][i]).collect();
    let vectors = order
        .iter()
        .map(|&i| (0..n).map(|k| v[k][i]).collect())
        .collect();
    (values, vectors)
}

/// Jacobian of the weighted residuals over `rows` w.r.t. the scaled parameters at `z`
/// (central differences, step 1e-2 of a decade for log parameters, 1e-3 of the range for
/// linear ones; one-sided at a bound). `[residual][param]`.
pub fn jacobian(model: &Model, z: &[f64], rows: &[usize]) -> Result<Vec<Vec<f64>>> {
    let params = &model.spec.parameters;
    let columns: Vec<usize> = (0..params.len()).collect();
    let cols: Vec<Vec<f64>> = Executor::new().try_map(&columns, |&j| {
        let p = &params[j];
        let (lo, hi) = p.scaled_bounds();
        let h = match p.scale {
            Scale::Log => 1e-2,
            Scale::Linear => 1e-3 * (hi - lo),
        };
        let (a, b) = ((z[j] - h).max(lo), (z[j] + h).min(hi));
        let mut za = z.to_vec();
        let mut zb = z.to_vec();
        za[j] = a;
        zb[j] = b;
        let ra = model.residuals_at(&za, rows)?;
        let rb = model.residuals_at(&zb, rows)?;
        Ok(ra.iter().zip(&rb).map(|(x, y)| (y - x) / (b - a)).collect())
    })?;
    let n = cols.first().map(Vec::len).unwrap_or(0);
    Ok((0..n)
        .map(|i| cols.iter().map(|c| c[i]).collect())
        .collect())
}

/// Singular values (descending) and right singular vectors of `J` (rows = residuals).
pub fn svd_right(j: &[Vec<f64>]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let p = j.first().map(Vec::len).unwrap_or(0);
    let mut jtj = vec![vec![0.0; p]; p];
    for row in j {
        for a in 0..p {
            for b in 0..p {
                jtj[a][b] += row[a] * row[b];
            }
        }
    }
    let (vals, vecs) = symmetric_eigen(&jtj);
    (vals.iter().map(|l| l.max(0.0).sqrt()).collect(), vecs)
}

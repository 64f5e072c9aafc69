//! One step of the 3-stage Radau IIA method (order 5, L-stable, stiffly accurate) for the
//! three interface unknowns `y = ([u]_N, beta, [u]_T)` of the coupled problem, with a
//! finite-difference Jacobian and simplified Newton iterations on the 9 stage unknowns.
//! Components whose right-hand side vanishes in the current phase (held gaps, frozen
//! adhesion) stay exactly constant. No allocation.

use crate::solver::radau::{A, C};

/// Number of unknowns.
pub const N: usize = 3;
const M: usize = 3 * N;

/// A stage-time evaluation of the right-hand side: `f(t, y)`.
pub trait Rhs {
    /// `dy/dt` at `(t, y)`.
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N];
}

/// The result of one step.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// Stage values `Y_j = y(t + c_j h)`, j = 0..3 (the last is the end of the step).
    pub stages: [[f64; N]; 3],
}

impl Step {
    /// State at the end of the step.
    pub fn end(&self) -> [f64; N] {
        self.stages[2]
    }
}

/// Solve `M x = b` in place by Gaussian elimination with partial pivoting; `false` if
/// singular.
fn solve(m: &mut [[f64; M]; M], b: &mut [f64; M]) -> bool {
    for col in 0..M {
        let mut piv = col;
        let mut best = m[col][col].abs();
        for (r, row) in m.iter().enumerate().skip(col + 1) {
            if row[col].abs() > best {
                best = row[col].abs();
                piv = r;
            }
        }
        if !(best > 0.0) || !best.is_finite() {
            return false;
        }
        m.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..M {
            let f = m[r][col] / m[col][col];
            if f != 0.0 {
                for c in col..M {
                    m[r][c] -= f * m[col][c];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for col in (0..M).rev() {
        let mut v = b[col];
        for c in col + 1..M {
            v -= m[col][c] * b[c];
        }
        b[col] = v / m[col][col];
    }
    true
}

/// One Radau IIA step of size `h` from `(t, y)`; `active[i]` says which components
/// evolve, `scale[i]` is their magnitude (for the finite-difference Jacobian and the
/// Newton tolerance). `None` when Newton does not converge (the caller splits the step).
pub fn step(
    f: &impl Rhs,
    t: f64,
    y: &[f64; N],
    h: f64,
    active: [bool; N],
    scale: [f64; N],
) -> Option<Step> {
    if !active.iter().any(|&a| a) {
        return Some(Step { stages: [*y; 3] });
    }
    // Jacobian by forward differences on the active components
    let f0 = f.rhs(t, y);
    let mut jac = [[0.0; N]; N];
    for j in 0..N {
        if !active[j] {
            continue;
        }
        let d = 1e-7 * y[j].abs().max(scale[j]);
        let mut yp = *y;
        yp[j] += d;
        let fp = f.rhs(t, &yp);
        for i in 0..N {
            if active[i] {
                jac[i][j] = (fp[i] - f0[i]) / d;
            }
        }
    }
    // iteration matrix I - h (A ⊗ J)
    let mut iter = [[0.0; M]; M];
    for a in 0..3 {
        for i in 0..N {
            let r = a * N + i;
            iter[r][r] = 1.0;
            for b in 0..3 {
                for j in 0..N {
                    iter[r][b * N + j] -= h * A[a][b] * jac[i][j];
                }
            }
        }
    }
    let mut z = [[0.0; N]; 3];
    // explicit predictor: Z_a = c_a h f(t, y)
    for (a, za) in z.iter_mut().enumerate() {
        for i in 0..N {
            if active[i] {
                za[i] = C[a] * h * f0[i];
            }
        }
    }
    let mut prev_norm = f64::INFINITY;
    for _ in 0..25 {
        let mut fz = [[0.0; N]; 3];
        for a in 0..3 {
            let mut ya = *y;
            for i in 0..N {
                ya[i] += z[a][i];
            }
            fz[a] = f.rhs(t + C[a] * h, &ya);
        }
        let mut rhs = [0.0; M];
        for a in 0..3 {
            for i in 0..N {
                if !active[i] {
                    continue;
                }
                let mut g = z[a][i];
                for b in 0..3 {
                    g -= h * A[a][b] * fz[b][i];
                }
                rhs[a * N + i] = -g;
            }
        }
        let mut m = iter;
        if !solve(&mut m, &mut rhs) {
            return None;
        }
        let mut norm: f64 = 0.0;
        for a in 0..3 {
            for i in 0..N {
                if active[i] {
                    z[a][i] += rhs[a * N + i];
                    norm = norm.max(rhs[a * N + i].abs() / (scale[i] + z[a][i].abs()));
                }
            }
        }
        if !norm.is_finite() {
            return None;
        }
        if norm < 1e-14 || (norm < 1e-11 && norm > 0.5 * prev_norm) {
            let mut stages = [*y; 3];
            for a in 0..3 {
                for i in 0..N {
                    stages[a][i] += z[a][i];
                }
            }
            return Some(Step { stages });
        }
        prev_norm = norm;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Decay;
    impl Rhs for Decay {
        fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N] {
            [-1e3 * (y[0] - t.sin()), 0.0, -y[2]]
        }
    }

    #[test]
    fn order_five_on_a_linear_problem_and_frozen_components_stay() {
        // y2' = -y2: exact exp(-t); error of 10 steps of 0.1 is O(h^5)
        let mut y = [0.0, 0.7, 1.0];
        let h = 0.1;
        for k in 0..10 {
            y = step(&Decay, k as f64 * h, &y, h, [true, false, true], [1.0; 3])
                .unwrap()
                .end();
        }
        assert!((y[2] - (-1.0f64).exp()).abs() < 1e-8);
        assert_eq!(y[1], 0.7);
        // stiff component: close to its slow manifold sin(t) - cos(t)/1e3
        let slow = 1f64.sin() - 1f64.cos() / 1e3;
        assert!((y[0] - slow).abs() < 1e-5);
    }
}

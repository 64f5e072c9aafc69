//! The derivative along one line of GLL points, by the even-odd decomposition: the GLL
//! derivative matrix is centro-antisymmetric (`d[M-1-i][M-1-j] = -d[i][j]`, the points
//! symmetric about the centre), and so is its transpose, so that with the sums
//! `s_k = x_k + x_{M-1-k}` and differences `o_k = x_k - x_{M-1-k}` of mirrored values
//!
//! ```text
//! y_a = E_a + O_a,  y_{M-1-a} = O_a - E_a,  E_a = sum_k p_ak s_k (+ d_a,mid x_mid),
//! O_a = sum_k q_ak o_k,  p_ak = (d_ak + d_a,M-1-k) / 2,  q_ak = (d_ak - d_a,M-1-k) / 2
//! ```
//!
//! (`k < M/2`; the middle row of an odd `M` is `y_mid = sum_k q_mid,k o_k`): 27 operations
//! for the five points of order 4 instead of 45, the same values to round-off. Each
//! operation acts on `L` lanes (elements) at once.

/// The coefficients `p`, `q` and the middle column of a centro-antisymmetric matrix.
#[derive(Debug, Clone, Copy)]
pub(super) struct EvenOdd<const M: usize> {
    pub(super) p: [[f64; M]; M],
    pub(super) q: [[f64; M]; M],
    pub(super) mid: [f64; M],
}

impl<const M: usize> EvenOdd<M> {
    /// From `d[i][j]` (the derivative matrix, or its transpose).
    pub(super) fn new(d: &[[f64; M]; M]) -> Self {
        let mut c = EvenOdd {
            p: [[0.0; M]; M],
            q: [[0.0; M]; M],
            mid: [0.0; M],
        };
        let h = M / 2;
        for a in 0..M.div_ceil(2) {
            for k in 0..h {
                c.p[a][k] = 0.5 * (d[a][k] + d[a][M - 1 - k]);
                c.q[a][k] = 0.5 * (d[a][k] - d[a][M - 1 - k]);
            }
            if M % 2 == 1 {
                c.mid[a] = d[a][h];
            }
        }
        c
    }

    /// `y = d x` on `L` lanes.
    #[inline(always)]
    pub(super) fn apply<const L: usize>(&self, x: &[[f64; L]; M], y: &mut [[f64; L]; M]) {
        let h = M / 2;
        let mut s = [[0.0f64; L]; M];
        let mut o = [[0.0f64; L]; M];
        for k in 0..h {
            for l in 0..L {
                s[k][l] = x[k][l] + x[M - 1 - k][l];
                o[k][l] = x[k][l] - x[M - 1 - k][l];
            }
        }
        for a in 0..h {
            let (mut e, mut od) = ([0.0f64; L], [0.0f64; L]);
            for l in 0..L {
                e[l] = self.p[a][0] * s[0][l];
                od[l] = self.q[a][0] * o[0][l];
            }
            for k in 1..h {
                for l in 0..L {
                    e[l] += self.p[a][k] * s[k][l];
                    od[l] += self.q[a][k] * o[k][l];
                }
            }
            if M % 2 == 1 {
                for l in 0..L {
                    e[l] += self.mid[a] * x[h][l];
                }
            }
            for l in 0..L {
                y[a][l] = e[l] + od[l];
                y[M - 1 - a][l] = od[l] - e[l];
            }
        }
        if M % 2 == 1 {
            let mut m = [0.0f64; L];
            for l in 0..L {
                m[l] = self.q[h][0] * o[0][l];
            }
            for k in 1..h {
                for l in 0..L {
                    m[l] += self.q[h][k] * o[k][l];
                }
            }
            y[h] = m;
        }
    }
}

impl<const M: usize> EvenOdd<M> {
    /// `y[b] (+)= sum_k d[b][k] x[k]` for whole rows `x[k]` of `M x L` values (the
    /// derivative along z of an element's lane arrays `[b][a][lane]`, every column at
    /// once); `ADD`: add to `y` instead of overwriting it.
    #[inline(always)]
    pub(super) fn apply_rows<const L: usize, const ADD: bool>(
        &self,
        x: &[[[f64; L]; M]; M],
        y: &mut [[[f64; L]; M]; M],
    ) {
        let h = M / 2;
        let mut s = [[[0.0f64; L]; M]; M];
        let mut o = [[[0.0f64; L]; M]; M];
        for k in 0..h {
            for a in 0..M {
                for l in 0..L {
                    s[k][a][l] = x[k][a][l] + x[M - 1 - k][a][l];
                    o[k][a][l] = x[k][a][l] - x[M - 1 - k][a][l];
                }
            }
        }
        for b in 0..h {
            let (mut e, mut od) = ([[0.0f64; L]; M], [[0.0f64; L]; M]);
            for a in 0..M {
                for l in 0..L {
                    e[a][l] = self.p[b][0] * s[0][a][l];
                    od[a][l] = self.q[b][0] * o[0][a][l];
                }
            }
            for k in 1..h {
                for a in 0..M {
                    for l in 0..L {
                        e[a][l] += self.p[b][k] * s[k][a][l];
                        od[a][l] += self.q[b][k] * o[k][a][l];
                    }
                }
            }
            if M % 2 == 1 {
                for a in 0..M {
                    for l in 0..L {
                        e[a][l] += self.mid[b] * x[h][a][l];
                    }
                }
            }
            for a in 0..M {
                for l in 0..L {
                    let (lo, hi) = (e[a][l] + od[a][l], od[a][l] - e[a][l]);
                    if ADD {
                        y[b][a][l] += lo;
                        y[M - 1 - b][a][l] += hi;
                    } else {
                        y[b][a][l] = lo;
                        y[M - 1 - b][a][l] = hi;
                    }
                }
            }
        }
        if M % 2 == 1 {
            let mut m = [[0.0f64; L]; M];
            for a in 0..M {
                for l in 0..L {
                    m[a][l] = self.q[h][0] * o[0][a][l];
                }
            }
            for k in 1..h {
                for a in 0..M {
                    for l in 0..L {
                        m[a][l] += self.q[h][k] * o[k][a][l];
                    }
                }
            }
            for a in 0..M {
                for l in 0..L {
                    if ADD {
                        y[h][a][l] += m[a][l];
                    } else {
                        y[h][a][l] = m[a][l];
                    }
                }
            }
        }
    }
}

/// The GLL weights of order `M - 1` and its derivative matrix (at the points, and
/// transposed for the divergence), by the even-odd decomposition.
pub(super) struct Rule<const M: usize> {
    pub(super) w: [f64; M],
    pub(super) grad: EvenOdd<M>,
    pub(super) div: EvenOdd<M>,
}

impl<const M: usize> Rule<M> {
    /// From the GLL weights and the row-major derivative matrix of order `M - 1`.
    pub(super) fn new(weights: &[f64], derivative: &[f64]) -> Self {
        let mut d = [[0.0; M]; M];
        let mut w = [0.0; M];
        for i in 0..M {
            w[i] = weights[i];
            for j in 0..M {
                d[i][j] = derivative[i * M + j];
            }
        }
        let transposed = std::array::from_fn(|i| std::array::from_fn(|j| d[j][i]));
        Rule {
            w,
            grad: EvenOdd::new(&d),
            div: EvenOdd::new(&transposed),
        }
    }
}

/// The constants of the `L` elements of a block, per lane: `2 / hx`, `2 / hz` (1/m),
/// `lambda + 2 mu`, `lambda`, `mu` (Pa), `hx / 2`, `hz / 2` (m).
pub(super) struct Params<const L: usize> {
    pub(super) sx: [f64; L],
    pub(super) sz: [f64; L],
    pub(super) l2m: [f64; L],
    pub(super) lam: [f64; L],
    pub(super) mu: [f64; L],
    pub(super) hx2: [f64; L],
    pub(super) hz2: [f64; L],
}

/// `check::<M>()` for the GLL points of every order the solver takes (2 to 8).
#[cfg(test)]
macro_rules! for_every_order {
    ($check:ident) => {
        $check::<3>();
        $check::<4>();
        $check::<5>();
        $check::<6>();
        $check::<7>();
        $check::<8>();
        $check::<9>();
    };
}
#[cfg(test)]
pub(super) use for_every_order;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::gll::Gll;

    /// The decomposition gives the matrix product of the derivative matrix and of its
    /// transpose to round-off, for every order the solver takes.
    #[test]
    fn even_odd_derivative_is_the_matrix_product() {
        fn check<const M: usize>() {
            let g = Gll::new(M - 1).unwrap();
            let mut d = [[0.0; M]; M];
            for i in 0..M {
                for j in 0..M {
                    d[i][j] = g.derivative[i * M + j];
                }
            }
            let dt: [[f64; M]; M] = std::array::from_fn(|i| std::array::from_fn(|j| d[j][i]));
            for m in [d, dt] {
                let c = EvenOdd::<M>::new(&m);
                let x: [[f64; 2]; M] =
                    std::array::from_fn(|k| [(k as f64 * 1.3).sin(), (k as f64 * 0.7).cos()]);
                let mut y = [[0.0; 2]; M];
                c.apply::<2>(&x, &mut y);
                let scale: f64 = m.iter().flatten().map(|v| v.abs()).sum();
                for i in 0..M {
                    for l in 0..2 {
                        let exact: f64 = (0..M).map(|k| m[i][k] * x[k][l]).sum();
                        assert!((y[i][l] - exact).abs() <= 1e-13 * scale, "{M} {i}");
                    }
                }
            }
        }
        // the rows form: every column of a 2D array at once, overwriting and adding
        let g = Gll::new(4).unwrap();
        let d: [[f64; 5]; 5] =
            std::array::from_fn(|i| std::array::from_fn(|j| g.derivative[i * 5 + j]));
        let c = EvenOdd::<5>::new(&d);
        let x: [[[f64; 3]; 5]; 5] = std::array::from_fn(|k| {
            std::array::from_fn(|a| {
                std::array::from_fn(|l| ((k * 15 + a * 3 + l) as f64 * 0.37).sin())
            })
        });
        let mut y = [[[1.0; 3]; 5]; 5];
        c.apply_rows::<3, true>(&x, &mut y);
        for b in 0..5 {
            for a in 0..5 {
                for l in 0..3 {
                    let exact: f64 = 1.0 + (0..5).map(|k| d[b][k] * x[k][a][l]).sum::<f64>();
                    assert!((y[b][a][l] - exact).abs() <= 1e-13 * 30.0, "{b} {a} {l}");
                }
            }
        }
        for_every_order!(check);
    }
}

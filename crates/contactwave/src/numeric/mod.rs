//! Small numerical building blocks of the physics kernels: a bracketing root-finder,
//! monotone cubic interpolation, Gauss-Legendre quadrature and a tiny dense solver.
//! They are ours because they sit inside the hot loops and must not allocate. Beside them,
//! [`table`]: the one reader of numeric CSV tables (measured and tabulated data).

pub mod gll;
pub mod pchip;
pub mod root;
pub mod table;

/// 4-point Gauss-Legendre nodes on [0, 1].
pub const GL4_NODES: [f64; 4] = [
    0.069_431_844_202_973_71,
    0.330_009_478_207_571_9,
    0.669_990_521_792_428_1,
    0.930_568_155_797_026_3,
];
/// 4-point Gauss-Legendre weights on [0, 1] (sum to 1).
pub const GL4_WEIGHTS: [f64; 4] = [
    0.173_927_422_568_726_93,
    0.326_072_577_431_273_07,
    0.326_072_577_431_273_07,
    0.173_927_422_568_726_93,
];

/// An angle of `rad` radians in degrees as a person wrote it: rounded to 1e-9 degree, so
/// that 30 degrees read in and shown back in a message is 30, not 29.999999999999996.
pub fn shown_degrees(rad: f64) -> f64 {
    let deg = rad.to_degrees();
    let r = (deg * 1e9).round() / 1e9;
    if r.is_finite() {
        r
    } else {
        deg
    }
}

/// Integral of `f` over [a, b] by 4-point Gauss-Legendre (exact for degree 7).
#[inline]
pub fn gauss4(a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    let h = b - a;
    let mut s = 0.0;
    for i in 0..4 {
        s += GL4_WEIGHTS[i] * f(a + GL4_NODES[i] * h);
    }
    s * h
}

/// Solve the dense `n x n` system `a x = b` in place (partial pivoting); `a` is row-major
/// with stride `n`. Returns `false` if the matrix is singular to working precision.
pub fn solve_dense(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for col in 0..n {
        let mut piv = col;
        let mut best = a[col * n + col].abs();
        for r in col + 1..n {
            let v = a[r * n + col].abs();
            if v > best {
                best = v;
                piv = r;
            }
        }
        if !(best > 0.0) || !best.is_finite() {
            return false;
        }
        if piv != col {
            for c in 0..n {
                a.swap(col * n + c, piv * n + c);
            }
            b.swap(col, piv);
        }
        let d = a[col * n + col];
        for r in col + 1..n {
            let f = a[r * n + col] / d;
            if f != 0.0 {
                for c in col..n {
                    a[r * n + c] -= f * a[col * n + c];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for col in (0..n).rev() {
        let mut s = b[col];
        for c in col + 1..n {
            s -= a[col * n + c] * b[c];
        }
        b[col] = s / a[col * n + col];
    }
    true
}

/// Two-sided 97.5% Student t quantile for `dof` degrees of freedom (Cornish-Fisher
/// expansion, < 1% error for dof >= 3).
pub fn t975(dof: usize) -> f64 {
    let z: f64 = 1.959964;
    if dof == 0 {
        return f64::INFINITY;
    }
    let n = dof as f64;
    z + (z.powi(3) + z) / (4.0 * n)
        + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * n * n)
        + (3.0 * z.powi(7) + 19.0 * z.powi(5) + 17.0 * z.powi(3) - 15.0 * z) / (384.0 * n.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn degrees_read_back_as_written() {
        assert_eq!(shown_degrees(30f64.to_radians()), 30.0);
        assert_eq!(shown_degrees((-12.5f64).to_radians()), -12.5);
        assert!(shown_degrees(f64::NAN).is_nan());
        assert_eq!(shown_degrees(f64::INFINITY), f64::INFINITY);
    }
    #[test]
    fn gauss4_exact_for_degree_7() {
        let v = gauss4(-1.0, 2.0, |x| x.powi(7) - 3.0 * x.powi(2));
        let exact = (2f64.powi(8) - 1.0) / 8.0 - (8.0 + 1.0);
        assert!((v - exact).abs() < 1e-12);
    }
    #[test]
    fn dense_solve() {
        let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
        let mut b = vec![3.0, 3.0, 6.0];
        assert!(solve_dense(&mut a, &mut b, 3));
        for x in b {
            assert!((x - 1.0).abs() < 1e-14);
        }
    }
}

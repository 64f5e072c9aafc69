//! Bracketing root-finder used to locate opening, closing and damage events to machine
//! precision: Illinois regula falsi, safeguarded by bisection (converges superlinearly on
//! smooth functions and never worse than bisection).

/// Find the root of `f` in the bracket `[a, b]`, given `fa = f(a)` and `fb = f(b)` of
/// opposite signs (or `fb == 0`).
///
/// Returns the bracket end on the side of `b`: a point *past* the event where `f` has the
/// sign of `f(b)` (or is zero), within `4 eps |x|` of the root (machine precision).
/// Returns `None` if the bracket is invalid or `f` returns a non-finite value.
pub fn brent_past(
    mut f: impl FnMut(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    max_iter: usize,
) -> Option<f64> {
    if !(fa.is_finite() && fb.is_finite()) || fa * fb > 0.0 || fa == 0.0 && fb == 0.0 {
        return None;
    }
    if fb == 0.0 {
        return Some(b);
    }
    let sign_b = fb > 0.0;
    let (mut lo, mut flo, mut hi, mut fhi) = (a, fa, b, fb);
    let mut width = (hi - lo).abs();
    let mut side = 0i8; // which end was kept last (Illinois)
    for it in 0..max_iter {
        let tol = 4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
        if (hi - lo).abs() <= tol {
            break;
        }
        // Every third iteration check that the bracket at least halved; else bisect.
        let bisect = it % 3 == 2 && (hi - lo).abs() > 0.5 * width;
        if it % 3 == 2 {
            width = (hi - lo).abs();
        }
        let mut x = if bisect || flo == fhi {
            0.5 * (lo + hi)
        } else {
            (lo * fhi - hi * flo) / (fhi - flo)
        };
        if !(x > lo.min(hi) && x < lo.max(hi)) {
            x = 0.5 * (lo + hi);
        }
        if x == lo || x == hi {
            break;
        }
        let fx = f(x);
        if !fx.is_finite() {
            return None;
        }
        if fx == 0.0 || (fx > 0.0) == sign_b {
            hi = x;
            fhi = fx;
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
            if fx == 0.0 {
                return Some(x);
            }
        } else {
            lo = x;
            flo = fx;
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn finds_root_past() {
        let f = |x: f64| x.cos() - x;
        let r = brent_past(f, 0.0, 1.0, f(0.0), f(1.0), 200).unwrap();
        assert!(f(r) <= 0.0);
        assert!((r - 0.739_085_133_215_160_7).abs() < 1e-15);
    }
    #[test]
    fn rejects_bad_bracket() {
        assert!(brent_past(|x| x, 1.0, 2.0, 1.0, 2.0, 50).is_none());
    }
    #[test]
    fn flat_function_converges() {
        let f = |x: f64| (x - 0.3).powi(3);
        let r = brent_past(f, 0.0, 1.0, f(0.0), f(1.0), 400).unwrap();
        assert!((r - 0.3).abs() < 1e-5);
        assert!(f(r) >= 0.0);
    }
}

//! Compression branches defined by a stiffness-pressure curve `K(p) = dp/d(closure)`
//! (thesis section 4.2): the gap is `[u](p) = integral_p^p0 dp'/K(p')` (model.md section
//! 2, `table` row), tabulated once on a pressure grid by Gauss-Legendre quadrature and
//! inverted by Newton's method (`d[u]/dp = -1/K` exactly), so that the stress, the tangent
//! (`K(p)` itself) and the energy are smooth to working precision.

use crate::law::{CompressionBranch, WarmStart};
use crate::numeric::gauss4;

/// A stiffness-pressure relation `K(p)`, Pa/m, for `p >= 0`, Pa. Must be positive for
/// `p > 0` (it may vanish at p = 0 if `1/K` stays integrable).
pub trait StiffnessPressure: std::fmt::Debug + Send + Sync {
    /// K(p), Pa/m.
    fn stiffness(&self, pressure: f64) -> f64;
    /// Pressures where K is not smooth (grid nodes are put there).
    fn kinks(&self) -> Vec<f64> {
        Vec::new()
    }
}

/// A compression branch built from any [`StiffnessPressure`] relation.
#[derive(Debug)]
pub struct StiffnessCurve<K: StiffnessPressure> {
    /// The stiffness-pressure relation.
    pub law: K,
    static_pressure: f64,
    /// Pressure grid, Pa (increasing, from 0).
    p: Vec<f64>,
    /// G(p_i) = integral_0^p_i dp/K.
    g: Vec<f64>,
    /// H(p_i) = integral_0^p_i p dp/K.
    h: Vec<f64>,
    /// Stiffness at the nodes, Pa/m.
    k: Vec<f64>,
    /// Interval index of the grid at uniform steps of `bucket_width` in G (see
    /// [`StiffnessCurve::interval`]).
    bucket: Vec<u32>,
    /// Width of one bucket in G, m.
    bucket_width: f64,
    /// Step of the uniform part of the pressure grid (`p <= p_lin`), Pa, and `p_lin`.
    dp_lin: f64,
    p_lin: f64,
    g0: f64,
    h0: f64,
    name: &'static str,
}

impl<K: StiffnessPressure> StiffnessCurve<K> {
    /// Tabulate the branch for static pressure `p0`, Pa.
    pub fn new(law: K, static_pressure: f64, name: &'static str) -> Self {
        let p0 = static_pressure;
        let p_lin = (8.0 * p0).max(2e6);
        let n_lin = 1024;
        let mut p: Vec<f64> = (0..=n_lin)
            .map(|i| p_lin * i as f64 / n_lin as f64)
            .collect();
        let mut q = p_lin;
        while q < 1e10 {
            q *= 1.02;
            p.push(q);
        }
        p.extend(law.kinks().into_iter().filter(|k| *k > 0.0 && *k < q));
        p.push(p0);
        p.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        p.dedup();
        let mut g = vec![0.0; p.len()];
        let mut h = vec![0.0; p.len()];
        for i in 1..p.len() {
            g[i] = g[i - 1] + gauss4(p[i - 1], p[i], |x| 1.0 / law.stiffness(x));
            h[i] = h[i - 1] + gauss4(p[i - 1], p[i], |x| x / law.stiffness(x));
        }
        let k = p.iter().map(|&x| law.stiffness(x)).collect();
        let (bucket, bucket_width) = buckets(&p, &g, p_lin, 4 * n_lin);
        let mut c = StiffnessCurve {
            law,
            static_pressure: p0,
            p,
            g,
            h,
            k,
            bucket,
            bucket_width,
            dp_lin: p_lin / n_lin as f64,
            p_lin,
            g0: 0.0,
            h0: 0.0,
            name,
        };
        let (g0, h0) = c.integrals(p0);
        c.g0 = g0;
        c.h0 = h0;
        c
    }

    /// (G(p), H(p)) at any pressure.
    fn integrals(&self, pr: f64) -> (f64, f64) {
        let n = self.p.len();
        if pr >= self.p[n - 1] {
            let k = self.law.stiffness(self.p[n - 1]);
            let dp = pr - self.p[n - 1];
            return (
                self.g[n - 1] + dp / k,
                self.h[n - 1] + (pr * pr - self.p[n - 1] * self.p[n - 1]) / (2.0 * k),
            );
        }
        let i = self.p.partition_point(|&v| v <= pr).saturating_sub(1);
        let a = self.p[i];
        (
            self.g[i] + gauss4(a, pr, |x| 1.0 / self.law.stiffness(x)),
            self.h[i] + gauss4(a, pr, |x| x / self.law.stiffness(x)),
        )
    }

    /// (G(p), K(p)) at `pr >= 0`, Pa: G as [`StiffnessCurve::integrals`] finds it (the
    /// quadrature from the grid node below), the pressure interval found from the uniform
    /// grid step (at most two inserted nodes, kinks and p0, shift it) instead of a binary
    /// search; K of the law (beyond the grid, its last node's, as G is extrapolated).
    #[inline]
    fn g_and_k(&self, pr: f64) -> (f64, f64) {
        let n = self.p.len();
        if pr >= self.p[n - 1] {
            let k = self.k[n - 1];
            return (self.g[n - 1] + (pr - self.p[n - 1]) / k, k);
        }
        let mut i = if pr < self.p_lin {
            ((pr / self.dp_lin) as usize).min(n - 2)
        } else {
            self.p.partition_point(|&v| v <= pr).saturating_sub(1)
        };
        while i > 0 && self.p[i] > pr {
            i -= 1;
        }
        while i + 2 < n && self.p[i + 1] <= pr {
            i += 1;
        }
        let a = self.p[i];
        (
            self.g[i] + gauss4(a, pr, |x| 1.0 / self.law.stiffness(x)),
            self.law.stiffness(pr),
        )
    }

    /// The grid interval holding `target` in G, m: the last `i` with `g[i] <= target`, for
    /// `0 <= target < g[n-1]` (what a binary search over `g` returns). On the uniform
    /// part of the pressure grid the bucket of `target` gives the interval to within a
    /// few nodes, then a short forward scan; beyond it, a binary search.
    fn interval(&self, target: f64) -> usize {
        let j = (target / self.bucket_width) as usize;
        if j >= self.bucket.len() {
            return self.g.partition_point(|&v| v <= target).saturating_sub(1);
        }
        let mut i = self.bucket[j] as usize;
        // the bucket's edge j w may round above target
        while i > 0 && self.g[i] > target {
            i -= 1;
        }
        while self.g[i + 1] <= target {
            i += 1;
        }
        i
    }

    /// Pressure at gap `[u]`, Pa (0 beyond `[u]_c`).
    pub fn pressure(&self, gap: f64) -> f64 {
        // G(p) = G(p0) - [u]
        let target = self.g0 - gap;
        if target <= 0.0 {
            return 0.0;
        }
        let n = self.p.len();
        if target >= self.g[n - 1] {
            let k = self.law.stiffness(self.p[n - 1]);
            return self.p[n - 1] + (target - self.g[n - 1]) * k;
        }
        let i = self.interval(target);
        let (a, b) = (self.p[i], self.p[(i + 1).min(n - 1)]);
        let (ga, gb) = (self.g[i], self.g[(i + 1).min(n - 1)]);
        // cubic Hermite guess in g with the exact slopes dp/dg = K at the nodes (fourth
        // order: one Newton step then reaches round-off)
        let mut x = if gb > ga {
            let hg = gb - ga;
            let s = (target - ga) / hg;
            let (ka, kb) = (self.k[i], self.k[(i + 1).min(n - 1)]);
            let h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
            let h10 = s * (1.0 - s) * (1.0 - s);
            let h01 = s * s * (3.0 - 2.0 * s);
            let h11 = s * s * (s - 1.0);
            (h00 * a + h10 * hg * ka + h01 * b + h11 * hg * kb).clamp(a, b)
        } else {
            a
        };
        // x stays in [a, b] = [p_i, p_i+1]: G(x) from node i without a search
        let g_in = |x: f64| self.g[i] + gauss4(a, x, |q| 1.0 / self.law.stiffness(q));
        for _ in 0..30 {
            let r = g_in(x) - target;
            let k = self.law.stiffness(x).max(1e-300);
            let nx = (x - r * k).clamp(a, b);
            // quadratic convergence: a correction below 1e-8 (relative) leaves an error
            // near 1e-16, so no confirming evaluation is needed
            if (nx - x).abs() <= 1e-8 * b.max(1.0) {
                x = nx;
                break;
            }
            x = nx;
        }
        x
    }
}

/// Bucket index of the curve inversion: `nb` buckets of equal width in G over the uniform
/// part of the pressure grid (`p <= p_lin`, Pa), each holding the last grid index `i`
/// with `g[i] <= ` its lower edge. Returns the buckets and their width, m.
fn buckets(p: &[f64], g: &[f64], p_lin: f64, nb: usize) -> (Vec<u32>, f64) {
    let end = p.partition_point(|&v| v <= p_lin).saturating_sub(1);
    let width = g[end] / nb as f64;
    let mut bucket = Vec::with_capacity(nb);
    let mut i = 0;
    for j in 0..nb {
        let edge = j as f64 * width;
        while i + 1 < g.len() && g[i + 1] <= edge {
            i += 1;
        }
        bucket.push(i as u32);
    }
    (bucket, width)
}

impl<K: StiffnessPressure> CompressionBranch for StiffnessCurve<K> {
    fn name(&self) -> &'static str {
        self.name
    }
    fn critical_gap(&self) -> f64 {
        self.g0
    }
    fn stress(&self, gap: f64) -> f64 {
        -self.pressure(gap)
    }
    fn tangent(&self, gap: f64) -> f64 {
        self.law.stiffness(self.pressure(gap))
    }
    /// `K(-sigma)`: the pressure is the recorded one (no curve inversion).
    fn tangent_at(&self, _gap: f64, stress: f64) -> f64 {
        self.law.stiffness((-stress).max(0.0))
    }
    fn stress_tangent(&self, gap: f64) -> (f64, f64) {
        let p = self.pressure(gap);
        (-p, self.law.stiffness(p))
    }
    fn energy(&self, gap: f64) -> f64 {
        let pr = self.pressure(gap);
        let (g, h) = self.integrals(pr);
        // integral_{p0}^{p} (p' - p0)/K dp'
        (h - self.h0) - self.static_pressure * (g - self.g0)
    }
    fn stiffness_at_rest(&self) -> f64 {
        self.law.stiffness(self.static_pressure)
    }
    /// Newton's method on the pressure instead of the gap: with `g = [u]_c - G(p)` the
    /// update reads `Phi(p) = chi p + G(p) - ([u]_c - q) = 0`, `Phi' = chi + 1/K(p) > 0`,
    /// one quadrature of `1/K` and one `K` per iteration (no curve inversion inside the
    /// iteration). The start is the root of the cubic Hermite model of `G` through the
    /// last two points evaluated on this interface (`warm`; the previous steps: one
    /// iteration as a rule). Converged when the correction is below 1e-9 (p + p0) (the
    /// error of the corrected pressure is then of the order of its square, round-off);
    /// the gap of the corrected pressure to first order in the correction. Bracketed by
    /// the signs of `Phi` (`Phi(0) <= 0` on the compressed side), bisection when an
    /// iterate leaves the bracket; `None` (the caller's iteration on the gap) if it does
    /// not converge.
    fn solve_compressed(&self, shifted_gap: f64, chi: f64, warm: &mut WarmStart) -> Option<f64> {
        let target = self.g0 - shifted_gap;
        if !(target >= 0.0 && chi > 0.0) {
            return None;
        }
        let scale = self.static_pressure;
        let (mut lo, mut hi) = (0.0, f64::INFINITY);
        let mut p = predict(warm, chi, target)
            .filter(|p| p.is_finite() && *p >= 0.0)
            .unwrap_or(scale);
        for _ in 0..60 {
            let (gp, k) = self.g_and_k(p);
            let phi = chi * p + gp - target;
            if phi <= 0.0 {
                lo = p;
            } else {
                hi = p;
            }
            let sk = 1.0 / k;
            let d = phi / (chi + sk);
            let np = p - d;
            if d.abs() <= 1e-9 * (p + scale) && np >= 0.0 {
                if warm.len == 0 || warm.points[1][0] != p {
                    warm.push([p, gp, sk]);
                }
                return Some(self.g0 - gp + d * sk);
            }
            p = if np > lo && np < hi {
                np
            } else if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                return None;
            };
        }
        None
    }
}

/// The start of the pressure iteration of [`StiffnessCurve::solve_compressed`]: the root
/// of `chi p + G(p) = target` (Pa) for the model of `G` the warm start holds (points
/// `(p, G, 1/K)`): the cubic Hermite through its two points (values and slopes `1/K`),
/// extrapolated no further than four times their distance, else the tangent at the
/// newest; `None` without a point.
fn predict(warm: &WarmStart, chi: f64, target: f64) -> Option<f64> {
    if warm.len == 0 {
        return None;
    }
    let [pb, gb, sb] = warm.points[1];
    let psi0 = chi * pb + gb - target;
    let d1 = chi + sb;
    let t = -psi0 / d1;
    let h = warm.points[0][0] - pb;
    if warm.len < 2 || !(h != 0.0 && t.abs() <= 4.0 * h.abs()) {
        return Some(pb + t);
    }
    let [_, ga, sa] = warm.points[0];
    // G(pb + t) = gb + sb t + c2 t^2 + c3 t^3 with value ga and slope sa at t = h; one
    // Newton step on chi (pb + t) + G(pb + t) = target from the tangent's root
    let ih = 1.0 / h;
    let r1 = ((ga - gb) * ih - sb) * ih;
    let r2 = (sa - sb) * ih;
    let c3 = (r2 - 2.0 * r1) * ih;
    let c2 = 3.0 * r1 - r2;
    let psi = psi0 + t * (d1 + t * (c2 + t * c3));
    let dpsi = d1 + t * (2.0 * c2 + 3.0 * c3 * t);
    Some(pb + t - psi / dpsi)
}

//! Three-stage Radau IIA collocation (order 5, L-stable, stiffly accurate) for the small
//! stiff systems of the interface: `M y' = f(t, y)` with `y = ([u], beta)` and a diagonal
//! mass `M` whose damage row may be 0 (the rate-independent limit, an index-1 DAE).
//! Newton's method on the 6 stage unknowns; no allocation.

/// Collocation nodes c_j.
pub const C: [f64; 3] = [
    (4.0 - 2.449_489_742_783_178) / 10.0,
    (4.0 + 2.449_489_742_783_178) / 10.0,
    1.0,
];

const S6: f64 = 2.449_489_742_783_178;

/// Butcher matrix A (row-major); its last row is the weights b.
pub const A: [[f64; 3]; 3] = [
    [
        (88.0 - 7.0 * S6) / 360.0,
        (296.0 - 169.0 * S6) / 1800.0,
        (-2.0 + 3.0 * S6) / 225.0,
    ],
    [
        (296.0 + 169.0 * S6) / 1800.0,
        (88.0 + 7.0 * S6) / 360.0,
        (-2.0 - 3.0 * S6) / 225.0,
    ],
    [(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0],
];

/// Quadrature weights b (= last row of A).
pub const B: [f64; 3] = A[2];

/// Inverse of A: stage derivatives from stage increments, `Y'_j = (1/h) sum_l Ainv_jl Z_l`.
pub fn a_inverse() -> [[f64; 3]; 3] {
    let a = A;
    let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    let mut inv = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let (r0, r1) = match j {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            let (c0, c1) = match i {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            let minor = a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0];
            let sign = if (i + j) % 2 == 0 { 1.0 } else { -1.0 };
            inv[i][j] = sign * minor / det;
        }
    }
    inv
}

/// A system `M y' = f(t, y)` of dimension 2.
pub trait System {
    /// Diagonal of the mass matrix.
    fn mass(&self) -> [f64; 2];
    /// Time-dependent forcing g(t) (evaluated once per stage time and step).
    fn forcing(&self, _t: f64) -> f64 {
        0.0
    }
    /// The forcing at the three stage times `t + C[j] h` of a step.
    fn forcing_stages(&self, t: f64, h: f64) -> [f64; 3] {
        [
            self.forcing(t + C[0] * h),
            self.forcing(t + C[1] * h),
            self.forcing(t + C[2] * h),
        ]
    }
    /// Right-hand side f(t, y) given the forcing g(t).
    fn rhs_forced(&self, t: f64, g: f64, y: [f64; 2]) -> [f64; 2];
    /// First component of the right-hand side at the three stage times `t + C[l] h` of a
    /// step, all at the same state `y`, given their forcings `g` (what an affine step needs).
    fn rhs_stages(&self, t: f64, h: f64, g: [f64; 3], y: [f64; 2]) -> [f64; 3] {
        std::array::from_fn(|l| self.rhs_forced(t + C[l] * h, g[l], y)[0])
    }
    /// Right-hand side f(t, y).
    fn rhs(&self, t: f64, y: [f64; 2]) -> [f64; 2] {
        self.rhs_forced(t, self.forcing(t), y)
    }
    /// Jacobian df/dy, row-major.
    fn jacobian(&self, t: f64, y: [f64; 2]) -> [[f64; 2]; 2];
    /// Number of evolving components: 1 if the second one is frozen (its rhs and
    /// Jacobian row vanish and its mass is 1), else 2.
    fn dim(&self) -> usize {
        2
    }
    /// Where a one-component system (`dim() == 1`) is affine in `y[0]` near the state `y`:
    /// `f(t, y + (z, 0)) = f(t, y) + slope z` for every `y[0] + z` in `[lower, upper]`.
    /// [`step`] then solves the collocation equations in one linear solve, without
    /// Newton's iterations; `None` (the default): no such interval.
    fn affine(&self, _y: [f64; 2]) -> Option<Affine> {
        None
    }
}

/// An interval where a scalar right-hand side is affine in the state ([`System::affine`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// `df/dy[0]` (units of f per unit of y).
    pub slope: f64,
    /// Smallest `y[0]` of the interval.
    pub lower: f64,
    /// Largest `y[0]` of the interval.
    pub upper: f64,
}

/// Result of one step.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// Stage values Y_j (the last one is the end value).
    pub stages: [[f64; 2]; 3],
    /// Forcing at the stage times.
    pub forcing: [f64; 3],
}

impl Step {
    /// State at the end of the step.
    pub fn end(&self) -> [f64; 2] {
        self.stages[2]
    }
}

/// One Radau IIA step of size `h` from `(t, y)`. `scale` gives the magnitude of each
/// component for the convergence test. Returns `None` if Newton does not converge.
pub fn step<S: System>(sys: &S, t: f64, y: [f64; 2], h: f64, scale: [f64; 2]) -> Option<Step> {
    let m = sys.mass();
    let n = sys.dim();
    if n == 1 {
        if let Some(a) = sys.affine(y) {
            if let Some(s) = affine_step(sys, t, y, h, m[0], a) {
                return Some(s);
            }
        }
    }
    let f0 = sys.rhs(t, y);
    let j0 = sys.jacobian(t, y);
    let g = sys.forcing_stages(t, h);
    let stiff = h * j0[0][0].abs() > 1.0 || (n == 2 && h * j0[1][1].abs() > m[1].abs());
    let mut z = [[0.0f64; 2]; 3];
    if !stiff {
        for (j, zj) in z.iter_mut().enumerate() {
            for i in 0..n {
                if m[i] != 0.0 {
                    zj[i] = C[j] * h * f0[i] / m[i];
                }
            }
        }
    }
    let nn = 3 * n;
    let mut rhs = [0.0f64; 6];
    let mut f = [[0.0; 2]; 3];
    for iter in 0..25 {
        for l in 0..3 {
            f[l] = sys.rhs_forced(t + C[l] * h, g[l], [y[0] + z[l][0], y[1] + z[l][1]]);
        }
        // residual R_{j,i} = m_i z_{j,i} - h sum_l a_jl f_{l,i}
        let mut res = 0.0f64;
        for j in 0..3 {
            for i in 0..n {
                let mut s = m[i] * z[j][i];
                for l in 0..3 {
                    s -= h * A[j][l] * f[l][i];
                }
                rhs[j * n + i] = s;
                res = res.max(s.abs() / scale[i]);
            }
        }
        if !res.is_finite() {
            return None;
        }
        if iter > 0 && res < 1e-14 {
            break;
        }
        let mut jj = [[[0.0; 2]; 2]; 3];
        for l in 0..3 {
            jj[l] = sys.jacobian(t + C[l] * h, [y[0] + z[l][0], y[1] + z[l][1]]);
        }
        let ok = if n == 1 {
            // 3x3 system of the scalar gap equation (no 6x6 buffer to clear per step)
            let mut jac = [0.0f64; 9];
            for j in 0..3 {
                for l in 0..3 {
                    let mut v = -h * A[j][l] * jj[l][0][0];
                    if j == l {
                        v += m[0];
                    }
                    jac[j * 3 + l] = v;
                }
            }
            solve3(&jac, &mut rhs)
        } else {
            let mut jac = [0.0f64; 36];
            for j in 0..3 {
                for i in 0..n {
                    let r = j * n + i;
                    for l in 0..3 {
                        for k in 0..n {
                            let c = l * n + k;
                            let mut v = -h * A[j][l] * jj[l][i][k];
                            if j == l && i == k {
                                v += m[i];
                            }
                            jac[r * nn + c] = v;
                        }
                    }
                }
            }
            crate::numeric::solve_dense(&mut jac[..nn * nn], &mut rhs[..nn], nn)
        };
        if !ok {
            return None;
        }
        let mut err = 0.0f64;
        for j in 0..3 {
            for i in 0..n {
                let d = rhs[j * n + i];
                z[j][i] -= d;
                err = err.max(d.abs() / scale[i]);
            }
        }
        if !err.is_finite() {
            return None;
        }
        if err < 1e-13 {
            break;
        }
        if iter == 24 {
            return None;
        }
    }
    let mut stages = [[0.0; 2]; 3];
    for j in 0..3 {
        stages[j] = [y[0] + z[j][0], y[1] + z[j][1]];
    }
    Some(Step { stages, forcing: g })
}

/// The Radau step of an affine scalar system ([`System::affine`]): the collocation
/// equations `m z_j = h sum_l A_jl (f(t_l, y) + slope z_l)` are linear, so one
/// [`AffineMap`] gives what Newton's iteration converges to (the same solution up to
/// round-off). `None` when the start or a stage is outside the affine interval (a step at
/// or across a kink of the law: Newton takes it) or the system is singular.
fn affine_step<S: System>(sys: &S, t: f64, y: [f64; 2], h: f64, m: f64, a: Affine) -> Option<Step> {
    // a start outside the interval (a grazing step-on across a kink): Newton
    if !(y[0] >= a.lower && y[0] <= a.upper) {
        return None;
    }
    affine_step_with(sys, t, y, h, a, &AffineMap::new(h, m, a.slope)?)
}

/// The step of the affine branch at `(t, y)` ([`System::affine`]) continued past its
/// interval: the collocation map applied whatever the stages, i.e. the step of the
/// phase's linear dynamics. It is [`step`]'s wherever the stages stay inside (the same
/// arithmetic as its affine step), and is smooth across the interval's end, where `step`
/// turns to Newton on the law's kink: what an event search between the two sides of a
/// contact event evaluates. `None` where the system is not scalar and affine at `y`, `y`
/// is outside the interval, the map is singular or a stage is not finite.
pub fn continued_step<S: System>(sys: &S, t: f64, y: [f64; 2], h: f64) -> Option<Step> {
    if sys.dim() != 1 {
        return None;
    }
    let a = sys.affine(y)?;
    if !(y[0] >= a.lower && y[0] <= a.upper) {
        return None;
    }
    let map = AffineMap::new(h, sys.mass()[0], a.slope)?;
    let g = sys.forcing_stages(t, h);
    let z = map.apply(sys.rhs_stages(t, h, g, y));
    let stages = z.map(|zj| [y[0] + zj, y[1]]);
    stages
        .iter()
        .all(|s| s[0].is_finite())
        .then_some(Step { stages, forcing: g })
}

/// The affine step from `(t, y)` of length `h` (s) with the planned `map` of that step
/// length and the slope of `a`: the forcing at the stage times, the stage right-hand sides
/// at `y`, `z = P f`; `None` when a stage leaves `a`'s interval.
pub fn affine_step_with<S: System>(
    sys: &S,
    t: f64,
    y: [f64; 2],
    h: f64,
    a: Affine,
    map: &AffineMap,
) -> Option<Step> {
    let g = sys.forcing_stages(t, h);
    let z = map.apply(sys.rhs_stages(t, h, g, y));
    let mut stages = [[0.0; 2]; 3];
    for j in 0..3 {
        let v = y[0] + z[j];
        if !(v >= a.lower && v <= a.upper) {
            return None;
        }
        stages[j] = [v, y[1]];
    }
    Some(Step { stages, forcing: g })
}

/// The solution of the collocation equations of an affine scalar system with mass `m`,
/// slope `slope` and step `h` (s): the stage increments `z = P f` from the right-hand side
/// `f_l = f(t_l, y)` at the stage times and the start state, with
/// `P = (m I - h slope A)^-1 h A` (plan once per step size and slope, apply per step).
///
/// ```
/// use contactwave::solver::radau::AffineMap;
/// // y' = -y from y = 1 over h = 0.1: f = -1 at every stage time at the start state
/// let map = AffineMap::new(0.1, 1.0, -1.0).unwrap();
/// let z = map.apply([-1.0; 3]);
/// // the end stage is Radau IIA's fifth-order step: e^-0.1 to 1e-9
/// assert!((1.0 + z[2] - (-0.1f64).exp()).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AffineMap {
    /// `P`, row-major (s, in units of y per unit of f).
    p: [[f64; 3]; 3],
}

impl AffineMap {
    /// The map of step `h` (s), mass `m` and slope `slope`; `None` when the collocation
    /// matrix is singular or not finite.
    pub fn new(h: f64, m: f64, slope: f64) -> Option<AffineMap> {
        // M = m I - h slope A, its inverse from the adjugate, then P = M^-1 (h A)
        let mut mm = [[0.0f64; 3]; 3];
        for j in 0..3 {
            for l in 0..3 {
                mm[j][l] = if j == l { m } else { 0.0 } - h * A[j][l] * slope;
            }
        }
        let cof = |r0: usize, r1: usize, c0: usize, c1: usize| {
            mm[r0][c0] * mm[r1][c1] - mm[r0][c1] * mm[r1][c0]
        };
        // adjugate (transposed cofactors): adj[i][j] = C[j][i]
        let adj = [
            [cof(1, 2, 1, 2), -cof(0, 2, 1, 2), cof(0, 1, 1, 2)],
            [-cof(1, 2, 0, 2), cof(0, 2, 0, 2), -cof(0, 1, 0, 2)],
            [cof(1, 2, 0, 1), -cof(0, 2, 0, 1), cof(0, 1, 0, 1)],
        ];
        let det = mm[0][0] * adj[0][0] + mm[0][1] * adj[1][0] + mm[0][2] * adj[2][0];
        if !(det.abs() > 0.0) || !det.is_finite() {
            return None;
        }
        let inv_det = 1.0 / det;
        let mut p = [[0.0; 3]; 3];
        for i in 0..3 {
            for l in 0..3 {
                let v: f64 = (0..3).map(|j| adj[i][j] * A[j][l]).sum();
                p[i][l] = h * v * inv_det;
            }
        }
        p.iter()
            .flatten()
            .all(|v| v.is_finite())
            .then_some(AffineMap { p })
    }

    /// `P`, row-major.
    #[inline]
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        self.p
    }

    /// The stage increments `z = P f`.
    #[inline]
    pub fn apply(&self, f: [f64; 3]) -> [f64; 3] {
        let p = &self.p;
        std::array::from_fn(|j| p[j][0] * f[0] + p[j][1] * f[1] + p[j][2] * f[2])
    }
}

/// Solve the 3x3 system (row-major in `a[..9]`) by Cramer's rule, in place in `b[..3]`.
#[inline]
fn solve3(a: &[f64; 9], b: &mut [f64; 6]) -> bool {
    let m = |r: usize, c: usize| a[r * 3 + c];
    let det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
        - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
        + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
    if !(det.abs() > 0.0) || !det.is_finite() {
        return false;
    }
    let (b0, b1, b2) = (b[0], b[1], b[2]);
    let x0 = b0 * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (b1 * m(2, 2) - m(1, 2) * b2)
        + m(0, 2) * (b1 * m(2, 1) - m(1, 1) * b2);
    let x1 = m(0, 0) * (b1 * m(2, 2) - m(1, 2) * b2) - b0 * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
        + m(0, 2) * (m(1, 0) * b2 - b1 * m(2, 0));
    let x2 = m(0, 0) * (m(1, 1) * b2 - b1 * m(2, 1)) - m(0, 1) * (m(1, 0) * b2 - b1 * m(2, 0))
        + b0 * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
    b[0] = x0 / det;
    b[1] = x1 / det;
    b[2] = x2 / det;
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    struct Decay(f64);
    impl System for Decay {
        fn mass(&self) -> [f64; 2] {
            [1.0, 1.0]
        }
        fn rhs_forced(&self, t: f64, _g: f64, y: [f64; 2]) -> [f64; 2] {
            [-self.0 * (y[0] - t.cos()), 0.0]
        }
        fn jacobian(&self, _t: f64, _y: [f64; 2]) -> [[f64; 2]; 2] {
            [[-self.0, 0.0], [0.0, 0.0]]
        }
    }
    /// `y' = -lambda max(y, 0) - 1 + cos t`: affine with slope `-lambda` on `[0, inf)`,
    /// or on the whole line (`kink = false`).
    struct Kinked {
        lambda: f64,
        kink: bool,
    }
    impl System for Kinked {
        fn mass(&self) -> [f64; 2] {
            [1.0, 1.0]
        }
        fn forcing(&self, t: f64) -> f64 {
            t.cos()
        }
        fn rhs_forced(&self, _t: f64, g: f64, y: [f64; 2]) -> [f64; 2] {
            let v = if self.kink { y[0].max(0.0) } else { y[0] };
            [-self.lambda * v - 1.0 + g, 0.0]
        }
        fn jacobian(&self, _t: f64, y: [f64; 2]) -> [[f64; 2]; 2] {
            let d = if self.kink && y[0] < 0.0 {
                0.0
            } else {
                -self.lambda
            };
            [[d, 0.0], [0.0, 0.0]]
        }
        fn dim(&self) -> usize {
            1
        }
        fn affine(&self, y: [f64; 2]) -> Option<Affine> {
            let lower = if self.kink { 0.0 } else { f64::NEG_INFINITY };
            (y[0] >= lower).then_some(Affine {
                slope: -self.lambda,
                lower,
                upper: f64::INFINITY,
            })
        }
    }

    /// The continued step is the step while the stages stay inside the affine interval,
    /// and past its end the step of the branch continued (the system without the kink),
    /// where Newton's step follows the kink instead.
    #[test]
    fn continued_step_is_the_branch_continued() {
        let kinked = Kinked {
            lambda: 3.0,
            kink: true,
        };
        let linear = Kinked {
            lambda: 3.0,
            kink: false,
        };
        let y = [0.05, 1.0];
        // y' ~ -1.15 at the start: the state reaches 0 after ~0.045
        for h in [0.01, 0.03, 0.06, 0.2] {
            let c = continued_step(&kinked, 0.2, y, h).expect("affine start");
            let l = step(&linear, 0.2, y, h, [1.0, 1.0]).expect("linear step");
            let k = step(&kinked, 0.2, y, h, [1.0, 1.0]).expect("kinked step");
            for j in 0..3 {
                assert!((c.stages[j][0] - l.stages[j][0]).abs() < 1e-14, "h {h}");
            }
            if c.stages.iter().all(|s| s[0] >= 0.0) {
                assert_eq!(c.stages, k.stages, "inside the interval: the step itself");
            } else {
                assert!(
                    (c.end()[0] - k.end()[0]).abs() > 1e-6,
                    "h {h}: the kink matters"
                );
            }
        }
        // not affine at the start (outside the interval): none
        assert!(continued_step(&kinked, 0.0, [-0.1, 1.0], 0.1).is_none());
    }

    #[test]
    fn fifth_order_convergence() {
        // y' = -(y - cos t), exact: y = (cos t + sin t)/2 + (y0 - 1/2) e^-t
        let sys = Decay(1.0);
        let exact = |t: f64| 0.5 * (t.cos() + t.sin()) + 0.5 * (-t).exp();
        let err = |n: usize| {
            let h = 2.0 / n as f64;
            let mut y = [1.0, 0.0];
            for k in 0..n {
                y = step(&sys, k as f64 * h, y, h, [1.0, 1.0]).unwrap().end();
            }
            (y[0] - exact(2.0)).abs()
        };
        let (e1, e2) = (err(10), err(20));
        let order = (e1 / e2).log2();
        assert!(order > 4.6, "observed order {order}");
    }
    #[test]
    fn l_stable_on_very_stiff_problem() {
        let sys = Decay(1e12);
        let mut y = [5.0, 0.0];
        for k in 0..10 {
            y = step(&sys, k as f64 * 0.1, y, 0.1, [1.0, 1.0])
                .unwrap()
                .end();
        }
        assert!((y[0] - 1.0f64.cos()).abs() < 1e-9);
    }
    /// The decay of [`Decay`] declaring itself affine above `lower`.
    struct AffineDecay(f64, f64);
    impl System for AffineDecay {
        fn mass(&self) -> [f64; 2] {
            [1.0, 1.0]
        }
        fn rhs_forced(&self, t: f64, _g: f64, y: [f64; 2]) -> [f64; 2] {
            Decay(self.0).rhs_forced(t, 0.0, y)
        }
        fn jacobian(&self, t: f64, y: [f64; 2]) -> [[f64; 2]; 2] {
            Decay(self.0).jacobian(t, y)
        }
        fn dim(&self) -> usize {
            1
        }
        fn affine(&self, _y: [f64; 2]) -> Option<Affine> {
            Some(Affine {
                slope: -self.0,
                lower: self.1,
                upper: f64::INFINITY,
            })
        }
    }
    #[test]
    fn affine_step_is_the_newton_step() {
        // mild and stiff decay rates: the one linear solve lands where Newton converges
        for (lambda, h) in [(1.0, 0.1), (1e3, 0.01), (1e12, 0.1)] {
            let (newton, affine) = (Decay(lambda), AffineDecay(lambda, f64::NEG_INFINITY));
            let a = step(&newton, 0.3, [2.0, 0.0], h, [1.0, 1.0]).unwrap();
            let b = step(&affine, 0.3, [2.0, 0.0], h, [1.0, 1.0]).unwrap();
            for j in 0..3 {
                let (x, y) = (a.stages[j][0], b.stages[j][0]);
                assert!(
                    (x - y).abs() <= 1e-14 * x.abs().max(1.0),
                    "{lambda}: {x} vs {y}"
                );
            }
        }
    }
    #[test]
    fn affine_step_leaves_a_kink_to_newton() {
        // a stage below `lower` (the law's kink): the affine solve is refused, and step
        // falls back to Newton on the true right-hand side (here the same: no kink)
        let sys = AffineDecay(1.0, 1.9);
        let g = sys.forcing_stages(0.3, 0.5);
        assert!(affine_step(
            &sys,
            0.3,
            [2.0, 0.0],
            0.5,
            1.0,
            sys.affine([2.0, 0.0]).unwrap()
        )
        .is_none());
        assert!(step(&sys, 0.3, [2.0, 0.0], 0.5, [1.0, 1.0]).is_some());
        assert_eq!(g, [0.0; 3]);
    }
    #[test]
    fn affine_map_solves_the_collocation_equations() {
        // (m I - h slope A) P = h A, from mild to very stiff slopes, and refused where the
        // matrix is singular
        for (h, m, slope) in [(0.1, 1.0, -1.0), (5e-9, 1.0, -6e6), (1e-3, 1.0, -1e12)] {
            let p = AffineMap::new(h, m, slope).unwrap().matrix();
            for j in 0..3 {
                for l in 0..3 {
                    let lhs: f64 = (0..3)
                        .map(|i| (if j == i { m } else { 0.0 } - h * A[j][i] * slope) * p[i][l])
                        .sum();
                    let rhs = h * A[j][l];
                    assert!(
                        (lhs - rhs).abs() <= 1e-13 * h,
                        "{h} {slope}: {lhs} vs {rhs}"
                    );
                }
            }
        }
        assert!(AffineMap::new(1.0, 0.0, 0.0).is_none());
    }
    #[test]
    fn a_inverse_is_inverse() {
        let inv = a_inverse();
        for i in 0..3 {
            for j in 0..3 {
                let s: f64 = (0..3).map(|k| A[i][k] * inv[k][j]).sum();
                assert!((s - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
    }
}

//! Three-stage Radau IIA collocation (order 5, L-stable, stiffly accurate) for the small
//! stiff systems of the interface, `M y' = f(t, y)` with `N` unknowns and a diagonal mass
//! `M` whose damage row may be 0 (the rate-independent limit, an index-1 DAE): the one
//! step of both exact solvers, the normal gap equation (`y = ([u], beta)`, analytic
//! Jacobian, full Newton, affine phases in one linear solve) and the coupled interface
//! (`y = ([u]_N, beta, [u]_T)`, forward-difference Jacobian, simplified Newton). Newton's
//! method on the `3 N` stage unknowns of the evolving components; no allocation.

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

/// Most unknowns of a [`System`] (the coupled interface's three).
pub const MAX_UNKNOWNS: usize = 3;

/// Most stage unknowns of a step, `3 MAX_UNKNOWNS`.
const MAX_STAGE_UNKNOWNS: usize = 3 * MAX_UNKNOWNS;

/// A system `M y' = f(t, y)` of `N` unknowns (at most [`MAX_UNKNOWNS`]) with a diagonal
/// mass `M`: the normal gap equation (`N = 2`: `([u], beta)`, analytic Jacobian) and the
/// coupled interface (`N = 3`: `([u]_N, beta, [u]_T)`, forward-difference Jacobian).
pub trait System<const N: usize> {
    /// Diagonal of the mass matrix (default: the identity).
    fn mass(&self) -> [f64; N] {
        [1.0; N]
    }
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
    fn rhs_forced(&self, t: f64, g: f64, y: [f64; N]) -> [f64; N];
    /// First component of the right-hand side at the three stage times `t + C[l] h` of a
    /// step, all at the same state `y`, given their forcings `g` (what an affine step needs).
    fn rhs_stages(&self, t: f64, h: f64, g: [f64; 3], y: [f64; N]) -> [f64; 3] {
        std::array::from_fn(|l| self.rhs_forced(t + C[l] * h, g[l], y)[0])
    }
    /// Right-hand side f(t, y).
    fn rhs(&self, t: f64, y: [f64; N]) -> [f64; N] {
        self.rhs_forced(t, self.forcing(t), y)
    }
    /// The analytic Jacobian df/dy (row-major), or `None` (the default): no analytic one.
    /// With it, [`step`] takes full Newton iterations (the Jacobian again at the stage
    /// values of every iteration); without, simplified ones on a forward-difference
    /// Jacobian at the step start.
    fn jacobian(&self, _t: f64, _y: [f64; N]) -> Option<[[f64; N]; N]> {
        None
    }
    /// Which components evolve (default: all). An inactive component's right-hand side
    /// and Jacobian row vanish (and its mass is 1): it stays exactly constant.
    fn active(&self) -> [bool; N] {
        [true; N]
    }
    /// Where a system whose only evolving component is `y[0]` is affine in it near the
    /// state `y`: `f(t, y + (z, 0, ..)) = f(t, y) + slope z` for every `y[0] + z` in
    /// `[lower, upper]`. [`step`] then solves the collocation equations in one linear
    /// solve, without Newton's iterations; `None` (the default): no such interval.
    fn affine(&self, _y: [f64; N]) -> Option<Affine> {
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
pub struct Step<const N: usize> {
    /// Stage values Y_j (the last one is the end value).
    pub stages: [[f64; N]; 3],
    /// Forcing at the stage times.
    pub forcing: [f64; 3],
}

impl<const N: usize> Step<N> {
    /// State at the end of the step.
    pub fn end(&self) -> [f64; N] {
        self.stages[2]
    }
}

/// `y + z`, componentwise.
#[inline(always)]
fn plus<const N: usize>(y: [f64; N], z: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| y[i] + z[i])
}

/// Whether the only evolving component is the first (a scalar system, [`System::affine`]).
#[inline]
fn only_first<const N: usize>(active: [bool; N]) -> bool {
    active.iter().enumerate().all(|(i, &a)| a == (i == 0))
}

/// `y` with its first component replaced by `v`.
#[inline(always)]
fn with_first<const N: usize>(mut y: [f64; N], v: f64) -> [f64; N] {
    y[0] = v;
    y
}

/// One Radau IIA step of size `h` from `(t, y)`. `scale` gives the magnitude of each
/// component (the convergence test; the difference quotients of a Jacobian without an
/// analytic form). Returns `None` if Newton does not converge (the caller splits the step).
///
/// Newton's method on the `3 n` stage unknowns of the `n` evolving components
/// ([`System::active`]) follows the Jacobian ([`System::jacobian`]):
/// - analytic: full Newton, the Jacobian at the stage values of every iteration; an
///   explicit predictor unless the step is stiff (`h |J_ii| > |M_ii|`); converged when the
///   residual falls below 1e-14 or the increment below 1e-13 of the scale; one unknown by
///   Cramer's rule on its 3x3 system;
/// - by forward differences (step `1e-7 max(|y_i|, scale_i)`, at the step start):
///   simplified Newton, the iteration matrix `M - h (A x J)` assembled once per step; an
///   explicit predictor; converged when the increment falls below 1e-14 of `scale + |z|`,
///   or below 1e-11 once it stops halving (round-off).
///
/// A one-component system affine at `y` ([`System::affine`]) whose stages stay in the
/// interval takes one linear solve instead.
pub fn step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: [f64; N],
    h: f64,
    scale: [f64; N],
) -> Option<Step<N>> {
    const { assert!(N <= MAX_UNKNOWNS) };
    let active = sys.active();
    // the evolving components, in order
    let mut idx = [0usize; N];
    let mut n = 0;
    for (i, &a) in active.iter().enumerate() {
        if a {
            idx[n] = i;
            n += 1;
        }
    }
    let idx = &idx[..n];
    if n == 0 {
        return Some(Step {
            stages: [y; 3],
            forcing: [0.0; 3],
        });
    }
    let m = sys.mass();
    if only_first(active)
        && let Some(a) = sys.affine(y)
        && let Some(s) = affine_step(sys, t, y, h, m[0], a)
    {
        return Some(s);
    }
    let f0 = sys.rhs(t, y);
    let analytic = sys.jacobian(t, y);
    let full = analytic.is_some();
    let j0 = analytic.unwrap_or_else(|| difference_jacobian(sys, t, y, f0, idx, scale));
    let g = sys.forcing_stages(t, h);
    let stiff = full && idx.iter().any(|&i| h * j0[i][i].abs() > m[i].abs());
    let mut z = [[0.0f64; N]; 3];
    if !stiff {
        for (j, zj) in z.iter_mut().enumerate() {
            for &i in idx {
                if m[i] != 0.0 {
                    zj[i] = C[j] * h * f0[i] / m[i];
                }
            }
        }
    }
    let nn = 3 * n;
    // simplified Newton: the iteration matrix of the step
    let fixed = (!full).then(|| iteration_matrix(h, &m, &[j0; 3], idx));
    let mut r = [0.0f64; MAX_STAGE_UNKNOWNS];
    let mut f = [[0.0; N]; 3];
    let mut prev = f64::INFINITY;
    for iter in 0..25 {
        for l in 0..3 {
            f[l] = sys.rhs_forced(t + C[l] * h, g[l], plus(y, z[l]));
        }
        // residual R_{j,i} = m_i z_{j,i} - h sum_l a_jl f_{l,i}
        let mut res = 0.0f64;
        for j in 0..3 {
            for (c, &i) in idx.iter().enumerate() {
                let mut s = m[i] * z[j][i];
                for l in 0..3 {
                    s -= h * A[j][l] * f[l][i];
                }
                r[j * n + c] = s;
                res = res.max(s.abs() / scale[i]);
            }
        }
        if !res.is_finite() {
            return None;
        }
        if full && iter > 0 && res < 1e-14 {
            break;
        }
        let ok = match &fixed {
            Some(matrix) => {
                let mut a = *matrix;
                crate::numeric::solve_dense(&mut a[..nn * nn], &mut r[..nn], nn)
            }
            None => {
                let jj: [[[f64; N]; N]; 3] = std::array::from_fn(|l| {
                    sys.jacobian(t + C[l] * h, plus(y, z[l]))
                        .unwrap_or([[0.0; N]; N])
                });
                if n == 1 {
                    // 3x3 system of one unknown (no dense buffer to clear per step)
                    let i = idx[0];
                    let mut jac = [0.0f64; 9];
                    for j in 0..3 {
                        for l in 0..3 {
                            let mut v = -h * A[j][l] * jj[l][i][i];
                            if j == l {
                                v += m[i];
                            }
                            jac[j * 3 + l] = v;
                        }
                    }
                    solve3(&jac, &mut r)
                } else {
                    let mut a = iteration_matrix(h, &m, &jj, idx);
                    crate::numeric::solve_dense(&mut a[..nn * nn], &mut r[..nn], nn)
                }
            }
        };
        if !ok {
            return None;
        }
        let mut err = 0.0f64;
        for j in 0..3 {
            for (c, &i) in idx.iter().enumerate() {
                let d = r[j * n + c];
                z[j][i] -= d;
                err = err.max(if full {
                    d.abs() / scale[i]
                } else {
                    d.abs() / (scale[i] + z[j][i].abs())
                });
            }
        }
        if !err.is_finite() {
            return None;
        }
        if full {
            if err < 1e-13 {
                break;
            }
            if iter == 24 {
                return None;
            }
        } else {
            if err < 1e-14 || (err < 1e-11 && err > 0.5 * prev) {
                break;
            }
            if iter == 24 {
                return None;
            }
            prev = err;
        }
    }
    Some(Step {
        stages: z.map(|zj| plus(y, zj)),
        forcing: g,
    })
}

/// The Jacobian of `sys` at `(t, y)` by forward differences on the evolving components
/// `idx`, from `f0 = f(t, y)` (step `1e-7 max(|y_j|, scale_j)`); zero elsewhere.
fn difference_jacobian<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: [f64; N],
    f0: [f64; N],
    idx: &[usize],
    scale: [f64; N],
) -> [[f64; N]; N] {
    let mut jac = [[0.0; N]; N];
    for &j in idx {
        let d = 1e-7 * y[j].abs().max(scale[j]);
        let mut yp = y;
        yp[j] += d;
        let fp = sys.rhs(t, yp);
        for &i in idx {
            jac[i][j] = (fp[i] - f0[i]) / d;
        }
    }
    jac
}

/// Newton's iteration matrix `M - h (A x J_l)` of the evolving components `idx`, row-major
/// with stride `3 idx.len()`, from the Jacobians `jj[l]` at the three stages.
#[inline]
fn iteration_matrix<const N: usize>(
    h: f64,
    m: &[f64; N],
    jj: &[[[f64; N]; N]; 3],
    idx: &[usize],
) -> [f64; MAX_STAGE_UNKNOWNS * MAX_STAGE_UNKNOWNS] {
    let n = idx.len();
    let nn = 3 * n;
    let mut a = [0.0f64; MAX_STAGE_UNKNOWNS * MAX_STAGE_UNKNOWNS];
    for j in 0..3 {
        for (ci, &i) in idx.iter().enumerate() {
            let row = j * n + ci;
            for l in 0..3 {
                for (ck, &k) in idx.iter().enumerate() {
                    let mut v = -h * A[j][l] * jj[l][i][k];
                    if j == l && i == k {
                        v += m[i];
                    }
                    a[row * nn + l * n + ck] = v;
                }
            }
        }
    }
    a
}

/// The Radau step of an affine scalar system ([`System::affine`]): the collocation
/// equations `m z_j = h sum_l A_jl (f(t_l, y) + slope z_l)` are linear, so one
/// [`AffineMap`] gives what Newton's iteration converges to (the same solution up to
/// round-off). `None` when the start or a stage is outside the affine interval (a step at
/// or across a kink of the law: Newton takes it) or the system is singular.
fn affine_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: [f64; N],
    h: f64,
    m: f64,
    a: Affine,
) -> Option<Step<N>> {
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
pub fn continued_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: [f64; N],
    h: f64,
) -> Option<Step<N>> {
    if !only_first(sys.active()) {
        return None;
    }
    let a = sys.affine(y)?;
    if !(y[0] >= a.lower && y[0] <= a.upper) {
        return None;
    }
    let map = AffineMap::new(h, sys.mass()[0], a.slope)?;
    let g = sys.forcing_stages(t, h);
    let z = map.apply(sys.rhs_stages(t, h, g, y));
    let stages = z.map(|zj| with_first(y, y[0] + zj));
    stages
        .iter()
        .all(|s| s[0].is_finite())
        .then_some(Step { stages, forcing: g })
}

/// The affine step from `(t, y)` of length `h` (s) with the planned `map` of that step
/// length and the slope of `a`: the forcing at the stage times, the stage right-hand sides
/// at `y`, `z = P f`; `None` when a stage leaves `a`'s interval.
pub fn affine_step_with<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: [f64; N],
    h: f64,
    a: Affine,
    map: &AffineMap,
) -> Option<Step<N>> {
    let g = sys.forcing_stages(t, h);
    let z = map.apply(sys.rhs_stages(t, h, g, y));
    let mut stages = [y; 3];
    for j in 0..3 {
        let v = y[0] + z[j];
        if !(v >= a.lower && v <= a.upper) {
            return None;
        }
        stages[j][0] = v;
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
fn solve3(a: &[f64; 9], b: &mut [f64; MAX_STAGE_UNKNOWNS]) -> bool {
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
    impl System<2> for Decay {
        fn mass(&self) -> [f64; 2] {
            [1.0, 1.0]
        }
        fn rhs_forced(&self, t: f64, _g: f64, y: [f64; 2]) -> [f64; 2] {
            [-self.0 * (y[0] - t.cos()), 0.0]
        }
        fn jacobian(&self, _t: f64, _y: [f64; 2]) -> Option<[[f64; 2]; 2]> {
            Some([[-self.0, 0.0], [0.0, 0.0]])
        }
    }
    /// `y' = -lambda max(y, 0) - 1 + cos t`: affine with slope `-lambda` on `[0, inf)`,
    /// or on the whole line (`kink = false`).
    struct Kinked {
        lambda: f64,
        kink: bool,
    }
    impl System<2> for Kinked {
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
        fn jacobian(&self, _t: f64, y: [f64; 2]) -> Option<[[f64; 2]; 2]> {
            let d = if self.kink && y[0] < 0.0 {
                0.0
            } else {
                -self.lambda
            };
            Some([[d, 0.0], [0.0, 0.0]])
        }
        fn active(&self) -> [bool; 2] {
            [true, false]
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
    impl System<2> for AffineDecay {
        fn mass(&self) -> [f64; 2] {
            [1.0, 1.0]
        }
        fn rhs_forced(&self, t: f64, _g: f64, y: [f64; 2]) -> [f64; 2] {
            Decay(self.0).rhs_forced(t, 0.0, y)
        }
        fn jacobian(&self, t: f64, y: [f64; 2]) -> Option<[[f64; 2]; 2]> {
            Decay(self.0).jacobian(t, y)
        }
        fn active(&self) -> [bool; 2] {
            [true, false]
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
    /// Three unknowns without an analytic Jacobian (simplified Newton on difference
    /// quotients): a stiff one relaxing to `sin t`, a frozen one, and `y' = -y`.
    struct Frozen;
    impl System<3> for Frozen {
        fn rhs_forced(&self, t: f64, _g: f64, y: [f64; 3]) -> [f64; 3] {
            [-1e3 * (y[0] - t.sin()), 0.0, -y[2]]
        }
        fn active(&self) -> [bool; 3] {
            [true, false, true]
        }
    }

    #[test]
    fn difference_jacobian_steps_are_fifth_order_and_frozen_components_stay() {
        // y2' = -y2: exact exp(-t); the error of 10 steps of 0.1 is O(h^5)
        let mut y = [0.0, 0.7, 1.0];
        let h = 0.1;
        for k in 0..10 {
            y = step(&Frozen, k as f64 * h, y, h, [1.0; 3]).unwrap().end();
        }
        assert!((y[2] - (-1.0f64).exp()).abs() < 1e-8);
        assert_eq!(y[1], 0.7);
        // the stiff component: close to its slow manifold sin(t) - cos(t)/1e3
        let slow = 1f64.sin() - 1f64.cos() / 1e3;
        assert!((y[0] - slow).abs() < 1e-5);
        // and fifth order: halving the step divides the error by about 32
        let err = |n: usize| {
            let h = 1.0 / n as f64;
            let mut y = [0.0, 0.7, 1.0];
            for k in 0..n {
                y = step(&Frozen, k as f64 * h, y, h, [1.0; 3]).unwrap().end();
            }
            (y[2] - (-1.0f64).exp()).abs()
        };
        let order = (err(5) / err(10)).log2();
        assert!(order > 4.6, "observed order {order}");
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

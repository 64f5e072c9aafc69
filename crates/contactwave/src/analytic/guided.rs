//! Guided waves of a free surface and of a free plate (docs/model.md section 15.9): the
//! Rayleigh wave speed and the fundamental Rayleigh-Lamb modes S0 and A0, the references
//! of the 2D solver's verification.
//!
//! With `xi = c / c_S` and `kappa = c_S / c_P`, the Rayleigh speed is the root in (0, 1) of
//!
//! ```text
//! R(xi) = (2 - xi^2)^2 - 4 sqrt(1 - xi^2) sqrt(1 - kappa^2 xi^2) = 0          (15.9a)
//! ```
//!
//! (`R ~ -2 (1 - kappa^2) xi^2 < 0` near 0, `R(1) = 1 > 0`: one sign change, found by
//! bisection on `R / xi^2`). A free plate of thickness `d = 2 h` carries waves
//! `exp(i (k x - omega t))` with `p^2 = omega^2 / c_P^2 - k^2`, `q^2 = omega^2 / c_S^2 - k^2`
//! where (Rayleigh-Lamb)
//!
//! ```text
//! symmetric:      (q^2 - k^2)^2 C_p S_q + 4 k^2 p^2 S_p C_q = 0                   (15.9b)
//! antisymmetric:  (q^2 - k^2)^2 S_p C_q + 4 k^2 q^2 C_p S_q = 0                   (15.9c)
//! ```
//!
//! with `C_p = cos(p h)`, `S_p = sin(p h) / p` (and the same with q): real, entire
//! functions of `p^2` and `q^2` (cosh and sinh / p' where `p^2 = -p'^2 < 0`), so one real
//! function serves above and below the bulk speeds. They are the classical forms
//! `tan(q h) / tan(p h) = -4 k^2 p q / (q^2 - k^2)^2` (and its inverse) multiplied through.
//! The fundamental roots: S0 is the lowest symmetric root in `(c_R, c_plate]` with
//! `c_plate = sqrt(E / (rho (1 - nu^2))) = 2 c_S sqrt(1 - kappa^2)` (its low-frequency
//! limit); A0 is the lowest antisymmetric root in `(0, c_R)`, which tends to the flexural law
//! `c = sqrt(omega) (D / (rho d))^(1/4)`, `D = E d^3 / (12 (1 - nu^2))`, at low frequency.
//! Both tend to `c_R` at high frequency-thickness. Each root is bracketed by a scan of
//! 4000 points in c and refined by bisection to round-off.

use std::f64::consts::PI;

/// Bulk speeds of an isotropic solid, m/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Speeds {
    /// P-wave speed c_P, m/s.
    pub p: f64,
    /// S-wave speed c_S, m/s.
    pub s: f64,
}

impl Speeds {
    fn valid(&self) -> bool {
        self.s > 0.0 && self.p > self.s * 2f64.sqrt() && self.p.is_finite()
    }

    /// Poisson's ratio `nu = (c_P^2 - 2 c_S^2) / (2 (c_P^2 - c_S^2))`.
    pub fn poisson(&self) -> f64 {
        let (p2, s2) = (self.p * self.p, self.s * self.s);
        (p2 - 2.0 * s2) / (2.0 * (p2 - s2))
    }

    /// The plate (S0 low-frequency) speed `sqrt(E / (rho (1 - nu^2)))`, m/s.
    pub fn plate(&self) -> f64 {
        let kappa2 = (self.s / self.p).powi(2);
        2.0 * self.s * (1.0 - kappa2).sqrt()
    }
}

/// A fundamental Lamb mode of a free plate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LambMode {
    /// Symmetric (extensional).
    S0,
    /// Antisymmetric (flexural).
    A0,
}

/// Bisection of `f` on `[a, b]` (opposite signs) to round-off.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> Option<f64> {
    let (mut fa, fb) = (f(a), f(b));
    if !(fa.is_finite() && fb.is_finite()) || fa * fb > 0.0 {
        return None;
    }
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let fm = f(m);
        if fm == 0.0 {
            return Some(m);
        }
        if (fm > 0.0) == (fa > 0.0) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}

/// The Rayleigh wave speed, m/s: the root of eq. 15.9a. `None` unless
/// `c_P > sqrt(2) c_S > 0`.
pub fn rayleigh_speed(speeds: Speeds) -> Option<f64> {
    if !speeds.valid() {
        return None;
    }
    let k2 = (speeds.s / speeds.p).powi(2);
    let r = |xi: f64| {
        let x2 = xi * xi;
        ((2.0 - x2).powi(2) - 4.0 * ((1.0 - x2) * (1.0 - k2 * x2)).sqrt()) / x2
    };
    bisect(r, 1e-3, 1.0).map(|xi| xi * speeds.s)
}

/// `(cos(sqrt(a) h), sin(sqrt(a) h) / sqrt(a))` for real `a` of either sign.
fn cs(a: f64, h: f64) -> (f64, f64) {
    if a > 0.0 {
        let r = a.sqrt();
        ((r * h).cos(), (r * h).sin() / r)
    } else if a < 0.0 {
        let r = (-a).sqrt();
        ((r * h).cosh(), (r * h).sinh() / r)
    } else {
        (1.0, h)
    }
}

/// The Rayleigh-Lamb function of `mode` (eq. 15.9b or c) at phase velocity `c` and
/// angular frequency `omega` for a plate of thickness `d`, scaled by `1 / k^4` and by the
/// exponential growth of its hyperbolic terms (a real function of c whose roots are the
/// mode's).
pub fn rayleigh_lamb(speeds: Speeds, mode: LambMode, omega: f64, d: f64, c: f64) -> f64 {
    let k = omega / c;
    let h = 0.5 * d;
    let p2 = (omega / speeds.p).powi(2) - k * k;
    let q2 = (omega / speeds.s).powi(2) - k * k;
    let (cp, sp) = cs(p2, h);
    let (cq, sq) = cs(q2, h);
    let a = (q2 - k * k).powi(2);
    let f = match mode {
        LambMode::S0 => a * cp * sq + 4.0 * k * k * p2 * sp * cq,
        LambMode::A0 => a * sp * cq + 4.0 * k * k * q2 * cp * sq,
    };
    let grow = (-p2.min(0.0)).sqrt() * h + (-q2.min(0.0)).sqrt() * h;
    f / k.powi(4) * (-grow).exp()
}

/// The phase velocity of the fundamental Lamb mode `mode` of a free plate at
/// frequency-thickness `fd` (Hz m), m/s. `None` for invalid speeds or `fd <= 0`.
pub fn lamb_phase_velocity(speeds: Speeds, mode: LambMode, fd: f64) -> Option<f64> {
    if !(speeds.valid() && fd > 0.0 && fd.is_finite()) {
        return None;
    }
    let cr = rayleigh_speed(speeds)?;
    // d = 1 m, f = fd
    let omega = 2.0 * PI * fd;
    let f = |c: f64| rayleigh_lamb(speeds, mode, omega, 1.0, c);
    let n = 4000;
    let (lo, hi) = match mode {
        // the lowest root in (0, c_R)
        LambMode::A0 => (1e-4 * cr, cr * (1.0 - 1e-12)),
        // the lowest root in (c_R, c_plate] (the higher symmetric modes stay above c_S,
        // which S0 crosses from above)
        LambMode::S0 => (cr * (1.0 + 1e-12), speeds.plate() * (1.0 + 1e-9)),
    };
    // scan for the first sign change, then bisect it
    let mut a = lo;
    let mut fa = f(a);
    for i in 1..=n {
        let b = lo + (hi - lo) * i as f64 / n as f64;
        let fb = f(b);
        if fa * fb <= 0.0 {
            return bisect(f, a, b);
        }
        a = b;
        fa = fb;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// c_P / c_S = sqrt(3): nu = 0.25.
    const POISSON_QUARTER: Speeds = Speeds {
        p: 1.7320508075688772 * 3000.0,
        s: 3000.0,
    };
    const ALUMINIUM: Speeds = Speeds {
        p: 6320.0,
        s: 3130.0,
    };

    /// nu = 0.25: c_R / c_S = sqrt(2 - 2 / sqrt(3)) = 0.919402 (the root of the cubic in
    /// xi^2, Rayleigh 1885), and Viktorov's approximation (0.87 + 1.12 nu) / (1 + nu)
    /// within 0.2% for aluminium.
    #[test]
    fn rayleigh_speed_matches_the_closed_form_at_nu_quarter() {
        let c = rayleigh_speed(POISSON_QUARTER).unwrap();
        let exact = (2.0 - 2.0 / 3f64.sqrt()).sqrt();
        assert!((c / 3000.0 - exact).abs() < 1e-13, "{}", c / 3000.0);
        assert!((exact - 0.9194).abs() < 1e-4);
        let nu = ALUMINIUM.poisson();
        let viktorov = (0.87 + 1.12 * nu) / (1.0 + nu) * ALUMINIUM.s;
        let c = rayleigh_speed(ALUMINIUM).unwrap();
        assert!((c / viktorov - 1.0).abs() < 2e-3, "{c} {viktorov}");
        assert!(rayleigh_speed(Speeds { p: 1.0, s: 1.0 }).is_none());
    }

    /// Low frequency: S0 tends to the plate speed and A0 to the flexural law, with
    /// relative errors of order (k d)^2; high frequency: both to c_R.
    #[test]
    fn lamb_modes_have_their_limits() {
        let sp = ALUMINIUM;
        let cr = rayleigh_speed(sp).unwrap();
        let nu = sp.poisson();
        let rho = 2700.0;
        let e = 2.0 * rho * sp.s * sp.s * (1.0 + nu);
        assert!((sp.plate() / (e / (rho * (1.0 - nu * nu))).sqrt() - 1.0).abs() < 1e-14);
        let mut s0_err = Vec::new();
        let mut a0_err = Vec::new();
        for fd in [1.0, 10.0] {
            // fd in Hz m: 1 Hz m = 1e-3 MHz mm
            let s0 = lamb_phase_velocity(sp, LambMode::S0, fd).unwrap();
            s0_err.push(s0 / sp.plate() - 1.0);
            let a0 = lamb_phase_velocity(sp, LambMode::A0, fd).unwrap();
            let d = 1.0;
            let dd = e * d * d * d / (12.0 * (1.0 - nu * nu));
            let omega = 2.0 * PI * fd;
            let flex = omega.sqrt() * (dd / (rho * d)).powf(0.25);
            a0_err.push(a0 / flex - 1.0);
        }
        eprintln!("S0 / c_plate - 1 at fd = 1, 10 Hz m: {s0_err:?}; A0 / flexural - 1: {a0_err:?}");
        // both approach their limit from below, S0 as fd^2, A0 as (k d)^2 ~ fd
        assert!(
            s0_err.iter().all(|&e| e < 0.0) && s0_err[0].abs() < 1e-6,
            "{s0_err:?}"
        );
        let ratio = s0_err[1] / s0_err[0];
        assert!((ratio / 100.0 - 1.0).abs() < 0.01, "S0 order: {ratio}");
        assert!(
            a0_err.iter().all(|&e| e < 0.0) && a0_err[0].abs() < 1e-3,
            "{a0_err:?}"
        );
        let ratio = a0_err[1] / a0_err[0];
        assert!((ratio / 10.0 - 1.0).abs() < 0.05, "A0 order: {ratio}");
        // 20 MHz mm: both within 1e-4 of c_R
        for mode in [LambMode::S0, LambMode::A0] {
            let c = lamb_phase_velocity(sp, mode, 20e3).unwrap();
            assert!((c / cr - 1.0).abs() < 1e-4, "{mode:?} {c} {cr}");
        }
        // the dispersion of the fundamental modes is monotone: S0 falls, A0 rises
        let fds: Vec<f64> = (1..=40).map(|i| 100.0 * i as f64).collect();
        let s0: Vec<f64> = fds
            .iter()
            .map(|&f| lamb_phase_velocity(sp, LambMode::S0, f).unwrap())
            .collect();
        let a0: Vec<f64> = fds
            .iter()
            .map(|&f| lamb_phase_velocity(sp, LambMode::A0, f).unwrap())
            .collect();
        assert!(s0.windows(2).all(|w| w[1] < w[0]), "{s0:?}");
        assert!(a0.windows(2).all(|w| w[1] > w[0]), "{a0:?}");
    }

    /// The roots satisfy the classical tangent form `tan(q h) / tan(p h) = -4 k^2 p q /
    /// (q^2 - k^2)^2` (S0) in the region where p^2 < 0 < q^2 (hyperbolic p).
    #[test]
    fn s0_root_satisfies_the_tangent_form() {
        let sp = ALUMINIUM;
        let fd = 2000.0; // 2 MHz mm
        let c = lamb_phase_velocity(sp, LambMode::S0, fd).unwrap();
        let omega = 2.0 * PI * fd;
        let (k, h) = (omega / c, 0.5);
        let pp = (k * k - (omega / sp.p).powi(2)).sqrt();
        let q2 = (omega / sp.s).powi(2) - k * k;
        assert!(q2 > 0.0, "{c}");
        let q = q2.sqrt();
        // tan(p h) = i tanh(p' h), p = i p': -4 k^2 p q / (..)^2 = 4 k^2 p' q ... / i
        let lhs = (q * h).tan() / (pp * h).tanh();
        let rhs = 4.0 * k * k * pp * q / (q2 - k * k).powi(2);
        assert!((lhs - rhs).abs() < 1e-8 * rhs.abs(), "{lhs} {rhs}");
    }
}

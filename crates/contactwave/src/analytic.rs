//! Analytical solutions of the half-space problem against a rigid wall (thesis section
//! 5.2.1, eqs. 5.2-5.15), used as references by the tests and `contactwave validate`.
//!
//! Incident stress `s_inc(t) = -S sin(omega t)` switched on at t = 0 (rectangular window),
//! gap equation `Z [u]' + (sigma + p0) = 2 s_inc` (eq. 5.5). With a linear compression
//! spring `K_c` and a linear traction spring `K_t` (continuous bilinear law,
//! `sigma = K_t ([u] - [u]_c)` beyond `[u]_c = p0 / K_c`), each phase is linear:
//!
//! ```text
//! compression:  [u]' + w1 [u] = (2/Z) s_inc,                       w1 = K_c / Z
//! open:         [u]' + w2 [u] = (2/Z) s_inc - (p0 - K_t [u]_c)/Z,  w2 = K_t / Z
//! ```
//!
//! and is solved in closed form (sinusoid + constant + decaying exponential). The
//! constant term of the open phase is the one eq. 5.10 omits, and the transient decays at
//! the open-phase rate w2 (model.md section 4). Phase changes at `[u] = [u]_c` are found
//! by bisection on the closed form to machine precision; the trajectory from rest is the
//! exact solution of the same initial-value problem the solver integrates, and iterating
//! it over periods gives the periodic steady state (times T1, T2 of eqs. 5.11-5.15).

pub mod cavity;
pub mod friction;
pub mod guided;
pub mod oblique;

/// Parameters of the bilinear problem, SI units.
#[derive(Debug, Clone, Copy)]
pub struct Bilinear {
    /// Incident stress amplitude S, Pa.
    pub amplitude: f64,
    /// Angular frequency omega, rad/s.
    pub omega: f64,
    /// Impedance Z of the medium, Pa s/m.
    pub impedance: f64,
    /// Static pressure p0, Pa.
    pub static_pressure: f64,
    /// Compression stiffness K_c, Pa/m.
    pub compression_stiffness: f64,
    /// Traction stiffness K_t, Pa/m (0: traction-free).
    pub traction_stiffness: f64,
}

/// Piecewise closed-form trajectory: phase starts `(t_start, u_start, open)`.
#[derive(Debug, Clone)]
pub struct BilinearSolution {
    p: Bilinear,
    starts: Vec<(f64, f64, bool)>,
}

impl Bilinear {
    fn uc(&self) -> f64 {
        self.static_pressure / self.compression_stiffness
    }
    fn rate(&self, open: bool) -> f64 {
        if open {
            self.traction_stiffness / self.impedance
        } else {
            self.compression_stiffness / self.impedance
        }
    }
    /// Particular solution of the phase at time t.
    fn particular(&self, open: bool, t: f64) -> f64 {
        let lam = self.rate(open);
        let w = self.omega;
        let f = -2.0 * self.amplitude / self.impedance; // forcing f sin(wt)
        let sinus = f * (lam * (w * t).sin() - w * (w * t).cos()) / (lam * lam + w * w);
        let constant = if open {
            let b = -(self.static_pressure - self.traction_stiffness * self.uc()) / self.impedance;
            if lam > 0.0 {
                b / lam
            } else {
                0.0
            }
        } else {
            0.0
        };
        sinus + constant
    }
    /// Gap at time t in a phase started at (ts, us).
    fn phase_gap(&self, open: bool, ts: f64, us: f64, t: f64) -> f64 {
        let lam = self.rate(open);
        if open && lam == 0.0 {
            // u' = (2/Z) s_inc - p0/Z: integrate exactly
            let w = self.omega;
            let f = -2.0 * self.amplitude / self.impedance;
            let b = -self.static_pressure / self.impedance;
            return us + f * ((w * ts).cos() - (w * t).cos()) / w + b * (t - ts);
        }
        self.particular(open, t) + (us - self.particular(open, ts)) * (-lam * (t - ts)).exp()
    }

    /// Integrate from rest over `[0, t_end]`.
    pub fn solve(&self, t_end: f64) -> BilinearSolution {
        let uc = self.uc();
        let mut starts = vec![(0.0, 0.0, false)];
        let period = 2.0 * std::f64::consts::PI / self.omega;
        let dt = period / 400.0;
        let (mut ts, mut us, mut open) = (0.0, 0.0, false);
        let mut t = 0.0;
        while t < t_end {
            let t1 = (t + dt).min(t_end);
            let g0 = self.phase_gap(open, ts, us, t) - uc;
            let g1 = self.phase_gap(open, ts, us, t1) - uc;
            let crossed = if open {
                g1 < 0.0 && g0 >= 0.0
            } else {
                g1 > 0.0 && g0 <= 0.0
            };
            if crossed {
                let (mut a, mut b) = (t, t1);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break;
                    }
                    let gm = self.phase_gap(open, ts, us, m) - uc;
                    let past = if open { gm < 0.0 } else { gm > 0.0 };
                    if past {
                        b = m;
                    } else {
                        a = m;
                    }
                }
                ts = b;
                us = uc;
                open = !open;
                starts.push((ts, us, open));
                t = b;
            } else {
                t = t1;
            }
        }
        BilinearSolution { p: *self, starts }
    }

    /// Steady amplitude of the gap of the linear spring without contact loss (eq. 5.6),
    /// `(2 S / Z) / sqrt(omega^2 + w1^2)`, m, and its phase lag `atan(omega / w1)` with
    /// respect to `-sin(omega t)`, rad.
    pub fn linear_steady_state(&self) -> (f64, f64) {
        let w1 = self.rate(false);
        (
            2.0 * self.amplitude / self.impedance / (self.omega.powi(2) + w1 * w1).sqrt(),
            (self.omega / w1).atan(),
        )
    }
}

impl BilinearSolution {
    /// Gap at time t, m.
    pub fn gap(&self, t: f64) -> f64 {
        let i = self.starts.partition_point(|s| s.0 <= t).max(1) - 1;
        let (ts, us, open) = self.starts[i];
        self.p.phase_gap(open, ts, us, t)
    }
    /// Interface stress at time t, Pa.
    pub fn stress(&self, t: f64) -> f64 {
        let u = self.gap(t);
        let uc = self.p.uc();
        if u <= uc {
            -self.p.static_pressure + self.p.compression_stiffness * u
        } else {
            self.p.traction_stiffness * (u - uc)
        }
    }
    /// Times where contact is lost (T1) and regained (T2).
    pub fn events(&self) -> impl Iterator<Item = (f64, bool)> + '_ {
        self.starts.iter().skip(1).map(|s| (s.0, s.2))
    }
}

/// Second-order perturbation solution for a smooth compression law without contact loss
/// between medium 1 and medium 2 (or a rigid wall), model.md section 8.1.
///
/// Incident stress `S cos(omega t)`, interface stress `sigma + p0 = K u - K K' u^2 / 2 +
/// O(u^3)` with `K = K(p0)`, `K' = dK/dp (p0)`. With `Y = 1/Z1 + 1/Z2`, `D = 1/Z1 - 1/Z2`,
/// the steady second harmonic of the reflected and transmitted particle velocities gives
///
/// ```text
/// beta*_R = 2 omega K |K'| / (Z1 sqrt(4 omega^2 + Y^2 K^2) (omega^2 + D^2 K^2))
/// beta*_T = Z2 omega |K'| / (2 K sqrt(4 omega^2 + Y^2 K^2))
/// ```
///
/// (`beta* = A2 / A1^2` of the particle velocities, s/m).
#[derive(Debug, Clone, Copy)]
pub struct Perturbation {
    /// Angular frequency omega, rad/s.
    pub omega: f64,
    /// Impedance Z1 of the incident side, Pa s/m.
    pub z1: f64,
    /// Impedance Z2 of medium 2, Pa s/m (`f64::INFINITY` for a rigid wall).
    pub z2: f64,
    /// Tangent stiffness K(p0), Pa/m.
    pub stiffness: f64,
    /// Pressure derivative dK/dp at p0, 1/m.
    pub stiffness_slope: f64,
}

impl Perturbation {
    fn y(&self) -> f64 {
        1.0 / self.z1 + 1.0 / self.z2
    }
    fn d(&self) -> f64 {
        1.0 / self.z1 - 1.0 / self.z2
    }

    /// `beta* = A2/A1^2` of the reflected particle velocity, s/m.
    pub fn beta_reflected(&self) -> f64 {
        let (w, k) = (self.omega, self.stiffness);
        let yk = self.y() * k;
        let dk = self.d() * k;
        2.0 * w * k * self.stiffness_slope.abs()
            / (self.z1 * (4.0 * w * w + yk * yk).sqrt() * (w * w + dk * dk))
    }

    /// `beta* = A2/A1^2` of the transmitted particle velocity, s/m (NaN against a wall).
    pub fn beta_transmitted(&self) -> f64 {
        if !self.z2.is_finite() {
            return f64::NAN;
        }
        let (w, k) = (self.omega, self.stiffness);
        let yk = self.y() * k;
        self.z2 * w * self.stiffness_slope.abs() / (2.0 * k * (4.0 * w * w + yk * yk).sqrt())
    }

    /// Steady gap amplitude for an incident stress amplitude `s` (Pa), m:
    /// `2 S / (Z1 sqrt(omega^2 + Y^2 K^2))`; `|K'| u` measures how weak the nonlinearity is.
    pub fn gap_amplitude(&self, s: f64) -> f64 {
        let yk = self.y() * self.stiffness;
        2.0 * s / (self.z1 * (self.omega * self.omega + yk * yk).sqrt())
    }
}

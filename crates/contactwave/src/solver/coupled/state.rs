//! Phases of the coupled interface and the right-hand side, stresses and event functions
//! in each (model.md section 13.3).
//!
//! Unknowns `y = ([u]_N, beta, [u]_T)`; the accumulated slip `s` of an elastic-stick
//! slider is carried beside them (frozen while sticking, algebraic while slipping or
//! open). Normal: `d[u]_N/dt = 2 s_inc/Z1 - k_N (sigma + p0)`; tangential:
//! `d[u]_T/dt = 2 tau_inc/Z1T - k_T (tau - q0)`, with `k = 1/Z1 + 1/Z2` of each wave type
//! and `tau = k(beta) [u]_T + tau_f`, `tau_f` the slider's stress.

use super::N;
use crate::excitation::Excitation;
use crate::law::tangential::coulomb::slider_stress;
pub use crate::law::tangential::coulomb::SliderPhase;
use crate::law::{ContactLaw, TangentialLaw};

/// Normal phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Normal {
    /// Gap held by a rigid branch at `[u]_N = 0` (Signorini closed) or `[u]_c` (bonded),
    /// or both branches rigid (locked).
    Held,
    /// Compliant compression branch.
    Compression,
    /// Compliant traction branch (open).
    Traction,
}

/// Phase of the coupled interface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phase {
    /// Normal phase.
    pub normal: Normal,
    /// Tangential phase.
    pub tangential: SliderPhase,
    /// Damage evolving.
    pub damaging: bool,
}

/// Everything evaluated at one `(t, y)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Eval {
    /// Incident normal stress, Pa.
    pub s_inc: f64,
    /// Incident shear stress, Pa.
    pub tau_inc: f64,
    /// Normal stress sigma, Pa (tension positive).
    pub sigma: f64,
    /// Normal contact pressure N >= 0, Pa.
    pub pressure: f64,
    /// Adhesion in effect.
    pub beta: f64,
    /// Shear stress tau, Pa.
    pub tau: f64,
    /// Slider stress tau_f, Pa.
    pub tau_f: f64,
    /// `dy/dt`.
    pub rate: [f64; N],
    /// Slip rate ds/dt, m/s.
    pub slip_rate: f64,
    /// Damage driving force phi, J/m^2 (beta decreases while < 0).
    pub phi: f64,
    /// Energy released per unit decrease of beta, `dpsi/dbeta`, J/m^2.
    pub psi_beta: f64,
}

/// The coupled interface problem in one phase.
pub struct Interface<'a> {
    /// Normal law.
    pub law: &'a ContactLaw,
    /// Tangential law.
    pub tangential: &'a TangentialLaw,
    /// Incident normal stress.
    pub s_inc: &'a dyn Excitation,
    /// Incident shear stress.
    pub tau_inc: &'a dyn Excitation,
    /// `2/Z1`, `1/Z1 + 1/Z2` (normal).
    pub two_over_z1: f64,
    /// Normal compliance k_N, m/(Pa s).
    pub k_n: f64,
    /// `2/Z1T` (shear).
    pub two_over_z1t: f64,
    /// SliderPhase compliance k_T, m/(Pa s).
    pub k_t: f64,
    /// Oblique incidence: coefficient of `tau - q0` in `d[u]_N/dt`, m/(Pa s) (0 at normal
    /// incidence; model.md section 14).
    pub k_nt: f64,
    /// Oblique incidence: coefficient of `sigma + p0` in `d[u]_T/dt`, m/(Pa s).
    pub k_tn: f64,
    /// Contact-loss gap, m.
    pub uc: f64,
    /// Held gap of a `Held` phase, m.
    pub held_gap: f64,
    /// Adhesion frozen at the start of a rate-independent damaging phase.
    pub beta_frozen: f64,
    /// Accumulated slip of an elastic-stick slider while sticking, m.
    pub slip: f64,
    /// Slip path `integral |ds|` up to the start of the current tangential phase, m.
    pub path: f64,
    /// Slip at the start of the current tangential phase, m.
    pub phase_slip: f64,
    /// Current phase.
    pub phase: Phase,
    /// Time step of the derivative of the incident stress (held contact pressure), s.
    pub fd_dt: f64,
}

impl Interface<'_> {
    pub(super) fn rate_independent(&self) -> bool {
        self.law.traction.damage_viscosity() == 0.0
    }

    /// Slip path at `y`, m: while a rigid-stick slider slips (its slip is `[u]_T`, monotone
    /// in the phase) the path grows with it; otherwise the path of the phase's start (an
    /// elastic-stick or free slider adds its net slip when the phase ends; a branch whose
    /// coefficient depends on the path sticks rigidly).
    pub fn path(&self, y: &[f64; N]) -> f64 {
        match self.phase.tangential {
            SliderPhase::Slip(_) if self.tangential.branch.stick_stiffness().is_infinite() => {
                self.path + (y[2] - self.phase_slip).abs()
            }
            _ => self.path,
        }
    }

    /// Damage driving force at opening `d >= 0`, tangential gap and adhesion.
    pub(super) fn phi(&self, d: f64, ut: f64, beta: f64) -> f64 {
        self.law.traction.damage_driving_force(d, beta)
            - self.tangential.branch.spring_energy_d_adhesion(beta, ut)
    }

    /// Adhesion in effect: the state's, or on the damage surface `phi = 0` (driving
    /// forces affine in beta, as RCCM's) in a rate-independent damaging phase.
    pub fn beta(&self, y: &[f64; N]) -> f64 {
        if !(self.phase.damaging && self.rate_independent()) {
            return y[1];
        }
        let b0 = self.beta_frozen;
        let d = (y[0] - self.uc).max(0.0);
        let at0 = self.phi(d, y[2], 0.0);
        let at1 = self.phi(d, y[2], b0);
        if at1 >= 0.0 || b0 <= 0.0 {
            return b0;
        }
        let root = at0 * b0 / (at0 - at1);
        root.clamp(0.0, b0)
    }

    /// Normal stress and contact pressure (Pa).
    fn normal_stress(&self, t: f64, y: &[f64; N], s_inc: f64, beta: f64) -> (f64, f64) {
        let law = self.law;
        let p0 = law.static_pressure;
        let sigma = match self.phase.normal {
            Normal::Held => -p0 + self.two_over_z1 * s_inc / self.k_n,
            Normal::Compression => law.compression.stress(y[0].min(self.uc)),
            Normal::Traction => law.traction.stress((y[0] - self.uc).max(0.0), beta),
        };
        let _ = t;
        let pressure = match self.phase.normal {
            Normal::Traction => 0.0,
            _ => (-sigma).max(0.0),
        };
        (sigma, pressure)
    }

    /// Evaluate at `(t, y)`.
    pub fn eval(&self, t: f64, y: &[f64; N]) -> Eval {
        let s_inc = self.s_inc.stress(t);
        let tau_inc = self.tau_inc.stress(t);
        self.eval_forced(t, y, s_inc, tau_inc)
    }

    /// Evaluate at `(t, y)` with the incident stresses given.
    pub fn eval_forced(&self, t: f64, y: &[f64; N], s_inc: f64, tau_inc: f64) -> Eval {
        if self.k_nt != 0.0 || self.k_tn != 0.0 {
            return self.eval_oblique(t, y, s_inc, tau_inc);
        }
        let p0 = self.law.static_pressure;
        let q0 = self.tangential.static_shear;
        let beta = self.beta(y);
        let (sigma, pressure) = self.normal_stress(t, y, s_inc, beta);
        let un_dot = match self.phase.normal {
            Normal::Held => 0.0,
            _ => self.two_over_z1 * s_inc - self.k_n * (sigma + p0),
        };
        let br = &*self.tangential.branch;
        let k = br.spring_stiffness(beta);
        let kt = br.stick_stiffness();
        let spring = k * y[2];
        let drive = self.two_over_z1t * tau_inc;
        let (tau_f, ut_dot) = match self.phase.tangential {
            SliderPhase::Stick if kt.is_infinite() => (q0 + drive / self.k_t - spring, 0.0),
            other => {
                // no slider: the spring carries the static shear (tau = q0 + k [u]_T); a
                // slider without normal load carries nothing
                let tau_f = slider_stress(
                    self.tangential,
                    other,
                    y[2],
                    self.slip,
                    self.path(y),
                    pressure,
                );
                (tau_f, drive - self.k_t * (spring + tau_f - q0))
            }
        };
        let slip_rate = match self.phase.tangential {
            SliderPhase::Stick => 0.0,
            SliderPhase::Free => ut_dot,
            SliderPhase::Slip(sg) if kt.is_finite() => {
                ut_dot - sg * br.friction_at(self.path) * self.pressure_rate(t, y, un_dot) / kt
            }
            SliderPhase::Slip(_) => ut_dot,
        };
        let (phi, psi_beta, beta_dot) = self.damage(y, beta);
        Eval {
            s_inc,
            tau_inc,
            sigma,
            pressure,
            beta,
            tau: spring + tau_f,
            tau_f,
            rate: [un_dot, beta_dot, ut_dot],
            slip_rate,
            phi,
            psi_beta,
        }
    }

    /// The damage terms of a state with adhesion `beta`: the driving force `phi` (Pa; +inf
    /// without damage), `dpsi/dbeta` of the stored energy (J/m^2) and the rate of `beta`
    /// (1/s; zero unless the phase is damaging at a finite rate).
    pub(super) fn damage(&self, y: &[f64; N], beta: f64) -> (f64, f64, f64) {
        let d = (y[0] - self.uc).max(0.0);
        let (phi, psi_beta) = if self.law.traction.has_damage() {
            (
                self.phi(d, y[2], beta),
                self.law.traction.energy_d_adhesion(d, beta)
                    + self.tangential.branch.spring_energy_d_adhesion(beta, y[2]),
            )
        } else {
            (f64::INFINITY, 0.0)
        };
        let beta_dot = if self.phase.damaging && !self.rate_independent() {
            phi.min(0.0) / self.law.traction.damage_viscosity()
        } else {
            0.0
        };
        (phi, psi_beta, beta_dot)
    }

    /// dN/dt, Pa/s.
    fn pressure_rate(&self, t: f64, y: &[f64; N], un_dot: f64) -> f64 {
        match self.phase.normal {
            Normal::Traction => 0.0,
            Normal::Compression => -self.law.compression.tangent(y[0].min(self.uc)) * un_dot,
            Normal::Held => {
                let h = self.fd_dt;
                let ds = (self.s_inc.stress(t + h) - self.s_inc.stress(t - h)) / (2.0 * h);
                -self.two_over_z1 * ds / self.k_n
            }
        }
    }

    /// Which unknowns evolve in the current phase.
    pub fn active(&self) -> [bool; N] {
        [
            self.phase.normal != Normal::Held,
            self.phase.damaging && !self.rate_independent(),
            !(self.phase.tangential == SliderPhase::Stick
                && self.tangential.branch.stick_stiffness().is_infinite()),
        ]
    }

    /// Event functions of the current phase: the phase holds while all are >= 0.
    /// Scaled by `stress_scale` (Pa) and `gap_scale` (m) to comparable magnitudes.
    pub fn events(&self, t: f64, y: &[f64; N], e: &Eval, scales: &Scales) -> [f64; 3] {
        let law = self.law;
        let normal = match self.phase.normal {
            Normal::Compression => (self.uc - y[0]) / scales.gap,
            Normal::Traction => (y[0] - self.uc) / scales.gap,
            Normal::Held => {
                let rigid_c = law.compression.is_rigid();
                let rigid_t = law.traction.is_rigid();
                if rigid_c && rigid_t {
                    1.0
                } else if self.held_gap == 0.0 && rigid_c {
                    // Signorini closed: holds while the contact stress is compressive
                    -e.sigma / scales.stress
                } else {
                    // bonded at [u]_c: holds while the stress is tensile
                    e.sigma / scales.stress
                }
            }
        };
        let tangential = match self.phase.tangential {
            SliderPhase::Free => {
                if self.tangential.branch.friction() > 0.0 && e.pressure > 0.0 {
                    -1.0
                } else {
                    1.0
                }
            }
            SliderPhase::Stick => {
                (self.tangential.friction_limit(e.pressure, self.path(y)) - e.tau_f.abs())
                    / scales.stress
            }
            SliderPhase::Slip(sg) => sg * e.slip_rate / scales.velocity,
        };
        let damage = if !law.traction.has_damage() {
            1.0
        } else if !self.phase.damaging {
            e.phi / scales.energy
        } else if self.rate_independent() {
            // stays while the damage energy grows: phi at frozen beta keeps decreasing
            let h = self.fd_dt;
            let mut yp = *y;
            for (i, v) in yp.iter_mut().enumerate() {
                *v += h * e.rate[i];
            }
            let d0 = (y[0] - self.uc).max(0.0);
            let d1 = (yp[0] - self.uc).max(0.0);
            (self.phi(d0, y[2], e.beta) - self.phi(d1, yp[2], e.beta)) / (h * scales.power)
        } else {
            -e.phi / scales.energy
        };
        let _ = t;
        [normal, tangential, damage]
    }
}

/// Magnitudes of the problem, for event functions and Newton tolerances.
#[derive(Debug, Clone, Copy)]
pub struct Scales {
    /// Stress, Pa.
    pub stress: f64,
    /// Gap, m.
    pub gap: f64,
    /// Velocity, m/s.
    pub velocity: f64,
    /// Energy density, J/m^2.
    pub energy: f64,
    /// Power density, W/m^2.
    pub power: f64,
}

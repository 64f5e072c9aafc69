//! The coupled interface at oblique incidence (model.md section 14): the normal and
//! tangential gap equations coupled through the plane-wave compliance `K = C1^T + C2`,
//!
//! ```text
//! d[u]/dt = 2 diag(C1) sigma_inc(t) - K (sigma - sigma_0),     sigma = (sigma_N, tau)
//! ```
//!
//! whose off-diagonal terms `k_nt = K[0][1]`, `k_tn = K[1][0]` vanish at normal incidence
//! (and between identical media). Rigid branches (Signorini closed, bonded, rigid stick)
//! hold their gap and their constraint stress now solves the coupled 2x2 relation.

use super::state::{Eval, Interface, Normal, SliderPhase};
use super::N;
use super::{Integrals, ObliqueCoupling};
use crate::law::tangential::coulomb::slider_stress;

/// Stresses and gap rates of one state.
struct Stresses {
    beta: f64,
    sigma: f64,
    pressure: f64,
    tau_f: f64,
    spring: f64,
    un_dot: f64,
    ut_dot: f64,
}

impl Interface<'_> {
    fn oblique_stresses(&self, y: &[f64; N], s_inc: f64, tau_inc: f64) -> Stresses {
        let law = self.law;
        let p0 = law.static_pressure;
        let q0 = self.tangential.static_shear;
        let beta = self.beta(y);
        let br = &*self.tangential.branch;
        let spring = br.spring_stiffness(beta) * y[2];
        let kt = br.stick_stiffness();
        let mu = br.friction_at(self.path(y));
        let (dn, dt) = (self.two_over_z1 * s_inc, self.two_over_z1t * tau_inc);
        let (kn, knt, ktn, ktt) = (self.k_n, self.k_nt, self.k_tn, self.k_t);
        let normal = self.phase.normal;
        let held = normal == Normal::Held;
        let rigid_stick = self.phase.tangential == SliderPhase::Stick && kt.is_infinite();
        let pressure_of = |sigma: f64| {
            if normal == Normal::Traction {
                0.0
            } else {
                (-sigma).max(0.0)
            }
        };
        // slider stress for a known normal stress (not rigid stick)
        let path = self.path(y);
        let slider = |sigma: f64| {
            slider_stress(
                self.tangential,
                self.phase.tangential,
                y[2],
                self.slip,
                path,
                pressure_of(sigma),
            )
        };
        // (sigma + p0, tau - q0)
        let (sn, st) = if !held {
            let sigma = match normal {
                Normal::Traction => law.traction.stress((y[0] - self.uc).max(0.0), beta),
                _ => law.compression.stress(y[0].min(self.uc)),
            };
            let sn = sigma + p0;
            let st = if rigid_stick {
                (dt - ktn * sn) / ktt
            } else {
                spring + slider(sigma) - q0
            };
            (sn, st)
        } else if rigid_stick {
            let det = kn * ktt - knt * ktn;
            ((dn * ktt - knt * dt) / det, (kn * dt - ktn * dn) / det)
        } else if let SliderPhase::Slip(sg) = self.phase.tangential {
            // tau_f = sg mu (p0 - sn) while compressive: linear in sn
            let sn = (dn - knt * (spring - q0 + sg * mu * p0)) / (kn - knt * sg * mu);
            if sn - p0 <= 0.0 {
                (sn, spring + sg * mu * (p0 - sn) - q0)
            } else {
                // tensile: no friction load
                let st = spring - q0;
                ((dn - knt * st) / kn, st)
            }
        } else {
            let st = spring + slider(f64::NAN) - q0;
            ((dn - knt * st) / kn, st)
        };
        let sigma = sn - p0;
        Stresses {
            beta,
            sigma,
            pressure: pressure_of(sigma),
            tau_f: st + q0 - spring,
            spring,
            un_dot: if held { 0.0 } else { dn - kn * sn - knt * st },
            ut_dot: if rigid_stick {
                0.0
            } else {
                dt - ktn * sn - ktt * st
            },
        }
    }

    /// [`Interface::eval_forced`] at oblique incidence.
    pub(super) fn eval_oblique(&self, t: f64, y: &[f64; N], s_inc: f64, tau_inc: f64) -> Eval {
        let s = self.oblique_stresses(y, s_inc, tau_inc);
        let br = &*self.tangential.branch;
        let kt = br.stick_stiffness();
        let slip_rate = match self.phase.tangential {
            SliderPhase::Stick => 0.0,
            SliderPhase::Free => s.ut_dot,
            SliderPhase::Slip(sg) if kt.is_finite() => {
                let dp = match self.phase.normal {
                    Normal::Traction => 0.0,
                    Normal::Compression => {
                        -self.law.compression.tangent(y[0].min(self.uc)) * s.un_dot
                    }
                    Normal::Held => {
                        // the constraint pressure moves with both incident tractions
                        let h = self.fd_dt;
                        let at = |dtt: f64| {
                            let mut yy = *y;
                            yy[2] += dtt * s.ut_dot;
                            let tt = t + dtt;
                            self.oblique_stresses(
                                &yy,
                                self.s_inc.stress(tt),
                                self.tau_inc.stress(tt),
                            )
                            .pressure
                        };
                        (at(h) - at(-h)) / (2.0 * h)
                    }
                };
                s.ut_dot - sg * br.friction_at(self.path) * dp / kt
            }
            SliderPhase::Slip(_) => s.ut_dot,
        };
        let (phi, psi_beta, beta_dot) = self.damage(y, s.beta);
        Eval {
            s_inc,
            tau_inc,
            sigma: s.sigma,
            pressure: s.pressure,
            beta: s.beta,
            tau: s.spring + s.tau_f,
            tau_f: s.tau_f,
            rate: [s.un_dot, beta_dot, s.ut_dot],
            slip_rate,
            phi,
            psi_beta,
        }
    }
}

/// Quadrature weight `w` (s) of the face displacements and the wave energies at one stage:
/// incident traction `inc`, reflected traction `rf = sigma - sigma_0 - inc`, transmitted
/// traction `tr = sigma - sigma_0` (each `[normal, tangential]`, Pa).
pub(super) fn accumulate(
    o: &ObliqueCoupling,
    acc: &mut Integrals,
    w: f64,
    inc: [f64; 2],
    rf: [f64; 2],
    tr: [f64; 2],
) {
    let (c1, c2) = (&o.c1, &o.c2);
    for i in 0..2 {
        // v_inc = -C1 inc, v_ref = C1^T rf, v_tr = -C2 tr
        let wave = &mut acc.wave[i];
        wave.disp_inc -= w * (c1[i][0] * inc[0] + c1[i][1] * inc[1]);
        wave.disp_ref += w * (c1[0][i] * rf[0] + c1[1][i] * rf[1]);
        wave.disp_tr -= w * (c2[i][0] * tr[0] + c2[i][1] * tr[1]);
    }
    for (k, (m, f, s)) in [
        (&o.reflected_waves, &o.reflected_flux, rf),
        (&o.transmitted_waves, &o.transmitted_flux, tr),
    ]
    .into_iter()
    .enumerate()
    {
        for j in 0..2 {
            let a = m[j][0] * s[0] + m[j][1] * s[1];
            acc.wave_energy[2 * k + j] += w * f[j] * a * a;
        }
    }
}

impl super::CoupledHalfSpace {
    /// The problem of a plane wave incident at oblique incidence (model.md section 14):
    /// `burst` is its wave stress `s(t) = -rho c w(t)` (Pa; `w` the particle velocity along
    /// its polarisation), `g` the waves at the interface (`crate::analytic::oblique`),
    /// built from the same media. The incident tractions at the interface are
    /// `sigma_inc = -(traction per unit w) s / (rho c)`.
    pub fn oblique(
        medium: crate::material::Material,
        counterpart: Option<crate::material::Material>,
        law: std::sync::Arc<crate::law::ContactLaw>,
        tangential: std::sync::Arc<crate::law::TangentialLaw>,
        g: &crate::analytic::oblique::Geometry,
        burst: std::sync::Arc<dyn crate::excitation::Excitation>,
    ) -> Self {
        use crate::excitation::Scaled;
        use std::sync::Arc;
        let inc = &g.incident;
        let (gn, gt) = (
            -inc.traction[0] / inc.impedance,
            -inc.traction[1] / inc.impedance,
        );
        let o = ObliqueCoupling::new(g);
        let inv = |c: f64| if c != 0.0 { 1.0 / c } else { f64::INFINITY };
        super::CoupledHalfSpace {
            normal: super::HalfSpace::new(
                medium,
                counterpart,
                law,
                Arc::new(Scaled::new(burst.clone(), gn)),
            ),
            z1t: 1.0 / o.c1[1][1],
            z2t: inv(o.c2[1][1]),
            tangential,
            shear_incident: Arc::new(Scaled::new(burst, gt)),
            oblique: Some(o),
        }
    }
}

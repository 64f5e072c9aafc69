//! Closed forms of a shear wave at a rigid-stick Coulomb interface under a constant normal
//! pressure (model.md section 13.5; the problem of Meziane, Norris and Shuvalov, JASA
//! 2011, between half-spaces of shear impedances Z1T and Z2T).
//!
//! A sinusoidal incident shear stress `tau_inc = A sin(theta)`, `theta = omega t`. While the
//! interface sticks, the dynamic shear stress is `T tau_inc` with `T = 2 Z2T / (Z1T + Z2T)`
//! (2 for a rigid wall); it slips where that would exceed the friction limit `c = mu p0`,
//! so the transmitted dynamic stress is `T tau_inc` clipped at `+-c` (no static shear), a
//! periodic signal with odd harmonics only. The slip rate is
//! `k_T (T tau_inc - c sign)` with `k_T = 1/Z1T + 1/Z2T`, and friction dissipates
//! `c |slip rate|` while slipping.

use std::f64::consts::PI;

/// The clipped-sine problem.
#[derive(Debug, Clone, Copy)]
pub struct ClippedShear {
    /// Incident shear amplitude A, Pa.
    pub amplitude: f64,
    /// Angular frequency omega, rad/s.
    pub omega: f64,
    /// Shear impedance of medium 1, Pa s/m.
    pub z1: f64,
    /// Shear impedance of medium 2, Pa s/m (`inf`: rigid wall).
    pub z2: f64,
    /// Friction limit `c = mu p0`, Pa.
    pub limit: f64,
}

impl ClippedShear {
    /// Stick transmission factor `T = 2 Z2 / (Z1 + Z2)`.
    pub fn stick_factor(&self) -> f64 {
        if self.z2.is_finite() {
            2.0 * self.z2 / (self.z1 + self.z2)
        } else {
            2.0
        }
    }

    /// `k_T = 1/Z1 + 1/Z2`, m/(Pa s).
    pub fn compliance(&self) -> f64 {
        1.0 / self.z1 + crate::material::admittance(self.z2)
    }

    /// Clip angle `theta_c = asin(c / (T A))` (`pi/2` when the interface never slips).
    pub fn clip_angle(&self) -> f64 {
        (self.limit / (self.stick_factor() * self.amplitude))
            .min(1.0)
            .asin()
    }

    /// Fourier sine coefficient `b_n` of the transmitted dynamic shear stress, Pa (zero for
    /// even n): `(4/pi) int_0^{pi/2} s(theta) sin(n theta) dtheta`.
    pub fn transmitted_harmonic(&self, n: usize) -> f64 {
        if n.is_multiple_of(2) {
            return 0.0;
        }
        let a = self.stick_factor() * self.amplitude;
        let c = self.limit.min(a);
        let tc = self.clip_angle();
        let nf = n as f64;
        let stick = if n == 1 {
            a * (tc / 2.0 - (2.0 * tc).sin() / 4.0)
        } else {
            a / 2.0 * (((nf - 1.0) * tc).sin() / (nf - 1.0) - ((nf + 1.0) * tc).sin() / (nf + 1.0))
        };
        4.0 / PI * (stick + c * (nf * tc).cos() / nf)
    }

    /// Energy dissipated by friction per cycle, J/m^2:
    /// `(4 c k_T / omega) (T A cos(theta_c) - c (pi/2 - theta_c))`.
    pub fn dissipation_per_cycle(&self) -> f64 {
        let a = self.stick_factor() * self.amplitude;
        if a <= self.limit {
            return 0.0;
        }
        let c = self.limit;
        let tc = self.clip_angle();
        4.0 * c * self.compliance() / self.omega * (a * tc.cos() - c * (PI / 2.0 - tc))
    }

    /// Incident energy per cycle `A^2 / (2 Z1) 2 pi / omega`, J/m^2.
    pub fn incident_energy_per_cycle(&self) -> f64 {
        self.amplitude * self.amplitude / (2.0 * self.z1) * 2.0 * PI / self.omega
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_match_quadrature_and_limits() {
        let p = ClippedShear {
            amplitude: 5e6,
            omega: 2.0 * PI * 1e6,
            z1: 8.5e6,
            z2: 8.5e6,
            limit: 3e6,
        };
        // midpoint quadrature of the clipped sine
        let m = 200_000;
        for n in [1usize, 2, 3, 5] {
            let mut acc = 0.0;
            for k in 0..m {
                let th = (k as f64 + 0.5) / m as f64 * 2.0 * PI;
                let s = (p.amplitude * th.sin()).clamp(-p.limit, p.limit);
                acc += s * (n as f64 * th).sin();
            }
            let b = acc * 2.0 / m as f64;
            assert!(
                (b - p.transmitted_harmonic(n)).abs() < 1e-6 * p.amplitude,
                "n = {n}"
            );
        }
        // no slip: linear transmission, no harmonics, no dissipation
        let stuck = ClippedShear { limit: 6e6, ..p };
        assert!((stuck.transmitted_harmonic(1) - 5e6).abs() < 1e-6);
        assert!(stuck.transmitted_harmonic(3).abs() < 1e-6);
        assert_eq!(stuck.dissipation_per_cycle(), 0.0);
        // no friction: nothing transmitted, the whole cycle's energy... is not dissipated
        let free = ClippedShear { limit: 0.0, ..p };
        assert!(free.transmitted_harmonic(1).abs() < 1e-9);
        assert_eq!(free.dissipation_per_cycle(), 0.0);
    }
}

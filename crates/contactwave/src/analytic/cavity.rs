//! A plane P wave scattered by a circular cylindrical cavity in an elastic solid, plane
//! strain (Pao and Mow, *Diffraction of Elastic Waves and Dynamic Stress Concentrations*,
//! 1973, chapter 4; docs/model.md eq. 15.13g): the reference of the mesh path's curved
//! boundaries.
//!
//! Time factor `exp(-i omega t)`, polar coordinates `(r, theta)` about the cavity's centre
//! (theta from the incident direction +x toward +z), cavity radius `a`,
//! `alpha = omega / c_P`, `beta = omega / c_S`. The displacement is
//! `u = grad phi + curl(psi e_y)`: `u_r = phi_r + psi_theta / r`,
//! `u_theta = phi_theta / r - psi_r`. The incident wave `u_x = U0 exp(i alpha x)` is
//! `phi_i = phi0 sum_n eps_n i^n J_n(alpha r) cos(n theta)` with `phi0 = U0 / (i alpha)`,
//! `eps_0 = 1`, `eps_n = 2`; the scattered waves are
//! `phi_s = phi0 sum_n A_n H_n(alpha r) cos(n theta)`,
//! `psi_s = phi0 sum_n B_n H_n(beta r) sin(n theta)` (`H_n` the Hankel function of the
//! first kind: outgoing). For one order, with `F(r)` the total P radial function and
//! `G(r)` the S one, the tractions on a circle `r` are
//!
//! ```text
//! sigma_rr     = [ -mu beta^2 F + 2 mu ((n^2 F - n G) / r^2 - F' / r + n G' / r) ] cos(n theta)
//! sigma_rtheta = mu [ 2 n (F / r^2 - F' / r) + 2 G' / r + (beta^2 - 2 n^2 / r^2) G ] sin(n theta)
//! ```
//!
//! (Bessel's equation removes `F''` and `G''`), and the cavity's face is free:
//! `sigma_rr = sigma_rtheta = 0` at `r = a` gives `A_n, B_n` (a 2 x 2 system; for `n = 0`
//! only `sigma_rr`, `B_0 = 0`). The series is summed to `n = beta a + 20`, past which its
//! terms are below round-off of the first ones.

use rustfft::num_complex::Complex64;

/// The cavity problem: the solid and the cavity's radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cavity {
    /// Density, kg/m^3.
    pub density: f64,
    /// P wave speed, m/s.
    pub p_speed: f64,
    /// S wave speed, m/s.
    pub s_speed: f64,
    /// Radius, m.
    pub radius: f64,
}

/// The total displacement on a circle about the cavity's centre, per unit incident
/// displacement amplitude `U0` (phasors of `exp(-i omega t)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Displacement {
    /// Radial, `u_r / U0`.
    pub radial: Complex64,
    /// Hoop, `u_theta / U0`.
    pub hoop: Complex64,
}

/// `Z_n(x)` and `Z_n'(x)` of `J` (`first`) or `H^(1)` for orders `0..=n_max`.
fn bessel(n_max: usize, x: f64, first: bool) -> Vec<(Complex64, Complex64)> {
    let z = |n: i32| {
        let j = libm::jn(n, x);
        if first {
            Complex64::new(j, 0.0)
        } else {
            Complex64::new(j, libm::yn(n, x))
        }
    };
    (0..=n_max as i32)
        .map(|n| {
            let zn = z(n);
            // Z_n' = Z_{n-1} - n Z_n / x (Z_{-1} = -Z_1)
            let prev = if n == 0 { -z(1) } else { z(n - 1) };
            (zn, prev - zn * (n as f64 / x))
        })
        .collect()
}

impl Cavity {
    fn lame(&self) -> (f64, f64) {
        let mu = self.density * self.s_speed * self.s_speed;
        (self.density * self.p_speed * self.p_speed - 2.0 * mu, mu)
    }

    /// The orders the series sums at `r`: the scattered waves' to `beta a + 20`, the
    /// incident wave's to `alpha r + 20` (past those, terms below round-off of the first).
    fn orders(&self, omega: f64, r: f64) -> (usize, usize) {
        let scattered = (omega / self.s_speed * self.radius).ceil() as usize + 20;
        let incident = (omega / self.p_speed * r).ceil() as usize + 20;
        (scattered, incident.max(scattered))
    }

    /// The radial functions at `r` (m) of each order: `(F, F', G, G')` per unit `phi0`,
    /// with `F = eps_n i^n J_n(alpha r) + A_n H_n(alpha r)` and `G = B_n H_n(beta r)`
    /// (derivatives in r, 1/m).
    fn radial(&self, omega: f64, r: f64) -> Vec<[Complex64; 4]> {
        let (_, mu) = self.lame();
        let (alpha, beta) = (omega / self.p_speed, omega / self.s_speed);
        let (n_s, n_max) = self.orders(omega, r);
        let a = self.radius;
        let (ja, ha, hb) = (
            bessel(n_s, alpha * a, true),
            bessel(n_s, alpha * a, false),
            bessel(n_s, beta * a, false),
        );
        let (jr, hr, hbr) = (
            bessel(n_max, alpha * r, true),
            bessel(n_max, alpha * r, false),
            bessel(n_max, beta * r, false),
        );
        let i = Complex64::new(0.0, 1.0);
        (0..=n_max)
            .map(|n| {
                let nf = n as f64;
                // tractions at r = a of a P function (F, F') and an S function (G, G')
                let t_rr = |f: Complex64, fp: Complex64, g: Complex64, gp: Complex64| {
                    -mu * beta * beta * f
                        + 2.0 * mu * ((nf * nf * f - nf * g) / (a * a) - fp / a + nf * gp / a)
                };
                let t_rt = |f: Complex64, fp: Complex64, g: Complex64, gp: Complex64| {
                    mu * (2.0 * nf * (f / (a * a) - fp / a)
                        + 2.0 * gp / a
                        + (beta * beta - 2.0 * nf * nf / (a * a)) * g)
                };
                let zero = Complex64::new(0.0, 0.0);
                let eps = if n == 0 { 1.0 } else { 2.0 } * i.powu(n as u32);
                if n > n_s {
                    return [eps * jr[n].0, alpha * eps * jr[n].1, zero, zero];
                }
                let (fi, fip) = (eps * ja[n].0, eps * alpha * ja[n].1);
                let (fs, fsp) = (ha[n].0, alpha * ha[n].1);
                let (gs, gsp) = (hb[n].0, beta * hb[n].1);
                let (coef_a, coef_b) = if n == 0 {
                    (-t_rr(fi, fip, zero, zero) / t_rr(fs, fsp, zero, zero), zero)
                } else {
                    // [m11 m12; m21 m22] [A; B] = -[r1; r2] (Cramer)
                    let (m11, m12) = (t_rr(fs, fsp, zero, zero), t_rr(zero, zero, gs, gsp));
                    let (m21, m22) = (t_rt(fs, fsp, zero, zero), t_rt(zero, zero, gs, gsp));
                    let (r1, r2) = (-t_rr(fi, fip, zero, zero), -t_rt(fi, fip, zero, zero));
                    let det = m11 * m22 - m12 * m21;
                    ((r1 * m22 - m12 * r2) / det, (m11 * r2 - r1 * m21) / det)
                };
                [
                    eps * jr[n].0 + coef_a * hr[n].0,
                    alpha * (eps * jr[n].1 + coef_a * hr[n].1),
                    coef_b * hbr[n].0,
                    beta * coef_b * hbr[n].1,
                ]
            })
            .collect()
    }

    /// The total displacement at `(r, theta)` (m, rad; `r >= radius`) at angular frequency
    /// `omega` (rad/s), per unit incident displacement amplitude.
    pub fn displacement(&self, omega: f64, r: f64, theta: f64) -> Displacement {
        let phi0 = Complex64::new(0.0, -1.0) * (self.p_speed / omega); // 1 / (i alpha)
        let (mut ur, mut ut) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
        for (n, [f, fp, g, gp]) in self.radial(omega, r).into_iter().enumerate() {
            let nf = n as f64;
            let (c, s) = ((nf * theta).cos(), (nf * theta).sin());
            ur += (fp + nf * g / r) * c;
            ut += (-nf * f / r - gp) * s;
        }
        Displacement {
            radial: ur * phi0,
            hoop: ut * phi0,
        }
    }

    /// The hoop stress `sigma_theta_theta` on the cavity's face at `theta` per unit
    /// incident displacement amplitude, Pa/m (`lambda lap phi + 2 mu (u_r + u_theta,theta)
    /// / a`).
    pub fn hoop_stress(&self, omega: f64, theta: f64) -> Complex64 {
        let (lambda, mu) = self.lame();
        let (a, alpha) = (self.radius, omega / self.p_speed);
        let phi0 = Complex64::new(0.0, -1.0) / alpha;
        let mut s = Complex64::new(0.0, 0.0);
        for (n, [f, fp, g, gp]) in self.radial(omega, a).into_iter().enumerate() {
            let nf = n as f64;
            let e_tt = (fp + nf * g / a) / a + nf * (-nf * f / a - gp) / a;
            s += (-lambda * alpha * alpha * f + 2.0 * mu * e_tt) * (nf * theta).cos();
        }
        s * phi0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const AL: Cavity = Cavity {
        density: 2700.0,
        p_speed: 6320.0,
        s_speed: 3130.0,
        radius: 1e-3,
    };

    /// At low frequency the cavity sees the incident wave's uniform strain `eps = i alpha
    /// U0`, a biaxial stress `S1 = (lambda + 2 mu) eps` along x and `S2 = lambda eps`
    /// across: Kirsch's hoop stress `S1 + S2 - 2 (S1 - S2) cos(2 theta)`. The strain's
    /// gradient across the cavity adds a part of order `alpha a` odd in x (`theta -> pi -
    /// theta`), removed by the mean of the two sides; what remains is of order
    /// `(alpha a)^2`.
    #[test]
    fn low_frequency_hoop_stress_is_kirschs() {
        let (lambda, mu) = AL.lame();
        let omega = 2.0 * PI * 1e2; // alpha a = 1e-4
        let eps = Complex64::new(0.0, omega / AL.p_speed);
        for k in 0..12 {
            let th = k as f64 * PI / 11.0;
            let (s1, s2) = ((lambda + 2.0 * mu) * eps, lambda * eps);
            let kirsch = s1 + s2 - 2.0 * (s1 - s2) * (2.0 * th).cos();
            let got = 0.5 * (AL.hoop_stress(omega, th) + AL.hoop_stress(omega, PI - th));
            assert!(
                (got - kirsch).norm() < 1e-6 * s1.norm(),
                "theta {th}: {got} against {kirsch}"
            );
        }
    }

    /// The series' field is traction free on the face (finite differences of its own
    /// displacement in r and theta, with Hooke's law in polar coordinates), and a cavity
    /// much smaller than the wavelength leaves the incident wave unchanged far from it.
    #[test]
    fn the_face_is_traction_free_and_a_small_cavity_leaves_the_incident_wave() {
        let (lambda, mu) = AL.lame();
        for f in [0.3e6, 1e6, 2e6] {
            let omega = 2.0 * PI * f;
            let alpha = omega / AL.p_speed;
            let scale = (lambda + 2.0 * mu) * alpha; // the incident stress per U0
            let a = AL.radius;
            let (dr, dt) = (1e-5 * a, 1e-5);
            for k in 0..7 {
                let th = 0.2 + k as f64 * 0.45;
                let u = |r: f64, t: f64| AL.displacement(omega, r, t);
                let (c, rp, tp, tm) = (u(a, th), u(a + dr, th), u(a, th + dt), u(a, th - dt));
                let ur_r = (rp.radial - c.radial) / dr;
                let ut_r = (rp.hoop - c.hoop) / dr;
                let ur_t = (tp.radial - tm.radial) / (2.0 * dt);
                let ut_t = (tp.hoop - tm.hoop) / (2.0 * dt);
                let s_rr = (lambda + 2.0 * mu) * ur_r + lambda * (c.radial + ut_t) / a;
                let s_rt = mu * (ut_r - c.hoop / a + ur_t / a);
                assert!(
                    s_rr.norm() < 1e-3 * scale,
                    "f {f}: sigma_rr {}",
                    s_rr.norm()
                );
                assert!(
                    s_rt.norm() < 1e-3 * scale,
                    "f {f}: sigma_rt {}",
                    s_rt.norm()
                );
            }
        }
        // a cavity of a thousandth of the wavelength: 10 wavelengths away, the incident
        // wave to 1e-4
        let tiny = Cavity { radius: 1e-6, ..AL };
        let omega = 2.0 * PI * 1e6;
        let alpha = omega / AL.p_speed;
        let r = 10.0 * 2.0 * PI / alpha;
        for th in [0.0, 1.0, 2.5] {
            let u = tiny.displacement(omega, r, th);
            let inc = Complex64::new(0.0, alpha * r * f64::cos(th)).exp();
            assert!((u.radial - inc * f64::cos(th)).norm() < 1e-4);
            assert!((u.hoop + inc * f64::sin(th)).norm() < 1e-4);
        }
    }
}

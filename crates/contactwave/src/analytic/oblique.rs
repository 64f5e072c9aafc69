//! Plane P and SV waves at oblique incidence on the interface x = 0 between two isotropic
//! half-spaces (model.md section 14): the waves' polarisations and interface tractions at a
//! fixed horizontal slowness, the plane-wave impedance matrices the exact solver uses, and
//! the closed-form reflection and transmission coefficients of a linear spring interface
//! (normal stiffness K_N, tangential K_T) and of a welded interface (the Zoeppritz
//! equations, Aki & Richards, *Quantitative Seismology*, 2nd ed. 2002, section 5.2.4, with
//! their explicit coefficients, eq. 5.40, as an independent check).
//!
//! Coordinates: x normal to the interface (medium 1 in x < 0, medium 2 in x > 0), y along
//! it in the plane of incidence; vectors are `[normal, tangential]`. Every field depends on
//! `t - p y - eta x` with the horizontal slowness `p = sin(theta)/c` common to all waves
//! (Snell's law) and the vertical slowness `eta = +-sqrt(1/c^2 - p^2)` (+ travels toward
//! +x, "down"). A wave's particle velocity is `w(t) a`, `a` its unit polarisation: along
//! the propagation direction `k` for P, `k` turned by +90 degrees (from x toward y) for SV.
//! Its "wave stress" is `s = -rho c w` (the normal, P, or shear, SV, stress at the interface
//! at normal incidence, the convention of model.md sections 3 and 13).

use rustfft::num_complex::Complex64;

/// An isotropic elastic medium for plane waves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Longitudinal (P) wave speed, m/s.
    pub cp: f64,
    /// Shear (S) wave speed, m/s.
    pub cs: f64,
}

/// Wave type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WaveType {
    /// Longitudinal wave.
    P,
    /// Shear wave polarised in the plane of incidence.
    Sv,
}

impl WaveType {
    /// Name, `"P"` or `"SV"`.
    pub fn name(self) -> &'static str {
        match self {
            WaveType::P => "P",
            WaveType::Sv => "SV",
        }
    }
}

impl Elastic {
    /// Speed of a wave type, m/s.
    pub fn speed(&self, w: WaveType) -> f64 {
        match w {
            WaveType::P => self.cp,
            WaveType::Sv => self.cs,
        }
    }
}

/// One plane wave at the interface, per unit particle velocity `w`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneWave {
    /// Unit polarisation `a` = particle velocity per unit w, `[normal, tangential]`.
    pub polarisation: [f64; 2],
    /// Traction `[sigma_xx, sigma_xy]` on the interface per unit w, Pa s/m.
    pub traction: [f64; 2],
    /// Energy flux toward +x (down) or -x (up) per unit `w^2`, `rho c cos(angle)`, Pa s/m.
    pub flux: f64,
    /// Angle from the interface normal, rad.
    pub angle: f64,
    /// `rho c` of the wave, Pa s/m (`s = -rho c w`).
    pub impedance: f64,
}

/// The plane wave of type `w` in medium `m` at horizontal slowness `p` (s/m), travelling
/// down (+x) or up (-x). `None` when it does not propagate (`p c >= 1`).
pub fn plane_wave(m: &Elastic, w: WaveType, p: f64, down: bool) -> Option<PlaneWave> {
    let c = m.speed(w);
    let sin = p * c;
    if !(sin.abs() < 1.0) {
        return None;
    }
    let cos = (1.0 - sin * sin).sqrt();
    let sgn = if down { 1.0 } else { -1.0 };
    let eta = sgn * cos / c;
    // propagation direction k = (sgn cos, sin); SV: k turned by +90 degrees
    let a = match w {
        WaveType::P => [sgn * cos, sin],
        WaveType::Sv => [-sin, sgn * cos],
    };
    let mu = m.density * m.cs * m.cs;
    let lam2mu = m.density * m.cp * m.cp;
    let lam = lam2mu - 2.0 * mu;
    // u = a f(t - p y - eta x): d/dx = -eta f', d/dy = -p f'
    let traction = [
        -(lam2mu * eta * a[0] + lam * p * a[1]),
        -mu * (p * a[0] + eta * a[1]),
    ];
    Some(PlaneWave {
        polarisation: a,
        traction,
        flux: m.density * c * cos,
        angle: sin.asin(),
        impedance: m.density * c,
    })
}

/// A critical angle exceeded: the wave that would not propagate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Critical {
    /// The critical angle of the incident wave, degrees.
    pub angle_deg: f64,
    /// Medium (1 or 2) of the evanescent wave.
    pub medium: u8,
    /// Type of the evanescent wave.
    pub wave: WaveType,
}

/// The four outgoing waves (reflected P, SV in medium 1; transmitted P, SV in medium 2) and
/// the incident one, at one horizontal slowness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Horizontal slowness p, s/m.
    pub slowness: f64,
    /// The incident wave (down, medium 1).
    pub incident: PlaneWave,
    /// Type of the incident wave.
    pub incident_type: WaveType,
    /// Reflected P and SV (up, medium 1).
    pub reflected: [PlaneWave; 2],
    /// Down-going P and SV of medium 1 (the pair whose compliance is `C1`).
    pub down1: [PlaneWave; 2],
    /// Transmitted P and SV (down, medium 2); `None` for a rigid wall.
    pub transmitted: Option<[PlaneWave; 2]>,
}

/// Critical angle (degrees) of an incident wave of speed `c_inc` for a wave of speed `c`
/// (90 when `c <= c_inc`).
fn critical_deg(c_inc: f64, c: f64) -> f64 {
    if c <= c_inc {
        90.0
    } else {
        (c_inc / c).asin().to_degrees()
    }
}

impl Geometry {
    /// The waves of an incident `wave` at `angle` (rad, in [0, pi/2)) from the normal in
    /// medium 1, medium 2 `m2` (`None`: rigid wall). Err names the smallest critical angle
    /// exceeded (reached) when a reflected or transmitted wave would be evanescent.
    pub fn new(
        m1: &Elastic,
        m2: Option<&Elastic>,
        wave: WaveType,
        angle: f64,
    ) -> Result<Geometry, Critical> {
        let c_inc = m1.speed(wave);
        let p = angle.sin() / c_inc;
        let mut worst: Option<Critical> = None;
        let mut media = vec![(1u8, *m1)];
        if let Some(m) = m2 {
            media.push((2, *m));
        }
        for (k, m) in media {
            for w in [WaveType::P, WaveType::Sv] {
                if p * m.speed(w) >= 1.0 {
                    let c = Critical {
                        angle_deg: critical_deg(c_inc, m.speed(w)),
                        medium: k,
                        wave: w,
                    };
                    if worst.is_none_or(|x| c.angle_deg < x.angle_deg) {
                        worst = Some(c);
                    }
                }
            }
        }
        if let Some(c) = worst {
            return Err(c);
        }
        let pw = |m: &Elastic, w, down| {
            plane_wave(m, w, p, down).ok_or(Critical {
                angle_deg: 90.0,
                medium: 1,
                wave: w,
            })
        };
        Ok(Geometry {
            slowness: p,
            incident: pw(m1, wave, true)?,
            incident_type: wave,
            reflected: [pw(m1, WaveType::P, false)?, pw(m1, WaveType::Sv, false)?],
            down1: [pw(m1, WaveType::P, true)?, pw(m1, WaveType::Sv, true)?],
            transmitted: match m2 {
                Some(m) => Some([pw(m, WaveType::P, true)?, pw(m, WaveType::Sv, true)?]),
                None => None,
            },
        })
    }

    /// Compliance `C = Z^-1` of a pair of outgoing waves: the particle velocity of the face
    /// per unit traction, `v = -C sigma` for down-going waves (medium 2), `v = C^T sigma`
    /// for up-going ones (medium 1; the matrix of its down-going pair, transposed),
    /// m/(Pa s). Built as `C = -A T^-1` (`A`, `T` the columns of polarisations and
    /// tractions of the down-going pair).
    pub fn compliance(pair: &[PlaneWave; 2]) -> [[f64; 2]; 2] {
        let a = [
            [pair[0].polarisation[0], pair[1].polarisation[0]],
            [pair[0].polarisation[1], pair[1].polarisation[1]],
        ];
        let t = [
            [pair[0].traction[0], pair[1].traction[0]],
            [pair[0].traction[1], pair[1].traction[1]],
        ];
        let ti = inv2(&t);
        let mut c = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                c[i][j] = -(a[i][0] * ti[0][j] + a[i][1] * ti[1][j]);
            }
        }
        c
    }

    /// Wave amplitudes `(w_P, w_SV)` of a pair of waves whose summed traction is `sigma`:
    /// the inverse of the traction columns, Pa^-1 m/s.
    pub fn traction_to_waves(pair: &[PlaneWave; 2]) -> [[f64; 2]; 2] {
        inv2(&[
            [pair[0].traction[0], pair[1].traction[0]],
            [pair[0].traction[1], pair[1].traction[1]],
        ])
    }
}

/// Inverse of a 2x2 matrix.
pub fn inv2(m: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let d = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    [[m[1][1] / d, -m[0][1] / d], [-m[1][0] / d, m[0][0] / d]]
}

/// Complex reflection and transmission coefficients of particle velocity (`w` of each
/// outgoing wave per unit `w` of the incident one): `[R_P, R_SV, T_P, T_SV]` (T zero for a
/// rigid wall).
pub type Coefficients = [Complex64; 4];

/// Interface of the closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bond {
    /// Linear springs: dynamic traction `K [u]` with `[u] = u2 - u1`, normal and
    /// tangential stiffness K_N, K_T (Pa/m, either may be 0: free in that direction).
    Springs {
        /// Normal stiffness K_N, Pa/m.
        normal: f64,
        /// Tangential stiffness K_T, Pa/m.
        tangential: f64,
    },
    /// Welded: displacement and traction continuous (the Zoeppritz equations).
    Welded,
}

/// Closed-form coefficients at angular frequency `omega` (rad/s; fields `exp(i omega t)`)
/// from the interface conditions as a linear system (4x4 with medium 2, 2x2 against a
/// rigid wall): traction continuous, `sigma = K [u]` (springs, `i omega [u] = v2 - v1`) or
/// `v1 = v2` (welded).
pub fn coefficients(g: &Geometry, bond: Bond, omega: f64) -> Coefficients {
    let c = |x: f64| Complex64::new(x, 0.0);
    let z = Complex64::new(0.0, 0.0);
    let io = Complex64::new(0.0, omega);
    let inc = g.incident;
    let [rp, rs] = g.reflected;
    match g.transmitted {
        Some([tp, ts]) => {
            // unknowns (R_P, R_SV, T_P, T_SV)
            let mut m = [[z; 4]; 4];
            let mut b = [z; 4];
            for i in 0..2 {
                // sigma1 - sigma2 = 0
                m[i] = [
                    c(rp.traction[i]),
                    c(rs.traction[i]),
                    c(-tp.traction[i]),
                    c(-ts.traction[i]),
                ];
                b[i] = c(-inc.traction[i]);
                let r = 2 + i;
                match bond {
                    Bond::Welded => {
                        // v1 - v2 = 0
                        m[r] = [
                            c(rp.polarisation[i]),
                            c(rs.polarisation[i]),
                            c(-tp.polarisation[i]),
                            c(-ts.polarisation[i]),
                        ];
                        b[r] = c(-inc.polarisation[i]);
                    }
                    Bond::Springs { normal, tangential } => {
                        // i omega sigma2 - K (v2 - v1) = 0
                        let k = c(if i == 0 { normal } else { tangential });
                        m[r] = [
                            k * rp.polarisation[i],
                            k * rs.polarisation[i],
                            io * tp.traction[i] - k * tp.polarisation[i],
                            io * ts.traction[i] - k * ts.polarisation[i],
                        ];
                        b[r] = -k * inc.polarisation[i];
                    }
                }
            }
            solve_complex(&mut m, &mut b);
            b
        }
        None => {
            // rigid wall: i omega sigma1 + K v1 = 0 (springs) or v1 = 0 (welded)
            let mut m = [[z; 2]; 2];
            let mut b = [z; 2];
            for i in 0..2 {
                match bond {
                    Bond::Welded => {
                        m[i] = [c(rp.polarisation[i]), c(rs.polarisation[i])];
                        b[i] = c(-inc.polarisation[i]);
                    }
                    Bond::Springs { normal, tangential } => {
                        let k = if i == 0 { normal } else { tangential };
                        m[i] = [
                            io * rp.traction[i] + k * rp.polarisation[i],
                            io * rs.traction[i] + k * rs.polarisation[i],
                        ];
                        b[i] = -(io * inc.traction[i] + k * inc.polarisation[i]);
                    }
                }
            }
            solve_complex(&mut m, &mut b);
            [b[0], b[1], z, z]
        }
    }
}

/// Energy flux of each outgoing wave per unit incident flux, `|coef|^2 flux / flux_inc`:
/// `[R_P, R_SV, T_P, T_SV]`; sums to 1 for an interface that stores no energy over a
/// cycle (springs, welded).
pub fn energy_fractions(g: &Geometry, coef: &Coefficients) -> [f64; 4] {
    let f0 = g.incident.flux;
    let mut out = [0.0; 4];
    out[0] = coef[0].norm_sqr() * g.reflected[0].flux / f0;
    out[1] = coef[1].norm_sqr() * g.reflected[1].flux / f0;
    if let Some(t) = g.transmitted {
        out[2] = coef[2].norm_sqr() * t[0].flux / f0;
        out[3] = coef[3].norm_sqr() * t[1].flux / f0;
    }
    out
}

/// Gaussian elimination with partial pivoting on a small complex system, in place (the
/// solution in `b`).
fn solve_complex<const K: usize>(m: &mut [[Complex64; K]; K], b: &mut [Complex64; K]) {
    for col in 0..K {
        let piv = (col..K)
            .max_by(|&x, &y| m[x][col].norm().total_cmp(&m[y][col].norm()))
            .unwrap_or(col);
        m.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..K {
            let f = m[r][col] / m[col][col];
            for cc in col..K {
                let v = m[col][cc];
                m[r][cc] -= f * v;
            }
            let v = b[col];
            b[r] -= f * v;
        }
    }
    for col in (0..K).rev() {
        let mut v = b[col];
        for cc in col + 1..K {
            v -= m[col][cc] * b[cc];
        }
        b[col] = v / m[col][col];
    }
}

/// Aki & Richards' explicit displacement coefficients for an incident P wave on a welded
/// interface (their eq. 5.40): `[PP reflected, PS reflected, PP transmitted, PS
/// transmitted]` in their sign conventions (the magnitudes are the same as ours).
pub fn aki_richards_p(m1: &Elastic, m2: &Elastic, angle: f64) -> [f64; 4] {
    let (r1, a1, b1) = (m1.density, m1.cp, m1.cs);
    let (r2, a2, b2) = (m2.density, m2.cp, m2.cs);
    let p = angle.sin() / a1;
    let cos = |c: f64| (1.0 - (p * c).powi(2)).sqrt();
    let (ci1, ci2, cj1, cj2) = (cos(a1), cos(a2), cos(b1), cos(b2));
    let p2 = p * p;
    let a = r2 * (1.0 - 2.0 * b2 * b2 * p2) - r1 * (1.0 - 2.0 * b1 * b1 * p2);
    let b = r2 * (1.0 - 2.0 * b2 * b2 * p2) + 2.0 * r1 * b1 * b1 * p2;
    let c = r1 * (1.0 - 2.0 * b1 * b1 * p2) + 2.0 * r2 * b2 * b2 * p2;
    let d = 2.0 * (r2 * b2 * b2 - r1 * b1 * b1);
    let e = b * ci1 / a1 + c * ci2 / a2;
    let f = b * cj1 / b1 + c * cj2 / b2;
    let g = a - d * (ci1 / a1) * (cj2 / b2);
    let h = a - d * (ci2 / a2) * (cj1 / b1);
    let dd = e * f + g * h * p2;
    [
        ((b * ci1 / a1 - c * ci2 / a2) * f - (a + d * (ci1 / a1) * (cj2 / b2)) * h * p2) / dd,
        -2.0 * (ci1 / a1) * (a * b + c * d * (ci2 / a2) * (cj2 / b2)) * p * a1 / (b1 * dd),
        2.0 * r1 * (ci1 / a1) * f * a1 / (a2 * dd),
        2.0 * r1 * (ci1 / a1) * h * p * a1 / (b2 * dd),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const AL: Elastic = Elastic {
        density: 2700.0,
        cp: 6320.0,
        cs: 3130.0,
    };
    const STEEL: Elastic = Elastic {
        density: 7850.0,
        cp: 5900.0,
        cs: 3200.0,
    };

    #[test]
    fn impedance_is_rho_c_at_normal_incidence_and_flux_orthogonal_oblique() {
        let g = Geometry::new(&AL, Some(&STEEL), WaveType::P, 0.0).unwrap();
        let c = Geometry::compliance(&g.transmitted.unwrap());
        assert!((c[0][0] * STEEL.density * STEEL.cp - 1.0).abs() < 1e-14);
        assert!((c[1][1] * STEEL.density * STEEL.cs - 1.0).abs() < 1e-14);
        assert!(c[0][1].abs() < 1e-25 && c[1][0].abs() < 1e-25);
        let g = Geometry::new(&AL, Some(&STEEL), WaveType::P, 0.5).unwrap();
        // a pair's cross flux vanishes and the compliance's off-diagonal is antisymmetric
        let [p, s] = g.transmitted.unwrap();
        let dot = |x: [f64; 2], y: [f64; 2]| x[0] * y[0] + x[1] * y[1];
        let cross = dot(p.traction, s.polarisation) + dot(s.traction, p.polarisation);
        assert!(cross.abs() < 1e-9 * p.flux);
        let c = Geometry::compliance(&g.transmitted.unwrap());
        assert!((c[0][1] + c[1][0]).abs() < 1e-12 * c[0][0]);
        assert!(c[0][1].abs() > 1e-3 * c[0][0]);
        // a wave's own flux: -sigma . v = rho c cos
        assert!((-dot(p.traction, p.polarisation) - p.flux).abs() < 1e-9 * p.flux);
    }

    #[test]
    fn welded_matches_aki_richards_and_conserves_energy() {
        for deg in [0.0f64, 10.0, 20.0, 30.0] {
            let g = Geometry::new(&AL, Some(&STEEL), WaveType::P, deg.to_radians()).unwrap();
            let r = coefficients(&g, Bond::Welded, 1e6);
            let ar = aki_richards_p(&AL, &STEEL, deg.to_radians());
            for k in 0..4 {
                assert!(
                    (r[k].norm() - ar[k].abs()).abs() < 1e-12,
                    "{deg} {k} {} {}",
                    r[k],
                    ar[k]
                );
            }
            let e = energy_fractions(&g, &r);
            assert!((e.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn critical_angle_is_named() {
        // SV in aluminium: reflected P evanescent beyond asin(cs/cp)
        let e = Geometry::new(&AL, None, WaveType::Sv, 40f64.to_radians()).unwrap_err();
        assert!((e.angle_deg - (AL.cs / AL.cp).asin().to_degrees()).abs() < 1e-12);
        assert_eq!((e.medium, e.wave), (1, WaveType::P));
        assert!(Geometry::new(&AL, None, WaveType::Sv, 29f64.to_radians()).is_ok());
    }
}

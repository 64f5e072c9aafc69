//! The scheme's numerical dispersion by Bloch-wave analysis (docs/model.md section 15.4):
//! the phase velocity of a plane wave of any direction on the uniform mesh of square
//! elements, from the spectral elements' own operator (GLL quadrature, diagonal mass)
//! and the central differences in time, without running the solver.
//!
//! On a uniform mesh every element is the same, so a plane wave `u = U e^{i (k.x - omega t)}`
//! is carried by the `n x n` nodes of one element (order `n`) with the Bloch phases
//! `e^{i k_x h}`, `e^{i k_z h}` on its far edges. Its frequencies are the eigenvalues of
//!
//! ```text
//!     (15.6a)  K(k) U = omega_h^2 M U,     sin(omega dt / 2) = omega_h dt / 2,
//! ```
//!
//! the second relation being the central differences' (`u^{n+1} - 2 u^n + u^{n-1} =
//! -dt^2 omega_h^2 u^n`). The branch of the continuum's wave is followed by Rayleigh
//! quotient iteration from the nodal samples of the continuum's mode, and the error
//! reported is `omega / (c k) - 1` at the continuum's `k = omega / c`.

use super::{Elastic, WaveType};
use crate::error::{Error, Result};
use crate::numeric::gll::Gll;
use rustfft::num_complex::Complex64;

/// The plane waves of the analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Branch {
    /// Longitudinal (P-SV runs).
    P,
    /// Shear in the plane (P-SV runs).
    Sv,
    /// Antiplane shear (SH runs).
    Sh,
}

impl Branch {
    /// The wave type of the runs that carry it.
    pub fn wave(self) -> WaveType {
        match self {
            Branch::Sh => WaveType::Sh,
            _ => WaveType::PSv,
        }
    }
}

/// The relative phase velocity error `c_num / c - 1` of the scheme for a plane wave of
/// `branch` at `frequency` (Hz) travelling at `angle` (rad from +z toward +x) in
/// `material`, with elements of `order` (2 to 8) and size `h` (m), time step `dt` (s; 0:
/// the semi-discrete scheme, exact in time).
///
/// ```
/// use contactwave::solver::solid_2d::dispersion::{phase_error, Branch};
/// use contactwave::solver::solid_2d::Elastic;
/// let al = Elastic { density: 2700.0, p_speed: 6320.0, s_speed: 3130.0 };
/// // order 4, 1.6 elements per S wavelength, exact in time: along z the elements are
/// // slow (-2.6e-4), at 26 degrees fast (+3.0e-4)
/// let h = 3130.0 / 15e6 / 1.6;
/// let e = phase_error(4, h, 0.0, &al, Branch::Sv, 0.0, 15e6).unwrap();
/// assert!(e < -2e-4 && e > -3e-4);
/// let e = phase_error(4, h, 0.0, &al, Branch::Sv, 26f64.to_radians(), 15e6).unwrap();
/// assert!(e > 2.5e-4 && e < 3.5e-4);
/// ```
pub fn phase_error(
    order: usize,
    h: f64,
    dt: f64,
    material: &Elastic,
    branch: Branch,
    angle: f64,
    frequency: f64,
) -> Result<f64> {
    let (omega_h, omega) = spatial(order, h, material, branch, angle, frequency)?;
    with_step(omega_h, omega, dt)
}

/// The error `omega_num / omega - 1` of the central differences at step `dt` (s; 0: none)
/// on a wave whose semi-discrete frequency is `omega_h` (rad/s) for the continuum's
/// `omega`.
fn with_step(omega_h: f64, omega: f64, dt: f64) -> Result<f64> {
    if !(dt >= 0.0 && dt.is_finite()) {
        return Err(Error::invalid("<dispersion>", "dt", dt, ">= 0"));
    }
    let w = if dt > 0.0 {
        let a = omega_h * dt / 2.0;
        if a >= 1.0 {
            return Err(Error::invalid(
                "<dispersion>",
                "dt",
                dt,
                "below the stability limit of the wave",
            ));
        }
        2.0 / dt * a.asin()
    } else {
        omega_h
    };
    Ok(w / omega - 1.0)
}

/// The semi-discrete frequency (rad/s) of the branch's wave of the continuum's wavenumber
/// at `frequency`, and the continuum's angular frequency.
fn spatial(
    order: usize,
    h: f64,
    material: &Elastic,
    branch: Branch,
    angle: f64,
    frequency: f64,
) -> Result<(f64, f64)> {
    let bad = |field: &str, value: f64, allowed: &str| {
        Err(Error::invalid("<dispersion>", field, value, allowed))
    };
    if !super::ORDERS.contains(&order) {
        return bad("order", order as f64, "2 to 8");
    }
    if !(h > 0.0 && h.is_finite()) {
        return bad("h", h, "> 0");
    }
    if !(frequency > 0.0 && frequency.is_finite()) {
        return bad("frequency", frequency, "> 0");
    }
    let gll =
        Gll::new(order).ok_or_else(|| Error::invalid("<dispersion>", "order", order, "2 to 8"))?;
    let c = if branch == Branch::P {
        material.p_speed
    } else {
        material.s_speed
    };
    let omega = 2.0 * std::f64::consts::PI * frequency;
    let k = omega / c;
    let (s, co) = angle.sin_cos();
    let cell = Cell::new(&gll, h, material, branch.wave(), [k * s * h, k * co * h]);
    // the continuum's mode sampled at the nodes, mass-weighted: the starting vector
    let pol = match branch {
        Branch::P => [s, co],
        Branch::Sv => [co, -s],
        Branch::Sh => [1.0, 0.0],
    };
    let x0: Vec<Complex64> = (0..cell.size)
        .map(|r| {
            let (i, j, comp) = cell.unpack(r);
            let (x, z) = (cell.xi[i] * h, cell.xi[j] * h);
            Complex64::from_polar(pol[comp] * cell.mass[r].sqrt(), k * (s * x + co * z))
        })
        .collect();
    let omega_h2 = cell.eigenvalue(&x0)?;
    Ok((omega_h2.max(0.0).sqrt(), omega))
}

/// The largest phase velocity error (signed; the largest magnitude) of the waves of `wave`
/// in `material` at `frequency` (Hz) over the directions 0 to 45 degrees (3 degrees apart;
/// square elements make the other octants alike: the error at `90 - theta` is that at
/// `theta`, the cell mirrored about its diagonal), with time step `dt` (s) and with any
/// smaller one (the semi-discrete error too), for elements of `order` and size `h` (m);
/// with the branch and direction (degrees) where it occurs.
pub fn worst_phase_error(
    order: usize,
    h: f64,
    dt: f64,
    material: &Elastic,
    wave: WaveType,
    frequency: f64,
) -> Result<(f64, Branch, f64)> {
    let branches: &[Branch] = match wave {
        WaveType::PSv => &[Branch::P, Branch::Sv],
        WaveType::Sh => &[Branch::Sh],
    };
    let mut worst = (0.0f64, branches[0], 0.0);
    for &b in branches {
        for deg in (0..=45).step_by(3) {
            let e = errors(order, h, dt, material, b, f64::from(deg), frequency)?;
            if e.abs() > worst.0.abs() {
                worst = (e, b, f64::from(deg));
            }
        }
    }
    Ok(worst)
}

/// The error of larger magnitude with step `dt` and without, at `deg` degrees.
fn errors(
    order: usize,
    h: f64,
    dt: f64,
    material: &Elastic,
    branch: Branch,
    deg: f64,
    frequency: f64,
) -> Result<f64> {
    let (omega_h, omega) = spatial(order, h, material, branch, deg.to_radians(), frequency)?;
    let (a, b) = (
        with_step(omega_h, omega, 0.0)?,
        with_step(omega_h, omega, dt)?,
    );
    Ok(if a.abs() > b.abs() { a } else { b })
}

/// The largest element size (m) of `order` that keeps every wave of `wave` in every one
/// of `materials` within `budget` of its phase velocity at `frequency` (Hz) in every
/// direction, with time step `dt` (s) or any smaller one ([`worst_phase_error`]): the
/// first of 4, 4.1, 4.2, ... 16 GLL points per S wavelength of the slowest material that
/// does (`None` when none does, or for no material). Remembered for the process (the
/// last [`REMEMBERED`] questions): a sweep or an identification asks the same one at
/// every point, and order 6 takes about 0.1 s.
pub fn element_size_for(
    order: usize,
    dt: f64,
    materials: &[Elastic],
    wave: WaveType,
    frequency: f64,
    budget: f64,
) -> Option<f64> {
    type Memo = Vec<(Vec<u64>, Option<f64>)>;
    static MEMO: std::sync::Mutex<Memo> = std::sync::Mutex::new(Vec::new());
    let mut key = vec![
        order as u64,
        dt.to_bits(),
        frequency.to_bits(),
        budget.to_bits(),
    ];
    key.push(u64::from(wave == WaveType::PSv));
    for m in materials {
        key.extend([m.density, m.p_speed, m.s_speed].map(f64::to_bits));
    }
    // (a poisoned lock only loses the memo: the answer is computed again)
    let found = MEMO
        .lock()
        .ok()
        .and_then(|m| m.iter().find(|(k, _)| *k == key).map(|(_, h)| *h));
    if let Some(h) = found {
        return h;
    }
    let search = || -> Option<f64> {
        let cs = materials
            .iter()
            .map(|m| m.s_speed)
            .fold(f64::INFINITY, f64::min);
        if !(cs.is_finite() && cs > 0.0) {
            return None;
        }
        // a candidate is first tried where the last one failed (most fail there, at once)
        let mut hint: Option<(usize, Branch, f64)> = None;
        (40..=160).find_map(|tenths| {
            let h = cs / frequency * order as f64 / (f64::from(tenths) / 10.0);
            if let Some((i, b, deg)) = hint {
                let e = errors(order, h, dt, &materials[i], b, deg, frequency);
                if !e.is_ok_and(|e| e.abs() <= budget) {
                    return None;
                }
            }
            for (i, m) in materials.iter().enumerate() {
                match worst_phase_error(order, h, dt, m, wave, frequency) {
                    Ok((e, b, deg)) if e.abs() > budget => {
                        hint = Some((i, b, deg));
                        return None;
                    }
                    Ok(_) => {}
                    Err(_) => return None,
                }
            }
            Some(h)
        })
    };
    let h = search();
    if let Ok(mut m) = MEMO.lock() {
        if m.len() >= REMEMBERED {
            m.remove(0);
        }
        m.push((key, h));
    }
    h
}

/// The questions [`element_size_for`] remembers.
pub const REMEMBERED: usize = 64;

/// One periodic element: its Hermitian operator `M^{-1/2} K(k) M^{-1/2}`, row-major.
struct Cell {
    n: usize,
    size: usize,
    /// Node positions in the element, in units of h, from 0 to 1.
    xi: Vec<f64>,
    mass: Vec<f64>,
    a: Vec<Complex64>,
}

impl Cell {
    fn new(gll: &Gll, h: f64, m: &Elastic, wave: WaveType, phase: [f64; 2]) -> Cell {
        let n = gll.order;
        let np = n + 1;
        let comps = if wave == WaveType::PSv { 2 } else { 1 };
        let size = comps * n * n;
        let (w, d) = (&gll.weights, &gll.derivative);
        let mu = m.mu();
        let l2m = m.density * m.p_speed * m.p_speed;
        let lam = l2m - 2.0 * mu;
        let (j2, s) = (h * h / 4.0, 2.0 / h);
        // Bloch factor of element node (i, j) and its periodic unknown
        let bloch = |i: usize, j: usize| {
            Complex64::from_polar(
                1.0,
                if i == n { phase[0] } else { 0.0 } + if j == n { phase[1] } else { 0.0 },
            )
        };
        let mut mass = vec![0.0; size];
        for i in 0..np {
            for j in 0..np {
                for c in 0..comps {
                    mass[(c * n + j % n) * n + i % n] += m.density * j2 * w[i] * w[j];
                }
            }
        }
        let mut a = vec![Complex64::new(0.0, 0.0); size * size];
        let zero = Complex64::new(0.0, 0.0);
        let mut u = vec![[zero; 2]; np * np];
        let mut sig = vec![[zero; 3]; np * np];
        for col in 0..size {
            let (i0, j0, c0) = (col % n, (col / n) % n, col / (n * n));
            for i in 0..np {
                for j in 0..np {
                    u[j * np + i] = [zero; 2];
                    if i % n == i0 && j % n == j0 {
                        u[j * np + i][c0] = bloch(i, j);
                    }
                }
            }
            // stresses at the quadrature points: [s_xx, s_zz, s_xz] (P-SV) or [s_xy, s_zy]
            for q in 0..np {
                for p in 0..np {
                    let (mut dx, mut dz) = ([zero; 2], [zero; 2]);
                    for r in 0..np {
                        for c in 0..comps {
                            dx[c] += d[p * np + r] * u[q * np + r][c] * s;
                            dz[c] += d[q * np + r] * u[r * np + p][c] * s;
                        }
                    }
                    sig[q * np + p] = if comps == 2 {
                        [
                            dx[0] * l2m + dz[1] * lam,
                            dx[0] * lam + dz[1] * l2m,
                            (dz[0] + dx[1]) * mu,
                        ]
                    } else {
                        [dx[0] * mu, dz[0] * mu, zero]
                    };
                }
            }
            // forces: the quadrature of sigma : grad(test), folded with conjugate phases
            for b in 0..np {
                for a_ in 0..np {
                    let mut f = [zero; 2];
                    for r in 0..np {
                        let sx = sig[b * np + r];
                        let sz = sig[r * np + a_];
                        let gx = d[r * np + a_] * s * w[r] * w[b] * j2;
                        let gz = d[r * np + b] * s * w[a_] * w[r] * j2;
                        if comps == 2 {
                            f[0] += sx[0] * gx + sz[2] * gz;
                            f[1] += sx[2] * gx + sz[1] * gz;
                        } else {
                            f[0] += sx[0] * gx + sz[1] * gz;
                        }
                    }
                    let back = bloch(a_, b).conj();
                    for (c, fc) in f.iter().enumerate().take(comps) {
                        let row = (c * n + b % n) * n + a_ % n;
                        a[row * size + col] += fc * back;
                    }
                }
            }
        }
        for r in 0..size {
            for col in 0..size {
                a[r * size + col] /= (mass[r] * mass[col]).sqrt();
            }
        }
        let xi = gll.points.iter().map(|p| (p + 1.0) / 2.0).collect();
        Cell {
            n,
            size,
            xi,
            mass,
            a,
        }
    }

    /// `(i, j, component)` of unknown `r`.
    fn unpack(&self, r: usize) -> (usize, usize, usize) {
        (r % self.n, (r / self.n) % self.n, r / (self.n * self.n))
    }

    /// The eigenvalue of the operator whose eigenvector is nearest `x0`, by Rayleigh
    /// quotient iteration from `x0`; an error when the vector found is not mostly `x0`
    /// (the continuum's wave has no branch of its own at this resolution).
    fn eigenvalue(&self, x0: &[Complex64]) -> Result<f64> {
        let size = self.size;
        let norm = |x: &[Complex64]| x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        let mut x: Vec<Complex64> = x0.iter().map(|v| v / norm(x0)).collect();
        let mut lambda = f64::NAN;
        let mut m = vec![Complex64::new(0.0, 0.0); size * size];
        for _ in 0..30 {
            // the Rayleigh quotient
            let mut q = 0.0;
            for r in 0..size {
                let mut ax = Complex64::new(0.0, 0.0);
                for c in 0..size {
                    ax += self.a[r * size + c] * x[c];
                }
                q += (x[r].conj() * ax).re;
            }
            let done = (q - lambda).abs() <= 1e-15 * q.abs();
            lambda = q;
            if done {
                break;
            }
            m.copy_from_slice(&self.a);
            for r in 0..size {
                // a relative nudge keeps the solve regular at convergence
                m[r * size + r] -= lambda * (1.0 + 1e-13);
            }
            let y = solve(&mut m, &x, size);
            let ny = norm(&y);
            if !(ny.is_finite() && ny > 0.0) {
                break;
            }
            x = y.iter().map(|v| v / ny).collect();
        }
        let overlap: f64 = {
            let s: Complex64 = x.iter().zip(x0).map(|(a, b)| a.conj() * b).sum();
            s.norm() / norm(x0)
        };
        if overlap < 0.9 || !lambda.is_finite() {
            return Err(Error::invalid(
                "<dispersion>",
                "h",
                format!("{overlap:.3} overlap with the continuum's wave"),
                "at least two GLL points per wavelength",
            ));
        }
        Ok(lambda)
    }
}

/// Solve `m y = b` (`m` row-major `size x size`, overwritten) by Gaussian elimination with
/// partial pivoting.
fn solve(m: &mut [Complex64], b: &[Complex64], size: usize) -> Vec<Complex64> {
    let mut y = b.to_vec();
    for k in 0..size {
        let p = (k..size)
            .max_by(|&i, &j| {
                m[i * size + k]
                    .norm_sqr()
                    .total_cmp(&m[j * size + k].norm_sqr())
            })
            .unwrap_or(k);
        if p != k {
            for c in 0..size {
                m.swap(k * size + c, p * size + c);
            }
            y.swap(k, p);
        }
        let piv = m[k * size + k];
        if piv == Complex64::default() {
            continue;
        }
        for r in k + 1..size {
            let f = m[r * size + k] / piv;
            if f == Complex64::default() {
                continue;
            }
            for c in k..size {
                let v = m[k * size + c];
                m[r * size + c] -= f * v;
            }
            let v = y[k];
            y[r] -= f * v;
        }
    }
    for k in (0..size).rev() {
        let mut s = y[k];
        for c in k + 1..size {
            s -= m[k * size + c] * y[c];
        }
        let piv = m[k * size + k];
        y[k] = if piv == Complex64::default() {
            s
        } else {
            s / piv
        };
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    const AL: Elastic = Elastic {
        density: 2700.0,
        p_speed: 6320.0,
        s_speed: 3130.0,
    };

    fn h(per_s: f64) -> f64 {
        AL.s_speed / 15e6 / per_s
    }

    /// The elements' error falls as h^(2n) (order n = 4: 8), from below.
    #[test]
    fn semi_discrete_error_converges_at_order_2n() {
        let e = |per: f64| phase_error(4, h(per), 0.0, &AL, Branch::Sh, 0.0, 15e6).unwrap();
        let (e1, e2) = (e(1.5), e(3.0));
        let order = (e1 / e2).log2();
        eprintln!("{e1:e} {e2:e}: observed order {order:.2}");
        assert!(e1 < 0.0 && e2 < 0.0, "{e1:e} {e2:e}");
        assert!((7.5..8.5).contains(&order), "{order}");
    }

    /// Along an axis the SV wave is an SH wave (u_x of z alone has no normal stress).
    #[test]
    fn sv_along_an_axis_is_sh() {
        for a in [0.0, std::f64::consts::FRAC_PI_2] {
            let e = |b| phase_error(4, h(1.6), 0.0, &AL, b, a, 15e6).unwrap();
            let (sv, sh) = (e(Branch::Sv), e(Branch::Sh));
            assert!((sv - sh).abs() < 1e-12 && sv != 0.0, "{sv:e} {sh:e}");
        }
    }

    /// The x and z axes are alike (square elements), and so are +a and -a.
    #[test]
    fn symmetric_in_direction() {
        for b in [Branch::P, Branch::Sv, Branch::Sh] {
            let e = |a: f64| phase_error(5, h(1.2), 0.0, &AL, b, a.to_radians(), 15e6).unwrap();
            let (a, m, c) = (e(20.0), e(-20.0), e(70.0));
            assert!(
                (a - m).abs() < 1e-12 && (a - c).abs() < 1e-12,
                "{b:?} {a:e} {m:e} {c:e}"
            );
        }
    }

    /// With a fine mesh the error is the central differences': `2 asin(w dt / 2) / (w dt)
    /// - 1`, about `(omega dt)^2 / 24`.
    #[test]
    fn central_differences_add_their_phase_error() {
        let w = 2.0 * std::f64::consts::PI * 15e6;
        let dt = 0.12 / w;
        let e = phase_error(6, h(4.0), dt, &AL, Branch::P, 0.3, 15e6).unwrap();
        let exact = 2.0 * (w * dt / 2.0).asin() / (w * dt) - 1.0;
        assert!((e - exact).abs() < 1e-9, "{e:e} {exact:e}");
        assert!((e - 0.12f64.powi(2) / 24.0).abs() < 2e-6, "{e:e}");
    }

    /// The default order-4 elements for aluminium-like solids: about 1.6 to 1.7 elements
    /// per S wavelength (6.4 to 6.8 points); nearly incompressible solids need finer.
    #[test]
    fn element_size_follows_the_budget_and_poisson_ratio() {
        let w = 2.0 * std::f64::consts::PI * 15e6;
        let per = |nu: f64| {
            let m = Elastic {
                density: 2700.0,
                p_speed: 3000.0 * ((2.0 - 2.0 * nu) / (1.0 - 2.0 * nu)).sqrt(),
                s_speed: 3000.0,
            };
            let h = element_size_for(4, 0.12 / w, &[m], WaveType::PSv, 15e6, 9e-4).unwrap();
            let (e, _, _) = worst_phase_error(4, h, 0.12 / w, &m, WaveType::PSv, 15e6).unwrap();
            assert!(e.abs() <= 9e-4, "{e:e}");
            3000.0 / 15e6 / h
        };
        let (a, b) = (per(0.34), per(0.45));
        eprintln!("elements per S wavelength: nu 0.34 {a}, nu 0.45 {b}");
        assert!((1.55..1.75).contains(&a) && b > a, "{a} {b}");
    }

    /// A wave at a band edge of the elements (two elements per wavelength along an axis),
    /// an unstable step and bad arguments are errors, not panics.
    #[test]
    fn band_edge_and_bad_input_are_errors() {
        assert!(phase_error(4, h(2.0), 0.0, &AL, Branch::Sh, 0.0, 15e6).is_err());
        assert!(phase_error(4, h(1.6), 1e-6, &AL, Branch::P, 0.0, 15e6).is_err());
        assert!(phase_error(9, h(1.6), 0.0, &AL, Branch::P, 0.0, 15e6).is_err());
        assert!(phase_error(4, -1.0, 0.0, &AL, Branch::P, 0.0, 15e6).is_err());
        assert!(phase_error(4, h(1.6), 0.0, &AL, Branch::P, 0.0, f64::NAN).is_err());
    }
}

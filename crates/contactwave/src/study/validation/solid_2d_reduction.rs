//! The reduction to 1D (docs/model.md section 15.8, table 15.8-2), as `contactwave
//! validate` rows and tests: a full-width interface in a periodic strip (absorbing top and
//! bottom) under a plane wave at normal incidence, injected by total-field/scattered-field,
//! against the exact half-space solver (P: Signorini, linear, power law, quadratic, RCCM
//! with damage) and the coupled exact solver (SH: Coulomb friction, the full RCCM), at two
//! or more element sizes: gap, contact stress, reflected and transmitted A1 and A2/A1, and
//! the observed order of convergence.

use super::ValidationCase;
use super::{law_from_toml as law, ALUMINIUM};
use crate::error::{Error, Result};
use crate::excitation::{Excitation, ToneBurst, Window};
use crate::law::point::SharedLaw;
use crate::law::{ContactLaw, NormalPart, TangentialPart};
use crate::material::Material;
use crate::solver::half_space::{HalfSpace, HalfSpaceSettings};
use crate::solver::solid_2d::{Crack, Incidence, Solid2d, WaveType};
use std::sync::Arc;

fn failed(what: &str) -> Error {
    Error::invalid(
        "<validation>",
        "solid_2d reduction",
        what,
        "a converged reference",
    )
}

fn burst(amplitude: f64, f0: f64, cycles: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(amplitude, f0, cycles, Window::Hann))
}

/// The errors of a 2D run against the exact 1D solution, each over its scale: gap and
/// contact stress (max error over the max dynamic value), the reflected and transmitted
/// A1 (relative) and A2/A1 (absolute difference of the ratios).
#[derive(Debug, Clone, Copy)]
pub struct Reduction {
    /// Gap: the largest error over the largest exact gap.
    pub gap: f64,
    /// Contact stress: the largest error over the largest exact dynamic stress.
    pub stress: f64,
    /// Contact stress, root-mean-square error over the rms of the exact dynamic stress
    /// (the rigid laws' discrete impacts are spikes of one step: their max error does not
    /// fall with the resolution, their rms does).
    pub stress_rms: f64,
    /// The reflected wave's A1 at the receiver, relative error.
    pub reflected_a1: f64,
    /// The reflected wave's A2/A1, absolute difference from the exact ratio.
    pub reflected_ratio: f64,
    /// The transmitted wave's A1, relative error.
    pub transmitted_a1: f64,
    /// The transmitted wave's A2/A1, absolute difference from the exact ratio.
    pub transmitted_ratio: f64,
    /// The exact A2/A1 of the reflected and transmitted waves.
    pub exact_ratio: [f64; 2],
}

/// The 1D histories a 2D run is compared with: times (s, 0 when the incident front
/// reaches the interface), gap (m), contact stress (Pa), reflected and transmitted stress
/// at the interface (Pa).
pub struct Exact1d<'a> {
    /// Times, s.
    pub t: &'a [f64],
    /// Gap (normal or tangential), m.
    pub gap: &'a [f64],
    /// Contact stress, Pa.
    pub stress: &'a [f64],
    /// Reflected stress at the interface, Pa.
    pub reflected: &'a [f64],
    /// Transmitted stress at the interface, Pa.
    pub transmitted: &'a [f64],
}

fn interp(t: &[f64], y: &[f64], at: f64) -> f64 {
    if at <= t[0] {
        return if at < t[0] { 0.0 } else { y[0] };
    }
    let k = t.partition_point(|&x| x < at).clamp(1, t.len() - 1);
    let (t0, t1) = (t[k - 1], t[k]);
    let s = ((at - t0) / (t1 - t0)).clamp(0.0, 1.0);
    y[k - 1] + s * (y[k] - y[k - 1])
}

/// `|integral x(t) exp(-i 2 pi f t) dt|` of samples `x` at times `t` (uniform step).
fn amplitude(t: &[f64], x: &[f64], f: f64) -> f64 {
    let w = 2.0 * std::f64::consts::PI * f;
    let dt = t[1] - t[0];
    let (mut re, mut im) = (0.0, 0.0);
    for (&ti, &xi) in t.iter().zip(x) {
        re += xi * (w * ti).cos() * dt;
        im -= xi * (w * ti).sin() * dt;
    }
    re.hypot(im)
}

/// A full-width interface with `law` at `2.5 lambda` in a periodic strip (absorbing top and
/// bottom) under a plane wave of `incidence` at normal incidence injected at `lambda` (the
/// wave's wavelength at `f0`), at each element size of `sizes` (wavelengths), against
/// `exact`. Receivers at `0.5 lambda` (the scattered region: the reflected wave alone) and
/// `4.5 lambda` (the transmitted wave).
pub fn reduction<L: NormalPart + TangentialPart + Clone>(
    wave: WaveType,
    incidence: Incidence,
    law: L,
    signal: Arc<dyn Excitation>,
    exact: &Exact1d,
    sizes: &[f64],
) -> Result<Vec<Reduction>> {
    let f0 = signal.fundamental();
    let c = if incidence == Incidence::P {
        ALUMINIUM.p_speed
    } else {
        ALUMINIUM.s_speed
    };
    let z = ALUMINIUM.density * c;
    let lambda = c / f0;
    let (z_line, zc, depth) = (lambda, 2.5 * lambda, 5.0 * lambda);
    let (zr, zt) = (0.5 * lambda, 4.5 * lambda);
    let shear = incidence != Incidence::P;
    let comp = if incidence == Incidence::P { 1 } else { 0 };
    let t_exact = match exact.t.last() {
        Some(&t) if exact.t.len() >= 2 => t,
        _ => return Err(failed("an empty exact solution")),
    };
    let mut out = Vec::new();
    for &size in sizes {
        let h = size * lambda;
        let problem = Solid2d {
            cracks: vec![Crack::across(h, zc, law.clone())],
            receivers: vec![[0.0, zr], [0.0, zt]],
            ..Solid2d::plane_wave_strip(
                ALUMINIUM,
                wave,
                incidence,
                h,
                depth,
                z_line,
                signal.clone(),
                (zc - z_line) / c + 2.0 * lambda / c + 4.0 / f0,
            )
        };
        let plan = problem.plan("<validation>")?;
        let tau = plan.plane_waves[0].delay_at([0.0, zc]);
        // the receivers sit on the mesh line nearest to their depth
        let node = |z: f64| {
            plan.mesh
                .z
                .iter()
                .copied()
                .min_by(|a, b| (a - z).abs().total_cmp(&(b - z).abs()))
                .unwrap_or(z)
        };
        let (zr_node, zt_node) = (node(zr), node(zt));
        let o = plan.run()?;
        if !(o.energy.closure_error() < 1e-9) {
            return Err(failed("the energy of a 1D reduction run does not close"));
        }
        let rec = &o.cracks[0];
        let n = rec.position.len();
        let (gap_2d, stress_2d) = if shear {
            (&rec.tangential_gap, &rec.shear_stress)
        } else {
            (&rec.normal_gap, &rec.normal_stress)
        };
        let s0 = exact.stress[0];
        let gmax = exact.gap.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let smax = exact
            .stress
            .iter()
            .fold(0.0f64, |a, &b| a.max((b - s0).abs()));
        let (mut eg, mut es) = (0.0f64, 0.0f64);
        let (mut e2, mut s2) = (0.0f64, 0.0f64);
        for (k, &t) in rec.time.iter().enumerate() {
            if t - tau > t_exact {
                break;
            }
            let g = gap_2d[k * n];
            let s = stress_2d[k * n];
            eg = eg.max((g - interp(exact.t, exact.gap, t - tau)).abs());
            let se = if t - tau < 0.0 {
                s0
            } else {
                interp(exact.t, exact.stress, t - tau)
            };
            es = es.max((s - se).abs());
            e2 += (s - se) * (s - se);
            s2 += (se - s0) * (se - s0);
        }
        // the receivers' traces against the exact waves carried to them, on the window
        // both cover
        let t_end = t_exact.min(o.time.last().copied().unwrap_or(0.0) - tau - 2.0 * lambda / c);
        let window = |delay: f64| -> (Vec<f64>, usize) {
            let k = o.time.partition_point(|&t| t - tau - delay < t_end);
            (o.time[..k].to_vec(), k)
        };
        let harmonics = |t: &[f64], x: &[f64]| {
            let a1 = amplitude(t, x, f0);
            (a1, amplitude(t, x, 2.0 * f0) / a1)
        };
        let mut res = [(0.0, 0.0); 2];
        let mut ratios = [0.0; 2];
        for (i, (node_z, series, sign)) in [
            (zr_node, exact.reflected, 1.0),
            (zt_node, exact.transmitted, -1.0),
        ]
        .into_iter()
        .enumerate()
        {
            let delay = (node_z - zc).abs() / c;
            let (t2, k) = window(delay);
            let tr = &o.trace(i, comp)[..k];
            let ex: Vec<f64> = t2
                .iter()
                .map(|&t| sign * interp(exact.t, series, t - tau - delay) / z)
                .collect();
            let (a_2d, r_2d) = harmonics(&t2, tr);
            let (a_ex, r_ex) = harmonics(&t2, &ex);
            res[i] = ((a_2d / a_ex - 1.0).abs(), (r_2d - r_ex).abs());
            ratios[i] = r_ex;
        }
        out.push(Reduction {
            gap: eg / gmax,
            stress: es / smax,
            stress_rms: (e2 / s2).sqrt(),
            reflected_a1: res[0].0,
            reflected_ratio: res[0].1,
            transmitted_a1: res[1].0,
            transmitted_ratio: res[1].1,
            exact_ratio: ratios,
        });
    }
    Ok(out)
}

/// The observed orders between successive halvings of the element size.
pub fn orders(e: &[f64]) -> Vec<f64> {
    e.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Aluminium as the 1D solvers take it (P-wave modulus as Young's modulus).
fn medium() -> Material {
    Material {
        youngs_modulus: ALUMINIUM.density * ALUMINIUM.p_speed * ALUMINIUM.p_speed,
        density: ALUMINIUM.density,
        shear_modulus: Some(ALUMINIUM.mu()),
    }
}

fn settings() -> HalfSpaceSettings {
    HalfSpaceSettings {
        samples_per_period: 4000,
        tail_periods: Some(2.0),
        summary_only: false,
    }
}

/// The P-wave reduction of `law` under a 2-cycle 1 MHz burst of `amplitude` Pa, at the
/// element sizes `sizes` (P wavelengths, order 4).
pub fn p_reduction(law: SharedLaw, amplitude: f64, sizes: &[f64]) -> Result<Vec<Reduction>> {
    let signal = burst(amplitude, 1e6, 2.0);
    let normal: Arc<ContactLaw> = law.normal.clone();
    let ex = HalfSpace::new(medium(), Some(medium()), normal, signal.clone()).solve(&settings())?;
    reduction(
        WaveType::PSv,
        Incidence::P,
        law,
        signal,
        &Exact1d {
            t: &ex.t,
            gap: &ex.gap,
            stress: &ex.contact_stress,
            reflected: &ex.reflected_stress,
            transmitted: &ex.transmitted_stress,
        },
        sizes,
    )
}

/// The SH reduction of `law` (Coulomb or full RCCM) under a 2-cycle 1 MHz shear burst of
/// `amplitude` Pa against the coupled exact solver (no normal wave), at `sizes` (S
/// wavelengths, order 4).
pub fn sh_reduction(law: SharedLaw, amplitude: f64, sizes: &[f64]) -> Result<Vec<Reduction>> {
    use crate::solver::coupled::{CoupledHalfSpace, CoupledSolver};
    use crate::solver::Solver;
    let signal = burst(amplitude, 1e6, 2.0);
    let zt = ALUMINIUM.density * ALUMINIUM.s_speed;
    let problem = CoupledHalfSpace {
        normal: HalfSpace::new(
            medium(),
            Some(medium()),
            law.normal.clone(),
            burst(0.0, 1e6, 2.0),
        ),
        z1t: zt,
        z2t: zt,
        tangential: law.tangential.clone(),
        shear_incident: signal.clone(),
        oblique: None,
    };
    let ex = CoupledSolver {
        settings: settings(),
    }
    .solve(&problem)?;
    let sh = &ex.shear;
    reduction(
        WaveType::Sh,
        Incidence::Sh,
        law,
        signal,
        &Exact1d {
            t: &sh.t,
            gap: &sh.gap,
            stress: &sh.contact_stress,
            reflected: &sh.reflected_stress,
            transmitted: &sh.transmitted_stress,
        },
        sizes,
    )
}

const FREE: &str = "law = \"free\"";

/// One law of the reduction: its name, the wave (P or SH), the burst's amplitude (Pa),
/// the law, and whether it is smooth (no impact, no stick-slip: second order expected).
pub struct ReductionCase {
    /// Short name (`signorini`, `linear`, `power`, `quadratic`, `rccm`, `coulomb`,
    /// `full rccm`).
    pub name: &'static str,
    /// SH wave against the coupled solver (else P against the half-space solver).
    pub sh: bool,
    /// Burst amplitude, Pa.
    pub amplitude: f64,
    /// The interface's law.
    pub law: SharedLaw,
    /// No impacts or stick-slip: second order expected.
    pub smooth: bool,
    /// What the row's name says of the law.
    pub label: &'static str,
}

impl ReductionCase {
    /// Its errors at `sizes` (wavelengths).
    pub fn run(&self, sizes: &[f64]) -> Result<Vec<Reduction>> {
        if self.sh {
            sh_reduction(self.law.clone(), self.amplitude, sizes)
        } else {
            p_reduction(self.law.clone(), self.amplitude, sizes)
        }
    }
}

/// Every law of table 15.8-2.
pub fn cases() -> Result<Vec<ReductionCase>> {
    let case = |name, sh, amplitude, law, smooth, label| ReductionCase {
        name,
        sh,
        amplitude,
        law,
        smooth,
        label,
    };
    Ok(vec![
        case(
            "linear",
            false,
            1e6,
            law(
                1e6,
                "law = \"linear\"\nstiffness = 1e14",
                "law = \"linear\"\nstiffness = 1e14",
                FREE,
            )?,
            true,
            "P, linear spring K = 1e14 Pa/m, p0 1 MPa, 1 MPa",
        ),
        case(
            "power",
            false,
            1e6,
            law(1e6, "law = \"power\"\nc = 1.81e10\nm = 0.35", FREE, FREE)?,
            true,
            "P, power law C = 1.81e10, m = 0.35, p0 1 MPa, 1 MPa",
        ),
        case(
            "quadratic",
            false,
            1e6,
            law(1e6, "law = \"quadratic\"\nk0 = 1e14\nk1 = 1e21", FREE, FREE)?,
            true,
            "P, quadratic K0 = 1e14, K1 = 1e21, p0 1 MPa, 1 MPa",
        ),
        case(
            "signorini",
            false,
            1e6,
            law(0.3e6, "law = \"rigid\"", FREE, FREE)?,
            false,
            "P, Signorini, p0 0.3 MPa, 1 MPa",
        ),
        case(
            "rccm",
            false,
            3e6,
            law(
                0.3e6,
                "law = \"rigid\"",
                "law = \"rccm\"\nstiffness = 2e13\nenergy = 0.01\nviscosity = 1e-8",
                FREE,
            )?,
            false,
            "P, RCCM with damage, p0 0.3 MPa, 3 MPa",
        ),
        case(
            "coulomb",
            true,
            1e6,
            law(
                1e6,
                "law = \"rigid\"",
                FREE,
                "law = \"coulomb\"\nfriction = 0.3",
            )?,
            false,
            "SH, Coulomb mu 0.3, p0 1 MPa, 1 MPa",
        ),
        case(
            "full rccm",
            true,
            1e6,
            law(
                1e6,
                "law = \"rigid\"",
                "law = \"rccm\"\nstiffness = 2e13\nenergy = 0.1\nviscosity = 1e-8",
                "law = \"rccm\"\nstiffness = 2e13\nfriction = 0.3",
            )?,
            false,
            "SH, full RCCM (C_T 2e13, mu 0.3), p0 1 MPa, 1 MPa",
        ),
    ])
}

/// The element sizes of the validate rows, wavelengths (4, 8 and 16 order-4 elements per
/// wavelength; every law at all three takes about 5 s).
pub const ROW_SIZES: [f64; 3] = [0.25, 0.125, 0.0625];

/// The validate rows of every law: the gap error at 4, 8 and 16 elements per wavelength,
/// the observed orders between them, and the reflected and transmitted A2/A1 at 16
/// against the exact ratio. Smooth laws: gap within 1e-2, 2e-3 and 1e-3, order 2 within
/// 0.4; laws with impacts or stick-slip (first order expected, table 15.8-2): within 0.1,
/// 0.05 and 0.03, order at least 0.5 (one-sided: [`ValidationCase::at_least`]); A2/A1
/// within 0.01 of the exact ratio (absolute).
pub fn run_rows() -> Result<Vec<ValidationCase>> {
    let mut v = Vec::new();
    let per = |k: usize| (1.0 / ROW_SIZES[k]).round();
    for c in cases()? {
        let r = c.run(&ROW_SIZES)?;
        let tol = if c.smooth {
            [1e-2, 2e-3, 1e-3]
        } else {
            [0.1, 0.05, 0.03]
        };
        for (k, &t) in tol.iter().enumerate() {
            v.push(ValidationCase::new(
                format!(
                    "2D 1D reduction, {}: max gap error / max gap, {} el./wavelength",
                    c.label,
                    per(k)
                ),
                0.0,
                r[k].gap,
                t,
            ));
        }
        let gaps: Vec<f64> = r.iter().map(|x| x.gap).collect();
        for (k, order) in orders(&gaps).into_iter().enumerate() {
            let name = format!(
                "2D 1D reduction, {}: observed order of the gap error, {} to {} el./wavelength",
                c.label,
                per(k),
                per(k + 1)
            );
            v.push(if c.smooth {
                ValidationCase::new(name, 2.0, order, 0.2)
            } else {
                // impacts and stick-slip: first order expected, at least 0.5 checked
                ValidationCase::at_least(
                    name + " (at least first order, within 0.5)",
                    1.0,
                    order,
                    0.5,
                )
            });
        }
        let last = r[r.len() - 1];
        for (what, got) in [
            ("reflected", last.reflected_ratio),
            ("transmitted", last.transmitted_ratio),
        ] {
            v.push(ValidationCase::new(
                format!(
                    "2D 1D reduction, {}: {what} A2/A1, |2D - exact|, {} el./wavelength",
                    c.label,
                    per(ROW_SIZES.len() - 1)
                ),
                0.0,
                got,
                0.01,
            ));
        }
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(name: &str, r: &[Reduction]) {
        let col = |f: fn(&Reduction) -> f64| r.iter().map(f).collect::<Vec<f64>>();
        for (what, v) in [
            ("gap", col(|x| x.gap)),
            ("stress", col(|x| x.stress)),
            ("stress rms", col(|x| x.stress_rms)),
            ("reflected A1", col(|x| x.reflected_a1)),
            ("reflected A2/A1", col(|x| x.reflected_ratio)),
            ("transmitted A1", col(|x| x.transmitted_a1)),
            ("transmitted A2/A1", col(|x| x.transmitted_ratio)),
        ] {
            let e: Vec<String> = v.iter().map(|x| format!("{x:.2e}")).collect();
            let o: Vec<String> = orders(&v).iter().map(|x| format!("{x:.2}")).collect();
            eprintln!("{name}: {what} errors {e:?}, orders {o:?}");
        }
        eprintln!(
            "{name}: exact A2/A1 (reflected, transmitted) {:?}",
            r[0].exact_ratio
        );
    }

    /// The assertions of a reduction at 2, 4, 8 and 16 elements per wavelength: a smooth law
    /// (no impact) converges at second order in gap, stress and A1 (each halving divides the
    /// error by more than 3) and reaches 2e-3; a law whose faces open and close (impacts,
    /// stick-slip) converges at about first order: gap error below 5% and A1 within 2%, A2/A1
    /// within 0.01, at 16 elements per wavelength, the gap error falling by 4 over the range.
    fn check(name: &str, r: &[Reduction], smooth: bool) {
        let last = r.last().unwrap();
        let first = r[0];
        if smooth {
            for (what, v) in [
                ("gap", r.iter().map(|x| x.gap).collect::<Vec<_>>()),
                ("stress", r.iter().map(|x| x.stress).collect()),
                ("reflected A1", r.iter().map(|x| x.reflected_a1).collect()),
            ] {
                assert!(*v.last().unwrap() < 2e-3, "{name} {what}: {v:?}");
                for w in v.windows(2) {
                    assert!(w[1] < w[0] / 3.0, "{name} {what}: {v:?}");
                }
            }
            assert!(last.transmitted_a1 < 2e-3, "{name}: {last:?}");
        } else {
            assert!(
                last.gap < 0.05 && last.gap < 0.25 * first.gap,
                "{name}: {r:?}"
            );
            assert!(last.stress_rms < 0.5 * first.stress_rms, "{name}: {r:?}");
        }
        for x in [last.reflected_a1, last.transmitted_a1] {
            assert!(x < 0.02, "{name}: {last:?}");
        }
        for x in [last.reflected_ratio, last.transmitted_ratio] {
            assert!(x < 0.01, "{name}: {last:?}");
        }
    }

    /// Every law of table 15.8-2 at 2, 4, 8 and 16 elements per wavelength (order 4): a
    /// full-width interface under a plane P wave (Signorini, linear, power law, quadratic,
    /// RCCM with damage; the exact half-space solver) or SH wave (Coulomb, full RCCM; the
    /// coupled exact solver) reproduces the 1D solution: gap, contact stress, reflected
    /// and transmitted A1 and A2/A1.
    #[test]
    fn plane_wave_reduction_every_law() {
        let sizes = [0.5, 0.25, 0.125, 0.0625];
        for c in cases().unwrap() {
            let r = c.run(&sizes).unwrap();
            report(c.name, &r);
            check(c.name, &r, c.smooth);
        }
    }
}

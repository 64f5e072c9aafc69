//! Validation cases of the 2D solver's plane waves (docs/model.md section 15.8): oblique P
//! and SV waves, injected by total-field/scattered-field, on a linear spring interface
//! across a wide rectangle with absorbing sides, against the closed-form reflection and
//! transmission coefficients of model.md section 14 (mode conversion included).

use super::{ValidationCase, ALUMINIUM};
use crate::analytic::oblique::{self, coefficients, Bond, Geometry};
use crate::error::{Error, Result};
use crate::excitation::{Excitation, ToneBurst, Window};
use crate::law::point::SharedLaw;
use crate::law::registry::{build_law, build_tangential};
use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use crate::solver::solid_2d::{
    Crack, Incidence, Layer, Side, Solid2d, Source, SourceKind, WaveType,
};
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;
use std::sync::Arc;

const F0: f64 = 1e6;

/// The largest |measured - closed form| of a coefficient the validation rows allow at
/// 1.5 mm elements.
const ABSOLUTE: f64 = 3e-3;

/// The measured magnitudes `|R_P|, |R_SV|, |T_P|, |T_SV|` (particle velocity per unit
/// incident particle velocity, at f0 = 1 MHz) of a 2-cycle Hann burst of `incidence` (P or
/// SV) at `deg` degrees on a linear spring interface (K_N = 1e14, K_T = 0.5e14 Pa/m) in
/// aluminium, with elements of `h` m (order 4), and the closed form's.
pub fn oblique_case(incidence: Incidence, deg: f64, h: f64) -> Result<([f64; 4], [f64; 4])> {
    oblique_run(incidence, deg, h, true).map(|r| (r.0, r.1))
}

/// [`oblique_case`], with the interface or without it (`interface` false: then the third
/// value is the largest velocity at the reflected waves' receiver, in the scattered
/// region, over the incident wave's peak velocity: the injection's leakage at an angle).
fn oblique_run(
    incidence: Incidence,
    deg: f64,
    h: f64,
    interface: bool,
) -> Result<([f64; 4], [f64; 4], f64)> {
    let (kn, kt) = (1e14, 0.5e14);
    let p0 = 50e6;
    let file = "<validation>";
    let spec = |s: &str| -> Result<(CompressionSpec, TractionSpec, TangentialSpec)> {
        let bad = |e: toml::de::Error| Error::invalid(file, "law", e.to_string(), "a law table");
        Ok((
            toml::from_str(&format!("law = \"linear\"\nstiffness = {s}")).map_err(bad)?,
            toml::from_str(&format!("law = \"linear\"\nstiffness = {s}")).map_err(bad)?,
            toml::from_str(&format!("law = \"linear\"\nstiffness = {kt:e}")).map_err(bad)?,
        ))
    };
    let (c, t, b) = spec(&format!("{kn:e}"))?;
    let normal = build_law(p0, &c, &t, file, "crack")?;
    let tangential = build_tangential(&b, 0.0, &normal, file, "crack")?;
    let law = SharedLaw {
        normal: Arc::new(normal),
        tangential: Arc::new(tangential),
    };
    let angle = deg.to_radians();
    let signal: Arc<dyn Excitation> = Arc::new(ToneBurst::new(1e6, F0, 2.0, Window::Hann));
    let burst = signal.duration();
    // layout (m): the reflected waves' receiver, the TF/SF line, the interface, the
    // transmitted waves' receiver; each receiver 12 mm from the absorbing top or bottom so
    // that their echoes come after the window, x_r = 120 mm from the left end so that the
    // waves of the line's end come after it too
    let (z_r, z_line, z_c, z_t, depth) = (12e-3, 14e-3, 16e-3, 20e-3, 32e-3);
    let (width, x_r) = (200e-3, 120e-3);
    let m = oblique::Elastic {
        density: ALUMINIUM.density,
        cp: ALUMINIUM.p_speed,
        cs: ALUMINIUM.s_speed,
    };
    let wave = match incidence {
        Incidence::P => oblique::WaveType::P,
        _ => oblique::WaveType::Sv,
    };
    let g = Geometry::new(&m, Some(&m), wave, angle).map_err(|c| {
        Error::invalid(
            file,
            "source.angle",
            deg,
            format!("below the critical angle {:.1} degrees", c.angle_deg),
        )
    })?;
    let eta_s = g.reflected[1].angle.cos() / ALUMINIUM.s_speed;
    let problem = |duration: f64| Solid2d {
        width,
        layers: vec![Layer {
            bottom: depth,
            material: ALUMINIUM,
        }],
        wave: WaveType::PSv,
        top: Side::Absorbing,
        bottom: Side::Absorbing,
        sides: Side::Absorbing,
        element_size: h,
        pml: crate::solver::solid_2d::Pml::elements(
            crate::solver::solid_2d::pml::DEFAULT_ELEMENTS,
            h,
        ),
        order: 4,
        courant: 0.8,
        max_time_step: f64::INFINITY,
        cracks: if interface {
            vec![Crack {
                start: [0.0, z_c],
                end: [width, z_c],
                full_width: false,
                law: law.clone(),
                profile: None,
            }]
        } else {
            vec![]
        },
        sources: vec![Source {
            kind: SourceKind::PlaneWave {
                incidence,
                angle,
                z: z_line,
            },
            signal: signal.clone(),
        }],
        receivers: vec![[x_r, z_r], [x_r, z_t]],
        duration,
        crack_every: 100_000,
    };
    // the windows: the slowest outgoing wave (SV) past each receiver, and a margin
    let probe = problem(1e-9).plan(file)?;
    let tau = probe.plane_waves[0].delay_at([x_r, z_c]);
    let windows = [
        tau + (z_c - z_r) * eta_s + burst + 0.25 / F0,
        tau + (z_t - z_c) * eta_s + burst + 0.25 / F0,
    ];
    let out = problem(windows[0].max(windows[1])).plan(file)?.run()?;
    let w = 2.0 * PI * F0;
    let ft = |x: &[f64], t_end: f64| {
        let mut s = Complex64::new(0.0, 0.0);
        for (&t, &v) in out.time.iter().zip(x) {
            if t <= t_end {
                s += v * Complex64::from_polar(out.dt, -w * t);
            }
        }
        s
    };
    // the incident particle velocity -s / (rho c) at its origin
    let c_inc = if incidence == Incidence::P {
        ALUMINIUM.p_speed
    } else {
        ALUMINIUM.s_speed
    };
    let n_inc = 4000;
    let dt_inc = burst / n_inc as f64;
    let mut w_inc = Complex64::new(0.0, 0.0);
    for k in 0..n_inc {
        let t = (k as f64 + 0.5) * dt_inc;
        w_inc +=
            -signal.stress(t) / (ALUMINIUM.density * c_inc) * Complex64::from_polar(dt_inc, -w * t);
    }
    // each receiver's (v_x, v_z) as the sum of a P and an SV wave of known polarisations
    let split = |r: usize, pair: &[oblique::PlaneWave; 2]| -> [f64; 2] {
        let (vx, vz) = (
            ft(out.trace(r, 0), windows[r]),
            ft(out.trace(r, 1), windows[r]),
        );
        // polarisation [normal = z, tangential = x]
        let (px, pz) = (pair[0].polarisation[1], pair[0].polarisation[0]);
        let (sx, sz) = (pair[1].polarisation[1], pair[1].polarisation[0]);
        let det = px * sz - sx * pz;
        let a_p = (vx * sz - sx * vz) / det;
        let a_s = (px * vz - vx * pz) / det;
        [a_p.norm() / w_inc.norm(), a_s.norm() / w_inc.norm()]
    };
    let transmitted = g
        .transmitted
        .ok_or_else(|| Error::invalid(file, "counterpart", "rigid", "a transmitting medium"))?;
    let [rp, rs] = split(0, &g.reflected);
    let [tp, ts] = split(1, &transmitted);
    let exact = coefficients(
        &g,
        Bond::Springs {
            normal: kn,
            tangential: kt,
        },
        w,
    );
    let mut leak = 0.0f64;
    for (k, &t) in out.time.iter().enumerate() {
        if t <= windows[0] {
            leak = leak.max(out.trace(0, 0)[k].hypot(out.trace(0, 1)[k]));
        }
    }
    let peak = signal.peak() / (ALUMINIUM.density * c_inc);
    Ok((
        [rp, rs, tp, ts],
        [
            exact[0].norm(),
            exact[1].norm(),
            exact[2].norm(),
            exact[3].norm(),
        ],
        leak / peak,
    ))
}

/// The cases: P at 40 degrees, SV at 20 degrees (below SV's critical angle for P, 29.7
/// degrees), 1.5 mm elements (two per S wavelength at f0): every coefficient within 0.003
/// of the closed form's (the largest error measured there is 1.7e-3, model.md table
/// 15.8-4).
pub fn run_all() -> Result<Vec<ValidationCase>> {
    let mut v = Vec::new();
    for (inc, deg) in [(Incidence::P, 40.0), (Incidence::Sv, 20.0)] {
        let (m, e) = oblique_case(inc, deg, 1.5e-3)?;
        let label = if inc == Incidence::P { "P" } else { "SV" };
        for (k, name) in ["R_P", "R_SV", "T_P", "T_SV"].iter().enumerate() {
            v.push(ValidationCase::new(
                format!(
                    "2D plane wave (TF/SF), {label} {deg} deg on linear springs: |{name}| vs closed form"
                ),
                e[k],
                m[k],
                // absolute: |measured - exact| <= ABSOLUTE
                ABSOLUTE / e[k].max(1e-3),
            ));
        }
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oblique P and SV plane waves on a linear spring interface: the 2D solver's reflected
    /// and transmitted P and SV magnitudes (mode conversion) against the closed form,
    /// within 0.003 at 1.5 mm elements (two per S wavelength at f0), and closer at 1 mm.
    #[test]
    #[ignore = "slow: full tier"]
    fn oblique_plane_waves_match_the_closed_form() {
        for (inc, deg) in [(Incidence::P, 40.0), (Incidence::Sv, 20.0)] {
            let mut errs = Vec::new();
            for h in [1.5e-3, 1e-3] {
                let (m, e) = oblique_case(inc, deg, h).unwrap();
                let err = (0..4).map(|k| (m[k] - e[k]).abs()).fold(0.0, f64::max);
                eprintln!(
                    "{inc:?} {deg} deg, h {h}: measured {m:?}, closed form {e:?}, max error {err:.2e}"
                );
                errs.push(err);
            }
            assert!(errs[0] < ABSOLUTE, "{inc:?} {deg}: {errs:?}");
            // without the interface the scattered region stays quiet at an angle too
            let (_, _, leak) = oblique_run(inc, deg, 1.5e-3, false).unwrap();
            let db = 20.0 * leak.log10();
            eprintln!("{inc:?} {deg} deg, h 1.5 mm: leakage {db:.1} dB");
            assert!(db < -40.0, "{inc:?} {deg}: {db} dB");
            assert!(errs[1] < errs[0], "{inc:?} {deg}: {errs:?}");
        }
    }
}

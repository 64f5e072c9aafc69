//! A Rayleigh wave at a closed surface-breaking crack: the transmitted second-harmonic
//! efficiency against the crack's depth (Yuan et al., "Numerical simulation of Rayleigh
//! wave interaction with surface closed cracks under external pressure", Wave Motion,
//! 2015: hard contact with Coulomb friction; the efficiency rises sharply with the depth
//! and falls slightly beyond about a quarter of the Rayleigh wavelength).
//!
//! An aluminium half-space (absorbing sides and bottom, free top), a 1 MHz 5-cycle Hann
//! burst of normal traction from a transducer half a Rayleigh wavelength wide on the
//! surface, a vertical crack open to the surface (docs/model.md 15.2) 17.25 mm away (about
//! six Rayleigh wavelengths: the Rayleigh wave has left the bulk waves behind), held shut by
//! a closure p0 (Signorini in the normal direction, Coulomb friction), and a receiver on
//! the surface 14 mm beyond it, gated to the Rayleigh burst and analysed by pulse
//! inversion (the linear waves cancel in the even part): the transmitted efficiency
//! `beta* = A2 / A1^2` of the vertical velocity against the depth d / lambda_R. The top
//! rows of elements are as thick as the depth step, so every crack ends on an element edge
//! of the same mesh.

use super::super::{argmax_refined, column, finding, fmt_value, panel, Figure, Finding};
use super::{summaries, Cost, Resolution, CYCLES, F0};
use crate::analytic::guided::{rayleigh_speed, Speeds};
use crate::error::Result;
use crate::output::plot::Series;
use crate::reproduce::Ctx;

/// Aluminium: density (kg/m^3), c_P and c_S (m/s).
const RHO: f64 = 2700.0;
const C_P: f64 = 6320.0;
const C_S: f64 = 3130.0;
/// The transducer's aperture on the top surface, m.
const X_SOURCE: [f64; 2] = [2e-3, 3.5e-3];
/// The crack's x, m.
const X_CRACK: f64 = 20e-3;
/// The receiver beyond the crack, m.
const X_BEYOND: f64 = 34e-3;
/// Width of the rectangle, m.
const WIDTH: f64 = 40e-3;
/// Depth of the rectangle, Rayleigh wavelengths.
const DEPTH: f64 = 3.0;
/// Depth of the finely meshed rows, Rayleigh wavelengths.
const FINE: f64 = 1.2;
/// Transducer traction amplitude, Pa.
pub(super) const AMPLITUDE: f64 = 10e6;
/// Closure of the crack, Pa.
pub(super) const P0: f64 = 1e6;
/// Coulomb friction coefficient.
pub(super) const FRICTION: f64 = 0.5;
/// The published depth of the largest efficiency, Rayleigh wavelengths, and the tolerance
/// of the verdict.
const PUBLISHED_PEAK: f64 = 0.25;
const PEAK_TOLERANCE: f64 = 0.1;

/// The Rayleigh speed, m/s.
pub(super) fn c_r() -> f64 {
    rayleigh_speed(Speeds { p: C_P, s: C_S }).unwrap_or(f64::NAN)
}

/// The Rayleigh wavelength at f0, m.
pub(super) fn lambda_r() -> f64 {
    c_r() / F0
}

/// Depth steps per Rayleigh wavelength.
fn steps(res: Resolution) -> usize {
    if res.quick {
        10
    } else {
        20
    }
}

/// The crack depths, Rayleigh wavelengths: every step from one to one wavelength.
pub(super) fn depths(res: Resolution) -> Vec<f64> {
    let n = steps(res);
    (1..=n).map(|k| k as f64 / n as f64).collect()
}

/// The scenario: a crack `depth` Rayleigh wavelengths deep (`None`: no crack), rounded to
/// the depth step, with closure `p0` (Pa) and Coulomb `friction` (1 GPa with friction 1
/// keeps it bonded: the welded limit).
pub(super) fn text(res: Resolution, depth: Option<f64>, p0: f64, friction: f64) -> String {
    let lr = lambda_r();
    let n = steps(res);
    let delta = lr / n as f64;
    let fine = (FINE * n as f64).round() as usize;
    let mut layers = String::new();
    let material = format!("p_speed = {C_P:e}\ns_speed = {C_S:e}\ndensity = {RHO:e}\n");
    for _ in 0..fine {
        layers.push_str(&format!("[[layer]]\nthickness = {delta:e}\n{material}"));
    }
    layers.push_str(&format!(
        "[[layer]]\nthickness = {:e}\n{material}",
        DEPTH * lr - fine as f64 * delta
    ));
    let crack = match depth {
        None => String::new(),
        Some(d) => {
            let k = (d * n as f64).round();
            format!(
                "[[crack]]\nstart = [{X_CRACK:e}, 0.0]\nend = [{X_CRACK:e}, {:e}]\n\
                 static_pressure = {p0:e}\ncompression = {{ law = \"rigid\" }}\n\
                 traction = {{ law = \"free\" }}\n\
                 tangential = {{ law = \"coulomb\", friction = {friction} }}\n",
                k * delta
            )
        }
    };
    let period = 1.0 / F0;
    let arrival = (X_BEYOND - 0.5 * (X_SOURCE[0] + X_SOURCE[1])) / c_r();
    let gate = (arrival - 0.5 * period, arrival + (CYCLES + 1.0) * period);
    format!(
        "[model]\nkind = \"solid_2d\"\nwave = \"p_sv\"\nwidth = {WIDTH:e}\nduration = {:e}\n\
         element_size = {:e}\norder = 4\nharmonic = {}\ntop = \"free\"\nbottom = \"absorbing\"\n\
         sides = \"absorbing\"\ncrack_every = 100\n{layers}{crack}\
         [[source]]\nkind = \"transducer\"\nx0 = {:e}\nx1 = {:e}\ncomponent = \"normal\"\n\
         signal = {{ frequency = {F0:e}, cycles = {CYCLES}, amplitude = {AMPLITUDE:e}, window = \"hann\" }}\n\
         [[receiver]]\nname = \"beyond\"\nat = [{X_BEYOND:e}, 0.0]\n\
         [analysis]\nmethod = \"band_peak\"\ngate = [{:e}, {:e}]\ntaper = {:e}\n",
        gate.1 + 0.1 * period,
        res.element(),
        res.harmonic(),
        X_SOURCE[0],
        X_SOURCE[1],
        gate.0,
        gate.1,
        0.5 * period,
    )
}

/// The closures of the two curves, Pa: hard contact without external pressure (the
/// published case) and under [`P0`].
const CLOSURES: [f64; 2] = [0.0, P0];

/// Run the study: its figure and findings are appended to the chapter's.
pub(crate) fn run(
    ctx: &Ctx,
    res: Resolution,
    figures: &mut Vec<Figure>,
    findings: &mut Vec<Finding>,
) -> Result<()> {
    let cost = Cost::start(ctx);
    let ds = depths(res);
    let mut texts = vec![text(res, None, 0.0, FRICTION)];
    for p0 in CLOSURES {
        texts.extend(ds.iter().map(|d| text(res, Some(*d), p0, FRICTION)));
    }
    let s = summaries(
        ctx,
        "finite crack: Rayleigh wave at a surface-breaking crack",
        &texts,
    )?;
    let a1_inc = s[0].get("beyond_A1").unwrap_or(f64::NAN);
    let floor = s[0].get("beyond_A2").unwrap_or(f64::NAN);
    let n = ds.len();
    let curve = |i: usize, key: &str| column(&s[1 + i * n..1 + (i + 1) * n], key);
    let eff: Vec<Vec<f64>> = (0..2)
        .map(|i| {
            curve(i, "beyond_A2")
                .iter()
                .map(|a2| a2 / (a1_inc * a1_inc))
                .collect()
        })
        .collect();
    let trans: Vec<Vec<f64>> = (0..2)
        .map(|i| curve(i, "beyond_A1").iter().map(|a| a / a1_inc).collect())
        .collect();
    let ratio: Vec<Vec<f64>> = (0..2).map(|i| curve(i, "beyond_A2_over_A1")).collect();
    let closure = column(&s, "energy_closure_error")
        .iter()
        .fold(0.0f64, |m, e| m.max(e.abs()));
    let peak: Vec<f64> = eff.iter().map(|e| argmax_refined(&ds, e)).collect();
    let top = |e: &[f64]| e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let label = |p0: f64| {
        if p0 == 0.0 {
            "no closure (p0 = 0)".to_string()
        } else {
            format!("p0 = {} MPa", fmt_value(p0 * 1e-6))
        }
    };
    let xl = "crack depth / Rayleigh wavelength";
    let lr = lambda_r();
    let mut fig = Figure::new(
        "finite_crack_rayleigh",
        "Second harmonic of a Rayleigh wave transmitted past a closed surface-breaking crack \
         against its depth",
        format!(
            "Beyond the thesis; after Yuan et al. (Wave Motion, 2015). Aluminium (rho = {RHO} \
             kg/m^3, c_P = {C_P} m/s, c_S = {C_S} m/s: c_R = {} m/s, lambda_R = {} mm at 1 MHz), \
             a half-space of {DEPTH} lambda_R with absorbing sides and bottom; a 1 MHz \
             {CYCLES}-cycle Hann burst of {} MPa normal traction from a transducer on the \
             surface at x = {}-{} mm; a vertical crack open to the surface at x = {} mm, d = \
             {} to 1 lambda_R deep in steps of lambda_R / {} (the top {FINE} lambda_R meshed in \
             rows of that height), hard contact (Signorini) with Coulomb friction mu = \
             {FRICTION}, without closure and under p0 = {} MPa; the receiver on the surface at \
             x = {} mm, its vertical velocity gated to the Rayleigh burst (band peak). (a) the \
             transmitted second-harmonic efficiency A2 / A1,inc^2, A1,inc the fundamental at \
             the receiver without a crack; (b) the transmission A1 / A1,inc and the \
             transmitted A2/A1. Element size {} mm (order 4). Resolution: {}.",
            fmt_value(c_r()),
            fmt_value(lr * 1e3),
            AMPLITUDE * 1e-6,
            X_SOURCE[0] * 1e3,
            X_SOURCE[1] * 1e3,
            X_CRACK * 1e3,
            fmt_value(ds[0]),
            steps(res),
            P0 * 1e-6,
            X_BEYOND * 1e3,
            fmt_value(res.element() * 1e3),
            res.name()
        ),
        vec![
            panel(
                "(a) transmitted second-harmonic efficiency",
                xl,
                "A2 / A1,inc^2 (s/m)",
                CLOSURES
                    .iter()
                    .zip(&eff)
                    .map(|(p0, e)| Series::new(label(*p0), &ds, e))
                    .collect(),
            ),
            panel(
                "(b) transmission and transmitted A2/A1",
                xl,
                "ratio",
                CLOSURES
                    .iter()
                    .enumerate()
                    .flat_map(|(i, p0)| {
                        [
                            Series::new(format!("A1 / A1,inc, {}", label(*p0)), &ds, &trans[i]),
                            Series::new(format!("A2 / A1, {}", label(*p0)), &ds, &ratio[i]),
                        ]
                    })
                    .collect(),
            ),
        ],
    );
    fig = fig.compare(format!(
        "Yuan et al.: the efficiency rises sharply with the depth and falls slightly beyond \
         about lambda_R / 4 / here: its largest at d = {} lambda_R without closure ({} s/m), {} \
         lambda_R under {} MPa ({} s/m); at 1 lambda_R {} and {} of the largest",
        fmt_value(peak[0]),
        fmt_value(top(&eff[0])),
        fmt_value(peak[1]),
        P0 * 1e-6,
        fmt_value(top(&eff[1])),
        fmt_value(eff[0][n - 1] / top(&eff[0])),
        fmt_value(eff[1][n - 1] / top(&eff[1])),
    ));
    fig = fig.compare(cost.line(ctx, res));
    figures.push(fig);

    let statement = "Yuan et al. (Wave Motion, 2015): the transmitted second-harmonic \
                     efficiency of a Rayleigh wave at a closed surface-breaking crack (hard \
                     contact, Coulomb friction) rises sharply with the crack depth and falls \
                     slightly once the depth reaches about a quarter of the Rayleigh wavelength";
    let mut f = finding(
        "finite_crack_rayleigh_peak_depth",
        peak[0],
        "lambda_R",
        statement,
        Some((peak[0] - PUBLISHED_PEAK).abs() <= PEAK_TOLERANCE),
    );
    f.note = format!(
        "depth of the largest A2 / A1,inc^2 without closure (parabola through the largest \
         sample and its neighbours; steps of lambda_R / {}), against {PUBLISHED_PEAK} \
         lambda_R within {PEAK_TOLERANCE}; their mesh, frequency and source differ",
        steps(res)
    );
    let rise = top(&eff[0]) / eff[0][0];
    let fall = eff[0][n - 1] / top(&eff[0]);
    let mut g = finding(
        "finite_crack_rayleigh_rise_from_shallowest",
        rise,
        "",
        "(not in the thesis) the largest efficiency without closure over that at the \
         shallowest depth",
        None,
    );
    g.note = format!("shallowest depth {} lambda_R", fmt_value(ds[0]));
    let mut h = finding(
        "finite_crack_rayleigh_deepest_over_peak",
        fall,
        "",
        statement,
        Some(fall < 1.0 && fall > 0.5),
    );
    h.note = "the efficiency at 1 lambda_R over the largest, without closure: agrees when it \
              falls (below 1) but by less than half"
        .into();
    findings.extend([
        f,
        g,
        h,
        finding(
            "finite_crack_rayleigh_peak_depth_under_closure",
            peak[1],
            "lambda_R",
            "(not in the thesis) depth of the largest efficiency under the closure p0 = 1 MPa \
             (the closure governs the harmonic generation)",
            None,
        ),
        finding(
            "finite_crack_rayleigh_floor_over_shallowest_a2",
            floor / curve(0, "beyond_A2")[0],
            "",
            "(not in the thesis) A2 at the receiver without a crack (the burst's own second \
             harmonic and the bulk waves in the gate) over the transmitted A2 of the \
             shallowest crack",
            None,
        ),
        finding(
            "finite_crack_rayleigh_energy_closure_error",
            closure,
            "",
            "(not in the thesis) energy audit of the 2D runs (model.md eq. 15.5)",
            Some(closure < 1e-9),
        ),
    ]);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::summaries;
    use super::*;
    use std::sync::atomic::AtomicUsize;

    /// A bonded surface-breaking crack (1 GPa closure, sticking friction) generates no
    /// second harmonic: its transmitted A2 is the receiver's without a crack (the burst's
    /// own and the bulk waves', within 1 %); a crack without closure generates one far
    /// above it, larger at 0.3 lambda_R than at 0.1 (the efficiency rises from the
    /// shallowest depth). Four runs at `--quick`, about 6 s of CPU.
    #[test]
    fn a_bonded_crack_makes_no_second_harmonic_and_depth_raises_it() {
        let ctx = Ctx {
            progress: &|_, _, _| {},
            runs: AtomicUsize::new(0),
        };
        let res = Resolution { quick: true };
        let texts = [
            text(res, None, 0.0, FRICTION),
            text(res, Some(0.3), 1e9, 1.0),
            text(res, Some(0.1), 0.0, FRICTION),
            text(res, Some(0.3), 0.0, FRICTION),
        ];
        let s = summaries(&ctx, "test", &texts).unwrap();
        let a2 = column(&s, "beyond_A2");
        let a1 = column(&s, "beyond_A1");
        eprintln!("A2 {a2:?}, A1 {a1:?}");
        assert!((a2[1] / a2[0] - 1.0).abs() < 0.01, "{a2:?}");
        assert!((a1[1] / a1[0] - 1.0).abs() < 1e-3, "{a1:?}");
        assert!(a2[2] > 20.0 * a2[0], "{a2:?}");
        assert!(a2[3] > 1.5 * a2[2], "{a2:?}");
        for e in column(&s, "energy_closure_error") {
            assert!(e < 1e-9, "{e:e}");
        }
    }
}

//! An A0 Lamb wave on a closed delamination (a crack parallel to the plate's surfaces):
//! the reflected and transmitted second harmonic against the delamination's length, whose
//! peaks and dips mark the delaminated region's resonances (Ye, Biwa and Mori, JASA 148,
//! 2020: a closed delamination with a quadratic interface spring).
//!
//! A 2 mm aluminium plate with absorbing ends, a 500 kHz 5-cycle Hann burst of normal
//! traction from a 4 mm transducer on the top surface (fd = 1 MHz mm: mostly the A0 mode,
//! as `examples/solid_2d/lamb_delamination.toml`), a delamination 0.5 mm under the top
//! surface from x = 30 mm, held shut by a 1 MPa closure and a quadratic normal spring
//! (`sigma = -p0 + K0 [u] - K1 [u]^2`) with a linear tangential spring. The receivers
//! `before` (x = 20 mm, between the transducer and the delamination) and `beyond` (past its
//! longest length) on the top surface, analysed by pulse inversion: the linear waves
//! (the incident burst among them) cancel in the even part, so `before`'s A2 is the
//! reflected second harmonic alone and `beyond`'s the transmitted one.

use super::super::{finding, fmt_value, lin, panel, Figure, Finding, AMPLITUDE_FLOOR};
use super::{summaries, Cost, Resolution};
use crate::error::Result;
use crate::output::plot::Series;
use crate::reproduce::Ctx;

/// Plate thickness, m.
const THICKNESS: f64 = 2e-3;
/// Depth of the delamination, m.
const DEPTH: f64 = 0.5e-3;
/// Start of the delamination, m.
const X_START: f64 = 30e-3;
/// Longest delamination, m.
const L_MAX: f64 = 25e-3;
/// The `before` receiver, m.
const X_BEFORE: f64 = 20e-3;
/// Frequency, Hz.
const F0: f64 = 500e3;
/// Closure, Pa.
const P0: f64 = 1e6;
/// Quadratic spring: K0 (Pa/m), K1 (Pa/m^2, 0.9 of the largest the closure allows).
const K0: f64 = 1e14;
const K1: f64 = 0.9 * K0 * K0 / (4.0 * P0);
/// Tangential spring, Pa/m.
const KT: f64 = 0.5e14;
/// Transducer traction amplitude, Pa.
const AMPLITUDE: f64 = 5e6;
/// A0 phase velocity at fd = 1 MHz mm in aluminium (model.md 15.9), m/s.
const C_A0: f64 = 2336.0;

/// Delamination lengths, m: steps of 1 mm (`--quick`; a step of 2 mm aliases the maxima,
/// about 4 mm apart) or 0.5 mm.
fn lengths(res: Resolution) -> Vec<f64> {
    if res.quick {
        lin(1e-3, L_MAX, 25)
    } else {
        lin(1e-3, L_MAX, 49)
    }
}

/// Element size, m: the sub-laminate one element (order 4) thick, the plate four; the
/// second harmonic's Lamb wavelengths (fd = 2 MHz mm) span about five elements.
fn element(_res: Resolution) -> f64 {
    0.5e-3
}

/// The scenario for a delamination `length` long.
fn text(res: Resolution, length: f64) -> String {
    let width = X_START + L_MAX + 20e-3;
    let beyond = X_START + L_MAX + 10e-3;
    // the A0 burst to the far receiver and its reflection back to `before`, with margin
    let duration = 60e-6;
    format!(
        "[model]\nkind = \"solid_2d\"\nwave = \"p_sv\"\nwidth = {width:e}\nduration = {duration:e}\n\
         element_size = {:e}\norder = 4\nharmonic = {}\ntop = \"free\"\nbottom = \"free\"\nsides = \"absorbing\"\n\
         crack_every = 100\n\
         [[layer]]\nthickness = {THICKNESS:e}\nmaterial = \"aluminium\"\n\
         [[crack]]\nstart = [{X_START:e}, {DEPTH:e}]\nlength = {length:e}\nstatic_pressure = {P0:e}\n\
         compression = {{ law = \"quadratic\", k0 = {K0:e}, k1 = {K1:e} }}\n\
         traction = {{ law = \"free\" }}\ntangential = {{ law = \"linear\", stiffness = {KT:e} }}\n\
         [[source]]\nkind = \"transducer\"\nx0 = 8e-3\nx1 = 12e-3\ncomponent = \"normal\"\n\
         signal = {{ frequency = {F0:e}, cycles = 5, amplitude = {AMPLITUDE:e}, window = \"hann\" }}\n\
         [[receiver]]\nname = \"before\"\nat = [{X_BEFORE:e}, 0.0]\n\
         [[receiver]]\nname = \"beyond\"\nat = [{beyond:e}, 0.0]\n\
         [analysis]\nmethod = \"pulse_inversion\"\n",
        element(res),
        res.harmonic(),
    )
}

/// Indices of the interior local maxima of `y` that stand above both neighbouring minima
/// by more than `contrast` (relative to the maximum).
fn peaks(y: &[f64], contrast: f64) -> Vec<usize> {
    let mut out = Vec::new();
    for i in 1..y.len().saturating_sub(1) {
        if y[i] > y[i - 1] && y[i] >= y[i + 1] {
            // the lowest points between this maximum and its neighbouring higher points
            let lo = |r: &mut dyn Iterator<Item = f64>| {
                let mut m = y[i];
                for v in r {
                    if v > y[i] {
                        break;
                    }
                    m = m.min(v);
                }
                m
            };
            let dl = lo(&mut y[..i].iter().rev().copied());
            let dr = lo(&mut y[i + 1..].iter().copied());
            if y[i] - dl.max(dr) > contrast * y[i] {
                out.push(i);
            }
        }
    }
    out
}

/// Run the study: its figure and findings are appended to the chapter's.
pub(crate) fn run(
    ctx: &Ctx,
    res: Resolution,
    figures: &mut Vec<Figure>,
    findings: &mut Vec<Finding>,
) -> Result<()> {
    let cost = Cost::start(ctx);
    let ls = lengths(res);
    let texts: Vec<String> = ls.iter().map(|l| text(res, *l)).collect();
    let s = summaries(ctx, "finite crack: A0 on a delamination", &texts)?;
    let get = |k: &str| -> Vec<f64> { s.iter().map(|x| x.get(k).unwrap_or(f64::NAN)).collect() };
    let a1 = get("before_A1");
    let refl: Vec<f64> = get("before_A2")
        .iter()
        .zip(&a1)
        .map(|(a, b)| a / b)
        .collect();
    let tran: Vec<f64> = get("beyond_A2")
        .iter()
        .zip(&a1)
        .map(|(a, b)| a / b)
        .collect();
    let tran_ratio = get("beyond_A2_over_A1");
    let closure = get("energy_closure_error")
        .iter()
        .fold(0.0f64, |m, e| m.max(e.abs()));
    let max_gap = get("crack_max_gap_0").iter().fold(0.0f64, |m, g| m.max(*g));
    // the spring's stress reaches zero at K0 u - K1 u^2 = p0
    let u_open = (K0 - (K0 * K0 - 4.0 * K1 * P0).sqrt()) / (2.0 * K1);
    let lmm: Vec<f64> = ls.iter().map(|l| l * 1e3).collect();
    let contrast = 0.2;
    let pr = peaks(&refl, contrast);
    let pt = peaks(&tran, contrast);
    let at = |p: &[usize]| {
        p.iter()
            .map(|&i| fmt_value(lmm[i]))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let xl = "delamination length (mm)";
    let half = C_A0 / F0 / 2.0 * 1e3;
    let mut fig = Figure::new(
        "finite_crack_delamination",
        "Second harmonic of an A0 Lamb wave at a closed delamination against its length",
        format!(
            "Beyond the thesis; after Ye, Biwa and Mori (JASA 148, 2020). A {} mm aluminium \
             plate, absorbing ends; a 500 kHz 5-cycle Hann burst of 5 MPa normal traction \
             from a 4 mm transducer on the top surface at x = 8-12 mm (fd = 1 MHz mm: mostly \
             A0, lambda_A0 = {} mm); a horizontal delamination {} mm under the top surface \
             from x = {} mm, {} to {} mm long ({} lengths), closed by p0 = {} MPa, a \
             quadratic normal spring (K0 = {:e} Pa/m, K1 = {:e} Pa/m^2: 0.9 of the largest the \
             closure allows) and a tangential spring {:e} Pa/m; receivers on the top surface \
             at x = {} mm (before) and {} mm (beyond); pulse inversion (the incident and \
             every linear wave cancel in the even part). (a) reflected and transmitted A2 \
             over the incident A1 at the receiver before; (b) the transmitted A2/A1. Element \
             size {} mm (order 4). Resolution: {}.",
            THICKNESS * 1e3,
            fmt_value(C_A0 / F0 * 1e3),
            DEPTH * 1e3,
            X_START * 1e3,
            fmt_value(lmm[0]),
            fmt_value(lmm[lmm.len() - 1]),
            ls.len(),
            P0 * 1e-6,
            K0,
            K1,
            KT,
            X_BEFORE * 1e3,
            (X_START + L_MAX + 10e-3) * 1e3,
            element(res) * 1e3,
            res.name()
        ),
        vec![
            panel(
                "(a) second harmonic over the incident A1",
                xl,
                "A2 / A1(before)",
                vec![
                    Series::new("reflected (before)", &lmm, &refl),
                    Series::new("transmitted (beyond)", &lmm, &tran),
                ],
            ),
            panel(
                "(b) transmitted A2/A1",
                xl,
                "A2/A1 (beyond)",
                vec![Series::new("transmitted", &lmm, &tran_ratio)],
            ),
        ],
    );
    fig = fig.compare(format!(
        "Ye, Biwa and Mori: the second harmonic peaks and dips against the delamination \
         length (the delaminated region's resonances) / here: maxima (dips deeper than {} % \
         on both sides) of the reflected A2 at {} mm, of the transmitted A2 at {} mm \
         (half the plate's A0 wavelength: {} mm); largest opening of the spring {} m \
         against {} m where its stress reaches zero ({})",
        contrast * 100.0,
        at(&pr),
        at(&pt),
        fmt_value(half),
        fmt_value(max_gap),
        fmt_value(u_open),
        if max_gap < u_open {
            "the delamination stays shut"
        } else {
            "it opens: clapping"
        }
    ));
    fig = fig.compare(cost.line(ctx, res));
    figures.push(fig);

    let spacing = |p: &[usize]| {
        if p.len() < 2 {
            f64::NAN
        } else {
            (lmm[p[p.len() - 1]] - lmm[p[0]]) / (p.len() - 1) as f64
        }
    };
    let statement = "Ye, Biwa and Mori (JASA 148, 2020): the reflected and transmitted second \
                     harmonics of an A0 wave at a closed delamination peak and dip against \
                     its length, at the delaminated region's resonances";
    let resonant = pr.len() >= 2 || pt.len() >= 2;
    let mut f = finding(
        "finite_crack_delamination_transmitted_peaks",
        pt.len() as f64,
        "",
        statement,
        Some(resonant),
    );
    f.note = format!(
        "count of maxima of the transmitted A2 with dips deeper than {} % on both sides \
         (reflected: {}); qualitative only: their plate, frequency and spring differ",
        contrast * 100.0,
        pr.len()
    );
    findings.extend([
        f,
        finding(
            "finite_crack_delamination_reflected_peak_spacing_mm",
            spacing(&pr),
            "mm",
            "(not in the thesis) mean spacing of the reflected A2's maxima against the \
             delamination length",
            None,
        ),
        finding(
            "finite_crack_delamination_transmitted_peak_spacing_mm",
            spacing(&pt),
            "mm",
            "(not in the thesis) mean spacing of the transmitted A2's maxima against the \
             delamination length",
            None,
        ),
        finding(
            "finite_crack_delamination_reflected_a2_max",
            refl.iter().copied().fold(0.0, f64::max),
            "",
            "(not in the thesis) largest reflected A2 over the incident A1",
            None,
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "finite_crack_delamination_energy_closure_error",
            closure,
            "",
            "(not in the thesis) energy audit of the 2D runs (model.md eq. 15.5)",
            Some(closure < 1e-9),
        ),
    ]);
    Ok(())
}

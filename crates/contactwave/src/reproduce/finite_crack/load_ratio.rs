//! The load-ratio curve of a finite crack: A2/A_inc of the reflected wave against the load
//! ratio xi = p0 / sigma_max (static closure over the wave's stress amplitude) for
//! Signorini cracks of a few lengths at normal incidence, beside the plane interface in 2D
//! and the exact 1D solver, whose curve peaks near the thesis' xi_opt = 0.35 (chapter 3).
//!
//! Geometry as [`super::length`] ([`super::Plane`]); the incident amplitude A_inc at the
//! receiver is the reflected A1 of an open crack across the strip (a free surface: the whole
//! incident wave comes back), analysed with the same gate, so that 2D and 1D share the
//! normalisation.

use super::super::{argmax_refined, column, finding, fmt_value, lin, panel, Figure, Finding};
use super::{one_d_text, summaries, Cost, Law, Plane, Resolution, SIGNORINI};
use crate::error::Result;
use crate::output::plot::Series;
use crate::reproduce::Ctx;

/// The wave's stress amplitude, Pa (p0 = xi times it).
const AMPLITUDE: f64 = 1e6;

/// Load ratios.
fn xis(res: Resolution) -> Vec<f64> {
    if res.quick {
        vec![0.05, 0.15, 0.25, 0.35, 0.45, 0.6, 0.8, 1.0]
    } else {
        lin(0.05, 1.0, 20)
    }
}

/// Crack lengths, P wavelengths.
fn lengths(res: Resolution) -> Vec<f64> {
    if res.quick {
        vec![1.0, 4.0]
    } else {
        vec![1.0, 2.0, 4.0, 8.0]
    }
}

/// An open crack (free faces: an initial gap of 1 mm, which the wave never takes up): its
/// reflection is the incident wave.
const OPEN: Law = Law {
    name: "open",
    branches: "compression = { law = \"rigid\" }\ntraction = { law = \"free\" }\n\
               closure = { position = [0.0], gap = [1e-3] }",
    p0: 0.0,
    amplitude: AMPLITUDE,
};

/// Run the study: its figure and findings are appended to the chapter's.
pub(crate) fn run(
    ctx: &Ctx,
    res: Resolution,
    figures: &mut Vec<Figure>,
    findings: &mut Vec<Finding>,
) -> Result<()> {
    let cost = Cost::start(ctx);
    let xi = xis(res);
    let ls = lengths(res);
    let n = res.per_wavelength() as f64;
    let law = SIGNORINI;
    // the finite cracks, then the crack across the strip; last the open crack
    let mut geometries: Vec<Plane> = ls
        .iter()
        .map(|l| Plane {
            res,
            length: Some((l * n).round() as usize),
        })
        .collect();
    geometries.push(Plane { res, length: None });
    let mut texts = Vec::new();
    for g in &geometries {
        texts.extend(xi.iter().map(|x| g.text(&law, x * AMPLITUDE, AMPLITUDE)));
    }
    texts.push(Plane { res, length: None }.text(&OPEN, 0.0, AMPLITUDE));
    let two_d = summaries(ctx, "finite crack: load ratio (2D)", &texts)?;
    let one_texts: Vec<String> = xi
        .iter()
        .map(|x| one_d_text(&law, x * AMPLITUDE, AMPLITUDE))
        .collect();
    let one_d = summaries(ctx, "finite crack: load ratio (1D)", &one_texts)?;

    let a_inc = two_d[texts.len() - 1]
        .get("reflected_A1")
        .unwrap_or(f64::NAN);
    let m = xi.len();
    let curve = |g: usize| -> Vec<f64> {
        column(&two_d[g * m..(g + 1) * m], "reflected_A2")
            .iter()
            .map(|v| v / a_inc)
            .collect()
    };
    let exact = column(&one_d, "A2_over_Ainc");
    let peak = |y: &[f64]| {
        (
            argmax_refined(&xi, y),
            y.iter().copied().fold(0.0, f64::max),
        )
    };
    let (xi_1d, h_1d) = peak(&exact);
    let plane = curve(ls.len());
    let (xi_plane, h_plane) = peak(&plane);

    let mut series = Vec::new();
    let mut rel = Vec::new();
    let mut peaks = Vec::new();
    for (g, l) in ls.iter().enumerate() {
        let y = curve(g);
        let label = format!("L = {} lambda", fmt_value(*l));
        let r: Vec<f64> = y.iter().zip(&plane).map(|(a, b)| a / b).collect();
        rel.push(Series::new(label.clone(), &xi, &r));
        series.push(Series::new(label, &xi, &y));
        peaks.push(peak(&y));
    }
    series.push(Series::new("plane interface (2D)", &xi, &plane));
    series.push(Series::new("exact 1D", &xi, &exact));
    let r: Vec<f64> = exact.iter().zip(&plane).map(|(a, b)| a / b).collect();
    rel.push(Series::new("exact 1D", &xi, &r));
    let xl = "xi = p0 / sigma_max";
    let mut fig = Figure::new(
        "finite_crack_load_ratio",
        "Second harmonic of the wave reflected by a finite Signorini crack against the load ratio",
        format!(
            "Beyond the thesis (thesis chapter 3 for the plane interface). The geometry of \
             the length study: a plane 1 MHz P wave (5-cycle Hann burst, sigma_max = 1 MPa) \
             at normal incidence on a Signorini crack (rigid in compression, free in \
             traction) under the closure p0 = xi sigma_max, xi = {} to {} ({} points), \
             lengths {} P wavelengths, beside the crack across the strip (plane interface, \
             2D) and the exact 1D solver. A_inc: the reflected A1 of an open crack across the \
             strip (the incident wave, with the same gate and analysis; the 1D solver's own \
             A_inc for 1D). (a) A2/A_inc; (b) over the plane interface in 2D (the same mesh, \
             gate and analysis: what the finite length alone changes). Resolution: {}.",
            fmt_value(xi[0]),
            fmt_value(xi[m - 1]),
            m,
            ls.iter()
                .map(|v| fmt_value(*v))
                .collect::<Vec<_>>()
                .join(", "),
            res.name()
        ),
        vec![
            panel("(a) reflected A2/A_inc", xl, "A2/A_inc", series),
            panel(
                "(b) over the plane interface (2D)",
                xl,
                "over the plane (2D)",
                rel,
            ),
        ],
    );
    fig = fig.compare(format!(
        "thesis: xi_opt = 0.35 / exact 1D: maximum {} at xi = {}; plane interface (2D): {} \
         at xi = {}",
        fmt_value(h_1d),
        fmt_value(xi_1d),
        fmt_value(h_plane),
        fmt_value(xi_plane)
    ));
    for (l, (x, h)) in ls.iter().zip(&peaks) {
        fig = fig.compare(format!(
            "L = {} lambda: maximum {} ({} of the plane interface's in 2D) at xi = {}",
            fmt_value(*l),
            fmt_value(*h),
            fmt_value(h / h_plane),
            fmt_value(*x)
        ));
    }
    fig = fig.compare(cost.line(ctx, res));
    figures.push(fig);

    findings.extend([
        finding(
            "finite_crack_load_ratio_xi_opt_1d",
            xi_1d,
            "",
            "xi ~ 0.35 (accepted 0.30-0.40: a 5-cycle Hann burst here, the grid's step \
             refined by a parabola)",
            Some((xi_1d - 0.35).abs() <= 0.05),
        ),
        finding(
            "finite_crack_load_ratio_xi_opt_plane_2d",
            xi_plane,
            "",
            "(not in the thesis) the crack across the strip in 2D: xi of the maximum, as \
             the exact 1D solver's within 0.05",
            Some((xi_plane - xi_1d).abs() <= 0.05),
        ),
        finding(
            "finite_crack_load_ratio_peak_plane_2d_over_1d",
            h_plane / h_1d,
            "",
            "(not in the thesis) height of the maximum, the crack across the strip in 2D \
             over the exact 1D solver's: 1 within 5 % (the mesh's dispersion and the gate)",
            Some((h_plane / h_1d - 1.0).abs() <= 0.05),
        ),
    ]);
    for (l, (x, h)) in ls.iter().zip(&peaks) {
        let tag = format!("{l}").replace('.', "p");
        findings.push(finding(
            &format!("finite_crack_load_ratio_xi_opt_{tag}lambda"),
            *x,
            "",
            "(not in the thesis) xi of the A2/A_inc maximum of a finite Signorini crack \
             (the plane interface's: about 0.35)",
            None,
        ));
        findings.push(finding(
            &format!("finite_crack_load_ratio_peak_over_plane_{tag}lambda"),
            h / h_plane,
            "",
            "(not in the thesis) height of the A2/A_inc maximum of a finite Signorini crack \
             over the plane interface's in 2D (same mesh and analysis)",
            None,
        ));
    }
    Ok(())
}

//! Beyond the thesis: shear waves and friction (issue 11; the tangential model of
//! `law::tangential` and `solver::coupled`). Two identical aluminium half-spaces under a
//! static pressure p0, a 1 MHz shear burst of amplitude tau_inc:
//!
//! 1. rigid-stick Coulomb friction (`examples/shear/clipping.toml`, mu = 0.3, tau_inc =
//!    5 MPa) swept over the friction ratio `r = mu p0 / tau_inc` (p0 varied): the third
//!    harmonic of the transmitted and reflected shear waves against the clipped-sine closed
//!    form ([`ClippedShear`]) with rectangular bursts and the projection over the burst's
//!    whole periods ([`period_harmonics`]), and the experiment-like band-peak values of
//!    Hann-ramped bursts (summary keys `shear_tr_A3_over_A1`, `shear_A3_over_A1`);
//! 2. stress-slip hysteresis loops (tau against `[u]_T`) at a few friction ratios;
//! 3. friction dissipation per cycle and as a fraction of the incident energy against the
//!    closed form;
//! 4. the full RCCM law (`examples/shear/rccm_shear.toml`: C_N = 2e13 Pa/m, w = 0.1 J/m^2,
//!    C_T = 1e13 Pa/m, mu = 0.4, p0 = 0.82 MPa): the competition of adhesion and friction
//!    (thesis chapter 1, Figure 5) under a normal and a shear burst, against the shear
//!    amplitude, with a shear-only series and the Coulomb limit (no adhesion);
//! 5. oblique incidence ([`super::oblique`]): the reflected P wave's A2/A1 against the static
//!    pressure at 0, 22.5 and 45 degrees.

use super::{
    argmax_refined, column, f, finding, fmt_value, lin, panel, tv, Chapter, ChapterResult, Ctx,
    Edits, Figure, Finding, AMPLITUDE_FLOOR,
};
use crate::analysis::projection::period_harmonics;
use crate::analysis::{velocity_bands, Summary};
use crate::analytic::friction::ClippedShear;
use crate::error::{Error, Result};
use crate::output::plot::Series;
use std::f64::consts::PI;

/// Friction coefficient of the clipping study (`clipping.toml`).
const MU: f64 = 0.3;
/// Incident shear amplitude of the clipping study, Pa.
const TAU: f64 = 5e6;
/// Frequency, Hz.
const F0: f64 = 1e6;
/// Cycles of the rectangular bursts (closed-form comparison).
const RECT_CYCLES: usize = 10;
/// Samples per period of the rectangular runs.
const RECT_SPP: i64 = 1000;
/// Cycles of the Hann-ramped bursts (band-peak analysis).
const HANN_CYCLES: i64 = 15;
/// Samples per period of the Hann-ramped runs.
const HANN_SPP: i64 = 200;
/// Friction ratios of the loops (grid indices of [`ratios`]: 0.2, 0.5, 0.8).
const LOOP_RATIOS: [usize; 3] = [3, 9, 15];
/// Stick stiffness of the elastic-stick loop, Pa/m.
const K_STICK: f64 = 5e13;
/// Shear amplitudes of the RCCM study, Pa.
const RCCM_AMPS: [f64; 11] = [
    0.25e6, 0.5e6, 0.75e6, 1e6, 1.5e6, 2e6, 3e6, 4e6, 5e6, 6e6, 8e6,
];
/// Shear amplitudes of the RCCM traces, Pa.
const RCCM_TRACE_AMPS: [f64; 3] = [0.5e6, 2e6, 5e6];
/// Shear amplitude of the example `rccm_shear.toml`, Pa.
const RCCM_CASE_AMP: f64 = 2e6;

/// The friction-ratio grid: 0.05 to 1.5 by 0.05.
fn ratios() -> Vec<f64> {
    (1..=30).map(|k| k as f64 * 0.05).collect()
}

/// The closed form at friction ratio `r` (identical aluminium half-spaces of shear
/// impedance `z`, Pa s/m).
fn closed(r: f64, z: f64) -> ClippedShear {
    ClippedShear {
        amplitude: TAU,
        omega: 2.0 * PI * F0,
        z1: z,
        z2: z,
        limit: r * TAU,
    }
}

/// Closed-form transmitted and reflected A3/A1. The reflected stress is the transmitted one
/// minus the incident one (stress continuity): its fundamental is `|b1 - A|`, its third
/// harmonic the transmitted one (the incident wave has none).
fn closed_a3_over_a1(c: &ClippedShear) -> (f64, f64) {
    let (b1, b3) = (c.transmitted_harmonic(1), c.transmitted_harmonic(3).abs());
    let r1 = (c.amplitude - b1).abs();
    let q = |a: f64, b: f64| if b > 1e-12 * c.amplitude { a / b } else { 0.0 };
    (q(b3, b1), q(b3, r1))
}

/// One rectangular run: harmonics (projection over the whole periods) of the transmitted
/// and reflected shear stresses, the summary, and the loop when asked.
struct RectRun {
    tr: Vec<f64>,
    re: Vec<f64>,
    summary: Summary,
    /// The histories, kept for the loops of [`LOOP_RATIOS`].
    trace: Option<Trace>,
}

/// Histories of one run: time (s), `[u]_T` (m), tau (Pa), incident and transmitted shear
/// stresses (Pa), adhesion beta.
#[derive(Default)]
struct Trace {
    t: Vec<f64>,
    gap: Vec<f64>,
    tau: Vec<f64>,
    inc: Vec<f64>,
    tr: Vec<f64>,
    beta: Vec<f64>,
}

/// A simulated run's shear histories (and the normal adhesion).
fn trace_of(r: &crate::RunResult) -> Result<Trace> {
    let sh = shear_of(r)?;
    let o = &sh.interface;
    Ok(Trace {
        t: o.t.clone(),
        gap: o.gap.clone(),
        tau: o.contact_stress.clone(),
        inc: o.incident_stress.clone(),
        tr: o.transmitted_stress.clone(),
        beta: r.interface.beta.clone(),
    })
}

fn shear_of(r: &crate::RunResult) -> Result<&crate::model::half_space::shear::ShearResult> {
    r.shear
        .as_ref()
        .ok_or_else(|| Error::invalid("<reproduce>", "shear", "none", "a shear scenario"))
}

/// Shared set-up: the base scenarios and the shear impedance.
struct Setup {
    clipping: toml::Table,
    rccm: toml::Table,
    /// Shear impedance of aluminium, Pa s/m.
    z: f64,
    ratios: Vec<f64>,
}

impl Setup {
    fn new(ctx: &Ctx) -> Result<Setup> {
        let clipping = ctx.base("shear_clipping.toml")?;
        let rccm = ctx.base("shear_rccm.toml")?;
        let z = ctx
            .scenario(&clipping, &Vec::new())?
            .shear
            .map(|s| s.z1t)
            .unwrap_or(f64::NAN);
        Ok(Setup {
            clipping,
            rccm,
            z,
            ratios: ratios(),
        })
    }

    fn p0(r: f64) -> f64 {
        r * TAU / MU
    }
}

/// Figures and findings as they are added, in report order.
#[derive(Default)]
struct Collected {
    figures: Vec<Figure>,
    findings: Vec<Finding>,
}

/// Run the chapter.
pub(crate) fn run(ctx: &Ctx) -> Result<ChapterResult> {
    let s = Setup::new(ctx)?;
    let mut out = Collected::default();
    let rect = rect_runs(ctx, &s)?;
    let hann = hann_runs(ctx, &s)?;
    harmonics(&s, &rect, &hann, &mut out);
    loops(ctx, &s, &rect, &mut out)?;
    dissipation(&s, &rect, &hann, &mut out);
    rccm(ctx, &s, &mut out)?;
    super::oblique::run(ctx, &mut out.figures, &mut out.findings)?;
    Ok(ChapterResult {
        chapter: Chapter::Shear,
        title: "Beyond the thesis: shear waves, friction and oblique incidence".into(),
        intro: "Not in the thesis (its chapter 1 states the full RCCM law, chapters 3-5 probe \
                it with longitudinal waves only). Two identical aluminium half-spaces (E = 71 \
                GPa, nu = 0.33, rho = 2710 kg/m^3, shear impedance Z_T = rho c_T) under a \
                static pressure p0, hit by a 1 MHz shear burst, exact coupled solver. With \
                rigid-stick Coulomb friction the transmitted shear stress is the incident one \
                clipped at +-mu p0: odd harmonics, friction dissipation, and nothing at all \
                above the friction ratio mu p0 / tau_inc = 1 (closed form: model of Meziane, \
                Norris and Shuvalov, JASA 2011, analytic::friction). The full RCCM law adds \
                an adhesive spring beta^2 C_T [u]_T, damaged by the normal and tangential gaps \
                together, so friction takes over as beta falls to 0. Last, a P wave at 0, 22.5 \
                and 45 degrees on a pressed power-law contact with friction (oblique \
                incidence, mode conversion, model.md section 14)."
            .into(),
        figures: out.figures,
        findings: out.findings,
        seconds: 0.0,
        runs: 0,
    })
}

/// Rectangular bursts over the ratio grid (projection over the whole periods).
fn rect_runs(ctx: &Ctx, s: &Setup) -> Result<Vec<RectRun>> {
    let jobs: Vec<(usize, f64)> = s.ratios.iter().copied().enumerate().collect();
    ctx.map("shear: rectangular bursts", &jobs, |&(i, r)| {
        let e: Edits = vec![
            ("interface.static_pressure", f(Setup::p0(r))),
            ("solver.samples_per_period", toml::Value::Integer(RECT_SPP)),
        ];
        let run = crate::simulate(&ctx.scenario(&s.clipping, &e)?)?;
        let o = &shear_of(&run)?.interface;
        let h = |v: &[f64]| {
            period_harmonics(v, o.dt, F0, 0, RECT_CYCLES, 5).unwrap_or_else(|| vec![f64::NAN; 6])
        };
        Ok(RectRun {
            tr: h(&o.transmitted_stress),
            re: h(&o.reflected_stress),
            trace: if LOOP_RATIOS.contains(&i) {
                Some(trace_of(&run)?)
            } else {
                None
            },
            summary: run.summary,
        })
    })
}

/// Hann-ramped bursts over the ratio grid: the summary and the A3/A1 floor of the band
/// analysis (the incident burst itself).
fn hann_runs(ctx: &Ctx, s: &Setup) -> Result<Vec<(Summary, f64)>> {
    ctx.map("shear: Hann-ramped bursts", &s.ratios, |&r| {
        let e: Edits = vec![
            ("interface.static_pressure", f(Setup::p0(r))),
            ("solver.samples_per_period", toml::Value::Integer(HANN_SPP)),
            (
                "shear_incident.window",
                toml::Value::String("hann_ramps".into()),
            ),
            ("shear_incident.cycles", toml::Value::Integer(HANN_CYCLES)),
        ];
        let run = crate::simulate(&ctx.scenario(&s.clipping, &e)?)?;
        let o = &shear_of(&run)?.interface;
        let fl = velocity_bands(&o.incident_displacement, o.dt, F0, None);
        Ok((run.summary, fl.harmonic[3] / fl.harmonic[1]))
    })
}

/// A dense grid of friction ratios for the closed-form curves.
fn dense() -> Vec<f64> {
    lin(0.005, 1.5, 300)
}

/// Figure: A3/A1 of the transmitted and reflected waves against the friction ratio.
fn harmonics(s: &Setup, rect: &[RectRun], hann: &[(Summary, f64)], out: &mut Collected) {
    let r = &s.ratios;
    let xd = dense();
    let cf: Vec<(f64, f64)> = xd
        .iter()
        .map(|&x| closed_a3_over_a1(&closed(x, s.z)))
        .collect();
    let cf_tr: Vec<f64> = cf.iter().map(|c| c.0).collect();
    let cf_re: Vec<f64> = cf.iter().map(|c| c.1).collect();
    // A3/A1 where the wave exists (A1/A_inc > 1e-9; the reflected wave vanishes above r = 1)
    let q = |h: &[f64]| {
        if h[1] > 1e-9 * TAU {
            h[3] / h[1]
        } else {
            f64::NAN
        }
    };
    let tr: Vec<f64> = rect.iter().map(|x| q(&x.tr)).collect();
    let re: Vec<f64> = rect.iter().map(|x| q(&x.re)).collect();
    let sums: Vec<Summary> = hann.iter().map(|h| h.0.clone()).collect();
    let band_tr = column(&sums, "shear_tr_A3_over_A1");
    let band_re: Vec<f64> = column(&sums, "shear_A3_over_A1")
        .iter()
        .zip(column(&sums, "shear_A1_over_Ainc"))
        .map(|(a, a1)| if a1 > 1e-9 { *a } else { f64::NAN })
        .collect();
    let floor: Vec<f64> = hann.iter().map(|h| h.1).collect();
    let lg = |v: &[f64]| v.iter().map(|x| x.max(1e-16).log10()).collect::<Vec<_>>();

    // closed-form agreement over the slipping points (r < 1)
    let mut err_tr = 0.0f64;
    let mut err_re = 0.0f64;
    let mut band_diff = 0.0f64;
    for (i, &x) in r.iter().enumerate().filter(|&(_, &x)| x < 0.999) {
        let (c_tr, c_re) = closed_a3_over_a1(&closed(x, s.z));
        err_tr = err_tr.max((tr[i] / c_tr - 1.0).abs());
        err_re = err_re.max((re[i] / c_re - 1.0).abs());
        if x < 0.901 {
            band_diff = band_diff.max((band_tr[i] / c_tr - 1.0).abs());
        }
    }
    let above: Vec<usize> = (0..r.len()).filter(|&i| r[i] > 1.001).collect();
    // above r = 1: transmitted A3/A1 and the reflected wave's amplitude (both zero)
    let rect_above = above
        .iter()
        .map(|&i| (rect[i].tr[3] / rect[i].tr[1]).max(rect[i].re[1] / TAU))
        .fold(0.0f64, f64::max);
    let band_over_floor = above
        .iter()
        .map(|&i| band_tr[i] / floor[i])
        .fold(0.0f64, f64::max);
    let a3_inc: Vec<f64> = rect.iter().map(|x| x.tr[3] / TAU).collect();
    let a3_inc_cf: Vec<f64> = xd
        .iter()
        .map(|&x| closed(x, s.z).transmitted_harmonic(3).abs() / TAU)
        .collect();
    let r_a3max = argmax_refined(r, &a3_inc);
    let r_a3max_cf = argmax_refined(&xd, &a3_inc_cf);

    let fig = Figure::new(
        "shear_a3_vs_friction_ratio",
        "Third harmonic of the shear waves against the friction ratio mu p0 / tau_inc",
        format!(
            "Rigid-stick Coulomb friction between identical aluminium half-spaces, mu = {MU}, \
             tau_inc = {} MPa at 1 MHz, p0 = r tau_inc / mu from {} to {} MPa. Closed form: \
             the transmitted stress is the incident one clipped at +-mu p0 \
             (analytic::friction::ClippedShear). 'rectangular': {RECT_CYCLES}-cycle \
             rectangular bursts ({RECT_SPP} samples per period), harmonics projected over \
             the burst's whole periods (analysis::projection::period_harmonics). \
             'band peak': {HANN_CYCLES}-cycle Hann-ramped bursts ({HANN_SPP} samples per \
             period), summary keys shear_tr_A3_over_A1 and shear_A3_over_A1 (the \
             experiment-like band filter: the ramps clip less than the plateau). The reflected \
             A3/A1 grows to 1 as r -> 1, where the reflected wave itself vanishes (it is \
             not drawn above r = 1, where there is none). Panel (c): \
             the band-peak transmitted A3/A1 falls onto the analysis floor (the same filter on \
             the incident burst) above r = 1, where the interface never slips.",
            TAU / 1e6,
            fmt_value(Setup::p0(r[0]) / 1e6),
            fmt_value(Setup::p0(r[r.len() - 1]) / 1e6)
        ),
        vec![
            panel(
                "(a) transmitted wave",
                "friction ratio mu p0 / tau_inc",
                "A3/A1",
                vec![
                    Series::new("closed form", &xd, &cf_tr),
                    Series::new("rectangular, projection", r, &tr),
                    Series::new("Hann ramps, band peak", r, &band_tr),
                ],
            ),
            panel(
                "(b) reflected wave",
                "friction ratio mu p0 / tau_inc",
                "A3/A1",
                vec![
                    Series::new("closed form", &xd, &cf_re),
                    Series::new("rectangular, projection", r, &re),
                    Series::new("Hann ramps, band peak", r, &band_re),
                ],
            ),
            panel(
                "(c) band peak against its floor",
                "friction ratio mu p0 / tau_inc",
                "log10(A3/A1)",
                vec![
                    Series::new("transmitted, band peak", r, &lg(&band_tr)),
                    Series::new("reflected, band peak", r, &lg(&band_re)),
                    Series::new("floor (incident burst)", r, &lg(&floor)),
                ],
            ),
        ],
    )
    .compare(format!(
        "closed form / here: max relative error of A3/A1 below r = 1: transmitted {}, \
         reflected {}; above r = 1: harmonics <= {} (projection), band peak / floor <= {}",
        fmt_value(err_tr),
        fmt_value(err_re),
        fmt_value(rect_above),
        fmt_value(band_over_floor)
    ));
    out.figures.push(fig);
    const CF: &str = "(not in the thesis) clipped-sine closed form, analytic::friction";
    out.findings.extend([
        finding(
            "shear_clip_A3_rel_error",
            err_tr,
            "",
            CF,
            Some(err_tr < 1e-3),
        ),
        finding(
            "shear_clip_reflected_A3_rel_error",
            err_re,
            "",
            CF,
            Some(err_re < 1e-3),
        ),
        finding(
            "shear_clip_harmonics_above_ratio_1",
            rect_above,
            "",
            "(not in the thesis) no slip above mu p0 / tau_inc = 1: transmitted A3/A1 and reflected A1/A_inc are 0",
            Some(rect_above < 1e-9),
        )
.with_floor(AMPLITUDE_FLOOR),
        finding(
            "shear_band_A3_over_floor_above_ratio_1",
            band_over_floor,
            "",
            "(not in the thesis) band peak at its floor (the incident burst's own A3/A1) above ratio 1",
            Some((band_over_floor - 1.0).abs() < 1e-6),
        ),
        finding(
            "shear_band_tr_A3_rel_diff",
            band_diff,
            "",
            "(not in the thesis) band peak of Hann-ramped bursts against the closed form, r <= 0.9: the ramps clip less",
            None,
        ),
        finding(
            "shear_tr_A3_max_friction_ratio",
            r_a3max,
            "",
            &format!(
                "(not in the thesis) closed form: transmitted A3/A_inc largest at mu p0 / tau_inc = {}",
                fmt_value(r_a3max_cf)
            ),
            Some((r_a3max - r_a3max_cf).abs() < 0.02),
        ),
        finding(
            "shear_tr_A3_over_Ainc_max",
            a3_inc.iter().copied().fold(0.0f64, f64::max),
            "",
            &format!(
                "(not in the thesis) closed form: {}",
                fmt_value(a3_inc_cf.iter().copied().fold(0.0f64, f64::max))
            ),
            None,
        ),
    ]);
}

fn um(v: &[f64], scale: f64) -> Vec<f64> {
    v.iter().map(|x| x * scale).collect()
}

/// Figure: stress-slip loops at a few friction ratios, and the clipped signal.
fn loops(ctx: &Ctx, s: &Setup, rect: &[RectRun], out: &mut Collected) -> Result<()> {
    // one elastic-stick run at r = 0.5
    let r_el = s.ratios[LOOP_RATIOS[1]];
    let law = format!("{{ law = \"coulomb\", friction = {MU:?}, stiffness = {K_STICK:e} }}");
    let el = ctx.map("shear: elastic stick", &[r_el], |&r| {
        let e: Edits = vec![
            ("interface.static_pressure", f(Setup::p0(r))),
            ("solver.samples_per_period", toml::Value::Integer(RECT_SPP)),
            ("interface.tangential", tv(&law)),
        ];
        trace_of(&crate::simulate(&ctx.scenario(&s.clipping, &e)?)?)
    })?;
    let mut loop_series = Vec::new();
    for &i in &LOOP_RATIOS {
        if let Some(t) = &rect[i].trace {
            loop_series.push(Series::new(
                format!("r = {}", fmt_value(s.ratios[i])),
                &um(&t.gap, 1e9),
                &um(&t.tau, 1e-6),
            ));
        }
    }
    if let Some(t) = el.first() {
        loop_series.push(Series::new(
            format!(
                "r = {}, stick stiffness {} Pa/m",
                fmt_value(r_el),
                fmt_value(K_STICK)
            ),
            &um(&t.gap, 1e9),
            &um(&t.tau, 1e-6),
        ));
    }
    let mut signal = Vec::new();
    if let Some(t) = &rect[LOOP_RATIOS[1]].trace {
        let ts = um(&t.t, 1e6);
        signal.push(Series::new("incident tau_inc", &ts, &um(&t.inc, 1e-6)));
        signal.push(Series::new(
            "transmitted, rigid stick",
            &ts,
            &um(&t.tr, 1e-6),
        ));
    }
    if let Some(t) = el.first() {
        signal.push(Series::new(
            "transmitted, elastic stick",
            &um(&t.t, 1e6),
            &um(&t.tr, 1e-6),
        ));
    }
    out.figures.push(Figure::new(
        "shear_stress_slip_loops",
        "Friction hysteresis: shear stress against the tangential gap",
        format!(
            "The rectangular runs of the previous figure at r = mu p0 / tau_inc = 0.2, 0.5 \
             and 0.8 (rigid stick: the gap [u]_T moves only while slipping, at tau = +-mu p0), \
             and at r = 0.5 with an elastic stick of stiffness k_t = {} Pa/m in series with \
             the slider (the loop leans by 1/k_t). Each loop's area is the energy friction \
             dissipates (next figure). Panel (a): the clipped transmitted stress at r = 0.5.",
            fmt_value(K_STICK)
        ),
        vec![
            panel(
                "(a) shear stresses at the interface, r = 0.5",
                "t (us)",
                "tau (MPa)",
                signal,
            ),
            panel(
                "(b) tau against [u]_T",
                "[u]_T (nm)",
                "tau (MPa)",
                loop_series,
            ),
        ],
    ));
    Ok(())
}

/// Figure: friction dissipation per cycle and as a fraction of the incident energy.
fn dissipation(s: &Setup, rect: &[RectRun], hann: &[(Summary, f64)], out: &mut Collected) {
    let r = &s.ratios;
    let xd = dense();
    let sums: Vec<Summary> = rect.iter().map(|x| x.summary.clone()).collect();
    let per = column(&sums, "friction_dissipation_per_cycle");
    let frac = column(&sums, "friction_dissipation_fraction");
    let hs: Vec<Summary> = hann.iter().map(|h| h.0.clone()).collect();
    let frac_hann = column(&hs, "friction_dissipation_fraction");
    let cf_per: Vec<f64> = xd
        .iter()
        .map(|&x| closed(x, s.z).dissipation_per_cycle())
        .collect();
    let cf_frac: Vec<f64> = xd
        .iter()
        .map(|&x| {
            let c = closed(x, s.z);
            c.dissipation_per_cycle() / c.incident_energy_per_cycle()
        })
        .collect();
    let mut err = 0.0f64;
    for (i, &x) in r.iter().enumerate().filter(|&(_, &x)| x < 0.999) {
        err = err.max((per[i] / closed(x, s.z).dissipation_per_cycle() - 1.0).abs());
    }
    let above = r
        .iter()
        .zip(&per)
        .filter(|(x, _)| **x > 1.001)
        .map(|(_, y)| y.abs())
        .fold(0.0f64, f64::max);
    let frac_max = frac.iter().copied().fold(0.0f64, f64::max);
    let r_max = argmax_refined(r, &frac);
    let r_max_cf = argmax_refined(&xd, &cf_frac);
    let frac_max_cf = cf_frac.iter().copied().fold(0.0f64, f64::max);
    out.figures.push(
        Figure::new(
            "shear_friction_dissipation",
            "Friction dissipation against the friction ratio mu p0 / tau_inc",
            format!(
                "The runs of the first figure: energy friction dissipates per cycle (summary \
                 key friction_dissipation_per_cycle: the total over the burst's cycles) and as \
                 a fraction of the incident energy (friction_dissipation_fraction), against \
                 the closed form (4 c k_T / omega) (T A cos(theta_c) - c (pi/2 - theta_c)), \
                 c = mu p0, k_T = 2 / Z_T, sin(theta_c) = c / A (analytic::friction). The \
                 Hann-ramped bursts dissipate a smaller fraction (their ramps slip less). \
                 Nothing is dissipated above r = 1; the fraction is largest near r = {}.",
                fmt_value(r_max_cf)
            ),
            vec![
                panel(
                    "(a) dissipation per cycle",
                    "friction ratio mu p0 / tau_inc",
                    "J/m^2 per cycle",
                    vec![
                        Series::new("closed form", &xd, &cf_per),
                        Series::new("rectangular", r, &per),
                    ],
                ),
                panel(
                    "(b) fraction of the incident energy",
                    "friction ratio mu p0 / tau_inc",
                    "dissipated / incident",
                    vec![
                        Series::new("closed form", &xd, &cf_frac),
                        Series::new("rectangular", r, &frac),
                        Series::new("Hann ramps", r, &frac_hann),
                    ],
                ),
            ],
        )
        .compare(format!(
            "closed form: largest fraction {} at r = {} / here: {} at r = {}; per cycle within {} \
             (relative) below r = 1",
            fmt_value(frac_max_cf),
            fmt_value(r_max_cf),
            fmt_value(frac_max),
            fmt_value(r_max),
            fmt_value(err)
        )),
    );
    const CF: &str = "(not in the thesis) closed form, analytic::friction";
    out.findings.extend([
        finding("shear_dissipation_rel_error", err, "", CF, Some(err < 1e-3)),
        finding(
            "shear_dissipation_above_ratio_1",
            above,
            "J/m^2",
            "(not in the thesis) no slip, no dissipation above mu p0 / tau_inc = 1",
            Some(above == 0.0),
        ),
        finding(
            "shear_dissipation_fraction_max",
            frac_max,
            "",
            &format!(
                "(not in the thesis) closed form: {} (10-cycle rectangular burst)",
                fmt_value(frac_max_cf)
            ),
            Some((frac_max / frac_max_cf - 1.0).abs() < 0.01),
        ),
        finding(
            "shear_dissipation_fraction_max_friction_ratio",
            r_max,
            "",
            &format!("(not in the thesis) closed form: {}", fmt_value(r_max_cf)),
            Some((r_max - r_max_cf).abs() < 0.02),
        ),
    ]);
}

/// The RCCM variants: with the normal burst of the example, shear only, and Coulomb
/// friction without adhesion (the limit beta = 0), at shear amplitude `amp` (Pa).
#[derive(Clone, Copy)]
enum RccmCase {
    Both,
    ShearOnly,
    Coulomb,
}

impl RccmCase {
    const ALL: [RccmCase; 3] = [RccmCase::Both, RccmCase::ShearOnly, RccmCase::Coulomb];
    fn label(self) -> &'static str {
        match self {
            RccmCase::Both => "RCCM, normal + shear burst",
            RccmCase::ShearOnly => "RCCM, shear burst only",
            RccmCase::Coulomb => "no adhesion (Coulomb), normal + shear",
        }
    }
}

fn rccm_scenario(
    ctx: &Ctx,
    s: &Setup,
    case: RccmCase,
    amp: f64,
) -> Result<crate::scenario::Scenario> {
    let mut t = ctx.table(&s.rccm, &vec![("shear_incident.amplitude", f(amp))])?;
    match case {
        RccmCase::Both => {}
        RccmCase::ShearOnly => {
            t.remove("incident");
        }
        RccmCase::Coulomb => {
            let friction = s
                .rccm
                .get("interface")
                .and_then(|i| i.get("tangential"))
                .and_then(|t| t.get("friction"))
                .and_then(|v| v.as_float())
                .unwrap_or(f64::NAN);
            t = ctx.table(
                &t,
                &vec![
                    ("interface.traction", tv("{ law = \"free\" }")),
                    (
                        "interface.tangential",
                        tv(&format!("{{ law = \"coulomb\", friction = {friction:?} }}")),
                    ),
                ],
            )?;
        }
    }
    crate::scenario::Scenario::from_table(t, std::path::Path::new("<reproduce>"))
}

/// Figure: adhesion against friction on the full RCCM law.
fn rccm(ctx: &Ctx, s: &Setup, out: &mut Collected) -> Result<()> {
    let jobs: Vec<(RccmCase, f64)> = RccmCase::ALL
        .iter()
        .flat_map(|&c| RCCM_AMPS.iter().map(move |&a| (c, a)))
        .collect();
    let sums = ctx.map("shear: full RCCM law", &jobs, |&(c, a)| {
        crate::simulate_summary(&rccm_scenario(ctx, s, c, a)?)
    })?;
    let traces = ctx.map("shear: full RCCM traces", &RCCM_TRACE_AMPS, |&a| {
        trace_of(&crate::simulate(&rccm_scenario(
            ctx,
            s,
            RccmCase::Both,
            a,
        )?)?)
    })?;
    let n = RCCM_AMPS.len();
    let amps_mpa: Vec<f64> = RCCM_AMPS.iter().map(|a| a / 1e6).collect();
    let by_case = |k: usize, key: &str| column(&sums[k * n..(k + 1) * n], key);
    let series = |key: &str, cases: &[usize]| -> Vec<Series> {
        cases
            .iter()
            .map(|&k| Series::new(RccmCase::ALL[k].label(), &amps_mpa, &by_case(k, key)))
            .collect()
    };
    let label = |a: f64| format!("tau_inc = {} MPa", fmt_value(a / 1e6));
    let beta_t: Vec<Series> = RCCM_TRACE_AMPS
        .iter()
        .zip(&traces)
        .map(|(&a, t)| Series::new(label(a), &um(&t.t, 1e6), &t.beta))
        .collect();
    // (b) the loops of the example's amplitude, one every other cycle of the shear burst,
    // light to dark: from the adhesive, leaning loops to the flat Coulomb ones
    let shear_start = s
        .rccm
        .get("shear_incident")
        .and_then(|v| v.get("delay"))
        .and_then(|v| v.as_float())
        .unwrap_or(0.0);
    let case = RCCM_TRACE_AMPS
        .iter()
        .position(|&a| a == RCCM_CASE_AMP)
        .and_then(|i| traces.get(i));
    let cycles: Vec<usize> = (1..=15).step_by(2).collect();
    let colours = crate::output::plot::ramp(cycles.len());
    let loops: Vec<Series> = case
        .map(|t| {
            cycles
                .iter()
                .zip(&colours)
                .map(|(&k, &rgb)| {
                    let (a, b) = (
                        shear_start + (k - 1) as f64 / F0,
                        shear_start + k as f64 / F0,
                    );
                    let idx: Vec<usize> = (0..t.t.len())
                        .filter(|&i| t.t[i] >= a && t.t[i] <= b)
                        .collect();
                    let pick =
                        |v: &[f64], s: f64| idx.iter().map(|&i| v[i] * s).collect::<Vec<_>>();
                    Series::new(
                        format!("cycle {k}"),
                        &pick(&t.gap, 1e9),
                        &pick(&t.tau, 1e-6),
                    )
                    .colored(rgb)
                })
                .collect()
        })
        .unwrap_or_default();
    let at = |k: usize, key: &str, amp: f64| {
        RCCM_AMPS
            .iter()
            .position(|&a| a == amp)
            .map(|i| by_case(k, key)[i])
            .unwrap_or(f64::NAN)
    };
    let beta_case = at(0, "beta_end", RCCM_CASE_AMP);
    let beta_shear_only = at(1, "beta_end", RCCM_CASE_AMP);
    let top = RCCM_AMPS[n - 1];
    let beta_top_shear_only = at(1, "beta_end", top);
    let get = |path: &[&str]| {
        let mut v: Option<&toml::Value> = None;
        for (k, key) in path.iter().enumerate() {
            v = if k == 0 {
                s.rccm.get(*key)
            } else {
                v.and_then(|x| x.get(*key))
            };
        }
        v.and_then(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
    };
    let c_t = get(&["interface", "tangential", "stiffness"]).unwrap_or(f64::NAN);
    // the share of the adhesive spring beta^2 C_T [u]_T in the shear stress over the last
    // three periods of the shear burst of the example (friction carries the rest)
    let burst_end = get(&["shear_incident", "delay"]).unwrap_or(0.0)
        + get(&["shear_incident", "cycles"]).unwrap_or(15.0) / F0;
    let spring_share = RCCM_TRACE_AMPS
        .iter()
        .position(|&a| a == RCCM_CASE_AMP)
        .and_then(|i| traces.get(i))
        .map(|t| {
            let (mut spring, mut tau) = (0.0f64, 0.0f64);
            for k in 0..t.t.len() {
                if t.t[k] > burst_end - 3.0 / F0 && t.t[k] <= burst_end {
                    spring = spring.max((t.beta[k] * t.beta[k] * c_t * t.gap[k]).abs());
                    tau = tau.max(t.tau[k].abs());
                }
            }
            spring / tau
        })
        .unwrap_or(f64::NAN);
    let (p0, mu) = (
        s.rccm
            .get("interface")
            .and_then(|i| i.get("static_pressure"))
            .and_then(|v| v.as_float())
            .unwrap_or(f64::NAN),
        s.rccm
            .get("interface")
            .and_then(|i| i.get("tangential"))
            .and_then(|t| t.get("friction"))
            .and_then(|v| v.as_float())
            .unwrap_or(f64::NAN),
    );
    out.figures.push(
        Figure::new(
            "shear_rccm_adhesion_friction",
            "Full RCCM law: adhesion against friction (thesis chapter 1, Figure 5)",
            format!(
                "examples/shear/rccm_shear.toml: aluminium half-spaces, p0 = {} MPa, RCCM \
                 traction C_N = 2e13 Pa/m, w = 0.1 J/m^2, tangential RCCM C_T = 1e13 Pa/m, mu \
                 = {} (friction limit mu p0 = {} MPa while in contact); a 15-cycle 1 MHz \
                 normal burst of 3 MPa (it opens the interface) and a 15-cycle 1 MHz shear \
                 burst two periods later, amplitude tau_inc. (a) adhesion beta against time, \
                 (b) tau against [u]_T at tau_inc = {} MPa, one loop every other cycle of the \
                 shear burst (light to dark): while beta is large the adhesive spring beta^2 \
                 C_T [u]_T carries the load beside friction (leaning loops); the normal and \
                 tangential gaps together damage beta towards 0 and the loops become the flat \
                 Coulomb ones at +-mu N, drifting as the interface slips. (c) beta at the end and (d) \
                 transmitted A3/A1 (band peak) against tau_inc, with the shear burst alone \
                 (no normal burst: damage needs a larger shear) and with no adhesion at all \
                 (traction-free Coulomb friction: the limit beta = 0; the damaged RCCM \
                 interface still differs over the burst's first, adhesive cycles).",
                fmt_value(p0 / 1e6),
                fmt_value(mu),
                fmt_value(mu * p0 / 1e6),
                fmt_value(RCCM_CASE_AMP / 1e6)
            ),
            vec![
                panel("(a) adhesion", "t (us)", "beta", beta_t),
                panel("(b) tau against [u]_T", "[u]_T (nm)", "tau (MPa)", loops),
                panel(
                    "(c) adhesion at the end",
                    "tau_inc (MPa)",
                    "beta_end",
                    series("beta_end", &[0, 1]),
                ),
                panel(
                    "(d) transmitted third harmonic",
                    "tau_inc (MPa)",
                    "A3/A1",
                    series("shear_tr_A3_over_A1", &[0, 1, 2]),
                ),
            ],
        )
        .compare(format!(
            "here: beta_end = {} with both bursts at tau_inc = {} MPa, {} with the shear \
             burst alone; over the last three periods of that burst the adhesive spring \
             beta^2 C_T [u]_T carries {} of the largest |tau|: friction carries the rest",
            fmt_value(beta_case),
            fmt_value(RCCM_CASE_AMP / 1e6),
            fmt_value(beta_shear_only),
            fmt_value(spring_share)
        )),
    );
    const NT: &str = "(not in the thesis) thesis chapter 1 states the law, Figure 5";
    out.findings.extend([
        finding("shear_rccm_beta_end", beta_case, "", NT, None),
        finding(
            "shear_rccm_beta_end_shear_only",
            beta_shear_only,
            "",
            "(not in the thesis) the same shear burst without the normal one",
            None,
        ),
        finding(
            "shear_rccm_beta_end_shear_only_8MPa",
            beta_top_shear_only,
            "",
            "(not in the thesis) a shear burst alone damages at large amplitude",
            None,
        ),
        finding(
            "shear_rccm_spring_share_end",
            spring_share,
            "",
            "(not in the thesis) damaged RCCM is Coulomb friction (beta -> 0): the adhesive spring's share of |tau| over the last 3 periods",
            None,
        ),
    ]);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_reflected_limits() {
        // no friction: nothing transmitted, the reflected wave is the incident one (no A3)
        let c = closed(0.0, 8.5e6);
        assert_eq!(closed_a3_over_a1(&c), (0.0, 0.0));
        // small friction: a square wave of amplitude c transmitted (A3/A1 = 1/3)
        let (tr, re) = closed_a3_over_a1(&closed(1e-4, 8.5e6));
        assert!((tr - 1.0 / 3.0).abs() < 1e-6 && re < 1e-3, "{tr} {re}");
        // stuck: no harmonics
        assert!(closed_a3_over_a1(&closed(1.2, 8.5e6)).0 < 1e-12);
    }
}

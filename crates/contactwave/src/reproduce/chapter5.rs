//! Thesis chapter 5 studies: PMMA, p0 = 0.14 MPa, 5 kHz, 15-cycle burst, rigid wall.
//!
//! 1. The bilinear law (linear compression C_N1 = 3e11 Pa/m, linear traction C_N2 = 1e10
//!    Pa/m) against its closed-form solution ([`crate::analytic::Bilinear`], thesis eqs.
//!    5.10-5.15): gap and stress of the exact and the finite-difference solvers (Figures
//!    78 and 80), the FD error against the space step (Figure 81), the contact and
//!    contact-loss durations of the periodic state against xi (Figure 79).
//! 2. Linear compression C_N1 in {2, 3, 6} e11 Pa/m with C_N2 = 1e10 Pa/m against RCCM
//!    (rigid compression, w = 1000 J/m^2: undamaged) and unilateral contact (Figures 83-87).
//! 3. The modified power law in compression with a linear traction spring (undamaged,
//!    Figures 89-94) and with RCCM traction (damaged, w = 0.1 J/m^2, and w in {0, 0.1,
//!    1000} J/m^2, Figures 96-101).

use super::{column, f, fmt_value, tv, Chapter, ChapterResult, Ctx, Edits, Figure, Finding};
use crate::analysis::Summary;
use crate::analytic::{Bilinear, BilinearSolution};
use crate::error::{Error, Result};
use crate::output::plot::{Panel, Series};

/// Static pressure, Pa.
const P0: f64 = 0.14e6;
/// Incident frequency, Hz.
const F0: f64 = 5e3;
/// Traction stiffness C_N2, Pa/m.
const KT: f64 = 1e10;
/// Compression stiffness of the bilinear reference case C_N1, Pa/m.
const KC: f64 = 3e11;
/// FD resolutions of the convergence study (samples per period, dx = c / (f0 spp)).
const FD_SPP: [i64; 5] = [125, 250, 500, 1000, 2000];

/// A contact law: a label and its compression and traction branches (TOML tables).
#[derive(Clone)]
struct Law {
    label: String,
    compression: toml::Value,
    traction: toml::Value,
}

impl Law {
    fn new(label: &str, compression: &str, traction: &str) -> Law {
        Law {
            label: label.into(),
            compression: tv(compression),
            traction: tv(traction),
        }
    }
    fn edits(&self) -> Edits {
        vec![
            ("interface.compression", self.compression.clone()),
            ("interface.traction", self.traction.clone()),
        ]
    }
    fn with_traction(&self, label: &str, traction: &str) -> Law {
        Law {
            label: label.into(),
            compression: self.compression.clone(),
            traction: tv(traction),
        }
    }
}

fn linear(k: f64) -> String {
    format!("{{ law = \"linear\", stiffness = {k:e} }}")
}

fn rccm(k: f64, w: f64) -> String {
    format!("{{ law = \"rccm\", stiffness = {k:e}, energy = {w:e}, viscosity = 1e-8 }}")
}

const RIGID: &str = "{ law = \"rigid\" }";
const FREE: &str = "{ law = \"free\" }";

/// The xi grid of the sweeps: 0.05 to 1.5 by 0.05.
fn xi_grid() -> Vec<f64> {
    (1..=30).map(|k| k as f64 / 20.0).collect()
}

/// Value of `y` at the grid point nearest to `x`.
fn at(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    xs.iter()
        .enumerate()
        .min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()))
        .and_then(|(i, _)| ys.get(i).copied())
        .unwrap_or(f64::NAN)
}

fn finding(key: &str, value: f64, unit: &str, thesis: &str, agrees: Option<bool>) -> Finding {
    Finding {
        key: key.into(),
        value,
        unit: unit.into(),
        thesis: thesis.into(),
        agrees,
        note: String::new(),
    }
}

fn panel(title: &str, xlabel: &str, ylabel: &str, series: Vec<Series>) -> Panel {
    Panel {
        title: title.into(),
        xlabel: xlabel.into(),
        ylabel: ylabel.into(),
        series,
        markers: Vec::new(),
    }
}

/// Interface histories of one run: time (s), gap (m), stress (Pa), cut after `t_end`.
struct Trace {
    t: Vec<f64>,
    gap: Vec<f64>,
    stress: Vec<f64>,
}

/// Runs of `base` with the edits, returning their interface histories up to `t_end` (s).
fn traces(
    ctx: &Ctx,
    study: &str,
    base: &toml::Table,
    variants: &[Edits],
    t_end: f64,
) -> Result<Vec<Trace>> {
    ctx.map(study, variants, |e| {
        let r = crate::simulate(&ctx.scenario(base, e)?)?;
        let io = r.interface;
        let n = io.t.partition_point(|&t| t <= t_end);
        Ok(Trace {
            t: io.t[..n].to_vec(),
            gap: io.gap[..n].to_vec(),
            stress: io.contact_stress[..n].to_vec(),
        })
    })
}

/// Panels of Figures 89-90 and 97-98: (a) stress against gap at `xi_loop`, then gap and
/// stress against time at `xi_signal`, one curve per law.
fn loops_and_signals(
    ctx: &Ctx,
    study: &str,
    base: &toml::Table,
    laws: &[Law],
    (xi_loop, xi_signal): (f64, f64),
    t_end: f64,
) -> Result<Vec<Panel>> {
    let labels: Vec<String> = laws.iter().map(|l| l.label.clone()).collect();
    let mut v = Vec::new();
    for x in [xi_loop, xi_signal] {
        for l in laws {
            let mut e = l.edits();
            e.push(("incident.xi", f(x)));
            v.push(e);
        }
    }
    let tr = traces(ctx, study, base, &v, t_end)?;
    let n = laws.len();
    let mut p = vec![loop_panel(
        &format!("(a) sigma against [u], xi = {xi_loop}"),
        &labels,
        &tr[..n],
    )];
    p.extend(
        trace_panels(&labels, &tr[n..], false)
            .into_iter()
            .map(|mut q| {
                q.title = format!("{}, xi = {xi_signal}", q.title);
                q
            }),
    );
    Ok(p)
}

/// Summaries of each law over the xi grid (one `Vec` per law), with `extra` edits.
fn sweep(
    ctx: &Ctx,
    study: &str,
    base: &toml::Table,
    laws: &[Law],
    xis: &[f64],
    extra: &Edits,
) -> Result<Vec<Vec<Summary>>> {
    let variants: Vec<Edits> = laws
        .iter()
        .flat_map(|l| {
            xis.iter().map(move |&x| {
                let mut e = extra.clone();
                e.extend(l.edits());
                e.push(("incident.xi", f(x)));
                e
            })
        })
        .collect();
    let s = ctx.summaries(study, base, &variants)?;
    Ok(s.chunks(xis.len().max(1)).map(|c| c.to_vec()).collect())
}

/// Series `key` (times `scale`) against xi, one per law.
/// The fundamental and second-harmonic panels against xi (`A1/A_inc`, `A2/A_inc`), titled
/// with the two letters given.
fn a1_a2_panels(letters: [&str; 2], laws: &[Law], xis: &[f64], s: &[Vec<Summary>]) -> [Panel; 2] {
    [
        panel(
            &format!("{} fundamental", letters[0]),
            "xi",
            "A1/A_inc",
            xi_series(laws, xis, s, "A1_over_Ainc"),
        ),
        panel(
            &format!("{} second harmonic", letters[1]),
            "xi",
            "A2/A_inc",
            xi_series(laws, xis, s, "A2_over_Ainc"),
        ),
    ]
}

fn xi_series(laws: &[Law], xis: &[f64], s: &[Vec<Summary>], key: &str) -> Vec<Series> {
    laws.iter()
        .zip(s)
        .map(|(l, s)| Series::new(l.label.clone(), xis, &column(s, key)))
        .collect()
}

/// Max |gap - analytic| / max |analytic| over `0 <= t <= t_max`.
fn gap_error(t: &[f64], gap: &[f64], sol: &BilinearSolution, t_max: f64) -> f64 {
    let (mut e, mut g) = (0.0f64, 0.0f64);
    for (&ti, &gi) in t.iter().zip(gap) {
        if !(0.0..=t_max).contains(&ti) {
            continue;
        }
        let a = sol.gap(ti);
        g = g.max(a.abs());
        e = e.max((gi - a).abs());
    }
    if g > 0.0 {
        e / g
    } else {
        f64::NAN
    }
}

/// Least-squares slope of log(y) against log(x).
fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| **a > 0.0 && **b > 0.0)
        .map(|(a, b)| (a.ln(), b.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

fn ms(t: &[f64]) -> Vec<f64> {
    t.iter().map(|v| v * 1e3).collect()
}
fn um(g: &[f64]) -> Vec<f64> {
    g.iter().map(|v| v * 1e6).collect()
}
fn mpa(s: &[f64]) -> Vec<f64> {
    s.iter().map(|v| v * 1e-6).collect()
}

/// Gap and stress against time (two panels) and stress against gap, for labelled traces.
fn trace_panels(labels: &[String], tr: &[Trace], loop_panel: bool) -> Vec<Panel> {
    let gap = labels
        .iter()
        .zip(tr)
        .map(|(l, t)| Series::new(l.clone(), &ms(&t.t), &um(&t.gap)))
        .collect();
    let stress = labels
        .iter()
        .zip(tr)
        .map(|(l, t)| Series::new(l.clone(), &ms(&t.t), &mpa(&t.stress)))
        .collect();
    let mut p = vec![
        panel("(a) gap at the interface", "t (ms)", "[u] (um)", gap),
        panel("(b) contact stress", "t (ms)", "sigma (MPa)", stress),
    ];
    if loop_panel {
        p.push(self::loop_panel(
            "(c) contact stress against gap",
            labels,
            tr,
        ));
    }
    p
}

/// Stress against gap only.
fn loop_panel(title: &str, labels: &[String], tr: &[Trace]) -> Panel {
    panel(
        title,
        "[u] (um)",
        "sigma (MPa)",
        labels
            .iter()
            .zip(tr)
            .map(|(l, t)| Series::new(l.clone(), &um(&t.gap), &mpa(&t.stress)))
            .collect(),
    )
}

/// Root-mean-square difference of two curves.
fn rms_diff(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()).max(1) as f64;
    (a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / n).sqrt()
}

/// Open (contact-loss) time per period of the analytical solution over `[ta, tb]`, s.
fn open_time_per_period(sol: &BilinearSolution, uc: f64, ta: f64, tb: f64, periods: f64) -> f64 {
    let mut open = sol.gap(ta) > uc;
    let mut last = ta;
    let mut total = 0.0;
    for (te, opens) in sol.events().filter(|e| e.0 > ta && e.0 < tb) {
        if open {
            total += te - last;
        }
        last = te;
        open = opens;
    }
    if open {
        total += tb - last;
    }
    total / periods
}

pub(crate) fn run(ctx: &Ctx) -> Result<ChapterResult> {
    let base = ctx.base("ch5_bilinear.toml")?;
    let mpl_base = ctx.base("ch5_modified_pl.toml")?;
    let mpl_compression = mpl_base
        .get("interface")
        .and_then(|v| v.get("compression"))
        .cloned()
        .ok_or_else(|| {
            Error::invalid(
                "examples/thesis/ch5_modified_pl.toml",
                "interface.compression",
                "(missing)",
                "a compression law",
            )
        })?;
    let period = 1.0 / F0;
    let mut figures = Vec::new();
    let mut findings = Vec::new();

    // ---------------------------------------------------------------------------------
    // 1. Bilinear: analytical against both solvers (Figures 78, 80, 81)
    // ---------------------------------------------------------------------------------
    let xi_bl = 0.5;
    let cycles = 15.0;
    let burst = cycles * period;
    let rect: Edits = vec![
        ("incident.window", toml::Value::String("rectangular".into())),
        ("incident.xi", f(xi_bl)),
        ("solver.tail_periods", f(2.0)),
    ];
    let sc = ctx.scenario(&base, &rect)?;
    let amplitude = sc.incident.peak();
    let z = sc.medium.impedance();
    let c = sc.medium.wave_speed();
    let bl = Bilinear {
        amplitude,
        omega: 2.0 * std::f64::consts::PI * F0,
        impedance: z,
        static_pressure: P0,
        compression_stiffness: KC,
        traction_stiffness: KT,
    };
    let sol = bl.solve(burst);
    let mut variants = vec![rect.clone()];
    for spp in FD_SPP {
        let mut e = rect.clone();
        e.push(("solver.method", toml::Value::String("fd".into())));
        e.push(("solver.samples_per_period", toml::Value::Integer(spp)));
        variants.push(e);
    }
    let tr = traces(
        ctx,
        "bilinear: exact and FD solvers",
        &base,
        &variants,
        burst,
    )?;
    let exact_err = gap_error(&tr[0].t, &tr[0].gap, &sol, burst);
    let fd_err: Vec<f64> = tr[1..]
        .iter()
        .map(|t| gap_error(&t.t, &t.gap, &sol, burst))
        .collect();
    let dx: Vec<f64> = FD_SPP.iter().map(|&n| c / (F0 * n as f64)).collect();
    let i_fd = FD_SPP.iter().position(|&n| n == 1000).unwrap_or(0);
    let fd_default = fd_err.get(i_fd).copied().unwrap_or(f64::NAN);
    let order = loglog_slope(&dx, &fd_err);
    let decreasing = fd_err.windows(2).all(|w| w[1] < w[0]);

    let f_exact = finding(
        "bilinear_max_rel_error",
        exact_err,
        "",
        "numerical and analytical bilinear solutions agree (Figure 80)",
        Some(exact_err < 1e-6),
    );
    let f_fd = finding(
        "ch5_fd_max_rel_error",
        fd_default,
        "",
        "FD error below 5% (Figure 81)",
        Some(fd_default < 0.05),
    );
    let f_order = finding(
        "ch5_fd_error_order",
        order,
        "",
        "the FD error decreases as the mesh is refined (Figure 81)",
        Some(decreasing && order > 0.5),
    );
    let t_an: Vec<f64> = tr[0].t.clone();
    let an_trace = Trace {
        gap: t_an.iter().map(|&t| sol.gap(t)).collect(),
        stress: t_an.iter().map(|&t| sol.stress(t)).collect(),
        t: t_an,
    };
    let fd_trace = &tr[1 + i_fd];
    let labels = vec![
        "analytical (eqs. 5.10-5.15)".to_string(),
        "exact solver (200 samples/period)".to_string(),
        format!("FD solver ({} samples/period)", FD_SPP[i_fd]),
    ];
    let three = [
        an_trace,
        Trace {
            t: tr[0].t.clone(),
            gap: tr[0].gap.clone(),
            stress: tr[0].stress.clone(),
        },
        Trace {
            t: fd_trace.t.clone(),
            gap: fd_trace.gap.clone(),
            stress: fd_trace.stress.clone(),
        },
    ];
    figures.push(
        Figure::new(
            "ch5_fig78_80_bilinear_analytic_vs_numerical",
            "Figures 78 and 80: bilinear law, analytical against the exact and FD solvers",
            format!(
                "Gap, contact stress and stress-gap loop at x = 0. PMMA, p0 = 0.14 MPa, \
                 f0 = 5 kHz, 15-cycle rectangular burst, xi = {xi_bl} (incident amplitude \
                 {} MPa), C_N1 = 3e11 Pa/m in compression, C_N2 = 1e10 Pa/m in traction. \
                 The analytical curve is the closed-form solution from rest (continuous law).",
                fmt_value(amplitude * 1e-6)
            ),
            trace_panels(&labels, &three, true),
        )
        .compare(f_exact.line())
        .compare(format!(
            "thesis: FD and analytical curves agree / here: FD max relative gap error {} at {} samples/period",
            fmt_value(fd_default),
            FD_SPP[i_fd]
        )),
    );
    let err_pct: Vec<f64> = fd_err.iter().map(|e| e * 100.0).collect();
    let dx_mm: Vec<f64> = dx.iter().map(|d| d * 1e3).collect();
    figures.push(
        Figure::new(
            "ch5_fig81_fd_error_vs_dx",
            "Figure 81: FD error against the space step",
            format!(
                "max |[u]_FD - [u]_analytic| / max |[u]_analytic| over the 15-cycle \
                 rectangular burst (xi = {xi_bl}, C_N1 = 3e11, C_N2 = 1e10 Pa/m, 5 kHz, \
                 wavelength {} m) for {} samples per period (Courant number 1, dx = c dt). \
                 The exact solver's error is {}.",
                fmt_value(c / F0),
                FD_SPP.map(|n| n.to_string()).join(", "),
                fmt_value(exact_err)
            ),
            vec![panel(
                "relative gap error",
                "dx (mm)",
                "error (%)",
                vec![Series::new("FD solver", &dx_mm, &err_pct)],
            )],
        )
        .compare(f_fd.line())
        .compare(f_order.line()),
    );
    findings.extend([f_exact, f_fd, f_order]);

    // Figure 79: durations of contact and contact loss in the periodic state.
    let xis79: Vec<f64> = (1..=26).map(|k| k as f64 * 0.05).collect();
    let amps: Vec<f64> = xis79
        .iter()
        .map(|&x| {
            let mut e = rect.clone();
            e.push(("incident.xi", f(x)));
            Ok(ctx.scenario(&base, &e)?.incident.peak())
        })
        .collect::<Result<_>>()?;
    let uc = P0 / KC;
    let open_of = |a: f64| {
        let s = Bilinear { amplitude: a, ..bl }.solve(40.0 * period);
        open_time_per_period(&s, uc, 30.0 * period, 40.0 * period, 10.0)
    };
    let open: Vec<f64> = amps.iter().map(|&a| open_of(a)).collect();
    // onset of contact loss: bisection on xi (amplitude ~ 1/xi)
    let a1 = amps.first().copied().unwrap_or(f64::NAN) * xis79.first().copied().unwrap_or(1.0);
    let (mut lo, mut hi) = (0.5, 1.5);
    for _ in 0..30 {
        let m = 0.5 * (lo + hi);
        if open_of(a1 / m) > 1e-9 * period {
            lo = m;
        } else {
            hi = m;
        }
    }
    let onset = 0.5 * (lo + hi);
    let f_onset = finding(
        "ch5_contact_loss_onset_xi",
        onset,
        "",
        "contact loss for xi < 1 only",
        Some((onset - 1.0).abs() < 0.01),
    );
    let closed: Vec<f64> = open.iter().map(|o| (period - o) * 1e3).collect();
    let open_ms: Vec<f64> = open.iter().map(|o| o * 1e3).collect();
    figures.push(
        Figure::new(
            "ch5_fig79_contact_durations_vs_xi",
            "Figure 79: contact and contact-loss durations against xi",
            format!(
                "Per period of the periodic state of the analytical bilinear solution \
                 (periods 30-40 from rest), C_N1 = 3e11, C_N2 = 1e10 Pa/m, p0 = 0.14 MPa, \
                 5 kHz (period {} ms); xi from eq. 5.9.",
                fmt_value(period * 1e3)
            ),
            vec![panel(
                "durations per period",
                "xi",
                "duration (ms)",
                vec![
                    Series::new("contact", &xis79, &closed),
                    Series::new("contact loss", &xis79, &open_ms),
                ],
            )],
        )
        .compare(f_onset.line()),
    );
    findings.push(f_onset);

    // ---------------------------------------------------------------------------------
    // 2. Linear compression against RCCM and unilateral (Figures 83-87)
    // ---------------------------------------------------------------------------------
    let kcs = [2e11, 3e11, 6e11];
    let mut laws: Vec<Law> = kcs
        .iter()
        .map(|&k| {
            Law::new(
                &format!("bilinear C_N1 = {}e11", k / 1e11),
                &linear(k),
                &linear(KT),
            )
        })
        .collect();
    let rccm_law = Law::new("RCCM (rigid, w = 1000)", RIGID, &rccm(KT, 1000.0));
    let unilateral = Law::new("unilateral", RIGID, FREE);
    laws.push(rccm_law.clone());
    laws.push(unilateral.clone());
    let xis = xi_grid();
    let none: Edits = Vec::new();
    // the Hann-ramped burst's own second-harmonic content: the floor of A2/A_inc (a linear
    // response reflects it unchanged); findings at xi > 1 are given above it
    let floor = crate::simulate(&ctx.scenario(&base, &vec![("incident.xi", f(1.5))])?)?
        .summary
        .get("incident_A2_over_Ainc")
        .unwrap_or(f64::NAN);
    let s_lin = sweep(
        ctx,
        "linear compression: A2 vs xi",
        &base,
        &laws,
        &xis,
        &none,
    )?;
    let a2: Vec<Vec<f64>> = s_lin.iter().map(|s| column(s, "A2_over_Ainc")).collect();
    let below1: Vec<usize> = (0..xis.len()).filter(|&i| xis[i] < 1.0).collect();
    let pick = |v: &[f64]| below1.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let dist: Vec<f64> = (0..3)
        .map(|k| rms_diff(&pick(&a2[k]), &pick(&a2[3])))
        .collect();
    let approaches = dist.windows(2).all(|w| w[1] < w[0]);
    let mut lin_findings = Vec::new();
    for (k, d) in kcs.iter().zip(&dist) {
        lin_findings.push(finding(
            &format!("ch5_linear_rccm_rms_a2_diff_{}e11", k / 1e11),
            *d,
            "",
            "distance of the bilinear A2/A_inc curve (xi < 1) to RCCM falls as C_N1 grows",
            None,
        ));
    }
    lin_findings.push(finding(
        "ch5_linear_approaches_rccm",
        dist[2] / dist[0],
        "",
        "response approaches RCCM as C_N1 grows (Figure 84a): ratio of the distances \
         for C_N1 = 6e11 and 2e11 below 1",
        Some(approaches && dist[2] < dist[0]),
    ));
    let lin_above1 = (0..xis.len())
        .filter(|&i| xis[i] > 1.05)
        .map(|i| a2[1][i] - floor)
        .fold(0.0f64, f64::max);
    lin_findings.push(finding(
        "ch5_linear_a2_above_xi_1",
        lin_above1,
        "",
        "no second harmonic for xi > 1 with linear compression (C_N1 = 3e11); here \
         A2/A_inc above the burst's floor",
        Some(lin_above1 < 1e-3),
    ));
    let bl6_u = at(&xis, &a2[2], 0.1) / at(&xis, &a2[4], 0.1);
    let (imax6, imaxu) = (
        super::argmax_refined(&xis, &a2[2]),
        super::argmax_refined(&xis, &a2[4]),
    );
    lin_findings.push(finding(
        "ch5_bilinear6e11_over_unilateral_a2_at_xi_0_1",
        bl6_u,
        "",
        "at low xi the bilinear law (C_N1 = 6e11) generates more A2 than unilateral contact",
        Some(bl6_u > 1.0),
    ));
    lin_findings.push(finding(
        "ch5_unilateral_a2_max_xi",
        imaxu,
        "",
        "unilateral A2 maximum near xi = 0.35 (chapter 3)",
        Some((imaxu - 0.35).abs() < 0.05),
    ));
    lin_findings.push(finding(
        "ch5_bilinear6e11_a2_max_xi",
        imax6,
        "",
        "the optimum depends on the compression/traction contrast",
        None,
    ));

    // Figure 83: stress-gap loops at xi = 0.1.
    let loop_variants: Vec<Edits> = laws
        .iter()
        .map(|l| {
            let mut e = l.edits();
            e.push(("incident.xi", f(0.1)));
            e
        })
        .collect();
    let t_show = burst + 2.0 * period;
    let loops = traces(
        ctx,
        "linear compression: loops",
        &base,
        &loop_variants,
        t_show,
    )?;
    let law_labels: Vec<String> = laws.iter().map(|l| l.label.clone()).collect();
    figures.push(Figure::new(
        "ch5_fig83_linear_compression_loops",
        "Figure 83: contact stress against gap, linear compression, RCCM, unilateral",
        "15-cycle Hann-ramped burst at 5 kHz, xi = 0.1, p0 = 0.14 MPa; C_N1 in {2, 3, 6}e11 \
         Pa/m with C_N2 = 1e10 Pa/m linear traction; RCCM: rigid compression, C_N = 1e10 Pa/m, \
         w = 1000 J/m^2, b = 1e-8 J s/m^2; unilateral: rigid, traction-free."
            .into(),
        vec![loop_panel(
            "sigma against [u], xi = 0.1",
            &law_labels,
            &loops,
        )],
    ));
    let mut fig84 = Figure::new(
        "ch5_fig84_linear_compression_a2_vs_xi",
        "Figure 84: A2/A_inc against xi, linear compression against RCCM and unilateral",
        "Reflected second harmonic over incident amplitude; 15-cycle Hann-ramped burst at \
         5 kHz, p0 = 0.14 MPa, xi from eq. 5.9 with each law's tangent compression stiffness. \
         (a) C_N1 in {2, 3, 6}e11 Pa/m, C_N2 = 1e10 Pa/m against RCCM (C_N = 1e10 Pa/m, \
         w = 1000 J/m^2, b = 1e-8); (b) C_N1 = 6e11 against unilateral contact."
            .into(),
        vec![
            panel(
                "(a) bilinear against RCCM",
                "xi",
                "A2/A_inc",
                xi_series(&laws[..4], &xis, &s_lin[..4], "A2_over_Ainc"),
            ),
            panel(
                "(b) bilinear C_N1 = 6e11 against unilateral",
                "xi",
                "A2/A_inc",
                vec![
                    Series::new(laws[2].label.clone(), &xis, &a2[2]),
                    Series::new(laws[4].label.clone(), &xis, &a2[4]),
                ],
            ),
        ],
    );
    for fd in &lin_findings {
        fig84 = fig84.compare(fd.line());
    }
    figures.push(fig84);
    findings.extend(lin_findings);

    // Figures 86-87: A2 against the normalised frequency omega Z / C_N2.
    let exps: Vec<f64> = (0..9).map(|k| 7.5 + 0.5 * k as f64).collect();
    let kts: Vec<f64> = exps.iter().map(|e| 10f64.powf(*e)).collect();
    let omega = 2.0 * std::f64::consts::PI * F0;
    let nf: Vec<f64> = kts.iter().map(|k| (omega * z / k).log10()).collect();
    let nf_laws: Vec<(String, f64)> = kcs
        .iter()
        .map(|&k| (format!("bilinear C_N1 = {}e11", k / 1e11), k))
        .chain(std::iter::once(("RCCM (rigid, w = 1000)".to_string(), 0.0)))
        .collect();
    let xi_nf = [0.1, 0.35, 0.8];
    let mut nf_variants = Vec::new();
    for &x in &xi_nf {
        for (_, kc) in &nf_laws {
            for &kt in &kts {
                let (comp, trac) = if *kc > 0.0 {
                    (linear(*kc), linear(kt))
                } else {
                    (RIGID.to_string(), rccm(kt, 1000.0))
                };
                nf_variants.push(vec![
                    ("interface.compression", tv(&comp)),
                    ("interface.traction", tv(&trac)),
                    ("incident.xi", f(x)),
                ]);
            }
        }
    }
    let s_nf = ctx.summaries(
        "linear compression: A2 vs normalised frequency",
        &base,
        &nf_variants,
    )?;
    let a2_nf = column(&s_nf, "A2_over_Ainc");
    let per_xi = nf_laws.len() * kts.len();
    let nf_panels: Vec<Panel> = xi_nf
        .iter()
        .enumerate()
        .map(|(ix, x)| {
            panel(
                &format!("xi = {x}"),
                "log10(omega Z / C_N2)",
                "A2/A_inc",
                nf_laws
                    .iter()
                    .enumerate()
                    .map(|(il, (label, _))| {
                        let o = ix * per_xi + il * kts.len();
                        Series::new(label.clone(), &nf, &a2_nf[o..o + kts.len()])
                    })
                    .collect(),
            )
        })
        .collect();
    figures.push(Figure::new(
        "ch5_fig86_87_a2_vs_normalised_frequency",
        "Figures 86-87: A2/A_inc against the normalised frequency (C_N2 varied)",
        format!(
            "C_N2 from 10^7.5 to 10^11.5 Pa/m (normalised frequency omega Z / C_N2, Z = {} Pa s/m, \
             5 kHz); bilinear C_N1 in {{2, 3, 6}}e11 Pa/m and RCCM (rigid, w = 1000 J/m^2, \
             b = 1e-8); xi = 0.1, 0.35, 0.8; p0 = 0.14 MPa, 15-cycle Hann-ramped burst.",
            fmt_value(z)
        ),
        nf_panels,
    ));

    // ---------------------------------------------------------------------------------
    // 3a. Modified PL compression, linear traction: undamaged (Figures 89-94)
    // ---------------------------------------------------------------------------------
    let mpl_lin = Law {
        label: "modified PL + linear traction".into(),
        compression: mpl_compression.clone(),
        traction: tv(&linear(KT)),
    };
    let und_laws = vec![
        mpl_lin.clone(),
        laws[1].clone(),
        rccm_law.clone(),
        unilateral.clone(),
    ];
    let s_mpl = sweep(
        ctx,
        "modified PL (undamaged): A1, A2 vs xi",
        &base,
        &und_laws[..1],
        &xis,
        &none,
    )?;
    let s_und = vec![
        s_mpl[0].clone(),
        s_lin[1].clone(),
        s_lin[3].clone(),
        s_lin[4].clone(),
    ];
    let a2_mpl = column(&s_und[0], "A2_over_Ainc");
    let a2_rigid = column(&s_und[2], "A2_over_Ainc");
    let a2_uni = column(&s_und[3], "A2_over_Ainc");
    let mpl15 = at(&xis, &a2_mpl, 1.5) - floor;
    let rig15 = at(&xis, &a2_rigid, 1.5) - floor;
    let uni15 = at(&xis, &a2_uni, 1.5) - floor;
    let lin15 = at(&xis, &a2[1], 1.5) - floor;
    let low = at(&xis, &a2_rigid, 0.1) / at(&xis, &a2_mpl, 0.1);
    // smallest xi from which the modified PL dominates RCCM for every larger xi
    let mut dominates = f64::NAN;
    for i in (0..xis.len()).rev() {
        if a2_mpl[i] > a2_rigid[i] {
            dominates = xis[i];
        } else {
            break;
        }
    }
    let mut mpl_findings = vec![
        finding(
            "ch5_a2_floor_hann_burst",
            floor,
            "",
            "(no thesis value) A2/A_inc of the 15-cycle Hann-ramped incident burst itself: \
             the floor of the analysis; the A2 findings at xi = 1.5 are given above it",
            None,
        ),
        finding(
            "ch5_mpl_a2_at_xi_1_5",
            mpl15,
            "",
            "with the modified PL in compression A2 does not vanish for xi > 1",
            Some(mpl15 > 1e-3),
        ),
        finding(
            "ch5_rigid_a2_at_xi_1_5",
            rig15,
            "",
            "rigid compression (RCCM): no second harmonic for xi > 1",
            Some(rig15 < 1e-3),
        ),
        finding(
            "ch5_unilateral_a2_at_xi_1_5",
            uni15,
            "",
            "unilateral contact: no second harmonic for xi > 1",
            Some(uni15 < 1e-3),
        ),
        finding(
            "ch5_linear_a2_at_xi_1_5",
            lin15,
            "",
            "linear compression (C_N1 = 3e11): no second harmonic for xi > 1",
            Some(lin15 < 1e-3),
        ),
        finding(
            "ch5_rigid_over_mpl_a2_at_xi_0_1",
            low,
            "",
            "rigid compression (RCCM) dominates at low xi",
            Some(low > 1.0),
        ),
        finding(
            "ch5_mpl_dominates_above_xi",
            dominates,
            "",
            "the modified PL dominates at high xi (no number given)",
            Some(dominates.is_finite() && dominates < 1.0),
        ),
    ];
    // Figures 89-90: loops at xi = 0.1, time signals at xi = 0.8.
    let und3 = [mpl_lin.clone(), laws[1].clone(), rccm_law.clone()];
    let und_panels = loops_and_signals(
        ctx,
        "modified PL (undamaged): signals",
        &base,
        &und3,
        (0.1, 0.8),
        t_show,
    )?;
    figures.push(Figure::new(
        "ch5_fig89_90_mpl_undamaged_signals",
        "Figures 89-90: modified PL (linear traction) against linear compression and RCCM",
        "(a) Contact stress against gap at xi = 0.1; (b, c) gap and stress against time at \
         xi = 0.8. Modified PL: C = 1.81e10 Pa^(1-m)/m, m = 0.35 (power law above 0.2 MPa) \
         with linear traction C_N2 = 1e10 Pa/m; linear: C_N1 = 3e11, C_N2 = 1e10 Pa/m; RCCM: \
         rigid, C_N = 1e10 Pa/m, w = 1000 J/m^2, b = 1e-8. p0 = 0.14 MPa, 5 kHz, 15-cycle \
         Hann-ramped burst."
            .into(),
        und_panels,
    ));
    // Figure 91: contact loss / contact duration ratio.
    let ratio = |s: &[Summary]| -> Vec<f64> {
        column(s, "contact_loss_fraction")
            .iter()
            .map(|c| if *c < 1.0 { c / (1.0 - c) } else { f64::NAN })
            .collect()
    };
    figures.push(Figure::new(
        "ch5_fig91_contact_loss_ratio_vs_xi",
        "Figure 91: ratio of contact-loss to contact durations against xi",
        "Open time over closed time during the burst (contact_loss_fraction f: f/(1-f)); \
         laws as in Figures 89-90, p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        vec![panel(
            "contact loss / contact",
            "xi",
            "ratio",
            und_laws[..3]
                .iter()
                .zip(&s_und)
                .map(|(l, s)| Series::new(l.label.clone(), &xis, &ratio(s)))
                .collect(),
        )],
    ));
    let mut fig92 = Figure::new(
        "ch5_fig92_mpl_undamaged_a1_a2_vs_xi",
        "Figure 92: A1/A_inc and A2/A_inc against xi, modified PL (undamaged)",
        "Modified PL + linear traction C_N2 = 1e10 Pa/m, linear C_N1 = 3e11 + C_N2 = 1e10, \
         RCCM (rigid, C_N = 1e10, w = 1000 J/m^2, b = 1e-8), unilateral; p0 = 0.14 MPa, \
         5 kHz, 15-cycle Hann-ramped burst; xi from eq. 5.9 with each law's tangent stiffness \
         at p0."
            .into(),
        a1_a2_panels(["(a)", "(b)"], &und_laws, &xis, &s_und).into(),
    );
    for fd in &mpl_findings {
        fig92 = fig92.compare(fd.line());
    }
    figures.push(fig92);

    // Figure 94: modified PL with different traction stiffnesses.
    let kt_laws: Vec<Law> = [1e9, 1e10, 1e11]
        .iter()
        .map(|&k| mpl_lin.with_traction(&format!("C_N2 = {k:.0e}"), &linear(k)))
        .collect();
    let s_kt_new = sweep(
        ctx,
        "modified PL: traction stiffness",
        &base,
        &[kt_laws[0].clone(), kt_laws[2].clone()],
        &xis,
        &none,
    )?;
    let s_kt = vec![s_kt_new[0].clone(), s_und[0].clone(), s_kt_new[1].clone()];
    let hi: Vec<usize> = (0..xis.len()).filter(|&i| xis[i] > 1.05).collect();
    let spread = hi
        .iter()
        .map(|&i| {
            let v: Vec<f64> = s_kt
                .iter()
                .map(|s| s[i].get("A2_over_Ainc").unwrap_or(f64::NAN))
                .collect();
            let mx = v.iter().cloned().fold(f64::MIN, f64::max);
            let mn = v.iter().cloned().fold(f64::MAX, f64::min);
            if mx > 0.0 {
                (mx - mn) / mx
            } else {
                0.0
            }
        })
        .fold(0.0f64, f64::max);
    let f_spread = finding(
        "ch5_mpl_traction_spread_above_xi_1",
        spread,
        "",
        "for xi > 1 the curves of all C_N2 overlap (only the modified PL acts)",
        Some(spread < 0.05),
    );
    figures.push(
        Figure::new(
            "ch5_fig94_mpl_a2_vs_xi_traction_stiffness",
            "Figure 94: A2/A_inc against xi, modified PL with C_N2 in {1e9, 1e10, 1e11}",
            "Modified PL compression (C = 1.81e10, m = 0.35) with linear traction of stiffness \
             C_N2; p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
                .into(),
            vec![panel(
                "second harmonic",
                "xi",
                "A2/A_inc",
                xi_series(&kt_laws, &xis, &s_kt, "A2_over_Ainc"),
            )],
        )
        .compare(f_spread.line()),
    );
    mpl_findings.push(f_spread);
    findings.extend(mpl_findings);

    // ---------------------------------------------------------------------------------
    // 3b. RCCM traction, damaged (w = 0.1) and w in {0, 0.1, 1000} (Figures 96-101)
    // ---------------------------------------------------------------------------------
    let w_dmg = 0.1;
    let dmg_laws = vec![
        Law {
            label: "modified PL + RCCM".into(),
            compression: mpl_compression.clone(),
            traction: tv(&rccm(KT, w_dmg)),
        },
        Law::new("linear 3e11 + RCCM", &linear(KC), &rccm(KT, w_dmg)),
        Law::new("rigid + RCCM", RIGID, &rccm(KT, w_dmg)),
    ];
    let ws = [0.0, 0.1, 1000.0];
    let w_laws: Vec<Law> = ws
        .iter()
        .map(|&w| {
            let label = format!("w = {w} J/m^2");
            dmg_laws[0].with_traction(&label, &rccm(KT, w))
        })
        .collect();
    let all: Vec<Law> = dmg_laws
        .iter()
        .chain([&w_laws[0], &w_laws[2]])
        .cloned()
        .collect();
    let s_all = sweep(ctx, "RCCM traction (damage)", &base, &all, &xis, &none)?;
    let s_dmg = &s_all[..3];
    let s_w = vec![s_all[3].clone(), s_all[0].clone(), s_all[4].clone()];
    let stiff = |s: &[Summary]| -> Vec<f64> {
        column(s, "beta_end")
            .iter()
            .map(|b| b * b * KT * 1e-9)
            .collect::<Vec<f64>>()
    };
    let onset = |s: &[Summary]| -> f64 {
        let b = column(s, "beta_end");
        (0..xis.len())
            .filter(|&i| b[i] < 0.99)
            .map(|i| xis[i])
            .fold(f64::NAN, f64::max)
    };
    let on_w: Vec<f64> = s_w.iter().map(|s| onset(s)).collect();
    let mpl_d15 = at(&xis, &column(&s_dmg[0], "A2_over_Ainc"), 1.5) - floor;
    let rig_d15 = at(&xis, &column(&s_dmg[2], "A2_over_Ainc"), 1.5) - floor;
    let rig_d01 = at(&xis, &column(&s_dmg[2], "A2_over_Ainc"), 0.1)
        / at(&xis, &column(&s_dmg[0], "A2_over_Ainc"), 0.1);
    let dmg_findings = vec![
        finding(
            "ch5_damaged_mpl_a2_at_xi_1_5",
            mpl_d15,
            "",
            "damaged interface: the modified PL dominates at high xi",
            Some(mpl_d15 > rig_d15),
        ),
        finding(
            "ch5_damaged_rigid_over_mpl_a2_at_xi_0_1",
            rig_d01,
            "",
            "damaged interface: RCCM (rigid) dominates at low xi",
            Some(rig_d01 > 1.0),
        ),
        finding(
            "ch5_damage_onset_xi_w0_1",
            on_w[1],
            "",
            "damage (beta_end < 0.99) below some xi, earlier (higher xi) for lower w",
            None,
        ),
        finding(
            "ch5_damage_onset_xi_w1000",
            on_w[2],
            "",
            "w = 1000 J/m^2: undamaged (NaN: no damage on the grid) or damaged only at the lowest xi",
            None,
        ),
        finding(
            "ch5_beta_end_mpl_w0_1_at_xi_0_1",
            at(&xis, &column(&s_dmg[0], "beta_end"), 0.1),
            "",
            "adhesion decreases as the amplitude grows (Figure 96)",
            None,
        ),
    ];
    let mut fig96 = Figure::new(
        "ch5_fig96_damage_vs_xi",
        "Figure 96: final adhesion and traction stiffness against xi (damaged interface)",
        "beta_end and beta_end^2 C_N2 at the end of each run; RCCM traction C_N2 = 1e10 Pa/m, \
         w = 0.1 J/m^2, b = 1e-8 J s/m^2 (Table 8) with modified PL, linear (3e11 Pa/m) or \
         rigid compression; p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        vec![
            panel(
                "(a) adhesion intensity",
                "xi",
                "beta_end",
                xi_series(&dmg_laws, &xis, s_dmg, "beta_end"),
            ),
            panel(
                "(b) traction stiffness",
                "xi",
                "beta_end^2 C_N2 (GPa/m)",
                dmg_laws
                    .iter()
                    .zip(s_dmg)
                    .map(|(l, s)| Series::new(l.label.clone(), &xis, &stiff(s)))
                    .collect(),
            ),
        ],
    );
    for fd in &dmg_findings[2..] {
        fig96 = fig96.compare(fd.line());
    }
    figures.push(fig96);
    // Figures 97-98: loops at xi = 0.1 and signals at xi = 0.36.
    let dmg_panels = loops_and_signals(
        ctx,
        "RCCM traction (damage): signals",
        &base,
        &dmg_laws,
        (0.1, 0.36),
        t_show,
    )?;
    figures.push(Figure::new(
        "ch5_fig97_98_damaged_signals",
        "Figures 97-98: damaged interface, loops and time signals",
        "(a) Contact stress against gap at xi = 0.1; (b, c) gap and stress against time at \
         xi = 0.36. RCCM traction C_N2 = 1e10 Pa/m, w = 0.1 J/m^2, b = 1e-8 with modified PL, \
         linear (3e11 Pa/m) or rigid compression; p0 = 0.14 MPa, 5 kHz."
            .into(),
        dmg_panels,
    ));
    let mut fig99 = Figure::new(
        "ch5_fig99_damaged_a1_a2_vs_xi",
        "Figure 99: A1/A_inc and A2/A_inc against xi (damaged interface)",
        "RCCM traction C_N2 = 1e10 Pa/m, w = 0.1 J/m^2, b = 1e-8 with modified PL, linear \
         (3e11 Pa/m) or rigid compression; p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        a1_a2_panels(["(a)", "(b)"], &dmg_laws, &xis, s_dmg).into(),
    );
    for fd in &dmg_findings[..2] {
        fig99 = fig99.compare(fd.line());
    }
    figures.push(fig99);
    let f_w = finding(
        "ch5_damage_onset_xi_w0",
        on_w[0],
        "",
        "higher w: damage starts at lower xi; w = 0 damages at any amplitude with contact loss",
        Some(!(on_w[0] < on_w[1]) && !(on_w[1] < on_w[2])),
    );
    figures.push(
        Figure::new(
            "ch5_fig100_101_decohesion_energy",
            "Figures 100-101: modified PL + RCCM, decohesion energy w in {0, 0.1, 1000} J/m^2",
            "beta_end, beta_end^2 C_N2, A1/A_inc and A2/A_inc against xi; modified PL compression \
             (C = 1.81e10, m = 0.35), RCCM traction C_N2 = 1e10 Pa/m, b = 1e-8 J s/m^2; \
             p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst (w = 0: damage at the \
             first opening)."
                .into(),
            [
                panel(
                    "(a) adhesion intensity",
                    "xi",
                    "beta_end",
                    xi_series(&w_laws, &xis, &s_w, "beta_end"),
                ),
                panel(
                    "(b) traction stiffness",
                    "xi",
                    "beta_end^2 C_N2 (GPa/m)",
                    w_laws
                        .iter()
                        .zip(&s_w)
                        .map(|(l, s)| Series::new(l.label.clone(), &xis, &stiff(s)))
                        .collect(),
                ),
            ]
            .into_iter()
            .chain(a1_a2_panels(["(c)", "(d)"], &w_laws, &xis, &s_w))
            .collect(),
        )
        .compare(f_w.line()),
    );
    findings.extend(dmg_findings);
    findings.push(f_w);

    Ok(ChapterResult {
        chapter: Chapter::Five,
        title: "Chapter 5: nonlinear compression with adhesion (PMMA, 5 kHz)".into(),
        intro: "PMMA (E = 5 GPa, rho = 1190 kg/m^3) against a rigid wall, static pressure \
                p0 = 0.14 MPa, 15-cycle 5 kHz burst (Hann ramps unless stated), exact \
                half-space solver unless stated. The bilinear law (C_N1 = 3e11, C_N2 = 1e10 \
                Pa/m) is checked against its closed-form solution with both solvers; then \
                linear, modified power-law and rigid compression are combined with linear or \
                RCCM (damageable) traction. xi is the generalised load ratio of eq. 5.9."
            .into(),
        figures,
        findings,
        seconds: 0.0,
        runs: 0,
    })
}

#[cfg(test)]
mod tests {
    use super::super::{run_chapter, Chapter};

    #[test]
    fn chapter5_physics() {
        let r = run_chapter(Chapter::Five, &|_, _, _| {}).unwrap();
        let get = |k: &str| {
            r.findings
                .iter()
                .find(|f| f.key == k)
                .unwrap_or_else(|| panic!("finding {k}"))
                .value
        };
        eprintln!("chapter 5: {:.2} s, {} runs", r.seconds, r.runs);
        for f in &r.findings {
            eprintln!("{} = {}", f.key, f.value);
        }
        let e = get("bilinear_max_rel_error");
        assert!(e < 1e-6, "bilinear_max_rel_error {e}");
        assert!(get("ch5_fd_max_rel_error") < 0.05);
        assert!(get("ch5_fd_error_order") > 0.5);
        let fig = r
            .figures
            .iter()
            .find(|f| f.id == "ch5_fig81_fd_error_vs_dx")
            .unwrap();
        let pts = &fig.panels[0].series[0].points;
        // dx decreases along the series: the error must decrease too
        assert!(pts.windows(2).all(|w| w[1].0 < w[0].0 && w[1].1 < w[0].1));
        assert!(get("ch5_mpl_a2_at_xi_1_5") > 1e-3);
        assert!(get("ch5_rigid_a2_at_xi_1_5") < 1e-3);
        assert!(get("ch5_linear_approaches_rccm") < 1.0);
        let d: Vec<f64> = ["2e11", "3e11", "6e11"]
            .iter()
            .map(|k| get(&format!("ch5_linear_rccm_rms_a2_diff_{k}")))
            .collect();
        assert!(d[0] > d[1] && d[1] > d[2], "{d:?}");
        assert!((get("ch5_contact_loss_onset_xi") - 1.0).abs() < 0.01);
        for f in &r.figures {
            f.svg().unwrap();
        }
    }
}

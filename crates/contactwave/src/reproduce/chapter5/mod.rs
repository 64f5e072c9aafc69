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
//!
//! One file per section (`bilinear`, `linear`, `modified_pl`, `damage`), one function per
//! figure or group of figures; [`run`] calls them in report order. This file holds the
//! shared set-up ([`Setup`]), the contact laws and the panel helpers.

mod bilinear;
mod damage;
mod linear;
mod modified_pl;
mod weak;

use super::{column, f, finding, panel, tv, Chapter, ChapterResult, Ctx, Edits, Figure, Finding};
use crate::analysis::Summary;
use crate::analytic::Bilinear;
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
/// xi of the bilinear reference runs (Figures 78, 80 and 81).
const XI_BL: f64 = 0.5;

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

/// Series `key` against xi, one per law.
fn xi_series(laws: &[Law], xis: &[f64], s: &[Vec<Summary>], key: &str) -> Vec<Series> {
    laws.iter()
        .zip(s)
        .map(|(l, s)| Series::new(l.label.clone(), xis, &column(s, key)))
        .collect()
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

/// Shared set-up of the chapter: the base scenarios and the parameters that several figure
/// groups use.
struct Setup {
    /// Base scenario of every run (`ch5_bilinear.toml`).
    base: toml::Table,
    /// The modified power law in compression (`interface.compression` of
    /// `ch5_modified_pl.toml`).
    mpl_compression: toml::Value,
    /// Incident period, s.
    period: f64,
    /// Duration of the 15-cycle burst, s.
    burst: f64,
    /// End of the time signals shown: the burst and two periods, s.
    t_show: f64,
    /// The xi grid of the sweeps ([`xi_grid`]).
    xis: Vec<f64>,
    /// Edits of the bilinear reference runs: rectangular burst at xi = [`XI_BL`], two tail
    /// periods.
    rect: Edits,
    /// The bilinear reference problem (closed form) at the amplitude of `rect`.
    bl: Bilinear,
    /// Impedance of the medium, Pa s/m.
    z: f64,
    /// Wave speed of the medium, m/s.
    c: f64,
}

impl Setup {
    fn new(ctx: &Ctx) -> Result<Setup> {
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
        let cycles = 15.0;
        let burst = cycles * period;
        let rect: Edits = vec![
            ("incident.window", toml::Value::String("rectangular".into())),
            ("incident.xi", f(XI_BL)),
            ("solver.tail_periods", f(2.0)),
        ];
        let sc = ctx.scenario(&base, &rect)?;
        let z = sc.medium.impedance();
        let c = sc.medium.wave_speed();
        let bl = Bilinear {
            amplitude: sc.incident.peak(),
            omega: 2.0 * std::f64::consts::PI * F0,
            impedance: z,
            static_pressure: P0,
            compression_stiffness: KC,
            traction_stiffness: KT,
        };
        Ok(Setup {
            base,
            mpl_compression,
            period,
            burst,
            t_show: burst + 2.0 * period,
            xis: xi_grid(),
            rect,
            bl,
            z,
            c,
        })
    }
}

/// Figures and findings as the figure groups add them, in report order.
#[derive(Default)]
struct Collected {
    figures: Vec<Figure>,
    findings: Vec<Finding>,
}

/// A2/A_inc of the 15-cycle Hann-ramped incident burst itself (one run at xi = 1.5): the
/// floor of the analysis (a linear response reflects it unchanged); findings at xi > 1 are
/// given above it.
fn a2_floor(ctx: &Ctx, setup: &Setup) -> Result<f64> {
    Ok(
        crate::simulate(&ctx.scenario(&setup.base, &vec![("incident.xi", f(1.5))])?)?
            .summary
            .get("incident_A2_over_Ainc")
            .unwrap_or(f64::NAN),
    )
}

/// Run the chapter: each figure group adds its figure(s) and the findings they compare, in
/// report order (the order of the calls is that of the figures, of `findings.json` and of
/// the studies run).
pub(crate) fn run(ctx: &Ctx) -> Result<ChapterResult> {
    let s = Setup::new(ctx)?;
    let mut out = Collected::default();

    // 1. The bilinear law against its closed-form solution
    let bl = bilinear::runs(ctx, &s)?;
    bilinear::signals(&s, &bl, &mut out); // Figures 78, 80
    bilinear::fd_error(&s, &bl, &mut out); // Figure 81
    bilinear::contact_durations(ctx, &s, &mut out)?; // Figure 79

    // 2. Linear compression against RCCM and unilateral contact
    let floor = a2_floor(ctx, &s)?;
    let lin = linear::sweep_laws(ctx, &s)?;
    linear::loops(ctx, &s, &lin, &mut out)?; // Figure 83
    linear::a2_vs_xi(&s, &lin, floor, &mut out); // Figure 84
    linear::normalised_frequency(ctx, &s, &mut out)?; // Figures 86-87

    // 3a. Modified PL compression, linear traction: undamaged
    let und = modified_pl::sweep_undamaged(ctx, &s, &lin)?;
    modified_pl::signals(ctx, &s, &und, &mut out)?; // Figures 89-90
    modified_pl::contact_loss_ratio(&s, &und, &mut out); // Figure 91
    modified_pl::a1_a2_vs_xi(&s, &und, floor, &mut out); // Figure 92
    modified_pl::traction_stiffness(ctx, &s, &und, &mut out)?; // Figure 94

    // 3b. RCCM traction: damaged (w = 0.1) and decohesion energy
    let dmg = damage::sweep_damaged(ctx, &s)?;
    let dmg_findings = damage::findings(&s, &dmg, floor);
    damage::damage_vs_xi(&s, &dmg, &dmg_findings[2..], &mut out); // Figure 96
    damage::signals(ctx, &s, &dmg, &mut out)?; // Figures 97-98
    damage::a1_a2_vs_xi(&s, &dmg, &dmg_findings[..2], &mut out); // Figure 99
    out.findings.extend(dmg_findings); // those compared in Figures 96 and 99
    damage::decohesion_energy(&s, &dmg, &mut out); // Figures 100-101

    // 4. Weak nonlinearity (not in the thesis): the analysis methods against the
    //    second-order perturbation solution (model.md sections 6.1, 8.1)
    weak::figure(ctx, &mut out)?;

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
        figures: out.figures,
        findings: out.findings,
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

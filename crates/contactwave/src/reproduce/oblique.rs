//! Beyond the thesis, oblique incidence (issue 14, model.md section 14): the second harmonic
//! of the reflected P wave against the static pressure at 0, 22.5 and 45 degrees, a section
//! of the shear chapter ([`super::shear`]). Two aluminium half-spaces pressed together, the
//! thesis' power-law fit of the Al-Al contact stiffness (`K = C p^m`, C = 1.81e10, m = 0.35,
//! Table 2) and rigid-stick Coulomb friction (mu = 0.3), hit by a 1 MHz P wave of 1 MPa
//! (`examples/oblique/p_45deg.toml`), exact coupled solver.
//!
//! Each outgoing wave is analysed by pulse inversion (a second solve with the burst
//! negated; the even harmonics from the sum of the two responses, where every linear part
//! cancels): at these amplitudes the reflected wave's A2/A1 lies at or below the band-peak
//! method's leakage floor. At each curve's maximum the plateau fit (least squares over the
//! burst's flat top, a different extraction) and the band peak are run as checks.

use super::{
    argmax_refined, column, f, finding, fmt_value, panel, tv, Ctx, Edits, Figure, Finding,
};
use crate::error::Result;
use crate::output::plot::Series;

/// Angles of incidence, degrees.
const ANGLES: [f64; 3] = [0.0, 22.5, 45.0];
/// Static pressures: `10^2` to `10^7` Pa, this many points evenly spaced in log10.
const N_P0: usize = 21;
/// log10 of the lowest and highest static pressure (Pa).
const LOG_P0: (f64, f64) = (2.0, 7.0);
/// Samples per period (A2/A1 within 0.5 % of 100 samples per period on this grid).
const SPP: i64 = 40;
/// Friction coefficient of the no-slip series (the interface sticks unless it opens).
const STICK_MU: f64 = 1e3;
/// Largest relative difference between pulse inversion and the plateau fit at the maxima
/// taken as agreement.
const METHOD_TOL: f64 = 0.05;

/// Summary key of the figure.
const KEY: &str = "reflected_P_A2_over_A1";

fn log_p0() -> Vec<f64> {
    super::lin(LOG_P0.0, LOG_P0.1, N_P0)
}

/// The variant at `angle` (degrees), `p0` (Pa), analysed by `method`.
fn edits(angle: f64, p0: f64, method: &str) -> Edits {
    vec![
        ("incident.angle", f(angle)),
        ("interface.static_pressure", f(p0)),
        ("analysis.method", toml::Value::String(method.into())),
        ("solver.samples_per_period", toml::Value::Integer(SPP)),
    ]
}

/// `0`, `22p5`, `45`: the angle (degrees, a multiple of 0.5) in a finding's key.
fn tag(angle: f64) -> String {
    if angle.fract() == 0.0 {
        format!("{angle:.0}")
    } else {
        format!("{angle:.1}").replace('.', "p")
    }
}

/// Run the section: its figure and findings are appended to the chapter's.
pub(super) fn run(ctx: &Ctx, figures: &mut Vec<Figure>, findings: &mut Vec<Finding>) -> Result<()> {
    let base = ctx.base("oblique_p.toml")?;
    let lp = log_p0();
    let p0: Vec<f64> = lp.iter().map(|x| 10f64.powf(*x)).collect();
    let mut variants: Vec<Edits> = Vec::new();
    for a in ANGLES {
        variants.extend(p0.iter().map(|&p| edits(a, p, "pulse_inversion")));
    }
    let stick = tv(&format!(
        "{{ law = \"coulomb\", friction = {STICK_MU:.1} }}"
    ));
    variants.extend(p0.iter().map(|&p| {
        let mut e = edits(45.0, p, "pulse_inversion");
        e.push(("interface.tangential", stick.clone()));
        e
    }));
    let all = ctx.summaries("oblique: pressure sweeps", &base, &variants)?;
    let part = |k: usize| &all[k * N_P0..(k + 1) * N_P0];
    let lg = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x.log10()).collect() };

    // the maxima, and the checks at each one's grid point
    let mut maxima = Vec::new();
    let mut checks: Vec<Edits> = Vec::new();
    for (k, &a) in ANGLES.iter().enumerate() {
        let y = column(part(k), KEY);
        let i = (0..N_P0)
            .max_by(|&u, &v| y[u].total_cmp(&y[v]))
            .unwrap_or(0);
        let x_max = argmax_refined(&lp, &y);
        maxima.push((i, y[i], 10f64.powf(x_max)));
        checks.push(edits(a, p0[i], "plateau_fit"));
        checks.push(edits(a, p0[i], "band_peak"));
    }
    let c = ctx.summaries("oblique: analysis checks", &base, &checks)?;
    let check = column(&c, KEY);
    let mut pi_vs_fit: f64 = 0.0;
    let mut bp_over_pi: f64 = 0.0;
    for (k, m) in maxima.iter().enumerate() {
        pi_vs_fit = pi_vs_fit.max((check[2 * k] / m.1 - 1.0).abs());
        bp_over_pi = bp_over_pi.max(check[2 * k + 1] / m.1);
    }
    let stick_y = column(part(3), KEY);
    let stick_max = stick_y.iter().copied().fold(0.0f64, f64::max);
    let closure = (0..4)
        .flat_map(|k| column(part(k), "energy_closure_error"))
        .fold(0.0f64, |m, e| m.max(e.abs()));

    let label = |a: f64| format!("{} deg", tag(a).replace('p', "."));
    let mut curves = Vec::new();
    let mut log_curves = Vec::new();
    let mut mech = Vec::new();
    for (k, &a) in ANGLES.iter().enumerate() {
        let y = column(part(k), KEY);
        curves.push(Series::new(label(a), &lp, &y));
        log_curves.push(Series::new(label(a), &lp, &lg(&y)));
        if a > 0.0 {
            let slip = column(part(k), "slip_fraction");
            mech.push(Series::new(format!("slip, {}", label(a)), &lp, &slip));
        }
        let open = column(part(k), "contact_loss_fraction");
        mech.push(Series::new(format!("open, {}", label(a)), &lp, &open));
    }
    log_curves.push(Series::new("45 deg, no slip", &lp, &lg(&stick_y)));
    let xl = "log10(p0 / Pa)";
    let mut fig = Figure::new(
        "oblique_a2_vs_pressure",
        "Second harmonic of the reflected P wave against the static pressure at 0, 22.5 and 45 degrees",
        format!(
            "Beyond the thesis (model.md section 14). Two aluminium half-spaces, power-law \
             contact stiffness K = C p^m (C = 1.81e10 Pa^(1-m)/m, m = 0.35: the thesis' Al-Al \
             fit, Table 2), rigid-stick Coulomb friction mu = 0.3; a 1 MHz P wave, 10-cycle \
             Hann-ramped burst of 1 MPa wave stress, at 0, 22.5 and 45 degrees; p0 from \
             1e{} to 1e{} Pa ({N_P0} points per angle); exact coupled solver, {SPP} samples per \
             period. A2/A1 of the reflected P wave (its particle velocity along its \
             polarisation, summary key {KEY}) by pulse inversion: a second solve with the \
             burst negated, the second harmonic from the sum of the two responses, where the \
             linear response and the fundamental's leakage cancel exactly. Compared at each \
             maximum: the plateau fit (least squares over the burst's flat top) and the \
             band-peak method (the thesis' band filter, whose leakage floor is of the order \
             of these values). (b) the same on a log scale, with the 45-degree case without \
             slip (mu = {STICK_MU:.0}). (c) fraction of the burst during which the interface \
             slips or is open.",
            LOG_P0.0, LOG_P0.1
        ),
        vec![
            panel("(a) reflected P wave", xl, "A2/A1", curves),
            panel(
                "(b) log scale; 45 degrees without slip",
                xl,
                "log10(A2/A1)",
                log_curves,
            ),
            panel(
                "(c) slip and contact loss",
                xl,
                "fraction of the burst",
                mech,
            ),
        ],
    );
    fig = fig.compare(format!(
        "pulse inversion / plateau fit at the maxima: max relative difference {}; band peak / \
         pulse inversion up to {} (leakage); 45 degrees: largest A2/A1 {} with friction, {} \
         without slip",
        fmt_value(pi_vs_fit),
        fmt_value(bp_over_pi),
        fmt_value(maxima[2].1),
        fmt_value(stick_max)
    ));
    figures.push(fig);

    const EXP: &str = "(not in the thesis) experiments on pressed aluminium blocks at 0, 22.5 \
                       and 45 degrees: the second harmonic goes through a maximum against \
                       pressure, of a different height at each angle";
    for (k, &a) in ANGLES.iter().enumerate() {
        let (_, height, p_max) = maxima[k];
        findings.push(finding(
            &format!("oblique_A2_over_A1_max_{}deg", tag(a)),
            height,
            "",
            EXP,
            None,
        ));
        findings.push(finding(
            &format!("oblique_A2_max_pressure_{}deg", tag(a)),
            p_max,
            "Pa",
            "(not in the thesis) static pressure of the maximum (parabola through log10 p0)",
            None,
        ));
    }
    findings.extend([
        finding(
            "oblique_A2_over_A1_max_45deg_no_slip",
            stick_max,
            "",
            "(not in the thesis) 45 degrees with the interface sticking (mu = 1000)",
            None,
        ),
        finding(
            "oblique_pulse_inversion_vs_plateau_fit",
            pi_vs_fit,
            "",
            "(not in the thesis) A2/A1 at the maxima by two extractions: relative difference",
            Some(pi_vs_fit < METHOD_TOL),
        ),
        finding(
            "oblique_band_peak_over_pulse_inversion",
            bp_over_pi,
            "",
            "(not in the thesis) the band peak's leakage floor at these amplitudes",
            None,
        ),
        finding(
            "oblique_energy_closure_error",
            closure,
            "",
            "(not in the thesis) energy audit of the coupled runs",
            Some(closure < 1e-6),
        ),
    ]);
    Ok(())
}

//! Section 1: the bilinear law (C_N1 = 3e11, C_N2 = 1e10 Pa/m) against its closed-form
//! solution (thesis eqs. 5.10-5.15), Figures 78-81.

use super::{
    finding, panel, trace_panels, traces, Collected, Setup, Trace, F0, FD_SPP, KC, P0, XI_BL,
};
use crate::analytic::{Bilinear, BilinearSolution};
use crate::error::Result;
use crate::output::plot::Series;
use crate::reproduce::{f, fmt_value, Ctx, Figure};

/// The runs of the bilinear reference case (15-cycle rectangular burst, xi = [`XI_BL`]):
/// the exact solver, then the FD solver at each resolution of [`FD_SPP`], with their gap
/// errors against the closed-form solution.
pub(super) struct BilinearRuns {
    /// Interface histories: the exact solver, then FD at each of [`FD_SPP`].
    tr: Vec<Trace>,
    /// The closed-form solution from rest over the burst.
    sol: BilinearSolution,
    /// Max relative gap error of the exact solver.
    exact_err: f64,
    /// Max relative gap error of the FD solver at each of [`FD_SPP`].
    fd_err: Vec<f64>,
    /// Space step of each FD run, m.
    dx: Vec<f64>,
    /// Index in [`FD_SPP`] of the default FD resolution (1000 samples per period).
    i_fd: usize,
}

/// Run the exact and the FD solvers on the bilinear reference case and measure their
/// errors against the closed-form solution (data of Figures 78, 80 and 81).
pub(super) fn runs(ctx: &Ctx, setup: &Setup) -> Result<BilinearRuns> {
    let Setup {
        base,
        burst,
        rect,
        bl,
        c,
        ..
    } = setup;
    let burst = *burst;
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
        base,
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
    Ok(BilinearRuns {
        tr,
        sol,
        exact_err,
        fd_err,
        dx,
        i_fd,
    })
}

/// Figures 78 and 80: gap, contact stress and stress-gap loop of the bilinear law under a
/// rectangular burst, the closed-form solution against the exact solver and the FD solver
/// at its default resolution. Finding: the exact solver's max relative gap error.
pub(super) fn signals(setup: &Setup, r: &BilinearRuns, out: &mut Collected) {
    let BilinearRuns {
        tr, sol, exact_err, ..
    } = r;
    let exact_err = *exact_err;
    let i_fd = r.i_fd;
    let fd_default = r.fd_err.get(i_fd).copied().unwrap_or(f64::NAN);
    let f_exact = finding(
        "bilinear_max_rel_error",
        exact_err,
        "",
        "numerical and analytical bilinear solutions agree (Figure 80)",
        Some(exact_err < 1e-6),
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
    out.figures.push(
        Figure::new(
            "ch5_fig78_80_bilinear_analytic_vs_numerical",
            "Figures 78 and 80: bilinear law, analytical against the exact and FD solvers",
            format!(
                "Gap, contact stress and stress-gap loop at x = 0. PMMA, p0 = 0.14 MPa, \
                 f0 = 5 kHz, 15-cycle rectangular burst, xi = {XI_BL} (incident amplitude \
                 {} MPa), C_N1 = 3e11 Pa/m in compression, C_N2 = 1e10 Pa/m in traction. \
                 The analytical curve is the closed-form solution from rest (continuous law).",
                fmt_value(setup.bl.amplitude * 1e-6)
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
    out.findings.push(f_exact);
}

/// Figure 81: the FD solver's max relative gap error against the space step, with the
/// fitted convergence order. Findings: the error at the default resolution and the order.
pub(super) fn fd_error(setup: &Setup, r: &BilinearRuns, out: &mut Collected) {
    let BilinearRuns {
        exact_err,
        fd_err,
        dx,
        i_fd,
        ..
    } = r;
    let c = setup.c;
    let fd_default = fd_err.get(*i_fd).copied().unwrap_or(f64::NAN);
    let order = loglog_slope(dx, fd_err);
    let decreasing = fd_err.windows(2).all(|w| w[1] < w[0]);
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
    let err_pct: Vec<f64> = fd_err.iter().map(|e| e * 100.0).collect();
    let dx_mm: Vec<f64> = dx.iter().map(|d| d * 1e3).collect();
    out.figures.push(
        Figure::new(
            "ch5_fig81_fd_error_vs_dx",
            "Figure 81: FD error against the space step",
            format!(
                "max |[u]_FD - [u]_analytic| / max |[u]_analytic| over the 15-cycle \
                 rectangular burst (xi = {XI_BL}, C_N1 = 3e11, C_N2 = 1e10 Pa/m, 5 kHz, \
                 wavelength {} m) for {} samples per period (Courant number 1, dx = c dt). \
                 The exact solver's error is {}.",
                fmt_value(c / F0),
                FD_SPP.map(|n| n.to_string()).join(", "),
                fmt_value(*exact_err)
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
    out.findings.extend([f_fd, f_order]);
}

/// Figure 79: durations of contact and contact loss per period in the periodic state of
/// the closed-form bilinear solution (periods 30-40 from rest) against xi, and the xi of
/// the onset of contact loss (bisection).
pub(super) fn contact_durations(ctx: &Ctx, setup: &Setup, out: &mut Collected) -> Result<()> {
    let Setup {
        base,
        period,
        rect,
        bl,
        ..
    } = setup;
    let (period, bl) = (*period, *bl);
    let xis79: Vec<f64> = (1..=26).map(|k| k as f64 * 0.05).collect();
    let amps: Vec<f64> = xis79
        .iter()
        .map(|&x| {
            let mut e = rect.clone();
            e.push(("incident.xi", f(x)));
            Ok(ctx.scenario(base, &e)?.incident.peak())
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
    out.figures.push(
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
    out.findings.push(f_onset);
    Ok(())
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

//! Section 3a: the modified power law in compression with a linear traction spring
//! (undamaged), against linear compression, RCCM and unilateral contact, Figures 89-94.

use super::linear::LinearSweep;
use super::{
    a1_a2_panels, at, finding, linear, loops_and_signals, panel, sweep, xi_series, Collected, Law,
    Setup, KT,
};
use crate::analysis::Summary;
use crate::error::Result;
use crate::output::plot::Series;
use crate::reproduce::{column, tv, Ctx, Edits, Figure, AMPLITUDE_FLOOR};

/// The laws of Figures 89-92 and their summaries over the xi grid.
pub(super) struct Undamaged {
    /// Modified PL + linear traction, linear C_N1 = 3e11, RCCM (rigid, w = 1000),
    /// unilateral.
    laws: Vec<Law>,
    /// Their summaries over the xi grid (one `Vec` per law; all but the first reused from
    /// the linear-compression sweep).
    s: Vec<Vec<Summary>>,
}

/// Sweep the modified PL with linear traction over the xi grid and set it beside the
/// linear (3e11), RCCM and unilateral curves of `lin` (data of Figures 91-94).
pub(super) fn sweep_undamaged(ctx: &Ctx, setup: &Setup, lin: &LinearSweep) -> Result<Undamaged> {
    let mpl_lin = Law {
        label: "modified PL + linear traction".into(),
        compression: setup.mpl_compression.clone(),
        traction: tv(&linear(KT)),
    };
    let laws = vec![
        mpl_lin,
        lin.laws[1].clone(),
        lin.laws[3].clone(),
        lin.laws[4].clone(),
    ];
    let s_mpl = sweep(
        ctx,
        "modified PL (undamaged): A1, A2 vs xi",
        &setup.base,
        &laws[..1],
        &setup.xis,
        &Edits::new(),
    )?;
    let s = vec![
        s_mpl[0].clone(),
        lin.s[1].clone(),
        lin.s[3].clone(),
        lin.s[4].clone(),
    ];
    Ok(Undamaged { laws, s })
}

/// Figures 89-90: (a) contact stress against gap at xi = 0.1, (b, c) gap and stress
/// against time at xi = 0.8, for the modified PL (linear traction), linear compression and
/// RCCM.
pub(super) fn signals(
    ctx: &Ctx,
    setup: &Setup,
    und: &Undamaged,
    out: &mut Collected,
) -> Result<()> {
    let und_panels = loops_and_signals(
        ctx,
        "modified PL (undamaged): signals",
        &setup.base,
        &und.laws[..3],
        (0.1, 0.8),
        setup.t_show,
    )?;
    out.figures.push(Figure::new(
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
    Ok(())
}

/// Figure 91: ratio of the contact-loss to the contact durations during the burst against
/// xi, for the laws of Figures 89-90.
pub(super) fn contact_loss_ratio(setup: &Setup, und: &Undamaged, out: &mut Collected) {
    let ratio = |s: &[Summary]| -> Vec<f64> {
        column(s, "contact_loss_fraction")
            .iter()
            .map(|c| if *c < 1.0 { c / (1.0 - c) } else { f64::NAN })
            .collect()
    };
    out.figures.push(Figure::new(
        "ch5_fig91_contact_loss_ratio_vs_xi",
        "Figure 91: ratio of contact-loss to contact durations against xi",
        "Open time over closed time during the burst (contact_loss_fraction f: f/(1-f)); \
         laws as in thesis Figures 89-90, p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        vec![panel(
            "contact loss / contact",
            "xi",
            "ratio",
            und.laws[..3]
                .iter()
                .zip(&und.s)
                .map(|(l, s)| Series::new(l.label.clone(), &setup.xis, &ratio(s)))
                .collect(),
        )],
    ));
}

/// Figure 92: A1/A_inc and A2/A_inc against xi for the modified PL (linear traction),
/// linear compression, RCCM and unilateral contact. Findings: the burst's own A2 `floor`,
/// A2 of each law at xi = 1.5 above it, and which law dominates at low and high xi.
pub(super) fn a1_a2_vs_xi(setup: &Setup, und: &Undamaged, floor: f64, out: &mut Collected) {
    let (xis, s_und) = (&setup.xis, &und.s);
    let a2_mpl = column(&s_und[0], "A2_over_Ainc");
    let a2_lin = column(&s_und[1], "A2_over_Ainc");
    let a2_rigid = column(&s_und[2], "A2_over_Ainc");
    let a2_uni = column(&s_und[3], "A2_over_Ainc");
    let mpl15 = at(xis, &a2_mpl, 1.5) - floor;
    let rig15 = at(xis, &a2_rigid, 1.5) - floor;
    let uni15 = at(xis, &a2_uni, 1.5) - floor;
    let lin15 = at(xis, &a2_lin, 1.5) - floor;
    let low = at(xis, &a2_rigid, 0.1) / at(xis, &a2_mpl, 0.1);
    // smallest xi from which the modified PL dominates RCCM for every larger xi
    let mut dominates = f64::NAN;
    for i in (0..xis.len()).rev() {
        if a2_mpl[i] > a2_rigid[i] {
            dominates = xis[i];
        } else {
            break;
        }
    }
    let mpl_findings = vec![
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
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "ch5_rigid_a2_at_xi_1_5",
            rig15,
            "",
            "rigid compression (RCCM): no second harmonic for xi > 1",
            Some(rig15 < 1e-3),
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "ch5_unilateral_a2_at_xi_1_5",
            uni15,
            "",
            "unilateral contact: no second harmonic for xi > 1",
            Some(uni15 < 1e-3),
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "ch5_linear_a2_at_xi_1_5",
            lin15,
            "",
            "linear compression (C_N1 = 3e11): no second harmonic for xi > 1",
            Some(lin15 < 1e-3),
        )
        .with_floor(AMPLITUDE_FLOOR),
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
    let mut fig92 = Figure::new(
        "ch5_fig92_mpl_undamaged_a1_a2_vs_xi",
        "Figure 92: A1/A_inc and A2/A_inc against xi, modified PL (undamaged)",
        "Modified PL + linear traction C_N2 = 1e10 Pa/m, linear C_N1 = 3e11 + C_N2 = 1e10, \
         RCCM (rigid, C_N = 1e10, w = 1000 J/m^2, b = 1e-8), unilateral; p0 = 0.14 MPa, \
         5 kHz, 15-cycle Hann-ramped burst; xi from eq. 5.9 with each law's tangent stiffness \
         at p0."
            .into(),
        a1_a2_panels(["(a)", "(b)"], &und.laws, xis, s_und).into(),
    );
    for fd in &mpl_findings {
        fig92 = fig92.compare(fd.line());
    }
    out.figures.push(fig92);
    out.findings.extend(mpl_findings);
}

/// Figure 94: A2/A_inc against xi for the modified PL with linear traction of stiffness
/// C_N2 in {1e9, 1e10, 1e11} Pa/m. Finding: the spread of the curves above xi = 1.
pub(super) fn traction_stiffness(
    ctx: &Ctx,
    setup: &Setup,
    und: &Undamaged,
    out: &mut Collected,
) -> Result<()> {
    let (xis, s_und) = (&setup.xis, &und.s);
    let kt_laws: Vec<Law> = [1e9, 1e10, 1e11]
        .iter()
        .map(|&k| und.laws[0].with_traction(&format!("C_N2 = {k:.0e}"), &linear(k)))
        .collect();
    let s_kt_new = sweep(
        ctx,
        "modified PL: traction stiffness",
        &setup.base,
        &[kt_laws[0].clone(), kt_laws[2].clone()],
        xis,
        &Edits::new(),
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
    )
    .with_floor(AMPLITUDE_FLOOR);
    out.figures.push(
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
                xi_series(&kt_laws, xis, &s_kt, "A2_over_Ainc"),
            )],
        )
        .compare(f_spread.line()),
    );
    out.findings.push(f_spread);
    Ok(())
}

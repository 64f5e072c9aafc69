//! Section 3b: RCCM (damageable) traction with modified PL, linear or rigid compression:
//! the damaged interface (w = 0.1 J/m^2, Figures 96-99) and the decohesion energy w in
//! {0, 0.1, 1000} J/m^2 (Figures 100-101).

use super::{
    a1_a2_panels, at, finding, linear, loops_and_signals, panel, rccm, sweep, xi_series, Collected,
    Law, Setup, KC, KT, RIGID,
};
use crate::analysis::Summary;
use crate::error::Result;
use crate::output::plot::{Panel, Series};
use crate::reproduce::{column, tv, Ctx, Edits, Figure, Finding, AMPLITUDE_FLOOR};

/// The laws of Figures 96-101 and their summaries over the xi grid.
pub(super) struct Damage {
    /// RCCM traction (w = 0.1 J/m^2) with modified PL, linear (3e11) and rigid compression.
    laws: Vec<Law>,
    /// Their summaries over the xi grid (one `Vec` per law).
    s: Vec<Vec<Summary>>,
    /// Modified PL + RCCM with w = 0, 0.1 and 1000 J/m^2.
    w_laws: Vec<Law>,
    /// Their summaries over the xi grid.
    s_w: Vec<Vec<Summary>>,
    /// Largest xi of the grid with damage (beta_end < 0.99) for each of `w_laws` (NaN:
    /// none).
    on_w: Vec<f64>,
}

/// Sweep the damageable laws over the xi grid in one study (the w = 0.1 modified-PL law
/// serves both the damaged and the decohesion-energy figures).
pub(super) fn sweep_damaged(ctx: &Ctx, setup: &Setup) -> Result<Damage> {
    let xis = &setup.xis;
    let w_dmg = 0.1;
    let dmg_laws = vec![
        Law {
            label: "modified PL + RCCM".into(),
            compression: setup.mpl_compression.clone(),
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
    let s_all = sweep(
        ctx,
        "RCCM traction (damage)",
        &setup.base,
        &all,
        xis,
        &Edits::new(),
    )?;
    let s_dmg = s_all[..3].to_vec();
    let s_w = vec![s_all[3].clone(), s_all[0].clone(), s_all[4].clone()];
    let onset = |s: &[Summary]| -> f64 {
        let b = column(s, "beta_end");
        (0..xis.len())
            .filter(|&i| b[i] < 0.99)
            .map(|i| xis[i])
            .fold(f64::NAN, f64::max)
    };
    let on_w: Vec<f64> = s_w.iter().map(|s| onset(s)).collect();
    Ok(Damage {
        laws: dmg_laws,
        s: s_dmg,
        w_laws,
        s_w,
        on_w,
    })
}

/// Findings of the damaged interface (w = 0.1), in report order: which law dominates at
/// high and low xi (A2 above the burst's `floor`; compared in Figure 99), the damage onset
/// for w = 0.1 and 1000 and the final adhesion at xi = 0.1 (compared in Figure 96).
pub(super) fn findings(setup: &Setup, d: &Damage, floor: f64) -> Vec<Finding> {
    let (xis, s_dmg, on_w) = (&setup.xis, &d.s, &d.on_w);
    let mpl_d15 = at(xis, &column(&s_dmg[0], "A2_over_Ainc"), 1.5) - floor;
    let rig_d15 = at(xis, &column(&s_dmg[2], "A2_over_Ainc"), 1.5) - floor;
    let rig_d01 = at(xis, &column(&s_dmg[2], "A2_over_Ainc"), 0.1)
        / at(xis, &column(&s_dmg[0], "A2_over_Ainc"), 0.1);
    vec![
        finding(
            "ch5_damaged_mpl_a2_at_xi_1_5",
            mpl_d15,
            "",
            "damaged interface: the modified PL dominates at high xi",
            Some(mpl_d15 > rig_d15),
        )
        .with_floor(AMPLITUDE_FLOOR),
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
            at(xis, &column(&s_dmg[0], "beta_end"), 0.1),
            "",
            "adhesion decreases as the amplitude grows (Figure 96)",
            None,
        ),
    ]
}

/// Figure 96: final adhesion beta_end and traction stiffness beta_end^2 C_N2 against xi,
/// damaged interface (w = 0.1), with the comparison lines of `compared`.
pub(super) fn damage_vs_xi(setup: &Setup, d: &Damage, compared: &[Finding], out: &mut Collected) {
    let mut fig96 = Figure::new(
        "ch5_fig96_damage_vs_xi",
        "Figure 96: final adhesion and traction stiffness against xi (damaged interface)",
        "beta_end and beta_end^2 C_N2 at the end of each run; RCCM traction C_N2 = 1e10 Pa/m, \
         w = 0.1 J/m^2, b = 1e-8 J s/m^2 (Table 8) with modified PL, linear (3e11 Pa/m) or \
         rigid compression; p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        adhesion_panels(&d.laws, &setup.xis, &d.s).into(),
    );
    for fd in compared {
        fig96 = fig96.compare(fd.line());
    }
    out.figures.push(fig96);
}

/// Figures 97-98: damaged interface (w = 0.1), (a) contact stress against gap at xi = 0.1,
/// (b, c) gap and stress against time at xi = 0.36.
pub(super) fn signals(ctx: &Ctx, setup: &Setup, d: &Damage, out: &mut Collected) -> Result<()> {
    let dmg_panels = loops_and_signals(
        ctx,
        "RCCM traction (damage): signals",
        &setup.base,
        &d.laws,
        (0.1, 0.36),
        setup.t_show,
    )?;
    out.figures.push(Figure::new(
        "ch5_fig97_98_damaged_signals",
        "Figures 97-98: damaged interface, loops and time signals",
        "(a) Contact stress against gap at xi = 0.1; (b, c) gap and stress against time at \
         xi = 0.36. RCCM traction C_N2 = 1e10 Pa/m, w = 0.1 J/m^2, b = 1e-8 with modified PL, \
         linear (3e11 Pa/m) or rigid compression; p0 = 0.14 MPa, 5 kHz."
            .into(),
        dmg_panels,
    ));
    Ok(())
}

/// Figure 99: A1/A_inc and A2/A_inc against xi, damaged interface (w = 0.1), with the
/// comparison lines of `compared`.
pub(super) fn a1_a2_vs_xi(setup: &Setup, d: &Damage, compared: &[Finding], out: &mut Collected) {
    let mut fig99 = Figure::new(
        "ch5_fig99_damaged_a1_a2_vs_xi",
        "Figure 99: A1/A_inc and A2/A_inc against xi (damaged interface)",
        "RCCM traction C_N2 = 1e10 Pa/m, w = 0.1 J/m^2, b = 1e-8 with modified PL, linear \
         (3e11 Pa/m) or rigid compression; p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst."
            .into(),
        a1_a2_panels(["(a)", "(b)"], &d.laws, &setup.xis, &d.s).into(),
    );
    for fd in compared {
        fig99 = fig99.compare(fd.line());
    }
    out.figures.push(fig99);
}

/// Figures 100-101: modified PL + RCCM with decohesion energy w in {0, 0.1, 1000} J/m^2:
/// beta_end, beta_end^2 C_N2, A1/A_inc and A2/A_inc against xi. Finding: the damage onset
/// for w = 0 and the ordering of the onsets with w.
pub(super) fn decohesion_energy(setup: &Setup, d: &Damage, out: &mut Collected) {
    let (xis, w_laws, s_w, on_w) = (&setup.xis, &d.w_laws, &d.s_w, &d.on_w);
    let f_w = finding(
        "ch5_damage_onset_xi_w0",
        on_w[0],
        "",
        "higher w: damage starts at lower xi; w = 0 damages at any amplitude with contact loss",
        Some(!(on_w[0] < on_w[1]) && !(on_w[1] < on_w[2])),
    );
    out.figures.push(
        Figure::new(
            "ch5_fig100_101_decohesion_energy",
            "Figures 100-101: modified PL + RCCM, decohesion energy w in {0, 0.1, 1000} J/m^2",
            "beta_end, beta_end^2 C_N2, A1/A_inc and A2/A_inc against xi; modified PL compression \
             (C = 1.81e10, m = 0.35), RCCM traction C_N2 = 1e10 Pa/m, b = 1e-8 J s/m^2; \
             p0 = 0.14 MPa, 5 kHz, 15-cycle Hann-ramped burst (w = 0: damage at the \
             first opening)."
                .into(),
            adhesion_panels(w_laws, xis, s_w)
                .into_iter()
                .chain(a1_a2_panels(["(c)", "(d)"], w_laws, xis, s_w))
                .collect(),
        )
        .compare(f_w.line()),
    );
    out.findings.push(f_w);
}

/// The final adhesion panel (`beta_end`) and the final traction stiffness panel
/// (`beta_end^2 C_N2`, GPa/m) against xi, titled (a) and (b).
fn adhesion_panels(laws: &[Law], xis: &[f64], s: &[Vec<Summary>]) -> [Panel; 2] {
    let stiff = |s: &[Summary]| -> Vec<f64> {
        column(s, "beta_end")
            .iter()
            .map(|b| b * b * KT * 1e-9)
            .collect::<Vec<f64>>()
    };
    [
        panel(
            "(a) adhesion intensity",
            "xi",
            "beta_end",
            xi_series(laws, xis, s, "beta_end"),
        ),
        panel(
            "(b) traction stiffness",
            "xi",
            "beta_end^2 C_N2 (GPa/m)",
            laws.iter()
                .zip(s)
                .map(|(l, s)| Series::new(l.label.clone(), xis, &stiff(s)))
                .collect(),
        ),
    ]
}

//! Section 2: linear compression C_N1 in {2, 3, 6} e11 Pa/m with linear traction C_N2 =
//! 1e10 Pa/m against RCCM (rigid compression, w = 1000 J/m^2: undamaged) and unilateral
//! contact, Figures 83-87.

use super::{
    at, finding, linear, loop_panel, panel, rccm, sweep, traces, xi_series, Collected, Law, Setup,
    F0, FREE, KT, RIGID,
};
use crate::analysis::Summary;
use crate::error::Result;
use crate::output::plot::{Panel, Series};
use crate::reproduce::{
    argmax_refined, column, f, fmt_value, tv, Ctx, Edits, Figure, AMPLITUDE_FLOOR,
};

/// The compression stiffnesses C_N1 of the bilinear laws, Pa/m.
const KCS: [f64; 3] = [2e11, 3e11, 6e11];

/// The laws of Figures 83-84 and their sweep over the xi grid.
pub(super) struct LinearSweep {
    /// Bilinear C_N1 in [`KCS`] (C_N2 = 1e10 Pa/m), RCCM (rigid, w = 1000), unilateral.
    pub(super) laws: Vec<Law>,
    /// Their summaries over the xi grid (one `Vec` per law).
    pub(super) s: Vec<Vec<Summary>>,
}

/// Sweep the bilinear laws, RCCM and unilateral contact over the xi grid (data of
/// Figure 84, reused by Figures 91-92).
pub(super) fn sweep_laws(ctx: &Ctx, setup: &Setup) -> Result<LinearSweep> {
    let mut laws: Vec<Law> = KCS
        .iter()
        .map(|&k| {
            Law::new(
                &format!("bilinear C_N1 = {}e11", k / 1e11),
                &linear(k),
                &linear(KT),
            )
        })
        .collect();
    laws.push(Law::new("RCCM (rigid, w = 1000)", RIGID, &rccm(KT, 1000.0)));
    laws.push(Law::new("unilateral", RIGID, FREE));
    let s = sweep(
        ctx,
        "linear compression: A2 vs xi",
        &setup.base,
        &laws,
        &setup.xis,
        &Edits::new(),
    )?;
    Ok(LinearSweep { laws, s })
}

/// Figure 83: contact stress against gap at xi = 0.1 for the bilinear laws, RCCM and
/// unilateral contact.
pub(super) fn loops(
    ctx: &Ctx,
    setup: &Setup,
    lin: &LinearSweep,
    out: &mut Collected,
) -> Result<()> {
    let laws = &lin.laws;
    let loop_variants: Vec<Edits> = laws
        .iter()
        .map(|l| {
            let mut e = l.edits();
            e.push(("incident.xi", f(0.1)));
            e
        })
        .collect();
    let loops = traces(
        ctx,
        "linear compression: loops",
        &setup.base,
        &loop_variants,
        setup.t_show,
    )?;
    let law_labels: Vec<String> = laws.iter().map(|l| l.label.clone()).collect();
    out.figures.push(Figure::new(
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
    Ok(())
}

/// Figure 84: A2/A_inc against xi, (a) the bilinear laws against RCCM, (b) C_N1 = 6e11
/// against unilateral contact. Findings: the distance of each bilinear curve to RCCM
/// below xi = 1, A2 above xi = 1 (over the burst's `floor`), and the low-xi ratio and the
/// optimum xi of bilinear 6e11 and unilateral contact.
pub(super) fn a2_vs_xi(setup: &Setup, lin: &LinearSweep, floor: f64, out: &mut Collected) {
    let (laws, s_lin, xis) = (&lin.laws, &lin.s, &setup.xis);
    let a2: Vec<Vec<f64>> = s_lin.iter().map(|s| column(s, "A2_over_Ainc")).collect();
    let below1: Vec<usize> = (0..xis.len()).filter(|&i| xis[i] < 1.0).collect();
    let pick = |v: &[f64]| below1.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let dist: Vec<f64> = (0..3)
        .map(|k| rms_diff(&pick(&a2[k]), &pick(&a2[3])))
        .collect();
    let approaches = dist.windows(2).all(|w| w[1] < w[0]);
    let mut lin_findings = Vec::new();
    for (k, d) in KCS.iter().zip(&dist) {
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
    lin_findings.push(
        finding(
            "ch5_linear_a2_above_xi_1",
            lin_above1,
            "",
            "no second harmonic for xi > 1 with linear compression (C_N1 = 3e11); here \
         A2/A_inc above the burst's floor",
            Some(lin_above1 < 1e-3),
        )
        .with_floor(AMPLITUDE_FLOOR),
    );
    let bl6_u = at(xis, &a2[2], 0.1) / at(xis, &a2[4], 0.1);
    let (imax6, imaxu) = (argmax_refined(xis, &a2[2]), argmax_refined(xis, &a2[4]));
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
                xi_series(&laws[..4], xis, &s_lin[..4], "A2_over_Ainc"),
            ),
            panel(
                "(b) bilinear C_N1 = 6e11 against unilateral",
                "xi",
                "A2/A_inc",
                vec![
                    Series::new(laws[2].label.clone(), xis, &a2[2]),
                    Series::new(laws[4].label.clone(), xis, &a2[4]),
                ],
            ),
        ],
    );
    for fd in &lin_findings {
        fig84 = fig84.compare(fd.line());
    }
    out.figures.push(fig84);
    out.findings.extend(lin_findings);
}

/// Figures 86-87: A2/A_inc against the normalised frequency omega Z / C_N2 (C_N2 from
/// 10^7.5 to 10^11.5 Pa/m) for the bilinear laws and RCCM, at xi = 0.1, 0.35 and 0.8.
pub(super) fn normalised_frequency(ctx: &Ctx, setup: &Setup, out: &mut Collected) -> Result<()> {
    let z = setup.z;
    let exps: Vec<f64> = (0..9).map(|k| 7.5 + 0.5 * k as f64).collect();
    let kts: Vec<f64> = exps.iter().map(|e| 10f64.powf(*e)).collect();
    let omega = 2.0 * std::f64::consts::PI * F0;
    let nf: Vec<f64> = kts.iter().map(|k| (omega * z / k).log10()).collect();
    let nf_laws: Vec<(String, f64)> = KCS
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
        &setup.base,
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
    out.figures.push(Figure::new(
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
    Ok(())
}

/// Root-mean-square difference of two curves.
fn rms_diff(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()).max(1) as f64;
    (a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / n).sqrt()
}

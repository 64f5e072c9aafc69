//! Plots of the project's own studies (law curves, sweeps, convergence), drawn with the
//! primitives of [`crate::render::svg`].

use crate::error::Result;
use crate::law::ContactLaw;
pub(crate) use crate::render::svg::{color, plot_error};
pub use crate::render::svg::{figure, ramp, Panel, Series};
use crate::render::svg::{panel, render, scaled, short, Curve};
use crate::study::{AxisSpec, Sweep, SweepTable};
use plotters::prelude::*;

/// `law_curve.svg`: the monotone-loading stress-gap curve of a law.
pub fn law_curve(law: &ContactLaw, gap: &[f64], stress: &[f64]) -> Result<String> {
    let (g, gu) = scaled(gap, "m");
    let (s, su) = scaled(stress, "Pa");
    let title = format!(
        "Contact law: {} compression + {} traction, p0 = {} Pa",
        law.compression.name(),
        law.traction.name(),
        law.static_pressure
    );
    render("law_curve.svg", (750, 550), |root| {
        panel(
            root,
            &title,
            &format!("gap [u], {gu}"),
            &format!("stress, {su}"),
            &[Curve {
                label: String::new(),
                points: g.iter().copied().zip(s.iter().copied()).collect(),
                color: color(0),
            }],
            &[],
            None,
        )
    })
}

/// `law_tangential.svg`: shear stress against tangential gap under monotone loading at the
/// static pressure.
pub fn tangential_law_curve(
    law: &ContactLaw,
    t: &crate::law::TangentialLaw,
    gap: &[f64],
    tau: &[f64],
) -> Result<String> {
    let (g, gu) = scaled(gap, "m");
    let (s, su) = scaled(tau, "Pa");
    let title = format!(
        "Tangential law: {}, mu = {}, p0 = {} Pa, q0 = {} Pa",
        t.branch.name(),
        t.branch.friction(),
        law.static_pressure,
        t.static_shear
    );
    render("law_tangential.svg", (750, 550), |root| {
        panel(
            root,
            &title,
            &format!("tangential gap [u]_T, {gu}"),
            &format!("shear stress tau, {su}"),
            &[Curve {
                label: String::new(),
                points: g.iter().copied().zip(s.iter().copied()).collect(),
                color: color(0),
            }],
            &[],
            None,
        )
    })
}

/// `sweep.svg`: the results against the first axis, one curve per combination of the other
/// axes: `A1_over_Ainc` and `A2_over_Ainc` for half-space sweeps; `first_mode_hz`, `A1`,
/// `A2_over_A1`, the mean contact stiffness and the minimum contact pressure for bar-stack
/// sweeps. Axes are labelled with names and units ([`crate::output::labels`]).
pub fn sweep(sw: &Sweep, table: &SweepTable) -> Result<String> {
    let axes: Vec<(String, bool)> = sw
        .axes
        .iter()
        .map(|a| {
            (
                a.parameter.clone(),
                matches!(a.spec, AxisSpec::Logspace { .. }),
            )
        })
        .collect();
    sweep_table(&axes, table)
}

/// The axes of a sweep CSV without its sweep file: the dotted-key columns after `point`
/// (sweep parameters are dotted scenario keys), none logspace.
pub fn axes_of_table(table: &SweepTable) -> Vec<(String, bool)> {
    table
        .header
        .iter()
        .skip_while(|h| h.as_str() == "point")
        .take_while(|h| h.contains('.'))
        .map(|h| (h.clone(), false))
        .collect()
}

/// A value with its unit for a legend: `1.5 MPa`, `0.35` (dimensionless).
fn with_unit(v: f64, unit: &str) -> String {
    let (k, p) = if v == 0.0
        || (1.0..1e3).contains(&v.abs())
        || (unit.is_empty() && v.abs() >= 1e-3 && v.abs() < 1e4)
    {
        (1.0, "")
    } else {
        crate::render::svg::prefix(v.abs())
    };
    let n = short(v * k);
    if unit.is_empty() && p.is_empty() {
        n
    } else {
        format!("{n} {p}{unit}")
    }
}

/// `sweep.svg` from a sweep table and its axes (`(parameter, logspace)`, first axis on x).
pub fn sweep_table(axes: &[(String, bool)], table: &SweepTable) -> Result<String> {
    use crate::output::labels::{axis_label, quantity};
    use crate::render::svg::{panel_with, prefix, PanelOpts};
    let name = "sweep.svg";
    let Some((first, first_log)) = axes.first() else {
        return Err(plot_error(name, "the sweep has no axis".into()));
    };
    let xcol = table
        .column(first)
        .ok_or_else(|| plot_error(name, format!("no column `{first}`").into()))?;
    let xs: Vec<f64> = table.rows.iter().map(|r| r[xcol]).collect();
    let positive = xs.iter().all(|v| *v > 0.0);
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    let log_x = positive && (*first_log || (lo > 0.0 && hi / lo >= 1e3));
    // linear axis: values in a scaled unit (MPa); log axis: ticks carry the SI prefix
    let (xk, xp) = if log_x {
        (1.0, "")
    } else {
        prefix(crate::render::svg::max_abs(&xs))
    };
    let xlabel = if log_x {
        format!("{} (log scale)", axis_label(first, ""))
    } else {
        axis_label(first, xp)
    };
    let others: Vec<(usize, &str)> = axes[1..]
        .iter()
        .filter_map(|(a, _)| table.column(a).map(|c| (c, a.as_str())))
        .collect();
    // group rows by the values of the other axes, in order of first appearance in grid order
    let mut rows: Vec<&Vec<f64>> = table.rows.iter().collect();
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut groups: Vec<(Vec<f64>, Vec<&Vec<f64>>)> = Vec::new();
    for r in rows {
        let key: Vec<f64> = others.iter().map(|(c, _)| r[*c]).collect();
        match groups.iter_mut().find(|g| g.0 == key) {
            Some(g) => g.1.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let curves_of = |col: usize, yk: f64| -> Vec<Curve> {
        groups
            .iter()
            .enumerate()
            .map(|(i, (key, rs))| {
                let mut pts: Vec<(f64, f64)> = rs
                    .iter()
                    .map(|r| {
                        let x = r[xcol];
                        (if log_x { x.log10() } else { x * xk }, r[col] * yk)
                    })
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let label = others
                    .iter()
                    .zip(key)
                    .map(|((_, n), v)| {
                        let (q, unit) = quantity(n);
                        // the symbol (last word, e.g. `p0`) when the name ends with one
                        let sym = q.rsplit(' ').next().filter(|w| w.len() <= 4).unwrap_or(&q);
                        format!("{sym} = {}", with_unit(*v, unit))
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                Curve {
                    label,
                    points: pts,
                    color: color(i),
                }
            })
            .collect()
    };
    // half-space sweeps: the reflected harmonics; bar-stack sweeps: the resonance study
    // of thesis chapter 4 (first mode, A1, A2/A1, mean contact stiffness, min pressure)
    // (shear sweeps: the third harmonic and the friction dissipation)
    // (oblique sweeps: the outgoing P and SV waves)
    let panels: Vec<(&str, &str)> = if table.column("reflected_P_A1_over_Ainc").is_some() {
        vec![
            (
                "reflected_P_A1_over_Ainc",
                "Fundamental of the reflected P wave",
            ),
            (
                "reflected_SV_A1_over_Ainc",
                "Fundamental of the reflected SV wave",
            ),
            (
                "reflected_P_A2_over_A1",
                "Second harmonic of the reflected P wave",
            ),
            (
                "reflected_SV_A2_over_A1",
                "Second harmonic of the reflected SV wave",
            ),
            (
                "friction_dissipation_fraction",
                "Energy dissipated by friction",
            ),
        ]
    } else if table.column("A1_over_Ainc").is_some() || table.column("shear_A1_over_Ainc").is_some()
    {
        vec![
            ("A1_over_Ainc", "Fundamental of the reflected wave"),
            ("A2_over_Ainc", "Second harmonic of the reflected wave"),
            (
                "shear_A3_over_A1",
                "Third harmonic of the reflected shear wave",
            ),
            (
                "shear_tr_A3_over_A1",
                "Third harmonic of the transmitted shear wave",
            ),
            (
                "friction_dissipation_fraction",
                "Energy dissipated by friction",
            ),
        ]
    } else if table.column("crack_max_gap_0").is_some() {
        // 2D sweeps: each receiver's second harmonic, the first crack's opening and slip
        let mut v: Vec<(&str, &str)> = table
            .header
            .iter()
            .filter(|h| h.ends_with("_A2_over_A1"))
            .map(|h| (h.as_str(), "Second harmonic at a receiver"))
            .collect();
        v.push(("crack_max_gap_0", "Largest opening of crack 0"));
        v.push(("crack_max_slip_0", "Largest slip of crack 0"));
        v
    } else {
        vec![
            ("first_mode_hz", "First mode"),
            ("A1", "Response at the first mode"),
            ("A2_over_A1", "Second harmonic"),
            (
                "mean_contact_stiffness_0",
                "Mean contact stiffness, interface 0 (the first in stack order; eq. 4.2)",
            ),
            (
                "min_contact_pressure",
                "Minimum contact pressure, all interfaces",
            ),
        ]
    }
    .into_iter()
    .filter(|(c, _)| table.column(c).is_some())
    .collect();
    if panels.is_empty() {
        return Err(plot_error(name, "no known result column to plot".into()));
    }
    let data: Vec<(String, Vec<Curve>)> = panels
        .iter()
        .filter_map(|(c, _)| {
            let col = table.column(c)?;
            let ys: Vec<f64> = table.rows.iter().map(|r| r[col]).collect();
            let (_, unit) = quantity(c);
            let (yk, yp) = if unit.is_empty() {
                (1.0, "")
            } else {
                prefix(crate::render::svg::max_abs(&ys))
            };
            Some((axis_label(c, yp), curves_of(col, yk)))
        })
        .collect();
    let height = 400 * panels.len() as u32;
    let legend = !others.is_empty();
    render(name, (if legend { 1150 } else { 900 }, height), |root| {
        let areas = root.split_evenly((panels.len(), 1));
        for ((area, (_, title)), (ylabel, curves)) in areas.iter().zip(&panels).zip(&data) {
            panel_with(
                area,
                title,
                &xlabel,
                ylabel,
                curves,
                &[],
                PanelOpts {
                    log_x,
                    ..Default::default()
                },
            )?;
        }
        Ok(())
    })
}

/// `convergence.svg` (thesis Figure 22): `A_n/A_inc` against xi for each resolution and
/// the exact solver; the eq. 2.43 error against the time step (log-log).
pub fn convergence(r: &crate::study::convergence::ConvergenceResult) -> Result<String> {
    let name = "convergence.svg";
    let mut curves: Vec<Curve> = r
        .levels
        .iter()
        .enumerate()
        .map(|(i, l)| Curve {
            label: format!("{} samples/period", l.samples_per_period),
            points: r
                .xi
                .iter()
                .zip(&l.efficiency)
                .map(|(x, y)| (*x, 100.0 * y))
                .filter(|p| p.1.is_finite())
                .collect(),
            color: color(i + 1),
        })
        .collect();
    curves.push(Curve {
        label: "exact solver".into(),
        points: r
            .xi
            .iter()
            .zip(&r.exact)
            .map(|(x, y)| (*x, 100.0 * y))
            .filter(|p| p.1.is_finite())
            .collect(),
        color: RGBColor(0, 0, 0),
    });
    let err = |f: &dyn Fn(&crate::study::convergence::ConvergenceLevel) -> f64| -> Vec<(f64, f64)> {
        r.levels
            .iter()
            .map(|l| (l.dt.log10(), (100.0 * f(l)).log10()))
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect()
    };
    let errors = vec![
        Curve {
            label: format!("vs exact solver (order {:.2})", r.order_exact),
            points: err(&|l| l.error_exact),
            color: color(0),
        },
        Curve {
            label: format!("vs finest (eq. 2.43, order {:.2})", r.order_finest),
            points: err(&|l| l.error_finest),
            color: color(1),
        },
    ];
    let n = r.harmonic;
    render(name, (900, 800), |root| {
        let areas = root.split_evenly((2, 1));
        panel(
            &areas[0],
            &format!("Harmonic efficiency A{n}/A_inc per resolution"),
            "xi",
            &format!("A{n}/A_inc, %"),
            &curves,
            &[],
            None,
        )?;
        panel(
            &areas[1],
            "Error (eq. 2.43) against the time step",
            "log10(dt / s)",
            "log10(error, %)",
            &errors,
            &[],
            None,
        )?;
        Ok(())
    })
}

/// Most quantities `convergence.svg` of a 2D study draws (a receiver line's points are
/// many; `convergence.csv` has every one).
pub const CONVERGENCE_2D_CURVES: usize = 12;

/// `convergence.svg` of a 2D study (`contactwave convergence` on a `solid_2d` scenario):
/// each receiver's `A_n/A1` against the element size, and its change against the finest
/// level (log-log: the slope is the observed order).
pub fn convergence_2d(r: &crate::study::convergence_2d::Convergence2dResult) -> Result<String> {
    let name = "convergence.svg";
    let shown = r.quantities.len().min(CONVERGENCE_2D_CURVES);
    let h = |l: &crate::study::convergence_2d::Level2d| (1e3 * l.element_size).log10();
    let label = |i: usize| {
        let q = &r.quantities[i];
        let order = r.order[i];
        format!(
            "{} A{}/A1 (order {})",
            r.receivers[q.receiver],
            q.harmonic,
            if order.is_finite() {
                format!("{order:.2}")
            } else {
                "n/a".into()
            }
        )
    };
    let values: Vec<Curve> = (0..shown)
        .map(|i| Curve {
            label: label(i),
            points: r
                .levels
                .iter()
                .map(|l| (h(l), l.values[i]))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect(),
            color: color(i),
        })
        .collect();
    let changes: Vec<Curve> = (0..shown)
        .map(|i| Curve {
            label: label(i),
            points: r
                .levels
                .iter()
                .map(|l| (h(l), (100.0 * l.change[i].abs()).log10()))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect(),
            color: color(i),
        })
        .collect();
    let more = if shown < r.quantities.len() {
        format!(" (the first {shown} of {})", r.quantities.len())
    } else {
        String::new()
    };
    let marked = vec![true; shown];
    render(name, (1150, 800), |root| {
        let areas = root.split_evenly((2, 1));
        crate::render::svg::panel_with(
            &areas[0],
            &format!("Harmonics at the receivers against the element size{more}"),
            "element size, mm",
            "A_n/A1",
            &values,
            &[],
            crate::render::svg::PanelOpts {
                log_x: true,
                marked: &marked,
                ..Default::default()
            },
        )?;
        crate::render::svg::panel_with(
            &areas[1],
            "Change against the finest level (slope: the observed order)",
            "element size, mm",
            "log10(|change|, %)",
            &changes,
            &[],
            crate::render::svg::PanelOpts {
                log_x: true,
                marked: &marked,
                ..Default::default()
            },
        )?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 24: one numbering of interfaces (from 0, as the keys `_0`, `_1`,
    /// `interface.0` and the CLI's `[0]`): the bar-stack sweep.svg's panel title and its
    /// y-label name the same interface as the column `mean_contact_stiffness_0`.
    #[test]
    fn bar_stack_sweep_plot_numbers_interfaces_as_the_keys() {
        let header = [
            "excitation.peak",
            "first_mode_hz",
            "A1",
            "A2_over_A1",
            "mean_contact_stiffness_0",
            "min_contact_pressure",
        ];
        let table = SweepTable {
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: (1..=3)
                .map(|k| {
                    let k = k as f64;
                    vec![9.0 * k, 830.0 - k, 10.0 * k, 0.1 * k, 1e12 - 1e10 * k, 2e4]
                })
                .collect(),
        };
        let svg = sweep_table(&[("excitation.peak".into(), false)], &table).unwrap();
        let named: Vec<&str> = svg
            .match_indices("interface ")
            .map(|(i, m)| {
                let rest = &svg[i + m.len()..];
                &rest[..rest
                    .find(|c: char| !c.is_ascii_digit())
                    .unwrap_or(rest.len())]
            })
            .filter(|n| !n.is_empty())
            .collect();
        assert!(
            named.len() >= 2,
            "title and y-label name the interface: {named:?}"
        );
        assert!(
            named.iter().all(|n| *n == "0"),
            "interfaces named {named:?}"
        );
    }
}

//! The files of an identification (`contactwave identify`): `identification.json`,
//! `fit.csv`, the fit and sensitivity plots and the HTML report, rendered from an
//! [`Identification`].

use crate::error::{Error, Result};
use crate::inverse::{Identification, Measured, Scale};
use crate::output::plot::{color, plot_error};
use crate::output::OutputFile;
use plotters::prelude::*;

/// Every file of an identification, rendered in memory.
pub fn identification_files(r: &Identification) -> Result<Vec<OutputFile>> {
    let json = serde_json::to_string_pretty(&r.to_json())
        .map_err(|e| Error::io("identification.json", std::io::Error::other(e)))?;
    let fit = fit_svg(r)?;
    let sens = sensitivity_svg(r)?;
    let html = html(r, &fit, &sens);
    Ok(vec![
        OutputFile {
            name: "identification.json".into(),
            contents: json + "\n",
        },
        OutputFile {
            name: "fit.csv".into(),
            contents: r.fit_csv(),
        },
        OutputFile {
            name: "fit.svg".into(),
            contents: fit,
        },
        OutputFile {
            name: "sensitivity.svg".into(),
            contents: sens,
        },
        OutputFile {
            name: "identification.html".into(),
            contents: html,
        },
    ])
}

type PlotResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Groups of rows with equal non-control conditions, in order of appearance; each group
/// sorted by the control value.
fn groups(m: &Measured) -> Vec<(String, Vec<usize>)> {
    let mut g: Vec<(Vec<f64>, Vec<usize>)> = Vec::new();
    for (i, r) in m.rows.iter().enumerate() {
        let key = r[1..].to_vec();
        match g.iter_mut().find(|x| x.0 == key) {
            Some(x) => x.1.push(i),
            None => g.push((key, vec![i])),
        }
    }
    g.into_iter()
        .map(|(key, mut rows)| {
            rows.sort_by(|&a, &b| m.rows[a][0].total_cmp(&m.rows[b][0]));
            let label = m.conditions[1..]
                .iter()
                .zip(&key)
                .map(|(n, v)| format!("{n} = {v:.4e}"))
                .collect::<Vec<_>>()
                .join(", ");
            (label, rows)
        })
        .collect()
}

fn log_x(m: &Measured) -> bool {
    let (lo, hi) = m.rows.iter().fold((f64::INFINITY, 0.0f64), |(l, h), r| {
        (l.min(r[0]), h.max(r[0]))
    });
    lo > 0.0 && hi / lo >= 1e3
}

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - pad, hi + pad)
}

fn fit_svg(r: &Identification) -> Result<String> {
    let m = &r.measured;
    let nobs = m.observed.len();
    let lx = log_x(m);
    let xs = |i: usize| {
        if lx {
            m.rows[i][0].log10()
        } else {
            m.rows[i][0]
        }
    };
    let xlabel = if lx {
        format!("log10({})", m.control())
    } else {
        m.control().to_string()
    };
    let gs = groups(m);
    let mut s = String::new();
    let mut draw = || -> PlotResult<()> {
        let root = SVGBackend::with_string(&mut s, (800, 320 * nobs as u32)).into_drawing_area();
        root.fill(&WHITE)?;
        let panels = root.split_evenly((nobs, 1));
        for (k, (o, area)) in m.observed.iter().zip(panels.iter()).enumerate() {
            let (x0, x1) = range((0..m.len()).map(xs));
            let (y0, y1) = range(
                o.values
                    .iter()
                    .copied()
                    .chain(r.fitted.iter().map(|f| f[k])),
            );
            let mut chart = ChartBuilder::on(area)
                .caption(
                    format!("{}: measured (points) and fitted (lines)", o.key),
                    ("sans-serif", 16),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, y0..y1)?;
            chart
                .configure_mesh()
                .x_desc(xlabel.clone())
                .y_desc(o.key.clone())
                .draw()?;
            for (g, (label, rows)) in gs.iter().enumerate() {
                let c = color(g);
                let line = chart.draw_series(LineSeries::new(
                    rows.iter()
                        .map(|&i| (xs(i), r.fitted[i][k]))
                        .filter(|p| p.1.is_finite()),
                    c.stroke_width(2),
                ))?;
                if !label.is_empty() {
                    line.label(label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2))
                    });
                }
                chart.draw_series(
                    rows.iter()
                        .map(|&i| Circle::new((xs(i), o.values[i]), 3, c.filled())),
                )?;
                chart.draw_series(rows.iter().map(|&i| {
                    PathElement::new(
                        vec![
                            (xs(i), o.values[i] - o.sigma[i]),
                            (xs(i), o.values[i] + o.sigma[i]),
                        ],
                        c,
                    )
                }))?;
            }
            if gs.len() > 1 {
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK)
                    .draw()?;
            }
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| plot_error("fit.svg", e))?;
    Ok(s)
}

fn sensitivity_svg(r: &Identification) -> Result<String> {
    let m = &r.measured;
    let nobs = m.observed.len();
    let np = r.parameters.len();
    let lx = log_x(m);
    let xs = |i: usize| {
        if lx {
            m.rows[i][0].log10()
        } else {
            m.rows[i][0]
        }
    };
    let xlabel = if lx {
        format!("log10({})", m.control())
    } else {
        m.control().to_string()
    };
    let jac = &r.identifiability.jacobian;
    let gs = groups(m);
    let mut s = String::new();
    let mut draw = || -> PlotResult<()> {
        let root = SVGBackend::with_string(&mut s, (800, 300 * np as u32)).into_drawing_area();
        root.fill(&WHITE)?;
        let panels = root.split_evenly((np, 1));
        for (j, (p, area)) in r.parameters.iter().zip(panels.iter()).enumerate() {
            let val = |i: usize, k: usize| jac.get(i * nobs + k).map_or(f64::NAN, |row| row[j]);
            let (x0, x1) = range((0..m.len()).map(xs));
            let (y0, y1) = range((0..m.len()).flat_map(|i| (0..nobs).map(move |k| val(i, k))));
            let unit = match p.scale {
                Scale::Log => "per decade",
                Scale::Linear => "per unit",
            };
            let mut chart = ChartBuilder::on(area)
                .caption(
                    format!("Sensitivity to {} (weighted residual, sigma {unit})", p.key),
                    ("sans-serif", 15),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, y0..y1)?;
            chart
                .configure_mesh()
                .x_desc(xlabel.clone())
                .y_desc("d r / d z")
                .draw()?;
            let mut series = 0;
            for (label, rows) in &gs {
                for (k, o) in m.observed.iter().enumerate() {
                    let c = color(series);
                    series += 1;
                    let name = if label.is_empty() {
                        o.key.clone()
                    } else {
                        format!("{}, {label}", o.key)
                    };
                    chart
                        .draw_series(LineSeries::new(
                            rows.iter()
                                .map(|&i| (xs(i), val(i, k)))
                                .filter(|p| p.1.is_finite()),
                            c.stroke_width(2),
                        ))?
                        .label(name)
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2))
                        });
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()?;
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| plot_error("sensitivity.svg", e))?;
    Ok(s)
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn html(r: &Identification, fit: &str, sens: &str) -> String {
    let id = &r.identifiability;
    let mut rows = String::new();
    for (j, p) in r.parameters.iter().enumerate() {
        let iv = |x: Option<(f64, f64)>| match x {
            Some((a, b)) => format!("[{a:.4e}, {b:.4e}]"),
            None => "-".into(),
        };
        rows.push_str(&format!(
            "<tr><td><code>{}</code></td><td>{:.6e}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            esc(&p.key),
            r.estimate.values[j],
            iv(id.intervals[j]),
            iv(id.bootstrap_intervals[j]),
            esc(&id.verdicts[j].text)
        ));
    }
    let sv = id
        .singular_values
        .iter()
        .map(|s| format!("{s:.4e}"))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>contactwave identification</title>\
<style>body{{font-family:sans-serif;max-width:900px;margin:auto}}table{{border-collapse:collapse}}\
td,th{{border:1px solid #ccc;padding:4px 8px}}</style></head><body>\n\
<h1>Identification</h1>\n<p>{} data points, {} residuals; weighted residual norm {:.4e}; \
{} forward runs in {:.2} s.</p>\n\
<table><tr><th>parameter</th><th>estimate</th><th>95% CI (linearised)</th><th>95% CI (bootstrap, {} resamples)</th><th>verdict</th></tr>\n{}</table>\n\
<h2>Jacobian (weighted residuals, scaled parameters)</h2><p>singular values: {}; condition number {:.4e}; residual variance s<sup>2</sup> = {:.4e}.</p>\n\
<h2>Fitted versus measured</h2>\n{}\n<h2>Sensitivity</h2>\n{}\n</body></html>\n",
        r.measured.len(),
        r.measured.residual_count(),
        r.residual_norm(),
        r.forward_runs,
        r.wall_seconds,
        id.bootstrap_resamples,
        rows,
        sv,
        id.condition_number,
        id.residual_variance,
        fit,
        sens
    )
}

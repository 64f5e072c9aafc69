//! SVG figures (plotters, SVG backend, rendered into strings): the primitives every plot of
//! the project is drawn with (panels, curves, palette, scaled units, decimation).
//!
//! Quantities are drawn in scaled SI units (e.g. µs, nm, MPa) named in the axis labels.
//! Long time series are reduced to at most `MAX_POINTS` (4000) points per curve by keeping the
//! minimum and maximum of each bucket, which preserves peaks.

use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Largest number of points drawn per curve.
pub(crate) const MAX_POINTS: usize = 4000;

pub(crate) type PlotResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A plotting failure as an I/O error on the named file.
pub(crate) fn plot_error(name: &str, e: Box<dyn std::error::Error>) -> Error {
    Error::io(name, std::io::Error::other(format!("plot: {e}")))
}

/// An SI prefix for values up to `max_abs`: (multiplier, prefix).
pub(crate) fn prefix(max_abs: f64) -> (f64, &'static str) {
    let table = [
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "µ"),
        (1e-9, "n"),
        (1e-12, "p"),
    ];
    if !(max_abs.is_finite() && max_abs > 0.0) {
        return (1.0, "");
    }
    for (v, p) in table {
        if max_abs >= v {
            return (1.0 / v, p);
        }
    }
    (1e12, "p")
}

pub(crate) fn max_abs(v: &[f64]) -> f64 {
    v.iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Scale a quantity for display: (scaled values, unit label such as `MPa`).
pub(crate) fn scaled(v: &[f64], unit: &str) -> (Vec<f64>, String) {
    let (k, p) = prefix(max_abs(v));
    (v.iter().map(|x| x * k).collect(), format!("{p}{unit}"))
}

/// Reduce a curve to at most `MAX_POINTS` points keeping each bucket's min and max.
pub(crate) fn decimate(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    if n <= MAX_POINTS {
        return (0..n)
            .filter(|&i| x[i].is_finite() && y[i].is_finite())
            .map(|i| (x[i], y[i]))
            .collect();
    }
    let bucket = n.div_ceil(MAX_POINTS / 2);
    let mut out = Vec::with_capacity(MAX_POINTS + 2);
    let mut start = 0;
    while start < n {
        let end = (start + bucket).min(n);
        let (mut imin, mut imax) = (start, start);
        for i in start..end {
            if y[i] < y[imin] {
                imin = i;
            }
            if y[i] > y[imax] {
                imax = i;
            }
        }
        let (a, b) = if imin <= imax {
            (imin, imax)
        } else {
            (imax, imin)
        };
        for i in [a, b] {
            if x[i].is_finite() && y[i].is_finite() {
                out.push((x[i], y[i]));
            }
        }
        start = end;
    }
    out
}

/// Every `k`-th point so that at most `MAX_POINTS * 4` remain (for x-y loops).
pub(crate) fn stride(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    let k = n.div_ceil(MAX_POINTS * 4).max(1);
    (0..n)
        .step_by(k)
        .filter(|&i| x[i].is_finite() && y[i].is_finite())
        .map(|i| (x[i], y[i]))
        .collect()
}

/// A padded range over finite values (never empty).
pub(crate) fn range<'a>(points: impl Iterator<Item = &'a f64>) -> std::ops::Range<f64> {
    let (lo, hi) = points
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.05 * span
    } else if lo != 0.0 {
        0.1 * lo.abs()
    } else {
        1.0
    };
    (lo - pad)..(hi + pad)
}

/// A short label for a value: 4 significant digits.
pub(crate) fn short(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-3..1e4).contains(&a) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        let s = format!("{v:.3e}");
        match s.split_once('e') {
            Some((m, e)) => {
                let m = if m.contains('.') {
                    m.trim_end_matches('0').trim_end_matches('.')
                } else {
                    m
                };
                format!("{m}e{e}")
            }
            None => s,
        }
    }
}

/// A curve ready to draw.
pub(crate) struct Curve {
    /// Legend label (empty: none).
    pub label: String,
    /// Points in axis units.
    pub points: Vec<(f64, f64)>,
    /// Line colour.
    pub color: RGBColor,
}

/// The i-th colour of the palette shared by every plot.
pub(crate) fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 8] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

/// One panel: curves, optional vertical marker lines, labels, legend when labelled.
pub(crate) fn panel(
    area: &Area,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    curves: &[Curve],
    markers: &[f64],
    fixed_y: Option<std::ops::Range<f64>>,
) -> PlotResult<()> {
    let xr = range(curves.iter().flat_map(|c| c.points.iter().map(|p| &p.0)));
    let yr =
        fixed_y.unwrap_or_else(|| range(curves.iter().flat_map(|c| c.points.iter().map(|p| &p.1))));
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(10)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc(ylabel)
        .x_labels(8)
        .y_labels(6)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .x_label_formatter(&|v| format!("{}", (v * 1e4).round() / 1e4))
        .y_label_formatter(&|v| format!("{}", (v * 1e4).round() / 1e4))
        .draw()?;
    for &m in markers {
        if m >= xr.start && m <= xr.end {
            chart.draw_series(LineSeries::new(
                [(m, yr.start), (m, yr.end)],
                RGBColor(180, 180, 180).stroke_width(1),
            ))?;
        }
    }
    let mut labelled = false;
    for c in curves {
        let col = c.color;
        let s = chart.draw_series(LineSeries::new(
            c.points.iter().copied(),
            col.stroke_width(2),
        ))?;
        if !c.label.is_empty() {
            labelled = true;
            s.label(c.label.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2))
            });
        }
    }
    if labelled {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    Ok(())
}

pub(crate) fn render(
    name: &str,
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> PlotResult<()>,
) -> Result<String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(name, e.into()))?;
        draw(&root).map_err(|e| plot_error(name, e))?;
        root.present().map_err(|e| plot_error(name, e.into()))?;
    }
    Ok(buf)
}

/// A curve of a [`Panel`]: its legend label (empty: no legend entry) and (x, y) points.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points, in the units of the panel's axis labels.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A series from parallel x and y slices (non-finite points dropped).
    pub fn new(label: impl Into<String>, x: &[f64], y: &[f64]) -> Series {
        Series {
            label: label.into(),
            points: x
                .iter()
                .zip(y)
                .map(|(a, b)| (*a, *b))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect(),
        }
    }
}

/// One panel of a [`figure`].
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// x-axis label (with its unit).
    pub xlabel: String,
    /// y-axis label (with its unit).
    pub ylabel: String,
    /// Curves, drawn in order with the standard palette.
    pub series: Vec<Series>,
    /// Vertical marker lines at these x values.
    pub markers: Vec<f64>,
}

/// A figure of panels stacked vertically (400 px each), `width` px wide, as an SVG string.
/// Long curves are decimated keeping each bucket's extrema.
pub fn figure(name: &str, width: u32, panels: &[Panel]) -> Result<String> {
    if panels.is_empty() {
        return Err(plot_error(name, "a figure needs at least one panel".into()));
    }
    let curves: Vec<Vec<Curve>> = panels
        .iter()
        .map(|p| {
            p.series
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let (x, y): (Vec<f64>, Vec<f64>) = s.points.iter().copied().unzip();
                    // time-like curves keep their extrema; loops keep every k-th point
                    let monotone = x.windows(2).all(|w| w[1] >= w[0]);
                    Curve {
                        label: s.label.clone(),
                        points: if monotone {
                            decimate(&x, &y)
                        } else {
                            stride(&x, &y)
                        },
                        color: color(i),
                    }
                })
                .filter(|c| !c.points.is_empty())
                .collect()
        })
        .collect();
    let height = 400 * panels.len() as u32;
    render(name, (width, height), |root| {
        let areas = root.split_evenly((panels.len(), 1));
        for ((area, p), c) in areas.iter().zip(panels).zip(&curves) {
            if c.is_empty() {
                continue;
            }
            panel(area, &p.title, &p.xlabel, &p.ylabel, c, &p.markers, None)?;
        }
        Ok(())
    })
}

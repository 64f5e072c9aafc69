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
        (1e12, "T"),
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
    let mut out = Vec::with_capacity(MAX_POINTS + 2);
    extrema(x, y, 0..n, n.div_ceil(MAX_POINTS / 2), &mut out);
    out
}

/// [`decimate`] over each run of finite points, the runs separated by a `(NaN, NaN)` point,
/// where [`panel_with`] breaks the line: masked values are gaps, not lines across them.
pub(crate) fn decimate_gaps(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    // as decimate: every point up to MAX_POINTS, else buckets of the whole curve's size
    let bucket = if n <= MAX_POINTS {
        1
    } else {
        n.div_ceil(MAX_POINTS / 2)
    };
    let finite = |i: usize| x[i].is_finite() && y[i].is_finite();
    let mut out = Vec::with_capacity(MAX_POINTS + 2);
    let mut i = 0;
    while i < n {
        if !finite(i) {
            i += 1;
            continue;
        }
        let start = i;
        while i < n && finite(i) {
            i += 1;
        }
        if !out.is_empty() {
            out.push((f64::NAN, f64::NAN));
        }
        if bucket == 1 {
            out.extend((start..i).map(|k| (x[k], y[k])));
        } else {
            extrema(x, y, start..i, bucket, &mut out);
        }
    }
    out
}

/// Each bucket of `bucket` points of `x[span]`, `y[span]`: its min and max, in order.
fn extrema(
    x: &[f64],
    y: &[f64],
    span: std::ops::Range<usize>,
    bucket: usize,
    out: &mut Vec<(f64, f64)>,
) {
    let mut start = span.start;
    while start < span.end {
        let end = (start + bucket).min(span.end);
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

/// The i-th colour of the palette shared by every plot (10 colours; curves 10 and beyond
/// reuse them with another line style, see [`dash`]).
pub(crate) fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

/// Line style of the i-th curve of a panel: `None` solid (curves 0 to 9), else (dash,
/// gap) in pixels: dashed (10 to 19), dotted (20 to 29), long dashes (30 to 39), ...
pub(crate) fn dash(i: usize) -> Option<(u32, u32)> {
    match (i / 10) % 4 {
        0 => None,
        1 => Some((8, 4)),
        2 => Some((2, 3)),
        _ => Some((14, 4)),
    }
}

/// Tick labels of an axis over `r` with about `n` ticks: engineering notation that stays
/// short (at most about 7 characters): plain decimals with as many digits as the tick
/// step needs between 0.01 and 10^4, else an SI prefix on every tick (`940G`, `12.5µ`).
/// On a log10 axis (`log`) the tick at `v` is labelled with `10^v` (3 significant digits).
pub(crate) fn tick_label(r: &std::ops::Range<f64>, n: usize, log: bool) -> impl Fn(&f64) -> String {
    let span = (r.end - r.start).abs();
    let m = r.start.abs().max(r.end.abs());
    let (k, p) = if m.is_finite() && (m >= 1e4 || (m > 0.0 && m < 1e-2)) {
        prefix(m)
    } else {
        (1.0, "")
    };
    let step = span * k / n.max(1) as f64;
    let decimals = if step.is_finite() && step > 0.0 {
        (-step.log10()).ceil().clamp(0.0, 6.0) as usize
    } else {
        2
    };
    move |v: &f64| {
        if log {
            return eng(10f64.powf(*v));
        }
        let s = format!("{:.*}", decimals, v * k);
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        let s = if s == "-0" { "0".to_string() } else { s };
        format!("{s}{p}")
    }
}

/// A value with 3 significant digits and an SI prefix from f to P (`1.5M`, `250µ`, `0`);
/// beyond, scientific notation (`1e18`).
pub(crate) fn eng(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return if v == 0.0 { "0".into() } else { format!("{v}") };
    }
    const P: [&str; 11] = ["f", "p", "n", "µ", "m", "", "k", "M", "G", "T", "P"];
    let e3 = (v.abs().log10() / 3.0).floor() as i32;
    if !(-5..=5).contains(&e3) {
        return short(v);
    }
    let x = v / 10f64.powi(3 * e3);
    let d = if x.abs() >= 99.95 {
        0
    } else if x.abs() >= 9.995 {
        1
    } else {
        2
    };
    let s = format!("{x:.d$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    format!("{s}{}", P[(e3 + 5) as usize])
}

/// Options of a [`panel_with`].
#[derive(Default)]
pub(crate) struct PanelOpts<'a> {
    /// The x values are log10 of the quantity: ticks are labelled with the quantity.
    pub log_x: bool,
    /// Labels of the vertical markers (same order; missing ones unlabelled).
    pub marker_labels: &'a [String],
    /// Fixed y range (default: the curves' padded range).
    pub fixed_y: Option<std::ops::Range<f64>>,
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
    panel_with(
        area,
        title,
        xlabel,
        ylabel,
        curves,
        markers,
        PanelOpts {
            fixed_y,
            ..Default::default()
        },
    )
}

/// Largest number of legend entries drawn (the others are counted in a last line).
const MAX_LEGEND: usize = 40;

/// One panel with options: the data area on the left, the legend (when a curve is
/// labelled) in a column on its right, outside the data; curves beyond the 10th change
/// line style ([`dash`]); dashed grey markers with their labels at the top.
pub(crate) fn panel_with(
    area: &Area,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    curves: &[Curve],
    markers: &[f64],
    opts: PanelOpts,
) -> PlotResult<()> {
    let xr = range(curves.iter().flat_map(|c| c.points.iter().map(|p| &p.0)));
    let yr = opts
        .fixed_y
        .clone()
        .unwrap_or_else(|| range(curves.iter().flat_map(|c| c.points.iter().map(|p| &p.1))));
    let labelled: Vec<(usize, &Curve)> = curves
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.label.is_empty())
        .collect();
    let (w, _) = area.dim_in_pixel();
    let (chart_area, legend_area) = if labelled.is_empty() {
        (area.clone(), None)
    } else {
        let chars = labelled
            .iter()
            .map(|(_, c)| c.label.chars().count())
            .max()
            .unwrap_or(0);
        let lw = (chars as u32 * 7 + 45).clamp(90, w * 2 / 5);
        let (a, b) = area.split_horizontally(w.saturating_sub(lw));
        (a, Some(b))
    };
    let (cw, _) = chart_area.dim_in_pixel();
    let nx = ((cw.saturating_sub(90)) / 90).clamp(3, 8) as usize;
    let ny = 6;
    let xfmt = tick_label(&xr, nx, opts.log_x);
    let yfmt = tick_label(&yr, ny, false);
    let mut chart = ChartBuilder::on(&chart_area)
        .caption(title, ("sans-serif", 22))
        .margin(10)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc(ylabel)
        .x_labels(nx)
        .y_labels(ny)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .x_label_formatter(&xfmt)
        .y_label_formatter(&yfmt)
        .draw()?;
    let marker_style = RGBColor(90, 90, 90).stroke_width(1);
    for (i, &m) in markers.iter().enumerate() {
        if m >= xr.start && m <= xr.end {
            chart.draw_series(DashedLineSeries::new(
                [(m, yr.start), (m, yr.end)],
                6,
                4,
                marker_style,
            ))?;
            if let Some(l) = opts.marker_labels.get(i) {
                let top = yr.end - 0.02 * (yr.end - yr.start);
                chart.draw_series(std::iter::once(Text::new(
                    l.clone(),
                    (m, top),
                    ("sans-serif", 13).into_font().color(&RGBColor(60, 60, 60)),
                )))?;
            }
        }
    }
    for (i, c) in curves.iter().enumerate() {
        let style = c.color.stroke_width(2);
        // a non-finite point breaks the line (see decimate_gaps)
        let pieces: Vec<&[(f64, f64)]> = if c.points.iter().all(|p| p.0.is_finite()) {
            vec![&c.points]
        } else {
            c.points
                .split(|p| !p.0.is_finite())
                .filter(|p| !p.is_empty())
                .collect()
        };
        for piece in pieces {
            match dash(i) {
                None => {
                    chart.draw_series(LineSeries::new(piece.iter().copied(), style))?;
                }
                Some((d, g)) => {
                    chart.draw_series(DashedLineSeries::new(piece.iter().copied(), d, g, style))?;
                }
            }
        }
    }
    if let Some(la) = legend_area {
        let (_, lh) = la.dim_in_pixel();
        let shown = labelled.len().min(MAX_LEGEND);
        let more = labelled.len() - shown;
        let lines = shown + usize::from(more > 0);
        let top = 40i32;
        let room = lh.saturating_sub(top as u32 + 50).max(40) as i32;
        let pitch = (room / lines.max(1) as i32).clamp(9, 20);
        let font = (pitch - 2).clamp(8, 14);
        for (row, (i, c)) in labelled.iter().take(shown).enumerate() {
            let y = top + row as i32 * pitch + pitch / 2;
            let style = c.color.stroke_width(2);
            match dash(*i) {
                None => la.draw(&PathElement::new(vec![(4, y), (34, y)], style))?,
                Some((d, g)) => la.draw(&plotters::element::DashedPathElement::new(
                    vec![(4, y), (34, y)],
                    d,
                    g,
                    style,
                ))?,
            }
            la.draw(&Text::new(
                c.label.clone(),
                (40, y - font / 2),
                ("sans-serif", font),
            ))?;
        }
        if more > 0 {
            let y = top + shown as i32 * pitch;
            la.draw(&Text::new(
                format!("... and {more} more"),
                (40, y),
                ("sans-serif", font),
            ))?;
        }
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
                            decimate_gaps(&x, &y)
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

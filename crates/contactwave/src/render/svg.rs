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

/// Draw the point marker of the `rank`-th marked curve of a panel at pixel `at` of `area`
/// (its legend): circle, square, triangle, cross (in that order, repeating).
fn legend_marker(area: &Area, at: (i32, i32), rank: usize, style: ShapeStyle) -> PlotResult<()> {
    let e = EmptyElement::at(at);
    match rank % 4 {
        0 => area.draw(&(e + Circle::new((0, 0), 4, style)))?,
        1 => area.draw(&(e + Rectangle::new([(-4, -4), (4, 4)], style)))?,
        2 => area.draw(&(e + TriangleMarker::new((0, 0), 5, style)))?,
        _ => area.draw(&(e + Cross::new((0, 0), 4, style)))?,
    }
    Ok(())
}

/// Which curves coincide with another one of the panel (same x, largest |dy| within 1% of
/// the panel's y span): these get point markers so that they can be told apart.
pub(crate) fn coinciding(curves: &[Curve]) -> Vec<bool> {
    let ys = curves.iter().flat_map(|c| c.points.iter().map(|p| p.1));
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    let tol = 0.01 * (hi - lo);
    let same = |a: &Curve, b: &Curve| {
        a.points.len() == b.points.len()
            && a.points.len() > 1
            && a.points
                .iter()
                .zip(&b.points)
                .all(|(p, q)| p.0 == q.0 && (p.1 - q.1).abs() <= tol)
    };
    (0..curves.len())
        .map(|i| (0..curves.len()).any(|j| j != i && same(&curves[i], &curves[j])))
        .collect()
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

/// Tick labels of an axis over `r` with about `n` ticks, in engineering notation that stays
/// short (at most about 7 characters): plain decimals with as many digits as the tick
/// step needs between 0.01 and 10^4, else one power of ten, a multiple of 3, on every tick
/// (`940e9`, `12.5e-6`; the axis label names the unit). On a log10 axis (`log`) the tick
/// at `v` is labelled with `10^v` ([`eng`]: `1e12`, `10e12`, `100e12`).
pub(crate) fn tick_label(
    r: &std::ops::Range<f64>,
    n: usize,
    log: bool,
) -> impl Fn(&f64) -> String + use<> {
    let span = (r.end - r.start).abs();
    let m = r.start.abs().max(r.end.abs());
    let (k, p) = if m.is_finite() && (m >= 1e4 || (m > 0.0 && m < 1e-2)) {
        let e3 = (m.log10() / 3.0).floor() as i32 * 3;
        (10f64.powi(-e3), format!("e{e3}"))
    } else {
        (1.0, String::new())
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
        match s.as_str() {
            "0" | "-0" => "0".to_string(),
            _ => format!("{s}{p}"),
        }
    }
}

/// A value in engineering notation: 3 significant digits and a power of ten that is a
/// multiple of 3 (`1e12`, `10e12`, `250e-6`); plain between 0.01 and 10^4 (`0.5`, `1000`).
/// Log-axis ticks: the axis label names the unit (`C_N, Pa/m (log scale)`).
pub(crate) fn eng(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() || v == 0.0 || (1e-2..1e4).contains(&a) {
        return if v.is_finite() {
            short(v)
        } else {
            format!("{v}")
        };
    }
    let e3 = (a.log10() / 3.0).floor() as i32 * 3;
    let m = v / 10f64.powi(e3);
    let m = if m.abs() >= 999.5 { m / 1000.0 } else { m };
    let e3 = if (v / 10f64.powi(e3)).abs() >= 999.5 {
        e3 + 3
    } else {
        e3
    };
    let s = format!("{m:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    format!("{s}e{e3}")
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
    /// Curves drawn with point markers too (by index; missing ones without).
    pub marked: &'a [bool],
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
    // the rank of each marked curve (its marker shape) and its first marked point, staggered
    // so that the markers of coinciding curves do not hide each other
    let rank = |i: usize| -> Option<usize> {
        (opts.marked.get(i) == Some(&true)).then(|| opts.marked[..i].iter().filter(|m| **m).count())
    };
    let n_marked = opts.marked.iter().filter(|m| **m).count().max(1);
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
        if let Some(r) = rank(i) {
            let every = (c.points.len() / 12).max(1);
            let first = r * every / n_marked;
            let pts = c.points.iter().skip(first).step_by(every).copied();
            let st = c.color.stroke_width(2);
            let at = EmptyElement::at;
            match r % 4 {
                0 => chart.draw_series(pts.map(|p| at(p) + Circle::new((0, 0), 4, st)))?,
                1 => chart
                    .draw_series(pts.map(|p| at(p) + Rectangle::new([(-4, -4), (4, 4)], st)))?,
                2 => chart.draw_series(pts.map(|p| at(p) + TriangleMarker::new((0, 0), 5, st)))?,
                _ => chart.draw_series(pts.map(|p| at(p) + Cross::new((0, 0), 4, st)))?,
            };
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
            if let Some(r) = rank(*i) {
                legend_marker(&la, (19, y), r, c.color.stroke_width(2))?;
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
    /// Line colour (RGB; default: the palette's colour of the series' index).
    pub color: Option<(u8, u8, u8)>,
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
            color: None,
        }
    }

    /// The same series drawn in `rgb`.
    pub fn colored(mut self, rgb: (u8, u8, u8)) -> Series {
        self.color = Some(rgb);
        self
    }
}

/// `n` colours of one ramp, light to dark blue (for curves ordered in time or amplitude).
pub fn ramp(n: usize) -> Vec<(u8, u8, u8)> {
    (0..n)
        .map(|i| {
            let t = if n > 1 {
                i as f64 / (n - 1) as f64
            } else {
                1.0
            };
            let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
            (mix(158.0, 8.0), mix(202.0, 48.0), mix(225.0, 107.0))
        })
        .collect()
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
                        color: s
                            .color
                            .map(|(r, g, b)| RGBColor(r, g, b))
                            .unwrap_or_else(|| color(i)),
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
            let marked = coinciding(c);
            panel_with(
                area,
                &p.title,
                &p.xlabel,
                &p.ylabel,
                c,
                &p.markers,
                PanelOpts {
                    marked: &marked,
                    ..Default::default()
                },
            )?;
        }
        Ok(())
    })
}

/// A space-time map of a discrete state along a line (a crack's open/stick/slip state):
/// `states[k * n + j]` the state of point `j` (at `positions[j]`, display units) at record
/// `k` (at `times[k]`, display units), each drawn as the cell from its point's midpoints to
/// its neighbours' and from its record's time to the next; runs of one state along a row
/// are merged and the rows decimated to at most `MAX_ROWS`, so the file stays small.
/// `classes`: each state's value, legend label and colour.
pub struct StateMap<'a> {
    /// Title above the map.
    pub title: String,
    /// x-axis label (with its unit).
    pub xlabel: String,
    /// y-axis label (with its unit).
    pub ylabel: String,
    /// The points' positions, increasing.
    pub positions: &'a [f64],
    /// The records' times, increasing.
    pub times: &'a [f64],
    /// The states, record-major.
    pub states: &'a [f64],
    /// Each state's value, label and colour.
    pub classes: &'a [(f64, &'a str, (u8, u8, u8))],
}

/// Rows (records) drawn at most by [`state_map`].
pub const MAX_ROWS: usize = 400;

/// [`StateMap`] as an SVG string (900 x 500 px).
pub fn state_map(name: &str, m: &StateMap) -> Result<String> {
    let (n, rows) = (m.positions.len(), m.times.len());
    if n == 0 || rows == 0 || m.states.len() < n * rows {
        return Err(plot_error(
            name,
            "a state map needs points and records".into(),
        ));
    }
    // cell edges: midpoints between the points, half a spacing beyond the ends
    let half = |a: f64, b: f64| 0.5 * (b - a);
    let first = if n > 1 {
        half(m.positions[0], m.positions[1])
    } else {
        0.5
    };
    let last = if n > 1 {
        half(m.positions[n - 2], m.positions[n - 1])
    } else {
        0.5
    };
    let mut edges = vec![m.positions[0] - first];
    edges.extend(m.positions.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    edges.push(m.positions[n - 1] + last);
    let step = rows.div_ceil(MAX_ROWS);
    let dt = if rows > 1 {
        m.times[1] - m.times[0]
    } else {
        1.0
    };
    let t_end = m.times[rows - 1] + dt;
    // the legend in a column of its own right of the map (over the map it would hide the
    // states at late times near the far end), as wide as its longest label (about 7.5 px a
    // character of 14 px sans-serif)
    let longest = m
        .classes
        .iter()
        .map(|c| c.1.chars().count())
        .max()
        .unwrap_or(0);
    let legend = 40 + (7.5 * longest as f64).ceil() as u32;
    render(name, (800 + legend, 500), |root| {
        let (map_area, legend_area) = root.split_horizontally(800);
        let mut chart = ChartBuilder::on(&map_area)
            .caption(&m.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(edges[0]..edges[n], m.times[0]..t_end)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(m.xlabel.as_str())
            .y_desc(m.ylabel.as_str())
            .draw()?;
        let fill = |v: f64| {
            m.classes
                .iter()
                .find(|c| c.0 == v)
                .map(|c| RGBColor(c.2 .0, c.2 .1, c.2 .2))
        };
        let mut cells = Vec::new();
        for k in (0..rows).step_by(step) {
            let (t0, t1) = (m.times[k], m.times.get(k + step).copied().unwrap_or(t_end));
            let row = &m.states[k * n..(k + 1) * n];
            let mut j = 0;
            while j < n {
                let v = row[j];
                let mut e = j + 1;
                while e < n && row[e] == v {
                    e += 1;
                }
                if let Some(c) = fill(v) {
                    cells.push(Rectangle::new([(edges[j], t0), (edges[e], t1)], c.filled()));
                }
                j = e;
            }
        }
        chart.draw_series(cells)?;
        for (row, &(_, label, (r, g, b))) in m.classes.iter().enumerate() {
            let y = 50 + 24 * row as i32;
            legend_area.draw(&Rectangle::new(
                [(6, y - 6), (18, y + 6)],
                RGBColor(r, g, b).filled(),
            ))?;
            legend_area.draw(&Text::new(label, (24, y - 7), ("sans-serif", 14)))?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_map_merges_runs_and_names_its_states() {
        let positions = [0.0, 1.0, 2.0, 3.0];
        let times = [0.0, 1.0, 2.0];
        // row 0: all stick (one cell); row 1: open, open, slip, stick (three cells);
        // row 2: a state without a class (not drawn)
        let states = [1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 2.0, 1.0, 5.0, 5.0, 5.0, 5.0];
        let classes = [
            (0.0, "open", (200, 60, 60)),
            (1.0, "stick", (60, 60, 200)),
            (2.0, "slip", (240, 180, 40)),
        ];
        let svg = state_map(
            "m.svg",
            &StateMap {
                title: "t".into(),
                xlabel: "x".into(),
                ylabel: "t".into(),
                positions: &positions,
                times: &times,
                states: &states,
                classes: &classes,
            },
        )
        .unwrap();
        for label in ["open", "stick", "slip"] {
            assert!(
                svg.contains(&format!("\n{label}\n</text>")),
                "{label}: {svg}"
            );
        }
        // the cells in the map's colours: 4 (plus the 3 legend boxes)
        let fills = |rgb: &str| svg.matches(&format!("fill=\"{rgb}\"")).count();
        assert_eq!(fills("#C83C3C"), 2, "open");
        assert_eq!(fills("#3C3CC8"), 3, "stick");
        assert_eq!(fills("#F0B428"), 2, "slip");
    }

    #[test]
    fn ticks_are_in_engineering_notation_without_si_letters() {
        // log axes (the Pa/m of a stiffness sweep): powers of ten in multiples of 3
        let log = tick_label(&(9.0..16.0), 6, true);
        let labels: Vec<String> = [10.0, 12.0, 13.0, 14.0, 15.0, -4.0 + 0.39794]
            .iter()
            .map(&log)
            .collect();
        assert_eq!(
            labels,
            ["10e9", "1e12", "10e12", "100e12", "1e15", "250e-6"]
        );
        assert_eq!(log(&-std::f64::consts::LOG10_2), "0.5");
        // linear axes beyond 10^4: one power of ten on every tick, never `940G` or `20k`
        let lin = tick_label(&(0.0..9.4e11), 5, false);
        assert_eq!(lin(&9.4e11), "940e9");
        assert_eq!(lin(&0.0), "0");
        assert_eq!(tick_label(&(0.0..6e4), 4, false)(&2e4), "20e3");
        assert_eq!(tick_label(&(0.0..2.0), 4, false)(&1.5), "1.5");
    }

    #[test]
    fn coinciding_curves_get_point_markers() {
        let x: Vec<f64> = (0..30).map(|i| i as f64 / 29.0).collect();
        let y: Vec<f64> = x.iter().map(|v| v * v).collect();
        let y2: Vec<f64> = y.iter().map(|v| v + 1e-4).collect();
        let apart: Vec<f64> = x.iter().map(|v| 1.0 - v).collect();
        let fig = |series: Vec<Series>| {
            figure(
                "t.svg",
                600,
                &[Panel {
                    series,
                    ..Default::default()
                }],
            )
            .unwrap()
        };
        let distinct = fig(vec![Series::new("a", &x, &y), Series::new("b", &x, &apart)]);
        assert!(!distinct.contains("<circle") && !distinct.contains("<polygon"));
        let same = fig(vec![
            Series::new("a", &x, &y),
            Series::new("b", &x, &y2),
            Series::new("c", &x, &apart),
        ]);
        // the first coinciding curve: circles; the second: squares (rect); none for "c"
        assert!(
            same.matches("<circle").count() >= 12,
            "{}",
            same.matches("<circle").count()
        );
        assert!(same.matches("<rect").count() > 12);
        let marked = coinciding(&[
            Curve {
                label: "a".into(),
                points: x.iter().copied().zip(y.iter().copied()).collect(),
                color: color(0),
            },
            Curve {
                label: "c".into(),
                points: x.iter().copied().zip(apart.iter().copied()).collect(),
                color: color(1),
            },
        ]);
        assert_eq!(marked, [false, false]);
    }
}

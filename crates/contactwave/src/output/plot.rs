//! SVG plots (plotters, SVG backend, rendered into strings).
//!
//! Quantities are drawn in scaled SI units (e.g. µs, nm, MPa) named in the axis labels.
//! Long time series are reduced to at most [`MAX_POINTS`] points per curve by keeping the
//! minimum and maximum of each bucket, which preserves peaks.

use crate::error::{Error, Result};
use crate::law::ContactLaw;
use crate::study::{AxisSpec, Sweep, SweepTable};
use crate::RunResult;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Largest number of points drawn per curve.
const MAX_POINTS: usize = 4000;

type PlotResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A plotting failure as an I/O error on the named file.
pub(crate) fn plot_error(name: &str, e: Box<dyn std::error::Error>) -> Error {
    Error::io(name, std::io::Error::other(format!("plot: {e}")))
}

/// An SI prefix for values up to `max_abs`: (multiplier, prefix).
fn prefix(max_abs: f64) -> (f64, &'static str) {
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

fn max_abs(v: &[f64]) -> f64 {
    v.iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Scale a quantity for display: (scaled values, unit label such as `MPa`).
fn scaled(v: &[f64], unit: &str) -> (Vec<f64>, String) {
    let (k, p) = prefix(max_abs(v));
    (v.iter().map(|x| x * k).collect(), format!("{p}{unit}"))
}

/// Reduce a curve to at most `MAX_POINTS` points keeping each bucket's min and max.
fn decimate(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
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
fn stride(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    let k = n.div_ceil(MAX_POINTS * 4).max(1);
    (0..n)
        .step_by(k)
        .filter(|&i| x[i].is_finite() && y[i].is_finite())
        .map(|i| (x[i], y[i]))
        .collect()
}

/// A padded range over finite values (never empty).
fn range<'a>(points: impl Iterator<Item = &'a f64>) -> std::ops::Range<f64> {
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
fn short(v: f64) -> String {
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

struct Curve {
    label: String,
    points: Vec<(f64, f64)>,
    color: RGBColor,
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
fn panel(
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

fn render(
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

/// `time_histories.svg`: gap, contact stress and beta against time, three panels.
pub fn time_histories(r: &RunResult) -> Result<String> {
    let o = &r.interface;
    let (t, tu) = scaled(&o.t, "s");
    let (gap, gu) = scaled(&o.gap, "m");
    let (st, su) = scaled(&o.contact_stress, "Pa");
    render("time_histories.svg", (900, 900), |root| {
        let areas = root.split_evenly((3, 1));
        let one = |y: &[f64]| {
            vec![Curve {
                label: String::new(),
                points: decimate(&t, y),
                color: color(0),
            }]
        };
        panel(
            &areas[0],
            "Gap at the interface",
            &format!("t, {tu}"),
            &format!("gap [u], {gu}"),
            &one(&gap),
            &[],
            None,
        )?;
        panel(
            &areas[1],
            "Contact stress (tension > 0)",
            &format!("t, {tu}"),
            &format!("stress, {su}"),
            &one(&st),
            &[],
            None,
        )?;
        panel(
            &areas[2],
            "Adhesion intensity beta",
            &format!("t, {tu}"),
            "beta",
            &one(&o.beta),
            &[],
            Some(-0.05..1.05),
        )?;
        Ok(())
    })
}

/// `waves.svg`: incident and reflected stress at the probe.
pub fn waves(r: &RunResult) -> Result<String> {
    let p = &r.probe;
    let (t, tu) = scaled(&p.t, "s");
    let peak = max_abs(&p.incident_stress).max(max_abs(&p.reflected_stress));
    let (k, pre) = prefix(peak);
    let si: Vec<f64> = p.incident_stress.iter().map(|v| v * k).collect();
    let sr: Vec<f64> = p.reflected_stress.iter().map(|v| v * k).collect();
    render("waves.svg", (900, 450), |root| {
        panel(
            root,
            &format!("Stress at the probe, x = {} m", p.x),
            &format!("t, {tu}"),
            &format!("stress, {pre}Pa"),
            &[
                Curve {
                    label: "incident".into(),
                    points: decimate(&t, &si),
                    color: color(0),
                },
                Curve {
                    label: "reflected".into(),
                    points: decimate(&t, &sr),
                    color: color(1),
                },
            ],
            &[],
            None,
        )
    })
}

/// `spectrum.svg`: incident and reflected velocity spectra, dB relative to the incident
/// peak (floor at -160 dB), grey markers at the harmonics n f0.
pub fn spectrum(r: &RunResult, f0: f64) -> Result<String> {
    let f = &r.incident_spectrum.frequency;
    let (fs, fu) = scaled(f, "Hz");
    let reference = max_abs(&r.incident_spectrum.magnitude).max(f64::MIN_POSITIVE);
    let db = |m: &[f64]| -> Vec<f64> {
        m.iter()
            .map(|v| (20.0 * (v.abs() / reference).log10()).max(-160.0))
            .collect()
    };
    let di = db(&r.incident_spectrum.magnitude);
    let dr = db(&r.reflected_spectrum.magnitude);
    let k = if f.is_empty() {
        1.0
    } else {
        fs.last().copied().unwrap_or(1.0) / f.last().copied().unwrap_or(1.0)
    };
    let k = if k.is_finite() && k > 0.0 { k } else { 1.0 };
    let markers: Vec<f64> = (1..=6).map(|n| n as f64 * f0 * k).collect();
    render("spectrum.svg", (900, 450), |root| {
        panel(
            root,
            "Velocity spectra (markers: harmonics n f0)",
            &format!("frequency, {fu}"),
            "magnitude, dB re. incident peak",
            &[
                Curve {
                    label: "incident".into(),
                    points: decimate(&fs, &di),
                    color: color(0),
                },
                Curve {
                    label: "reflected".into(),
                    points: decimate(&fs, &dr),
                    color: color(1),
                },
            ],
            &markers,
            None,
        )
    })
}

/// `stress_gap.svg`: contact stress against gap over the whole run.
pub fn stress_gap(r: &RunResult) -> Result<String> {
    let o = &r.interface;
    let (gap, gu) = scaled(&o.gap, "m");
    let (st, su) = scaled(&o.contact_stress, "Pa");
    render("stress_gap.svg", (700, 550), |root| {
        panel(
            root,
            "Contact stress against gap",
            &format!("gap [u], {gu}"),
            &format!("contact stress, {su}"),
            &[Curve {
                label: String::new(),
                points: stride(&gap, &st),
                color: color(0),
            }],
            &[],
            None,
        )
    })
}

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

/// `sweep.svg`: the results against the first axis, one curve per combination of the other
/// axes (at most 12 curves are labelled): `A1_over_Ainc` and `A2_over_Ainc` for half-space
/// sweeps; `first_mode_hz`, `A1`, `A2_over_A1`, the mean contact stiffness and the minimum
/// contact pressure for bar-stack sweeps.
pub fn sweep(sw: &Sweep, table: &SweepTable) -> Result<String> {
    let name = "sweep.svg";
    let Some(first) = sw.axes.first() else {
        return Err(plot_error(name, "the sweep has no axis".into()));
    };
    let xcol = table
        .column(&first.parameter)
        .ok_or_else(|| plot_error(name, format!("no column `{}`", first.parameter).into()))?;
    let positive = first.values.iter().all(|v| *v > 0.0);
    let (lo, hi) = first
        .values
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    let log_x = positive
        && (matches!(first.spec, AxisSpec::Logspace { .. }) || (lo > 0.0 && hi / lo >= 1e3));
    let xlabel = if log_x {
        format!("log10({})", first.parameter)
    } else {
        first.parameter.clone()
    };
    let others: Vec<(usize, &str)> = sw.axes[1..]
        .iter()
        .filter_map(|a| {
            table
                .column(&a.parameter)
                .map(|c| (c, a.parameter.as_str()))
        })
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
    let curves_of = |col: Option<usize>| -> Vec<Curve> {
        let Some(col) = col else { return vec![] };
        groups
            .iter()
            .enumerate()
            .map(|(i, (key, rs))| {
                let mut pts: Vec<(f64, f64)> = rs
                    .iter()
                    .map(|r| {
                        let x = r[xcol];
                        (if log_x { x.log10() } else { x }, r[col])
                    })
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let label = if others.is_empty() || i >= 12 {
                    String::new()
                } else {
                    others
                        .iter()
                        .zip(key)
                        .map(|((_, n), v)| format!("{n} = {}", short(*v)))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
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
    let panels: Vec<(&str, &str, &str)> = if table.column("A1_over_Ainc").is_some() {
        vec![
            (
                "A1_over_Ainc",
                "Fundamental of the reflected wave",
                "A1 / A_inc",
            ),
            (
                "A2_over_Ainc",
                "Second harmonic of the reflected wave",
                "A2 / A_inc",
            ),
        ]
    } else {
        vec![
            ("first_mode_hz", "First mode", "f1, Hz"),
            ("A1", "Response at the first mode", "A1, m/s^2"),
            ("A2_over_A1", "Second harmonic", "A2 / A1"),
            (
                "mean_contact_stiffness_0",
                "Mean contact stiffness, interface 1 (eq. 4.2)",
                "K, Pa/m",
            ),
            (
                "min_contact_pressure",
                "Minimum contact pressure",
                "p_min, Pa",
            ),
        ]
        .into_iter()
        .filter(|(c, _, _)| table.column(c).is_some())
        .collect()
    };
    if panels.is_empty() {
        return Err(plot_error(name, "no known result column to plot".into()));
    }
    let data: Vec<Vec<Curve>> = panels
        .iter()
        .map(|(c, _, _)| curves_of(table.column(c)))
        .collect();
    let height = 400 * panels.len() as u32;
    render(name, (900, height), |root| {
        let areas = root.split_evenly((panels.len(), 1));
        for ((area, (_, title, ylabel)), curves) in areas.iter().zip(&panels).zip(&data) {
            panel(area, title, &xlabel, ylabel, curves, &[], None)?;
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

//! The files of a half-space run (`contactwave run`), all SI units:
//!
//! | file | content |
//! |---|---|
//! | `summary.json` | `scenario` (file name) then the [`crate::analysis::Summary`] keys in order (non-finite values as `null`), then the wave speeds (m/s) and impedances (Pa s/m) used: `medium_wave_speed`, `medium_impedance`, `medium_shear_wave_speed`, `medium_shear_impedance` and the same of `counterpart_` (none for a rigid wall) |
//! | `timeseries.csv` | `t,gap,contact_stress,beta,incident_stress,reflected_stress,transmitted_stress` at the interface: s, m, Pa, -, Pa, Pa, Pa |
//! | `probe.csv` | `t,incident_stress,reflected_stress,incident_velocity,reflected_velocity,displacement` at the probe: s, Pa, Pa, m/s, m/s, m |
//! | `spectrum.csv` | `frequency,incident,reflected`: Hz and amplitude spectra of the incident and reflected particle velocity, m/s |
//! | `time_histories.svg` | gap, contact stress and adhesion beta against time (three panels) |
//! | `waves.svg` | incident and reflected stress at the probe |
//! | `spectrum.svg` | spectra in dB relative to the incident peak, with markers at the harmonics n f0 |
//! | `stress_gap.svg` | contact stress against gap over the run (the hysteresis loop) |
//! | `shear.csv` | with a tangential part: `t,shear_gap,slip,shear_stress,friction_limit,slip_state,shear_incident_stress,shear_reflected_stress,shear_transmitted_stress`: s, m, m, Pa, Pa, -, Pa, Pa, Pa (slip_state 0 stick, +-1 slipping, empty free) |
//! | `shear_loop.svg` | with a tangential part: shear stress against tangential gap (the friction hysteresis loop) and the friction limit +-mu N against time |
//!
//! The SVG files (and the functions that draw them) need the `plot` feature (on by
//! default); without it a run has its JSON and CSV files only.

use super::RunResult;
use crate::error::Result;
#[cfg(feature = "plot")]
use crate::render::svg::{color, decimate, max_abs, panel, prefix, render, scaled, stride, Curve};
use crate::render::{csv_columns, summary_json, OutputFile};

/// Header of `timeseries.csv`.
pub const TIMESERIES_HEADER: &str =
    "t,gap,contact_stress,beta,incident_stress,reflected_stress,transmitted_stress";
/// Header of `probe.csv`.
pub const PROBE_HEADER: &str =
    "t,incident_stress,reflected_stress,incident_velocity,reflected_velocity,displacement";
/// Header of `shear.csv`.
pub const SHEAR_HEADER: &str = "t,shear_gap,slip,shear_stress,friction_limit,slip_state,\
shear_incident_stress,shear_reflected_stress,shear_transmitted_stress";

/// `shear.csv` of a run with a tangential part (interface values, SI); `None` without.
pub fn shear_csv(result: &RunResult) -> Option<String> {
    let sh = result.shear.as_ref()?;
    let o = &sh.interface;
    Some(csv_columns(
        SHEAR_HEADER,
        &[
            &o.t,
            &o.gap,
            &sh.slip,
            &o.contact_stress,
            &sh.friction_limit,
            &sh.slip_state,
            &o.incident_stress,
            &o.reflected_stress,
            &o.transmitted_stress,
        ],
    ))
}

/// Header of `spectrum.csv`.
pub const SPECTRUM_HEADER: &str = "frequency,incident,reflected";

/// `timeseries.csv` of a run (interface values, SI).
pub fn timeseries_csv(result: &RunResult) -> String {
    let o = &result.interface;
    csv_columns(
        TIMESERIES_HEADER,
        &[
            &o.t,
            &o.gap,
            &o.contact_stress,
            &o.beta,
            &o.incident_stress,
            &o.reflected_stress,
            &o.transmitted_stress,
        ],
    )
}

/// `probe.csv` of a run (probe values, SI).
pub fn probe_csv(result: &RunResult) -> String {
    let p = &result.probe;
    csv_columns(
        PROBE_HEADER,
        &[
            &p.t,
            &p.incident_stress,
            &p.reflected_stress,
            &p.incident_velocity,
            &p.reflected_velocity,
            &p.displacement,
        ],
    )
}

/// `spectrum.csv` of a run: frequency (Hz), incident and reflected velocity magnitudes
/// (m/s) on the incident spectrum's frequency grid.
pub fn spectrum_csv(result: &RunResult) -> String {
    csv_columns(
        SPECTRUM_HEADER,
        &[
            &result.incident_spectrum.frequency,
            &result.incident_spectrum.magnitude,
            &result.reflected_spectrum.magnitude,
        ],
    )
}

/// The summary of `summary.json`: the run's summary keys, then the wave speeds and
/// impedances it used (`medium_wave_speed`, `medium_impedance`, ...).
pub(super) fn summary_with_waves(result: &RunResult) -> crate::analysis::Summary {
    let mut s = result.summary.clone();
    for (k, v) in &result.waves {
        s.set(k, *v);
    }
    s
}

/// Every file of a run, rendered in memory (see the module doc for the list).
pub fn run_files(result: &RunResult) -> Result<Vec<OutputFile>> {
    let mut files = vec![
        OutputFile::new(
            "summary.json",
            summary_json(&result.file, &summary_with_waves(result)),
        ),
        OutputFile::new("timeseries.csv", timeseries_csv(result)),
        OutputFile::new("probe.csv", probe_csv(result)),
        OutputFile::new("spectrum.csv", spectrum_csv(result)),
    ];
    if let Some(csv) = shear_csv(result) {
        files.push(OutputFile::new("shear.csv", csv));
    }
    files.extend(figures(result)?);
    Ok(files)
}

/// The SVG files of a run, rendered in memory (none without the `plot` feature).
#[cfg(feature = "plot")]
pub fn figures(result: &RunResult) -> Result<Vec<OutputFile>> {
    let mut v = vec![
        OutputFile::new("time_histories.svg", time_histories(result)?),
        OutputFile::new("waves.svg", waves(result)?),
        OutputFile::new("spectrum.svg", spectrum(result, result.fundamental)?),
        OutputFile::new("stress_gap.svg", stress_gap(result)?),
    ];
    if result.shear.is_some() {
        v.push(OutputFile::new("shear_loop.svg", shear_loop(result)?));
    }
    Ok(v)
}

/// The SVG files of a run, rendered in memory (none without the `plot` feature).
#[cfg(not(feature = "plot"))]
pub fn figures(_result: &RunResult) -> Result<Vec<OutputFile>> {
    Ok(Vec::new())
}

/// `time_histories.svg`: gap, contact stress and beta against time, three panels.
#[cfg(feature = "plot")]
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
#[cfg(feature = "plot")]
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
#[cfg(feature = "plot")]
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
    let labels: Vec<String> = (1..=6)
        .map(|n| {
            if n == 1 {
                "f0".into()
            } else {
                format!("{n}f0")
            }
        })
        .collect();
    render("spectrum.svg", (900, 450), |root| {
        crate::render::svg::panel_with(
            root,
            "Velocity spectra (dashed: harmonics n f0)",
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
            crate::render::svg::PanelOpts {
                marker_labels: &labels,
                ..Default::default()
            },
        )
    })
}

/// `stress_gap.svg`: contact stress against gap over the whole run.
#[cfg(feature = "plot")]
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

/// `shear_loop.svg`: shear stress against tangential gap (the friction loop, left) and
/// shear stress with the friction limit `+-mu N` against time (right).
#[cfg(feature = "plot")]
pub fn shear_loop(r: &RunResult) -> Result<String> {
    let Some(sh) = &r.shear else {
        return Ok(String::new());
    };
    let o = &sh.interface;
    let (gap, gu) = scaled(&o.gap, "m");
    let (tk, tp) = prefix(max_abs(&o.t));
    let ss = max_abs(&o.contact_stress).max(max_abs(&sh.friction_limit));
    let (sk, sp) = prefix(ss);
    let (tu, su) = (format!("{tp}s"), format!("{sp}Pa"));
    let t: Vec<f64> = o.t.iter().map(|v| v * tk).collect();
    let tau: Vec<f64> = o.contact_stress.iter().map(|v| v * sk).collect();
    let lim: Vec<f64> = sh.friction_limit.iter().map(|v| v * sk).collect();
    let neg: Vec<f64> = lim.iter().map(|v| -v).collect();
    render("shear_loop.svg", (1100, 480), |root| {
        let (left, right) = root.split_horizontally(550);
        panel(
            &left,
            "Shear stress against tangential gap",
            &format!("tangential gap [u]_T, {gu}"),
            &format!("shear stress tau, {su}"),
            &[Curve {
                label: String::new(),
                points: stride(&gap, &tau),
                color: color(0),
            }],
            &[],
            None,
        )?;
        panel(
            &right,
            "Shear stress and friction limit",
            &format!("time, {tu}"),
            &format!("stress, {su}"),
            &[
                Curve {
                    label: "tau".into(),
                    points: decimate(&t, &tau),
                    color: color(0),
                },
                Curve {
                    label: "+mu N".into(),
                    points: decimate(&t, &lim),
                    color: color(1),
                },
                Curve {
                    label: "-mu N".into(),
                    points: decimate(&t, &neg),
                    color: color(1),
                },
            ],
            &[],
            None,
        )
    })
}

//! The files of `contactwave analyze` (docs/scenario.md section 9): `summary.json` (the
//! fundamental, the method, the gate, each record's harmonics with the simulator's key
//! names and their floors, the series fit), `records.csv` (one row per record),
//! `spectrum.csv` (the largest gated record's spectrum) and, with the `plot` feature,
//! `record.svg` (the record and its gated part), `spectrum.svg` (with the harmonics
//! marked) and `fit.svg` (A2 against A1^2 with the fit, for a series).

use crate::analysis::push_csv_number;
use crate::error::Result;
use crate::measured::{Analysis, Series, HARMONIC_KEYS};
use crate::render::{csv_columns, OutputFile};
use crate::scenario::{HIGHEST_FREQUENCY, LOWEST_FREQUENCY};
use serde_json::{json, Map, Value};

fn num(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// The keys of one record in `summary.json` (and the columns of `records.csv`): `A1` ...
/// `A5`, `A2_over_A1`, `A3_over_A1`, `beta_star`, `A2_floor` ... `A5_floor`,
/// `A2_noise_floor` ..., `A2_leakage_floor` ..., `harmonic_floor_warning`, then
/// `clipped_samples` (0: not clipped), `clip_low`, `clip_high` (the levels, the record's
/// unit; empty where not clipped) and `harmonics_reliable` (0 for a clipped record);
/// `summary.json` adds `dc_offset` and `noise_window`.
pub fn record_keys() -> impl Iterator<Item = &'static str> {
    std::iter::once("amplitude")
        .chain(HARMONIC_KEYS)
        .chain(FLOOR_KEYS)
        .chain(CLIP_KEYS)
}

/// The clipping's keys of [`record_keys`].
const CLIP_KEYS: [&str; 4] = [
    "clipped_samples",
    "clip_low",
    "clip_high",
    "harmonics_reliable",
];

/// The floors' keys of [`record_keys`] (and the warning flag).
const FLOOR_KEYS: [&str; 13] = [
    "A2_floor",
    "A3_floor",
    "A4_floor",
    "A5_floor",
    "A2_noise_floor",
    "A3_noise_floor",
    "A4_noise_floor",
    "A5_noise_floor",
    "A2_leakage_floor",
    "A3_leakage_floor",
    "A4_leakage_floor",
    "A5_leakage_floor",
    "harmonic_floor_warning",
];

fn record_values(r: &crate::measured::RecordAnalysis) -> Vec<f64> {
    let mut v = vec![r.amplitude.unwrap_or(f64::NAN)];
    v.extend(HARMONIC_KEYS.map(|k| r.value(k)));
    v.extend((2..=5).map(|n| r.floor(n)));
    v.extend_from_slice(&r.noise[2..6]);
    v.extend_from_slice(&r.leakage[2..6]);
    v.push(if r.near_floor.is_empty() { 0.0 } else { 1.0 });
    match r.clipped {
        Some(c) => v.extend([c.samples as f64, c.low, c.high, 0.0]),
        None => v.extend([0.0, f64::NAN, f64::NAN, 1.0]),
    }
    v
}

/// One record's ratio `A{n}/A1` with its floor as a bound, as printed:
/// `A2/A1 = 2.3600e-2 (floor 3.0e-3)`, `(floor 1.2e-5, noise unknown)` where only the
/// method's leakage is known.
pub fn ratio_with_floor(r: &crate::measured::RecordAnalysis, n: usize) -> String {
    let a1 = r.harmonics[1];
    let floor = r.floor(n) / a1;
    let unknown = if r.noise_window.is_none() {
        ", noise unknown"
    } else {
        ""
    };
    format!(
        "A{n}/A1 = {:.4e} (floor {floor:.1e}{unknown})",
        r.harmonics[n] / a1
    )
}

/// One line per record with a harmonic near its floor, and one where a given f0 is more
/// than 10 % from the records' spectral peak.
pub fn warnings(a: &Analysis) -> Vec<String> {
    let far = !a.f0_detected && (a.peak - a.f0).abs() > 0.1 * a.f0;
    let f0 = far.then(|| {
        format!(
            "f0 = {:e} Hz given, but the records' spectral peak is at {:.6e} Hz: A1 is read in \
             the band of f0, which may not hold the fundamental (check --f0)",
            a.f0, a.peak
        )
    });
    // a time base in other units than s puts f0 far outside ultrasonics
    let units = if a.f0 < LOWEST_FREQUENCY {
        Some(format!(
            "f0 = {:e} Hz with a time step of {:e} s: below the audio range; are the time \
             stamps in us or ms? they are read in s (or give --sample-rate in Hz)",
            a.f0, a.dt
        ))
    } else if a.f0 > HIGHEST_FREQUENCY {
        Some(format!(
            "f0 = {:e} Hz with a time step of {:e} s: above 10 GHz; is --sample-rate in Hz \
             and are the time stamps in s?",
            a.f0, a.dt
        ))
    } else {
        None
    };
    units
        .into_iter()
        .chain(f0)
        .chain(a.records.iter().filter_map(|r| {
            r.clipped.map(|c| {
                format!(
                    "{}: clipped: {} samples {} (flat at the record's extremes{}): its harmonics \
                     are the clipping's, not the specimen's (harmonics_reliable = 0); re-record \
                     it within the digitiser's range",
                    r.name,
                    c.samples,
                    crate::measured::clip_levels(&c),
                    if a.full_scale.is_some() {
                        ", or at the full scale given"
                    } else {
                        ""
                    }
                )
            })
        }))
        .chain(
            a.records
                .iter()
                .filter(|r| !r.near_floor.is_empty())
                .map(|r| {
                    let h: Vec<String> = r
                        .near_floor
                        .iter()
                        .filter_map(|&n| {
                            crate::analysis::floor_reading(
                                &format!("A{n}"),
                                r.harmonics[n],
                                r.floor(n),
                            )
                        })
                        .collect();
                    format!(
                        "{}: {} (the analysis floor: noise or the method's leakage)",
                        r.name,
                        h.join("; ")
                    )
                }),
        )
        .chain(
            // without a gate and a quiet part before the arrival, the noise is not measured
            a.records.iter().any(|r| r.noise_window.is_none()).then(|| {
                "the noise floor is unknown (no samples outside the gate, or no quiet part \
                     before the arrival without one): the floors are the method's leakage \
                     only; a --gate around the echo with noise outside it measures it"
                    .to_string()
            }),
        )
        .collect()
}

/// `summary.json` of an analysis; `inputs` are the files read (shown as given).
pub fn summary(a: &Analysis, inputs: &[String]) -> Value {
    let records: Vec<Value> = a
        .records
        .iter()
        .map(|r| {
            let mut m = Map::new();
            m.insert("name".into(), json!(r.name));
            for (k, v) in record_keys().zip(record_values(r)) {
                m.insert(k.into(), num(v));
            }
            // a count, written as an integer
            m.insert(
                "clipped_samples".into(),
                json!(r.clipped.map_or(0, |c| c.samples)),
            );
            m.insert("dc_offset".into(), num(r.dc));
            m.insert(
                "noise_window".into(),
                r.noise_window
                    .map_or(Value::Null, |(s, e)| json!([num(s), num(e)])),
            );
            if let Some(k) = r.linear_scale {
                m.insert("linear_reference_scale".into(), num(k));
            }
            Value::Object(m)
        })
        .collect();
    let fit = a.fit.map(|f| {
        json!({
            "model": "A2 = slope * A1^2 + intercept",
            "count": f.count,
            "slope": num(f.slope),
            "slope_low": num(f.slope_interval.0),
            "slope_high": num(f.slope_interval.1),
            "intercept": num(f.intercept),
            "intercept_low": num(f.intercept_interval.0),
            "intercept_high": num(f.intercept_interval.1),
            "r_squared": num(f.r_squared),
            "interval": "95%, Student t with count - 2 degrees of freedom",
        })
    });
    json!({
        "command": "analyze",
        "inputs": inputs,
        "f0": num(a.f0),
        "f0_detected": a.f0_detected,
        "method": a.method.name(),
        "analysis_method": a.method.code(),
        "full_scale": a.full_scale.map(num),
        "gate": a.gate.map(|g| json!({"start": num(g.start), "end": num(g.end), "taper": num(g.taper)})),
        "plateau": [num(a.plateau.0), num(a.plateau.1)],
        "dt": num(a.dt),
        "t0": num(a.t0),
        "records": records,
        "fit": fit,
        "warnings": warnings(a),
    })
}

/// Index of the record with the largest A1 (the one the pictures show).
fn largest(a: &Analysis) -> usize {
    a.records
        .iter()
        .enumerate()
        .max_by(|x, y| x.1.harmonics[1].total_cmp(&y.1.harmonics[1]))
        .map_or(0, |(i, _)| i)
}

/// The largest record gated (its mean removed as the analysis did): (t, raw, gated).
fn gated_record(a: &Analysis, series: &Series) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let i = largest(a);
    let dc = a.records.get(i).map_or(0.0, |r| r.dc);
    let raw: Vec<f64> = series
        .records
        .get(i)
        .map(|r| r.samples.iter().map(|v| v - dc).collect())
        .unwrap_or_default();
    let t: Vec<f64> = (0..raw.len()).map(|k| a.t0 + k as f64 * a.dt).collect();
    let mut gated = raw.clone();
    if let Some(g) = &a.gate {
        g.apply(&mut gated, a.t0, a.dt);
    }
    (t, raw, gated)
}

/// What the pictures of an analysis show (`record.svg`, `spectrum.svg`, `spectrum.csv`;
/// the Python `Analysis.plot()`): the record with the largest A1, its time base, the
/// record as read with its mean removed, the same gated, and the gated record's spectrum.
#[derive(Debug, Clone)]
pub struct Picture {
    /// Index of the record shown (the largest A1).
    pub record: usize,
    /// Sample times, s.
    pub t: Vec<f64>,
    /// The record as read, its mean (the analysis' DC offset) removed; the record's unit.
    pub raw: Vec<f64>,
    /// The same through the gate (equal to `raw` without a gate).
    pub gated: Vec<f64>,
    /// Frequencies of the spectrum, Hz, up to 6 f0.
    pub frequency: Vec<f64>,
    /// `|X(f)| dt` of the gated record: the record's unit times s.
    pub magnitude: Vec<f64>,
}

/// The [`Picture`] of an analysis (the series it analysed).
pub fn picture(a: &Analysis, series: &Series) -> Picture {
    let (t, raw, gated) = gated_record(a, series);
    let spec = crate::analysis::with_analyzer(|an| an.spectrum(&gated, a.dt, 6.0 * a.f0));
    Picture {
        record: largest(a),
        t,
        raw,
        gated,
        frequency: spec.frequency,
        magnitude: spec.magnitude,
    }
}

/// The files of an analysis (nothing written here).
pub fn files(a: &Analysis, series: &Series, inputs: &[String]) -> Result<Vec<OutputFile>> {
    let mut out = Vec::new();
    let text = serde_json::to_string_pretty(&summary(a, inputs)).unwrap_or_default() + "\n";
    out.push(OutputFile::new("summary.json", text));
    // records.csv: name, then the keys
    let mut csv = String::from("name,");
    csv.push_str(&record_keys().collect::<Vec<_>>().join(","));
    csv.push('\n');
    let mut buf = zmij::Buffer::new();
    for r in &a.records {
        csv.push_str(&csv_cell(&r.name));
        for v in record_values(r) {
            csv.push(',');
            push_csv_number(&mut csv, &mut buf, v);
        }
        csv.push('\n');
    }
    out.push(OutputFile::new("records.csv", csv));
    let pic = picture(a, series);
    out.push(OutputFile::new(
        "spectrum.csv",
        csv_columns("frequency,magnitude", &[&pic.frequency, &pic.magnitude]),
    ));
    #[cfg(feature = "plot")]
    out.extend(plots(a, &pic)?);
    Ok(out)
}

/// The pictures' mark of a clipped record (empty otherwise).
#[cfg(feature = "plot")]
fn clip_note(a: &Analysis, i: usize) -> String {
    a.records
        .get(i)
        .and_then(|r| r.clipped)
        .map_or(String::new(), |c| {
            format!(
                " - CLIPPED ({} samples {}): harmonics unreliable",
                c.samples,
                crate::measured::clip_levels(&c)
            )
        })
}

fn csv_cell(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(feature = "plot")]
fn plots(a: &Analysis, pic: &Picture) -> Result<Vec<OutputFile>> {
    use crate::render::svg::{figure, Panel, Series as Curve};
    let mut out = Vec::new();
    let (t, raw, gated) = (&pic.t, &pic.raw, &pic.gated);
    let name = a.records.get(pic.record).map_or("", |r| r.name.as_str());
    let us: Vec<f64> = t.iter().map(|v| v * 1e6).collect();
    let mut markers = Vec::new();
    if let Some(g) = &a.gate {
        markers = vec![g.start * 1e6, g.end * 1e6];
    }
    out.push(OutputFile::new(
        "record.svg",
        figure(
            "record.svg",
            900,
            &[Panel {
                title: format!(
                    "record {name}: as read (mean removed) and gated{}",
                    clip_note(a, pic.record)
                ),
                xlabel: "t (µs)".into(),
                ylabel: "record (its unit)".into(),
                series: vec![
                    Curve::new("record", &us, raw).colored((170, 170, 170)),
                    Curve::new("gated", &us, gated),
                ],
                markers,
            }],
        )?,
    ));
    let peak = pic.magnitude.iter().fold(0.0f64, |m, &v| m.max(v));
    let mhz: Vec<f64> = pic.frequency.iter().map(|f| f * 1e-6).collect();
    let db: Vec<f64> = pic
        .magnitude
        .iter()
        .map(|m| 20.0 * (m / peak).max(1e-12).log10())
        .collect();
    out.push(OutputFile::new(
        "spectrum.svg",
        figure(
            "spectrum.svg",
            900,
            &[Panel {
                title: format!(
                    "spectrum of the gated record {name} (f0 = {:.4} MHz{}; markers at n f0){}",
                    a.f0 * 1e-6,
                    if a.f0_detected { ", detected" } else { "" },
                    clip_note(a, pic.record)
                ),
                xlabel: "f (MHz)".into(),
                ylabel: "magnitude (dB re peak)".into(),
                series: vec![Curve::new("gated record", &mhz, &db)],
                markers: (1..=5).map(|n| n as f64 * a.f0 * 1e-6).collect(),
            }],
        )?,
    ));
    if let Some(f) = a.fit {
        let x: Vec<f64> = a.records.iter().map(|r| r.harmonics[1].powi(2)).collect();
        let y: Vec<f64> = a.records.iter().map(|r| r.harmonics[2]).collect();
        let xmax = x.iter().fold(0.0f64, |m, &v| m.max(v));
        let line_x = [0.0, xmax];
        let line_y = [f.intercept, f.intercept + f.slope * xmax];
        let mut pts = Curve::new("measured A2", &x, &y);
        pts.points.sort_by(|p, q| p.0.total_cmp(&q.0));
        out.push(OutputFile::new(
            "fit.svg",
            figure(
                "fit.svg",
                900,
                &[Panel {
                    title: if f.count < 3 {
                        format!(
                            "A2 against A1^2: slope {:.4e} (a line through two points: no fit statistics)",
                            f.slope
                        )
                    } else {
                        format!(
                            "A2 against A1^2: slope {:.4e} (95% {:.3e} .. {:.3e}), R^2 = {:.4}",
                            f.slope, f.slope_interval.0, f.slope_interval.1, f.r_squared
                        )
                    },
                    xlabel: "A1^2 (unit^2)".into(),
                    ylabel: "A2 (unit)".into(),
                    series: vec![pts, Curve::new("least-squares fit", &line_x, &line_y)],
                    markers: Vec::new(),
                }],
            )?,
        ));
    }
    Ok(out)
}

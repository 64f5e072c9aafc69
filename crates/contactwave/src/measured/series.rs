//! Records on one uniform time base: which arrays of a file are records and which is the
//! time ([`Layout`]), their checks (a uniform time step, equal lengths, finite values),
//! and a series of records with their drive amplitudes, opposite-polarity twins and
//! linear reference ([`Series`]).

use super::arrays::{read_arrays, Format, NamedArray};
use crate::error::{Error, Result};
use std::path::Path;

/// Names a time column or array is recognised by (case-insensitive) when
/// [`Layout::time`] is not given.
pub const TIME_NAMES: [&str; 5] = ["t", "time", "time_s", "t_s", "times"];

/// Largest deviation of a time stamp from the uniform grid, in time steps: a time column
/// written with a few significant digits rounds its stamps, a record with a gap or two
/// sampling rates is off by a step or more.
pub const TIME_TOLERANCE: f64 = 0.25;

/// Which arrays of a file are records and which is their time base.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Layout {
    /// Sampling rate, Hz: the records have no time column (their first sample at t = 0).
    pub sample_rate: Option<f64>,
    /// The time column / array / dataset, s (default: one named as in [`TIME_NAMES`]).
    pub time: Option<String>,
    /// The columns / arrays / datasets holding records (default: every one but the time).
    /// A two-dimensional array holds one record per column (or per row, when it has
    /// more columns than rows: the records run along the longer dimension).
    pub records: Vec<String>,
}

/// One record: its name and samples (in the record's own unit, e.g. V or m/s).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// Name: the column, array or dataset (with `[j]` for the j-th record, from 0, of a
    /// two-dimensional array).
    pub name: String,
    /// Samples at `t0 + k dt`.
    pub samples: Vec<f64>,
}

/// The records of a file on their uniform time base.
#[derive(Debug, Clone, PartialEq)]
pub struct Records {
    /// The file format.
    pub format: Format,
    /// Time step, s.
    pub dt: f64,
    /// Time of the first sample, s.
    pub t0: f64,
    /// The records, in the file's order.
    pub traces: Vec<Trace>,
}

/// A record of a series, with what the analysis methods may need beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Name.
    pub name: String,
    /// Drive amplitude (any unit: V, Pa; only its order matters to plots and fits).
    pub amplitude: Option<f64>,
    /// The record.
    pub samples: Vec<f64>,
    /// The response to the opposite-polarity drive (pulse inversion).
    pub inverse: Option<Vec<f64>>,
    /// A low-amplitude record of the same echo (linear reference), scaled to this record
    /// by least squares over the gate before it is subtracted.
    pub linear: Option<Vec<f64>>,
}

impl Measured {
    /// A record without amplitude or companions.
    pub fn new(name: impl Into<String>, samples: Vec<f64>) -> Measured {
        Measured {
            name: name.into(),
            amplitude: None,
            samples,
            inverse: None,
            linear: None,
        }
    }
}

/// Records on one time base: one record, or a series (one per drive amplitude).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Time step, s.
    pub dt: f64,
    /// Time of the first sample, s.
    pub t0: f64,
    /// The records.
    pub records: Vec<Measured>,
}

/// Read the records of `path` laid out as `layout` says. Every error is one line naming
/// the file, the column or array, the value and what is allowed.
pub fn read_records(path: &Path, layout: &Layout) -> Result<Records> {
    let shown = path.display().to_string();
    let mut names = layout.records.clone();
    if let Some(t) = &layout.time
        && !names.is_empty()
    {
        names.push(t.clone());
    }
    let (format, arrays) = read_arrays(path, &names)?;
    let find = |name: &str| {
        arrays
            .iter()
            .find(|a| a.name == name.trim_start_matches('/'))
    };
    // the time base: a column named as a time is one, so a sampling rate beside it would
    // make it a record, and two of them are ambiguous
    let is_time = |a: &&NamedArray| {
        let base = a.name.rsplit('/').next().unwrap_or("").to_ascii_lowercase();
        TIME_NAMES.contains(&base.as_str())
    };
    if let (Some(t), Some(fs)) = (&layout.time, layout.sample_rate) {
        return Err(Error::invalid(
            &shown,
            "sample_rate",
            format!("{fs} Hz"),
            format!(
                "only for a file without a time column: `{t}` is named as the time (give \
                 one of the two)"
            ),
        ));
    }
    if layout.time.is_none() {
        let named: Vec<&str> = arrays
            .iter()
            .filter(is_time)
            .map(|a| a.name.as_str())
            .collect();
        if let (Some(fs), Some(first)) = (layout.sample_rate, named.first()) {
            return Err(Error::invalid(
                &shown,
                "sample_rate",
                format!("{fs} Hz"),
                format!(
                    "only for a file without a time column: this one has `{first}`, which \
                     gives the time base (leave out the sampling rate)"
                ),
            ));
        }
        if named.len() > 1 {
            return Err(Error::invalid(
                &shown,
                "time",
                named.join(", "),
                "one time column: name it with --time (Python: time=...)",
            ));
        }
    }
    let time: Option<&NamedArray> = match (&layout.time, layout.sample_rate) {
        (Some(t), _) => Some(find(t).ok_or_else(|| {
            Error::invalid(
                &shown,
                "time",
                t,
                format!("a column or array of the file ({})", listing(&arrays)),
            )
        })?),
        (None, Some(_)) => None,
        (None, None) => arrays.iter().find(is_time),
    };
    let time_name = time.map(|a| a.name.clone());
    // the records
    let chosen: Vec<&NamedArray> = if layout.records.is_empty() {
        // every array but the time as long as the time (or as the longest array)
        let others: Vec<&NamedArray> = arrays
            .iter()
            .filter(|a| Some(&a.name) != time_name.as_ref())
            .collect();
        let long = |a: &NamedArray| a.shape.iter().copied().max().unwrap_or(0);
        let len = time
            .map(|t| t.data.len())
            .unwrap_or_else(|| others.iter().map(|a| long(a)).max().unwrap_or(0));
        others
            .into_iter()
            .filter(|a| a.shape.contains(&len) || (a.shape.len() == 1 && a.data.len() == len))
            .collect()
    } else {
        layout
            .records
            .iter()
            .map(|n| {
                find(n).ok_or_else(|| {
                    Error::invalid(
                        &shown,
                        "records",
                        n,
                        format!("a column or array of the file ({})", listing(&arrays)),
                    )
                })
            })
            .collect::<Result<_>>()?
    };
    let mut traces = Vec::new();
    for a in chosen {
        let cols = match a.shape.as_slice() {
            [r, c] if *r > 1 && *c > 1 => {
                if r >= c {
                    a.columns()
                } else {
                    a.rows()
                }
            }
            _ => a.columns(),
        };
        let many = cols.len() > 1;
        for (j, samples) in cols.into_iter().enumerate() {
            let name = if many {
                format!("{}[{j}]", a.name)
            } else {
                a.name.clone()
            };
            traces.push(Trace { name, samples });
        }
    }
    // a first column that increases in uniform steps is a time axis, not a record (an
    // `.npy` saved as `[t, x]` columns, a CSV whose time column has another name): it is
    // the time base when the file has none, refused beside a sampling rate
    let mut axis: Option<Trace> = None;
    if time.is_none()
        && layout.records.is_empty()
        && traces.len() > 1
        && is_time_axis(&traces[0].samples)
    {
        let t = traces.remove(0);
        if let Some(fs) = layout.sample_rate {
            return Err(Error::invalid(
                &shown,
                &t.name,
                format!(
                    "{:e} .. {:e} in uniform steps",
                    t.samples[0],
                    t.samples[t.samples.len() - 1]
                ),
                format!(
                    "a record, not a time axis: it increases in uniform steps (the time, s?); \
                     leave out --sample-rate {fs} to take it as the time base, or choose the \
                     records with --datasets"
                ),
            ));
        }
        axis = Some(t);
    }
    if traces.is_empty() {
        return Err(Error::invalid(
            &shown,
            "records",
            "none",
            "at least one record besides the time (a column, array or dataset)",
        ));
    }
    let n = traces[0].samples.len();
    for t in &traces {
        if t.samples.len() != n {
            return Err(Error::invalid(
                &shown,
                &t.name,
                format!("{} samples", t.samples.len()),
                format!("as many samples as {} ({n})", traces[0].name),
            ));
        }
        if let Some(k) = t.samples.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(
                &shown,
                &t.name,
                format!("{} at sample {k}", t.samples[k]),
                "finite samples (trim the record or replace the gap)",
            ));
        }
    }
    if n < 16 {
        return Err(Error::invalid(
            &shown,
            &traces[0].name,
            format!("{n} samples"),
            "at least 16 samples",
        ));
    }
    let (dt, t0) = match (time, layout.sample_rate) {
        (Some(t), _) => uniform_step(&shown, &t.name, &t.data, n)?,
        (None, None) if axis.is_some() => {
            let t = axis.as_ref().map_or(&[][..], |t| &t.samples[..]);
            let name = axis.as_ref().map_or("", |t| t.name.as_str());
            uniform_step(&shown, name, t, n)?
        }
        (None, Some(fs)) => {
            if !(fs > 0.0) || !fs.is_finite() {
                return Err(Error::invalid(&shown, "sample_rate", fs, "must be > 0 Hz"));
            }
            (1.0 / fs, 0.0)
        }
        (None, None) => {
            return Err(Error::invalid(
                &shown,
                "time",
                "none",
                format!(
                    "a time column or array (named t, time or time_s, or given with --time), or the sampling rate (--sample-rate HZ); the file has {}",
                    listing(&arrays)
                ),
            ));
        }
    };
    Ok(Records {
        format,
        dt,
        t0,
        traces,
    })
}

/// Whether `v` (at least 16 values) increases in uniform steps (within
/// [`TIME_TOLERANCE`] of a step): a time axis. No record of a wave does.
fn is_time_axis(v: &[f64]) -> bool {
    let n = v.len();
    if n < 16 || v.iter().any(|x| !x.is_finite()) {
        return false;
    }
    let dt = (v[n - 1] - v[0]) / (n - 1) as f64;
    dt > 0.0
        && v.iter()
            .enumerate()
            .all(|(k, &x)| ((x - v[0]) / dt - k as f64).abs() <= TIME_TOLERANCE)
        && v.windows(2).all(|w| w[1] > w[0])
}

fn listing(arrays: &[NamedArray]) -> String {
    let names: Vec<&str> = arrays.iter().map(|a| a.name.as_str()).take(12).collect();
    if names.is_empty() {
        "no numeric arrays".to_string()
    } else {
        names.join(", ")
    }
}

/// The step and start of a time base `t` (s) for records of `n` samples: a uniform grid
/// within [`TIME_TOLERANCE`] steps, increasing.
fn uniform_step(file: &str, name: &str, t: &[f64], n: usize) -> Result<(f64, f64)> {
    if t.len() != n {
        return Err(Error::invalid(
            file,
            name,
            format!("{} time stamps", t.len()),
            format!("one per sample of the records ({n})"),
        ));
    }
    if let Some(k) = t.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            file,
            name,
            format!("{} at sample {k}", t[k]),
            "finite time stamps, s",
        ));
    }
    let dt = (t[n - 1] - t[0]) / (n - 1) as f64;
    if !(dt > 0.0) {
        return Err(Error::invalid(
            file,
            name,
            format!("{} .. {}", t[0], t[n - 1]),
            "increasing time stamps, s",
        ));
    }
    // a missing, repeated or misplaced sample first shows as one step unlike the others
    // (the grid's drift would only show it farther on, where the drift is largest)
    if let Some(k) = (1..n).find(|&k| ((t[k] - t[k - 1]) / dt - 1.0).abs() > 0.5) {
        return Err(Error::invalid(
            file,
            name,
            format!("{} at sample {k}", t[k]),
            format!(
                "a uniform time base: the step from sample {} is {:e} s, the mean step {dt:e} s \
                 (a missing or repeated sample?); resample the record onto a uniform grid",
                k - 1,
                t[k] - t[k - 1]
            ),
        ));
    }
    for (k, &tk) in t.iter().enumerate() {
        let off = (tk - (t[0] + k as f64 * dt)) / dt;
        if off.abs() > TIME_TOLERANCE {
            return Err(Error::invalid(
                file,
                name,
                format!("{tk} at sample {k}"),
                format!(
                    "a uniform time base: the samples are {off:.2} steps off the grid of step {dt:e} s there (at most {TIME_TOLERANCE}); resample the record onto a uniform grid"
                ),
            ));
        }
    }
    Ok((dt, t[0]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_bases_must_be_uniform() {
        let t: Vec<f64> = (0..100).map(|k| 2e-6 + k as f64 * 1e-8).collect();
        let (dt, t0) = uniform_step("f", "t", &t, 100).unwrap();
        assert!((dt - 1e-8).abs() < 1e-20 && t0 == 2e-6);
        // rounded stamps (6 significant digits) pass
        let r: Vec<f64> = t
            .iter()
            .map(|v| format!("{v:.5e}").parse().unwrap())
            .collect();
        assert!(uniform_step("f", "t", &r, 100).is_ok());
        // a missing sample does not
        let mut g = t.clone();
        g.remove(50);
        g.push(t[99] + 1e-8);
        let e = uniform_step("f", "t", &g, 100).unwrap_err().to_string();
        assert!(e.contains("uniform time base"), "{e}");
        assert!(uniform_step("f", "t", &t, 99).is_err());
        let rev: Vec<f64> = t.iter().rev().copied().collect();
        assert!(uniform_step("f", "t", &rev, 100).is_err());
    }

    /// A time column is never read as a record: a sampling rate beside one is refused,
    /// and two time columns need `--time`.
    #[test]
    fn a_time_column_is_never_a_record() {
        let path = std::env::temp_dir().join(format!("cw-time-{}.csv", std::process::id()));
        let write = |header: &str, cols: usize| {
            let mut s = format!("{header}\n");
            for k in 0..32 {
                let row: Vec<String> = (0..cols)
                    .map(|c| {
                        format!(
                            "{}",
                            if c < 2 {
                                k as f64 * 1e-8
                            } else {
                                0.1 * k as f64
                            }
                        )
                    })
                    .collect();
                s.push_str(&row.join(","));
                s.push('\n');
            }
            std::fs::write(&path, s).unwrap();
        };
        write("time,t,ch1", 3);
        let e = read_records(&path, &Layout::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("time, t") && e.contains("--time"), "{e}");
        let named = Layout {
            time: Some("t".into()),
            ..Layout::default()
        };
        let r = read_records(&path, &named).unwrap();
        let names: Vec<&str> = r.traces.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["time", "ch1"]);
        write("time,ch1", 2);
        let rate = Layout {
            sample_rate: Some(50e6),
            ..Layout::default()
        };
        let e = read_records(&path, &rate).unwrap_err().to_string();
        assert!(e.contains("sample_rate") && e.contains("`time`"), "{e}");
        let r = read_records(&path, &Layout::default()).unwrap();
        assert_eq!(r.traces.len(), 1);
        assert!((r.dt - 1e-8).abs() < 1e-20);
        std::fs::remove_file(&path).ok();
    }

    /// Issue 56 item 3: an `.npy` of `[t, x]` columns had its time column analysed as
    /// record 0. A first column in uniform steps is the time base, refused beside a
    /// sampling rate; a record that merely rises is not taken for one.
    #[test]
    fn a_uniformly_stepped_first_column_is_the_time_axis() {
        let path = std::env::temp_dir().join(format!("cw-axis-{}.npy", std::process::id()));
        let n = 200;
        let mut data = Vec::new();
        for k in 0..n {
            let t = 1e-6 + k as f64 * 2e-8;
            data.extend([t, (2.0 * std::f64::consts::PI * 1e6 * t).sin()]);
        }
        use npyz::WriterBuilder;
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&[n as u64, 2])
            .writer(std::fs::File::create(&path).unwrap())
            .begin_nd()
            .unwrap();
        w.extend(data.iter().copied()).unwrap();
        w.finish().unwrap();
        let r = read_records(&path, &Layout::default()).unwrap();
        assert_eq!(
            r.traces.len(),
            1,
            "{:?}",
            r.traces.iter().map(|t| &t.name).collect::<Vec<_>>()
        );
        assert!((r.dt - 2e-8).abs() < 1e-20 && (r.t0 - 1e-6).abs() < 1e-18);
        assert!(r.traces[0].samples[0].abs() < 1.0);
        let rate = Layout {
            sample_rate: Some(50e6),
            ..Layout::default()
        };
        let e = read_records(&path, &rate).unwrap_err().to_string();
        assert!(
            e.contains("time axis") && e.contains("--sample-rate"),
            "{e}"
        );
        std::fs::remove_file(&path).ok();
        // a rising record (not uniform steps) is a record
        let ramp: Vec<f64> = (0..64).map(|k| (k as f64).powi(2)).collect();
        assert!(!is_time_axis(&ramp));
        let line: Vec<f64> = (0..64).map(|k| 3.0 + 0.5 * k as f64).collect();
        assert!(is_time_axis(&line));
    }
}

//! Which recorded series a run writes (`contactwave run --record`, `--record-step`): the
//! time-series files (`timeseries.csv`, `probe.csv`, `probes.csv`, `waves.csv`,
//! `shear.csv`) in full,
//! decimated to a size a person can open (the default: at most [`DEFAULT_MAX_ROWS`]
//! rows), sampled every given step, or not at all. Summaries, spectra, FRFs and plots are
//! computed from the full series and do not change.
//!
//! ```
//! use contactwave::output::{recording::{apply, Recording, Series}, OutputFile};
//! let rows: String = (0..100).map(|k| format!("{},{}\n", k as f64 * 0.5, k)).collect();
//! let files = vec![OutputFile { name: "timeseries.csv".into(), contents: format!("t,x\n{rows}") }];
//! // every 10 s: rows 0, 20, 40, ... (dt = 0.5 s), and always the last one
//! let rec = Recording { series: Series::Decimated, step: Some(10.0) };
//! let out = apply(files.clone(), &rec).unwrap();
//! let lines: Vec<&str> = out[0].contents.lines().collect();
//! assert_eq!(lines[..3], ["t,x", "0,0", "10,20"]);
//! assert_eq!(lines.last(), Some(&"49.5,99"));
//! // none: the time-series files are left out
//! let none = Recording { series: Series::None, step: None };
//! assert!(apply(files, &none).unwrap().is_empty());
//! ```

use crate::error::{Error, Result};
use crate::render::OutputFile;

/// Files that hold recorded series, one row per time sample.
pub const TIME_SERIES_FILES: [&str; 5] = [
    "timeseries.csv",
    "probe.csv",
    "probes.csv",
    "waves.csv",
    "shear.csv",
];

/// Rows a decimated time-series file keeps at most, by default (a Tribobrake run:
/// about 4 MB instead of 52 MB).
pub const DEFAULT_MAX_ROWS: usize = 20_000;

/// How much of the recorded series is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Series {
    /// No time-series file.
    None,
    /// Every k-th time sample: at most [`DEFAULT_MAX_ROWS`] rows, or one row per
    /// [`Recording::step`].
    #[default]
    Decimated,
    /// Every time sample.
    Full,
}

/// The recording choice of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Recording {
    /// Which series.
    pub series: Series,
    /// Sampling step of the written rows, s (rounded to a whole number of time steps, at
    /// least one); implies [`Series::Decimated`].
    pub step: Option<f64>,
}

impl Recording {
    /// Check the step: finite and > 0.
    pub fn validate(&self) -> Result<()> {
        match self.step {
            Some(s) if !(s.is_finite() && s > 0.0) => Err(Error::invalid(
                "<arguments>",
                "record-step",
                s,
                "must be a finite number of seconds > 0",
            )),
            _ => Ok(()),
        }
    }
}

/// Apply a recording choice to a run's files: time-series files are decimated, kept or
/// left out; every other file is unchanged.
pub fn apply(files: Vec<OutputFile>, rec: &Recording) -> Result<Vec<OutputFile>> {
    rec.validate()?;
    let series = if rec.step.is_some() {
        Series::Decimated
    } else {
        rec.series
    };
    Ok(files
        .into_iter()
        .filter_map(|f| {
            if !TIME_SERIES_FILES.contains(&f.name.as_str()) {
                return Some(f);
            }
            match series {
                Series::None => None,
                Series::Full => Some(f),
                Series::Decimated => Some(OutputFile {
                    contents: decimate(&f.contents, rec.step),
                    name: f.name,
                }),
            }
        })
        .collect())
}

/// Keep the header, every k-th row from the first and the last row: k from `step` (s, the
/// time step read from the first column) or so that at most [`DEFAULT_MAX_ROWS`] rows
/// remain.
fn decimate(csv: &str, step: Option<f64>) -> String {
    let mut lines = csv.lines();
    let Some(header) = lines.next() else {
        return csv.to_string();
    };
    let rows: Vec<&str> = lines.collect();
    let n = rows.len();
    let time = |r: &str| r.split(',').next().and_then(|t| t.parse::<f64>().ok());
    let k = match step {
        Some(s) => {
            let dt = match (
                rows.first().and_then(|r| time(r)),
                rows.get(1).and_then(|r| time(r)),
            ) {
                (Some(a), Some(b)) if b > a => b - a,
                _ => s,
            };
            ((s / dt).round() as usize).max(1)
        }
        None => n.div_ceil(DEFAULT_MAX_ROWS).max(1),
    };
    if k == 1 {
        return csv.to_string();
    }
    let mut out = String::with_capacity(csv.len() / k + header.len() + 64);
    out.push_str(header);
    out.push('\n');
    for (i, r) in rows.iter().enumerate() {
        if i % k == 0 || i + 1 == n {
            out.push_str(r);
            out.push('\n');
        }
    }
    out
}

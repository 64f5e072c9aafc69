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
use crate::model::Outcome;
pub use crate::render::TIME_SERIES_FILES;
use crate::render::{pick_rows, OutputFile, Rows};

/// Rows a decimated time-series file keeps at most, by default (a Tribobrake run:
/// about 3.7 MB instead of 52 MB).
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
                "<command line>",
                "record-step",
                s,
                "must be a finite number of seconds > 0",
            )),
            _ => Ok(()),
        }
    }

    /// The rows of the time-series files this choice keeps.
    pub fn rows(&self) -> Rows {
        match (self.step, self.series) {
            (Some(s), _) => Rows::Every(s),
            (None, Series::None) => Rows::None,
            (None, Series::Full) => Rows::All,
            (None, Series::Decimated) => Rows::AtMost(DEFAULT_MAX_ROWS),
        }
    }
}

/// Apply a recording choice to a run's files: time-series files are decimated, kept or
/// left out; every other file is unchanged.
pub fn apply(files: Vec<OutputFile>, rec: &Recording) -> Result<Vec<OutputFile>> {
    rec.validate()?;
    let rows = rec.rows();
    Ok(files
        .into_iter()
        .filter_map(|f| pick_rows(f, rows))
        .collect())
}

/// The files of a run under a recording choice: [`apply`] to [`Outcome::files`], but the
/// time-series files are rendered with the chosen rows only (a default Tribobrake run
/// formats 20 000 rows, not 273 000).
pub fn files(outcome: &dyn Outcome, rec: &Recording) -> Result<Vec<OutputFile>> {
    rec.validate()?;
    outcome.files_with(rec.rows())
}

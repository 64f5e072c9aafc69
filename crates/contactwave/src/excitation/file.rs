//! Arbitrary incident waveform from a CSV file (time s, stress Pa), interpolated by
//! monotone cubics (PCHIP) and optionally rescaled to a given peak.

use super::Excitation;
use crate::error::{Error, Result};
use crate::numeric::pchip::Pchip;
use crate::numeric::table::{CsvReader, Header};
use std::path::Path;

/// Waveform from samples.
#[derive(Debug, Clone)]
pub struct FileWaveform {
    interp: Pchip,
    t0: f64,
    duration: f64,
    scale: f64,
    frequency: f64,
}

impl FileWaveform {
    /// Read `path` (two columns: time, stress; an optional header line; `#` comments; more
    /// columns are ignored) with the one CSV reader ([`crate::numeric::table`]): errors
    /// name the file's line and column. Times must be strictly increasing and finite; the
    /// waveform is shifted so it starts at t = 0.
    pub fn read(path: &Path, field: &str) -> Result<(Vec<f64>, Vec<f64>)> {
        // parsed rows and their interpolant take a few times the text in memory
        crate::budget::check_file(path, field, 4.0)?;
        Self::read_window(path, field, None)
    }

    /// [`FileWaveform::read`] of the rows within `window` seconds of the first sample
    /// only (and the first row beyond, for the interpolation up to the window's end):
    /// the rest of a file longer than the simulated time is never read, whatever its
    /// size. The rows kept are checked against the memory budget as they are read.
    pub fn read_window(
        path: &Path,
        field: &str,
        window: Option<f64>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let shown = path.display().to_string();
        let mut rdr = CsvReader::open(path, Header::Optional).map_err(|e| {
            // the file cannot be opened: the scenario's field names it
            Error::invalid(&shown, field, &shown, e.expected)
        })?;
        let (mut t, mut s) = (Vec::new(), Vec::new());
        let mut row = Vec::with_capacity(2);
        while let Some(line) = rdr.next_row(&[0, 1], &mut row)? {
            let (a, b) = (row[0], row[1]);
            if !a.is_finite() || !b.is_finite() || b.abs() > super::MAX_AMPLITUDE {
                return Err(rdr
                    .error(
                        line,
                        None,
                        format!("{a}, {b}"),
                        format!(
                            "finite times, and stresses within +-{:e} Pa",
                            super::MAX_AMPLITUDE
                        ),
                    )
                    .into());
            }
            if let Some(&last) = t.last()
                && !(a > last)
            {
                return Err(rdr
                    .error(
                        line,
                        Some(rdr.column_name(0)),
                        a,
                        "times must be strictly increasing",
                    )
                    .into());
            }
            t.push(a);
            s.push(b);
            if t.len() % (1 << 20) == 0 {
                crate::budget::check(
                    &shown,
                    field,
                    &shown,
                    t.len() as f64 * 64.0,
                    &format!("{} rows read", t.len()),
                )?;
            }
            if window.is_some_and(|w| a - t[0] > w) {
                break;
            }
        }
        if t.len() < 2 {
            return Err(Error::invalid(
                &shown,
                field,
                &shown,
                format!(
                    "a file of at least 2 samples (rows of time, stress); it has {}",
                    t.len()
                ),
            ));
        }
        Ok((t, s))
    }

    /// From samples; `peak` rescales the waveform so that max |s| = peak (Pa).
    pub fn new(time: &[f64], stress: &[f64], frequency: f64, peak: Option<f64>) -> Option<Self> {
        let t0 = time[0];
        let shifted: Vec<f64> = time.iter().map(|v| v - t0).collect();
        let interp = Pchip::new(&shifted, stress)?;
        let raw_peak = interp.max_abs();
        let scale = match peak {
            Some(p) if raw_peak > 0.0 => p / raw_peak,
            _ => 1.0,
        };
        Some(FileWaveform {
            duration: *shifted.last()?,
            interp,
            t0,
            scale,
            frequency,
        })
    }

    /// Time of the first sample in the file, s.
    pub fn file_start(&self) -> f64 {
        self.t0
    }
}

impl Excitation for FileWaveform {
    fn stress(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.duration {
            return 0.0;
        }
        self.scale * self.interp.eval(t)
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn fundamental(&self) -> f64 {
        self.frequency
    }
    fn breakpoints(&self) -> Vec<f64> {
        let k = self.interp.knots();
        if k.len() <= 4096 {
            k.to_vec()
        } else {
            vec![0.0, self.duration]
        }
    }
    fn peak(&self) -> f64 {
        self.scale * self.interp.max_abs()
    }
}

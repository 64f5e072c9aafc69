//! A series from files: records from one or more files (a file per amplitude, or several
//! records in one file), their drive amplitudes (a list, or an array of the first file),
//! opposite-polarity twins (pulse inversion) and a low-amplitude linear reference, all
//! checked to share one time base.

use super::arrays::read_arrays;
use super::series::{read_records, Layout, Measured, Records, Series};
use crate::error::{Error, Result};
use std::path::PathBuf;

/// Drive amplitudes of a series.
#[derive(Debug, Clone, PartialEq)]
pub enum Amplitudes {
    /// One per record, in order.
    Values(Vec<f64>),
    /// The name of a one-dimensional array (or column) of the first records file.
    Array(String),
}

/// Where a series' records are.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Sources {
    /// Record files: every record of each, in order.
    pub records: Vec<PathBuf>,
    /// Which arrays are records and which the time, in every file.
    pub layout: Layout,
    /// Files of the opposite-polarity records, one per record in the same order.
    pub inverse: Vec<PathBuf>,
    /// A file of the low-amplitude linear reference: one record for all, or one per record.
    pub linear: Option<PathBuf>,
    /// Drive amplitudes.
    pub amplitudes: Option<Amplitudes>,
}

/// Read the series `sources` names.
pub fn load(sources: &Sources) -> Result<Series> {
    let Some(first_file) = sources.records.first() else {
        return Err(Error::invalid(
            "<command line>",
            "records",
            "none",
            "at least one record file",
        ));
    };
    let first_shown = first_file.display().to_string();
    let files = |paths: &[PathBuf]| -> Result<Vec<(String, Records)>> {
        paths
            .iter()
            .map(|p| Ok((p.display().to_string(), read_records(p, &sources.layout)?)))
            .collect()
    };
    let main = files(&sources.records)?;
    let (dt, t0, n) = {
        let r = &main[0].1;
        (r.dt, r.t0, r.traces[0].samples.len())
    };
    let same_base = |file: &str, r: &Records| -> Result<()> {
        let len = r.traces[0].samples.len();
        if (r.dt - dt).abs() > 1e-9 * dt {
            return Err(Error::invalid(
                file,
                "time step",
                format!("{:e} s", r.dt),
                format!("the time step of {first_shown} ({dt:e} s): every record on one time base"),
            ));
        }
        if (r.t0 - t0).abs() > 0.25 * dt || len != n {
            return Err(Error::invalid(
                file,
                "time base",
                format!("{len} samples from {:e} s", r.t0),
                format!("the time base of {first_shown} ({n} samples from {t0:e} s)"),
            ));
        }
        Ok(())
    };
    let mut records = Vec::new();
    for (file, r) in &main {
        same_base(file, r)?;
        let many = main.len() > 1 && r.traces.len() == 1;
        for t in &r.traces {
            // a file per amplitude: the record is named by its file
            let name = if many {
                std::path::Path::new(file)
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| t.name.clone())
            } else {
                t.name.clone()
            };
            records.push(Measured::new(name, t.samples.clone()));
        }
    }
    let count = records.len();
    if !sources.inverse.is_empty() {
        let inv = files(&sources.inverse)?;
        let mut traces = Vec::new();
        for (file, r) in &inv {
            same_base(file, r)?;
            traces.extend(r.traces.iter().map(|t| t.samples.clone()));
        }
        if traces.len() != count {
            return Err(Error::invalid(
                &inv[0].0,
                "inverse",
                format!("{} records", traces.len()),
                format!("one opposite-polarity record per record ({count}), in the same order"),
            ));
        }
        for (r, t) in records.iter_mut().zip(traces) {
            r.inverse = Some(t);
        }
    }
    if let Some(lin) = &sources.linear {
        let shown = lin.display().to_string();
        let r = read_records(lin, &sources.layout)?;
        same_base(&shown, &r)?;
        match r.traces.len() {
            1 => records
                .iter_mut()
                .for_each(|m| m.linear = Some(r.traces[0].samples.clone())),
            k if k == count => {
                for (m, t) in records.iter_mut().zip(&r.traces) {
                    m.linear = Some(t.samples.clone());
                }
            }
            k => {
                return Err(Error::invalid(
                    &shown,
                    "linear",
                    format!("{k} records"),
                    format!("one low-amplitude record for all, or one per record ({count})"),
                ));
            }
        }
    }
    if let Some(a) = &sources.amplitudes {
        let values = match a {
            Amplitudes::Values(v) => v.clone(),
            Amplitudes::Array(name) => {
                let (_, arrays) = read_arrays(first_file, std::slice::from_ref(name))?;
                arrays
                    .into_iter()
                    .find(|x| x.name == name.trim_start_matches('/'))
                    .map(|x| x.data)
                    .ok_or_else(|| {
                        Error::invalid(
                            &first_shown,
                            "amplitudes",
                            name,
                            "an array of the file holding one drive amplitude per record",
                        )
                    })?
            }
        };
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(
                &first_shown,
                "amplitudes",
                format!("{} (value {k}, from 0)", values[k]),
                "finite drive amplitudes, one per record",
            ));
        }
        if values.len() != count {
            return Err(Error::invalid(
                &first_shown,
                "amplitudes",
                format!("{} values", values.len()),
                format!("one finite drive amplitude per record ({count})"),
            ));
        }
        for (r, v) in records.iter_mut().zip(values) {
            r.amplitude = Some(v);
        }
    }
    Ok(Series { dt, t0, records })
}

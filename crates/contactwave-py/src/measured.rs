//! `contactwave._core.analyze`: measured records through the library's analysis
//! (`contactwave::measured`), for `contactwave.analyze` (python/contactwave/measured.py).

use super::to_py;
use contactwave::Error;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

/// `contactwave.analyze`: measured records (arrays, or files named in `options`) through
/// the simulator's analysis; returns `summary.json` of `contactwave analyze` as text and
/// the picture of the largest record (`output::analyze::Picture`): `(summary, record index,
/// t (s), record (mean removed), gated record, frequency (Hz), magnitude)`.
/// `options` (JSON): `dt`, `t0`, `f0`, `gate` ([start, end, taper]), `method`, `keep_dc`,
/// `amplitudes` (numbers, or the name of an array of the first file), `files`,
/// `sample_rate`, `time`, `datasets`, `inverse_files`, `linear_file`.
#[pyfunction]
pub fn analyze<'py>(
    py: Python<'py>,
    records: Vec<PyReadonlyArray1<'py, f64>>,
    inverse: Vec<PyReadonlyArray1<'py, f64>>,
    linear: Vec<PyReadonlyArray1<'py, f64>>,
    options: &str,
) -> PyResult<Analyzed<'py>> {
    use contactwave::analysis::{AnalysisMethod, Gate};
    use contactwave::measured::{self, Amplitudes, Layout, Measured, Series, Settings, Sources};
    let o: serde_json::Value =
        serde_json::from_str(options).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let num = |k: &str| o.get(k).and_then(serde_json::Value::as_f64);
    let strs = |k: &str| -> Vec<String> {
        o.get(k)
            .and_then(|v| v.as_array())
            .map(|a| {
                a.iter()
                    .filter_map(|x| x.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default()
    };
    let method_name = o
        .get("method")
        .and_then(|v| v.as_str())
        .unwrap_or("band_peak");
    let method = AnalysisMethod::from_name(method_name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "method = {method_name:?}: one of band_peak, pulse_inversion, linear_reference, plateau_fit"
        ))
    })?;
    let gate = match o.get("gate").and_then(|v| v.as_array()) {
        Some(g) => {
            let v: Vec<f64> = g.iter().filter_map(serde_json::Value::as_f64).collect();
            let gate = Gate::from_values(&v).ok_or_else(|| {
                PyValueError::new_err(
                    "gate: (start, end) or (start, end, taper) in s, start < end, taper in [0, (end - start) / 2]",
                )
            })?;
            Some(gate)
        }
        None => None,
    };
    let amplitudes = match o.get("amplitudes") {
        Some(serde_json::Value::String(name)) => Some(Amplitudes::Array(name.clone())),
        Some(serde_json::Value::Array(a)) => Some(Amplitudes::Values(
            a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect(),
        )),
        _ => None,
    };
    let files: Vec<PathBuf> = strs("files").into_iter().map(PathBuf::from).collect();
    let to_vec =
        |a: &PyReadonlyArray1<'py, f64>| a.as_array().iter().copied().collect::<Vec<f64>>();
    let (records, inverse, linear): (Vec<_>, Vec<_>, Vec<_>) = (
        records.iter().map(to_vec).collect(),
        inverse.iter().map(to_vec).collect(),
        linear.iter().map(to_vec).collect(),
    );
    let settings = Settings {
        f0: num("f0"),
        gate,
        method,
        keep_dc: o.get("keep_dc").and_then(|v| v.as_bool()).unwrap_or(false),
        full_scale: num("full_scale"),
    };
    let (dt, t0) = (num("dt").unwrap_or(f64::NAN), num("t0").unwrap_or(0.0));
    let layout = Layout {
        sample_rate: num("sample_rate"),
        time: o.get("time").and_then(|v| v.as_str()).map(str::to_string),
        records: strs("datasets"),
    };
    let inverse_files: Vec<PathBuf> = strs("inverse_files")
        .into_iter()
        .map(PathBuf::from)
        .collect();
    let linear_file = o
        .get("linear_file")
        .and_then(|v| v.as_str())
        .map(PathBuf::from);
    py.detach(move || {
        let (series, inputs) = if files.is_empty() {
            let n = records.len();
            let mut recs: Vec<Measured> = records
                .into_iter()
                .enumerate()
                .map(|(i, x)| Measured::new(format!("record_{i}"), x))
                .collect();
            for (what, list) in [("inverse", &inverse), ("linear", &linear)] {
                if !list.is_empty() && list.len() != n && !(what == "linear" && list.len() == 1) {
                    return Err(Error::invalid(
                        "<arrays>",
                        what,
                        format!("{} records", list.len()),
                        format!("one per record ({n})"),
                    ));
                }
            }
            for (i, r) in recs.iter_mut().enumerate() {
                r.inverse = inverse.get(i).cloned();
                r.linear = linear.get(i).or(linear.first()).cloned();
            }
            match &amplitudes {
                Some(Amplitudes::Values(v)) if v.len() == n => {
                    for (r, a) in recs.iter_mut().zip(v) {
                        r.amplitude = Some(*a);
                    }
                }
                Some(_) => {
                    return Err(Error::invalid(
                        "<arrays>",
                        "amplitudes",
                        "given",
                        format!("one number per record ({n})"),
                    ))
                }
                None => {}
            }
            let series = Series {
                dt,
                t0,
                records: recs,
            };
            (series, vec!["<arrays>".to_string()])
        } else {
            let sources = Sources {
                records: files.clone(),
                layout,
                inverse: inverse_files,
                linear: linear_file,
                amplitudes,
            };
            let inputs = files.iter().map(|p| p.display().to_string()).collect();
            (measured::load(&sources)?, inputs)
        };
        let a = measured::analyze(&series, &settings, &inputs[0])?;
        let picture = contactwave::output::analyze::picture(&a, &series);
        Ok((
            contactwave::output::analyze::summary(&a, &inputs).to_string(),
            picture,
        ))
    })
    .map_err(to_py)
    .map(|(summary, p)| {
        (
            summary,
            p.record,
            p.t.into_pyarray(py),
            p.raw.into_pyarray(py),
            p.gated.into_pyarray(py),
            p.frequency.into_pyarray(py),
            p.magnitude.into_pyarray(py),
        )
    })
}

/// What `analyze` returns to Python (see there).
type Analyzed<'py> = (
    String,
    usize,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
);

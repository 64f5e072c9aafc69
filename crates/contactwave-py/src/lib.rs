//! `contactwave._core`: the compiled half of the `contactwave` Python package.
//!
//! The pure-Python package (`python/contactwave/`) wraps these functions into the public
//! API (`load_scenario`, `run`, `law_curve`, `sweep`, `fit_power_law`) and documents it;
//! this module only converts between Python and the library, and releases the GIL around
//! every computation.
//!
//! Errors: invalid input ([`contactwave::Error::Invalid`] / `Parse`) raises `ValueError`
//! with the library's message (file, field, value, allowed range); a missing file raises
//! `FileNotFoundError` (other I/O errors `OSError`); a numerical failure raises
//! `contactwave.SimulationError` (a `RuntimeError`); an interrupted sweep raises
//! `KeyboardInterrupt`.

use contactwave::model::{self, Record, RunControl, Template, Value};
use contactwave::run::{Executor, Progress, Quiet, Workspaces};
use contactwave::scenario::Scenario;
use contactwave::study::Sweep;
use contactwave::Error;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

mod measured;
use measured::analyze;

create_exception!(
    contactwave,
    SimulationError,
    PyRuntimeError,
    "A simulation failed numerically (non-finite state, root-finder failure)."
);

/// How often a waiting sweep checks for Ctrl-C.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

pub(crate) fn to_py(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::Invalid { .. } | Error::Parse { .. } => PyValueError::new_err(msg),
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(msg)
        }
        Error::Io { .. } => PyOSError::new_err(msg),
        Error::Numerical { .. } => SimulationError::new_err(msg),
        Error::Interrupted => PyKeyboardInterrupt::new_err(msg),
        Error::Internal { .. } | Error::Device { .. } => PyRuntimeError::new_err(msg),
    }
}

/// A validated scenario of any kind (built by `load_scenario` or from a dict): a planned
/// template, run with `run`.
#[pyclass(name = "Scenario", module = "contactwave._core", frozen)]
struct PyScenario {
    template: Arc<dyn Template>,
    /// The file it came from, or `<dict>` (relative paths resolve against its folder).
    path: PathBuf,
}

#[pymethods]
impl PyScenario {
    /// File the scenario came from (`<dict>` for one built from a dict).
    #[getter]
    fn file(&self) -> String {
        self.template.file().to_string()
    }

    /// Kind of scenario: `half_space`, `bar_stack` or `solid_2d`.
    #[getter]
    fn kind(&self) -> &'static str {
        self.template.kind()
    }

    /// Load ratio xi (resolved from the amplitude when the scenario gives `amplitude`;
    /// for a bar stack, at its first interface; 0 without an incident wave; NaN for a 2D
    /// scenario, whose cracks meet diffracted waves, not one incident wave).
    #[getter]
    fn xi(&self) -> f64 {
        self.template.base().map_or(f64::NAN, |m| m.load_ratio())
    }

    /// Path the scenario stands for: its file, or `<dict>` (its folder resolves the
    /// scenario's relative paths).
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// Values that are legal but almost surely a unit slip (`frequency = 1` meant as
    /// 1 MHz), one line each (`FILE: FIELD = VALUE: reason`); `run` warns with them.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.template
            .base()
            .map(|m| m.warnings().iter().map(|w| w.to_string()).collect())
            .unwrap_or_default()
    }

    /// The scenario's keys as given (no defaults filled in), as JSON text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(self.template.table())
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Pickle support: `(scenario_from_json, (keys as JSON, path))`, so a scenario (and
    /// every result holding one) crosses process pools, Dask futures and caches.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let rebuild = py
            .import("contactwave._core")?
            .getattr("scenario_from_json")?;
        Ok((
            rebuild,
            (self.to_json()?, self.path.to_string_lossy().into_owned()),
        ))
    }

    fn __repr__(&self) -> String {
        let (file, kind, xi) = (self.template.file(), self.template.kind(), self.xi());
        if xi.is_nan() {
            format!("Scenario(file={file:?}, kind={kind:?})")
        } else {
            format!("Scenario(file={file:?}, kind={kind:?}, xi={xi:?})")
        }
    }
}

/// JSON value -> TOML value; `null` is an error naming the dotted key.
fn json_to_toml(v: &serde_json::Value, key: &str, file: &str) -> Result<toml::Value, Error> {
    use serde_json::Value as J;
    Ok(match v {
        J::Null => {
            return Err(Error::invalid(
                file,
                key,
                "None",
                "None is not a value; leave the key out to get its default",
            ))
        }
        J::Bool(b) => toml::Value::Boolean(*b),
        J::Number(n) => match n.as_i64() {
            Some(i) => toml::Value::Integer(i),
            None => toml::Value::Float(n.as_f64().unwrap_or(f64::NAN)),
        },
        J::String(s) => toml::Value::String(s.clone()),
        J::Array(a) => toml::Value::Array(
            a.iter()
                .enumerate()
                .map(|(i, x)| json_to_toml(x, &format!("{key}.{i}"), file))
                .collect::<Result<_, _>>()?,
        ),
        J::Object(o) => toml::Value::Table(json_object_to_table(o, key, file)?),
    })
}

fn json_object_to_table(
    o: &serde_json::Map<String, serde_json::Value>,
    prefix: &str,
    file: &str,
) -> Result<toml::Table, Error> {
    let mut t = toml::Table::new();
    for (k, v) in o {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        t.insert(k.clone(), json_to_toml(v, &key, file)?);
    }
    Ok(t)
}

/// A JSON object's text -> TOML table (`file` names it in errors).
fn table_from_json(text: &str, file: &str) -> Result<toml::Table, Error> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Parse {
        file: file.to_string(),
        message: format!("not valid JSON: {e}"),
    })?;
    match &v {
        serde_json::Value::Object(o) => json_object_to_table(o, "", file),
        _ => Err(Error::Parse {
            file: file.to_string(),
            message: "a scenario must be a dict (mapping of section names to dicts)".into(),
        }),
    }
}

/// Load and validate a scenario file (TOML), whichever its kind.
#[pyfunction]
fn load_scenario(py: Python<'_>, path: PathBuf) -> PyResult<PyScenario> {
    let p = path.clone();
    let template = py.detach(move || model::load(&p)).map_err(to_py)?;
    Ok(PyScenario { template, path })
}

/// Validate a scenario given as JSON text (a dict's `json.dumps`). `file` names it in
/// errors and its folder resolves relative paths (`<dict>`: the working directory).
#[pyfunction]
#[pyo3(signature = (text, file = "<dict>"))]
fn scenario_from_json(py: Python<'_>, text: &str, file: &str) -> PyResult<PyScenario> {
    let table = table_from_json(text, file).map_err(to_py)?;
    planned(py, table, file)
}

/// A scenario table validated as if read from `file` (the GIL released meanwhile).
fn planned(py: Python<'_>, table: toml::Table, file: &str) -> PyResult<PyScenario> {
    let path = PathBuf::from(file);
    let p = path.clone();
    let template = py
        .detach(move || model::plan_valid(table, &p))
        .map_err(to_py)?;
    Ok(PyScenario { template, path })
}

/// Validate a scenario given as TOML text (a scenario file's contents). `file` names it
/// in errors and its folder resolves relative paths (`<toml>`: the working directory).
#[pyfunction]
#[pyo3(signature = (text, file = "<toml>"))]
fn scenario_from_toml(py: Python<'_>, text: &str, file: &str) -> PyResult<PyScenario> {
    let table = contactwave::scenario::parse_toml(text, file).map_err(to_py)?;
    planned(py, table, file)
}

/// A record (plain values of a run) as Python objects: numbers, strings, lists, numpy
/// arrays (1-D, and 2-D for rows), tuples and dicts, in the record's order.
fn record_to_py<'py>(py: Python<'py>, r: Record) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in r.entries {
        d.set_item(k, value_to_py(py, v)?)?;
    }
    Ok(d)
}

fn value_to_py(py: Python<'_>, v: Value) -> PyResult<Bound<'_, PyAny>> {
    Ok(match v {
        Value::None => py.None().into_bound(py),
        Value::Number(x) => x.into_pyobject(py)?.into_any(),
        Value::Text(t) => t.into_pyobject(py)?.into_any(),
        Value::List(l) => l.into_pyobject(py)?.into_any(),
        Value::Array(a) => a.into_pyarray(py).into_any(),
        Value::Rows(r) => rows(py, &r)?.into_any(),
        Value::Tuple(items) => {
            let items = items
                .into_iter()
                .map(|x| value_to_py(py, x))
                .collect::<PyResult<Vec<_>>>()?;
            PyTuple::new(py, items)?.into_any()
        }
        Value::Map(m) => record_to_py(py, m)?.into_any(),
    })
}

/// Run a scenario of any kind (GIL released while it runs). Returns its record as a dict:
/// `kind` and the kind's arrays and summary (see `Outcome::record` of each model: for a
/// half-space run the interface arrays `t`, `gap`, ..., the probe arrays `probe_t`, ...,
/// `summary`, `spectrum`, `incident_bands` / `reflected_bands`, `A_inc`, `dt`, `probe_x`;
/// for a bar stack `t`, `force`, ..., `gap`, `pressure`, `beta`, `stiffness` (2-D),
/// `frf`, `waves`, `probes`, `static_pressure`, `dt`, `summary`).
#[pyfunction]
fn run<'py>(py: Python<'py>, scenario: &PyScenario) -> PyResult<Bound<'py, PyDict>> {
    let m = scenario.template.base().map_err(to_py)?;
    contactwave::interrupt::clear();
    // the run goes on a helper thread while this one watches for Ctrl-C: a long bar-stack
    // run stops at its next time-step check and raises KeyboardInterrupt
    let record = detach_interruptibly(py, move || {
        WORKSPACES
            .with(|ws| m.run_in(&RunControl::default(), ws))
            .map(|o| o.record())
    })?;
    record_to_py(py, record)
}

/// The table of a scenario file (TOML) or of a dict's JSON text, and the path naming it.
fn any_table(
    path: Option<PathBuf>,
    text: Option<&str>,
    file: &str,
) -> PyResult<(toml::Table, PathBuf)> {
    match (path, text) {
        (Some(p), None) => Ok((contactwave::scenario::read_table(&p).map_err(to_py)?, p)),
        (None, Some(t)) => Ok((
            table_from_json(t, file).map_err(to_py)?,
            PathBuf::from(file),
        )),
        _ => Err(PyTypeError::new_err(
            "give exactly one of `path` and `text`",
        )),
    }
}

/// The table of a scenario file (TOML), as JSON text (what sweeps take as their base).
#[pyfunction]
fn table_json(path: PathBuf) -> PyResult<String> {
    let (table, _) = any_table(Some(path), None, "")?;
    serde_json::to_string(&table).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The table of a scenario's TOML text (read as the file `file`), as JSON text (a sweep's
/// base given as text).
#[pyfunction]
#[pyo3(signature = (text, file = "<toml>"))]
fn toml_table_json(text: &str, file: &str) -> PyResult<String> {
    let table = contactwave::scenario::parse_toml(text, file).map_err(to_py)?;
    serde_json::to_string(&table).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// One row per history of equal length: a 2-D array (rows x samples).
fn rows<'py>(py: Python<'py>, v: &[Vec<f64>]) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let n = v.first().map_or(0, Vec::len);
    let flat: Vec<f64> = v.iter().flat_map(|r| r.iter().copied()).collect();
    let a = Array2::from_shape_vec((v.len(), n), flat)
        .map_err(|e| PyValueError::new_err(format!("ragged histories: {e}")))?;
    Ok(a.into_pyarray(py))
}

/// Time `n` runs of the Rust `simulate` of a scenario (GIL released): the wall time of
/// each, in seconds. For measuring the Python overhead of `run`.
#[pyfunction]
fn bench_simulate(py: Python<'_>, scenario: &PyScenario, n: usize) -> PyResult<Vec<f64>> {
    let m = scenario.template.base().map_err(to_py)?;
    py.detach(move || {
        (0..n)
            .map(|_| {
                let t0 = Instant::now();
                let r = m.run(&RunControl::default())?;
                let dt = t0.elapsed().as_secs_f64();
                std::hint::black_box(r);
                Ok(dt)
            })
            .collect::<Result<Vec<f64>, Error>>()
    })
    .map_err(to_py)
}

/// Stress (Pa) of the scenario's contact law at each gap (m), on the monotone-loading
/// curve: the adhesion beta evolves in its rate-independent limit as the gap increases
/// through the given values (taken in increasing order, whatever their order in `gap`),
/// like `ContactLaw::curve`. On a rigid compression branch, gaps <= 0 give `-p0`; on a
/// bonded traction branch, openings give 0 (the constraint sets the stress there).
#[pyfunction]
fn law_curve<'py>(
    py: Python<'py>,
    scenario: &PyScenario,
    gap: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let gaps: Vec<f64> = gap.as_array().iter().copied().collect();
    if let Some(g) = gaps.iter().find(|g| g.is_nan()) {
        return Err(PyValueError::new_err(format!(
            "gap: {g} is not a number; every gap must be a number (m)"
        )));
    }
    let base = scenario.template.base().map_err(to_py)?;
    let Some(hs) = base.as_any().downcast_ref::<Scenario>() else {
        return Err(PyValueError::new_err(format!(
            "{}: law_curve takes a half-space scenario (or a law dict), not a {} scenario",
            scenario.template.file(),
            scenario.template.kind()
        )));
    };
    let law = hs.law.clone();
    let stress = py.detach(move || {
        let uc = law.critical_gap();
        let mut order: Vec<usize> = (0..gaps.len()).collect();
        order.sort_by(|&a, &b| gaps[a].total_cmp(&gaps[b]));
        let mut stress = vec![0.0; gaps.len()];
        let mut beta = 1.0;
        for i in order {
            let g = gaps[i];
            if g > uc && !law.traction.is_rigid() {
                beta = law.traction.update_adhesion(g - uc, beta, f64::INFINITY);
            }
            stress[i] = law.stress(g, beta);
        }
        stress
    });
    Ok(stress.into_pyarray(py))
}

/// Least-squares fit of `K = C p^m` in log-log: dict `{c, m, r2}`.
#[pyfunction]
fn fit_power_law<'py>(
    py: Python<'py>,
    pressure: PyReadonlyArray1<'py, f64>,
    stiffness: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let p: Vec<f64> = pressure.as_array().iter().copied().collect();
    let k: Vec<f64> = stiffness.as_array().iter().copied().collect();
    let f = contactwave::analysis::fit::fit_power_law(&p, &k).map_err(to_py)?;
    let d = PyDict::new(py);
    d.set_item("c", f.c)?;
    d.set_item("m", f.m)?;
    d.set_item("r2", f.r2)?;
    Ok(d)
}

/// `(name, SI unit)` of a dotted scenario key or a summary key, as the CLI's plots label
/// their axes (`interface.static_pressure` -> `("static pressure p0", "Pa")`; `""` when
/// dimensionless or unknown): the labels of the Python `.plot()` helpers.
#[pyfunction]
fn quantity(key: &str) -> (String, &'static str) {
    contactwave::output::labels::quantity(key)
}

/// The SI value of `value` for the scenario key `key`: a number as it is, a unit string
/// (`"1 MHz"`) converted; an unknown or mismatched unit is a `ValueError` naming the key.
#[pyfunction]
fn si_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    if let Ok(text) = value.extract::<String>() {
        let dim = contactwave::scenario::units::dimension_of_key(key).ok_or_else(|| {
            PyValueError::new_err(format!(
                "field `{key}` = {text:?}: expected a number (this key takes no unit)"
            ))
        })?;
        return contactwave::scenario::units::parse(&text, dim)
            .map_err(|why| PyValueError::new_err(format!("field `{key}` = {text:?}: {why}")));
    }
    value.extract::<f64>()
}

/// What one sweep point gave: its summary or its error message.
type Outcome = Result<contactwave::analysis::Summary, String>;

/// The executor's results as outcomes (a point not started: `cancelled`).
fn outcomes(
    results: Vec<Option<contactwave::Result<contactwave::analysis::Summary>>>,
) -> Vec<Outcome> {
    results
        .into_iter()
        .map(|r| match r {
            Some(r) => r.map_err(|e| e.to_string()),
            None => Err("cancelled".to_string()),
        })
        .collect()
}

/// Outcomes -> `(keys, values[n_points, n_keys], errors[(row, message)])`. Keys: those of
/// the first successful point, then any new key of later points; missing values are NaN
/// (so are all values of a failed point).
type Table<'py> = (
    Vec<String>,
    Bound<'py, numpy::PyArray2<f64>>,
    Vec<(usize, String)>,
);

fn outcomes_table(py: Python<'_>, outcomes: Vec<Outcome>) -> PyResult<Table<'_>> {
    let mut keys: Vec<String> = Vec::new();
    for s in outcomes.iter().flatten() {
        for k in s.keys() {
            if !keys.iter().any(|x| x == k) {
                keys.push(k.to_string());
            }
        }
    }
    let mut data = vec![f64::NAN; outcomes.len() * keys.len()];
    let mut errors = Vec::new();
    for (i, o) in outcomes.into_iter().enumerate() {
        match o {
            Ok(s) => {
                for (k, key) in keys.iter().enumerate() {
                    data[i * keys.len() + k] = s.get(key).unwrap_or(f64::NAN);
                }
            }
            Err(e) => errors.push((i, e)),
        }
    }
    let rows = data.len().checked_div(keys.len()).unwrap_or(errors.len());
    let arr = Array2::from_shape_vec((rows, keys.len()), data)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((keys, arr.into_pyarray(py), errors))
}

/// What `sweep_plan` returns: the points, the hash, the memory estimates.
type SweepPlan<'py> = (
    Bound<'py, numpy::PyArray2<f64>>,
    String,
    Bound<'py, numpy::PyArray1<f64>>,
);

/// Build and validate a sweep (base scenario table as JSON, axes `(key, values)`); returns
/// `(points[n, n_axes], hash, memory[n])`: `memory[i]` is the bytes one run of point `i`
/// needs ([`contactwave::model::Model::memory_estimate`]; NaN where the kind gives no
/// estimate). Every point is validated as a scenario (ValueError naming the field and the
/// point otherwise).
#[pyfunction]
#[pyo3(signature = (base_json, base_path, axes))]
fn sweep_plan<'py>(
    py: Python<'py>,
    base_json: &str,
    base_path: PathBuf,
    axes: Vec<(String, Vec<f64>)>,
) -> PyResult<SweepPlan<'py>> {
    let file = base_path.display().to_string();
    let table = table_from_json(base_json, &file).map_err(to_py)?;
    let (sweep, memory) = py
        .detach(move || -> Result<(Sweep, Vec<f64>), Error> {
            let sweep = Sweep::from_parts(Path::new("<sweep>"), base_path, table, axes)?;
            let memory = sweep
                .runnable()?
                .iter()
                .map(|m| Ok(m.memory_estimate()?.unwrap_or(f64::NAN)))
                .collect::<Result<Vec<f64>, Error>>()?;
            Ok((sweep, memory))
        })
        .map_err(to_py)?;
    Ok((
        points_array(py, &sweep)?,
        sweep.hash,
        memory.into_pyarray(py),
    ))
}

/// Points a local sweep builds and runs at a time: the models and summaries of one chunk
/// are alive at once, then folded into the result columns (memory: the result table plus
/// one chunk, whatever the number of points).
const SWEEP_CHUNK: usize = 4096;

/// Result columns of a sweep, filled chunk by chunk: keys in order of first appearance,
/// one column of `n` values per key (NaN where a point has no value).
struct Columns {
    n: usize,
    keys: Vec<String>,
    columns: Vec<Vec<f64>>,
    errors: Vec<(usize, String)>,
}

impl Columns {
    fn new(n: usize) -> Self {
        Columns {
            n,
            keys: Vec::new(),
            columns: Vec::new(),
            errors: Vec::new(),
        }
    }

    /// Fold the outcomes of points `start..start + outcomes.len()`.
    fn fold(&mut self, start: usize, outcomes: Vec<Outcome>) {
        for (j, o) in outcomes.into_iter().enumerate() {
            match o {
                Ok(s) => {
                    for key in s.keys() {
                        if !self.keys.iter().any(|k| k == key) {
                            self.keys.push(key.to_string());
                            self.columns.push(vec![f64::NAN; self.n]);
                        }
                    }
                    for (k, key) in self.keys.iter().enumerate() {
                        self.columns[k][start + j] = s.get(key).unwrap_or(f64::NAN);
                    }
                }
                Err(e) => self.errors.push((start + j, e)),
            }
        }
    }

    fn into_table(self, py: Python<'_>) -> PyResult<Table<'_>> {
        let k = self.keys.len();
        let mut data = vec![f64::NAN; self.n * k];
        for (c, col) in self.columns.iter().enumerate() {
            for (i, v) in col.iter().enumerate() {
                data[i * k + c] = *v;
            }
        }
        let arr = Array2::from_shape_vec((self.n, k), data)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok((self.keys, arr.into_pyarray(py), self.errors))
    }
}

/// Run a whole sweep on local cores (the executor; `threads=None`: all cores) with the GIL
/// released; Ctrl-C cancels it (KeyboardInterrupt once the running points finish).
/// Every point is validated first (flat memory), then the points are built and run in
/// chunks of [`SWEEP_CHUNK`]: memory is the result table plus one chunk.
/// Returns `(points[n, n_axes], hash, (keys, values[n_points, n_keys], errors[(point,
/// message)]))` in grid order.
#[pyfunction]
#[pyo3(signature = (base_json, base_path, axes, threads = None, progress = None))]
fn sweep_local<'py>(
    py: Python<'py>,
    base_json: &str,
    base_path: PathBuf,
    axes: Vec<(String, Vec<f64>)>,
    threads: Option<usize>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, numpy::PyArray2<f64>>, String, Table<'py>)> {
    let file = base_path.display().to_string();
    let table = table_from_json(base_json, &file).map_err(to_py)?;
    if let Some(n) = threads {
        contactwave::run::check_threads(n).map_err(|_| {
            PyValueError::new_err(format!(
                "threads = {n}: must be an integer in [1, {}] (or None: one per core)",
                contactwave::run::MAX_THREADS
            ))
        })?;
    }
    contactwave::interrupt::clear();
    let (sweep, plan) = detach_interruptibly(py, move || -> Result<_, Error> {
        let sweep = Sweep::from_parts(Path::new("<sweep>"), base_path, table, axes)?;
        let plan = sweep.validate()?;
        Ok((sweep, plan))
    })?;
    let n = sweep.points.len();
    let mut cols = Columns::new(n);
    for start in (0..n).step_by(SWEEP_CHUNK) {
        let end = (start + SWEEP_CHUNK).min(n);
        let models = detach_interruptibly(py, || {
            (start..end)
                .map(|i| sweep.model(&plan, i))
                .collect::<Result<Vec<_>, Error>>()
        })?;
        let outs = run_interruptibly(
            py,
            &models,
            Executor::new().threads(threads),
            progress.as_ref(),
            (start, n),
        )?;
        drop(models);
        cols.fold(start, outs);
    }
    if n == 0 {
        if let Some(cb) = &progress {
            cb.call1((0, 0))?;
        }
    }
    Ok((
        points_array(py, &sweep)?,
        sweep.hash.clone(),
        cols.into_table(py)?,
    ))
}

fn points_array<'py>(py: Python<'py>, sweep: &Sweep) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let flat: Vec<f64> = sweep.points.iter().flatten().copied().collect();
    let arr = Array2::from_shape_vec((sweep.points.len(), sweep.axes.len()), flat)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(arr.into_pyarray(py))
}

/// Run `f` (library work that checks [`contactwave::interrupt`], e.g. the validation of
/// a sweep's points) in a helper thread while this thread, GIL released between polls,
/// checks for signals every [`SIGNAL_POLL`]; on a signal, request the interruption, wait
/// for `f` and return the signal's exception (KeyboardInterrupt for Ctrl-C).
fn detach_interruptibly<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> Result<T, Error> + Send,
) -> PyResult<T> {
    let finished = (Mutex::new(false), Condvar::new());
    std::thread::scope(|s| {
        let worker = s.spawn(|| {
            let out = f();
            let (m, cv) = &finished;
            *m.lock().unwrap_or_else(|p| p.into_inner()) = true;
            cv.notify_all();
            out
        });
        loop {
            let finished_now = py.detach(|| {
                let (m, cv) = &finished;
                let g = m.lock().unwrap_or_else(|p| p.into_inner());
                let (g, _) = cv
                    .wait_timeout_while(g, SIGNAL_POLL, |d| !*d)
                    .unwrap_or_else(|p| p.into_inner());
                *g
            });
            if let Err(e) = py.check_signals() {
                contactwave::interrupt::request();
                let _ = py.detach(|| worker.join());
                contactwave::interrupt::clear();
                return Err(e);
            }
            if finished_now {
                break;
            }
        }
        py.detach(|| worker.join())
            .map_err(|_| PyRuntimeError::new_err("worker thread panicked"))?
            .map_err(to_py)
    })
}

/// The workspaces of this process's runs (one per run at a time, kept from run to run:
/// the locked interface's floors and the kept incident table, model.md sections 4 and
/// 6.1), so that a `cw.run` or a sweep point after the first is a warm run, as in a Rust
/// loop, whichever Python thread calls. Owned by the module, not by a thread: each call
/// may run on a fresh thread.
static WORKSPACES: Workspaces<contactwave::model::Workspace> = Workspaces::new();

/// Run `models` on the executor in a helper thread while this thread (GIL released
/// between polls) checks for signals every [`SIGNAL_POLL`] and calls the Python
/// `progress(offset + done, total)` callback when the count moved; on a signal (or an exception in
/// the callback), cancel (the executor starts no new point), wait for the running points
/// and return the exception.
fn run_interruptibly(
    py: Python<'_>,
    models: &[Arc<dyn contactwave::model::Model>],
    executor: Executor,
    progress: Option<&Bound<'_, PyAny>>,
    (offset, total): (usize, usize),
) -> PyResult<Vec<Outcome>> {
    contactwave::interrupt::clear();
    let cancel = AtomicBool::new(false);
    let done = AtomicUsize::new(offset);
    let finished = (Mutex::new(false), Condvar::new());
    let mut reported = usize::MAX;
    std::thread::scope(|s| {
        let worker = s.spawn(|| {
            let count = |d: usize, _total: usize| done.store(offset + d, Ordering::SeqCst);
            let observer = Progress {
                report: &count,
                cancel: Some(&cancel),
            };
            let out = executor.map(
                models,
                |m| WORKSPACES.with(|ws| m.summary_in(ws)),
                &observer,
            );
            let (m, cv) = &finished;
            *m.lock().unwrap_or_else(|p| p.into_inner()) = true;
            cv.notify_all();
            out
        });
        loop {
            let finished_now = py.detach(|| {
                let (m, cv) = &finished;
                let g = m.lock().unwrap_or_else(|p| p.into_inner());
                let (g, _) = cv
                    .wait_timeout_while(g, SIGNAL_POLL, |d| !*d)
                    .unwrap_or_else(|p| p.into_inner());
                *g
            });
            let mut check = py.check_signals();
            if let (Some(cb), Ok(())) = (progress, &check) {
                let d = done.load(Ordering::SeqCst);
                if d != reported {
                    reported = d;
                    check = cb.call1((d, total)).map(|_| ());
                }
            }
            if let Err(e) = check {
                cancel.store(true, Ordering::SeqCst);
                // running points stop at their next check too
                contactwave::interrupt::request();
                let _ = py.detach(|| worker.join());
                contactwave::interrupt::clear();
                return Err(e);
            }
            if finished_now {
                break;
            }
        }
        // the last count once, unless the loop's last poll reported it already
        if let Some(cb) = progress {
            let d = done.load(Ordering::SeqCst);
            if d != reported {
                cb.call1((d, total))?;
            }
        }
        py.detach(|| worker.join())
            .map_err(|_| PyRuntimeError::new_err("sweep worker thread panicked"))?
            .map(outcomes)
            .map_err(to_py)
    })
}

/// Run a list of sweep points, one after the other (what one distributed task does):
/// `points[i]` holds the values of the dotted keys `parameters` for point `i`, written
/// into the base table (JSON) exactly as a local sweep does, so the values are
/// bit-identical to the local run's. GIL released. Returns the table of `sweep_local`.
#[pyfunction]
fn run_points<'py>(
    py: Python<'py>,
    base_json: &str,
    base_path: PathBuf,
    parameters: Vec<String>,
    points: PyReadonlyArray2<'py, f64>,
) -> PyResult<Table<'py>> {
    let file = base_path.display().to_string();
    let table = table_from_json(base_json, &file).map_err(to_py)?;
    let pts = points.as_array();
    if pts.ncols() != parameters.len() {
        return Err(PyTypeError::new_err(format!(
            "points: {} columns for {} parameters",
            pts.ncols(),
            parameters.len()
        )));
    }
    let rows: Vec<Vec<f64>> = pts.outer_iter().map(|r| r.to_vec()).collect();
    let outcomes = py
        .detach(move || -> Result<Vec<Outcome>, Error> {
            // plan once, set numbers per point: exactly what a local sweep does
            let template = model::plan(table, &base_path);
            let params = parameters
                .iter()
                .map(|k| template.param(k))
                .collect::<Result<Vec<_>, Error>>()?;
            let run = |values: &Vec<f64>| {
                let v: Vec<_> = params.iter().zip(values.iter().copied()).collect();
                let m = template.build(&v)?;
                WORKSPACES.with(|ws| m.summary_in(ws))
            };
            // one task runs its points one after the other (the cluster runs the tasks)
            Ok(outcomes(
                Executor::new().threads(Some(1)).map(&rows, run, &Quiet)?,
            ))
        })
        .map_err(to_py)?;
    outcomes_table(py, outcomes)
}

/// The compiled core of the `contactwave` package.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScenario>()?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(load_scenario, m)?)?;
    m.add_function(wrap_pyfunction!(scenario_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(scenario_from_toml, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(table_json, m)?)?;
    m.add_function(wrap_pyfunction!(toml_table_json, m)?)?;
    m.add_function(wrap_pyfunction!(bench_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(law_curve, m)?)?;
    m.add_function(wrap_pyfunction!(fit_power_law, m)?)?;
    m.add_function(wrap_pyfunction!(si_value, m)?)?;
    m.add_function(wrap_pyfunction!(quantity, m)?)?;
    m.add_function(wrap_pyfunction!(identify, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_local, m)?)?;
    m.add_function(wrap_pyfunction!(run_points, m)?)?;
    Ok(())
}

/// Inverse identification (`contactwave identify`): `text` is the identification table as
/// JSON (a dict's `json.dumps`; `None`: read the TOML file at `path`); `path` names it and
/// its folder resolves `base` and `data`. Returns the `identification.json` object as JSON
/// text (with `design = True`: the design ranking, `design.json`) and the text of
/// `fit.csv` (empty for a design). With `out`, the output files are written there. The computation runs without the GIL.
#[pyfunction]
#[pyo3(signature = (text, path, out = None, design = false))]
fn identify(
    py: Python<'_>,
    text: Option<String>,
    path: PathBuf,
    out: Option<PathBuf>,
    design: bool,
) -> PyResult<(String, String)> {
    use contactwave::inverse::{self, IdentifySpec, Model};
    use contactwave::output::provenance::Provenance;
    py.detach(move || -> Result<(String, String), Error> {
        let from_file = text.is_none();
        let spec = match text {
            Some(t) => {
                let table = table_from_json(&t, &path.display().to_string())?;
                IdentifySpec::from_table(table, &path)?
            }
            None => IdentifySpec::load(&path)?,
        };
        // the files' provenance: a dict has no input file, its base and data are data files
        let call = if from_file {
            format!(
                "python: contactwave.identify({:?})",
                path.display().to_string()
            )
        } else {
            "python: contactwave.identify(<dict>)".to_string()
        };
        let provenance = if from_file {
            Provenance::of_identification(&path, &spec, call)?
        } else {
            let mut p = Provenance::new(call);
            p.add_data_file(&spec.base)?;
            if let Some(d) = &spec.data_file {
                p.add_data_file(d)?;
            }
            p
        };
        if let Some(o) = &out {
            if o.exists() && !o.is_dir() {
                return Err(Error::io(
                    o,
                    std::io::Error::other("exists and is not a directory"),
                ));
            }
        }
        let (json, files) = if design {
            let model = Model::new(&spec);
            let r = inverse::design(&model)?;
            let json = r.to_json();
            let text = serde_json::to_string_pretty(&json).unwrap_or_default();
            let files = vec![
                contactwave::output::OutputFile {
                    name: "design.json".into(),
                    contents: text + "\n",
                },
                contactwave::output::OutputFile {
                    name: "design.csv".into(),
                    contents: r.to_csv(),
                },
            ];
            (json, files)
        } else {
            let r = inverse::identify(&spec, &|_| {})?;
            (
                r.to_json(),
                contactwave::output::identify::identification_files(&r)?,
            )
        };
        // fit.csv (measured and fitted values per row) for `Identification.plot()`
        let fit_csv = files
            .iter()
            .find(|f| f.name == "fit.csv")
            .map(|f| f.contents.clone())
            .unwrap_or_default();
        if let Some(o) = &out {
            let mut files = files;
            provenance.stamp(&mut files);
            contactwave::output::write_files(o, &files)?;
        }
        Ok((json.to_string(), fit_csv))
    })
    .map_err(to_py)
}

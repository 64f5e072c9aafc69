//! Inverse identification of interface parameters from a measured nonlinear signature
//! (`contactwave identify`).
//!
//! # Identification file (TOML)
//!
//! ```toml
//! base = "base.toml"          # base scenario, relative to this file
//! data = "measured.csv"       # measured curve(s), relative to this file
//! observed = ["A2_over_A1"]   # optional: the summary columns fitted (default: all in the CSV)
//!
//! [set]                       # optional fixed overrides of the base scenario
//! "solver.samples_per_period" = 100
//!
//! [[parameter]]               # the unknowns
//! key = "interface.traction.stiffness"
//! bounds = [1e9, 1e17]        # in the key's SI unit
//! scale = "log"               # "log" (fit log10 of the value) or "linear"
//! # initial = 1e12            # optional start (default: the base value, else the middle)
//! # also = ["..."]            # optional further keys set to the same value (tied)
//!
//! [fit]                       # optional
//! relative_noise = 0.01       # sigma = relative_noise |y| + absolute_noise where the CSV
//! absolute_noise = 0.0        #   has no `sigma_<name>` column
//! particles = 16              # particle swarm (global stage)
//! iterations = 20
//! local_iterations = 80       # Nelder-Mead (local refinement)
//! local_starts = 3            # refinements from the best distinct swarm points
//! bootstrap = 20              # bootstrap resamples (0: none)
//! bootstrap_iterations = 20   # Nelder-Mead iterations per bootstrap refit
//! seed = 1
//!
//! [design]                    # optional: `identify --design`
//! key = "incident.frequency"
//! values = [0.5e6, 1e6, 2e6]
//! ```
//!
//! # Measured data (CSV)
//!
//! A header line, then one row per measured point. Columns whose name contains a `.` are
//! dotted scenario keys set at that point (the control variable such as `incident.xi`,
//! `incident.amplitude`, `interface.static_pressure`, `excitation.peak`, and any further
//! condition such as `incident.frequency`); `sigma_<name>` columns give the standard
//! uncertainty of the observed column `<name>`; the other columns are observed summary
//! keys (`A2_over_A1`, `A1_over_Ainc`, `first_mode_hz`, ...). `#` starts a comment line.
//!
//! # Method
//!
//! Weighted least squares `sum_i ((model_i - y_i) / sigma_i)^2` in the scaled parameter
//! space (log10 of `log` parameters), a global stage (argmin particle swarm) then a local
//! one (argmin Nelder-Mead); forward runs in parallel (rayon). Identifiability: see
//! [`identifiability`].

pub mod design;
pub mod estimate;
pub mod identifiability;
pub mod report;

use crate::analysis::Summary;
use crate::error::{Error, Result};
use crate::scenario::{apply_set, parse_toml, set_dotted, AnyScenario};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

pub use design::{design, DesignCandidate, DesignReport};
pub use estimate::{estimate, Estimate};
pub use identifiability::{Identifiability, Verdict};
pub use report::{identification_files, Identification};

/// How a parameter is searched and reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// The fit works on `log10(value)` (value > 0).
    Log,
    /// The fit works on the value itself.
    Linear,
}

/// One unknown parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Dotted scenario key, e.g. `interface.traction.stiffness` (unit: that of the key).
    pub key: String,
    /// Lower bound (key's unit).
    pub lower: f64,
    /// Upper bound (key's unit).
    pub upper: f64,
    /// Search scale.
    pub scale: Scale,
    /// Starting value (key's unit).
    pub initial: f64,
    /// Further keys set to the same value (a parameter shared by several interfaces,
    /// e.g. `interface.1.compression.c` tied to `interface.0.compression.c`).
    pub also: Vec<String>,
}

impl Parameter {
    /// Value -> scaled coordinate (log10 for log parameters).
    pub fn to_scaled(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Log => v.log10(),
            Scale::Linear => v,
        }
    }
    /// Scaled coordinate -> value.
    pub fn from_scaled(&self, z: f64) -> f64 {
        match self.scale {
            Scale::Log => 10f64.powf(z),
            Scale::Linear => z,
        }
    }
    /// Bounds in the scaled space.
    pub fn scaled_bounds(&self) -> (f64, f64) {
        (self.to_scaled(self.lower), self.to_scaled(self.upper))
    }
}

/// One observed column with its uncertainties.
#[derive(Debug, Clone, PartialEq)]
pub struct Observed {
    /// Summary key, e.g. `A2_over_A1`.
    pub key: String,
    /// Measured values, one per row.
    pub values: Vec<f64>,
    /// Standard uncertainties (> 0), one per row.
    pub sigma: Vec<f64>,
}

/// The measured data: conditions per row and observed columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Dotted keys set at each row (the control variable first).
    pub conditions: Vec<String>,
    /// `rows[i][k]`: value of `conditions[k]` at row `i`.
    pub rows: Vec<Vec<f64>>,
    /// Observed columns.
    pub observed: Vec<Observed>,
}

impl Measured {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }
    /// True when there is no row.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
    /// Number of residuals (rows x observed columns).
    pub fn residual_count(&self) -> usize {
        self.rows.len() * self.observed.len()
    }
    /// The control variable (first condition).
    pub fn control(&self) -> &str {
        self.conditions.first().map(String::as_str).unwrap_or("")
    }
}

/// Options of the estimation.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Default relative uncertainty of the observed values (without `sigma_` column).
    pub relative_noise: f64,
    /// Default absolute uncertainty added to it (unit of the observed key).
    pub absolute_noise: f64,
    /// Particles of the swarm (0: skip the global stage).
    pub particles: usize,
    /// Swarm iterations.
    pub iterations: u64,
    /// Nelder-Mead iterations.
    pub local_iterations: u64,
    /// Local refinements started from the best distinct points of the swarm (>= 1).
    pub local_starts: usize,
    /// Bootstrap resamples (0: none).
    pub bootstrap: usize,
    /// Nelder-Mead iterations per bootstrap refit.
    pub bootstrap_iterations: u64,
    /// Seed of the swarm and of the bootstrap.
    pub seed: u64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            relative_noise: 0.01,
            absolute_noise: 0.0,
            particles: 16,
            iterations: 20,
            local_iterations: 80,
            local_starts: 3,
            bootstrap: 20,
            bootstrap_iterations: 20,
            seed: 1,
        }
    }
}

/// `[design]`: candidate values of a condition key to rank (`identify --design`).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpec {
    /// Dotted key varied between candidates (default `incident.frequency`).
    pub key: String,
    /// Candidate values (key's unit).
    pub values: Vec<f64>,
    /// Control-variable values of each candidate experiment (default: those of the data).
    pub control_values: Option<Vec<f64>>,
}

/// A loaded identification file.
#[derive(Debug, Clone)]
pub struct IdentifySpec {
    /// The identification file (or `<dict>`).
    pub file: PathBuf,
    /// The base scenario file.
    pub base: PathBuf,
    /// Base scenario with the `[set]` overrides applied.
    pub base_table: toml::Table,
    /// The data file (`None` when the data were given inline).
    pub data_file: Option<PathBuf>,
    /// The measured data.
    pub measured: Measured,
    /// The unknowns.
    pub parameters: Vec<Parameter>,
    /// Estimation options.
    pub fit: FitOptions,
    /// Experiment design candidates.
    pub design: Option<DesignSpec>,
}

fn show(v: &toml::Value) -> String {
    v.to_string()
}

fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// The number at a dotted key of a table (`interface.0.compression.c` indexes arrays).
pub fn get_dotted(table: &toml::Table, key: &str) -> Option<f64> {
    let mut parts = key.split('.');
    let mut cur: &toml::Value = table.get(parts.next()?)?;
    for p in parts {
        cur = match cur {
            toml::Value::Table(t) => t.get(p)?,
            toml::Value::Array(a) => a.get(p.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    number(cur)
}

/// Keys whose TOML value must be an integer.
fn wants_integer(key: &str) -> bool {
    key == "solver.samples_per_period"
}

pub(crate) fn toml_number(key: &str, v: f64) -> toml::Value {
    if wants_integer(key) && v.fract() == 0.0 && v.abs() < 9e15 {
        toml::Value::Integer(v as i64)
    } else {
        toml::Value::Float(v)
    }
}

/// Summary keys an observed column may name, with whether they must be >= 0.
fn observable(key: &str) -> Option<bool> {
    let nonneg = key.starts_with('A') && key.contains("_over_")
        || key.ends_with("_hz")
        || matches!(
            key,
            "A1" | "A2" | "beta_end" | "max_gap" | "contact_loss_fraction" | "beta_star"
        )
        || key.starts_with("mean_contact_stiffness");
    let plain = key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    (plain && !key.is_empty()).then_some(nonneg)
}

impl IdentifySpec {
    /// Load an identification file, its base scenario and its data. Errors name the file,
    /// the field, the value and what is allowed.
    pub fn load(path: &Path) -> Result<IdentifySpec> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let table = parse_toml(&text, &path.display().to_string())?;
        IdentifySpec::from_table(table, path)
    }

    /// Build from a parsed identification table that came from `path` (relative paths
    /// resolve against its folder). `data` may be a file name or an inline table of
    /// equally long arrays (column name -> values).
    pub fn from_table(table: toml::Table, path: &Path) -> Result<IdentifySpec> {
        let file = path.display().to_string();
        const KEYS: &[&str] = &[
            "base",
            "data",
            "observed",
            "set",
            "parameter",
            "fit",
            "design",
        ];
        for key in table.keys() {
            if !KEYS.contains(&key.as_str()) {
                return Err(Error::invalid(
                    &file,
                    key,
                    show(&table[key]),
                    format!(
                        "unknown key; an identification file has {}",
                        KEYS.join(", ")
                    ),
                ));
            }
        }
        let dir = path.parent().unwrap_or(Path::new("."));
        let base_rel = match table.get("base") {
            Some(toml::Value::String(s)) if !s.trim().is_empty() => s.clone(),
            Some(v) => {
                return Err(Error::invalid(
                    &file,
                    "base",
                    show(v),
                    "the path of the base scenario file, relative to this file",
                ))
            }
            None => {
                return Err(Error::invalid(
                    &file,
                    "base",
                    "(missing)",
                    "required: the path of the base scenario file, relative to this file",
                ))
            }
        };
        let base = dir.join(&base_rel);
        let base_text = std::fs::read_to_string(&base).map_err(|e| Error::io(&base, e))?;
        let base_file = base.display().to_string();
        let mut base_table = parse_toml(&base_text, &base_file)?;
        if let Some(set) = table.get("set") {
            let toml::Value::Table(set) = set else {
                return Err(Error::invalid(
                    &file,
                    "set",
                    show(set),
                    "a table of dotted scenario keys and values",
                ));
            };
            apply_set(&mut base_table, set, &file)?;
        }
        // the base (with overrides) must be a valid scenario
        AnyScenario::from_table(base_table.clone(), &base)?;

        let fit = parse_fit(table.get("fit"), &file)?;
        let (measured, data_file) = parse_data(&table, dir, &file, &fit)?;
        let parameters = parse_parameters(table.get("parameter"), &file, &base_table)?;
        let design = parse_design(table.get("design"), &file)?;

        if measured.residual_count() < parameters.len() {
            return Err(Error::invalid(
                data_file
                    .as_ref()
                    .map(|p| p.display().to_string())
                    .unwrap_or_else(|| file.clone()),
                "rows",
                measured.len(),
                format!(
                    "at least as many measured values (rows x observed columns, here {}) as \
                     unknown parameters ({})",
                    measured.residual_count(),
                    parameters.len()
                ),
            ));
        }
        for c in &measured.conditions {
            if parameters.iter().any(|p| &p.key == c) {
                return Err(Error::invalid(
                    &file,
                    "parameter",
                    c,
                    "a parameter cannot also be a column of the measured data",
                ));
            }
        }
        let spec = IdentifySpec {
            file: path.to_path_buf(),
            base,
            base_table,
            data_file,
            measured,
            parameters,
            fit,
            design,
        };
        // every row must build a valid scenario at the starting values, and every
        // parameter key must be a key of the scenario
        let z0: Vec<f64> = spec
            .parameters
            .iter()
            .map(|p| p.to_scaled(p.initial))
            .collect();
        let model = Model::new(&spec);
        for (k, p) in spec.parameters.iter().enumerate() {
            let mut table = spec.base_table.clone();
            std::iter::once(&p.key)
                .chain(&p.also)
                .try_for_each(|key| set_dotted(&mut table, key, toml_number(key, p.initial)))
                .and_then(|_| AnyScenario::from_table(table, &spec.base))
                .map_err(|e| {
                    let why = match e {
                        Error::Invalid { field, allowed, .. } => format!("{field}: {allowed}"),
                        Error::Parse { message, .. } => message,
                        other => other.to_string(),
                    };
                    Error::invalid(
                        &file,
                        format!("parameter[{k}].key"),
                        &p.key,
                        format!(
                            "a dotted key of a number of the base scenario (setting it to \
                             {} fails: {why})",
                            p.initial
                        ),
                    )
                })?;
        }
        for i in 0..spec.measured.len() {
            model.scenario(i, &model.values(&z0))?;
        }
        // every observed column must be a key of this scenario's summary (one forward run)
        if let Ok(summary) = model.scenario(0, &model.values(&z0))?.summary() {
            for o in &spec.measured.observed {
                if summary.get(&o.key).is_none() {
                    return Err(Error::invalid(
                        model.data_name(),
                        "header",
                        &o.key,
                        format!(
                            "an observed column must be a summary key of the base scenario: {}",
                            summary.keys().collect::<Vec<_>>().join(", ")
                        ),
                    ));
                }
            }
        }
        Ok(spec)
    }
}

fn parse_fit(v: Option<&toml::Value>, file: &str) -> Result<FitOptions> {
    let mut o = FitOptions::default();
    let Some(v) = v else { return Ok(o) };
    let toml::Value::Table(t) = v else {
        return Err(Error::invalid(file, "fit", show(v), "a table"));
    };
    for (k, v) in t {
        let field = format!("fit.{k}");
        let x = number(v).ok_or_else(|| Error::invalid(file, &field, show(v), "a number"))?;
        let count = |max: f64| -> Result<u64> {
            if x.is_finite() && x.fract() == 0.0 && x >= 0.0 && x <= max {
                Ok(x as u64)
            } else {
                Err(Error::invalid(
                    file,
                    &field,
                    show(v),
                    format!("an integer in [0, {max}]"),
                ))
            }
        };
        match k.as_str() {
            "relative_noise" | "absolute_noise" => {
                if !(x >= 0.0 && x.is_finite()) {
                    return Err(Error::invalid(file, &field, show(v), "finite, >= 0"));
                }
                if k == "relative_noise" {
                    o.relative_noise = x
                } else {
                    o.absolute_noise = x
                }
            }
            "particles" => o.particles = count(10_000.0)? as usize,
            "iterations" => o.iterations = count(1e6)?,
            "local_iterations" => o.local_iterations = count(1e6)?,
            "local_starts" => o.local_starts = count(1000.0)?.max(1) as usize,
            "bootstrap" => o.bootstrap = count(10_000.0)? as usize,
            "bootstrap_iterations" => o.bootstrap_iterations = count(1e6)?,
            "seed" => o.seed = count(9e15)?,
            _ => {
                return Err(Error::invalid(
                    file,
                    &field,
                    show(v),
                    "unknown key; [fit] has relative_noise, absolute_noise, particles, \
                     iterations, local_iterations, local_starts, bootstrap, bootstrap_iterations, seed",
                ))
            }
        }
    }
    if o.particles == 1 {
        return Err(Error::invalid(
            file,
            "fit.particles",
            1,
            "0 (no global stage) or >= 2",
        ));
    }
    Ok(o)
}

fn parse_parameters(
    v: Option<&toml::Value>,
    file: &str,
    base: &toml::Table,
) -> Result<Vec<Parameter>> {
    let items = match v {
        Some(toml::Value::Array(a)) if !a.is_empty() => a,
        Some(v) => {
            return Err(Error::invalid(
                file,
                "parameter",
                show(v),
                "one or more [[parameter]] tables",
            ))
        }
        None => {
            return Err(Error::invalid(
                file,
                "parameter",
                "(missing)",
                "required: one or more [[parameter]] tables with key, bounds, scale",
            ))
        }
    };
    let mut out: Vec<Parameter> = Vec::new();
    for (k, item) in items.iter().enumerate() {
        let f = |name: &str| format!("parameter[{k}].{name}");
        let toml::Value::Table(t) = item else {
            return Err(Error::invalid(
                file,
                format!("parameter[{k}]"),
                show(item),
                "a table",
            ));
        };
        for key in t.keys() {
            if !["key", "bounds", "scale", "initial", "also"].contains(&key.as_str()) {
                return Err(Error::invalid(
                    file,
                    f(key),
                    show(&t[key]),
                    "unknown key; a [[parameter]] has key, bounds, scale, initial, also",
                ));
            }
        }
        let key = match t.get("key") {
            Some(toml::Value::String(s))
                if !s.is_empty() && s.split('.').all(|p| !p.is_empty()) =>
            {
                s.clone()
            }
            other => {
                return Err(Error::invalid(
                    file,
                    f("key"),
                    other.map(show).unwrap_or_else(|| "(missing)".into()),
                    "a dotted scenario key such as `interface.traction.stiffness`",
                ))
            }
        };
        if out.iter().any(|p| p.key == key) {
            return Err(Error::invalid(
                file,
                f("key"),
                &key,
                "each key at most once",
            ));
        }
        let scale = match t.get("scale") {
            None => Scale::Linear,
            Some(toml::Value::String(s)) if s == "log" => Scale::Log,
            Some(toml::Value::String(s)) if s == "linear" => Scale::Linear,
            Some(v) => {
                return Err(Error::invalid(
                    file,
                    f("scale"),
                    show(v),
                    "\"log\" or \"linear\"",
                ))
            }
        };
        let bounds = match t.get("bounds") {
            Some(toml::Value::Array(a)) if a.len() == 2 => match (number(&a[0]), number(&a[1])) {
                (Some(l), Some(u)) if l.is_finite() && u.is_finite() && l < u => (l, u),
                _ => {
                    return Err(Error::invalid(
                        file,
                        f("bounds"),
                        show(&t["bounds"]),
                        "[lower, upper], finite numbers with lower < upper",
                    ))
                }
            },
            other => {
                return Err(Error::invalid(
                    file,
                    f("bounds"),
                    other.map(show).unwrap_or_else(|| "(missing)".into()),
                    "required: [lower, upper] in the key's unit",
                ))
            }
        };
        if scale == Scale::Log && !(bounds.0 > 0.0) {
            return Err(Error::invalid(
                file,
                f("bounds"),
                show(&t["bounds"]),
                "both bounds > 0 for scale = \"log\"",
            ));
        }
        let range = format!("within the bounds [{:e}, {:e}]", bounds.0, bounds.1);
        let base_value = get_dotted(base, &key);
        if let Some(b) = base_value {
            if !(b >= bounds.0 && b <= bounds.1) {
                return Err(Error::invalid(
                    file,
                    f("bounds"),
                    show(&t["bounds"]),
                    format!("must contain the base scenario's value {key} = {b:e}"),
                ));
            }
        }
        let initial = match t.get("initial") {
            Some(v) => match number(v) {
                Some(x) if x >= bounds.0 && x <= bounds.1 => x,
                _ => return Err(Error::invalid(file, f("initial"), show(v), range)),
            },
            None => match base_value {
                Some(b) => b,
                None => match scale {
                    Scale::Log => (bounds.0 * bounds.1).sqrt(),
                    Scale::Linear => 0.5 * (bounds.0 + bounds.1),
                },
            },
        };
        let also = match t.get("also") {
            None => vec![],
            Some(toml::Value::Array(a)) => a
                .iter()
                .map(|x| match x {
                    toml::Value::String(s) if s.split('.').all(|p| !p.is_empty()) => Ok(s.clone()),
                    _ => Err(Error::invalid(
                        file,
                        f("also"),
                        show(x),
                        "dotted scenario keys set to the same value",
                    )),
                })
                .collect::<Result<_>>()?,
            Some(v) => {
                return Err(Error::invalid(
                    file,
                    f("also"),
                    show(v),
                    "a list of dotted scenario keys set to the same value",
                ))
            }
        };
        out.push(Parameter {
            key,
            lower: bounds.0,
            upper: bounds.1,
            scale,
            initial,
            also,
        });
    }
    Ok(out)
}

fn parse_design(v: Option<&toml::Value>, file: &str) -> Result<Option<DesignSpec>> {
    let Some(v) = v else { return Ok(None) };
    let toml::Value::Table(t) = v else {
        return Err(Error::invalid(file, "design", show(v), "a table"));
    };
    let nums = |name: &str, v: &toml::Value| -> Result<Vec<f64>> {
        match v {
            toml::Value::Array(a) if !a.is_empty() => a
                .iter()
                .map(|x| {
                    number(x).filter(|x| x.is_finite()).ok_or_else(|| {
                        Error::invalid(file, format!("design.{name}"), show(v), "finite numbers")
                    })
                })
                .collect(),
            _ => Err(Error::invalid(
                file,
                format!("design.{name}"),
                show(v),
                "a non-empty list of numbers",
            )),
        }
    };
    let mut d = DesignSpec {
        key: "incident.frequency".into(),
        values: vec![],
        control_values: None,
    };
    for (k, v) in t {
        match k.as_str() {
            "key" => match v {
                toml::Value::String(s) if s.contains('.') => d.key = s.clone(),
                _ => {
                    return Err(Error::invalid(
                        file,
                        "design.key",
                        show(v),
                        "a dotted scenario key such as `incident.frequency`",
                    ))
                }
            },
            "values" | "frequencies" => d.values = nums(k, v)?,
            "control" => d.control_values = Some(nums(k, v)?),
            "control_linspace" => {
                let a = nums(k, v)?;
                if a.len() != 3 || !(a[2] >= 2.0 && a[2].fract() == 0.0 && a[2] <= 1e5) {
                    return Err(Error::invalid(
                        file,
                        "design.control_linspace",
                        show(v),
                        "[start, end, n] with an integer n >= 2",
                    ));
                }
                d.control_values = Some(crate::study::linspace(a[0], a[1], a[2] as usize));
            }
            _ => {
                return Err(Error::invalid(
                    file,
                    format!("design.{k}"),
                    show(v),
                    "unknown key; [design] has key, values (or frequencies), control, \
                     control_linspace",
                ))
            }
        }
    }
    if d.values.is_empty() {
        return Err(Error::invalid(
            file,
            "design.values",
            "(missing)",
            "required: the candidate values of design.key",
        ));
    }
    Ok(Some(d))
}

/// Raw columns: (header, columns of numbers as text-parsed f64), from a CSV file or an
/// inline table.
fn parse_data(
    table: &toml::Table,
    dir: &Path,
    file: &str,
    fit: &FitOptions,
) -> Result<(Measured, Option<PathBuf>)> {
    let (header, rows, data_name, data_file) = match table.get("data") {
        Some(toml::Value::String(s)) if !s.trim().is_empty() => {
            let p = dir.join(s);
            let name = p.display().to_string();
            let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
            let (h, r) = read_csv(&text, &name)?;
            (h, r, name, Some(p))
        }
        Some(toml::Value::Table(t)) => {
            let mut header = Vec::new();
            let mut cols: Vec<Vec<f64>> = Vec::new();
            for (k, v) in t {
                let toml::Value::Array(a) = v else {
                    return Err(Error::invalid(
                        file,
                        format!("data.{k}"),
                        show(v),
                        "a list of numbers",
                    ));
                };
                let col = a
                    .iter()
                    .map(|x| {
                        number(x).ok_or_else(|| {
                            Error::invalid(file, format!("data.{k}"), show(x), "a number")
                        })
                    })
                    .collect::<Result<Vec<f64>>>()?;
                header.push(k.clone());
                cols.push(col);
            }
            let n = cols.first().map(Vec::len).unwrap_or(0);
            if let Some((k, c)) = header.iter().zip(&cols).find(|(_, c)| c.len() != n) {
                return Err(Error::invalid(
                    file,
                    format!("data.{k}"),
                    c.len(),
                    format!("every column as long as the first ({n} values)"),
                ));
            }
            let rows = (0..n)
                .map(|i| cols.iter().map(|c| c[i]).collect())
                .collect();
            (header, rows, file.to_string(), None)
        }
        other => {
            return Err(Error::invalid(
                file,
                "data",
                other.map(show).unwrap_or_else(|| "(missing)".into()),
                "required: the measured CSV file (relative to this file) or an inline table \
                 of columns",
            ))
        }
    };
    let observed_filter: Option<Vec<String>> = match table.get("observed") {
        None => None,
        Some(toml::Value::Array(a)) if !a.is_empty() => Some(
            a.iter()
                .map(|x| match x {
                    toml::Value::String(s) => Ok(s.clone()),
                    _ => Err(Error::invalid(file, "observed", show(x), "column names")),
                })
                .collect::<Result<_>>()?,
        ),
        Some(v) => {
            return Err(Error::invalid(
                file,
                "observed",
                show(v),
                "a non-empty list of observed column names",
            ))
        }
    };
    let mut conditions = Vec::new();
    let mut cond_cols = Vec::new();
    let mut obs_cols = Vec::new();
    for (c, h) in header.iter().enumerate() {
        if h.contains('.') {
            conditions.push(h.clone());
            cond_cols.push(c);
        } else if h.starts_with("sigma_") {
            // paired below
        } else {
            if observable(h).is_none() {
                return Err(Error::invalid(
                    &data_name,
                    "header",
                    h,
                    "dotted scenario keys (conditions), summary keys such as A2_over_A1 or \
                     first_mode_hz (observed), sigma_<observed> (uncertainties)",
                ));
            }
            if observed_filter.as_ref().map_or(true, |f| f.contains(h)) {
                obs_cols.push(c);
            }
        }
    }
    if let Some(f) = &observed_filter {
        for name in f {
            if !header.contains(name) {
                return Err(Error::invalid(
                    file,
                    "observed",
                    name,
                    format!("a column of the measured data: {}", header.join(", ")),
                ));
            }
        }
    }
    if conditions.is_empty() {
        return Err(Error::invalid(
            &data_name,
            "header",
            header.join(","),
            "a control-variable column named by its dotted scenario key, e.g. incident.xi",
        ));
    }
    if obs_cols.is_empty() {
        return Err(Error::invalid(
            &data_name,
            "header",
            header.join(","),
            "at least one observed column (a summary key such as A2_over_A1)",
        ));
    }
    for h in &header {
        if let Some(name) = h.strip_prefix("sigma_") {
            if !header.iter().any(|x| x == name) {
                return Err(Error::invalid(
                    &data_name,
                    "header",
                    h,
                    "sigma_<name> needs an observed column <name>",
                ));
            }
        }
    }
    for (i, row) in rows.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            if !v.is_finite() {
                return Err(Error::invalid(
                    &data_name,
                    format!("row {} {}", i + 1, header[c]),
                    v,
                    "a finite number",
                ));
            }
            let h = &header[c];
            let nonneg = observable(h).unwrap_or(false);
            if h.starts_with("sigma_") && !(*v > 0.0) {
                return Err(Error::invalid(
                    &data_name,
                    format!("row {} {h}", i + 1),
                    v,
                    "an uncertainty > 0",
                ));
            }
            if !h.contains('.') && !h.starts_with("sigma_") && nonneg && *v < 0.0 {
                return Err(Error::invalid(
                    &data_name,
                    format!("row {} {h}", i + 1),
                    v,
                    "an amplitude or frequency >= 0",
                ));
            }
        }
    }
    let observed: Vec<Observed> = obs_cols
        .iter()
        .map(|&c| {
            let key = header[c].clone();
            let values: Vec<f64> = rows.iter().map(|r| r[c]).collect();
            let sc = header.iter().position(|h| *h == format!("sigma_{key}"));
            let sigma = match sc {
                Some(s) => rows.iter().map(|r| r[s]).collect(),
                None => values
                    .iter()
                    .map(|y| fit.relative_noise * y.abs() + fit.absolute_noise)
                    .collect(),
            };
            Observed { key, values, sigma }
        })
        .collect();
    for o in &observed {
        if let Some(i) = o.sigma.iter().position(|s| !(*s > 0.0)) {
            return Err(Error::invalid(
                &data_name,
                format!("row {} {}", i + 1, o.key),
                o.values[i],
                "a nonzero value, or a sigma_ column, or fit.absolute_noise > 0 (the \
                 uncertainty would be 0)",
            ));
        }
    }
    let crow = rows
        .iter()
        .map(|r| cond_cols.iter().map(|&c| r[c]).collect())
        .collect();
    Ok((
        Measured {
            conditions,
            rows: crow,
            observed,
        },
        data_file,
    ))
}

/// Parse CSV text (header line, `#` comments) into header and numeric rows; a cell that
/// is not a number is an error naming the row and column (`NaN` parses, and is refused by
/// the caller).
fn read_csv(text: &str, name: &str) -> Result<(Vec<String>, Vec<Vec<f64>>)> {
    let mut rdr = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| Error::invalid(name, "header", "?", format!("CSV error: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut rows = Vec::new();
    for (i, rec) in rdr.records().enumerate() {
        let rec = rec.map_err(|e| {
            Error::invalid(
                name,
                format!("row {}", i + 1),
                "?",
                format!("CSV error: {e}"),
            )
        })?;
        if rec.len() != header.len() {
            return Err(Error::invalid(
                name,
                format!("row {}", i + 1),
                rec.len(),
                format!("{} cells, as the header", header.len()),
            ));
        }
        let row = rec
            .iter()
            .enumerate()
            .map(|(c, v)| {
                v.parse::<f64>().map_err(|_| {
                    Error::invalid(name, format!("row {} {}", i + 1, header[c]), v, "a number")
                })
            })
            .collect::<Result<Vec<f64>>>()?;
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(Error::invalid(name, "rows", 0, "at least one data row"));
    }
    Ok((header, rows))
}

/// The forward model of an identification: scenario of row `i` at parameter values `p`,
/// and the weighted residuals. Counts its forward runs.
pub struct Model<'a> {
    /// The spec.
    pub spec: &'a IdentifySpec,
    runs: AtomicUsize,
}

impl<'a> Model<'a> {
    /// A model over a spec.
    pub fn new(spec: &'a IdentifySpec) -> Self {
        Model {
            spec,
            runs: AtomicUsize::new(0),
        }
    }

    /// Forward runs so far.
    pub fn forward_runs(&self) -> usize {
        self.runs.load(Ordering::Relaxed)
    }

    /// Scaled coordinates -> parameter values (clamped into the bounds).
    pub fn values(&self, z: &[f64]) -> Vec<f64> {
        self.spec
            .parameters
            .iter()
            .zip(z)
            .map(|(p, &z)| p.from_scaled(z).clamp(p.lower, p.upper))
            .collect()
    }

    /// The table of row `i` with `conditions` overridden by `extra` (key, value) pairs.
    fn table(&self, i: usize, values: &[f64], extra: &[(String, f64)]) -> Result<toml::Table> {
        let spec = self.spec;
        let mut t = spec.base_table.clone();
        let m = &spec.measured;
        for (k, c) in m.conditions.iter().enumerate() {
            let v = extra
                .iter()
                .find(|(e, _)| e == c)
                .map(|e| e.1)
                .unwrap_or(m.rows[i][k]);
            set_dotted(&mut t, c, toml_number(c, v)).map_err(|e| e.in_file(&self.data_name()))?;
        }
        for (e, v) in extra {
            if !m.conditions.contains(e) {
                set_dotted(&mut t, e, toml_number(e, *v))?;
            }
        }
        for (p, &v) in spec.parameters.iter().zip(values) {
            for key in std::iter::once(&p.key).chain(&p.also) {
                set_dotted(&mut t, key, toml_number(key, v))?;
            }
        }
        Ok(t)
    }

    fn data_name(&self) -> String {
        self.spec
            .data_file
            .as_ref()
            .unwrap_or(&self.spec.file)
            .display()
            .to_string()
    }

    /// The validated scenario of row `i` at parameter values `values`.
    pub fn scenario(&self, i: usize, values: &[f64]) -> Result<AnyScenario> {
        let t = self.table(i, values, &[])?;
        AnyScenario::from_table(t, &self.spec.base).map_err(|e| match e {
            Error::Invalid {
                field,
                value,
                allowed,
                ..
            } => Error::invalid(
                self.data_name(),
                format!("row {} -> {field}", i + 1),
                value,
                allowed,
            ),
            other => other,
        })
    }

    /// Run row `i` with overrides `extra` and parameter `values`.
    pub fn run_with(&self, i: usize, values: &[f64], extra: &[(String, f64)]) -> Result<Summary> {
        let t = self.table(i, values, extra)?;
        let s = AnyScenario::from_table(t, &self.spec.base)?;
        self.runs.fetch_add(1, Ordering::Relaxed);
        s.summary()
    }

    /// Model values `[row][observed]` at scaled coordinates `z`, for the given rows
    /// (forward runs in parallel).
    pub fn curves_at(&self, z: &[f64], rows: &[usize]) -> Result<Vec<Vec<f64>>> {
        let values = self.values(z);
        rows.par_iter()
            .map(|&i| {
                let s = self.run_with(i, &values, &[])?;
                Ok(self
                    .spec
                    .measured
                    .observed
                    .iter()
                    .map(|o| s.get(&o.key).unwrap_or(f64::NAN))
                    .collect())
            })
            .collect()
    }

    /// Model values for every row.
    pub fn curves(&self, z: &[f64]) -> Result<Vec<Vec<f64>>> {
        let rows: Vec<usize> = (0..self.spec.measured.len()).collect();
        self.curves_at(z, &rows)
    }

    /// Weighted residuals `(model - y) / sigma`, row-major over `rows` x observed.
    pub fn residuals_at(&self, z: &[f64], rows: &[usize]) -> Result<Vec<f64>> {
        let c = self.curves_at(z, rows)?;
        Ok(self.weigh(&c, rows))
    }

    /// Weighted residuals of model values `c` (`[row][observed]`, rows as listed).
    pub fn weigh(&self, c: &[Vec<f64>], rows: &[usize]) -> Vec<f64> {
        let obs = &self.spec.measured.observed;
        let mut r = Vec::with_capacity(rows.len() * obs.len());
        for (ci, &i) in c.iter().zip(rows) {
            for (k, o) in obs.iter().enumerate() {
                r.push((ci[k] - o.values[i]) / o.sigma[i]);
            }
        }
        r
    }

    /// Weighted residuals over every row.
    pub fn residuals(&self, z: &[f64]) -> Result<Vec<f64>> {
        let rows: Vec<usize> = (0..self.spec.measured.len()).collect();
        self.residuals_at(z, &rows)
    }
}

/// Run a whole identification: estimate, identifiability (Jacobian SVD, linearised and
/// bootstrap intervals, verdicts). `progress` receives one-line messages.
pub fn identify(spec: &IdentifySpec, progress: &(dyn Fn(&str) + Sync)) -> Result<Identification> {
    let t0 = std::time::Instant::now();
    let model = Model::new(spec);
    let est = estimate(&model, progress)?;
    progress(&format!(
        "estimate: cost {:.6e} after {} forward runs",
        est.cost,
        model.forward_runs()
    ));
    let ident = identifiability::analyse(&model, &est, progress)?;
    let fitted = model.curves(&est.z)?;
    Ok(Identification {
        parameters: spec.parameters.clone(),
        estimate: est,
        identifiability: ident,
        measured: spec.measured.clone(),
        fitted,
        forward_runs: model.forward_runs(),
        wall_seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Synthetic data: the spec's rows simulated with the parameters at `truth` (key, value;
/// keys not given stay at their starting values), each observed value multiplied by
/// `1 + noise g` with `g` standard normal (seeded), uncertainties reset to
/// `fit.relative_noise |y| + fit.absolute_noise`. Returns the spec with these data.
pub fn synthesize(
    spec: &IdentifySpec,
    truth: &[(String, f64)],
    noise: f64,
    seed: u64,
) -> Result<IdentifySpec> {
    use rand::{Rng, SeedableRng};
    let file = spec.file.display().to_string();
    for (k, _) in truth {
        if !spec.parameters.iter().any(|p| &p.key == k) {
            return Err(Error::invalid(
                &file,
                "synthesize",
                k,
                "a key of one of the file's [[parameter]] tables",
            ));
        }
    }
    if !(noise >= 0.0 && noise.is_finite()) {
        return Err(Error::invalid(&file, "noise", noise, "finite, >= 0"));
    }
    let values: Vec<f64> = spec
        .parameters
        .iter()
        .map(|p| {
            truth
                .iter()
                .find(|(k, _)| k == &p.key)
                .map_or(p.initial, |t| t.1)
        })
        .collect();
    let model = Model::new(spec);
    let z: Vec<f64> = spec
        .parameters
        .iter()
        .zip(&values)
        .map(|(p, &v)| p.to_scaled(v))
        .collect();
    let curves = model.curves(&z)?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut gauss = || {
        // Box-Muller
        let u1: f64 = rng.random_range(f64::MIN_POSITIVE..1.0);
        let u2: f64 = rng.random_range(0.0..1.0);
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    };
    let mut out = spec.clone();
    for (k, o) in out.measured.observed.iter_mut().enumerate() {
        for (i, c) in curves.iter().enumerate() {
            let y = c[k] * (1.0 + noise * gauss());
            o.values[i] = y;
            o.sigma[i] = spec.fit.relative_noise * y.abs() + spec.fit.absolute_noise;
        }
    }
    Ok(out)
}

impl Measured {
    /// CSV text of the data: conditions, then observed columns (`# comment` lines first).
    pub fn to_csv(&self, comment: &str) -> String {
        let mut s = String::new();
        for line in comment.lines() {
            s.push_str(&format!("# {line}\n"));
        }
        let mut h = self.conditions.clone();
        h.extend(self.observed.iter().map(|o| o.key.clone()));
        s.push_str(&h.join(","));
        s.push('\n');
        for (i, r) in self.rows.iter().enumerate() {
            let mut cells: Vec<String> = r.iter().map(|v| v.to_string()).collect();
            cells.extend(self.observed.iter().map(|o| o.values[i].to_string()));
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }
}

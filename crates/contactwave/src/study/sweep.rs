//! Sweep files, their grid, and the resumable `sweep.csv`.
//!
//! # Sweep file (TOML)
//!
//! ```toml
//! base = "unilateral.toml"          # base scenario, relative to this file
//!
//! [[axis]]                          # first axis: varies slowest
//! parameter = "incident.xi"         # any dotted scenario key holding a number
//! linspace = [0.05, 1.2, 47]        # start, end, number of points (>= 1)
//!
//! [[axis]]
//! parameter = "interface.traction.stiffness"
//! logspace = [9, 16, 8]             # exponents of 10: 1e9 ... 1e16, 8 points
//! # or: values = [1e9, 1e12, 1e15]
//! ```
//!
//! Several axes form a grid (cartesian product, first axis slowest, last fastest). Axis
//! indices in error messages are 0-based (`axis[0]` is the first `[[axis]]` table). Values
//! are written into the base scenario with [`crate::scenario::set_dotted`] (so sweeping
//! `incident.xi` removes the base's `incident.amplitude` and vice versa), and every point is
//! validated as a [`Scenario`] before anything runs. Units are those of the swept key
//! (SI: Pa, Pa/m, Hz, J/m^2, ...).
//!
//! # Output
//!
//! `sweep.csv`: a header line, then one row per finished point in order of completion:
//! `point` (0-based grid index; sort by it to get grid order), one column per axis named by
//! its dotted key, then the keys of [`crate::analysis::Summary`] in their order. Numbers are
//! written so that they parse back to the same `f64` (`NaN`, `inf` for non-finite values).
//! Each row is written with one `write` call as soon as its point finishes, so an
//! interrupted sweep loses no finished row.
//!
//! `sweep.csv.hash` (side file, one line): the SHA-256, in hex, of a canonical
//! serialisation of the contactwave version, the base scenario table, the axes and the
//! grid ([`Sweep::hash`]). A resumed sweep appends to a CSV only when its hash matches.
//! The hash lives in a side file rather than a comment line so that `sweep.csv` stays a
//! plain CSV for every reader.
//!
//! `sweep_errors.csv` (`<stem>_errors.csv` beside the CSV; only when a point failed):
//! `point,message` for each point whose simulation failed (numerical failure). Failed
//! points have no row in `sweep.csv`, so `--resume` retries them; the errors file is
//! rewritten by every run.

use super::shard::Shard;
use crate::analysis::Summary;
use crate::error::{Error, Result};
use crate::scenario::{apply_set, parse_toml, set_dotted, AnyScenario, Scenario};
use sha2::{Digest, Sha256};
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// Largest number of points of one axis.
const MAX_AXIS_POINTS: usize = 1_000_000;
/// Largest number of grid points of a sweep.
const MAX_GRID_POINTS: usize = 10_000_000;
/// Version tag of the canonical serialisation behind [`Sweep::hash`].
const HASH_FORMAT: &str = "contactwave-sweep-hash-1";

/// How an axis gives its values.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisSpec {
    /// Explicit values (`values = [..]`).
    Values(Vec<f64>),
    /// `n` evenly spaced values from `start` to `end` inclusive (`linspace = [a, b, n]`).
    Linspace {
        /// First value.
        start: f64,
        /// Last value.
        end: f64,
        /// Number of values (>= 1; 1 gives `[start]`).
        n: usize,
    },
    /// `n` values `10^e` with `e` evenly spaced from `start_exponent` to `end_exponent`
    /// inclusive (`logspace = [a, b, n]`).
    Logspace {
        /// Exponent of the first value.
        start_exponent: f64,
        /// Exponent of the last value.
        end_exponent: f64,
        /// Number of values (>= 1).
        n: usize,
    },
}

impl AxisSpec {
    /// The values this spec stands for.
    pub fn values(&self) -> Vec<f64> {
        match self {
            AxisSpec::Values(v) => v.clone(),
            AxisSpec::Linspace { start, end, n } => linspace(*start, *end, *n),
            AxisSpec::Logspace {
                start_exponent,
                end_exponent,
                n,
            } => logspace(*start_exponent, *end_exponent, *n),
        }
    }
}

/// One axis of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Dotted scenario key, e.g. `incident.xi` (the CSV column name).
    pub parameter: String,
    /// How the file gave the values.
    pub spec: AxisSpec,
    /// The values, in the units of the swept key.
    pub values: Vec<f64>,
}

/// A loaded sweep: base scenario, axes and the grid they span.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The sweep file.
    pub file: PathBuf,
    /// The base scenario file (resolved against the sweep file's folder).
    pub base: PathBuf,
    /// The base scenario as parsed (before any axis value is written into it).
    pub base_table: toml::Table,
    /// The axes, in file order (first varies slowest).
    pub axes: Vec<Axis>,
    /// The grid: `points[i][k]` is the value of axis `k` at point `i`.
    pub points: Vec<Vec<f64>>,
    /// SHA-256 (hex) of the resolved sweep: contactwave version, base table, axes, grid.
    pub hash: String,
}

/// Options of [`run_sweep`].
#[derive(Debug, Clone, Copy, Default)]
pub struct SweepOptions {
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// Append to an existing CSV of the same sweep, skipping its points.
    pub resume: bool,
}

/// What a finished [`run_sweep`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport {
    /// Grid points of the sweep.
    pub total: usize,
    /// Points found in the CSV already (resume) and not run again.
    pub skipped: usize,
    /// Points run now that produced a row.
    pub computed: usize,
    /// Points run now whose simulation failed (listed in the errors file).
    pub failed: usize,
    /// The CSV written.
    pub csv: PathBuf,
    /// The errors file, if any point failed.
    pub errors_csv: Option<PathBuf>,
}

/// A `sweep.csv` read back: header and numeric rows (in file order).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows; every row has `header.len()` values.
    pub rows: Vec<Vec<f64>>,
}

impl SweepTable {
    /// Index of a column.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }
}

/// `n` evenly spaced values from `a` to `b` inclusive (`[a]` for `n = 1`, empty for 0).
/// The end points are exact.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![a],
        _ => (0..n)
            .map(|i| {
                if i == n - 1 {
                    b
                } else {
                    a + (b - a) * i as f64 / (n - 1) as f64
                }
            })
            .collect(),
    }
}

/// `n` values `10^e`, `e` evenly spaced from `a` to `b` inclusive. Integer exponents give
/// exact powers of ten (`logspace(9, 16, 8)` is exactly `1e9, 1e10, ..., 1e16`).
pub fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    linspace(a, b, n)
        .into_iter()
        .map(|e| {
            if e.fract() == 0.0 && e.abs() <= 308.0 {
                // exact decimal power of ten (powi accumulates rounding errors)
                format!("1e{}", e as i64).parse().unwrap_or(10f64.powf(e))
            } else {
                10f64.powf(e)
            }
        })
        .collect()
}

/// Cartesian product of axis values, first axis slowest: `grid(&[[1,2],[a,b]])` is
/// `[1,a], [1,b], [2,a], [2,b]`. No axes give one empty point.
pub fn grid(axes: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut points: Vec<Vec<f64>> = vec![vec![]];
    for values in axes {
        let mut next = Vec::with_capacity(points.len() * values.len());
        for p in &points {
            for &v in values {
                let mut q = p.clone();
                q.push(v);
                next.push(q);
            }
        }
        points = next;
    }
    points
}

/// A number of a sweep file (integer or float).
fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// A count of a sweep file: an integer >= 1 (an integral float is accepted too).
fn count(v: &toml::Value) -> Option<usize> {
    let x = number(v)?;
    (x.is_finite() && x.fract() == 0.0 && x >= 1.0 && x <= MAX_AXIS_POINTS as f64)
        .then_some(x as usize)
}

fn show(v: &toml::Value) -> String {
    v.to_string()
}

impl Sweep {
    /// Load a sweep file and its base scenario, and build the grid. Errors name the sweep
    /// file and the field (`axis[1].linspace`, ...). The points are validated as scenarios
    /// by [`Sweep::scenarios`].
    pub fn load(path: &Path) -> Result<Sweep> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let file = path.display().to_string();
        let table = parse_toml(&text, &file)?;
        Sweep::from_table(table, path)
    }

    /// Build a sweep from a parsed sweep table that came from `path`.
    pub fn from_table(table: toml::Table, path: &Path) -> Result<Sweep> {
        let file = path.display().to_string();
        for key in table.keys() {
            if key != "base" && key != "axis" && key != "set" {
                return Err(Error::invalid(
                    &file,
                    key,
                    show(&table[key]),
                    "unknown key; a sweep file has `base` (the base scenario file), an \
                     optional `[set]` table of fixed overrides and `[[axis]]` tables",
                ));
            }
        }
        let base_rel = match table.get("base") {
            Some(toml::Value::String(s)) if !s.trim().is_empty() => s.clone(),
            Some(v) => {
                return Err(Error::invalid(
                    &file,
                    "base",
                    show(v),
                    "must be the path of the base scenario file, relative to the sweep file",
                ))
            }
            None => {
                return Err(Error::invalid(
                    &file,
                    "base",
                    "(missing)",
                    "required: the path of the base scenario file, relative to the sweep file",
                ))
            }
        };
        let axis_tables = match table.get("axis") {
            Some(toml::Value::Array(a)) if !a.is_empty() => a,
            Some(v) => {
                return Err(Error::invalid(
                    &file,
                    "axis",
                    show(v),
                    "must be one or more `[[axis]]` tables",
                ))
            }
            None => {
                return Err(Error::invalid(
                    &file,
                    "axis",
                    "(missing)",
                    "required: one or more `[[axis]]` tables",
                ))
            }
        };
        let mut axes: Vec<Axis> = Vec::with_capacity(axis_tables.len());
        for (i, a) in axis_tables.iter().enumerate() {
            let axis = parse_axis(a, i, &file)?;
            if axes.iter().any(|b| b.parameter == axis.parameter) {
                return Err(Error::invalid(
                    &file,
                    format!("axis[{i}].parameter"),
                    format!("\"{}\"", axis.parameter),
                    "is swept by an earlier axis already",
                ));
            }
            axes.push(axis);
        }
        check_axes(&file, &axes)?;
        let base = path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default()
            .join(&base_rel);
        let base_text = std::fs::read_to_string(&base).map_err(|e| Error::io(&base, e))?;
        let mut base_table = parse_toml(&base_text, &base.display().to_string())?;
        // `[set]`: fixed overrides of the base (any TOML value, e.g. another contact law),
        // written before the axes; `interface.0.compression` indexes an array of tables
        match table.get("set") {
            None => {}
            Some(toml::Value::Table(set)) => apply_set(&mut base_table, set, &file)?,
            Some(v) => {
                return Err(Error::invalid(
                    &file,
                    "set",
                    show(v),
                    "must be a table of dotted scenario keys and values",
                ))
            }
        }
        Ok(Sweep::assemble(path, base, base_table, axes))
    }

    /// Build a sweep in code (the Python bindings' `sweep`): a base scenario table that came
    /// from (or stands for) `base`, and `(dotted key, values)` axes, first axis slowest.
    /// `file` names the sweep in error messages and [`Sweep::file`]. The axes are checked
    /// like a sweep file's `values` axes; the grid and the hash are built the same way, so a
    /// sweep file with the same base table and values has the same [`Sweep::hash`].
    pub fn from_parts(
        file: &Path,
        base: PathBuf,
        base_table: toml::Table,
        axes: Vec<(String, Vec<f64>)>,
    ) -> Result<Sweep> {
        let name = file.display().to_string();
        if axes.is_empty() {
            return Err(Error::invalid(
                &name,
                "axis",
                "(none)",
                "required: one or more axes (dotted key -> values)",
            ));
        }
        let mut out: Vec<Axis> = Vec::with_capacity(axes.len());
        for (i, (parameter, values)) in axes.into_iter().enumerate() {
            if parameter.is_empty() || parameter.split('.').any(|p| p.trim().is_empty()) {
                return Err(Error::invalid(
                    &name,
                    format!("axis[{i}].parameter"),
                    format!("\"{parameter}\""),
                    "must be a dotted scenario key such as \"incident.xi\"",
                ));
            }
            let field = format!("axis[{i}].values");
            if values.is_empty() || values.len() > MAX_AXIS_POINTS {
                return Err(Error::invalid(
                    &name,
                    field,
                    format!("({} values)", values.len()),
                    format!("must hold 1 to {MAX_AXIS_POINTS} numbers"),
                ));
            }
            if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    &name,
                    field,
                    fmt_f64(*v),
                    "every value must be a finite number",
                ));
            }
            if out.iter().any(|b| b.parameter == parameter) {
                return Err(Error::invalid(
                    &name,
                    format!("axis[{i}].parameter"),
                    format!("\"{parameter}\""),
                    "is swept by an earlier axis already",
                ));
            }
            out.push(Axis {
                parameter,
                spec: AxisSpec::Values(values.clone()),
                values,
            });
        }
        check_axes(&name, &out)?;
        Ok(Sweep::assemble(file, base, base_table, out))
    }

    fn assemble(file: &Path, base: PathBuf, base_table: toml::Table, axes: Vec<Axis>) -> Sweep {
        let values: Vec<Vec<f64>> = axes.iter().map(|a| a.values.clone()).collect();
        let points = grid(&values);
        let hash = hash_sweep(&base_table, &axes, &points);
        Sweep {
            file: file.to_path_buf(),
            base,
            base_table,
            axes,
            points,
            hash,
        }
    }

    /// Column names of the swept parameters (the axes' dotted keys).
    pub fn parameters(&self) -> Vec<&str> {
        self.axes.iter().map(|a| a.parameter.as_str()).collect()
    }

    /// The scenario table of grid point `i` (base table with the point's values written in).
    pub fn point_table(&self, i: usize) -> Result<toml::Table> {
        let params = self.parameters();
        point_table(
            &self.base_table,
            &params,
            &self.points[i],
            &self.file.display().to_string(),
        )
    }

    /// Validate every grid point and return the scenarios, in grid order. The first invalid
    /// point fails with the scenario error (naming the base file and the field), followed by
    /// the sweep file, the point index and its values.
    pub fn scenarios(&self) -> Result<Vec<Scenario>> {
        self.runnable()?
            .into_iter()
            .map(|s| match s {
                AnyScenario::HalfSpace(s) => Ok(*s),
                AnyScenario::BarStack(_) => Err(Error::invalid(
                    self.base.display().to_string(),
                    "model.kind",
                    "bar_stack",
                    "this call needs half-space scenarios",
                )),
            })
            .collect()
    }

    /// Validate every grid point (half-space or bar-stack scenarios), in grid order.
    pub fn runnable(&self) -> Result<Vec<AnyScenario>> {
        (0..self.points.len())
            .map(|i| {
                let table = self.point_table(i)?;
                AnyScenario::from_table(table, &self.base).map_err(|e| {
                    let values = self
                        .axes
                        .iter()
                        .zip(&self.points[i])
                        .map(|(a, v)| format!("{} = {}", a.parameter, fmt_f64(*v)))
                        .collect::<Vec<_>>()
                        .join(", ");
                    with_context(
                        e,
                        &format!("in sweep {} at point {i}: {values}", self.file.display()),
                    )
                })
            })
            .collect()
    }

    /// CSV header: `point`, the parameters, then the summary keys.
    pub fn header<'a>(&'a self, summary_keys: impl Iterator<Item = &'a str>) -> Vec<String> {
        std::iter::once("point")
            .chain(self.parameters())
            .chain(summary_keys)
            .map(str::to_string)
            .collect()
    }
}

/// A base scenario table with `values[k]` written at the dotted key `parameters[k]`
/// (what a sweep does at each grid point, [`Sweep::point_table`]). Errors from a bad key
/// name `file` and the field `axis[k].parameter`.
pub fn point_table(
    base_table: &toml::Table,
    parameters: &[&str],
    values: &[f64],
    file: &str,
) -> Result<toml::Table> {
    let mut table = base_table.clone();
    for (k, (parameter, &v)) in parameters.iter().zip(values).enumerate() {
        let value = if wants_integer(parameter) && v.fract() == 0.0 {
            toml::Value::Integer(v as i64)
        } else {
            toml::Value::Float(v)
        };
        set_dotted(&mut table, parameter, value).map_err(|e| match e {
            Error::Invalid { value, allowed, .. } => Error::Invalid {
                file: file.to_string(),
                field: format!("axis[{k}].parameter"),
                value,
                allowed,
            },
            other => other,
        })?;
    }
    Ok(table)
}

/// Checks that need every axis: not both `incident.xi` and `incident.amplitude`, grid size.
fn check_axes(file: &str, axes: &[Axis]) -> Result<()> {
    let has = |k: &str| axes.iter().any(|a| a.parameter == k);
    if has("incident.xi") && has("incident.amplitude") {
        return Err(Error::invalid(
            file,
            "axis",
            "incident.xi, incident.amplitude",
            "sweep `incident.xi` or `incident.amplitude`, not both (they give the same \
                 quantity)",
        ));
    }
    let total = axes
        .iter()
        .try_fold(1usize, |acc, a| acc.checked_mul(a.values.len()))
        .filter(|&n| n <= MAX_GRID_POINTS);
    if total.is_none() {
        return Err(Error::invalid(
            file,
            "axis",
            axes.iter()
                .map(|a| a.values.len().to_string())
                .collect::<Vec<_>>()
                .join(" x "),
            format!("the grid may have at most {MAX_GRID_POINTS} points"),
        ));
    }
    Ok(())
}

/// Whether the swept key is an integer in the scenario format (written as a TOML integer
/// when the value is integral; every other key takes a float).
fn wants_integer(key: &str) -> bool {
    key == "solver.samples_per_period"
}

fn parse_axis(a: &toml::Value, i: usize, file: &str) -> Result<Axis> {
    let t = match a {
        toml::Value::Table(t) => t,
        v => {
            return Err(Error::invalid(
                file,
                format!("axis[{i}]"),
                show(v),
                "must be a table (`[[axis]]`)",
            ))
        }
    };
    for key in t.keys() {
        if !["parameter", "values", "linspace", "logspace"].contains(&key.as_str()) {
            return Err(Error::invalid(
                file,
                format!("axis[{i}].{key}"),
                show(&t[key]),
                "unknown key; an axis has `parameter` and one of `values`, `linspace`, \
                 `logspace`",
            ));
        }
    }
    let parameter = match t.get("parameter") {
        Some(toml::Value::String(s))
            if !s.is_empty() && s.split('.').all(|p| !p.trim().is_empty()) =>
        {
            s.clone()
        }
        Some(v) => {
            return Err(Error::invalid(
                file,
                format!("axis[{i}].parameter"),
                show(v),
                "must be a dotted scenario key such as \"incident.xi\"",
            ))
        }
        None => {
            return Err(Error::invalid(
                file,
                format!("axis[{i}].parameter"),
                "(missing)",
                "required: a dotted scenario key such as \"incident.xi\"",
            ))
        }
    };
    let given: Vec<&str> = ["values", "linspace", "logspace"]
        .into_iter()
        .filter(|k| t.contains_key(*k))
        .collect();
    if given.len() != 1 {
        return Err(Error::invalid(
            file,
            format!("axis[{i}]"),
            if given.is_empty() {
                "(none)".to_string()
            } else {
                given.join(", ")
            },
            "give exactly one of `values = [..]`, `linspace = [start, end, n]`, \
             `logspace = [start_exponent, end_exponent, n]`",
        ));
    }
    let key = given[0];
    let field = format!("axis[{i}].{key}");
    let raw = &t[key];
    let arr = match raw {
        toml::Value::Array(arr) => arr,
        v => {
            return Err(Error::invalid(
                file,
                field,
                show(v),
                "must be an array of numbers",
            ))
        }
    };
    let spec = if key == "values" {
        if arr.is_empty() {
            return Err(Error::invalid(
                file,
                field,
                show(raw),
                "must hold at least one number",
            ));
        }
        if arr.len() > MAX_AXIS_POINTS {
            return Err(Error::invalid(
                file,
                field,
                format!("({} values)", arr.len()),
                format!("at most {MAX_AXIS_POINTS} values"),
            ));
        }
        let mut v = Vec::with_capacity(arr.len());
        for x in arr {
            match number(x) {
                Some(y) if y.is_finite() => v.push(y),
                _ => {
                    return Err(Error::invalid(
                        file,
                        field,
                        show(x),
                        "every value must be a finite number",
                    ))
                }
            }
        }
        AxisSpec::Values(v)
    } else {
        let (what, limit) = if key == "linspace" {
            ("[start, end, n]", f64::MAX)
        } else {
            ("[start_exponent, end_exponent, n] (exponents of 10)", 300.0)
        };
        if arr.len() != 3 {
            return Err(Error::invalid(
                file,
                field,
                show(raw),
                format!("must be {what} with n an integer >= 1"),
            ));
        }
        let a = number(&arr[0]).filter(|x| x.is_finite() && x.abs() <= limit);
        let b = number(&arr[1]).filter(|x| x.is_finite() && x.abs() <= limit);
        let n = count(&arr[2]);
        match (a, b, n) {
            (Some(a), Some(b), Some(n)) => {
                if key == "linspace" {
                    AxisSpec::Linspace {
                        start: a,
                        end: b,
                        n,
                    }
                } else {
                    AxisSpec::Logspace {
                        start_exponent: a,
                        end_exponent: b,
                        n,
                    }
                }
            }
            _ => {
                return Err(Error::invalid(
                    file,
                    field,
                    show(raw),
                    format!(
                    "must be {what}: finite numbers{} and n an integer in [1, {MAX_AXIS_POINTS}]",
                    if key == "logspace" {
                        " in [-300, 300]"
                    } else {
                        ""
                    }
                ),
                ))
            }
        }
    };
    let values = spec.values();
    Ok(Axis {
        parameter,
        spec,
        values,
    })
}

fn with_context(e: Error, ctx: &str) -> Error {
    match e {
        Error::Invalid {
            file,
            field,
            value,
            allowed,
        } => Error::Invalid {
            file,
            field,
            value,
            allowed: format!("{allowed} ({ctx})"),
        },
        Error::Parse { file, message } => Error::Parse {
            file,
            message: format!("{message} ({ctx})"),
        },
        other => other,
    }
}

/// Canonical text of a TOML value: tables with sorted keys, floats by their bits.
fn canonical(v: &toml::Value, out: &mut String) {
    use std::fmt::Write as _;
    match v {
        toml::Value::String(s) => {
            let _ = write!(out, "s{}:{s}", s.len());
        }
        toml::Value::Integer(i) => {
            let _ = write!(out, "i{i};");
        }
        toml::Value::Float(x) => {
            let _ = write!(out, "f{:016x};", x.to_bits());
        }
        toml::Value::Boolean(b) => {
            let _ = write!(out, "b{b};");
        }
        toml::Value::Datetime(d) => {
            let d = d.to_string();
            let _ = write!(out, "d{}:{d}", d.len());
        }
        toml::Value::Array(a) => {
            let _ = write!(out, "a{}[", a.len());
            for x in a {
                canonical(x, out);
            }
            out.push(']');
        }
        toml::Value::Table(t) => canonical_table(t, out),
    }
}

fn canonical_table(t: &toml::Table, out: &mut String) {
    use std::fmt::Write as _;
    let mut keys: Vec<&String> = t.keys().collect();
    keys.sort();
    let _ = write!(out, "t{}{{", keys.len());
    for k in keys {
        let _ = write!(out, "k{}:{k}", k.len());
        canonical(&t[k], out);
    }
    out.push('}');
}

fn hash_sweep(base: &toml::Table, axes: &[Axis], points: &[Vec<f64>]) -> String {
    let mut h = Sha256::new();
    let mut s = String::new();
    s.push_str(HASH_FORMAT);
    s.push('\n');
    s.push_str(env!("CARGO_PKG_VERSION"));
    s.push('\n');
    canonical_table(base, &mut s);
    s.push('\n');
    for a in axes {
        s.push_str(&format!("axis {}:{}", a.parameter.len(), a.parameter));
        for v in &a.values {
            s.push_str(&format!(" {:016x}", v.to_bits()));
        }
        s.push('\n');
    }
    h.update(s.as_bytes());
    let mut line = String::new();
    for p in points {
        line.clear();
        for v in p {
            line.push_str(&format!("{:016x} ", v.to_bits()));
        }
        line.push('\n');
        h.update(line.as_bytes());
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A float that parses back to itself (`NaN`, `inf`, `-inf` for non-finite values).
pub(crate) fn fmt_f64(v: f64) -> String {
    format!("{v:?}")
}

/// Path of the hash side file of a sweep CSV (`<csv>.hash`).
pub fn hash_path(csv: &Path) -> PathBuf {
    let mut s = csv.as_os_str().to_owned();
    s.push(".hash");
    PathBuf::from(s)
}

/// Path of the errors file of a sweep CSV (`<stem>_errors.csv` beside it).
pub fn errors_path(csv: &Path) -> PathBuf {
    let stem = csv
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".to_string());
    csv.with_file_name(format!("{stem}_errors.csv"))
}

/// Read a `sweep.csv` (header, then numeric rows). A last line without its newline (a
/// write cut short) is ignored.
pub fn read_sweep_csv(path: &Path) -> Result<SweepTable> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_sweep_csv(&text, path)
}

fn parse_sweep_csv(text: &str, path: &Path) -> Result<SweepTable> {
    let file = path.display().to_string();
    let complete = match text.rfind('\n') {
        Some(k) => &text[..=k],
        None => "",
    };
    let mut lines = complete.lines();
    let header: Vec<String> = match lines.next() {
        Some(h) if !h.trim().is_empty() => h.split(',').map(|s| s.trim().to_string()).collect(),
        _ => {
            return Ok(SweepTable {
                header: vec![],
                rows: vec![],
            })
        }
    };
    let mut rows = Vec::new();
    for (k, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let row: std::result::Result<Vec<f64>, _> =
            line.split(',').map(|s| s.trim().parse::<f64>()).collect();
        match row {
            Ok(r) if r.len() == header.len() => rows.push(r),
            _ => {
                return Err(Error::Parse {
                    file,
                    message: format!(
                        "line {}: expected {} numbers separated by commas",
                        k + 2,
                        header.len()
                    ),
                })
            }
        }
    }
    Ok(SweepTable { header, rows })
}

/// State shared by the workers: the open files, behind one lock.
struct Writer {
    csv: File,
    csv_path: PathBuf,
    header: Option<Vec<String>>,
    errors: Option<File>,
    errors_path: PathBuf,
    computed: usize,
    failed: usize,
}

impl Writer {
    fn row(&mut self, sweep: &Sweep, i: usize, summary: &Summary) -> Result<()> {
        if self.header.is_none() {
            let h = sweep.header(summary.keys());
            let line = format!("{}\n", h.join(","));
            self.csv
                .write_all(line.as_bytes())
                .map_err(|e| Error::io(&self.csv_path, e))?;
            self.header = Some(h);
        }
        let header = self.header.as_deref().unwrap_or(&[]);
        let n_axes = sweep.axes.len();
        let mut line = i.to_string();
        for v in &sweep.points[i] {
            line.push(',');
            line.push_str(&fmt_f64(*v));
        }
        for key in header.iter().skip(1 + n_axes) {
            line.push(',');
            line.push_str(&fmt_f64(summary.get(key).unwrap_or(f64::NAN)));
        }
        line.push('\n');
        self.csv
            .write_all(line.as_bytes())
            .and_then(|_| self.csv.flush())
            .map_err(|e| Error::io(&self.csv_path, e))?;
        self.computed += 1;
        Ok(())
    }

    fn error(&mut self, i: usize, message: &str) -> Result<()> {
        if self.errors.is_none() {
            let mut f =
                File::create(&self.errors_path).map_err(|e| Error::io(&self.errors_path, e))?;
            f.write_all(b"point,message\n")
                .map_err(|e| Error::io(&self.errors_path, e))?;
            self.errors = Some(f);
        }
        let msg = message.replace('"', "\"\"").replace(['\n', '\r'], " ");
        if let Some(f) = self.errors.as_mut() {
            f.write_all(format!("{i},\"{msg}\"\n").as_bytes())
                .and_then(|_| f.flush())
                .map_err(|e| Error::io(&self.errors_path, e))?;
        }
        self.failed += 1;
        Ok(())
    }
}

/// Run a sweep, writing `out_csv` (and its hash and errors files, see the module doc).
///
/// Every point is validated first ([`Sweep::scenarios`]); nothing is written if one is
/// invalid. Points run on a rayon pool of `opts.threads` threads (all cores by default),
/// each with [`crate::simulate_summary`]; rows are appended and flushed as points finish.
/// `progress(done, total)` is called once at the start (with the points already in a
/// resumed CSV) and after each point. `cancel` is checked before each point; once it is
/// set, the running points finish and are written, and the call returns
/// [`Error::Interrupted`].
///
/// With `opts.resume` and an existing CSV whose hash file matches [`Sweep::hash`], the
/// points already in the CSV are skipped and the others appended; a different or missing
/// hash is an error and the CSV is left untouched. Without `resume`, an existing CSV is
/// overwritten. A point whose simulation fails is listed in the errors file and counted in
/// [`SweepReport::failed`]; the sweep goes on.
pub fn run_sweep(
    sweep: &Sweep,
    out_csv: &Path,
    opts: &SweepOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<SweepReport> {
    run_sweep_shard(sweep, Shard::ALL, out_csv, opts, progress, cancel)
}

/// [`run_sweep`] restricted to one shard of the grid: only the points `i` with
/// `shard.contains(i)` (`i % N == K - 1` for shard `K/N`) run and are written. The CSV's
/// header and hash file are those of the whole sweep, the same for every shard, so shard
/// CSVs can be merged ([`crate::study::merge_sweep_csvs`]) and resumed like whole ones.
/// [`SweepReport::total`] and `progress`'s total count the shard's points.
pub fn run_sweep_shard(
    sweep: &Sweep,
    shard: Shard,
    out_csv: &Path,
    opts: &SweepOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<SweepReport> {
    let scenarios = sweep.runnable()?;
    let grid_total = scenarios.len();
    let total = (0..grid_total).filter(|&i| shard.contains(i)).count();
    let hash_file = hash_path(out_csv);
    let errors_file = errors_path(out_csv);
    let mut done = vec![false; grid_total];
    let mut header = None;
    let csv = if opts.resume && out_csv.exists() {
        let stored = std::fs::read_to_string(&hash_file).map_err(|e| {
            Error::invalid(
                out_csv.display().to_string(),
                "hash",
                "(unreadable)",
                format!(
                    "cannot resume: {} cannot be read ({e}); remove the CSV or run \
                     without --resume",
                    hash_file.display()
                ),
            )
        })?;
        let stored = stored.trim();
        if stored != sweep.hash {
            return Err(Error::invalid(
                out_csv.display().to_string(),
                "hash",
                stored,
                format!(
                    "cannot resume: the CSV was written by a different sweep (base scenario, \
                     axes or contactwave version); this sweep's hash is {}; remove the CSV \
                     or run without --resume",
                    sweep.hash
                ),
            ));
        }
        let text = std::fs::read_to_string(out_csv).map_err(|e| Error::io(out_csv, e))?;
        let table = parse_sweep_csv(&text, out_csv)?;
        if !table.header.is_empty() {
            let expected: Vec<String> = sweep.header(std::iter::empty());
            if table.header.len() < expected.len() || table.header[..expected.len()] != expected {
                return Err(Error::Parse {
                    file: out_csv.display().to_string(),
                    message: format!(
                        "cannot resume: the header does not start with `{}`",
                        expected.join(",")
                    ),
                });
            }
            for r in &table.rows {
                let p = r[0];
                if p >= 0.0 && p.fract() == 0.0 && (p as usize) < grid_total {
                    done[p as usize] = true;
                }
            }
            header = Some(table.header);
        }
        // drop a last line cut short by an interruption
        let keep = text.rfind('\n').map(|k| k + 1).unwrap_or(0);
        let f = OpenOptions::new()
            .write(true)
            .open(out_csv)
            .map_err(|e| Error::io(out_csv, e))?;
        f.set_len(keep as u64).map_err(|e| Error::io(out_csv, e))?;
        drop(f);
        OpenOptions::new()
            .append(true)
            .open(out_csv)
            .map_err(|e| Error::io(out_csv, e))?
    } else {
        std::fs::write(&hash_file, format!("{}\n", sweep.hash))
            .map_err(|e| Error::io(&hash_file, e))?;
        File::create(out_csv).map_err(|e| Error::io(out_csv, e))?
    };
    if errors_file.exists() {
        std::fs::remove_file(&errors_file).map_err(|e| Error::io(&errors_file, e))?;
    }
    let todo: Vec<usize> = (0..grid_total)
        .filter(|&i| shard.contains(i) && !done[i])
        .collect();
    let skipped = total - todo.len();
    let writer = Mutex::new(Writer {
        csv,
        csv_path: out_csv.to_path_buf(),
        header,
        errors: None,
        errors_path: errors_file.clone(),
        computed: 0,
        failed: 0,
    });
    let processed = AtomicUsize::new(skipped);
    progress(skipped, total);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
        .map_err(|e| Error::io(out_csv, std::io::Error::other(e.to_string())))?;
    use rayon::prelude::*;
    pool.install(|| {
        todo.par_iter()
            .with_max_len(1)
            .try_for_each(|&i| -> Result<()> {
                if cancel.load(Ordering::SeqCst) {
                    return Ok(());
                }
                let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    scenarios[i].summary()
                }));
                {
                    let mut w = writer.lock().unwrap_or_else(|p| p.into_inner());
                    match outcome {
                        Ok(Ok(summary)) => w.row(sweep, i, &summary)?,
                        Ok(Err(e)) => w.error(i, &e.to_string())?,
                        Err(panic) => {
                            let msg = panic
                                .downcast_ref::<&str>()
                                .map(|s| s.to_string())
                                .or_else(|| panic.downcast_ref::<String>().cloned())
                                .unwrap_or_else(|| "unknown panic".to_string());
                            w.error(i, &format!("internal error (panic): {msg}"))?
                        }
                    }
                }
                let d = processed.fetch_add(1, Ordering::SeqCst) + 1;
                progress(d, total);
                Ok(())
            })
    })?;
    let w = writer.into_inner().unwrap_or_else(|p| p.into_inner());
    let _ = w.csv.sync_data();
    if cancel.load(Ordering::SeqCst) && processed.load(Ordering::SeqCst) < total {
        return Err(Error::Interrupted);
    }
    Ok(SweepReport {
        total,
        skipped,
        computed: w.computed,
        failed: w.failed,
        csv: out_csv.to_path_buf(),
        errors_csv: (w.failed > 0).then_some(errors_file),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "contactwave-sweep-{name}-{}-{:?}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_nanos())
                .unwrap_or(0)
        ));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn set_overrides_index_arrays_of_tables_and_bad_indices_are_errors() {
        let dir = tmpdir("set");
        let tribo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tribobrake.toml");
        std::fs::copy(&tribo, dir.join("base.toml")).unwrap();
        let good = "base = \"base.toml\"\n[set]\n\"interface.1.compression\" = \
                    { law = \"power\", c = 1.81e10, m = 0.35 }\n\
                    [[axis]]\nparameter = \"excitation.peak\"\nvalues = [9.0, 32.0]\n";
        std::fs::write(dir.join("good.toml"), good).unwrap();
        let sw = Sweep::load(&dir.join("good.toml")).unwrap();
        let t = sw.point_table(1).unwrap();
        let law = |i: usize| {
            t["interface"].as_array().unwrap()[i]["compression"]["law"]
                .as_str()
                .unwrap()
                .to_string()
        };
        assert_eq!(law(0), "modified_power");
        assert_eq!(law(1), "power");
        assert_eq!(t["excitation"]["peak"].as_float(), Some(32.0));
        match &sw.runnable().unwrap()[0] {
            AnyScenario::BarStack(_) => {}
            AnyScenario::HalfSpace(_) => panic!("a bar stack was expected"),
        }
        // an index past the end names the [set] key
        let bad = good.replace("interface.1.", "interface.2.");
        std::fs::write(dir.join("bad.toml"), bad).unwrap();
        match Sweep::load(&dir.join("bad.toml")) {
            Err(Error::Invalid { field, allowed, .. }) => {
                assert!(field.contains("interface.2.compression"), "{field}");
                assert!(allowed.contains("0..2"), "{allowed}");
            }
            other => panic!("expected an invalid-field error, got {other:?}"),
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    const BASE: &str = r#"
[medium]
material = "pmma"
[interface]
static_pressure = 0.1e6
[incident]
frequency = 1e6
cycles = 3
amplitude = 0.2e6
[solver]
samples_per_period = 32
tail_periods = 5
"#;

    fn setup(name: &str, sweep: &str) -> (PathBuf, PathBuf) {
        let d = tmpdir(name);
        std::fs::write(d.join("base.toml"), BASE).unwrap();
        let s = d.join("sweep.toml");
        std::fs::write(&s, sweep).unwrap();
        (d, s)
    }

    #[test]
    fn linspace_and_logspace_endpoints() {
        let v = linspace(0.05, 1.2, 47);
        assert_eq!(v.len(), 47);
        assert_eq!(v[0], 0.05);
        assert_eq!(v[46], 1.2);
        assert_eq!(linspace(2.0, 3.0, 1), vec![2.0]);
        let l = logspace(9.0, 16.0, 8);
        assert_eq!(l, vec![1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16]);
        let l = logspace(0.0, 1.0, 3);
        assert_eq!(l[0], 1.0);
        assert!((l[1] - 10f64.sqrt()).abs() < 1e-12);
        assert_eq!(l[2], 10.0);
    }

    #[test]
    fn grid_first_axis_slowest() {
        let g = grid(&[vec![1.0, 2.0], vec![10.0, 20.0, 30.0]]);
        assert_eq!(
            g,
            vec![
                vec![1.0, 10.0],
                vec![1.0, 20.0],
                vec![1.0, 30.0],
                vec![2.0, 10.0],
                vec![2.0, 20.0],
                vec![2.0, 30.0]
            ]
        );
    }

    #[test]
    fn load_builds_grid_and_stable_hash() {
        let (d, s) = setup(
            "load",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.2, 0.4, 3]\n\
             [[axis]]\nparameter = \"interface.static_pressure\"\nvalues = [1e5, 2e5]\n",
        );
        let a = Sweep::load(&s).unwrap();
        assert_eq!(a.points.len(), 6);
        assert_eq!(a.points[1], vec![0.2, 2e5]);
        assert_eq!(a.hash.len(), 64);
        let b = Sweep::load(&s).unwrap();
        assert_eq!(a.hash, b.hash);
        let sc = a.scenarios().unwrap();
        assert_eq!(sc.len(), 6);
        assert!((sc[2].xi - 0.3).abs() < 1e-12);
        // a different grid gives a different hash
        std::fs::write(
            &s,
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.2, 0.4, 4]\n\
             [[axis]]\nparameter = \"interface.static_pressure\"\nvalues = [1e5, 2e5]\n",
        )
        .unwrap();
        assert_ne!(Sweep::load(&s).unwrap().hash, a.hash);
        // so does a different base scenario
        std::fs::write(
            d.join("base.toml"),
            BASE.replace("cycles = 3", "cycles = 4"),
        )
        .unwrap();
        let c = Sweep::load(&s).unwrap();
        std::fs::write(d.join("base.toml"), BASE).unwrap();
        assert_ne!(Sweep::load(&s).unwrap().hash, c.hash);
        let _ = std::fs::remove_dir_all(d);
    }

    fn load_err(name: &str, body: &str) -> String {
        let (d, s) = setup(name, body);
        let e = Sweep::load(&s)
            .and_then(|sw| sw.scenarios().map(|_| ()))
            .unwrap_err()
            .to_string();
        let _ = std::fs::remove_dir_all(d);
        e
    }

    #[test]
    fn bad_axes_are_errors_naming_file_and_field() {
        let b = "base = \"base.toml\"\n";
        let cases = [
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.1, 0.2]\n"), "axis[0].linspace"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.1, 0.2, 0]\n"), "axis[0].linspace"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlogspace = [0.1, 0.2, 2.5]\n"), "axis[0].logspace"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = []\n"), "axis[0].values"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1, nan]\n"), "axis[0].values"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\nlinspace = [0.1, 0.2, 2]\n"), "axis[0]"),
            (format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n[[axis]]\nparameter = \"incident.cycles\"\nvalue = [3]\n"), "axis[1].value"),
            (format!("{b}[[axis]]\nvalues = [0.1]\n"), "axis[0].parameter"),
            (format!("{b}foo = 1\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n"), "foo"),
            ("[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n".to_string(), "base"),
            (b.to_string(), "axis"),
        ];
        for (k, (body, field)) in cases.iter().enumerate() {
            let e = load_err(&format!("bad{k}"), body);
            assert!(e.contains("sweep.toml"), "{e}");
            assert!(e.contains(&format!("`{field}`")), "{field}: {e}");
        }
    }

    #[test]
    fn invalid_point_names_base_field_and_point() {
        let e = load_err(
            "badpoint",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.3, -0.1]\n",
        );
        assert!(e.contains("base.toml"), "{e}");
        assert!(e.contains("incident.xi"), "{e}");
        assert!(e.contains("point 1"), "{e}");
        let e = load_err(
            "badkey",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xii\"\nvalues = [0.3]\n",
        );
        assert!(e.contains("xii"), "{e}");
    }

    #[test]
    fn run_and_resume_skip_done_points() {
        let (d, s) = setup(
            "resume",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.3, 1.2, 4]\n",
        );
        let sweep = Sweep::load(&s).unwrap();
        let csv = d.join("sweep.csv");
        let cancel = AtomicBool::new(false);
        let opts = SweepOptions {
            threads: Some(2),
            resume: false,
        };
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.total, r.skipped, r.computed, r.failed), (4, 0, 4, 0));
        let t = read_sweep_csv(&csv).unwrap();
        assert_eq!(t.header[0], "point");
        assert_eq!(t.header[1], "incident.xi");
        assert_eq!(t.header[2], "xi");
        assert_eq!(t.rows.len(), 4);
        // keep the header and two rows plus half a line, then resume
        let text = std::fs::read_to_string(&csv).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let partial = format!(
            "{}\n{}\n{}\n{}",
            lines[0],
            lines[1],
            lines[2],
            &lines[3][..5]
        );
        std::fs::write(&csv, partial).unwrap();
        let opts = SweepOptions {
            threads: Some(1),
            resume: true,
        };
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.skipped, r.computed), (2, 2));
        let t = read_sweep_csv(&csv).unwrap();
        let mut pts: Vec<usize> = t.rows.iter().map(|r| r[0] as usize).collect();
        pts.sort();
        assert_eq!(pts, vec![0, 1, 2, 3]);
        // nothing left to do
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.skipped, r.computed), (4, 0));
        // a different sweep refuses to resume into this CSV and leaves it alone
        std::fs::write(
            &s,
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.3, 1.2, 5]\n",
        )
        .unwrap();
        let other = Sweep::load(&s).unwrap();
        let before = std::fs::read_to_string(&csv).unwrap();
        let e = run_sweep(&other, &csv, &opts, &|_, _| {}, &cancel).unwrap_err();
        assert!(e.to_string().contains("hash"), "{e}");
        assert_eq!(std::fs::read_to_string(&csv).unwrap(), before);
        let _ = std::fs::remove_dir_all(d);
    }

    #[test]
    fn cancel_before_start_is_interrupted() {
        let (d, s) = setup(
            "cancel",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.3, 0.5]\n",
        );
        let sweep = Sweep::load(&s).unwrap();
        let cancel = AtomicBool::new(true);
        let e = run_sweep(
            &sweep,
            &d.join("sweep.csv"),
            &SweepOptions::default(),
            &|_, _| {},
            &cancel,
        )
        .unwrap_err();
        assert!(matches!(e, Error::Interrupted));
        let _ = std::fs::remove_dir_all(d);
    }
}

//! The sweep file format: parsing a sweep file (`base`, the optional `[set]` table and the
//! `[[axis]]` tables) into a [`Sweep`] with its [`Axis`]es ([`AxisSpec`]: `values`,
//! `linspace`, `logspace`), the checks on them, and the scenario table of each grid point
//! ([`point_table`]), and the sweep's plan: the base template with one typed parameter
//! per axis ([`Sweep::plan`], [`Sweep::model`]). The file format is described in the
//! `study::sweep` module doc.
//!
//! Below it: the grid (values and cartesian product) and the CSV side (the hash and the
//! number format). It runs nothing.

use super::csv_io::{fmt_f64, hash_sweep};
use super::grid::{grid, linspace, logspace};
use crate::error::{Error, Result};
use crate::model::{self, toml_number, Model, Param, Template};
use crate::scenario::{
    deserialize_format, parse_toml, read_base, same_key, set_dotted, FieldProblem,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Largest number of points of one axis.
const MAX_AXIS_POINTS: usize = 1_000_000;
/// Largest number of grid points of a sweep.
const MAX_GRID_POINTS: usize = 10_000_000;

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

impl Sweep {
    /// Load a sweep file and its base scenario, and build the grid. Errors name the sweep
    /// file and the field (`axis.1.linspace`, ...). The points are validated as scenarios
    /// by [`Sweep::runnable`].
    pub fn load(path: &Path) -> Result<Sweep> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let file = path.display().to_string();
        let table = parse_toml(&text, &file)?;
        Sweep::from_table(table, path)
    }

    /// Build a sweep from a parsed sweep table that came from `path`.
    pub fn from_table(table: toml::Table, path: &Path) -> Result<Sweep> {
        let file = path.display().to_string();
        let f: SweepFile = deserialize_format(&table, &file, sweep_allowed)?;
        if f.axis.is_empty() {
            return Err(Error::invalid(
                &file,
                "axis",
                "[]",
                sweep_allowed("axis", FieldProblem::Wrong),
            ));
        }
        let mut axes: Vec<Axis> = Vec::with_capacity(f.axis.len());
        for (i, a) in f.axis.into_iter().enumerate() {
            let axis = a.check(i, &file)?;
            if let Some(b) = axes
                .iter()
                .find(|b| same_key(&b.parameter, &axis.parameter))
            {
                return Err(Error::invalid(
                    &file,
                    format!("axis.{i}.parameter"),
                    format!("\"{}\"", axis.parameter),
                    swept_already(&b.parameter),
                ));
            }
            axes.push(axis);
        }
        check_axes(&file, &axes)?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let (base, base_table) = read_base(
            &file,
            &dir,
            &f.base,
            f.set.as_ref(),
            sweep_allowed("base", FieldProblem::Wrong),
        )?;
        Ok(Sweep::assemble(path, base, base_table, axes))
    }

    /// Build a sweep in code (the Python bindings' `sweep`): a base scenario table that came
    /// from (or stands for) `base`, and `(dotted key, values)` axes, first axis slowest.
    /// `file` names the sweep in error messages and [`Sweep::file`]. The axes are checked
    /// like a sweep file's `values` axes; the grid and the hash are built the same way, so a
    /// sweep file with the same base table and values has the same [`Sweep::hash`]. Values
    /// are in the SI unit of their key.
    ///
    /// ```
    /// use contactwave::scenario::parse_toml;
    /// use contactwave::study::Sweep;
    /// use std::path::{Path, PathBuf};
    /// let base = parse_toml(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.1e6
    ///     [incident]
    ///     frequency = 1e6
    ///     cycles = 10
    ///     xi = 0.5
    /// "#, "base.toml").unwrap();
    /// let sweep = Sweep::from_parts(
    ///     Path::new("xi_p0_sweep"),
    ///     PathBuf::from("base.toml"),
    ///     base.clone(),
    ///     vec![
    ///         ("incident.xi".into(), vec![0.25, 0.5, 2.0]),
    ///         ("interface.static_pressure".into(), vec![0.1e6, 1e6]), // Pa
    ///     ],
    /// )
    /// .unwrap();
    /// // the cartesian grid, first axis slowest
    /// assert_eq!(sweep.points.len(), 6);
    /// assert_eq!(sweep.points[1], [0.25, 1e6]);
    /// assert_eq!(sweep.parameters(), ["incident.xi", "interface.static_pressure"]);
    /// // every point builds a valid model
    /// let models = sweep.runnable().unwrap();
    /// assert_eq!(models[5].load_ratio(), 2.0);
    /// // a value the scenario rejects is reported with the point it belongs to
    /// let bad = Sweep::from_parts(
    ///     Path::new("bad_sweep"),
    ///     PathBuf::from("base.toml"),
    ///     base,
    ///     vec![("interface.static_pressure".into(), vec![0.1e6, -1.0])],
    /// )
    /// .unwrap();
    /// let err = bad.runnable().unwrap_err().to_string();
    /// assert!(err.contains("interface.static_pressure") && err.contains("at point 1"));
    /// ```
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
                    format!("axis.{i}.parameter"),
                    format!("\"{parameter}\""),
                    "must be a dotted scenario key such as \"incident.xi\"",
                ));
            }
            let field = format!("axis.{i}.values");
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
            if let Some(b) = out.iter().find(|b| same_key(&b.parameter, &parameter)) {
                return Err(Error::invalid(
                    &name,
                    format!("axis.{i}.parameter"),
                    format!("\"{parameter}\""),
                    swept_already(&b.parameter),
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
        let named: Vec<(&str, &[f64])> = axes
            .iter()
            .map(|a| (a.parameter.as_str(), a.values.as_slice()))
            .collect();
        let hash = hash_sweep(&base_table, &named, &points);
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

    /// Plan the sweep once: the base template (its table parsed, laws and files built
    /// once) and one typed parameter per axis. A key the scenario cannot take is an error
    /// naming the sweep file and the field `axis[k].parameter`.
    pub fn plan(&self) -> Result<SweepPlan> {
        let template = model::plan(self.base_table.clone(), &self.base);
        let file = self.file.display().to_string();
        let params = self
            .axes
            .iter()
            .enumerate()
            .map(|(k, a)| {
                template
                    .param(&a.parameter)
                    .map_err(|e| axis_error(e, &file, k))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(SweepPlan { template, params })
    }

    /// The model of grid point `i`, validated; an invalid point fails with the scenario
    /// error (naming the base file and the field), followed by the sweep file, the point
    /// index and its values.
    pub fn model(&self, plan: &SweepPlan, i: usize) -> Result<Arc<dyn Model>> {
        let values: Vec<(&Param, f64)> = plan
            .params
            .iter()
            .zip(self.points[i].iter().copied())
            .collect();
        plan.template.build(&values).map_err(|e| {
            // a key the scenario cannot take is the sweep file's mistake, not the base's
            if let Some(k) = self.axis_named_by(&e) {
                return Error::invalid(
                    self.file.display().to_string(),
                    format!("axis.{k}.parameter"),
                    &self.axes[k].parameter,
                    format!(
                        "the base scenario {} cannot take this key: {e}",
                        self.base.display()
                    ),
                );
            }
            e.within(&self.at_point(i))
        })
    }

    /// Whether point `i`'s model `m` fits the memory budget ([`Model::check_budget`]): the
    /// error followed by the sweep file, the point index and its values.
    fn fits(&self, m: &dyn Model, i: usize) -> Result<()> {
        m.check_budget().map_err(|e| e.within(&self.at_point(i)))
    }

    /// `in sweep FILE at point i: key = value, ...`.
    fn at_point(&self, i: usize) -> String {
        let values = self
            .axes
            .iter()
            .zip(&self.points[i])
            .map(|(a, v)| format!("{} = {}", a.parameter, fmt_f64(*v)))
            .collect::<Vec<_>>()
            .join(", ");
        format!("in sweep {} at point {i}: {values}", self.file.display())
    }

    /// The axis whose key a scenario's parse error (unknown key, wrong type, missing
    /// field) names: the axis' dotted key itself, or a table that the key created in the
    /// base (absent from it). A value outside its range is not such an error.
    fn axis_named_by(&self, e: &Error) -> Option<usize> {
        let Error::Parse { message, .. } = e else {
            return None;
        };
        let field = message.strip_prefix("field `")?.split('`').next()?;
        self.axes.iter().position(|a| {
            a.parameter == field
                || (a.parameter.starts_with(&format!("{field}."))
                    && !has_dotted(&self.base_table, field))
        })
    }

    /// Plan the sweep and validate every grid point (any kind of scenario) on all cores
    /// without keeping the models (flat memory): the first invalid point in grid order is
    /// the error.
    pub fn validate(&self) -> Result<SweepPlan> {
        self.validate_with(&|_, _| {})
    }

    /// [`Sweep::validate`] reporting (points checked, total) to `progress` as it goes.
    pub fn validate_with(&self, progress: &(dyn Fn(usize, usize) + Sync)) -> Result<SweepPlan> {
        let plan = self.plan()?;
        let idx: Vec<usize> = (0..self.points.len()).collect();
        let first_bad = std::sync::atomic::AtomicUsize::new(usize::MAX);
        crate::run::Executor::new().for_each(
            &idx,
            |&i| {
                // points after a known bad one need no check
                if i > first_bad.load(std::sync::atomic::Ordering::SeqCst) {
                    return Ok(());
                }
                // (and fits the memory budget: a point refused only when it runs would
                // stop the sweep halfway)
                self.model(&plan, i)
                    .and_then(|m| self.fits(&*m, i))
                    .inspect_err(|_| {
                        first_bad.fetch_min(i, std::sync::atomic::Ordering::SeqCst);
                    })
            },
            &crate::run::Progress {
                report: progress,
                cancel: None,
            },
        )?;
        // an interruption skipped points: they are not validated
        crate::interrupt::check()?;
        match first_bad.load(std::sync::atomic::Ordering::SeqCst) {
            usize::MAX => Ok(plan),
            i => Err(self
                .model(&plan, i)
                .and_then(|m| self.fits(&*m, i))
                .err()
                .unwrap_or(Error::Internal {
                    message: format!("point {i} failed validation once only"),
                })),
        }
    }

    /// Plan the sweep and validate every grid point (any kind of scenario), in grid order.
    pub fn runnable(&self) -> Result<Vec<Arc<dyn Model>>> {
        let plan = self.plan()?;
        (0..self.points.len())
            .map(|i| self.model(&plan, i))
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

/// A planned sweep: the base scenario's template and the parameter of each axis.
#[derive(Debug, Clone)]
pub struct SweepPlan {
    /// The base scenario (after `[set]`), planned once.
    pub template: Arc<dyn Template>,
    /// The parameter of each axis, in axis order.
    pub params: Vec<Param>,
}

/// Whether the table holds the dotted key `key`.
fn has_dotted(table: &toml::Table, key: &str) -> bool {
    let mut parts = key.split('.');
    let Some(first) = parts.next() else {
        return false;
    };
    let mut v = table.get(first);
    for p in parts {
        v = v.and_then(|x| x.as_table()).and_then(|t| t.get(p));
    }
    v.is_some()
}

/// A key error of axis `k`, naming the sweep file and `axis[k].parameter`.
fn axis_error(e: Error, file: &str, k: usize) -> Error {
    match e {
        Error::Invalid { value, allowed, .. } => Error::Invalid {
            file: file.to_string(),
            field: format!("axis.{k}.parameter"),
            value,
            allowed,
        },
        other => other,
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
        set_dotted(&mut table, parameter, toml_number(parameter, v))
            .map_err(|e| axis_error(e, file, k))?;
    }
    Ok(table)
}

/// Why an axis whose key sets what the earlier axis `earlier` sets is refused.
fn swept_already(earlier: &str) -> String {
    format!("is swept by an earlier axis already (`{earlier}` sets the same value)")
}

/// Checks that need every axis: not both `incident.xi` and `incident.amplitude`, not both
/// a crack's `length` and its `end` (each sets the other), grid size.
fn check_axes(file: &str, axes: &[Axis]) -> Result<()> {
    let has = |k: &str| axes.iter().any(|a| same_key(&a.parameter, k));
    if has("incident.xi") && has("incident.amplitude") {
        return Err(Error::invalid(
            file,
            "axis",
            "incident.xi, incident.amplitude",
            "sweep `incident.xi` or `incident.amplitude`, not both (they give the same \
                 quantity)",
        ));
    }
    for a in axes {
        let Some(crack) = a.parameter.strip_suffix(".length") else {
            continue;
        };
        for end in [format!("{crack}.end.x"), format!("{crack}.end.z")] {
            if (crack == "crack" || crack.starts_with("crack.")) && has(&end) {
                return Err(Error::invalid(
                    file,
                    "axis",
                    format!("{}, {end}", a.parameter),
                    "sweep a crack's `length` or its `end`, not both (each moves the other \
                     end)",
                ));
            }
        }
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
    let points = total.unwrap_or(0) as f64;
    crate::budget::check(
        file,
        "axis",
        axes.iter()
            .map(|a| a.values.len().to_string())
            .collect::<Vec<_>>()
            .join(" x "),
        points * (BYTES_PER_POINT + 8.0 * axes.len() as f64),
        &format!("{points:.3e} grid points: their values and result rows"),
    )
}

/// Memory one grid point takes while a sweep runs, bytes: an upper estimate of its axis
/// values and its result row (the CLI streams its rows to `sweep.csv`; Python's local
/// sweep builds and runs the points 4096 at a time and holds a table of 8-byte values,
/// about 40 columns, twice while the table is assembled). The models are never all
/// alive at once ([`Sweep::runnable`] is for small sweeps).
const BYTES_PER_POINT: f64 = 1024.0;

/// A sweep file as written: the serde shape of the format (the module doc of
/// `study::sweep` describes it); [`Sweep::from_table`] checks it into a [`Sweep`].
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepFile {
    base: String,
    #[serde(default)]
    set: Option<toml::Table>,
    axis: Vec<AxisFile>,
}

/// An `[[axis]]` table as written. The numbers stay TOML values until the check: their
/// unit is that of `parameter` (`values = ["1 MHz", "2 MHz"]`).
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct AxisFile {
    parameter: String,
    values: Option<Vec<toml::Value>>,
    linspace: Option<Vec<toml::Value>>,
    logspace: Option<Vec<toml::Value>>,
}

/// What a sweep file allows at `key` (array indices dropped), for the errors of
/// [`deserialize_format`] and of the checks.
fn sweep_allowed(key: &str, problem: FieldProblem) -> String {
    let must = if problem == FieldProblem::Missing {
        ""
    } else {
        "must be "
    };
    let what = match key {
        "" => {
            return "a sweep file has `base` (the base scenario file), an optional `[set]` \
                    table of fixed overrides and `[[axis]]` tables"
                .into();
        }
        "axis" if problem == FieldProblem::Unknown => {
            return "an axis has `parameter` and one of `values`, `linspace`, `logspace`".into();
        }
        "base" => "the path of the base scenario file, relative to the sweep file",
        "set" => "a table of dotted scenario keys and values",
        "axis" => "one or more `[[axis]]` tables",
        "axis.parameter" => "a dotted scenario key such as \"incident.xi\"",
        _ => "an array of numbers",
    };
    format!("{must}{what}")
}

impl AxisFile {
    /// Check axis `i` of `file` and build its values.
    fn check(self, i: usize, file: &str) -> Result<Axis> {
        let parameter = self.parameter;
        if parameter.is_empty() || parameter.split('.').any(|p| p.trim().is_empty()) {
            return Err(Error::invalid(
                file,
                format!("axis.{i}.parameter"),
                format!("\"{parameter}\""),
                sweep_allowed("axis.parameter", FieldProblem::Wrong),
            ));
        }
        let given: Vec<(&str, Vec<toml::Value>)> = [
            ("values", self.values),
            ("linspace", self.linspace),
            ("logspace", self.logspace),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| (k, v)))
        .collect();
        let [(key, arr)] = given.as_slice() else {
            return Err(Error::invalid(
                file,
                format!("axis.{i}"),
                if given.is_empty() {
                    "(none)".to_string()
                } else {
                    given.iter().map(|g| g.0).collect::<Vec<_>>().join(", ")
                },
                "give exactly one of `values = [..]`, `linspace = [start, end, n]`, \
                 `logspace = [start_exponent, end_exponent, n]`",
            ));
        };
        let field = format!("axis.{i}.{key}");
        let raw = || toml::Value::Array(arr.clone()).to_string();
        let spec = if *key == "values" {
            if arr.is_empty() || arr.len() > MAX_AXIS_POINTS {
                return Err(Error::invalid(
                    file,
                    field,
                    if arr.is_empty() {
                        raw()
                    } else {
                        format!("({} values)", arr.len())
                    },
                    format!("must hold 1 to {MAX_AXIS_POINTS} numbers"),
                ));
            }
            let mut v = Vec::with_capacity(arr.len());
            for x in arr {
                match crate::scenario::units::si_number(x, &parameter) {
                    Ok(y) if y.is_finite() => v.push(y),
                    Ok(_) => {
                        return Err(Error::invalid(
                            file,
                            field,
                            x,
                            "every value must be a finite number",
                        ));
                    }
                    Err(why) => return Err(Error::invalid(file, field, x, why)),
                }
            }
            AxisSpec::Values(v)
        } else {
            let linear = *key == "linspace";
            let (what, limit, range) = if linear {
                ("[start, end, n]", f64::MAX, "")
            } else {
                (
                    "[start_exponent, end_exponent, n] (exponents of 10)",
                    300.0,
                    " in [-300, 300]",
                )
            };
            // linspace ends take the parameter's unit; logspace exponents are plain numbers
            let end = |v: &toml::Value| {
                crate::scenario::units::si_number(v, if linear { &parameter } else { "" })
                    .ok()
                    .filter(|x| x.is_finite() && x.abs() <= limit)
            };
            let n = |v: &toml::Value| {
                crate::scenario::units::si_number(v, "").ok().filter(|x| {
                    x.is_finite() && x.fract() == 0.0 && *x >= 1.0 && *x <= MAX_AXIS_POINTS as f64
                })
            };
            match arr.as_slice() {
                [a, b, c] => match (end(a), end(b), n(c)) {
                    (Some(start), Some(stop), Some(n)) if linear => AxisSpec::Linspace {
                        start,
                        end: stop,
                        n: n as usize,
                    },
                    (Some(start), Some(stop), Some(n)) => AxisSpec::Logspace {
                        start_exponent: start,
                        end_exponent: stop,
                        n: n as usize,
                    },
                    _ => {
                        return Err(Error::invalid(
                            file,
                            field,
                            raw(),
                            format!(
                                "must be {what}: finite numbers{range} and n an integer in \
                                 [1, {MAX_AXIS_POINTS}]"
                            ),
                        ));
                    }
                },
                _ => {
                    return Err(Error::invalid(
                        file,
                        field,
                        raw(),
                        format!("must be {what} with n an integer >= 1"),
                    ));
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
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{setup, tmpdir, BASE};
    use super::*;

    #[test]
    fn a_crack_length_and_its_end_are_not_both_swept() {
        let axis = |p: &str| Axis {
            parameter: p.into(),
            spec: AxisSpec::Values(vec![1e-3]),
            values: vec![1e-3],
        };
        let e = check_axes("s.toml", &[axis("crack.0.length"), axis("crack.0.end.x")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("crack.0.length, crack.0.end.x") && e.contains("not both"),
            "{e}"
        );
        // another crack's end, or the start, may be swept beside a length
        check_axes("s.toml", &[axis("crack.0.length"), axis("crack.1.end.x")]).unwrap();
        check_axes("s.toml", &[axis("crack.0.length"), axis("crack.0.start.x")]).unwrap();
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
        assert_eq!(sw.runnable().unwrap()[0].kind(), "bar_stack");
        // an index past the end names the [set] key
        let bad = good.replace("interface.1.", "interface.2.");
        std::fs::write(dir.join("bad.toml"), bad).unwrap();
        match Sweep::load(&dir.join("bad.toml")) {
            Err(Error::Invalid { field, allowed, .. }) => {
                assert!(field.contains("interface.2.compression"), "{field}");
                assert!(allowed.contains("from 0 to 1"), "{allowed}");
            }
            other => panic!("expected an invalid-field error, got {other:?}"),
        }
        let _ = std::fs::remove_dir_all(&dir);
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
        let sc = a.runnable().unwrap();
        assert_eq!(sc.len(), 6);
        assert!((sc[2].load_ratio() - 0.3).abs() < 1e-12);
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
            .and_then(|sw| sw.runnable().map(|_| ()))
            .unwrap_err()
            .to_string();
        let _ = std::fs::remove_dir_all(d);
        e
    }

    #[test]
    fn bad_axes_are_errors_naming_file_and_field() {
        let b = "base = \"base.toml\"\n";
        let cases = [
            (
                format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.1, 0.2]\n"),
                "axis.0.linspace",
            ),
            (
                format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.1, 0.2, 0]\n"),
                "axis.0.linspace",
            ),
            (
                format!("{b}[[axis]]\nparameter = \"incident.xi\"\nlogspace = [0.1, 0.2, 2.5]\n"),
                "axis.0.logspace",
            ),
            (
                format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = []\n"),
                "axis.0.values",
            ),
            (
                format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1, nan]\n"),
                "axis.0.values",
            ),
            (
                format!(
                    "{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\nlinspace = [0.1, 0.2, 2]\n"
                ),
                "axis.0",
            ),
            (
                format!(
                    "{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n[[axis]]\nparameter = \"incident.cycles\"\nvalue = [3]\n"
                ),
                "axis.1.value",
            ),
            (format!("{b}[[axis]]\nvalues = [0.1]\n"), "axis.0.parameter"),
            (
                format!("{b}foo = 1\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n"),
                "foo",
            ),
            (
                "[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n".to_string(),
                "base",
            ),
            (b.to_string(), "axis"),
        ];
        for (k, (body, field)) in cases.iter().enumerate() {
            let e = load_err(&format!("bad{k}"), body);
            assert!(e.contains("sweep.toml"), "{e}");
            assert!(e.contains(&format!("`{field}`")), "{field}: {e}");
        }
    }

    /// The derived format's errors (issue 25, item 7) name the field, the value as written
    /// and what is allowed: the keys an axis has, the type a field takes.
    #[test]
    fn format_errors_say_what_is_allowed() {
        let b = "base = \"base.toml\"\n";
        let e = load_err(
            "unknown",
            &format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalue = [0.1]\n"),
        );
        assert!(
            e.contains(
                "field `axis.0.value` = [0.1]: unknown key; an axis has `parameter` and one of"
            ),
            "{e}"
        );
        let e = load_err(
            "type",
            "base = 3\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.1]\n",
        );
        assert!(
            e.contains("field `base` = 3: must be the path of the base scenario file"),
            "{e}"
        );
        let e = load_err("missing", &format!("{b}[[axis]]\nvalues = [0.1]\n"));
        assert!(
            e.contains("field `axis.0.parameter` = (missing): required: a dotted scenario key"),
            "{e}"
        );
        let e = load_err(
            "scalar",
            &format!("{b}[[axis]]\nparameter = \"incident.xi\"\nvalues = 0.1\n"),
        );
        assert!(
            e.contains("field `axis.0.values` = 0.1: must be an array of numbers"),
            "{e}"
        );
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
        // a typo in the axis' key is the sweep file's (issue 24: it was reported against
        // base.toml), naming the axis and its key; likewise a table the key creates
        let e = load_err(
            "badkey",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xii\"\nvalues = [0.3]\n",
        );
        assert!(
            e.contains("sweep.toml: field `axis.0.parameter` = incident.xii:"),
            "{e}"
        );
        assert!(e.contains("unknown field `xii`"), "{e}");
        let e = load_err(
            "badtable",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"interface.traction.stifness\"\nvalues = [1e12]\n",
        );
        assert!(
            e.contains("sweep.toml: field `axis.0.parameter` = interface.traction.stifness:"),
            "{e}"
        );
    }
}

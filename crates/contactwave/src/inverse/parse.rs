//! The identification file format: [`IdentifySpec::load`] and
//! [`IdentifySpec::from_table`] read the TOML (`base`, `data`, `observed`, `[set]`,
//! `[[parameter]]`, `[fit]`, `[design]`) and the measured data (a CSV file or an inline
//! table), check them, and check every row against the forward model at the starting
//! values. The format is described in the `inverse` module doc.

use super::model::Model;
use super::spec::{DesignSpec, FitOptions, IdentifySpec, Measured, Observed, Parameter, Scale};
use crate::error::{Error, Result};
use crate::model;
use crate::numeric::table::{read_table, CsvReader, Header};
use crate::scenario::{deserialize_format, parse_toml, read_base, set_dotted, FieldProblem};
use std::path::{Path, PathBuf};

/// A value of scenario key `key`, in SI: a number or a unit string (`"1 MHz"`).
fn quantity(v: &toml::Value, key: &str) -> Option<f64> {
    crate::scenario::units::si_number(v, key).ok()
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
    crate::scenario::units::si_number(cur, "").ok()
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

    /// [`Self::load`] without reading the files of `[records]` (their rows are the listed
    /// condition values, the observed values placeholders): what `identify --synthesize`
    /// needs to make those files. Other files load as in [`Self::load`].
    pub fn load_unmeasured(path: &Path) -> Result<IdentifySpec> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let table = parse_toml(&text, &path.display().to_string())?;
        IdentifySpec::from_table_with(table, path, false)
    }

    /// Build from a parsed identification table that came from `path` (relative paths
    /// resolve against its folder). `data` may be a file name or an inline table of
    /// equally long arrays (column name -> values). The format is described in the
    /// [`inverse`](crate::inverse) module doc.
    ///
    /// ```
    /// use contactwave::inverse::IdentifySpec;
    /// use contactwave::scenario::parse_toml;
    /// let dir = std::env::temp_dir().join(format!("contactwave-doc-spec-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// std::fs::write(dir.join("base.toml"), r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.1e6                             # Pa
    ///     compression = { law = "linear", stiffness = 1e12 }  # Pa/m
    ///     [incident]
    ///     frequency = 1e6                                     # Hz
    ///     cycles = 5
    ///     xi = 0.5
    /// "#).unwrap();
    /// let table = parse_toml(r#"
    ///     base = "base.toml"
    ///     observed = ["A2_over_A1"]
    ///     [data]                      # inline: one row per load ratio
    ///     "incident.xi" = [0.3, 0.5, 0.8]
    ///     A2_over_A1 = [0.058, 0.054, 0.043]
    ///     [[parameter]]
    ///     key = "interface.compression.stiffness"
    ///     bounds = [1e10, 1e14]       # Pa/m
    ///     scale = "log"
    /// "#, "identify.toml").unwrap();
    /// let spec = IdentifySpec::from_table(table, &dir.join("identify.toml")).unwrap();
    /// assert_eq!(spec.measured.conditions, ["incident.xi"]);
    /// assert_eq!((spec.measured.len(), spec.parameters.len()), (3, 1));
    /// // sigma = relative_noise |y| with the default relative_noise = 1 %
    /// assert!((spec.measured.observed[0].sigma[0] - 0.00058).abs() < 1e-12);
    /// // a parameter key the scenario does not have is an error naming it
    /// let table = parse_toml(r#"
    ///     base = "base.toml"
    ///     [data]
    ///     "incident.xi" = [0.3, 0.5, 0.8]
    ///     A2_over_A1 = [0.058, 0.054, 0.043]
    ///     [[parameter]]
    ///     key = "interface.compression.stifness"
    ///     bounds = [1e10, 1e14]
    /// "#, "identify.toml").unwrap();
    /// let err = IdentifySpec::from_table(table, &dir.join("identify.toml")).unwrap_err();
    /// assert!(err.to_string().contains("parameter.0.key"));
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
    pub fn from_table(table: toml::Table, path: &Path) -> Result<IdentifySpec> {
        IdentifySpec::from_table_with(table, path, true)
    }

    /// [`Self::from_table`], reading the `[records]` files when `read_records`.
    fn from_table_with(
        table: toml::Table,
        path: &Path,
        read_records: bool,
    ) -> Result<IdentifySpec> {
        let file = path.display().to_string();
        let f: IdentifyFile = deserialize_format(&table, &file, allowed)?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let (base, mut base_table) = read_base(
            &file,
            dir,
            &f.base,
            f.set.as_ref(),
            allowed("base", FieldProblem::Wrong),
        )?;
        let base_file = base.display().to_string();
        crate::scenario::units::to_si(&mut base_table, &base_file)?;
        default_analysis(&mut base_table);
        // the base (with overrides) must be a valid scenario
        model::plan_valid(base_table.clone(), &base).map_err(|e| {
            e.within(&if f.set.is_some() {
                format!("the base with the [set] of {file}")
            } else {
                format!("the base of {file}")
            })
        })?;

        let fit = f.fit.check(&file)?;
        let (measured, data_file, records) = match (&f.data, f.records) {
            (Some(data), None) => {
                let (m, d) = parse_data(data, f.observed.as_deref(), dir, &file, &fit)?;
                (m, d, None)
            }
            (None, Some(r)) => {
                let mut r = r.check(&file, dir)?;
                let rows = if read_records {
                    let noise = (fit.relative_noise, fit.absolute_noise);
                    r.measure(f.observed.as_deref(), &file, noise)?
                } else {
                    r.unmeasured(f.observed.as_deref(), &file)?
                };
                let m = Measured {
                    conditions: vec![r.condition.clone()],
                    rows: rows.rows,
                    observed: rows
                        .observed
                        .into_iter()
                        .map(|(key, values, sigma)| Observed { key, values, sigma })
                        .collect(),
                };
                // the forward runs are reduced by the records' analysis: the scenario's own
                // (and its second run) is not needed
                if model::kind_of(&base_table).name() != "bar_stack" {
                    set_dotted(
                        &mut base_table,
                        "analysis.method",
                        toml::Value::String("band_peak".into()),
                    )?;
                }
                (m, None, Some(r))
            }
            (data, _) => {
                return Err(Error::invalid(
                    &file,
                    if data.is_some() { "records" } else { "data" },
                    if data.is_some() {
                        "given with data"
                    } else {
                        "missing"
                    },
                    "either data (a reduced curve) or [records] (raw waveforms), not both",
                ));
            }
        };
        let parameters = parse_parameters(f.parameter, &file, &base_table)?;
        let frequency = model::kind_of(&base_table).frequency_key();
        let design = f.design.map(|d| d.check(&file, frequency)).transpose()?;

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
            records,
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
            model.at_start(p).map_err(|e| {
                let why = reason(e);
                Error::invalid(
                    &file,
                    format!("parameter.{k}.key"),
                    &p.key,
                    format!(
                        "a dotted key of a number of the base scenario (setting it to \
                             {} fails: {why})",
                        p.initial
                    ),
                )
            })?;
        }
        // every row of the data at the starting values: a bad column key or value is the
        // data's (the error names its file, row and key), not the parameters' bounds
        let start = model.values(&z0);
        for row in 0..spec.measured.len() {
            model.scenario(row, &start)?;
        }
        // every value within a parameter's bounds must make a valid scenario (the others
        // at their starting values): checked at both bounds and at a point inside that is
        // no round number (a key of whole numbers, or a length whose far end leaves the
        // rectangle, is refused here rather than halfway through the search)
        for (k, p) in spec.parameters.iter().enumerate() {
            let (lo, hi) = p.scaled_bounds();
            for z in [lo, hi, lo + 0.381_966 * (hi - lo)] {
                let mut v = start.clone();
                v[k] = p.from_scaled(z).clamp(p.lower, p.upper);
                if let Err(e) = model.scenario(0, &v) {
                    let why = reason(e);
                    return Err(Error::invalid(
                        &file,
                        format!("parameter.{k}.bounds"),
                        format!("[{:e}, {:e}]", p.lower, p.upper),
                        format!(
                            "bounds within which every value makes a valid scenario ({} = {:e} \
                             fails: {why})",
                            p.key, v[k]
                        ),
                    ));
                }
            }
        }
        // every candidate of a design must make a valid scenario too
        if let Some(d) = &spec.design {
            for &v in &d.values {
                if let Err(e) = model.scenario_with(0, &start, &[(d.key.clone(), v)]) {
                    return Err(Error::invalid(
                        &file,
                        "design.values",
                        format!("{v:e}"),
                        format!(
                            "values for which the base scenario is valid ({} = {v:e} fails: {})",
                            d.key,
                            reason(e)
                        ),
                    ));
                }
            }
        }
        for i in 0..spec.measured.len() {
            model.scenario(i, &model.values(&z0))?;
        }
        // every observed column must be a key of this scenario's summary (one forward run;
        // with records, the forward signal must exist and reduce)
        if spec.records.is_some() {
            model.run_with(0, &model.values(&z0), &[])?;
        } else if let Ok(summary) = model.scenario(0, &model.values(&z0))?.summary() {
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

/// Why a scenario was refused, in a few words: the field and what it allows.
fn reason(e: Error) -> String {
    match e {
        Error::Invalid { field, allowed, .. } => format!("{field}: {allowed}"),
        Error::Parse { message, .. } => message,
        other => other.to_string(),
    }
}

/// An identification file as written: the serde shape of the format (the `inverse` module
/// doc describes it); [`IdentifySpec::from_table`] checks it. Numbers that take the unit
/// of a key (bounds, initial values, design values) stay TOML values until the check.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct IdentifyFile {
    base: String,
    data: Option<toml::Value>,
    records: Option<super::records::RecordsFile>,
    observed: Option<Vec<String>>,
    set: Option<toml::Table>,
    parameter: Vec<ParameterFile>,
    #[serde(default)]
    fit: FitFile,
    design: Option<DesignFile>,
}

/// A `[[parameter]]` table as written.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ParameterFile {
    key: String,
    bounds: Vec<toml::Value>,
    scale: Option<ScaleFile>,
    initial: Option<toml::Value>,
    #[serde(default)]
    also: Vec<String>,
}

/// `scale = "log"` or `"linear"`.
#[derive(Debug, Clone, Copy, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
enum ScaleFile {
    Log,
    Linear,
}

/// `[fit]` as written (counts as numbers: `particles = 8.0` is accepted, as before).
#[derive(Debug, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct FitFile {
    relative_noise: Option<f64>,
    absolute_noise: Option<f64>,
    particles: Option<f64>,
    iterations: Option<f64>,
    local_iterations: Option<f64>,
    local_starts: Option<f64>,
    bootstrap: Option<f64>,
    bootstrap_iterations: Option<f64>,
    seed: Option<f64>,
}

/// `[design]` as written.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignFile {
    key: Option<String>,
    values: Option<Vec<toml::Value>>,
    frequencies: Option<Vec<toml::Value>>,
    control: Option<Vec<toml::Value>>,
    control_linspace: Option<Vec<toml::Value>>,
}

/// What an identification file allows at `key` (array indices dropped), for the errors of
/// [`deserialize_format`] and of the checks.
fn allowed(key: &str, problem: FieldProblem) -> String {
    let unknown = problem == FieldProblem::Unknown;
    let missing = problem == FieldProblem::Missing;
    match key {
        "" => {
            "an identification file has base, data or records, observed, set, parameter, \
             fit, design"
        }
        "records" => super::records::ALLOWED,
        "parameter" if unknown => "a [[parameter]] has key, bounds, scale, initial, also",
        "fit" if unknown => {
            "[fit] has relative_noise, absolute_noise, particles, iterations, \
             local_iterations, local_starts, bootstrap, bootstrap_iterations, seed"
        }
        "design" if unknown => {
            "[design] has key, values (or frequencies), control, control_linspace"
        }
        "base" => "the path of the base scenario file, relative to this file",
        "data" => "the measured CSV file (relative to this file) or an inline table of columns",
        "observed" => "a non-empty list of observed column names",
        "set" => "a table of dotted scenario keys and values",
        "parameter" if missing => "one or more [[parameter]] tables with key, bounds, scale",
        "parameter" => "one or more [[parameter]] tables",
        "parameter.key" => "a dotted scenario key such as `interface.traction.stiffness`",
        "parameter.bounds" if missing => "[lower, upper] in the key's unit",
        "parameter.bounds" => {
            "[lower, upper], finite numbers (SI) or unit strings with lower < upper"
        }
        "parameter.scale" => "\"log\" or \"linear\"",
        "parameter.initial" => "a number within the bounds",
        "parameter.also" => "a list of dotted scenario keys set to the same value",
        "fit" | "design" => "a table",
        "design.key" => "a dotted scenario key such as `incident.frequency`",
        "design.values" if missing => "the candidate values of design.key",
        k if k.starts_with("design.") => "a non-empty list of numbers",
        _ => "a number",
    }
    .to_string()
}

/// A TOML value as the user wrote it.
fn show(v: &toml::Value) -> String {
    v.to_string()
}

impl FitFile {
    /// Check the options against their ranges; unset ones keep their defaults.
    fn check(&self, file: &str) -> Result<FitOptions> {
        let mut o = FitOptions::default();
        let noise = |name: &str, v: Option<f64>, default: f64| match v {
            None => Ok(default),
            Some(x) if x >= 0.0 && x.is_finite() => Ok(x),
            Some(x) => Err(Error::invalid(
                file,
                format!("fit.{name}"),
                x,
                "finite, >= 0",
            )),
        };
        let count = |name: &str, v: Option<f64>, max: f64, default: u64| match v {
            None => Ok(default),
            Some(x) if x.is_finite() && x.fract() == 0.0 && x >= 0.0 && x <= max => Ok(x as u64),
            Some(x) => Err(Error::invalid(
                file,
                format!("fit.{name}"),
                x,
                format!("an integer in [0, {max}]"),
            )),
        };
        o.relative_noise = noise("relative_noise", self.relative_noise, o.relative_noise)?;
        o.absolute_noise = noise("absolute_noise", self.absolute_noise, o.absolute_noise)?;
        o.particles = count("particles", self.particles, 10_000.0, o.particles as u64)? as usize;
        o.iterations = count("iterations", self.iterations, 1e6, o.iterations)?;
        o.local_iterations = count(
            "local_iterations",
            self.local_iterations,
            1e6,
            o.local_iterations,
        )?;
        o.local_starts = count(
            "local_starts",
            self.local_starts,
            1000.0,
            o.local_starts as u64,
        )?
        .max(1) as usize;
        o.bootstrap = count("bootstrap", self.bootstrap, 10_000.0, o.bootstrap as u64)? as usize;
        o.bootstrap_iterations = count(
            "bootstrap_iterations",
            self.bootstrap_iterations,
            1e6,
            o.bootstrap_iterations,
        )?;
        o.seed = count("seed", self.seed, 9e15, o.seed)?;
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
}

/// A dotted key: non-empty parts.
fn dotted(s: &str) -> bool {
    !s.is_empty() && s.split('.').all(|p| !p.is_empty())
}

fn parse_parameters(
    items: Vec<ParameterFile>,
    file: &str,
    base: &toml::Table,
) -> Result<Vec<Parameter>> {
    if items.is_empty() {
        return Err(Error::invalid(
            file,
            "parameter",
            "[]",
            allowed("parameter", FieldProblem::Wrong),
        ));
    }
    let mut out: Vec<Parameter> = Vec::new();
    for (k, t) in items.into_iter().enumerate() {
        let f = |name: &str| format!("parameter.{k}.{name}");
        let key = t.key;
        if !dotted(&key) {
            return Err(Error::invalid(
                file,
                f("key"),
                format!("\"{key}\""),
                allowed("parameter.key", FieldProblem::Wrong),
            ));
        }
        if let Some(p) = out.iter().find(|p| crate::scenario::same_key(&p.key, &key)) {
            return Err(Error::invalid(
                file,
                f("key"),
                &key,
                format!("each key at most once (`{}` sets the same value)", p.key),
            ));
        }
        let scale = match t.scale {
            Some(ScaleFile::Log) => Scale::Log,
            None | Some(ScaleFile::Linear) => Scale::Linear,
        };
        let shown = show(&toml::Value::Array(t.bounds.clone()));
        let bounds = match t.bounds.as_slice() {
            [l, u] => match (quantity(l, &key), quantity(u, &key)) {
                (Some(l), Some(u)) if l.is_finite() && u.is_finite() && l < u => (l, u),
                _ => {
                    return Err(Error::invalid(
                        file,
                        f("bounds"),
                        shown,
                        allowed("parameter.bounds", FieldProblem::Wrong),
                    ));
                }
            },
            _ => {
                return Err(Error::invalid(
                    file,
                    f("bounds"),
                    shown,
                    allowed("parameter.bounds", FieldProblem::Wrong),
                ));
            }
        };
        if scale == Scale::Log && !(bounds.0 > 0.0) {
            return Err(Error::invalid(
                file,
                f("bounds"),
                shown,
                "both bounds > 0 for scale = \"log\"",
            ));
        }
        let range = format!("within the bounds [{:e}, {:e}]", bounds.0, bounds.1);
        let base_value = get_dotted(base, &key);
        if let Some(b) = base_value
            && !(b >= bounds.0 && b <= bounds.1)
        {
            return Err(Error::invalid(
                file,
                f("bounds"),
                shown,
                format!("must contain the base scenario's value {key} = {b:e}"),
            ));
        }
        let initial = match &t.initial {
            Some(v) => match quantity(v, &key) {
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
        if let Some(a) = t.also.iter().find(|a| !dotted(a)) {
            return Err(Error::invalid(
                file,
                f("also"),
                format!("\"{a}\""),
                allowed("parameter.also", FieldProblem::Wrong),
            ));
        }
        out.push(Parameter {
            key,
            lower: bounds.0,
            upper: bounds.1,
            scale,
            initial,
            also: t.also,
        });
    }
    Ok(out)
}

impl DesignFile {
    /// Check the candidates; their values take the unit of the design key (by default
    /// `frequency`, the base's frequency key).
    fn check(self, file: &str, frequency: &str) -> Result<DesignSpec> {
        let key = self.key.unwrap_or_else(|| frequency.into());
        if !key.contains('.') {
            return Err(Error::invalid(
                file,
                "design.key",
                format!("\"{key}\""),
                allowed("design.key", FieldProblem::Wrong),
            ));
        }
        let nums = |name: &str, a: &[toml::Value], unit_key: &str| -> Result<Vec<f64>> {
            let field = format!("design.{name}");
            let shown = || show(&toml::Value::Array(a.to_vec()));
            if a.is_empty() {
                return Err(Error::invalid(
                    file,
                    &field,
                    shown(),
                    allowed(&field, FieldProblem::Wrong),
                ));
            }
            a.iter()
                .map(|x| {
                    quantity(x, unit_key)
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| Error::invalid(file, &field, shown(), "finite numbers"))
                })
                .collect()
        };
        let (name, values) = match (&self.values, &self.frequencies) {
            (Some(v), _) => ("values", v),
            (None, Some(v)) => ("frequencies", v),
            (None, None) => {
                return Err(Error::invalid(
                    file,
                    "design.values",
                    "(missing)",
                    format!(
                        "required: {}",
                        allowed("design.values", FieldProblem::Missing)
                    ),
                ));
            }
        };
        let values = nums(name, values, &key)?;
        let control_values = match (&self.control_linspace, &self.control) {
            (Some(a), _) => {
                let a = nums("control_linspace", a, "")?;
                if a.len() != 3 || !(a[2] >= 2.0 && a[2].fract() == 0.0 && a[2] <= 1e5) {
                    return Err(Error::invalid(
                        file,
                        "design.control_linspace",
                        show(&toml::Value::Array(
                            a.iter().map(|x| toml::Value::Float(*x)).collect(),
                        )),
                        "[start, end, n] with an integer n >= 2",
                    ));
                }
                Some(crate::study::linspace(a[0], a[1], a[2] as usize))
            }
            (None, Some(c)) => Some(nums("control", c, "")?),
            (None, None) => None,
        };
        Ok(DesignSpec {
            key,
            values,
            control_values,
        })
    }
}

/// Raw columns: (header, columns of numbers as text-parsed f64), from a CSV file or an
/// inline table.
fn parse_data(
    data: &toml::Value,
    observed: Option<&[String]>,
    dir: &Path,
    file: &str,
    fit: &FitOptions,
) -> Result<(Measured, Option<PathBuf>)> {
    let (header, rows, data_name, data_file) = match data {
        toml::Value::String(s) if !s.trim().is_empty() => {
            let p = dir.join(s);
            let name = p.display().to_string();
            let t = read_table(CsvReader::open(&p, Header::Required)?)?;
            (t.header, t.rows, name, Some(p))
        }
        toml::Value::Table(t) => {
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
                        quantity(x, k).ok_or_else(|| {
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
                show(other),
                allowed("data", FieldProblem::Wrong),
            ));
        }
    };
    let observed_filter: Option<&[String]> = match observed {
        Some([]) => {
            return Err(Error::invalid(
                file,
                "observed",
                "[]",
                allowed("observed", FieldProblem::Wrong),
            ));
        }
        other => other,
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
            if observed_filter.as_ref().is_none_or(|f| f.contains(h)) {
                obs_cols.push(c);
            }
        }
    }
    if let Some(f) = observed_filter {
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
        if let Some(name) = h.strip_prefix("sigma_")
            && !header.iter().any(|x| x == name)
        {
            return Err(Error::invalid(
                &data_name,
                "header",
                h,
                "sigma_<name> needs an observed column <name>",
            ));
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

/// Identification defaults to a leakage-free analysis (model.md section 6.1) for a
/// half-space scenario with a smooth compression law and no `[analysis]` table:
/// `linear_reference` when `p0 > 0`, `pulse_inversion` otherwise (a power law has no
/// linearisation at `p0 = 0`). Rigid compression and bar stacks keep `band_peak`.
fn default_analysis(base: &mut toml::Table) {
    if base.contains_key("analysis") || base.contains_key("model") {
        return;
    }
    let Some(toml::Value::Table(interface)) = base.get("interface") else {
        return;
    };
    let law = match interface.get("compression") {
        Some(toml::Value::Table(c)) => c.get("law").and_then(|v| v.as_str()).unwrap_or("rigid"),
        _ => "rigid",
    };
    if law == "rigid" {
        return;
    }
    let p0 = interface
        .get("static_pressure")
        .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        .unwrap_or(0.0);
    let method = if p0 > 0.0 {
        "linear_reference"
    } else {
        "pulse_inversion"
    };
    let mut t = toml::Table::new();
    t.insert("method".into(), toml::Value::String(method.into()));
    base.insert("analysis".into(), toml::Value::Table(t));
}

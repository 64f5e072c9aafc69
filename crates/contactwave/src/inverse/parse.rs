//! The identification file format: [`IdentifySpec::load`] and
//! [`IdentifySpec::from_table`] read the TOML (`base`, `data`, `observed`, `[set]`,
//! `[[parameter]]`, `[fit]`, `[design]`) and the measured data (a CSV file or an inline
//! table), check them, and check every row against the forward model at the starting
//! values. The format is described in the `inverse` module doc.

use super::model::{toml_number, Model};
use super::spec::{DesignSpec, FitOptions, IdentifySpec, Measured, Observed, Parameter, Scale};
use crate::error::{Error, Result};
use crate::model;
use crate::scenario::{apply_set, parse_toml, set_dotted};
use std::path::{Path, PathBuf};

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
    number(cur)
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
    /// assert!(err.to_string().contains("parameter[0].key"));
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
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
        crate::scenario::units::to_si(&mut base_table, &base_file)?;
        default_analysis(&mut base_table);
        // the base (with overrides) must be a valid scenario
        model::plan_valid(base_table.clone(), &base)?;

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
                .and_then(|_| model::plan_valid(table, &spec.base))
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
            Some(toml::Value::Array(a)) if a.len() == 2 => {
                match (quantity(&a[0], &key), quantity(&a[1], &key)) {
                    (Some(l), Some(u)) if l.is_finite() && u.is_finite() && l < u => (l, u),
                    _ => return Err(Error::invalid(
                        file,
                        f("bounds"),
                        show(&t["bounds"]),
                        "[lower, upper], finite numbers (SI) or unit strings with lower < upper",
                    )),
                }
            }
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
    // the design values take the unit of the design key (a frequency by default)
    let design_key = t
        .get("key")
        .and_then(|v| v.as_str())
        .unwrap_or("incident.frequency");
    let nums = |name: &str, v: &toml::Value| -> Result<Vec<f64>> {
        let unit_key = if name == "values" || name == "frequencies" {
            design_key
        } else {
            ""
        };
        match v {
            toml::Value::Array(a) if !a.is_empty() => a
                .iter()
                .map(|x| {
                    quantity(x, unit_key)
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| {
                            Error::invalid(
                                file,
                                format!("design.{name}"),
                                show(v),
                                "finite numbers",
                            )
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

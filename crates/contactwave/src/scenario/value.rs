//! TOML text -> table -> spec, with error messages that name the file, the field path,
//! the value and what is allowed; and dotted-key overrides used by sweeps.

use super::spec::ScenarioSpec;
use crate::error::{Error, Result};
use std::path::Path;

/// Read a TOML file into a table (errors name the file).
pub fn read_table(path: &Path) -> Result<toml::Table> {
    // a TOML table takes about ten times its text in memory
    crate::budget::check_file(path, "<file size>", 10.0)?;
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_toml(&text, &path.display().to_string())
}

/// Parse TOML text into a table (syntax errors name the line and column).
pub fn parse_toml(text: &str, file: &str) -> Result<toml::Table> {
    text.parse::<toml::Table>().map_err(|e| {
        let msg = e.message().replace('\n', " ");
        let loc = e
            .span()
            .map(|s| {
                let line = text[..s.start.min(text.len())].matches('\n').count() + 1;
                format!("line {line}: ")
            })
            .unwrap_or_default();
        Error::Parse {
            file: file.to_string(),
            message: format!("{loc}TOML syntax error: {msg}"),
        }
    })
}

/// Deserialize a table into a [`ScenarioSpec`], naming the field path on failure.
/// Unit strings (`frequency = "1 MHz"`) are converted to SI first ([`super::units`]).
pub fn table_to_spec(table: toml::Table, file: &str) -> Result<ScenarioSpec> {
    deserialize_scenario(table, file, half_space_hint)
}

/// What a half-space scenario's key takes where serde's own message would not say it
/// ([`deserialize_scenario`]).
fn half_space_hint(key: &str, problem: FieldProblem) -> Option<String> {
    use FieldProblem::{Missing, Wrong};
    Some(match (key, problem) {
        ("medium", Missing) => {
            "a [medium] table: a material preset, or youngs_modulus, poisson_ratio and density \
             (a half-space scenario; a bar stack or a 2D scenario begins with [model] and its \
             kind = \"bar_stack\" or \"solid_2d\")"
                .into()
        }
        ("interface", Missing) => {
            "an [interface] table: its static_pressure (Pa) and contact laws".into()
        }
        ("solver.samples_per_period", Wrong) => whole_numbers(super::spec::SAMPLES_PER_PERIOD),
        _ => return None,
    })
}

/// What a count in `range` takes, as the field hints say it.
pub(crate) fn whole_numbers(range: std::ops::RangeInclusive<usize>) -> String {
    format!("a whole number from {} to {}", range.start(), range.end())
}

/// Deserialize a scenario table of any kind into its spec `T` (half-space, bar stack,
/// 2D), naming the field path on failure; unit strings are converted to SI first.
/// `hint(key, problem)` gives what is allowed at a key (without array indices:
/// `model.order`, `receiver.count`) where serde's own words would not say it (a count's
/// range, a required table); `None` keeps serde's message.
pub fn deserialize_scenario<T: serde::de::DeserializeOwned>(
    mut table: toml::Table,
    file: &str,
    hint: impl Fn(&str, FieldProblem) -> Option<String>,
) -> Result<T> {
    super::units::to_si(&mut table, file)?;
    // a count written as a whole float (`order = 6.0`, `crack_every = 1e3`) is that count:
    // each refused one is made an integer and the table read again (once per such key)
    let result = loop {
        let value = toml::Value::Table(table.clone());
        match serde_path_to_error::deserialize::<_, T>(value) {
            Err(e) if whole_float_to_integer(&mut table, &e) => continue,
            other => break other,
        }
    };
    result.map_err(|e| match field_error(e, &table, file, hint, false) {
        Ok(err) => err,
        Err((path, inner)) => Error::Parse {
            file: file.to_string(),
            message: if path.is_empty() {
                inner
            } else {
                format!("field `{path}`: {inner}")
            },
        },
    })
}

/// The keys inside law tables that `message` begins with (`law::param::law_error`: `in
/// law key `points[2]`: ...`, nested laws one after the other), each as its name and
/// array index, taken off the message.
fn law_keys(message: &mut String) -> Vec<(String, Option<String>)> {
    let mut keys = Vec::new();
    while let Some((inner, rest)) = message
        .strip_prefix(crate::law::param::LAW_KEY_PREFIX)
        .and_then(|m| m.split_once("`: "))
    {
        for part in inner.split('.') {
            keys.push(
                match part.strip_suffix(']').and_then(|p| p.split_once('[')) {
                    Some((name, i)) => (name.to_string(), Some(i.to_string())),
                    None => (part.to_string(), None),
                },
            );
        }
        *message = rest.to_string();
    }
    keys
}

/// Where `e` refuses a float for a whole number and the float at its key is whole (and
/// exactly representable), write it there as an integer; whether it did.
fn whole_float_to_integer(
    table: &mut toml::Table,
    e: &serde_path_to_error::Error<toml::de::Error>,
) -> bool {
    let mut message = e.inner().to_string();
    let mut keys: Vec<String> = Vec::new();
    for s in e.path().iter() {
        match s {
            serde_path_to_error::Segment::Seq { index } => keys.push(index.to_string()),
            serde_path_to_error::Segment::Map { key } => keys.push(key.clone()),
            _ => {}
        }
    }
    // inside a law table: its own key (`law::param::law_error`)
    for (name, index) in law_keys(&mut message) {
        keys.push(name);
        keys.extend(index);
    }
    let integer = ["expected u", "expected i"]
        .iter()
        .any(|t| message.contains(t));
    if !(message.starts_with("invalid type: floating point") && integer) {
        return false;
    }
    let mut cur: Option<&mut toml::Value> = None;
    for k in &keys {
        cur = match cur {
            None => table.get_mut(k),
            Some(toml::Value::Table(t)) => t.get_mut(k),
            Some(toml::Value::Array(a)) => k.parse::<usize>().ok().and_then(|i| a.get_mut(i)),
            Some(_) => None,
        };
        if cur.is_none() {
            return false;
        }
    }
    match cur {
        Some(v @ toml::Value::Float(_)) => {
            let x = v.as_float().unwrap_or(f64::NAN);
            if x.fract() == 0.0 && x.abs() <= 9.007_199_254_740_992e15 {
                *v = toml::Value::Integer(x as i64);
                true
            } else {
                false
            }
        }
        _ => false,
    }
}

/// Set `key` (dotted, e.g. `incident.xi`) to `value` in `table`, creating tables on the
/// way. Setting `incident.xi` removes `incident.amplitude` and vice versa (they are two
/// ways to give the same quantity).
pub fn set_dotted(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<()> {
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(Error::invalid(
            "<sweep>",
            "parameter",
            key,
            "a dotted scenario key such as `incident.xi`",
        ));
    }
    let mut cur = table;
    let mut k = 0;
    while k + 1 < parts.len() {
        let p = parts[k];
        k += 1;
        let mut entry = cur
            .entry(p.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        // `interface.1.compression`: an index into an array of tables; none before a key
        // where the array holds one table (`source.angle` is `source.0.angle`)
        if let toml::Value::Array(items) = entry {
            let index = parts.get(k).and_then(|i| i.parse::<usize>().ok());
            let len = items.len();
            let numbers = items.iter().all(|v| !v.is_table());
            // `crack.0.start.1`: one number of an array of numbers
            if let Some(i) = index.filter(|&i| numbers && i < len && k + 1 == parts.len()) {
                items[i] = value;
                return Ok(());
            }
            if numbers && len > 0 {
                return Err(Error::invalid(
                    "<sweep>",
                    "parameter",
                    key,
                    format!(
                        "`{p}` is an array of {len} numbers: follow it with an index from 0 to \
                         {} (or, for a point [x, z], `.x` or `.z`)",
                        len - 1
                    ),
                ));
            }
            let at = match index {
                Some(i) if i < len && k + 1 < parts.len() => {
                    k += 1;
                    Some(i)
                }
                None if len == 1 => Some(0),
                _ => None,
            };
            match at {
                Some(i) => entry = &mut items[i],
                None => {
                    return Err(Error::invalid(
                        "<sweep>",
                        "parameter",
                        key,
                        match len {
                            0 => format!("`{p}` is an empty array: there is no table to set"),
                            _ => format!(
                                "`{p}` is an array of {len} tables: follow it with an index \
                                 from 0 to {} and a key",
                                len - 1
                            ),
                        },
                    ));
                }
            }
        }
        cur = match entry {
            toml::Value::Table(t) => t,
            _ => {
                return Err(Error::invalid(
                    "<sweep>",
                    "parameter",
                    key,
                    format!("`{p}` is not a table in the base scenario"),
                ));
            }
        };
    }
    let last = parts[parts.len() - 1];
    if key == "incident.xi" {
        cur.remove("amplitude");
    }
    if key == "incident.amplitude" {
        cur.remove("xi");
    }
    // a friction coefficient replaces the one the table spells the other way
    if let Some(other) = other_spelling(&parts) {
        cur.remove(other);
    }
    cur.insert(last.to_string(), value);
    Ok(())
}

/// The other name of the key whose dotted parts are `parts`, where the scenario files take
/// two (a tangential law's `mu` and `friction`).
fn other_spelling(parts: &[&str]) -> Option<&'static str> {
    match parts {
        [.., "tangential", "mu"] => Some("friction"),
        [.., "tangential", "friction"] => Some("mu"),
        _ => None,
    }
}

/// Whether two dotted keys set the same value: equal, or one quantity's two spellings
/// (`crack.0.tangential.mu` and `crack.0.tangential.friction`), or one with and one
/// without the index of a one-table array (`source.angle` and `source.0.angle`: where
/// the array holds several tables the index-free key is refused when it is set), or a
/// point's coordinate by index or by name (`crack.0.end.0` and `crack.0.end.x`).
pub fn same_key(a: &str, b: &str) -> bool {
    a == b || canonical_key(a) == canonical_key(b)
}

/// The parts of the dotted key `key` in one spelling: a table array's index 0 dropped
/// (an index ends no key: a number array's index does), a point's last index as its
/// coordinate name (`0` as `x`, `1` as `z`), a friction coefficient as `friction`.
fn canonical_key(key: &str) -> Vec<&str> {
    let parts: Vec<&str> = key.split('.').collect();
    let last = parts.len().saturating_sub(1);
    let mut out = Vec::with_capacity(parts.len());
    for (k, &p) in parts.iter().enumerate() {
        let part = match (k == last, p) {
            (false, "0") if k > 0 => continue,
            (true, "0") if k > 0 => "x",
            (true, "1") if k > 0 => "z",
            _ => p,
        };
        out.push(part);
    }
    if other_spelling(&parts) == Some("friction")
        && let Some(l) = out.last_mut()
    {
        *l = "friction";
    }
    out
}

/// Write the `[set]` table of a sweep or identification file (dotted keys, any TOML value)
/// into a base scenario table. Errors name `file` and the field `set."<key>"`.
/// A unit string at a key with a dimension (`"incident.frequency" = "2 MHz"`) is converted
/// to SI.
pub fn apply_set(table: &mut toml::Table, set: &toml::Table, file: &str) -> Result<()> {
    for (key, value) in set {
        let value = match value {
            toml::Value::String(s) => match super::units::dimension_of_key(key) {
                Some(dim) => toml::Value::Float(super::units::parse(s, dim).map_err(|why| {
                    Error::invalid(file, format!("set.\"{key}\""), format!("\"{s}\""), why)
                })?),
                None => value.clone(),
            },
            _ => value.clone(),
        };
        set_dotted(table, key, value).map_err(|e| match e {
            Error::Invalid { value, allowed, .. } => Error::Invalid {
                file: file.to_string(),
                field: format!("set.\"{key}\""),
                value,
                allowed,
            },
            other => other,
        })?;
    }
    Ok(())
}

/// The base scenario of a sweep or identification file `file`: `base` (a path relative to
/// `dir`, the file's folder) read and parsed, with the file's `[set]` overrides written in.
/// An empty `base` is an error naming `file` and saying what `base` must be (`allowed`).
pub fn read_base(
    file: &str,
    dir: &Path,
    base: &str,
    set: Option<&toml::Table>,
    allowed: String,
) -> Result<(std::path::PathBuf, toml::Table)> {
    if base.trim().is_empty() {
        return Err(Error::invalid(file, "base", "\"\"", allowed));
    }
    let base = dir.join(base);
    let text = std::fs::read_to_string(&base).map_err(|e| Error::io(&base, e))?;
    let mut table = parse_toml(&text, &base.display().to_string())?;
    // `[set]`: fixed overrides of the base (any TOML value, e.g. another contact law);
    // `interface.0.compression` indexes an array of tables
    if let Some(set) = set {
        apply_set(&mut table, set, file)?;
    }
    Ok((base, table))
}

/// What went wrong at a field of a file read by [`deserialize_format`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldProblem {
    /// A required field is absent.
    Missing,
    /// A key the format does not have (the field is the unknown key; describe its table).
    Unknown,
    /// The value has the wrong shape (a string for a number, a number for a table, ...).
    Wrong,
}

/// Deserialize the table of a sweep or identification file into its format type `T`
/// (serde structs with `deny_unknown_fields`). A failure becomes an [`Error::Invalid`]
/// naming `file`, the field (`axis.1.values`), the value as written (or `(missing)`) and
/// what is allowed there: `allowed(key, problem)`, where `key` is the field without its
/// array indices (`axis.values`; for an unknown key, the table that holds it: `axis`,
/// or `""` at the top).
pub fn deserialize_format<T: serde::de::DeserializeOwned>(
    table: &toml::Table,
    file: &str,
    allowed: impl Fn(&str, FieldProblem) -> String,
) -> Result<T> {
    let value = toml::Value::Table(table.clone());
    serde_path_to_error::deserialize::<_, T>(value).map_err(|e| {
        field_error(e, table, file, |k, p| Some(allowed(k, p)), true).unwrap_or_else(|(_, m)| {
            Error::Parse {
                file: file.to_string(),
                message: m,
            }
        })
    })
}

/// A deserializer's failure as an [`Error::Invalid`] naming `file`, the field
/// (`axis.1.values`), the value as written (or `(missing)`) and `allowed(key, problem)`;
/// where `allowed` has nothing to say, the field (dotted, `""` at the top) and serde's
/// message in plain words (`Err`). A wrong value's message ends with serde's words in
/// brackets when `explain` is set.
fn field_error(
    e: serde_path_to_error::Error<toml::de::Error>,
    table: &toml::Table,
    file: &str,
    allowed: impl Fn(&str, FieldProblem) -> Option<String>,
    explain: bool,
) -> std::result::Result<Error, (String, String)> {
    let mut path: Vec<String> = Vec::new();
    let mut key: Vec<String> = Vec::new();
    for s in e.path().iter() {
        match s {
            serde_path_to_error::Segment::Seq { index } => {
                if let Some(last) = path.last_mut() {
                    last.push_str(&format!(".{index}"));
                }
            }
            serde_path_to_error::Segment::Map { key: k }
            | serde_path_to_error::Segment::Enum { variant: k } => {
                path.push(k.clone());
                key.push(k.clone());
            }
            serde_path_to_error::Segment::Unknown => {}
        }
    }
    let mut message = e.into_inner().to_string();
    // a law table's parameter: its key inside the table (`law::param::law_error`),
    // `points[2]` as `points.2`
    for (name, index) in law_keys(&mut message) {
        path.push(match &index {
            Some(i) => format!("{name}.{i}"),
            None => name.clone(),
        });
        key.push(name);
    }
    // (toml's own account of the keys, which the path already gives)
    if let Some(at) = message.find("\nin `") {
        message.truncate(at);
    }
    let plain = super::units::plain_serde_message(&message);
    let quoted = |prefix: &str| {
        message
            .strip_prefix(prefix)
            .and_then(|m| m.split('`').next())
            .map(str::to_string)
    };
    let join = |v: &[String]| v.join(".");
    if let Some(name) = quoted("missing field `") {
        let table_path = join(&path);
        path.push(name.clone());
        key.push(name);
        let Some(what) = allowed(&join(&key), FieldProblem::Missing) else {
            return Err((table_path, plain));
        };
        return Ok(Error::invalid(
            file,
            join(&path),
            "(missing)",
            format!("required: {what}"),
        ));
    }
    let shown = value_at(table, &path)
        .map(|v| v.to_string())
        .unwrap_or_else(|| "?".into());
    if message.starts_with("unknown field `") {
        // serde's path ends at the unknown key itself
        key.pop();
        let Some(what) = allowed(&join(&key), FieldProblem::Unknown) else {
            return Err((join(&path), plain));
        };
        return Ok(Error::invalid(
            file,
            join(&path),
            shown,
            format!("unknown key; {what}"),
        ));
    }
    let Some(what) = allowed(&join(&key), FieldProblem::Wrong) else {
        return Err((join(&path), plain));
    };
    Ok(Error::invalid(
        file,
        join(&path),
        shown,
        if explain {
            format!("{what} ({plain})")
        } else {
            what
        },
    ))
}

/// The value at a path of `deserialize_format` (`axis.1`, `values`): keys, each with
/// optional `.i` indices.
fn value_at<'a>(table: &'a toml::Table, path: &[String]) -> Option<&'a toml::Value> {
    let mut cur: Option<&toml::Value> = None;
    for part in path {
        let mut pieces = part.split('.');
        let name = pieces.next()?;
        let mut v = match cur {
            None => table.get(name)?,
            Some(c) => c.get(name)?,
        };
        for idx in pieces {
            v = v.get(idx.parse::<usize>().ok()?)?;
        }
        cur = Some(v);
    }
    cur
}

#[cfg(test)]
mod tests {
    use super::{same_key, set_dotted};

    /// A friction coefficient set under either name replaces the one the table has under
    /// the other (a table with both is refused by the law), and the two names are one key.
    #[test]
    fn a_friction_coefficient_is_one_key_under_two_names() {
        let mut t: toml::Table =
            toml::from_str("[[crack]]\ntangential = { law = \"coulomb\", friction = 0.3 }\n")
                .unwrap();
        set_dotted(&mut t, "crack.0.tangential.mu", toml::Value::Float(0.1)).unwrap();
        let tangential = &t["crack"].as_array().unwrap()[0]["tangential"];
        assert_eq!(tangential.get("mu").and_then(|v| v.as_float()), Some(0.1));
        assert!(tangential.get("friction").is_none());
        set_dotted(&mut t, "crack.tangential.friction", toml::Value::Float(0.2)).unwrap();
        let tangential = &t["crack"].as_array().unwrap()[0]["tangential"];
        assert_eq!(
            tangential.get("friction").and_then(|v| v.as_float()),
            Some(0.2)
        );
        assert!(tangential.get("mu").is_none());
        assert!(same_key(
            "crack.0.tangential.mu",
            "crack.0.tangential.friction"
        ));
        assert!(same_key(
            "interface.tangential.friction",
            "interface.tangential.mu"
        ));
        assert!(!same_key(
            "crack.0.tangential.mu",
            "crack.1.tangential.friction"
        ));
        assert!(!same_key(
            "crack.0.traction.mu",
            "crack.0.traction.friction"
        ));
        // an index-free key and its index 0 (the one table of an array), a point's
        // coordinate by index or name
        assert!(same_key("source.angle", "source.0.angle"));
        assert!(same_key(
            "crack.tangential.mu",
            "crack.0.tangential.friction"
        ));
        assert!(same_key("crack.0.end.1", "crack.end.z"));
        assert!(!same_key("source.1.angle", "source.angle"));
        assert!(!same_key("crack.0.end.x", "crack.0.end.z"));
        assert!(!same_key("crack.0.length", "crack.0.start.x"));
    }

    /// An array of one table takes keys with or without its index; one of several needs
    /// the index, and an index past the end is an error naming the last one.
    #[test]
    fn dotted_keys_reach_arrays_of_tables() {
        let mut t: toml::Table =
            toml::from_str("[[source]]\nx0 = 1.0\n[[layer]]\n[[layer]]\n").unwrap();
        set_dotted(&mut t, "source.angle", toml::Value::Float(30.0)).unwrap();
        set_dotted(&mut t, "source.0.x1", toml::Value::Float(2.0)).unwrap();
        let s = &t["source"].as_array().unwrap()[0];
        assert_eq!(s["angle"].as_float(), Some(30.0));
        assert_eq!(s["x1"].as_float(), Some(2.0));
        set_dotted(&mut t, "layer.1.density", toml::Value::Float(7.8e3)).unwrap();
        assert_eq!(t["layer"][1]["density"].as_float(), Some(7.8e3));
        let e = set_dotted(&mut t, "layer.density", toml::Value::Float(1.0)).unwrap_err();
        assert!(e.to_string().contains("an index from 0 to 1"), "{e}");
        let e = set_dotted(&mut t, "source.1.x0", toml::Value::Float(1.0)).unwrap_err();
        assert!(e.to_string().contains("from 0 to 0"), "{e}");
    }
}

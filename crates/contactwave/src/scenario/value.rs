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
pub fn table_to_spec(mut table: toml::Table, file: &str) -> Result<ScenarioSpec> {
    super::units::to_si(&mut table, file)?;
    let value = toml::Value::Table(table);
    serde_path_to_error::deserialize::<_, ScenarioSpec>(value).map_err(|e| {
        let path = e.path().to_string();
        let inner = super::units::plain_serde_message(&e.into_inner().to_string());
        Error::Parse {
            file: file.to_string(),
            message: if path.is_empty() || path == "." {
                inner
            } else {
                format!("field `{path}`: {inner}")
            },
        }
    })
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
        // `interface.1.compression`: an index into an array of tables
        if let toml::Value::Array(items) = entry {
            let index = parts.get(k).and_then(|i| i.parse::<usize>().ok());
            let len = items.len();
            match index.and_then(|i| items.get_mut(i)) {
                Some(item) if k + 1 < parts.len() => {
                    k += 1;
                    entry = item;
                }
                _ => {
                    return Err(Error::invalid(
                        "<sweep>",
                        "parameter",
                        key,
                        format!(
                            "`{p}` is an array of {len} tables: follow it with an index \
                             0..{len} and a key"
                        ),
                    ))
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
                ))
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
    cur.insert(last.to_string(), value);
    Ok(())
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

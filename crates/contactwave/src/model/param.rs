//! Parameters of a template: dotted scenario keys resolved once, then set as numbers.

use super::fields::Fields;
use crate::error::{Error, Result};
use crate::scenario::set_dotted;

/// A parameter of a template: a dotted scenario key (e.g. `incident.xi`) resolved by
/// [`super::Template::param`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Param {
    key: String,
    /// `true`: a number of the spec reached by a typed setter; `false`: a key the spec
    /// does not hold as it stands (e.g. a parameter of another law variant), written into
    /// the scenario table and validated with it.
    typed: bool,
}

impl Param {
    /// The dotted key.
    pub fn key(&self) -> &str {
        &self.key
    }
}

/// Whether a key is a count in the scenario format (written as a TOML integer when the
/// value is integral; every other key takes a float).
pub fn wants_integer(key: &str) -> bool {
    key == "solver.samples_per_period"
}

/// The TOML value a sweep or an identification writes for `key`.
pub fn toml_number(key: &str, v: f64) -> toml::Value {
    if wants_integer(key) && v.fract() == 0.0 && v.abs() < 9.0e15 {
        toml::Value::Integer(v as i64)
    } else {
        toml::Value::Float(v)
    }
}

/// The part of a template that every kind shares: the table as given, its typed spec, and
/// the resolution of keys into [`Param`]s and of values into specs.
#[derive(Debug, Clone)]
pub struct ParamTable<S> {
    file: String,
    table: toml::Table,
    /// The spec of the table as given; `None` when the table is not a spec by itself
    /// (e.g. a sweep's base without a key that every point sets): every key then goes
    /// through the table.
    spec: Option<S>,
    to_spec: fn(toml::Table, &str) -> Result<S>,
}

impl<S: Fields + Clone> ParamTable<S> {
    /// The table as given (`file` names it in errors) and the conversion from a table to
    /// a spec.
    pub fn new(
        file: &str,
        table: toml::Table,
        to_spec: fn(toml::Table, &str) -> Result<S>,
    ) -> Self {
        let spec = to_spec(table.clone(), file).ok();
        ParamTable {
            file: file.to_string(),
            table,
            spec,
            to_spec,
        }
    }

    /// The table as given.
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// The spec as given, or its error.
    pub fn spec(&self) -> Result<S> {
        match &self.spec {
            Some(s) => Ok(s.clone()),
            None => (self.to_spec)(self.table.clone(), &self.file),
        }
    }

    /// Resolve `key`: a typed number of the spec, or else a key the table can take (its
    /// value is then checked when a model is built). A malformed key, or one that runs
    /// through a value that is not a table, is an error naming it.
    pub fn param(&self, key: &str) -> Result<Param> {
        let parts: Vec<&str> = key.split('.').collect();
        let typed = match self.spec.clone() {
            Some(mut spec) => !parts.iter().any(|p| p.is_empty()) && spec.slot(&parts).is_some(),
            None => false,
        };
        if typed {
            return Ok(Param {
                key: key.to_string(),
                typed: true,
            });
        }
        let mut t = self.table.clone();
        set_dotted(&mut t, key, toml_number(key, 0.0))?;
        Ok(Param {
            key: key.to_string(),
            typed: false,
        })
    }

    /// The spec with `values` set. Typed parameters are written by their setters; the
    /// others go through the table and its validation, as if written in the file.
    pub fn spec_with(&self, values: &[(&Param, f64)]) -> Result<S> {
        let mut spec = match &self.spec {
            Some(spec) if values.iter().all(|(p, _)| p.typed) => spec.clone(),
            _ => {
                let mut t = self.table.clone();
                for (p, v) in values.iter().filter(|(p, _)| !p.typed) {
                    set_dotted(&mut t, &p.key, toml_number(&p.key, *v))?;
                }
                (self.to_spec)(t, &self.file)?
            }
        };
        for (p, v) in values.iter().filter(|(p, _)| p.typed) {
            let parts: Vec<&str> = p.key.split('.').collect();
            match spec.slot(&parts) {
                Some(slot) => slot.set(*v, &self.file, &p.key)?,
                None => {
                    return Err(Error::invalid(
                        &self.file,
                        &p.key,
                        v,
                        "is not a number of this scenario (another parameter changed its \
                         kind of law)",
                    ));
                }
            }
        }
        Ok(spec)
    }
}

//! The forward model of an identification: [`Model`] maps parameter values (or scaled
//! coordinates) to the scenario of each measured row, runs it, and returns the model curve
//! and the weighted residuals `(model - y) / sigma`. The base scenario is planned once
//! ([`crate::model::Template`]); each forward run sets the row's conditions and the
//! parameter values on it and runs on the [`Executor`].

use super::spec::IdentifySpec;
use crate::analysis::Summary;
use crate::error::{Error, Result};
use crate::model::{self, Model as ForwardModel, Param, Template};
use crate::run::{Executor, Workspaces};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// A value for `key` in a scenario table: an integer where the format wants one (and the
/// value is integral), a float otherwise.
pub(crate) use crate::model::toml_number;

/// The forward model of an identification: scenario of row `i` at parameter values `p`,
/// and the weighted residuals. Counts its forward runs.
pub struct Model<'a> {
    /// The spec.
    pub spec: &'a IdentifySpec,
    runs: AtomicUsize,
    /// Forward runs that failed numerically (or gave a non-finite observed value).
    failures: AtomicUsize,
    /// The first such failure: `row N: MESSAGE`.
    first_failure: Mutex<Option<String>>,
    /// The base scenario, planned once: every forward run sets numbers on it.
    template: Arc<dyn Template>,
    /// Keys resolved to parameters of the template so far.
    params: Mutex<Vec<(String, Param)>>,
    /// The forward runs' workspaces, one per worker, kept from run to run.
    workspaces: Workspaces<model::Workspace>,
}

impl<'a> Model<'a> {
    /// A model over a spec.
    pub fn new(spec: &'a IdentifySpec) -> Self {
        Model {
            spec,
            runs: AtomicUsize::new(0),
            failures: AtomicUsize::new(0),
            first_failure: Mutex::new(None),
            template: model::plan(spec.base_table.clone(), &spec.base),
            params: Mutex::new(Vec::new()),
            workspaces: Workspaces::new(),
        }
    }

    /// The template's parameter for `key` (resolved once).
    fn param(&self, key: &str) -> Result<Param> {
        let mut ps = self.params.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, p)) = ps.iter().find(|(k, _)| k == key) {
            return Ok(p.clone());
        }
        let p = self.template.param(key)?;
        ps.push((key.to_string(), p.clone()));
        Ok(p)
    }

    /// The base scenario with parameter `p`'s keys (its key and its `also` keys) set to
    /// its starting value, through the same typed setters as every forward run.
    pub(super) fn at_start(&self, p: &super::spec::Parameter) -> Result<Arc<dyn ForwardModel>> {
        let params = std::iter::once(&p.key)
            .chain(&p.also)
            .map(|k| self.param(k))
            .collect::<Result<Vec<_>>>()?;
        let refs: Vec<(&Param, f64)> = params.iter().map(|q| (q, p.initial)).collect();
        self.template.build(&refs)
    }

    /// Forward runs so far.
    pub fn forward_runs(&self) -> usize {
        self.runs.load(Ordering::Relaxed)
    }

    /// Forward runs so far that failed numerically or gave a non-finite observed value
    /// (the fit gives such a point a prohibitive cost and goes on).
    pub fn failed_runs(&self) -> usize {
        self.failures.load(Ordering::Relaxed)
    }

    /// The first failed forward run, `row N: MESSAGE` (`None` if none failed).
    pub fn first_failure(&self) -> Option<String> {
        self.first_failure
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone()
    }

    /// Count a failed forward run of row `i` (0-based) and keep the first message.
    fn record_failure(&self, i: usize, message: impl std::fmt::Display) {
        self.failures.fetch_add(1, Ordering::Relaxed);
        let mut first = self.first_failure.lock().unwrap_or_else(|p| p.into_inner());
        if first.is_none() {
            *first = Some(format!("row {}: {message}", i + 1));
        }
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

    /// The model of row `i` with `conditions` overridden by `extra` (key, value) pairs, at
    /// parameter values `values`: conditions, then the other extras, then the parameters
    /// (each key and its `also` keys) are set on the template.
    fn build(
        &self,
        i: usize,
        values: &[f64],
        extra: &[(String, f64)],
    ) -> Result<Arc<dyn ForwardModel>> {
        let spec = self.spec;
        let m = &spec.measured;
        let mut set: Vec<(Param, f64)> = Vec::new();
        for (k, c) in m.conditions.iter().enumerate() {
            let v = extra
                .iter()
                .find(|(e, _)| e == c)
                .map(|e| e.1)
                .unwrap_or(m.rows[i][k]);
            set.push((self.param(c).map_err(|e| e.in_file(&self.data_name()))?, v));
        }
        for (e, v) in extra {
            if !m.conditions.contains(e) {
                set.push((self.param(e)?, *v));
            }
        }
        for (p, &v) in spec.parameters.iter().zip(values) {
            for key in std::iter::once(&p.key).chain(&p.also) {
                set.push((self.param(key)?, v));
            }
        }
        let refs: Vec<(&Param, f64)> = set.iter().map(|(p, v)| (p, *v)).collect();
        self.template.build(&refs)
    }

    /// The data file (or the identification file, for inline data), for error messages.
    pub(super) fn data_name(&self) -> String {
        self.spec
            .data_file
            .as_ref()
            .unwrap_or(&self.spec.file)
            .display()
            .to_string()
    }

    /// [`Self::scenario`] with the extra `(key, value)` pairs `extra` set (a design's
    /// candidate), its errors as the scenario's own.
    pub(super) fn scenario_with(
        &self,
        i: usize,
        values: &[f64],
        extra: &[(String, f64)],
    ) -> Result<Arc<dyn ForwardModel>> {
        self.build(i, values, extra)
    }

    /// The validated scenario of row `i` at parameter values `values`.
    pub fn scenario(&self, i: usize, values: &[f64]) -> Result<Arc<dyn ForwardModel>> {
        self.build(i, values, &[]).map_err(|e| match e {
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
            // a column whose key the scenario format does not have (`incident.amplitud`):
            // the data's row and key, with the reader's words
            Error::Parse { message, file } => {
                let m = &self.spec.measured;
                match message
                    .strip_prefix("field `")
                    .and_then(|r| r.split_once("`: "))
                    .and_then(|(key, why)| {
                        let k = m.conditions.iter().position(|c| c == key)?;
                        Some((key, m.rows[i][k], why))
                    }) {
                    Some((key, v, why)) => Error::invalid(
                        self.data_name(),
                        format!("row {} -> {key}", i + 1),
                        v,
                        format!("a key of the base scenario ({why})"),
                    ),
                    None => Error::Parse { message, file },
                }
            }
            other => other,
        })
    }

    /// Run row `i` with overrides `extra` and parameter `values`: the summary's observed
    /// keys (other keys may be left out of the run, see [`ForwardModel::summary_for`]).
    pub fn run_with(&self, i: usize, values: &[f64], extra: &[(String, f64)]) -> Result<Summary> {
        let s = self.build(i, values, extra)?;
        self.runs.fetch_add(1, Ordering::Relaxed);
        let keys: Vec<&str> = self
            .spec
            .measured
            .observed
            .iter()
            .map(|o| o.key.as_str())
            .collect();
        let summary = self.workspaces.with(|ws| match &self.spec.records {
            Some(r) => r.forward(&*s, ws),
            None => s.summary_for_in(&keys, ws),
        });
        if let Err(e @ Error::Numerical { .. }) = &summary {
            self.record_failure(i, e);
        }
        summary
    }

    /// Model values `[row][observed]` at scaled coordinates `z`, for the given rows
    /// (forward runs in parallel).
    pub fn curves_at(&self, z: &[f64], rows: &[usize]) -> Result<Vec<Vec<f64>>> {
        let values = self.values(z);
        Executor::new().try_map(rows, |&i| {
            let s = self.run_with(i, &values, &[])?;
            let c: Vec<f64> = self
                .spec
                .measured
                .observed
                .iter()
                .map(|o| s.get(&o.key).unwrap_or(f64::NAN))
                .collect();
            if let Some((o, v)) = self
                .spec
                .measured
                .observed
                .iter()
                .zip(&c)
                .find(|(_, v)| !v.is_finite())
            {
                self.record_failure(i, format!("{} = {v} (not finite)", o.key));
            }
            Ok(c)
        })
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

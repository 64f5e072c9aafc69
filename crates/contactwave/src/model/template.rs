//! The template every kind of scenario shares: a table planned once, its typed parameters,
//! the build cache of its laws and files, and each point validated into the kind's
//! scenario. A kind says how its spec is read and validated ([`FromSpec`]); the rest is
//! here.

use super::{Fields, Model, Param, ParamTable, Template};
use crate::error::Result;
use crate::scenario::BuildCache;
use std::fmt::Debug;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

/// A validated scenario of one kind, built from its spec.
pub trait FromSpec: Model + Sized + 'static {
    /// The kind's serde-level spec, with typed access to its numbers.
    type Spec: Fields + Clone + Debug + Send + Sync;
    /// Name of the kind.
    const KIND: &'static str;
    /// Deserialize a table into the spec (errors name `file` and the field path).
    fn to_spec(table: toml::Table, file: &str) -> Result<Self::Spec>;
    /// Validate a spec; relative paths resolve against `dir`; laws and files through
    /// `cache`.
    fn from_spec(spec: Self::Spec, file: &str, dir: &Path, cache: &BuildCache) -> Result<Self>;
    /// The folder that relative paths of a scenario file at `path` refer to.
    fn base_dir(path: &Path) -> PathBuf;
}

/// A planned scenario of kind `S` with typed parameters: its table parsed once, its laws
/// and files built once ([`BuildCache`]), each point validated when built.
#[derive(Debug)]
pub struct SpecTemplate<S: FromSpec> {
    file: String,
    params: ParamTable<S::Spec>,
    dir: PathBuf,
    cache: BuildCache,
    base: OnceLock<Arc<S>>,
}

impl<S: FromSpec> SpecTemplate<S> {
    /// Plan a table that came from `path` (its values are validated when a model is built;
    /// [`Template::base`] validates the table as given).
    pub fn new(table: toml::Table, path: &Path) -> Self {
        let file = path.display().to_string();
        SpecTemplate {
            params: ParamTable::new(&file, table, S::to_spec),
            dir: S::base_dir(path),
            cache: BuildCache::new(),
            base: OnceLock::new(),
            file,
        }
    }

    /// The scenario as given, validated (once).
    pub fn scenario(&self) -> Result<Arc<S>> {
        if let Some(s) = self.base.get() {
            return Ok(s.clone());
        }
        let spec = self.params.spec()?;
        let s = Arc::new(S::from_spec(spec, &self.file, &self.dir, &self.cache)?);
        Ok(self.base.get_or_init(|| s).clone())
    }

    /// The scenario with `values` set, validated.
    pub fn scenario_with(&self, values: &[(&Param, f64)]) -> Result<Arc<S>> {
        if values.is_empty() {
            return self.scenario();
        }
        let spec = self.params.spec_with(values)?;
        Ok(Arc::new(S::from_spec(
            spec,
            &self.file,
            &self.dir,
            &self.cache,
        )?))
    }
}

impl<S: FromSpec> Template for SpecTemplate<S> {
    fn kind(&self) -> &'static str {
        S::KIND
    }

    fn file(&self) -> &str {
        &self.file
    }

    fn table(&self) -> &toml::Table {
        self.params.table()
    }

    fn base(&self) -> Result<Arc<dyn Model>> {
        Ok(self.scenario()?)
    }

    fn param(&self, key: &str) -> Result<Param> {
        self.params.param(key)
    }

    fn build(&self, values: &[(&Param, f64)]) -> Result<Arc<dyn Model>> {
        Ok(self.scenario_with(values)?)
    }
}

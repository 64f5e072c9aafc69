//! Models: the one contract every kind of scenario implements (the half-space problem,
//! the bar stack, and whatever comes next), so that every edge of the program — the CLI's
//! `run`, `sweep`, `identify` and `reproduce`, Python's `cw.run` and `cw.sweep`, Dask
//! tasks — dispatches once, here.
//!
//! The pipeline of one run:
//!
//! ```text
//! TOML table ──Kind::plan──▶ Template ──build(values)──▶ Model ──run──▶ Outcome
//!   (parsed once)            (validated once;            (solver inputs   (signals, summary,
//!                             tables and files            ready)           files, arrays)
//!                             built/read once)
//! ```
//!
//! * A [`Kind`] recognises its scenario tables and plans a [`Template`] from one.
//! * A [`Template`] is a validated scenario with typed parameters ([`Param`]): a sweep or an
//!   identification resolves its keys once ([`Template::param`]) and then only sets numbers
//!   ([`Template::build`]); tabulated laws and excitation files are built or read once per
//!   template.
//! * A [`Model`] runs: [`Model::summary`] (the scalars a sweep row needs, fast path) or
//!   [`Model::run`] (everything: an [`Outcome`]).
//! * An [`Outcome`] holds the signals and the summary, renders its own files
//!   ([`Outcome::files`]) and converts itself into plain arrays ([`Outcome::record`], what
//!   the Python package turns into numpy arrays).
//!
//! Adding a kind of scenario: one module implementing these traits and one line in
//! [`KINDS`].
//!
//! ```
//! use contactwave::model;
//! let template = model::from_toml_str(r#"
//!     [medium]
//!     material = "pmma"
//!     [interface]
//!     static_pressure = 0.1e6
//!     [incident]
//!     frequency = 1e6
//!     cycles = 10
//!     xi = 0.35
//! "#, "example.toml").unwrap();
//! assert_eq!(template.kind(), "half_space");
//! // plan once, run many: set the load ratio on the validated template
//! let xi = template.param("incident.xi").unwrap();
//! for v in [0.2, 0.35, 0.8] {
//!     let m = template.build(&[(&xi, v)]).unwrap();
//!     let s = m.summary().unwrap();
//!     assert!((s.get("xi").unwrap() - v).abs() < 1e-12);
//! }
//! // a full run gives the signals, the files and the arrays
//! let outcome = template.base().unwrap().run(&model::RunControl::default()).unwrap();
//! assert!(outcome.summary().get("A2_over_Ainc").unwrap() > 0.05);
//! assert!(outcome.files().unwrap().iter().any(|f| f.name == "timeseries.csv"));
//! ```

pub mod bar_stack;
mod fields;
pub mod half_space;
mod param;
mod record;
pub mod solid_2d;
mod template;

pub use fields::{Fields, Slot};
pub use param::{toml_number, wants_integer, Param, ParamTable};
pub use record::{Record, Value};
pub use template::{FromSpec, SpecTemplate};

use crate::analysis::{AnalysisMethod, Summary};
use crate::error::Result;
use crate::render::{OutputFile, Rows};
use crate::scenario::read_table;
use crate::solver::bar_stack::StepProgress;
use std::any::Any;
use std::fmt::Debug;
use std::path::Path;
use std::sync::Arc;

/// A sampled signal of a run ([`Outcome::waveform`]): `samples[k]` at `t0 + k dt`.
#[derive(Debug, Clone, PartialEq)]
pub struct Waveform {
    /// Time of the first sample, s (the run's own time origin).
    pub t0: f64,
    /// Sampling step, s.
    pub dt: f64,
    /// The samples, in the signal's unit (m/s for velocities, Pa for stresses, m for
    /// displacements).
    pub samples: Vec<f64>,
}

/// What a run may report while it goes (more to come: cancellation).
#[derive(Debug, Clone, Default)]
pub struct RunControl {
    /// Called with (steps done, total steps) by long time-stepping runs.
    pub progress: Option<StepProgress>,
}

/// A kind of scenario: recognises its tables and plans templates from them.
pub trait Kind: Sync {
    /// Name of the kind (`half_space`, `bar_stack`).
    fn name(&self) -> &'static str;
    /// Whether a parsed scenario table is of this kind.
    fn matches(&self, table: &toml::Table) -> bool;
    /// Plan a template from a table that came from (or stands for) `path`; relative paths
    /// in it resolve against `path`'s folder. Values are validated when a model is built
    /// ([`Template::build`], [`Template::base`]).
    fn plan(&self, table: toml::Table, path: &Path) -> Arc<dyn Template>;
    /// The dotted key of the frequency a run is driven at (what an experiment design
    /// varies when its file names no key).
    fn frequency_key(&self) -> &'static str {
        "incident.frequency"
    }
}

/// The registered kinds, tried in order (the half-space problem, the default, last).
pub static KINDS: [&dyn Kind; 3] = [&bar_stack::KIND, &solid_2d::KIND, &half_space::KIND];

/// The kind of a parsed scenario table.
pub fn kind_of(table: &toml::Table) -> &'static dyn Kind {
    KINDS
        .iter()
        .copied()
        .find(|k| k.matches(table))
        .unwrap_or(&half_space::KIND)
}

/// Plan a template from a parsed table that came from `path`, whichever its kind (nothing
/// is validated yet: see [`plan_valid`]).
pub fn plan(table: toml::Table, path: &Path) -> Arc<dyn Template> {
    kind_of(&table).plan(table, path)
}

/// Plan a template and validate the scenario as given (what loading a scenario to run it
/// means).
pub fn plan_valid(table: toml::Table, path: &Path) -> Result<Arc<dyn Template>> {
    // a `[model] kind` no kind claims (a typo) would read as a half-space scenario and
    // fail on its first table: name the kind instead
    if let Some(kind) = table.get("model").and_then(|m| m.get("kind")) {
        let half_space = half_space::KIND.name();
        if kind_of(&table).name() == half_space && kind.as_str() != Some(half_space) {
            let names: Vec<&str> = KINDS
                .iter()
                .map(|k| k.name())
                .filter(|n| *n != half_space)
                .collect();
            return Err(crate::error::Error::invalid(
                path.display().to_string(),
                "model.kind",
                kind,
                format!(
                    "{} (a half-space scenario has no `[model]` table)",
                    names.join(" or ")
                ),
            ));
        }
    }
    let t = plan(table, path);
    t.base()?;
    Ok(t)
}

/// Load a scenario file, plan its template and validate it. Relative paths in the file
/// (excitation files) resolve against its folder.
///
/// ```
/// use contactwave::model;
/// let dir = std::env::temp_dir().join(format!("contactwave-doc-load-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("unilateral.toml");
/// std::fs::write(&path, r#"
///     [medium]
///     material = "aluminium"
///     [interface]
///     static_pressure = 1e6       # Pa
///     [incident]
///     frequency = 0.5e6           # Hz
///     cycles = 5
///     xi = 0.5
/// "#).unwrap();
/// let template = model::load(&path).unwrap();
/// assert_eq!(template.kind(), "half_space");
/// assert_eq!(template.file(), path.display().to_string());
/// assert_eq!(template.base().unwrap().load_ratio(), 0.5);
/// // a missing file is an I/O error naming the path
/// let err = model::load(&dir.join("missing.toml")).unwrap_err();
/// assert!(err.to_string().contains("missing.toml"));
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn load(path: &Path) -> Result<Arc<dyn Template>> {
    plan_valid(read_table(path)?, path)
}

/// Parse TOML text named `file` (relative paths resolve against the current folder), plan
/// its template and validate it. The kind is recognised from the table (see [`KINDS`]).
///
/// ```
/// use contactwave::model;
/// // `[model] kind = "bar_stack"` makes a bar stack; a `[medium]` table the half-space problem
/// let stack = model::from_toml_str(r#"
///     [model]
///     kind = "bar_stack"
///     area = 1.0                  # m^2
///     static_force = 0.082e6      # N
///     first_end = "transparent"
///     last_end = "transparent"
///     [[segment]]
///     name = "upper"
///     length = 0.005              # m
///     material = "pmma"
///     [[segment]]
///     name = "lower"
///     length = 0.005
///     material = "pmma"
///     [[interface]]
///     between = ["upper", "lower"]
///     traction = { law = "rccm", stiffness = 2e13, energy = 0.1 }
///     [incident]
///     frequency = 1e6             # Hz
///     cycles = 5
///     amplitude = 2.5e6           # Pa
/// "#, "stack.toml").unwrap();
/// assert_eq!(stack.kind(), "bar_stack");
/// // the scenario is validated here: errors name the file, the field and what is allowed
/// let err = model::from_toml_str(r#"
///     [medium]
///     material = "glass"
///     [interface]
///     static_pressure = 0.1e6
///     [incident]
///     frequency = 1e6
///     cycles = 10
///     xi = 0.5
/// "#, "bad.toml").unwrap_err();
/// assert!(err.to_string().contains("bad.toml: field `medium.material`"));
/// ```
pub fn from_toml_str(text: &str, file: &str) -> Result<Arc<dyn Template>> {
    let table = crate::scenario::parse_toml(text, file)?;
    plan_valid(table, Path::new(file))
}

/// A validated scenario with typed parameters: plan once, build many.
pub trait Template: Debug + Send + Sync {
    /// Name of the kind.
    fn kind(&self) -> &'static str;
    /// File the scenario came from.
    fn file(&self) -> &str;
    /// The scenario table as given (before defaults).
    fn table(&self) -> &toml::Table;
    /// The model of the template as given (validated on first use).
    fn base(&self) -> Result<Arc<dyn Model>>;
    /// Resolve a dotted scenario key (e.g. `incident.xi`, `interface.1.compression.c`) to
    /// a parameter. An unknown key, or one that does not take a number, is an error that
    /// names the key.
    fn param(&self, key: &str) -> Result<Param>;
    /// The model with these parameter values set, validated (an invalid value is an error
    /// naming the key, the value and the allowed range).
    fn build(&self, values: &[(&Param, f64)]) -> Result<Arc<dyn Model>>;
}

/// What a worker keeps from one run to the next, owned by the caller (one per worker:
/// [`crate::run::Workspaces`]): the exact solver's incident table and the analysis floors
/// of locked interfaces. Plan caches: a run on a used workspace gives what it gives on a
/// new one.
#[derive(Debug, Default)]
pub struct Workspace {
    /// The exact half-space solver's.
    pub(crate) solver: crate::solver::half_space::Workspace,
    /// The locked interfaces' floors at unit peak.
    pub(crate) floors: half_space::methods::Floors,
}

impl Workspace {
    /// A new workspace (its first run is a cold run).
    pub fn new() -> Self {
        Workspace::default()
    }

    /// Forget what it keeps: the next run on it is a cold run (for benchmarks).
    pub fn clear(&mut self) {
        self.solver.clear();
        self.floors.clear();
    }
}

/// A runnable model: solver inputs ready.
pub trait Model: Debug + Send + Sync {
    /// Name of the kind.
    fn kind(&self) -> &'static str;
    /// File the scenario came from.
    fn file(&self) -> &str;
    /// Load ratio xi of the incident wave at the (first) interface (model.md section 2),
    /// 0 without an incident wave; NaN for a model that has no one ratio (a 2D run).
    fn load_ratio(&self) -> f64;
    /// Run and return only the summary scalars (what a sweep row needs; no recorded
    /// series or spectra beyond what the summary uses).
    fn summary(&self) -> Result<Summary>;
    /// [`Self::summary`] for a caller that reads only `keys` (an identification's observed
    /// keys): a model may skip work that no key of the list needs, leaving the other keys
    /// NaN or 0 (the half-space model skips the analysis floor's linearised solve when no
    /// key is a floor key). The listed keys are the same as from [`Self::summary`].
    fn summary_for(&self, keys: &[&str]) -> Result<Summary> {
        let _ = keys;
        self.summary()
    }
    /// [`Self::summary`] on the caller's workspace (the default ignores it).
    fn summary_in(&self, ws: &mut Workspace) -> Result<Summary> {
        let _ = ws;
        self.summary()
    }
    /// [`Self::summary_for`] on the caller's workspace (the default ignores it).
    fn summary_for_in(&self, keys: &[&str], ws: &mut Workspace) -> Result<Summary> {
        let _ = ws;
        self.summary_for(keys)
    }
    /// The memory one run of [`Self::summary`] needs at once, bytes, estimated without
    /// running it (what a caller that sends runs to another machine, a Dask worker, checks
    /// against that machine's memory first); `None` where the kind gives no estimate (the
    /// default). Runs are also checked against the local budget ([`crate::budget`]).
    fn memory_estimate(&self) -> Result<Option<f64>> {
        Ok(None)
    }
    /// Whether one run fits the local memory budget ([`crate::budget`]), checked without
    /// running it: an error names the key to change. What a sweep asks of every point
    /// before it runs any; the default accepts (a kind whose runs are small).
    fn check_budget(&self) -> Result<()> {
        Ok(())
    }
    /// Values of the scenario that are allowed but almost surely a unit slip (the run goes
    /// on; the CLI prints them on stderr, Python warns). None by default.
    fn warnings(&self) -> Vec<crate::scenario::Warning> {
        Vec::new()
    }
    /// Run fully: signals, spectra, summary.
    ///
    /// ```
    /// use contactwave::model::{self, RunControl};
    /// let m = model::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.1e6     # Pa
    ///     [incident]
    ///     frequency = 1e6             # Hz
    ///     cycles = 10
    ///     xi = 2.0                    # A = p0 / 4: the interface stays closed
    ///     [solver]
    ///     samples_per_period = 64
    /// "#, "closed.toml").unwrap().base().unwrap();
    /// let outcome = m.run(&RunControl::default()).unwrap();
    /// let s = outcome.summary();
    /// // a closed interface reflects linearly: no contact loss, no energy lost, and the
    /// // reflected second harmonic is the incident burst's own
    /// assert_eq!(s.get("contact_loss_fraction"), Some(0.0));
    /// assert_eq!(s.get("max_gap"), Some(0.0));
    /// let (e_inc, e_refl) = (s.get("energy_incident").unwrap(), s.get("energy_reflected").unwrap());
    /// assert!((e_refl / e_inc - 1.0).abs() < 1e-9);
    /// let a2 = s.get("A2_over_Ainc").unwrap();
    /// assert!((a2 - s.get("incident_A2_over_Ainc").unwrap()).abs() < 1e-6);
    /// ```
    fn run(&self, control: &RunControl) -> Result<Box<dyn Outcome>>;
    /// The second model a leakage-free analysis `method` needs (model.md section 6.1): the
    /// drive negated for `pulse_inversion`, the interfaces linearised at their static state
    /// for `linear_reference`; `None` for the other methods and for kinds without one (the
    /// default). The twin's own analysis is `band_peak` (it makes no twin of its own). An
    /// identification from raw records runs it to reduce the forward signal exactly as the
    /// measured one ([`crate::measured::analyze`]).
    fn twin(&self, method: AnalysisMethod) -> Result<Option<Arc<dyn Model>>> {
        let _ = method;
        Ok(None)
    }
    /// [`Self::run`] on the caller's workspace (the default ignores it).
    fn run_in(&self, control: &RunControl, ws: &mut Workspace) -> Result<Box<dyn Outcome>> {
        let _ = ws;
        self.run(control)
    }
    /// The concrete model, for callers that need kind-specific inputs.
    fn as_any(&self) -> &dyn Any;
}

/// Everything one run produced.
pub trait Outcome: Debug + Send + Sync {
    /// Name of the kind.
    fn kind(&self) -> &'static str;
    /// The summary scalars (`summary.json`, a sweep row).
    fn summary(&self) -> &Summary;
    /// The run's files, rendered in memory (`summary.json` first).
    ///
    /// ```
    /// use contactwave::model::{self, RunControl};
    /// let outcome = model::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.1e6
    ///     [incident]
    ///     frequency = 1e6
    ///     cycles = 10
    ///     xi = 0.5
    ///     [solver]
    ///     samples_per_period = 64
    /// "#, "open.toml").unwrap().base().unwrap().run(&RunControl::default()).unwrap();
    /// let files = outcome.files().unwrap();
    /// assert_eq!(files[0].name, "summary.json");
    /// assert!(files[0].contents.contains("\"A2_over_Ainc\""));
    /// let ts = files.iter().find(|f| f.name == "timeseries.csv").unwrap();
    /// assert!(ts.contents.starts_with("t,gap,contact_stress,"));
    /// assert!(files.iter().any(|f| f.name == "spectrum.svg"));
    /// // write them where they belong
    /// let dir = std::env::temp_dir().join(format!("contactwave-doc-files-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// for f in &files {
    ///     std::fs::write(dir.join(&f.name), &f.contents).unwrap();
    /// }
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
    fn files(&self) -> Result<Vec<OutputFile>>;
    /// [`Outcome::files`] with the rows of the time-series files
    /// ([`crate::render::TIME_SERIES_FILES`]) picked by `rows` (left out for
    /// [`Rows::None`]), the other files as they are. By default the files are rendered in
    /// full and the rows picked from their text; a kind with long records renders the
    /// picked rows only.
    fn files_with(&self, rows: Rows) -> Result<Vec<OutputFile>> {
        Ok(self
            .files()?
            .into_iter()
            .filter_map(|f| crate::render::pick_rows(f, rows))
            .collect())
    }
    /// The run's binary files (images: PNG frames, GIF), rendered in memory; none by
    /// default. Written beside [`Outcome::files`] (names may hold a subfolder).
    fn binary_files(&self) -> Result<Vec<crate::render::BinaryFile>> {
        Ok(Vec::new())
    }
    /// The run as plain named values and arrays (what Python receives as numpy arrays).
    ///
    /// ```
    /// use contactwave::model::{self, RunControl, Value};
    /// let outcome = model::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.1e6     # p0, Pa; rigid (Signorini) compression by default
    ///     [incident]
    ///     frequency = 1e6
    ///     cycles = 10
    ///     xi = 0.5                    # A = p0: the interface opens
    ///     [solver]
    ///     samples_per_period = 64
    /// "#, "open.toml").unwrap().base().unwrap().run(&RunControl::default()).unwrap();
    /// let r = outcome.record();
    /// let (Some(Value::Array(t)), Some(Value::Array(gap)), Some(Value::Array(stress))) =
    ///     (r.get("t"), r.get("gap"), r.get("contact_stress"))
    /// else {
    ///     panic!("half-space records hold t, gap and contact_stress arrays")
    /// };
    /// assert_eq!((t.len(), stress.len()), (gap.len(), gap.len()));
    /// // Signorini: the gap (m) never closes below 0 and the stress (Pa) vanishes while open
    /// assert!(gap.iter().all(|&g| g >= 0.0) && gap.iter().any(|&g| g > 0.0));
    /// assert!(gap.iter().zip(stress).all(|(&g, &s)| g == 0.0 || s == 0.0));
    /// // closed, the interface carries -(p0 + 2 A) at most: -0.3 MPa
    /// let most = stress.iter().copied().fold(0.0, f64::min);
    /// assert!((most / -0.3e6 - 1.0).abs() < 0.01);
    /// ```
    fn record(&self) -> Record;
    /// The run's signal `name`, uniformly sampled: a column of its probe or receiver file
    /// (half-space `probe.csv`: `reflected_velocity`, `incident_velocity`,
    /// `reflected_stress`, ...; 2D `receivers.csv`: `<receiver>_v<c>`, `<receiver>_s<cc>`);
    /// `None` if the run has no signal of that name (the default: none).
    fn waveform(&self, name: &str) -> Option<Waveform> {
        let _ = name;
        None
    }
    /// The names [`Self::waveform`] answers (for error messages); none by default.
    fn waveform_names(&self) -> Vec<String> {
        Vec::new()
    }
    /// The lines a person reads after the run (`contactwave run` prints them): the
    /// quantities that matter for this kind, one per line, label padded to 23 columns.
    fn report(&self) -> Vec<String>;
    /// What the results warn of (a harmonic within a factor 10 of its analysis floor), one
    /// line each without the `warning: ` that [`Self::report`] prints before it; with the
    /// scenario's own ([`Model::warnings`]) they are `summary.json`'s `warnings`
    /// ([`crate::render::stamp_warnings`]). None by default.
    fn warnings(&self) -> Vec<String> {
        Vec::new()
    }
    /// The concrete outcome, for callers that need kind-specific signals.
    fn as_any(&self) -> &dyn Any;
    /// The concrete outcome, by value.
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

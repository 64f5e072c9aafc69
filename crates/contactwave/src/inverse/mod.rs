//! Inverse identification of interface parameters from a measured nonlinear signature
//! (`contactwave identify`).
//!
//! # Identification file (TOML)
//!
//! ```toml
//! base = "base.toml"          # base scenario, relative to this file
//! data = "measured.csv"       # measured curve(s), relative to this file; or instead
//!                             #   [records]: raw waveforms reduced like the forward
//!                             #   signals (the `records` module, docs/identify.md section 8)
//! observed = ["A2_over_A1"]   # optional: the summary columns fitted (default: all in the CSV)
//!
//! [set]                       # optional fixed overrides of the base scenario
//! "solver.samples_per_period" = 100
//!
//! [[parameter]]               # the unknowns
//! key = "interface.traction.stiffness"
//! bounds = [1e9, 1e17]        # in the key's SI unit
//! scale = "log"               # "log" (fit log10 of the value) or "linear"
//! # initial = 1e12            # optional start (default: the base value, else the middle)
//! # also = ["..."]            # optional further keys set to the same value (tied)
//!
//! [fit]                       # optional
//! relative_noise = 0.01       # sigma = relative_noise |y| + absolute_noise where the CSV
//! absolute_noise = 0.0        #   has no `sigma_<name>` column
//! particles = 16              # particle swarm (global stage)
//! iterations = 20
//! local_iterations = 80       # Nelder-Mead (local refinement)
//! local_starts = 3            # refinements from the best distinct swarm points
//! bootstrap = 20              # bootstrap resamples (0: none)
//! bootstrap_iterations = 20   # Nelder-Mead iterations per bootstrap refit
//! seed = 1
//!
//! [design]                    # optional: `identify --design`
//! key = "incident.frequency"
//! values = [0.5e6, 1e6, 2e6]
//! ```
//!
//! # Measured data (CSV)
//!
//! A header line, then one row per measured point. Columns whose name contains a `.` are
//! dotted scenario keys set at that point (the control variable such as `incident.xi`,
//! `incident.amplitude`, `interface.static_pressure`, `excitation.peak`, and any further
//! condition such as `incident.frequency`); `sigma_<name>` columns give the standard
//! uncertainty of the observed column `<name>`; the other columns are observed summary
//! keys (`A2_over_A1`, `A1_over_Ainc`, `first_mode_hz`, ...). `#` starts a comment line.
//!
//! # Method
//!
//! Weighted least squares `sum_i ((model_i - y_i) / sigma_i)^2` in the scaled parameter
//! space (log10 of `log` parameters), a global stage (argmin particle swarm) then a local
//! one (argmin Nelder-Mead); forward runs in parallel (rayon). Identifiability: see
//! [`identifiability`].
//!
//! # Modules
//!
//! From the bottom up; each uses only those above it in this list:
//!
//! - `spec`: the data of an identification ([`IdentifySpec`], [`Parameter`], [`Measured`],
//!   ...);
//! - `model`: the forward model ([`Model`]: parameters -> scenarios -> curves, residuals);
//! - `parse`: the identification file and the measured data ([`IdentifySpec::load`]);
//! - `sensitivity`: Jacobian and SVD at a point;
//! - [`estimate`](mod@estimate): the weighted least squares and its minimisation;
//! - [`identifiability`]: intervals and verdicts at the optimum;
//! - [`design`](mod@design): ranking of candidate experiments;
//! - `result`: the result ([`Identification`]) and its files (it also draws with
//!   `crate::output`, a layer above this one; no other inverse module imports upwards);
//! - `driver`: [`identify`], [`synthesize`].

pub mod design;
mod driver;
pub mod estimate;
pub mod identifiability;
mod model;
mod parse;
pub mod records;
mod result;
mod sensitivity;
mod spec;

pub use design::{design, DesignCandidate, DesignReport};
pub use driver::{identify, synthesize, synthesize_records};
pub use estimate::{estimate, Estimate};
pub use identifiability::{Identifiability, Verdict};
pub use model::Model;
pub use parse::get_dotted;
pub use records::RecordsSpec;
pub use result::Identification;
pub use spec::{DesignSpec, FitOptions, IdentifySpec, Measured, Observed, Parameter, Scale};

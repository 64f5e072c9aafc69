//! # contactwave
//!
//! Nonlinear interaction of elastic waves with contact interfaces (closed cracks, kissing
//! bonds, rough and adhesive joints): contact laws built from any compression branch and
//! any traction branch ([`law`]), an exact solver of the half-space problem
//! ([`solver::half_space`]), incident waves ([`excitation`]), the harmonic analysis of the
//! thesis ([`analysis`]), scenario files ([`scenario`]), parameter studies ([`study`]) and
//! result files ([`output`]).
//!
//! Cargo features (all on by default; the CLI and the Python package use them all):
//! `plot` (SVG figures, with plotters: `render::svg`, `output::plot`; without it every
//! output keeps its CSV and JSON files and has no SVG file), `identify` (inverse
//! identification, with argmin and rand: `inverse`, `output::identify`; needs `plot`) and
//! `reproduce` (the thesis' studies and their HTML report: `reproduce`; needs `plot`).
//! A program that embeds only the solvers can depend on the library with
//! `default-features = false`.
//!
//! Conventions (model.md section 1): SI units; stress tension-positive; the static
//! pre-stress is a compression `p0 >= 0`; the gap `[u] = u(0+) - u(0-)` is opening-positive
//! and measured from the pre-loaded equilibrium.
//!
//! ```
//! use contactwave::{scenario::Scenario, simulate};
//! let s = Scenario::from_toml_str(r#"
//!     [medium]
//!     material = "pmma"
//!     [interface]
//!     static_pressure = 0.082e6
//!     traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
//!     [incident]
//!     frequency = 1e6
//!     cycles = 15
//!     amplitude = 0.82e6
//! "#, "rccm.toml").unwrap();
//! let r = simulate(&s).unwrap();
//! // 0.82 MPa opens the interface without damaging it (thesis chapter 3)
//! assert_eq!(r.summary.get("beta_end"), Some(1.0));
//! assert!(r.summary.get("contact_loss_fraction").unwrap() > 0.0);
//! ```

// `!(x > 0.0)` is deliberate throughout: it rejects NaN together with the out-of-range
// values, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Index loops mirror the Butcher tableaux and stencils of the numerical kernels.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod analysis;
pub mod analytic;
pub mod budget;
pub mod error;
pub mod excitation;
pub mod human;
pub mod interrupt;
#[cfg(feature = "identify")]
pub mod inverse;
pub mod law;
pub mod material;
pub mod measured;
pub mod model;
pub mod numeric;
pub mod output;
pub mod render;
#[cfg(feature = "reproduce")]
pub mod reproduce;
pub mod run;
pub mod scenario;
pub mod solver;
pub mod study;

pub use error::{Error, Result};
pub use model::bar_stack::{
    simulate_bar_stack, simulate_bar_stack_with_progress, BarStackResult, Frf, ProbeHistory,
    FRF_FORCE_FLOOR_DB,
};
pub use model::half_space::{
    half_space, settings, simulate, simulate_in, simulate_summary, simulate_summary_in,
    ProbeSeries, RunResult,
};

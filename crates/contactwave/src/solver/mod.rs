//! Solvers: each takes a problem built from solver inputs (media, laws, excitations; never
//! a scenario) and returns histories defined in [`output`].
//!
//! | solver | problem | output |
//! |---|---|---|
//! | [`half_space::ExactSolver`] (gap ODE with located events, model.md section 4) | [`half_space::HalfSpace`] | [`HalfSpaceOutput`] |
//! | [`half_space_fd::FdSolver`] (the bar-stack scheme on the same problem, model.md section 9.4) | [`half_space::HalfSpace`] | [`HalfSpaceOutput`] |
//! | [`coupled::CoupledSolver`] (coupled normal and tangential gap ODEs with located events, model.md sections 13.3 and 14) | [`coupled::CoupledHalfSpace`] | [`coupled::CoupledOutput`] |
//! | [`half_space_fd_shear::FdCoupledSolver`] (the bar-stack scheme with a shear field, model.md sections 9.6 and 13) | [`coupled::CoupledHalfSpace`] | [`coupled::CoupledOutput`] |
//! | [`bar_stack::FdRun`] (explicit FD bar stack, model.md section 9) | [`bar_stack::BarStack`] | [`FdOutput`] |
//!
//! The three finite-difference solvers share one field type (`bar_stack::field`: the
//! bar stack's fields at any Courant number, the half-space cross-checks' bars at
//! Courant 1) and one time loop (`stepping`: interrupt checks, progress, finiteness
//! checks and a recorder observing the levels).
//!
//! ```
//! use contactwave::excitation::{ToneBurst, Window};
//! use contactwave::law::registry::build_law;
//! use contactwave::law::spec::{CompressionSpec, TractionSpec};
//! use contactwave::material::Material;
//! use contactwave::solver::{half_space::{ExactSolver, HalfSpace}, Solver};
//! use std::sync::Arc;
//! let law = build_law(1e5, &CompressionSpec::Rigid, &TractionSpec::Free, "<code>", "interface").unwrap();
//! let pmma = Material::preset("pmma").unwrap();
//! let burst = ToneBurst::new(1e5, 1e6, 10.0, Window::HannRamps { ramp_fraction: 0.25 });
//! let problem = HalfSpace::new(pmma, None, Arc::new(law), Arc::new(burst));
//! let out = ExactSolver::default().solve(&problem).unwrap();
//! // the interface opens (clapping) and the energy audit closes
//! assert!(out.max_gap > 0.0);
//! assert!(out.energy.closure_error() < 1e-6);
//! ```

pub mod bar_stack;
pub mod coupled;
mod exact_loop;
pub mod half_space;
pub mod half_space_fd;
pub mod half_space_fd_shear;
pub mod output;
pub mod radau;
pub(crate) mod stepping;

pub use output::{EnergyAudit, FdOutput, HalfSpaceOutput};

use crate::error::Result;

/// A solver: settings that turn a problem into histories. Built once, run on many
/// problems (the settings hold no per-run state).
pub trait Solver {
    /// What it solves.
    type Problem;
    /// What it returns.
    type Output;
    /// Solve `problem`.
    fn solve(&self, problem: &Self::Problem) -> Result<Self::Output>;
}

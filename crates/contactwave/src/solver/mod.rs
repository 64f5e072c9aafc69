//! Solvers: each takes a problem built from solver inputs (media, laws, excitations; never
//! a scenario) and returns histories defined in [`output`].
//!
//! | solver | problem | output |
//! |---|---|---|
//! | [`halfspace::ExactSolver`] (gap ODE with located events, model.md section 4) | [`halfspace::HalfSpace`] | [`HalfSpaceOutput`] |
//! | [`halfspace_fd::FdSolver`] (the bar-stack scheme on the same problem) | [`halfspace::HalfSpace`] | [`HalfSpaceOutput`] |
//! | [`halfspace_fd_shear::FdCoupledSolver`] (the bar-stack scheme with a shear field, model.md section 13) | [`coupled::CoupledHalfSpace`] | [`coupled::CoupledOutput`] |
//! | [`barstack::FdRun`] (explicit FD bar stack, model.md section 5) | [`barstack::BarStack`] | [`FdOutput`] |
//!
//! ```
//! use contactwave::excitation::{ToneBurst, Window};
//! use contactwave::law::registry::build_law;
//! use contactwave::law::spec::{CompressionSpec, TractionSpec};
//! use contactwave::material::Material;
//! use contactwave::solver::{halfspace::{ExactSolver, HalfSpace}, Solver};
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

pub mod barstack;
pub mod coupled;
pub mod halfspace;
pub mod halfspace_fd;
pub mod halfspace_fd_shear;
pub mod interface;
pub mod interface_shear;
pub mod output;
pub mod radau;

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

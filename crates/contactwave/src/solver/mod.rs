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
//! let law = build_law(1e5, &CompressionSpec::Rigid(Default::default()), &TractionSpec::Free(Default::default()), "<code>", "interface").unwrap();
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
mod quadrature;
pub mod radau;
pub mod solid_2d;
pub(crate) mod stepping;

pub use output::{EnergyAudit, FdOutput, HalfSpaceOutput};

use crate::error::Result;

/// A solver: settings that turn a problem into histories. Built once, run on many
/// problems (the settings hold no per-run state). A run goes through a [`Plan`] (the
/// problem with the solver that solves it: [`Solver::plan`]) on a workspace that the
/// caller owns (what one run keeps for the next on the same worker: one per worker,
/// [`crate::run::Workspaces`], never a thread-local) into a recorder (the histories, filled
/// level by level as the run goes; a used one keeps its allocations).
///
/// ```
/// use contactwave::excitation::{ToneBurst, Window};
/// use contactwave::law::registry::build_law;
/// use contactwave::law::spec::{CompressionSpec, TractionSpec};
/// use contactwave::material::Material;
/// use contactwave::solver::{half_space::{ExactSolver, HalfSpace}, Solver};
/// use std::sync::Arc;
/// let law = build_law(1e5, &CompressionSpec::Rigid(Default::default()), &TractionSpec::Free(Default::default()), "<code>", "interface").unwrap();
/// let burst = ToneBurst::new(1e5, 1e6, 10.0, Window::HannRamps { ramp_fraction: 0.25 });
/// let problem = HalfSpace::new(Material::preset("pmma").unwrap(), None, Arc::new(law), Arc::new(burst));
/// let plan = ExactSolver::default().plan(&problem).unwrap();
/// let (mut ws, mut recorder) = (plan.workspace(), plan.recorder());
/// plan.run(&mut ws, &mut recorder).unwrap();
/// let first = recorder.reflected_stress.clone();
/// // a second run on the used workspace and recorder records the same histories
/// plan.run(&mut ws, &mut recorder).unwrap();
/// assert_eq!(recorder.reflected_stress, first);
/// assert!(recorder.max_gap > 0.0);
/// ```
pub trait Solver: Sized {
    /// What it solves.
    type Problem;
    /// What a run keeps for the next run on the same worker (plan caches: a run on a used
    /// workspace records what it records on a new one); `()` for a solver that keeps
    /// nothing.
    type Workspace: Default + Send;
    /// What a run records into and returns: its histories.
    type Output: Default;
    /// Plan `problem` with these settings: a [`Plan`] to run any number of times.
    fn plan(self, problem: &Self::Problem) -> Result<Plan<'_, Self>> {
        Ok(Plan {
            solver: self,
            problem,
        })
    }
    /// One run of `problem` on the workspace `ws`, recording into `out` (what it held
    /// before is replaced; on an error it holds no complete run).
    fn run_in(
        &self,
        problem: &Self::Problem,
        ws: &mut Self::Workspace,
        out: &mut Self::Output,
    ) -> Result<()>;
    /// Solve `problem` on a new workspace into a new recorder.
    fn solve(&self, problem: &Self::Problem) -> Result<Self::Output> {
        let mut out = Self::Output::default();
        self.run_in(problem, &mut Self::Workspace::default(), &mut out)?;
        Ok(out)
    }
}

/// A problem with the solver that solves it ([`Solver::plan`]): made once, run any number
/// of times, each run on a workspace and into a recorder that the caller owns (a sweep
/// keeps one workspace per worker: [`crate::run::Executor::run_plans`]).
#[derive(Debug, Clone)]
pub struct Plan<'p, S: Solver> {
    solver: S,
    problem: &'p S::Problem,
}

impl<'p, S: Solver> Plan<'p, S> {
    /// A new workspace for runs of this plan (its first run is a cold run).
    pub fn workspace(&self) -> S::Workspace {
        S::Workspace::default()
    }

    /// A new, empty recorder for runs of this plan.
    pub fn recorder(&self) -> S::Output {
        S::Output::default()
    }

    /// One run on the workspace `ws`, recording into `recorder` (what it held before is
    /// replaced; its allocations are reused where the solver records level by level).
    pub fn run(&self, ws: &mut S::Workspace, recorder: &mut S::Output) -> Result<()> {
        self.solver.run_in(self.problem, ws, recorder)
    }

    /// The solver (its settings).
    pub fn solver(&self) -> &S {
        &self.solver
    }

    /// The problem.
    pub fn problem(&self) -> &'p S::Problem {
        self.problem
    }
}

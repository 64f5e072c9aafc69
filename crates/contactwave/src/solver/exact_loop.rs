//! The one time loop of the exact solvers (the normal half-space solver and the coupled
//! one, model.md sections 4 and 13): the uniform output grid, each step split at the
//! waveforms' breakpoints, a tail after the burst that runs until the interface has been
//! at rest for a period (or a fixed one), an interrupt check every [`INTERRUPT_STEPS`]
//! steps and a record at every grid point. What a solver does within a step (its Radau
//! steps and located events, its record, its rest test, the normal solver's fast paths)
//! is its [`GridSolver`] ([`Driven`]).

use crate::error::Result;
use crate::numeric::root::brent_past;

/// Grid steps between two interrupt checks.
pub(crate) const INTERRUPT_STEPS: usize = super::stepping::CHECK_EVERY;

/// The output grid of a run: step, burst, tail and breakpoints.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    /// Grid step, s.
    pub h: f64,
    /// Duration of the burst (delay included), s: the tail starts after it.
    pub duration: f64,
    /// Period of the fundamental, s: the rest that ends an automatic tail.
    pub period: f64,
    /// Fewest grid steps (the burst and the shortest tail).
    pub n_min: usize,
    /// Most grid steps (the burst and the longest tail).
    pub n_max: usize,
    /// A fixed tail: the run ends after `n_min` steps.
    pub fixed_tail: bool,
    /// The waveforms' breakpoints (finite, positive, increasing), s.
    pub breaks: Vec<f64>,
}

impl Grid {
    /// The grid of step `h` (s) for a burst of `duration` (s) with fundamental `f0` (Hz):
    /// a tail of `tail_periods` periods, or (`None`) until rest, at least 3 and at most
    /// 400 periods; `breaks` are the waveforms' breakpoints in any order (s; those not
    /// finite or not positive are dropped).
    pub fn new(
        h: f64,
        duration: f64,
        f0: f64,
        tail_periods: Option<f64>,
        breaks: impl IntoIterator<Item = f64>,
    ) -> Self {
        let period = 1.0 / f0;
        let (min_tail, max_tail) = match tail_periods {
            Some(p) => (p * period, p * period),
            None => (3.0 * period, 400.0 * period),
        };
        let mut breaks: Vec<f64> = breaks
            .into_iter()
            .filter(|b| b.is_finite() && *b > 0.0)
            .collect();
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        Grid {
            h,
            duration,
            period,
            n_min: ((duration + min_tail) / h).ceil() as usize,
            n_max: ((duration + max_tail) / h).ceil() as usize,
            fixed_tail: tail_periods.is_some(),
            breaks,
        }
    }
}

/// A run as the time loop drives it: the solver's state (`solver`), its running
/// integrals (`acc`) and its records (`out`); each exact solver implements [`GridSolver`]
/// for its own.
pub(crate) struct Driven<'r, S, A, O> {
    /// The solver's state between grid points.
    pub solver: &'r mut S,
    /// The running integrals.
    pub acc: A,
    /// The records.
    pub out: O,
}

/// An exact solver as the time loop drives it, from grid point to grid point.
pub(crate) trait GridSolver {
    /// The interface unknowns.
    type State: Copy;
    /// Enter grid step `k`, from `ta` to `tb` (s).
    fn enter_step(&mut self, _k: usize, _ta: f64, _tb: f64) {}
    /// A specialised path: whole grid steps from `k` (before `k_end`, none with a
    /// breakpoint inside: `breaks[*bi..]` are the ones ahead, `bi` advanced as it goes),
    /// each recorded. Returns how many it took (the default: none).
    fn whole_steps(
        &mut self,
        _k: usize,
        _k_end: usize,
        _breaks: &[f64],
        _bi: &mut usize,
        _y: &mut Self::State,
    ) -> Result<usize> {
        Ok(0)
    }
    /// A specialised path: the whole grid step `k` from `ta` to `tb` (s), which has no
    /// breakpoint inside, as [`GridSolver::advance`] would take it. Returns `false` where
    /// it declines (the default), and `advance` takes the step.
    fn whole_step(&mut self, _k: usize, _ta: f64, _tb: f64, _y: &mut Self::State) -> Result<bool> {
        Ok(false)
    }
    /// Advance from `t` to `t_end` (s; no breakpoint inside), locating every event.
    fn advance(&mut self, t: f64, t_end: f64, y: &mut Self::State) -> Result<()>;
    /// Record the state at the grid point `t` (s).
    fn record(&mut self, t: f64, y: &Self::State);
    /// Whether the interface is at rest at the grid point `t` (s).
    fn at_rest(&self, t: f64, y: &Self::State) -> bool;
}

/// Run `solver` over `grid` from the state `y` at `t = 0` (recorded by the caller) to the
/// end of the tail. Returns the number of grid steps taken.
pub(crate) fn run<S: GridSolver>(grid: &Grid, solver: &mut S, y: &mut S::State) -> Result<usize> {
    let (h, breaks) = (grid.h, &grid.breaks[..]);
    let mut bi = 0usize;
    let mut k = 0usize;
    let mut rest = 0usize;
    while k < grid.n_max {
        let ta = k as f64 * h;
        let tb = (k + 1) as f64 * h;
        solver.enter_step(k, ta, tb);
        let mut t = ta;
        while bi < breaks.len() && breaks[bi] <= ta {
            bi += 1;
        }
        let whole = bi >= breaks.len() || breaks[bi] >= tb;
        // runs of whole steps (before the tail's end checks)
        if whole && k + 1 < grid.n_min {
            let n = solver.whole_steps(k, grid.n_min - 1, breaks, &mut bi, y)?;
            if n > 0 {
                k += n;
                continue;
            }
        }
        let done = whole && solver.whole_step(k, ta, tb, y)?;
        while !done && bi < breaks.len() && breaks[bi] < tb {
            solver.advance(t, breaks[bi], y)?;
            t = breaks[bi];
            bi += 1;
        }
        if !done {
            solver.advance(t, tb, y)?;
        }
        k += 1;
        if k.is_multiple_of(INTERRUPT_STEPS) {
            crate::interrupt::check()?;
        }
        solver.record(tb, y);
        if k >= grid.n_min && tb > grid.duration {
            if grid.fixed_tail {
                break;
            }
            if solver.at_rest(tb, y) {
                rest += 1;
                if rest as f64 * h >= grid.period {
                    break;
                }
            } else {
                rest = 0;
            }
        }
    }
    Ok(k)
}

/// Most events one call of an exact solver's `advance` may locate before it reaches the
/// end of its interval: more means the contact state chatters, and the run stops with an
/// error ([`EventGuard`]).
pub(crate) const MAX_EVENTS: usize = 10_000;

/// The event count of one `advance` (both exact solvers): [`EventGuard::tick`] once per
/// pass of its loop.
#[derive(Debug, Default)]
pub(crate) struct EventGuard(usize);

impl EventGuard {
    /// Count one pass at time `t` (s): an error after [`MAX_EVENTS`] passes, naming the
    /// `solver` and the `state` it chatters in.
    pub fn tick(&mut self, t: f64, solver: &str, state: impl FnOnce() -> String) -> Result<()> {
        self.0 += 1;
        if self.0 > MAX_EVENTS {
            return Err(crate::error::Error::numerical(
                t,
                format!(
                    "{solver}: more than {MAX_EVENTS} events in one time step (the contact \
                     state chatters)"
                ),
                state(),
            ));
        }
        Ok(())
    }
}

/// The one event locator of the exact solvers: the root in `(0, hi]` of an event function
/// along a trial step from time `t` (s), to machine precision.
///
/// `step_to(tau)` takes the trial step of length `tau` (s) and returns the event function
/// at its end with the step; `f_lo` is the function at the step's start and `f_hi` (of the
/// other sign, or 0) at `hi`, whose step is `s_hi`. The root is bracketed by
/// [`brent_past`] (Illinois regula falsi safeguarded by bisection) and returned on the far
/// side of the event: `tau` where the function has the sign of `f_hi` (or is 0), with the
/// step of that length when it was the last such one evaluated (the caller takes it
/// instead of stepping again; `None`: step again). `Ok(None)`: no bracket (the function is
/// not finite, or has the same sign at both ends); an error of `step_to` stops the search
/// and is returned.
pub(crate) fn locate<S>(
    mut step_to: impl FnMut(f64) -> Result<(f64, S)>,
    hi: f64,
    f_lo: f64,
    f_hi: f64,
    s_hi: S,
) -> Result<Option<(f64, Option<S>)>> {
    let past_side = |f: f64| f == 0.0 || (f > 0.0) == (f_hi > 0.0);
    let mut fail = None;
    // the last evaluated step past the event: brent_past returns the bracket end on that
    // side
    let mut past = (hi, Some(s_hi));
    let tau = brent_past(
        |tau| match step_to(tau) {
            Ok((f, s)) => {
                if past_side(f) {
                    past = (tau, Some(s));
                }
                f
            }
            Err(e) => {
                fail = Some(e);
                f64::NAN
            }
        },
        0.0,
        hi,
        f_lo,
        f_hi,
        200,
    );
    if let Some(e) = fail {
        return Err(e);
    }
    Ok(tau.map(|tau| (tau, if past.0 == tau { past.1 } else { None })))
}

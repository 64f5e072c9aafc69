//! The one executor (in the spirit of argmin's `Executor`): a parallel map over points —
//! sweep points, identification evaluations, reproduce's studies — with one observer
//! interface for progress, checkpointing (a sweep writes each row as its point ends) and
//! cancellation (Ctrl-C in the CLI, `KeyboardInterrupt` in Python). A panic in a point is
//! caught here, once, and becomes that point's [`Error::Internal`].
//!
//! ```
//! use contactwave::run::{Executor, Observer};
//! use std::sync::atomic::{AtomicUsize, Ordering};
//! struct Count(AtomicUsize);
//! impl Observer<f64> for Count {
//!     fn point(&self, _i: usize, _r: &contactwave::Result<f64>) -> contactwave::Result<()> {
//!         self.0.fetch_add(1, Ordering::SeqCst);
//!         Ok(())
//!     }
//! }
//! let obs = Count(AtomicUsize::new(0));
//! let squares = Executor::new().threads(Some(2))
//!     .map(&[1.0, 2.0, 3.0], |x: &f64| Ok(x * x), &obs)
//!     .unwrap();
//! assert_eq!(squares.into_iter().map(|r| r.unwrap().unwrap()).collect::<Vec<_>>(), [1.0, 4.0, 9.0]);
//! assert_eq!(obs.0.load(Ordering::SeqCst), 3);
//! ```

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Watches a map: progress, per-point results, cancellation. Every method has a default
/// that does nothing, so an observer implements only what it needs. Called from worker
/// threads: implementations synchronise what they share.
pub trait Observer<T>: Sync {
    /// Before the first point: the number of points that will run.
    fn start(&self, _total: usize) {}
    /// After each point (in completion order) with its index in the items and its result.
    /// An error here (e.g. a checkpoint file that cannot be written) stops the map.
    fn point(&self, _index: usize, _result: &Result<T>) -> Result<()> {
        Ok(())
    }
    /// After each point: points ended so far and the total.
    fn progress(&self, _done: usize, _total: usize) {}
    /// Checked before each point: once `true`, no new point starts (running ones finish).
    fn cancelled(&self) -> bool {
        false
    }
}

/// An observer that watches nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl<T> Observer<T> for Quiet {}

/// An observer that reports progress through a closure and cancels on a flag.
pub struct Progress<'a> {
    /// Called with (done, total).
    pub report: &'a (dyn Fn(usize, usize) + Sync),
    /// Set to stop starting new points.
    pub cancel: Option<&'a AtomicBool>,
}

impl<T> Observer<T> for Progress<'_> {
    fn progress(&self, done: usize, total: usize) {
        (self.report)(done, total)
    }
    fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::SeqCst))
    }
}

/// Most worker threads a map may use: more only costs memory (a stack each) and start-up
/// time on any machine this runs on.
pub const MAX_THREADS: usize = 1024;

/// Check a thread count asked for by a user (`--threads`, Python's `threads=`): an integer
/// in [1, [`MAX_THREADS`]].
///
/// ```
/// use contactwave::run::check_threads;
/// assert!(check_threads(4).is_ok());
/// assert!(check_threads(0).is_err());
/// assert!(check_threads(1_000_000).unwrap_err().to_string().contains("[1, 1024]"));
/// ```
pub fn check_threads(n: usize) -> Result<()> {
    if (1..=MAX_THREADS).contains(&n) {
        Ok(())
    } else {
        Err(Error::invalid(
            "<command line>",
            "threads",
            n,
            format!("must be an integer in [1, {MAX_THREADS}] (default: one per core)"),
        ))
    }
}

/// The workspaces of the workers of a map or of a run loop: plan caches that a point
/// reuses from the points run before it on the same workspace (the exact solver's incident
/// table, the locked interfaces' analysis floors: [`crate::model::Workspace`]), never a
/// result. A point takes one for its run and gives it back after ([`Workspaces::with`]),
/// so a map on `n` threads makes at most `n`, and a pool that outlives one map (an
/// identification's forward model, the Python module) keeps them warm from map to map.
/// No thread-local state: the owner of the pool owns the workspaces.
///
/// ```
/// use contactwave::run::Workspaces;
/// let pool: Workspaces<Vec<f64>> = Workspaces::new();
/// pool.with(|w| w.push(1.0));
/// // the next point gets the workspace the last one gave back
/// assert_eq!(pool.with(|w| w.len()), 1);
/// ```
#[derive(Debug, Default)]
pub struct Workspaces<W> {
    idle: std::sync::Mutex<Vec<W>>,
}

impl<W: Default> Workspaces<W> {
    /// An empty pool.
    pub const fn new() -> Self {
        Workspaces {
            idle: std::sync::Mutex::new(Vec::new()),
        }
    }

    /// Run `f` on an idle workspace (a new one when none is idle) and give it back. The
    /// pool's lock is only tried, never waited for: when another point holds it (for the
    /// time of a push or a pop) or it is poisoned, `f` runs on a new workspace (a cold run,
    /// the same result).
    pub fn with<R>(&self, f: impl FnOnce(&mut W) -> R) -> R {
        let mut w = match self.idle.try_lock() {
            Ok(mut idle) => idle.pop().unwrap_or_default(),
            Err(_) => W::default(),
        };
        let r = f(&mut w);
        if let Ok(mut idle) = self.idle.try_lock() {
            idle.push(w);
        }
        r
    }
}

/// Runs maps over points on a thread pool.
#[derive(Debug, Clone, Copy, Default)]
pub struct Executor {
    threads: Option<usize>,
}

/// The message of a caught panic.
fn panic_message(panic: Box<dyn std::any::Any + Send>) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_string())
}

impl Executor {
    /// An executor on all cores.
    pub fn new() -> Self {
        Executor::default()
    }

    /// On `n` threads (`None` or `Some(0)`: all cores; at most [`MAX_THREADS`], see
    /// [`check_threads`]).
    pub fn threads(mut self, n: Option<usize>) -> Self {
        self.threads = n.filter(|&n| n > 0).map(|n| n.min(MAX_THREADS));
        self
    }

    /// The number of threads a map will use.
    pub fn thread_count(&self) -> usize {
        self.threads.unwrap_or_else(rayon::current_num_threads)
    }

    /// Run `f` on every item in parallel (one point per task), reporting to `observer`.
    /// Returns the results in the items' order; `None` for points not started because the
    /// observer cancelled. A panic in `f` is that point's [`Error::Internal`]. The map
    /// itself fails when the thread pool cannot be built, the observer's
    /// [`Observer::point`] fails, or an interruption was requested
    /// ([`crate::interrupt`]: [`Error::Interrupted`]).
    pub fn map<I, T, F>(
        &self,
        items: &[I],
        f: F,
        observer: &dyn Observer<T>,
    ) -> Result<Vec<Option<Result<T>>>>
    where
        I: Sync,
        T: Send,
        F: Fn(&I) -> Result<T> + Sync,
    {
        use rayon::prelude::*;
        let total = items.len();
        observer.start(total);
        observer.progress(0, total);
        let done = AtomicUsize::new(0);
        let one = |(i, item): (usize, &I)| run_point(i, item, &f, observer, &done, total);
        let run = || {
            items
                .par_iter()
                .enumerate()
                .with_max_len(1)
                .map(one)
                .collect::<Result<Vec<_>>>()
        };
        let results = self.install(run)?;
        // an interruption ([`crate::interrupt`]) skipped or stopped points: the map's
        // results are incomplete, so the map is interrupted as a whole
        crate::interrupt::check()?;
        Ok(results)
    }

    /// [`Executor::map`] keeping no result: each point's result goes to the observer's
    /// [`Observer::point`] and is dropped, so memory stays flat whatever the number of
    /// points (a sweep streams its rows this way). Returns the number of points that ran
    /// (fewer than the items when the observer cancelled).
    pub fn for_each<I, T, F>(&self, items: &[I], f: F, observer: &dyn Observer<T>) -> Result<usize>
    where
        I: Sync,
        T: Send,
        F: Fn(&I) -> Result<T> + Sync,
    {
        use rayon::prelude::*;
        let total = items.len();
        observer.start(total);
        observer.progress(0, total);
        let done = AtomicUsize::new(0);
        let one =
            |(i, item): (usize, &I)| run_point(i, item, &f, observer, &done, total).map(|_| ());
        let run = || {
            items
                .par_iter()
                .enumerate()
                .with_max_len(1)
                .try_for_each(one)
        };
        self.install(run)?;
        Ok(done.load(Ordering::SeqCst))
    }

    /// Run `work` on this executor's pool (the global one without a thread count).
    fn install<R: Send>(&self, work: impl FnOnce() -> Result<R> + Send) -> Result<R> {
        match self.threads {
            None => work(),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| {
                    Error::invalid("<executor>", "threads", n, format!("thread pool: {e}"))
                })?
                .install(work),
        }
    }

    /// [`Executor::map`] with no observer, failing on the first point that failed (in
    /// the items' order).
    pub fn try_map<I, T, F>(&self, items: &[I], f: F) -> Result<Vec<T>>
    where
        I: Sync,
        T: Send,
        F: Fn(&I) -> Result<T> + Sync,
    {
        self.map(items, f, &Quiet)?
            .into_iter()
            .map(|r| r.unwrap_or(Err(Error::Interrupted)))
            .collect()
    }

    /// Run every plan on this executor's threads, each on a workspace of `pool` (one per
    /// worker: a plan's run reuses what the run before it on the same worker kept) into a
    /// new recorder: the recorders in the order of `plans`, failing on the first plan that
    /// failed. The same generic path for every solver ([`crate::solver::Solver`]).
    ///
    /// ```
    /// use contactwave::excitation::{ToneBurst, Window};
    /// use contactwave::law::registry::build_law;
    /// use contactwave::law::spec::{CompressionSpec, TractionSpec};
    /// use contactwave::material::Material;
    /// use contactwave::run::{Executor, Workspaces};
    /// use contactwave::solver::{half_space::{ExactSolver, HalfSpace}, Solver};
    /// use std::sync::Arc;
    /// let law = Arc::new(build_law(1e5, &CompressionSpec::Rigid(Default::default()), &TractionSpec::Free(Default::default()), "<code>", "interface").unwrap());
    /// let problems: Vec<HalfSpace> = [0.5e5, 1e5, 2e5]
    ///     .iter()
    ///     .map(|&a| {
    ///         let burst = ToneBurst::new(a, 1e6, 10.0, Window::HannRamps { ramp_fraction: 0.25 });
    ///         HalfSpace::new(Material::preset("pmma").unwrap(), None, law.clone(), Arc::new(burst))
    ///     })
    ///     .collect();
    /// let plans = problems
    ///     .iter()
    ///     .map(|p| ExactSolver::default().plan(p))
    ///     .collect::<Result<Vec<_>, _>>()
    ///     .unwrap();
    /// let outs = Executor::new().run_plans(&plans, &Workspaces::new()).unwrap();
    /// // the larger the burst, the wider the interface opens
    /// assert!(outs[0].max_gap < outs[1].max_gap && outs[1].max_gap < outs[2].max_gap);
    /// ```
    pub fn run_plans<S>(
        &self,
        plans: &[crate::solver::Plan<'_, S>],
        pool: &Workspaces<S::Workspace>,
    ) -> Result<Vec<S::Output>>
    where
        S: crate::solver::Solver + Sync,
        S::Problem: Sync,
        S::Output: Send,
    {
        self.try_map(plans, |plan| {
            pool.with(|ws| {
                let mut recorder = plan.recorder();
                plan.run(ws, &mut recorder).map(|()| recorder)
            })
        })
    }
}

/// One point of a map: skipped (`None`) once the observer cancelled or an interruption was
/// requested; otherwise `f(item)` with a panic caught as [`Error::Internal`], reported to
/// the observer (`point`, then `progress` with the count `done` of finished points).
fn run_point<I, T>(
    i: usize,
    item: &I,
    f: &impl Fn(&I) -> Result<T>,
    observer: &dyn Observer<T>,
    done: &AtomicUsize,
    total: usize,
) -> Result<Option<Result<T>>> {
    if observer.cancelled() || crate::interrupt::requested() {
        return Ok(None);
    }
    let r =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(item))).unwrap_or_else(|p| {
            Err(Error::Internal {
                message: panic_message(p),
            })
        });
    observer.point(i, &r)?;
    let d = done.fetch_add(1, Ordering::SeqCst) + 1;
    observer.progress(d, total);
    Ok(Some(r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panics_become_errors_of_their_point_and_order_is_kept() {
        let r = Executor::new()
            .threads(Some(2))
            .map(
                &[1, 2, 3, 4],
                |&x: &i32| {
                    if x == 3 {
                        panic!("boom {x}");
                    }
                    Ok(x * 10)
                },
                &Quiet,
            )
            .unwrap();
        let v: Vec<_> = r.into_iter().map(|x| x.unwrap()).collect();
        assert_eq!(v[0].as_ref().unwrap(), &10);
        assert_eq!(v[3].as_ref().unwrap(), &40);
        let e = v[2].as_ref().unwrap_err().to_string();
        assert_eq!(e, "internal error (panic): boom 3");
    }

    #[test]
    fn cancellation_stops_new_points() {
        let flag = AtomicBool::new(true);
        let obs = Progress {
            report: &|_, _| {},
            cancel: Some(&flag),
        };
        let r = Executor::new()
            .threads(Some(1))
            .map(&[1, 2, 3], |&x: &i32| Ok(x), &obs)
            .unwrap();
        assert!(r.iter().all(Option::is_none));
    }
}

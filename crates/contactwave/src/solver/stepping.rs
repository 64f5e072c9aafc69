//! The time loop of the explicit solvers ([`super::bar_stack`], and through it
//! [`super::half_space_fd`]; [`super::half_space_fd_shear`]; the 2D spectral elements of
//! [`super::solid_2d`]): one loop for every scheme that advances fixed steps `dt` from
//! `t0`. It checks for an interruption and reports progress every [`CHECK_EVERY`] steps
//! (or the schedule's own `check_every`), asks the scheme whether its new
//! level is finite at the same cadence and at the last step, and hands every
//! `record_every`-th level (and the first) to a [`Recorder`]. The schemes say how a step
//! is taken ([`Scheme`]); what is recorded, and in which form, is the recorder's.
//!
//! The loop has no breakpoints and no tail until rest: the explicit schemes run a number
//! of steps fixed beforehand (the burst and a tail of given length), and their step
//! functions evaluate the sources at the step's times themselves.
//!
//! Why the exact solvers keep their own loop ([`super::exact_loop`]) beside this one: a
//! step there is not a level of fixed length but an interval of the output grid that the
//! solver splits at the waveforms' breakpoints and at located events (variable sub-steps,
//! a tail that ends when the interface has rested a period, fast paths that take runs of
//! whole grid steps at once), while here a step is one level of a fixed-step scheme that
//! may be checked for finiteness and recorded every n-th level. The shared parts (the
//! interrupt check and its cadence, [`CHECK_EVERY`] = `exact_loop::INTERRUPT_STEPS`, and a
//! recorder that observes the levels) are the same in both. Measured (the grid steps of
//! `examples/rccm_0.82MPa.toml` and `examples/unilateral.toml`, 3799 each, counted in a
//! build instrumented for it): 3570 and 3574 are taken in runs of whole steps by the
//! normal solver's fast paths (no per-step call of the loop), 200 as single whole steps,
//! and only 29 and 25 through the general path with event location; the analysis run's
//! locked interface takes 3598 in runs. A per-level loop like this one would call into the
//! solver for every one of them, which is what the exact loop's runs avoid.

use crate::error::Result;

/// Steps between two interruption checks (and progress reports, and finiteness checks).
pub const CHECK_EVERY: usize = 4096;

/// An explicit time-stepping scheme as the loop drives it: levels `t0 + k dt`.
pub(crate) trait Scheme {
    /// Compute the next level from the current and previous ones: the step from `t` to
    /// `t1 = t + dt` (s). An error stops the run.
    fn step(&mut self, t: f64, t1: f64) -> Result<()>;
    /// An error when the next level holds a non-finite value (at `t1`, s). Called every
    /// [`CHECK_EVERY`] steps and after the last, before [`Scheme::advance`].
    fn check_finite(&self, t1: f64) -> Result<()>;
    /// Make the next level the current one.
    fn advance(&mut self);
}

/// What observes the levels of a run: the first level and every `record_every`-th after
/// it, after [`Scheme::advance`] (the recorded level is the scheme's current one).
pub(crate) trait Recorder<S: ?Sized> {
    /// Record the current level of `scheme`, at time `t` (s).
    fn record(&mut self, t: f64, scheme: &S);
}

/// The steps of a run.
#[derive(Clone, Copy)]
pub(crate) struct Schedule<'a> {
    /// Time of the first level, s.
    pub t0: f64,
    /// Time step, s.
    pub dt: f64,
    /// Number of steps.
    pub steps: usize,
    /// Record every n-th level (0 is taken as 1).
    pub record_every: usize,
    /// Steps between two interruption checks and progress reports (0: [`CHECK_EVERY`]; a
    /// scheme whose steps are long checks more often).
    pub check_every: usize,
    /// Progress report `(step, steps)`, every [`CHECK_EVERY`] steps.
    pub progress: Option<&'a (dyn Fn(usize, usize) + Send + Sync)>,
}

/// Run `scheme` over `schedule`, recording into `recorder`.
pub(crate) fn run<S: Scheme, R: Recorder<S>>(
    schedule: &Schedule,
    scheme: &mut S,
    recorder: &mut R,
) -> Result<()> {
    let Schedule {
        t0,
        dt,
        steps,
        record_every,
        check_every,
        progress,
    } = *schedule;
    let every = record_every.max(1);
    let check = if check_every == 0 {
        CHECK_EVERY
    } else {
        check_every
    };
    recorder.record(t0, scheme);
    for step in 0..steps {
        if step % check == 0 {
            crate::interrupt::check()?;
            if let Some(p) = progress {
                p(step, steps);
            }
        }
        let t = t0 + step as f64 * dt;
        let t1 = t + dt;
        scheme.step(t, t1)?;
        // (every CHECK_EVERY steps whatever the interruption cadence: a scan of the whole
        // state every few steps of a large 2D mesh took 4 % of a thread)
        if step % CHECK_EVERY == CHECK_EVERY - 1 || step + 1 == steps {
            scheme.check_finite(t1)?;
        }
        scheme.advance();
        if (step + 1) % every == 0 {
            recorder.record(t1, scheme);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    /// `u' = -u` by explicit Euler: `u_k = (1 - dt)^k`.
    struct Decay {
        u: f64,
        next: f64,
        dt: f64,
        steps: usize,
        checks: std::cell::Cell<usize>,
    }

    impl Scheme for Decay {
        fn step(&mut self, _t: f64, _t1: f64) -> Result<()> {
            self.next = self.u - self.dt * self.u;
            self.steps += 1;
            Ok(())
        }
        fn check_finite(&self, t1: f64) -> Result<()> {
            self.checks.set(self.checks.get() + 1);
            if self.next.is_finite() {
                Ok(())
            } else {
                Err(Error::numerical(t1, "decay", "non-finite"))
            }
        }
        fn advance(&mut self) {
            self.u = self.next;
        }
    }

    #[derive(Default)]
    struct Levels(Vec<(f64, f64)>);

    impl Recorder<Decay> for Levels {
        fn record(&mut self, t: f64, s: &Decay) {
            self.0.push((t, s.u));
        }
    }

    #[test]
    fn records_the_first_level_and_every_nth_after_the_step() {
        let mut s = Decay {
            u: 1.0,
            next: 0.0,
            dt: 0.1,
            steps: 0,
            checks: Default::default(),
        };
        let mut tape = Levels::default();
        let schedule = Schedule {
            t0: -0.2,
            dt: 0.1,
            steps: 10,
            record_every: 3,
            check_every: 0,
            progress: None,
        };
        run(&schedule, &mut s, &mut tape).unwrap();
        assert_eq!(s.steps, 10);
        // levels 0, 3, 6, 9 at t0 + k dt, each the value after k steps
        let want: Vec<(f64, f64)> = [0usize, 3, 6, 9]
            .iter()
            .map(|&k| {
                let t = (0..k).fold(-0.2, |t, _| t + 0.1);
                (t, 0.9f64.powi(k as i32))
            })
            .collect();
        assert_eq!(tape.0.len(), want.len());
        for ((t, u), (tw, uw)) in tape.0.iter().zip(&want) {
            assert!((t - tw).abs() < 1e-12, "t {t} vs {tw}");
            assert!((u - uw).abs() < 1e-12, "u {u} vs {uw}");
        }
    }

    #[test]
    fn a_non_finite_level_stops_the_run_at_the_last_step() {
        // dt = -1e308: the values overflow to infinity within a few steps
        let mut s = Decay {
            u: 1.0,
            next: 0.0,
            dt: -1e308,
            steps: 0,
            checks: Default::default(),
        };
        let schedule = Schedule {
            t0: 0.0,
            dt: 1.0,
            steps: 5,
            record_every: 1,
            check_every: 0,
            progress: None,
        };
        let err = run(&schedule, &mut s, &mut Levels::default()).unwrap_err();
        assert!(err.to_string().contains("non-finite"), "{err}");
        assert_eq!(s.steps, 5);
    }

    #[test]
    fn finiteness_is_checked_every_check_every_steps_whatever_the_interrupt_cadence() {
        // interruption checks every step; the scan of the state only every CHECK_EVERY
        // steps and after the last
        let mut s = Decay {
            u: 1.0,
            next: 0.0,
            dt: 1e-6,
            steps: 0,
            checks: Default::default(),
        };
        let schedule = Schedule {
            t0: 0.0,
            dt: 1e-6,
            steps: 2 * CHECK_EVERY + 5,
            record_every: 1,
            check_every: 1,
            progress: None,
        };
        run(&schedule, &mut s, &mut Levels::default()).unwrap();
        assert_eq!(s.steps, 2 * CHECK_EVERY + 5);
        assert_eq!(s.checks.get(), 3);
    }
}

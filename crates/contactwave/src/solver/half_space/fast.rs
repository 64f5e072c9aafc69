//! The time loop's fast paths (model.md section 4): whole grid steps taken as
//! [`GapRun::advance`] would take them, bit for bit, without its event machinery. A stuck
//! step reads the incident table; an ODE step of an affine phase applies the collocation
//! map planned once per step length and slope ([`AffineMap`]) and evaluates the damage
//! event function only above the law's damage onset. The time loop
//! ([`crate::solver::exact_loop::run`]) reaches them through the solver's [`GridSolver`].

use super::ode::Phase;
use super::{GapRun, HalfSpaceOutput, Integrals, Sink, EVENT_HYSTERESIS};
use crate::error::{Error, Result};
use crate::solver::exact_loop::{Driven, GridSolver};
use crate::solver::radau::{self, Affine, AffineMap, Step, System};

impl GapRun<'_> {
    /// The whole grid step `k` from `ta` to `tb` (s) of a stuck phase that it does not
    /// leave, straight from the incident table (after the burst: nothing to add): the
    /// quadrature of [`GapRun::advance`] without its event search. Returns `false`
    /// (nothing done) where `advance` must take the step: not a stuck phase, a step
    /// outside the table, or an exit event inside.
    #[inline]
    pub(super) fn stuck_grid_step(
        &mut self,
        acc: &mut Integrals,
        k: usize,
        ta: f64,
        tb: f64,
    ) -> bool {
        let phase = self.ode.phase;
        phase.is_stuck()
            && self
                .stuck_table_step(acc, phase, k, ta, tb, |r| r.stuck_event(phase, ta))
                .is_some()
    }

    /// [`GapRun::stuck_grid_step`] in the stuck `phase`, with `prev` giving the exit
    /// function at the step start (asked only where it is needed). Returns the exit
    /// function at the step end (the next step's start; NaN where none was evaluated), or
    /// `None` where the step is declined.
    #[inline]
    fn stuck_table_step(
        &mut self,
        acc: &mut Integrals,
        phase: Phase,
        k: usize,
        ta: f64,
        tb: f64,
        prev: impl FnOnce(&Self) -> f64,
    ) -> Option<f64> {
        if self.ode.grid.after_burst(k) {
            // a stuck phase with no incident wave: its exit function is the same at every
            // node (it cannot turn positive within the step) and the quadrature adds zeros
            return Some(f64::NAN);
        }
        let sinc = self.ode.grid.stuck_at(k)?;
        let mut end = f64::NAN;
        if phase != Phase::Locked {
            if self.stuck_exit(phase, prev(self), &sinc) {
                return None;
            }
            end = self.stuck_event_of(phase, sinc[4]);
        }
        self.ode.remember(tb, sinc[4]);
        self.acc_stuck_cached(acc, tb - ta, &sinc);
        Some(end)
    }

    /// [`GapRun::advance`]'s event check of a stuck step: whether an exit function turns
    /// positive at a node of `sinc` (the incident stress at [`super::ode::STUCK_NODES`],
    /// Pa), from `prev`, its value at the step start (no branch per node).
    #[inline]
    fn stuck_exit(&self, phase: Phase, prev: f64, sinc: &[f64; 5]) -> bool {
        let mut prev_quiet = prev <= 0.0;
        let mut exit = false;
        for &s in sinc {
            let e = self.stuck_event_of(phase, s);
            exit |= (e > 0.0) & prev_quiet;
            prev_quiet = e <= 0.0;
        }
        exit
    }

    /// Whole stuck grid steps from `k0` (up to `k_end`, exclusive) as the time loop takes
    /// them one by one through [`GapRun::stuck_grid_step`] (bit for bit), each recorded
    /// into `sink` (its next breakpoint advanced). Stops at a step with a breakpoint inside
    /// or one the fast path declines (an exit event). Returns the number of steps taken.
    pub(super) fn stuck_run(
        &mut self,
        sink: &mut Sink,
        k0: usize,
        k_end: usize,
        y: [f64; 2],
    ) -> Result<usize> {
        let (acc, out, breaks, bi) = (&mut *sink.acc, &mut *sink.out, sink.breaks, &mut *sink.bi);
        let phase = self.ode.phase;
        if !phase.is_stuck() {
            return Ok(0);
        }
        let h = self.h;
        self.max_gap = self.max_gap.max(y[0]);
        // the exit function at the step start: the last node's of the step before (the
        // value the incident cache holds for that time)
        let mut prev: Option<f64> = None;
        let mut k = k0;
        while k < k_end {
            let (ta, tb) = (k as f64 * h, (k + 1) as f64 * h);
            while *bi < breaks.len() && breaks[*bi] <= ta {
                *bi += 1;
            }
            if *bi < breaks.len() && breaks[*bi] < tb {
                break;
            }
            let start = |r: &Self| prev.unwrap_or_else(|| r.stuck_event(phase, ta));
            match self.stuck_table_step(acc, phase, k, ta, tb, start) {
                Some(end) => prev = end.is_finite().then_some(end),
                None => break,
            }
            k += 1;
            if k.is_multiple_of(4096) {
                crate::interrupt::check()?;
            }
            self.record(out, acc, tb, y);
        }
        Ok(k - k0)
    }

    /// Take the ODE step `st` of length `h` from `(t, y0)`: the largest gap over its
    /// stages, its quadrature, and its end state in `y` (beta never increases); a
    /// non-finite end state is refused.
    pub(super) fn take_ode(
        &mut self,
        acc: &mut Integrals,
        t: f64,
        h: f64,
        y0: [f64; 2],
        st: &radau::Step<2>,
        y: &mut [f64; 2],
    ) -> Result<()> {
        if !(st.end()[0].is_finite() && st.end()[1].is_finite()) {
            return Err(Error::numerical(
                t,
                "non-finite state",
                format!("{:?}", st.end()),
            ));
        }
        for s in &st.stages {
            self.max_gap = self.max_gap.max(s[0]);
        }
        self.acc_ode(acc, t, h, y0, st);
        *y = st.end();
        y[1] = self.ode.beta(*y).min(y0[1]).max(0.0);
        Ok(())
    }

    /// The whole grid step `[ta, tb]` (s) of an ODE phase when no event happens in it, as
    /// [`GapRun::advance`] takes it (the same step, event checks and quadrature, bit for
    /// bit) without its event machinery. Returns `false` (nothing done) where `advance`
    /// must take the step: a stuck phase, a boundary-layer ramp, a step right after a
    /// switch, an event function past its threshold at the start, the end or a stage, or
    /// a step Newton cannot take in one piece, or in an affine phase a step that leaves the
    /// interval (the gap event is past its threshold there). In an affine phase the step
    /// is [`AffineMap`]'s (planned once per step length and slope) and the damage event
    /// function is evaluated only above the law's damage onset.
    #[inline]
    pub(super) fn ode_grid_step(
        &mut self,
        acc: &mut Integrals,
        ta: f64,
        tb: f64,
        y: &mut [f64; 2],
    ) -> Result<bool> {
        let phase = self.ode.phase;
        if phase.is_stuck()
            || self.ramp.is_some()
            || ta == self.last_switch
            || ta == self.last_mode_switch
        {
            return Ok(false);
        }
        let h = tb - ta;
        let y0 = *y;
        let ap = self.affine_phase(y0);
        // the start is the previous step's end when the state was left as it was
        let start_quiet = match self.end_events {
            (t, bits, p, q) if t == ta && bits == y0.map(f64::to_bits) && p == phase => q,
            _ => self.quiet(&ap, phase, ta, y0).1,
        };
        if !start_quiet {
            return Ok(false);
        }
        // the step leaves the incident cache as advance would find it if declined (its
        // Newton path reads the step start from the cache: the tabulated value)
        let cache = self.ode.cache.get();
        let st = match self.affine_stages(&ap, ta, h, y0) {
            Some(st) => Some(st),
            // an affine phase whose step leaves the interval: the gap event is past its
            // threshold at a stage (the general path locates it)
            None if ap.affine.is_some() => None,
            None => {
                self.ode.cache.set(cache);
                radau::step(&self.ode, ta, y0, h, self.scale)
            }
        };
        let decline = |r: &Self| {
            r.ode.cache.set(cache);
            Ok(false)
        };
        let Some(st) = st else {
            return decline(self);
        };
        let (end_quiet, next_start_quiet) = self.quiet(&ap, phase, tb, st.end());
        if !end_quiet {
            return decline(self);
        }
        for j in 0..2 {
            let tj = ta + radau::C[j] * h;
            if !self.quiet(&ap, phase, tj, st.stages[j]).0 {
                return decline(self);
            }
        }
        self.take_ode(acc, ta, h, y0, &st, y)?;
        self.end_events = (tb, st.end().map(f64::to_bits), phase, next_start_quiet);
        Ok(true)
    }

    /// The affine interval and damage onset of the current ODE phase at adhesion `y[1]`
    /// (cached until the phase or the adhesion changes).
    #[inline]
    pub(super) fn affine_phase(&mut self, y: [f64; 2]) -> AffinePhase {
        let phase = self.ode.phase;
        match self.affine_phase {
            Some(a) if a.phase == phase && a.adhesion == y[1].to_bits() => a,
            _ => {
                let a = AffinePhase {
                    phase,
                    adhesion: y[1].to_bits(),
                    affine: if !self.ode.active()[1] {
                        self.ode.affine(y)
                    } else {
                        None
                    },
                    stiffness: self.ode.affine_stiffness(y).unwrap_or(f64::NAN),
                    onset: match phase {
                        Phase::Traction if self.has_damage => {
                            self.hs.law.traction.damage_onset(y[1])
                        }
                        Phase::Compression | Phase::Traction => f64::INFINITY,
                        _ => 0.0,
                    },
                };
                self.affine_phase = Some(a);
                a
            }
        }
    }

    /// Whether no event function of `phase` at `(t, y)` is past its threshold:
    /// `(at the hysteresis of a step's end and stages, at 0 as a step's start)`. The
    /// values of [`GapRun::ode_events`]; below the opening `ap.onset` (where the damage
    /// function is negative, or the phase has none) only the gap event's sign decides, and
    /// its division is made only where the gap is past `[u]_c`.
    #[inline]
    pub(super) fn quiet(
        &self,
        ap: &AffinePhase,
        phase: Phase,
        t: f64,
        y: [f64; 2],
    ) -> (bool, bool) {
        let uc = self.ode.uc;
        if phase != Phase::Damaging && (y[0] - uc).max(0.0) < ap.onset {
            let toward_other_branch = if phase == Phase::Compression {
                y[0] - uc
            } else {
                uc - y[0]
            };
            let gap = toward_other_branch <= 0.0 || self.gap_event(phase, y) <= 0.0;
            return (gap, gap);
        }
        let e = self.ode_events(phase, t, y);
        (
            e[0] <= 0.0 && e[1] <= EVENT_HYSTERESIS,
            e[0] <= 0.0 && e[1] <= 0.0,
        )
    }

    /// The step of [`radau::step`] in an affine phase (its `affine_step`, the same
    /// arithmetic), with the map from [`Maps`]; `None` where that step is refused (a start
    /// or stage outside the interval, a singular map) or the phase is not affine.
    #[inline]
    fn affine_stages(&mut self, ap: &AffinePhase, t: f64, h: f64, y: [f64; 2]) -> Option<Step<2>> {
        let a = ap.affine?;
        if !(y[0] >= a.lower && y[0] <= a.upper) {
            return None;
        }
        let map = self.maps.get(h, self.ode.mass()[0], a.slope)?;
        radau::affine_step_with(&self.ode, t, y, h, a, map)
    }
}

/// The affine interval of an ODE phase at one adhesion, and its damage onset.
#[derive(Debug, Clone, Copy)]
pub(super) struct AffinePhase {
    phase: Phase,
    /// The adhesion beta, as bits.
    adhesion: u64,
    /// [`System::affine`] of the phase (`None`: not affine).
    pub(super) affine: Option<Affine>,
    /// The branch's constant tangent where the phase is affine, Pa/m (else NaN).
    pub(super) stiffness: f64,
    /// The opening below which no damage event can happen, m:
    /// [`crate::law::TractionBranch::damage_onset`] in a damaging traction phase, `inf` in
    /// a phase without damage, 0 while damaging.
    pub(super) onset: f64,
}

/// The [`AffineMap`]s of the last few `(step, mass, slope)` met: a grid step `tb - ta` takes
/// a few values that differ in the last bits, and a phase keeps its slope.
#[derive(Debug)]
pub(super) struct Maps {
    /// `(step, mass, slope)` as bits (`u64::MAX`: empty).
    keys: [[u64; 3]; MAPS],
    maps: [Option<AffineMap>; MAPS],
    next: usize,
}

/// Entries of [`Maps`].
const MAPS: usize = 4;

impl Default for Maps {
    fn default() -> Self {
        Maps {
            keys: [[u64::MAX; 3]; MAPS],
            maps: [None; MAPS],
            next: 0,
        }
    }
}

impl Maps {
    /// The map of step `h` (s), mass `m` and slope `slope` (`None`: singular).
    #[inline]
    pub(super) fn get(&mut self, h: f64, m: f64, slope: f64) -> Option<&AffineMap> {
        let (a, b, c) = (h.to_bits(), m.to_bits(), slope.to_bits());
        let i = match (0..MAPS).find(|&i| {
            let k = &self.keys[i];
            k[0] == a && k[1] == b && k[2] == c
        }) {
            Some(i) => i,
            None => {
                let i = self.next;
                self.keys[i] = [a, b, c];
                self.maps[i] = AffineMap::new(h, m, slope);
                self.next = (i + 1) % MAPS;
                i
            }
        };
        self.maps[i].as_ref()
    }
}

/// The paths a run may take: every one (what every run does), or (in the tests that
/// compare them with the general path) fewer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Paths {
    /// Every path: the fast paths and the runs of affine steps.
    All,
    /// The fast paths of whole grid steps, but no runs of affine steps.
    #[cfg(test)]
    NoAffineBlocks,
    /// Every step through [`GapRun::advance`].
    #[cfg(test)]
    General,
}

impl Paths {
    /// Whether whole grid steps may take the fast paths.
    #[inline]
    pub(super) fn fast(self) -> bool {
        #[cfg(test)]
        return self != Paths::General;
        #[cfg(not(test))]
        true
    }

    /// Whether runs of affine steps may be taken by [`GapRun::affine_block`].
    #[inline]
    pub(super) fn affine_blocks(self) -> bool {
        self == Paths::All
    }
}

/// A run of the exact solver as [`exact_loop::run`] drives it: its fast paths take whole
/// grid steps where the run's `paths` allow.
impl GridSolver for Driven<'_, GapRun<'_>, Integrals, HalfSpaceOutput> {
    type State = [f64; 2];

    #[inline]
    fn enter_step(&mut self, k: usize, ta: f64, tb: f64) {
        self.solver.ode.grid.enter_step(k, ta, tb);
    }

    fn whole_steps(
        &mut self,
        k: usize,
        k_end: usize,
        breaks: &[f64],
        bi: &mut usize,
        y: &mut [f64; 2],
    ) -> Result<usize> {
        let mut sink = Sink {
            acc: &mut self.acc,
            out: &mut self.out,
            breaks,
            bi,
        };
        if self.solver.ode.phase.is_stuck() {
            if self.solver.paths.fast() {
                return self.solver.stuck_run(&mut sink, k, k_end, *y);
            }
        } else if self.solver.paths.affine_blocks() {
            return self.solver.affine_block(&mut sink, k, k_end, y);
        }
        Ok(0)
    }

    #[inline]
    fn whole_step(&mut self, k: usize, ta: f64, tb: f64, y: &mut [f64; 2]) -> Result<bool> {
        Ok(self.solver.paths.fast()
            && (self.solver.stuck_grid_step(&mut self.acc, k, ta, tb)
                || self.solver.ode_grid_step(&mut self.acc, ta, tb, y)?))
    }

    fn advance(&mut self, t: f64, t_end: f64, y: &mut [f64; 2]) -> Result<()> {
        self.solver.advance(&mut self.acc, t, t_end, y)
    }

    #[inline]
    fn record(&mut self, t: f64, y: &[f64; 2]) {
        self.solver.max_gap = self.solver.max_gap.max(y[0]);
        self.solver.record(&mut self.out, &self.acc, t, *y);
    }

    fn at_rest(&self, _t: f64, y: &[f64; 2]) -> bool {
        self.solver.at_rest(*y)
    }
}

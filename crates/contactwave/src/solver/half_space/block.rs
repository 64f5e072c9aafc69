//! Runs of whole grid steps in one affine ODE phase (model.md section 4): a compliant
//! compression branch of constant stiffness, or a traction branch linear in the opening at
//! fixed adhesion (free, linear, RCCM below its damage onset). The gap equation is then
//! linear, `d[u]/dt = (2/Z1) s_inc - (1/Z1 + 1/Z2) (S0 + K ([u] - [u]0))`, and the Radau
//! step is the collocation map `z = P f` ([`AffineMap`]) of the stage right-hand sides.
//! One loop takes step after step with the phase's constants in registers, reads the
//! incident stress from the grid's table, checks the event functions at the stages and
//! the end as [`GapRun::advance`] does, integrates and records; it hands the step back to
//! the general path where anything happens (an event function past its threshold, a stage
//! leaving the interval, a breakpoint inside the step, a step beyond the table inside the
//! burst).

use super::fast::AffinePhase;
use super::ode::Phase;
use super::{GapRun, Sink};
use crate::error::{Error, Result};
use crate::solver::quadrature::StageSums;
use crate::solver::radau::{self, AffineMap};

impl GapRun<'_> {
    /// Take whole grid steps from `k0` (at most up to `k_end`, exclusive) while the interface
    /// stays in its affine ODE phase and nothing happens, into `sink` (its next breakpoint
    /// advanced as the loop goes). Records each step. Returns the number of
    /// steps taken (0: the first step is not one this loop takes).
    pub(super) fn affine_block(
        &mut self,
        sink: &mut Sink,
        k0: usize,
        k_end: usize,
        y: &mut [f64; 2],
    ) -> Result<usize> {
        let (acc, out, breaks, bi) = (&mut *sink.acc, &mut *sink.out, sink.breaks, &mut *sink.bi);
        let phase = self.ode.phase;
        let h = self.h;
        let ta0 = k0 as f64 * h;
        if phase.is_stuck()
            || self.ramp.is_some()
            || ta0 == self.last_switch
            || ta0 == self.last_mode_switch
            || k0 >= k_end
        {
            return Ok(0);
        }
        let ap = self.affine_phase(*y);
        let Some(a) = ap.affine else {
            return Ok(0);
        };
        let start_quiet = match self.end_events {
            (t, bits, p, q) if t == ta0 && bits == y.map(f64::to_bits) && p == phase => q,
            _ => self.quiet(&ap, phase, ta0, *y).1,
        };
        if !(start_quiet && y[0] >= a.lower && y[0] <= a.upper) {
            return Ok(0);
        }
        let c = BlockConstants::new(self, &ap, *y);
        let uc = self.ode.uc;
        let mut map: Option<(u64, AffineMap)> = None;
        let mut k = k0;
        let result = loop {
            if k >= k_end {
                break Ok(());
            }
            let (ta, tb) = (k as f64 * h, (k + 1) as f64 * h);
            while *bi < breaks.len() && breaks[*bi] <= ta {
                *bi += 1;
            }
            if *bi < breaks.len() && breaks[*bi] < tb {
                break Ok(());
            }
            let hk = tb - ta;
            let g = match self.ode.grid.radau_at(k) {
                Some(g) => g,
                None if self.ode.grid.after_burst(k) => [0.0; 3],
                None => break Ok(()),
            };
            let p = match map {
                Some((bits, m)) if bits == hk.to_bits() => m,
                _ => match self.maps.get(hk, 1.0, a.slope) {
                    Some(m) => {
                        map = Some((hk.to_bits(), *m));
                        *m
                    }
                    None => break Ok(()),
                },
            };
            // the step: stage right-hand sides at the start state, then z = P f
            let s = c.s0 + c.stiffness * (y[0] - c.y0);
            let f = g.map(|gl| c.two_over_z1 * gl - c.k * s);
            let z = p.apply(f);
            let stages = z.map(|zj| y[0] + zj);
            if !stages.iter().all(|&v| v >= a.lower && v <= a.upper) {
                break Ok(());
            }
            // event functions at the two inner stages and the end (threshold: the
            // hysteresis), and at the end as the next step's start (threshold 0); below
            // the damage onset only the gap event's sign counts (GapRun::quiet), and a
            // stage inside the interval is on the phase's side of [u]_c
            let mut quiet = true;
            let mut next_quiet = true;
            if !stages.iter().all(|&v| (v - uc).max(0.0) < ap.onset) {
                for (j, &v) in stages.iter().enumerate() {
                    let (q, q0) = self.quiet(&ap, phase, ta + radau::C[j] * hk, [v, y[1]]);
                    quiet &= q;
                    if j == 2 {
                        next_quiet = q0;
                    }
                }
            }
            if !quiet {
                break Ok(());
            }
            if !stages[2].is_finite() {
                break Err(Error::numerical(
                    ta,
                    "non-finite state",
                    format!("{stages:?}"),
                ));
            }
            // quadrature (Radau weights), as GapRun::acc_ode
            let mut sum = StageSums::default();
            for j in 0..3 {
                sum.add(radau::B[j], g[j], s + c.stiffness * z[j]);
                // (the stages are numbers here: the interval check refuses NaN)
                if stages[j] > self.max_gap {
                    self.max_gap = stages[j];
                }
            }
            self.add_step(acc, ta, hk, &sum, phase == Phase::Traction);
            y[0] = stages[2];
            self.ode.remember(tb, g[2]);
            k += 1;
            if k.is_multiple_of(4096)
                && let Err(e) = crate::interrupt::check()
            {
                break Err(e);
            }
            self.record(out, acc, tb, *y);
            if !next_quiet {
                break Ok(());
            }
        };
        // the next step starts from scratch (its start events are evaluated again)
        self.end_events.0 = f64::NAN;
        result.map(|()| k - k0)
    }
}

/// What an affine phase keeps constant over a block.
struct BlockConstants {
    /// `2 / Z1`, m/(Pa s).
    two_over_z1: f64,
    /// `1/Z1 + 1/Z2`, m/(Pa s).
    k: f64,
    /// `S = sigma + p0` at the block's start, Pa.
    s0: f64,
    /// The gap at the block's start, m.
    y0: f64,
    /// `d sigma / d[u]` of the phase, Pa/m.
    stiffness: f64,
}

impl BlockConstants {
    fn new(r: &GapRun, ap: &AffinePhase, y: [f64; 2]) -> Self {
        BlockConstants {
            two_over_z1: r.ode.two_over_z1,
            k: r.ode.k,
            s0: r.ode.sigma(y) + r.ode.p0,
            y0: y[0],
            stiffness: ap.stiffness,
        }
    }
}

//! Exact solver of the half-space problem (model.md section 4; thesis eqs. 2.3-2.9, 5.5).
//!
//! Medium 1 fills x < 0, the interface is at x = 0, behind it a rigid wall or medium 2.
//! d'Alembert's solution reduces the problem to one ODE for the gap,
//!
//! ```text
//! d[u]/dt = 2 s_inc(t)/Z1 - (sigma([u], beta) + p0) (1/Z1 + 1/Z2)
//! ```
//!
//! with `s_ref = sigma + p0 - s_inc` and `s_tr = sigma + p0` travelling away undistorted.
//! The solver is exact in space. In time it integrates each phase (closed, compression,
//! traction, damaging) with the 3-stage Radau IIA method (order 5, L-stable) on the
//! output grid, splits steps at the waveform's breakpoints, and locates every opening,
//! closing and damage event by a bracketing root-finder on the event function to machine
//! precision. While a rigid branch is active (Signorini closed, or bonded) the gap is held
//! exactly and the stress is the constraint stress. Energies (incident, reflected,
//! transmitted, released by damage) are integrated with the same quadrature, so the energy
//! audit closes to the integration error.

mod block;
mod fast;
mod ode;

use super::exact_loop::{self, Driven, Grid};
pub use super::output::{EnergyAudit, HalfSpaceOutput};
use super::quadrature::{StageSums, WaveIntegrals};
use super::radau::{self, System};
use super::Solver;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::ContactLaw;
use crate::material::Material;
use crate::numeric::root::brent_past;
use crate::numeric::{GL4_NODES, GL4_WEIGHTS};
use fast::Paths;
pub use ode::Workspace;
use ode::{GapOde, IncidentGrid, Phase, STUCK_NODES};
use std::sync::Arc;

/// Settings of the exact solver.
#[derive(Debug, Clone, Copy)]
pub struct HalfSpaceSettings {
    /// Time samples per period of the highest input frequency.
    pub samples_per_period: usize,
    /// Fixed tail after the burst, periods of f0; `None` = automatic (until the interface
    /// is back at rest, at least 3 and at most 400 periods).
    pub tail_periods: Option<f64>,
    /// Record only the histories a summary needs (`t`, `beta` and
    /// `reflected_displacement`); the other histories of the output stay empty. The
    /// solution and every scalar of the output are the same either way.
    pub summary_only: bool,
}

impl Default for HalfSpaceSettings {
    fn default() -> Self {
        HalfSpaceSettings {
            samples_per_period: 200,
            tail_periods: None,
            summary_only: false,
        }
    }
}

/// The half-space problem: media, law and incident wave.
#[derive(Debug, Clone)]
pub struct HalfSpace {
    /// Medium 1 (x < 0), where the incident wave travels.
    pub medium: Material,
    /// Medium 2 (x > 0), or `None` for a rigid wall.
    pub counterpart: Option<Material>,
    /// Impedance of medium 1, Pa s/m.
    pub z1: f64,
    /// Impedance of medium 2, Pa s/m (`inf`: rigid wall).
    pub z2: f64,
    /// Contact law.
    pub law: Arc<ContactLaw>,
    /// Incident wave.
    pub incident: Arc<dyn Excitation>,
}

#[cfg(test)]
mod tests;

/// Relative threshold of the stuck phases' event functions: a constraint stress that
/// passes the opening (or debonding) threshold by less than this fraction of the stress
/// scale is round-off (a burst whose peak just reaches it, xi = 1, does not open).
const STUCK_TOLERANCE: f64 = 1e-12;

/// Normalised threshold of the damage on/off event functions (phi / w and the scaled
/// opening rate) below which no switch is made.
const EVENT_HYSTERESIS: f64 = 1e-10;

/// Where a run of whole grid steps taken in one go ([`GapRun::stuck_run`],
/// [`GapRun::affine_block`]) writes: the running integrals, the records, and the
/// breakpoints with the index of the next one (advanced as the run goes).
struct Sink<'t> {
    acc: &'t mut Integrals,
    out: &'t mut HalfSpaceOutput,
    breaks: &'t [f64],
    bi: &'t mut usize,
}

/// The running integrals of a run over time: the incident, reflected and transmitted
/// displacements (m), the energies of the three waves and the energy released by damage
/// (J/m^2), and the time the interface was open while the burst was at it (s).
#[derive(Debug, Default, Clone, Copy)]
struct Integrals {
    wave: WaveIntegrals,
    e_damage: f64,
    open_in_burst: f64,
}

impl HalfSpace {
    /// `1/Z1 + 1/Z2`, m/(Pa s).
    pub fn compliance(&self) -> f64 {
        1.0 / self.z1 + crate::material::admittance(self.z2)
    }

    /// Initial phase at rest.
    fn rest_phase(&self) -> Phase {
        match (
            self.law.compression.is_rigid(),
            self.law.traction.is_rigid(),
        ) {
            (true, true) => Phase::Locked,
            (true, false) => Phase::Closed,
            _ => Phase::Compression,
        }
    }

    /// The problem between `medium` and `counterpart` (`None`: a rigid wall).
    pub fn new(
        medium: Material,
        counterpart: Option<Material>,
        law: Arc<ContactLaw>,
        incident: Arc<dyn Excitation>,
    ) -> Self {
        HalfSpace {
            z1: medium.impedance(),
            z2: counterpart.map_or(f64::INFINITY, |m| m.impedance()),
            medium,
            counterpart,
            law,
            incident,
        }
    }

    /// Run the exact solver (on a fresh [`Workspace`]: a first run).
    pub fn solve(&self, settings: &HalfSpaceSettings) -> Result<HalfSpaceOutput> {
        self.solve_in(settings, &mut Workspace::new())
    }

    /// Run the exact solver on the caller's workspace `ws` (one per worker): the incident
    /// table its last run kept is used again, and this run's is kept for the next.
    pub fn solve_in(
        &self,
        settings: &HalfSpaceSettings,
        ws: &mut Workspace,
    ) -> Result<HalfSpaceOutput> {
        self.solve_taking(settings, ws, Paths::All)
    }

    /// [`HalfSpace::solve_in`] taking the `paths` allowed.
    fn solve_taking(
        &self,
        settings: &HalfSpaceSettings,
        ws: &mut Workspace,
        paths: Paths,
    ) -> Result<HalfSpaceOutput> {
        let mut out = HalfSpaceOutput::default();
        self.run_taking(settings, ws, paths, &mut out)?;
        Ok(out)
    }

    /// One run taking the `paths` allowed, recording into `out` (its series' allocations
    /// reused).
    fn run_taking(
        &self,
        settings: &HalfSpaceSettings,
        ws: &mut Workspace,
        paths: Paths,
        out: &mut HalfSpaceOutput,
    ) -> Result<()> {
        let mut run = GapRun::new(self, settings, ws);
        let done = run.run(paths, out);
        ws.keep(&mut run.ode.grid);
        done
    }
}

/// The exact solver as a [`Solver`] of the half-space problem.
#[derive(Debug, Clone, Copy, Default)]
pub struct ExactSolver {
    /// Sampling and tail settings.
    pub settings: HalfSpaceSettings,
}

impl Solver for ExactSolver {
    type Problem = HalfSpace;
    type Workspace = Workspace;
    type Output = HalfSpaceOutput;
    fn run_in(
        &self,
        problem: &HalfSpace,
        ws: &mut Workspace,
        out: &mut HalfSpaceOutput,
    ) -> Result<()> {
        problem.run_taking(&self.settings, ws, Paths::All, out)
    }
}

/// One run of the exact solver: the gap equation of the current phase, the grid step,
/// and what the event location keeps between steps (the time loop is
/// [`exact_loop::run`], driving it as a [`Driven`] run).
struct GapRun<'a> {
    hs: &'a HalfSpace,
    ode: GapOde<'a>,
    h: f64,
    duration: f64,
    scale: [f64; 2],
    ainv: [[f64; 3]; 3],
    settings: HalfSpaceSettings,
    f0: f64,
    events: usize,
    max_gap: f64,
    /// After a phase switch into a stiff phase: the current sub-step size that resolves the
    /// boundary layer (doubled after each sub-step until it reaches the grid step).
    ramp: Option<f64>,
    /// Time of the last damage on/off switch: a second one at the very same time is a
    /// grazing point where both modes agree, and is skipped (no chattering).
    last_mode_switch: f64,
    /// Time of the last phase switch of an ODE phase.
    last_switch: f64,
    /// Gap-event switches made at `last_switch` (guards a grazing ping-pong).
    flips_here: usize,
    /// Whether the traction law damages (cached: asked at every event check).
    has_damage: bool,
    /// Normaliser of the damage event functions, `|w(beta = 1)|` (J/m^2, at least 1e-300).
    w_norm: f64,
    /// `S / s_inc` in a stuck phase, `(2 / Z1) / (1/Z1 + 1/Z2)` (1).
    stuck_gain: f64,
    /// Threshold of the stuck event functions, Pa: [`STUCK_TOLERANCE`] times the larger of
    /// `p0` and the peak stuck stress.
    stuck_tol: f64,
    /// `[1/Z1, 1/Z2]` (`1/Z2 = 0` at a rigid wall), m/(Pa s).
    inv_z: [f64; 2],
    /// What [`GapRun::ode_grid_step`] found last at a step end: time (s), state as bits,
    /// phase, and whether no event function is positive there (the start of the next
    /// step when nothing changed).
    end_events: (f64, [u64; 2], Phase, bool),
    /// The affine interval of the current ODE phase ([`fast::AffinePhase`]).
    affine_phase: Option<fast::AffinePhase>,
    /// The affine maps of the step lengths and slopes met.
    maps: fast::Maps,
    /// The paths the time loop may take.
    paths: Paths,
}

impl<'a> GapRun<'a> {
    fn new(hs: &'a HalfSpace, settings: &HalfSpaceSettings, ws: &mut Workspace) -> Self {
        let k = hs.compliance();
        let p0 = hs.law.static_pressure;
        let uc = hs.law.critical_gap();
        let fmax = hs.incident.highest_frequency();
        let f0 = hs.incident.fundamental();
        let h = 1.0 / (fmax * settings.samples_per_period as f64);
        // typical gap: blocked stress over impedance and frequency, or [u]_c
        let omega = 2.0 * std::f64::consts::PI * f0;
        let gap_scale = (2.0 * hs.incident.peak() / hs.z1 / omega)
            .max(uc.abs())
            .max(1e-30);
        GapRun {
            hs,
            ode: GapOde {
                hs,
                cache: std::cell::Cell::new([(f64::NAN, 0.0); 2]),
                grid: IncidentGrid::new(&*hs.incident, h, hs.rest_phase() == Phase::Locked, ws),
                phase: hs.rest_phase(),
                k,
                p0,
                uc,
                two_over_z1: 2.0 / hs.z1,
            },
            h,
            duration: hs.incident.duration(),
            scale: [gap_scale, 1.0],
            ainv: radau::a_inverse(),
            settings: *settings,
            f0,
            events: 0,
            max_gap: 0.0,
            ramp: None,
            last_mode_switch: f64::NAN,
            last_switch: f64::NAN,
            flips_here: 0,
            has_damage: hs.law.traction.has_damage(),
            w_norm: hs.law.traction.adhesion_energy(1.0).abs().max(1e-300),
            stuck_gain: 2.0 / hs.z1 / k,
            inv_z: [1.0 / hs.z1, crate::material::admittance(hs.z2)],
            end_events: (f64::NAN, [0; 2], Phase::Locked, false),
            affine_phase: None,
            maps: fast::Maps::default(),
            paths: Paths::All,
            stuck_tol: STUCK_TOLERANCE * p0.abs().max(2.0 / hs.z1 / k * hs.incident.peak()),
        }
    }

    /// Interface stress plus p0 (S = sigma + p0) in a stuck phase at time t.
    #[inline]
    fn stuck_s(&self, t: f64) -> f64 {
        self.s_of(self.ode.forcing(t))
    }

    /// Event function of a stuck phase (exit when > 0).
    #[inline]
    fn stuck_event(&self, phase: Phase, t: f64) -> f64 {
        self.stuck_event_of(phase, self.ode.forcing(t))
    }

    /// Event function of a stuck phase from the incident stress `sinc` (Pa): the
    /// constraint stress past [`STUCK_TOLERANCE`] of the stress scale in the direction that
    /// ends the phase (a grazing touch of the threshold within round-off is no event).
    #[inline]
    fn stuck_event_of(&self, phase: Phase, sinc: f64) -> f64 {
        let sigma = self.s_of(sinc) - self.ode.p0;
        match phase {
            Phase::Closed => sigma - self.stuck_tol,
            Phase::Bonded => -sigma - self.stuck_tol,
            _ => f64::NEG_INFINITY,
        }
    }

    /// The gap event function of an ODE phase at state `y` (exit when > 0): the gap past
    /// `[u]_c` towards the other branch, over the gap scale.
    #[inline]
    fn gap_event(&self, phase: Phase, y: [f64; 2]) -> f64 {
        match phase {
            Phase::Compression => (y[0] - self.ode.uc) / self.scale[0],
            _ => (self.ode.uc - y[0]) / self.scale[0],
        }
    }

    /// Event functions of an ODE phase at state y (exit when > 0): `[the gap event, the
    /// damage on/off event]`.
    fn ode_events(&self, phase: Phase, t: f64, y: [f64; 2]) -> [f64; 2] {
        let tr = &self.hs.law.traction;
        let uc = self.ode.uc;
        match phase {
            Phase::Compression => [self.gap_event(phase, y), f64::NEG_INFINITY],
            Phase::Traction => {
                let dmg = if self.has_damage {
                    -tr.damage_driving_force((y[0] - uc).max(0.0), y[1]) / self.w_norm
                } else {
                    f64::NEG_INFINITY
                };
                [self.gap_event(phase, y), dmg]
            }
            Phase::Damaging => {
                let heal = if tr.damage_viscosity() > 0.0 {
                    tr.damage_driving_force((y[0] - uc).max(0.0), y[1]) / self.w_norm
                } else {
                    // rate-independent: damage stops when the opening stops growing
                    -self.ode.gap_rate(t, y) * self.h / self.scale[0]
                };
                [(uc - y[0]) / self.scale[0], heal]
            }
            _ => [f64::NEG_INFINITY; 2],
        }
    }

    fn step_ode(&self, t: f64, y: [f64; 2], h: f64) -> Result<radau::Step<2>> {
        if let Some(s) = radau::step(&self.ode, t, y, h, self.scale) {
            return Ok(s);
        }
        // Newton failed: try two half steps (composition), a few levels deep.
        self.step_ode_split(t, y, h, 0)
    }

    /// A trial step of an event search from `(t, y)` of length `h`: in an affine phase
    /// the phase's linear dynamics continued past the event ([`radau::continued_step`]:
    /// smooth on both sides of a contact event, and the step itself up to it), else the
    /// step.
    /// Also returns whether the step is the step itself ([`GapRun::step_ode`]'s: every
    /// stage inside the affine interval, or not an affine phase).
    fn event_step(&self, t: f64, y: [f64; 2], h: f64) -> Result<(radau::Step<2>, bool)> {
        match radau::continued_step(&self.ode, t, y, h) {
            Some(s) => {
                let inside = self
                    .ode
                    .affine(y)
                    .is_some_and(|a| s.stages.iter().all(|v| v[0] >= a.lower && v[0] <= a.upper));
                Ok((s, inside))
            }
            None => Ok((self.step_ode(t, y, h)?, true)),
        }
    }

    fn step_ode_split(&self, t: f64, y: [f64; 2], h: f64, depth: usize) -> Result<radau::Step<2>> {
        if depth > 12 {
            return Err(Error::numerical(
                t,
                format!("Newton iteration of the gap equation did not converge (step {h:e} s)"),
                format!(
                    "gap = {:e} m, beta = {}, phase = {:?}",
                    y[0], y[1], self.ode.phase
                ),
            ));
        }
        let half = 0.5 * h;
        let a = match radau::step(&self.ode, t, y, half, self.scale) {
            Some(s) => s,
            None => self.step_ode_split(t, y, half, depth + 1)?,
        };
        let b = match radau::step(&self.ode, t + half, a.end(), half, self.scale) {
            Some(s) => s,
            None => self.step_ode_split(t + half, a.end(), half, depth + 1)?,
        };
        // Stage values of a composed step are not collocation values of one step; return
        // the end state in all three (used only for the end value and coarse checks).
        let _ = t;
        Ok(radau::Step {
            stages: [a.end(), b.end(), b.end()],
            forcing: [a.forcing[2], b.forcing[2], b.forcing[2]],
        })
    }

    /// The incident stress at the nodes of the stuck step `[t, t_end]` ([`STUCK_NODES`]:
    /// GL4 and the end, which is cached), from the grid's table where it is a grid step.
    #[inline]
    fn stuck_nodes(&self, t: f64, t_end: f64) -> [f64; 5] {
        let h = t_end - t;
        let v = self.ode.grid.stuck(t, h).unwrap_or_else(|| {
            let mut v = [0.0; 5];
            self.hs.incident.stress_nodes(t, h, &STUCK_NODES, &mut v);
            v
        });
        self.ode.remember(t_end, v[4]);
        v
    }

    /// Accumulate integrals over [t, t_end] of a stuck phase (explicit, GL4).
    fn acc_stuck(&self, acc: &mut Integrals, t: f64, t_end: f64) {
        let sinc = self.stuck_nodes(t, t_end);
        self.acc_stuck_cached(acc, t_end - t, &sinc);
    }

    /// Accumulate a stuck step from the incident stress at its nodes (GL4: sums, then
    /// scale; the end node is not used).
    fn acc_stuck_cached(&self, acc: &mut Integrals, h: f64, sinc: &[f64; 5]) {
        // S = g s_inc and s_ref = (g - 1) s_inc: the integrals of s_inc and s_inc^2 give all
        let (mut d_inc, mut e_inc) = (0.0, 0.0);
        for i in 0..4 {
            let (w, si) = (GL4_WEIGHTS[i], sinc[i]);
            d_inc += w * si;
            e_inc += w * si * si;
        }
        let [iz1, iz2] = self.inv_z;
        acc.wave
            .add_proportional(h, iz1, iz2, self.stuck_gain, d_inc, e_inc);
    }

    /// S = sigma + p0 in a stuck phase from the incident stress.
    #[inline]
    fn s_of(&self, sinc: f64) -> f64 {
        self.stuck_gain * sinc
    }

    /// Accumulate integrals of an ODE step with its stages (Radau quadrature: weighted
    /// sums over the stages, then scaled by `h / Z`).
    fn acc_ode(&self, acc: &mut Integrals, t: f64, h: f64, y0: [f64; 2], st: &radau::Step<2>) {
        let p0 = self.ode.p0;
        let mut sum = StageSums::default();
        for j in 0..3 {
            sum.add(
                radau::B[j],
                st.forcing[j],
                self.ode.sigma(st.stages[j]) + p0,
            );
        }
        let open = matches!(self.ode.phase, Phase::Traction | Phase::Damaging);
        self.add_step(acc, t, h, &sum, open);
        if self.ode.phase == Phase::Damaging {
            let tr = &self.hs.law.traction;
            let b0 = self.ode.beta(y0);
            let betas = [
                self.ode.beta(st.stages[0]),
                self.ode.beta(st.stages[1]),
                self.ode.beta(st.stages[2]),
            ];
            for j in 0..3 {
                let mut dbeta = 0.0;
                for l in 0..3 {
                    dbeta += self.ainv[j][l] * (betas[l] - b0);
                }
                dbeta /= h;
                let d = (st.stages[j][0] - self.ode.uc).max(0.0);
                acc.e_damage += radau::B[j] * h * tr.energy_d_adhesion(d, betas[j]) * (-dbeta);
            }
        }
    }

    /// Add an ODE step from `t` of length `h` (s) to the integrals from its stage sums, and
    /// to the open time in the burst when the interface is `open`.
    #[inline]
    fn add_step(&self, acc: &mut Integrals, t: f64, h: f64, sum: &StageSums, open: bool) {
        acc.wave.add(h, self.inv_z[0], self.inv_z[1], sum, true);
        if open {
            let lo = t.max(0.0);
            let hi = (t + h).min(self.duration);
            if hi > lo {
                acc.open_in_burst += hi - lo;
            }
        }
    }

    /// Record a phase switch at time t (s).
    fn note_switch(&mut self, t: f64) {
        if t == self.last_switch {
            self.flips_here += 1;
        } else {
            self.last_switch = t;
            self.flips_here = 1;
        }
    }

    /// Switch phase after an event at time t with state y (already projected).
    fn switch(&mut self, from: Phase, which: usize, t: f64, y: &mut [f64; 2]) {
        let comp_rigid = self.hs.law.compression.is_rigid();
        let trac_rigid = self.hs.law.traction.is_rigid();
        let uc = self.ode.uc;
        self.events += 1;
        let to = match (from, which) {
            (Phase::Closed, _) => {
                y[0] = 0.0;
                Phase::Traction
            }
            (Phase::Bonded, _) => {
                y[0] = uc;
                Phase::Compression
            }
            (Phase::Compression, _) => {
                y[0] = uc;
                if trac_rigid {
                    Phase::Bonded
                } else {
                    Phase::Traction
                }
            }
            (Phase::Traction | Phase::Damaging, 0) => {
                y[0] = uc;
                if comp_rigid {
                    Phase::Closed
                } else {
                    Phase::Compression
                }
            }
            (Phase::Traction, _) => Phase::Damaging,
            (Phase::Damaging, _) => Phase::Traction,
            (p, _) => p,
        };
        // Closed entered with a tensile constraint stress (grazing): stay open.
        let to = if to == Phase::Closed && self.stuck_event(Phase::Closed, t) > 0.0 {
            Phase::Traction
        } else {
            to
        };
        self.ode.phase = to;
        // A stiff phase entered with a velocity far from its quasi-static one has a
        // boundary layer of duration ~1/lambda: resolve it with growing sub-steps.
        self.ramp = None;
        if !to.is_stuck() {
            // the stiffness of the new phase at the switch state may vanish (a power law
            // at contact loss) while it is large one step later: take the larger of both
            // (with viscous damage the adhesion equation b dbeta/dt = phi is stiff too:
            // its rate is |dphi/dbeta| / b)
            let stiffness = |y: [f64; 2]| {
                let j = self.ode.gap_jacobian(y);
                let mut l = j[0][0].abs();
                if self.ode.active()[1] {
                    // |dphi/dbeta| whether or not damage is active at y (at beta = 0 with
                    // w = 0 the Jacobian row vanishes although the rate is not small)
                    let d = (y[0] - self.ode.uc).max(0.0);
                    let (_, pb) = self.hs.law.traction.damage_driving_force_gradient(d, y[1]);
                    l = l.max(pb.abs() / self.ode.mass()[1]);
                }
                l
            };
            let mut lambda = stiffness(*y);
            // (a one-component phase whose branch has a constant tangent has the same
            // stiffness one step later: no probe step)
            let constant = !self.ode.active()[1] && self.ode.affine(*y).is_some();
            if constant {
            } else if let Ok(st) = self.step_ode(t, *y, self.h) {
                let end = st.end();
                if end[0].is_finite() && end[1].is_finite() {
                    lambda = lambda.max(stiffness(end));
                }
            }
            if lambda * self.h > 2.0 {
                self.ramp = Some(0.05 / lambda);
            }
        }
    }

    /// Advance from t to t_end (no breakpoint inside), updating y, the phase, the
    /// integrals. Returns when t_end is reached.
    fn advance(
        &mut self,
        acc: &mut Integrals,
        mut t: f64,
        t_end: f64,
        y: &mut [f64; 2],
    ) -> Result<()> {
        let mut guard = exact_loop::EventGuard::default();
        while t < t_end {
            guard.tick(t, "half-space solver", || {
                format!(
                    "gap = {:e} m, beta = {}, phase = {:?}",
                    y[0], y[1], self.ode.phase
                )
            })?;
            let h = t_end - t;
            let phase = self.ode.phase;
            if phase.is_stuck() {
                if phase == Phase::Locked {
                    self.acc_stuck(acc, t, t_end);
                    return Ok(());
                }
                let e0 = self.stuck_event(phase, t);
                // incident stress at the GL nodes and the end: used for the event check
                // and the quadrature alike
                let sinc = self.stuck_nodes(t, t_end);
                let ev = |s: f64| self.stuck_event_of(phase, s);
                let mut hit = None;
                let mut prev_t = t;
                let mut prev_e = e0;
                for i in 0..5 {
                    let tau = if i < 4 { t + GL4_NODES[i] * h } else { t_end };
                    let e = ev(sinc[i]);
                    if e > 0.0 && prev_e <= 0.0 {
                        hit = Some((prev_t, prev_e, tau, e));
                        break;
                    }
                    prev_t = tau;
                    prev_e = e;
                }
                match hit {
                    None => {
                        self.acc_stuck_cached(acc, h, &sinc);
                        t = t_end;
                    }
                    Some((a, fa, b, fb)) => {
                        let fa = if fa == 0.0 { -f64::MIN_POSITIVE } else { fa };
                        let te = brent_past(|s| self.stuck_event(phase, s), a, b, fa, fb, 200)
                            .ok_or_else(|| {
                                Error::numerical(
                                    a,
                                    "cannot bracket the opening event",
                                    format!("phase = {phase:?}"),
                                )
                            })?;
                        self.acc_stuck(acc, t, te);
                        t = te;
                        self.switch(phase, 0, t, y);
                    }
                }
                continue;
            }
            // ODE phase (sub-steps growing from the boundary-layer scale after a switch)
            // (a ramp longer than what is left of this step continues into the next one)
            let (h, t_end) = match self.ramp {
                Some(r) if r < h => (r, t + r),
                _ => (h, t_end),
            };
            let y0 = *y;
            let e_start = self.ode_events(phase, t, y0);
            // the state is already across the gap event (a grazing touch stepped over, or
            // round-off): switch now; twice at the same instant means a true grazing point
            // where both phases agree, so step on
            if e_start[0] > 0.0 && !(t == self.last_switch && self.flips_here >= 2) {
                self.note_switch(t);
                self.switch(phase, 0, t, y);
                continue;
            }
            // clearly past the damage on/off threshold (e.g. w = 0: any opening damages, and
            // the event is already positive one step into the opening): switch now
            if e_start[1] > EVENT_HYSTERESIS
                && t != self.last_mode_switch
                && !(t == self.last_switch && self.flips_here >= 2)
            {
                self.note_switch(t);
                self.last_mode_switch = t;
                self.switch(phase, 1, t, y);
                continue;
            }
            // (the step, or in an affine phase whose step leaves the interval the branch
            // continued: what the event search evaluates on both sides of the event)
            let (st, whole) = self.event_step(t, y0, h)?;
            // (which, tau_hi, the step of length tau_hi: reused as the bracket's end)
            let mut first: Option<(usize, f64, radau::Step<2>)> = None;
            // the event functions at the step end and (when needed) at the first two
            // stages, each evaluated once for both events
            let ev_end = self.ode_events(phase, t_end, st.end());
            let mut ev_stage: [Option<[f64; 2]>; 2] = [None; 2];
            for which in 0..2 {
                if e_start[which] > 0.0 || (which == 1 && t == self.last_mode_switch) {
                    continue;
                }
                // damage on/off switches happen where the opening turns (grazing): a
                // small hysteresis keeps round-off from chattering between the modes
                let thr = if which == 1 { EVENT_HYSTERESIS } else { 0.0 };
                let e_end = ev_end[which];
                if e_end > thr {
                    if first.is_none_or(|(_, th, _)| h < th) {
                        first = Some((which, h, st));
                    }
                    continue;
                }
                for j in 0..2 {
                    let tj = t + radau::C[j] * h;
                    let ev = *ev_stage[j]
                        .get_or_insert_with(|| self.ode_events(phase, tj, st.stages[j]));
                    if ev[which] > thr {
                        let hj = radau::C[j] * h;
                        let sj = self.event_step(t, y0, hj)?.0;
                        if self.ode_events(phase, tj, sj.end())[which] > thr
                            && first.is_none_or(|(_, th, _)| hj < th)
                        {
                            first = Some((which, hj, sj));
                        }
                        break;
                    }
                }
            }
            // an event found again at the very time of the previous switch is a grazing
            // touch (both phases agree there): step on without switching
            let mut event = None;
            if let Some((which, hi, s_hi)) = first {
                let fa = e_start[which].min(-f64::MIN_POSITIVE);
                let f_hi = self.ode_events(phase, t + hi, s_hi.end())[which];
                let (tau, past) = exact_loop::locate(
                    |tau| {
                        let (s, _) = self.event_step(t, y0, tau)?;
                        Ok((self.ode_events(phase, t + tau, s.end())[which], s))
                    },
                    hi,
                    fa,
                    f_hi,
                    s_hi,
                )?
                .ok_or_else(|| {
                    Error::numerical(
                        t,
                        "cannot bracket a contact event",
                        format!("gap = {:e} m, beta = {}", y0[0], y0[1]),
                    )
                })?;
                if t + tau <= t
                    && (which == 0 || t != self.last_mode_switch)
                    && !(t == self.last_switch && self.flips_here >= 2)
                {
                    // the new phase leaves at once (grazing touch of the contact-loss
                    // gap, or damage from the first opening when w = 0): switch without
                    // a step
                    if which == 1 {
                        self.last_mode_switch = t;
                    }
                    self.note_switch(t);
                    self.switch(phase, which, t, y);
                    continue;
                }
                if !(t + tau <= t && t == self.last_switch) {
                    event = Some((which, tau, past));
                }
            }
            match event {
                None => {
                    // (no event after all: the step itself where st was the continued one)
                    let st = if whole { st } else { self.step_ode(t, y0, h)? };
                    self.take_ode(acc, t, h, y0, &st, y)?;
                    t = t_end;
                    if let Some(r) = self.ramp {
                        self.ramp = (2.0 * r < self.h).then_some(2.0 * r);
                    }
                }
                Some((which, tau, past)) => {
                    let se = match past {
                        Some(se) => se,
                        None => self.step_ode(t, y0, tau)?,
                    };
                    self.take_ode(acc, t, tau, y0, &se, y)?;
                    t += tau;
                    if which == 1 {
                        self.last_mode_switch = t;
                    }
                    self.note_switch(t);
                    self.switch(phase, which, t, y);
                }
            }
        }
        Ok(())
    }

    /// Record the state at time `t` (s): the series a summary needs, then (unless
    /// `summary_only`) the others.
    #[inline(always)]
    fn record(&self, out: &mut HalfSpaceOutput, acc: &Integrals, t: f64, y: [f64; 2]) {
        out.push_summary(t, self.ode.beta(y), acc.wave.disp_ref);
        if !self.settings.summary_only {
            self.record_full(out, acc, t, y);
        }
    }

    /// The series beyond a summary's ([`GapRun::record`]).
    fn record_full(&self, out: &mut HalfSpaceOutput, acc: &Integrals, t: f64, y: [f64; 2]) {
        let sinc = self.ode.forcing(t);
        let sigma = if self.ode.phase.is_stuck() {
            self.stuck_s(t) - self.ode.p0
        } else {
            self.ode.sigma(y)
        };
        let s = sigma + self.ode.p0;
        out.push_fields(y[0], sigma, sinc, s, [acc.wave.disp_inc, acc.wave.disp_tr]);
    }

    fn at_rest(&self, y: [f64; 2]) -> bool {
        match self.ode.phase {
            Phase::Closed | Phase::Locked => true,
            Phase::Compression => y[0].abs() < 1e-9 * self.scale[0],
            _ => false,
        }
    }

    /// Run over the grid, taking the `paths` allowed.
    fn run(&mut self, paths: Paths, recorder: &mut HalfSpaceOutput) -> Result<()> {
        let grid = Grid::new(
            self.h,
            self.duration,
            self.f0,
            self.settings.tail_periods,
            self.hs.incident.breakpoints(),
        );
        let h = self.h;
        // the recorder's series, emptied (their allocations kept for this run)
        let mut out = std::mem::take(recorder);
        out.reset(h, self.duration);
        let summary_only = self.settings.summary_only;
        // the shortest record, plus the period of rest that ends an automatic tail (an
        // interface at rest by the shortest tail's end: no vector grows in the run)
        let reserve = (grid.n_min + (grid.period / h).ceil() as usize + 2).min(grid.n_max + 1);
        for (v, needed) in [
            (&mut out.t, true),
            (&mut out.beta, true),
            (&mut out.reflected_displacement, true),
            (&mut out.gap, !summary_only),
            (&mut out.contact_stress, !summary_only),
            (&mut out.incident_stress, !summary_only),
            (&mut out.reflected_stress, !summary_only),
            (&mut out.transmitted_stress, !summary_only),
            (&mut out.incident_displacement, !summary_only),
            (&mut out.transmitted_displacement, !summary_only),
        ] {
            if needed {
                v.reserve(reserve);
            }
        }
        let acc = Integrals::default();
        let mut y = [0.0, 1.0];
        self.record(&mut out, &acc, 0.0, y);
        self.paths = paths;
        let mut run = Driven {
            solver: self,
            acc,
            out,
        };
        exact_loop::run(&grid, &mut run, &mut y)?;
        let Driven { acc, mut out, .. } = run;
        let law = &self.hs.law;
        let yend = y;
        out.energy = acc.wave.audit(
            law.stored_energy(yend[0], yend[1]),
            acc.e_damage,
            law.traction.adhesion_energy(1.0) - law.traction.adhesion_energy(yend[1]),
        );
        out.open_time_in_burst = acc.open_in_burst;
        out.max_gap = self.max_gap;
        out.events = self.events;
        *recorder = out;
        Ok(())
    }
}

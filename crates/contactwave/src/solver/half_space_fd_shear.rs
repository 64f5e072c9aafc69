//! The coupled half-space problem (normal and shear waves, model.md sections 9.6 and 13)
//! solved by the bar-stack finite-difference scheme: the FD counterpart of
//! [`super::coupled`], so that the two solvers check each other. It is a configuration of
//! the bar stack's field (`Field::courant_one` in `solver/bar_stack/field.rs`) run by the
//! FD time loop (`solver/stepping.rs`); what is specific here is the interface update and
//! the reading of the waves into interface-time histories and the energy audit.
//!
//! Each wave type is a scalar field on its own bars: the longitudinal displacement with
//! impedance `Z = rho c_L`, the transverse displacement with `Z_T = rho c_T`, both at the
//! common time step `dt` and each at Courant number 1 on its own cells (`dx = c dt` and
//! `dx_T = c_T dt`). At Courant 1 the interior update is `u+ = u_{j+1} + u_{j-1} - u-`
//! whatever the cell size, and the half-mass end node at the interface has compliance
//! `chi = 2 dt / Z`: the cell size drops out and the scheme depends on the impedances
//! only. Medium 1 is 16 cells ending in a transparent boundary that injects the incident
//! wave; medium 2 is 16 cells with a transparent far end (or a rigid wall). The interface
//! is updated each step by [`crate::law::contact::coupled_step`]: the normal law (damage
//! driven by both gaps) and the tangential return mapping (spring, Coulomb slider on the
//! contact pressure of the same step), iterated to a fixed point. Reflected and
//! transmitted displacements are read where the waves leave the bars, 16 steps later.
//!
//! Stresses of compliant branches are those of the new level (the `Average` scheme's
//! trapezoidal rule); a rigid-stick slider's stress is its constraint reaction, the force
//! of the centred scheme at the level where the step starts, and is recorded there (the
//! normal Signorini reaction keeps [`super::half_space_fd::FdSolver`]'s labelling, one
//! level later, so that the normal histories are that solver's).
//!
//! The energy audit is the discrete one: fluxes are `Z sum (Delta u)^2 / dt` of the
//! incident, outgoing and transmitted displacements on the time grid, the damage
//! `sum (dpsi/dbeta) (-Delta beta)` and the friction `sum tau_f Delta s` per step; it
//! closes to the time discretisation error (first order at switches).

use super::bar_stack::{Field, InterfaceScheme, Joint};
use super::coupled::{CoupledHalfSpace, CoupledOutput};
use super::output::HalfSpaceOutput;
use super::stepping::{self, Recorder, Schedule, Scheme};
use super::Solver;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::contact::{coupled_step, CoupledStepInput};
use crate::law::tangential::coulomb::ShearState;
use crate::law::{ContactLaw, TangentialLaw};
use crate::numeric::gauss4;

/// Cells per bar.
const CELLS: usize = 16;

/// The FD scheme as a solver of the coupled half-space problem.
#[derive(Debug, Clone, Copy)]
pub struct FdCoupledSolver {
    /// Time steps per period of the highest input frequency (both waves share `dt`).
    pub samples_per_period: usize,
    /// Time simulated after the burst, periods of f0 (`None`: 100).
    pub tail_periods: Option<f64>,
    /// Interface time discretisation.
    pub interface_scheme: InterfaceScheme,
}

impl Default for FdCoupledSolver {
    fn default() -> Self {
        FdCoupledSolver {
            samples_per_period: 1000,
            tail_periods: None,
            interface_scheme: InterfaceScheme::Average,
        }
    }
}

impl Solver for FdCoupledSolver {
    type Problem = CoupledHalfSpace;
    /// (nothing kept from run to run)
    type Workspace = ();
    type Output = CoupledOutput;
    /// (the run records the interface series of its two fields, which become the output:
    /// the recorder given is replaced)
    fn run_in(
        &self,
        problem: &CoupledHalfSpace,
        _: &mut (),
        out: &mut CoupledOutput,
    ) -> Result<()> {
        *out = solve(problem, self)?;
        Ok(())
    }
}

/// The interface nodes of a field of [`CELLS`]-cell bars: the end of medium 1 and the
/// start of medium 2 (`None`: a rigid wall).
fn interface_nodes(two: bool) -> Joint {
    Joint {
        a: Some(CELLS),
        b: two.then_some(CELLS + 1),
    }
}

/// The fields of one wave type: medium 1 (and medium 2 unless it is a rigid wall) as
/// [`CELLS`]-cell bars at Courant 1 with impedances `z1`, `z2` (Pa s/m), the incident
/// wave entering through the transparent far end of medium 1.
fn field(z1: f64, z2: f64, inc: &dyn Excitation, dt: f64, levels: usize) -> (Field, Joint) {
    let two = z2.is_finite();
    let bars = if two { 2 } else { 1 };
    let (cells, z) = ([CELLS; 2], [z1, z2]);
    (
        Field::courant_one(dt, &cells[..bars], &z[..bars], inc, levels),
        interface_nodes(two),
    )
}

/// Outgoing displacement at the far end of medium 1 and displacement at the far end of
/// medium 2 (0 for a wall), current level, m.
fn ends(field: &Field, joint: Joint) -> (f64, f64) {
    let right = if joint.b.is_some() {
        field.u[field.u.len() - 1]
    } else {
        0.0
    };
    (field.outgoing_first().unwrap_or(f64::NAN), right)
}

/// The coupled problem in the time loop: both fields and the interface state.
struct CoupledFd<'a> {
    law: &'a ContactLaw,
    tl: &'a TangentialLaw,
    scheme: InterfaceScheme,
    dt: f64,
    normal: Field,
    shear: Field,
    /// The interface nodes (the same in both fields).
    joint: Joint,
    /// Adhesion of the current level.
    beta: f64,
    /// Normal gap of the current level, m.
    gap: f64,
    /// Normal dynamic stress of the previous and the current level, Pa.
    s_prev: f64,
    s_cur: f64,
    /// Tangential dynamic stress of the previous and the current level, Pa.
    t_prev: f64,
    t_cur: f64,
    /// Tangential state of the current level.
    sh: ShearState,
    /// Friction limit of the current level, Pa.
    limit: f64,
}

impl Scheme for CoupledFd<'_> {
    fn step(&mut self, t: f64, t1: f64) -> Result<()> {
        let joint = self.joint;
        for f in [&mut self.normal, &mut self.shear] {
            f.bulk();
            f.transparent_first(t, t1);
            if joint.b.is_some() {
                f.transparent_last();
            }
        }
        let chi_n = joint.compliances(&self.normal);
        let chi_t = joint.compliances(&self.shear);
        let input = CoupledStepInput {
            scheme: self.scheme,
            chi_n: chi_n.0 + chi_n.1,
            chi_t: chi_t.0 + chi_t.1,
            beta_old: self.beta,
            s_old: self.s_prev,
            t_old: self.t_prev,
            dt: self.dt,
            t: t1,
        };
        let (gn, gt) = (
            joint.gap(&self.normal.u_next),
            joint.gap(&self.shear.u_next),
        );
        let upd = coupled_step(self.law, self.tl, gn, gt, &self.sh, &input)?;
        joint.apply(&mut self.normal.u_next, chi_n, upd.normal_applied);
        joint.apply(&mut self.shear.u_next, chi_t, upd.shear.applied);
        self.s_prev = self.s_cur;
        self.s_cur = upd.normal.dynamic_stress;
        self.t_prev = self.t_cur;
        self.t_cur = upd.shear.new.dynamic_stress;
        self.beta = upd.normal.adhesion;
        self.gap = upd.normal.gap;
        // the limit this step applied: at the slip path of the level it started from
        let path = self.sh.path;
        self.sh = upd.shear.new;
        let pressure = if self.tl.branch.stick_stiffness().is_infinite() {
            upd.pressure_applied
        } else {
            upd.pressure
        };
        self.limit = self.tl.friction_limit(pressure, path);
        if !(self.gap.is_finite() && self.sh.gap.is_finite()) {
            return Err(Error::numerical(
                t1,
                "coupled FD: non-finite gap",
                format!(
                    "gaps = ({:e}, {:e}) m, beta = {}",
                    self.gap, self.sh.gap, self.beta
                ),
            ));
        }
        Ok(())
    }

    fn check_finite(&self, t1: f64) -> Result<()> {
        if self.normal.finite() && self.shear.finite() {
            return Ok(());
        }
        Err(Error::numerical(
            t1,
            "coupled FD: non-finite displacement",
            format!("gaps = ({:e}, {:e}) m", self.gap, self.sh.gap),
        ))
    }

    fn advance(&mut self) {
        self.normal.rotate();
        self.shear.rotate();
    }
}

/// The interface histories and the displacements where the waves leave the bars, at
/// every level (the recorder of the time loop; [`assemble`] turns them into the output).
#[derive(Default)]
struct Histories {
    t: Vec<f64>,
    /// Normal and tangential gap, m.
    gap: [Vec<f64>; 2],
    /// Normal and tangential dynamic stress, Pa.
    stress: [Vec<f64>; 2],
    beta: Vec<f64>,
    /// Slip, m, and slider stress, Pa.
    slip: Vec<f64>,
    slider: Vec<f64>,
    /// Friction limit, Pa.
    limit: Vec<f64>,
    /// Slider state (0 stick, +-1 slip, NaN free).
    state: Vec<f64>,
    /// Outgoing displacement at the far end of medium 1 (normal, shear), m.
    left: [Vec<f64>; 2],
    /// Displacement at the far end of medium 2 (normal, shear), m.
    right: [Vec<f64>; 2],
}

impl Histories {
    fn with_capacity(n: usize) -> Self {
        let v = || Vec::with_capacity(n);
        Histories {
            t: v(),
            gap: [v(), v()],
            stress: [v(), v()],
            beta: v(),
            slip: v(),
            slider: v(),
            limit: v(),
            state: v(),
            left: [v(), v()],
            right: [v(), v()],
        }
    }
}

impl Recorder<CoupledFd<'_>> for Histories {
    fn record(&mut self, t: f64, s: &CoupledFd<'_>) {
        let sh = &s.sh;
        let normal_ends = ends(&s.normal, s.joint);
        let shear_ends = ends(&s.shear, s.joint);
        self.t.push(t);
        self.gap[0].push(s.gap);
        self.gap[1].push(sh.gap);
        self.stress[0].push(s.s_cur);
        self.stress[1].push(sh.dynamic_stress);
        self.beta.push(s.beta);
        self.slip.push(sh.slip);
        self.slider.push(sh.slider);
        self.limit.push(s.limit);
        self.state.push(sh.state);
        self.left[0].push(normal_ends.0);
        self.left[1].push(shear_ends.0);
        self.right[0].push(normal_ends.1);
        self.right[1].push(shear_ends.1);
    }
}

fn solve(p: &CoupledHalfSpace, settings: &FdCoupledSolver) -> Result<CoupledOutput> {
    let hs = &p.normal;
    let law = &*hs.law;
    let tl = &*p.tangential;
    if p.oblique.is_some() {
        return Err(Error::invalid(
            "<problem>",
            "solver.method",
            "fd",
            "oblique incidence runs on the exact solver only (`solver.method = \"exact\"`)",
        ));
    }
    if !(p.z1t.is_finite() && p.z1t > 0.0 && p.z2t > 0.0) {
        return Err(Error::invalid(
            "<problem>",
            "shear impedance",
            format!("({}, {})", p.z1t, p.z2t),
            "Z1T must be finite and > 0, Z2T > 0 (inf: rigid wall)",
        ));
    }
    let f0 = p.fundamental();
    let dt = 1.0 / (settings.samples_per_period.max(1) as f64 * p.highest_frequency());
    let duration = p.duration();
    let tail = settings.tail_periods.unwrap_or(100.0) / f0;
    // interface levels k = 0..=n_out (t = k dt), plus CELLS steps to reach the interface
    // and CELLS for the outgoing waves to leave the bars
    let n_out = ((duration + tail) / dt).ceil() as usize;
    let steps = n_out + 2 * CELLS;
    let t0 = -(CELLS as f64) * dt;
    let (normal, joint) = field(hs.z1, hs.z2, &*hs.incident, dt, steps + 1);
    let (shear, _) = field(p.z1t, p.z2t, &*p.shear_incident, dt, steps + 1);
    let p0 = law.static_pressure;
    let mut scheme = CoupledFd {
        law,
        tl,
        scheme: settings.interface_scheme,
        dt,
        normal,
        shear,
        joint,
        beta: 1.0,
        gap: 0.0,
        s_prev: 0.0,
        s_cur: 0.0,
        t_prev: 0.0,
        t_cur: 0.0,
        sh: ShearState::at_rest(tl, p0),
        limit: tl.friction_limit(p0, 0.0),
    };
    let mut rec = Histories::with_capacity(steps + 1);
    let schedule = Schedule {
        t0,
        dt,
        steps,
        record_every: 1,
        check_every: 0,
        progress: None,
    };
    stepping::run(&schedule, &mut scheme, &mut rec)?;
    Ok(assemble(p, &rec, dt, duration, n_out))
}

/// Interface-time histories and the energy audit from the recorded levels.
fn assemble(
    p: &CoupledHalfSpace,
    rec: &Histories,
    dt: f64,
    duration: f64,
    n_out: usize,
) -> CoupledOutput {
    let hs = &p.normal;
    let law = &*hs.law;
    let tl = &*p.tangential;
    let br = &*tl.branch;
    let (p0, q0) = (law.static_pressure, tl.static_shear);
    let uc = law.critical_gap();
    let k0 = CELLS; // level of t = 0
                    // a rigid-stick slider's stress is the constraint reaction acting over the step that
                    // starts at the level (the centred scheme's force of that level): record it there
    let lag = usize::from(br.stick_stiffness().is_infinite());
    let lags = [0, lag];
    let n = n_out + 1;
    let mut out = CoupledOutput::default();
    let incs: [&dyn Excitation; 2] = [&*hs.incident, &*p.shear_incident];
    let zs = [[hs.z1, hs.z2], [p.z1t, p.z2t]];
    // contact stress = dynamic stress + this: sigma = S - p0, tau = T + q0
    let statics = [-p0, q0];
    for c in 0..2 {
        let o: &mut HalfSpaceOutput = if c == 0 {
            &mut out.normal
        } else {
            &mut out.shear
        };
        o.dt = dt;
        o.burst_duration = duration;
        let (z1, z2) = (zs[c][0], zs[c][1]);
        let mut inc_disp = 0.0;
        let (mut e_inc, mut e_ref, mut e_tr) = (0.0, 0.0, 0.0);
        for k in 0..n {
            let i = k0 + k;
            let j = i + CELLS;
            let t = k as f64 * dt;
            let s_inc = incs[c].stress(t);
            let s = rec.stress[c][i + lags[c]];
            if k > 0 {
                let d_inc = -gauss4(t - dt, t, |x| incs[c].stress(x)) / z1;
                inc_disp += d_inc;
                e_inc += z1 * d_inc * d_inc / dt;
                let d_ref = rec.left[c][j] - rec.left[c][j - 1];
                e_ref += z1 * d_ref * d_ref / dt;
                if z2.is_finite() {
                    let d_tr = rec.right[c][j] - rec.right[c][j - 1];
                    e_tr += z2 * d_tr * d_tr / dt;
                }
            }
            o.push_summary(t, rec.beta[i], rec.left[c][j]);
            o.push_fields(
                rec.gap[c][i],
                s + statics[c],
                s_inc,
                s,
                [inc_disp, rec.right[c][j]],
            );
        }
        o.energy.incident = e_inc;
        o.energy.reflected = e_ref;
        o.energy.transmitted = e_tr;
    }
    let (mut damage, mut friction) = (0.0, 0.0);
    let (mut open_time, mut max_gap, mut events) = (0.0, 0.0f64, 0usize);
    let (mut slip_time, mut slip_events) = (0.0, 0usize);
    for k in 0..n {
        let i = k0 + k;
        let t = k as f64 * dt;
        let (g, ut, b) = (rec.gap[0][i], rec.gap[1][i], rec.beta[i]);
        out.slip.push(rec.slip[i]);
        out.friction_limit.push(rec.limit[i + lag]);
        out.slip_state.push(rec.state[i + lag]);
        if k > 0 {
            let d = (g - uc).max(0.0);
            let psi_beta =
                law.traction.energy_d_adhesion(d, b) + br.spring_energy_d_adhesion(b, ut);
            damage += psi_beta * (rec.beta[i - 1] - b);
            friction += rec.slider[i] * (rec.slip[i] - rec.slip[i - 1]);
            let (was, is) = (rec.gap[0][i - 1] > uc, g > uc);
            events += usize::from(was != is);
            let (s0, s1) = (rec.state[i + lag - 1], rec.state[i + lag]);
            // stick/slip switches while loaded (as the exact solver counts them)
            if !s0.is_nan() && !s1.is_nan() && s0 != s1 {
                slip_events += 1;
            }
        }
        if t < duration {
            if g > uc {
                open_time += dt;
            }
            if rec.state[i + lag].abs() == 1.0 {
                slip_time += dt;
            }
        }
        max_gap = max_gap.max(g);
    }
    let last = k0 + n - 1;
    let (g, ut, b) = (rec.gap[0][last], rec.gap[1][last], rec.beta[last]);
    let kt = br.stick_stiffness();
    let series = if kt.is_finite() {
        let f = rec.slider[last] - q0;
        0.5 * f * f / kt
    } else {
        0.0
    };
    out.normal.energy.stored = law.stored_energy(g, b);
    out.normal.energy.damage = damage;
    out.normal.energy.adhesion_decrease =
        law.traction.adhesion_energy(1.0) - law.traction.adhesion_energy(b);
    out.shear.energy.stored = br.spring_energy(b, ut) + series;
    out.friction_dissipation = friction;
    out.static_shear_work = q0 * rec.slip[last];
    out.normal.open_time_in_burst = open_time;
    out.normal.max_gap = max_gap;
    out.normal.events = events;
    out.shear.events = slip_events;
    out.slip_events = slip_events;
    out.slip_time_in_burst = slip_time;
    out.shear.max_gap = out.shear.gap.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    out
}

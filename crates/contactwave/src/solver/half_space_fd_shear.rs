//! The coupled half-space problem (normal and shear waves, model.md section 13) solved by
//! the bar-stack finite-difference scheme: the FD counterpart of [`super::coupled`], so
//! that the two solvers check each other.
//!
//! Each wave type is a scalar field on its own bars: the longitudinal displacement with
//! impedance `Z = rho c_L`, the transverse displacement with `Z_T = rho c_T`, both at the
//! common time step `dt` and each at Courant number 1 on its own cells (`dx = c dt` and
//! `dx_T = c_T dt`). At Courant 1 the interior update is `u+ = u_{j+1} + u_{j-1} - u-`
//! whatever the cell size, and the half-mass end node at the interface has compliance
//! `chi = 2 dt / Z`: the cell size drops out and the scheme depends on the impedances
//! only. Medium 1 is 16 cells ending in a transparent boundary that injects the incident
//! wave; medium 2 is 16 cells with a transparent far end (or a rigid wall). The interface
//! is updated each step by [`super::interface_shear::coupled_step`]: the normal law (damage
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

use super::bar_stack::InterfaceScheme;
use super::coupled::{CoupledHalfSpace, CoupledOutput};
use super::interface_shear::{coupled_step, CoupledStepInput, ShearState};
use super::output::HalfSpaceOutput;
use super::Solver;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
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
    type Output = CoupledOutput;
    fn solve(&self, problem: &CoupledHalfSpace) -> Result<CoupledOutput> {
        solve(problem, self)
    }
}

/// One scalar wave field on medium 1 (and medium 2 unless it is a rigid wall), at
/// Courant 1.
struct Line<'a> {
    u_prev: Vec<f64>,
    u: Vec<f64>,
    u_next: Vec<f64>,
    /// Interface node of medium 1.
    a: usize,
    /// Whether medium 2 is a bar (else a rigid wall).
    two: bool,
    chi_a: f64,
    chi_b: f64,
    z1: f64,
    inc: &'a dyn Excitation,
    /// Incident displacement at the left end, `F(tau) = -(1/Z1) int_0^tau s_inc`, at
    /// `tau = (m - 1, m, m + 1) dt`.
    f: [f64; 3],
    m: usize,
    dt: f64,
}

impl<'a> Line<'a> {
    fn new(z1: f64, z2: f64, inc: &'a dyn Excitation, dt: f64) -> Self {
        let two = z2.is_finite();
        let n = if two { 2 * (CELLS + 1) } else { CELLS + 1 };
        let mut line = Line {
            u_prev: vec![0.0; n],
            u: vec![0.0; n],
            u_next: vec![0.0; n],
            a: CELLS,
            two,
            chi_a: 2.0 * dt / z1,
            chi_b: if two { 2.0 * dt / z2 } else { 0.0 },
            z1,
            inc,
            f: [0.0; 3],
            m: 0,
            dt,
        };
        line.f[2] = line.f_step(0);
        line
    }

    /// `F((m + 1) dt) - F(m dt)` (4 Gauss-Legendre panels per step).
    fn f_step(&self, m: usize) -> f64 {
        let h = 0.25 * self.dt;
        let t0 = m as f64 * self.dt;
        let mut s = 0.0;
        for i in 0..4 {
            let a = t0 + i as f64 * h;
            s += gauss4(a, a + h, |x| self.inc.stress(x));
        }
        -s / self.z1
    }

    /// Bulk step and boundary nodes with no interface force; returns the predicted gap.
    fn predict(&mut self) -> f64 {
        let n = self.u.len();
        let (up, u, un) = (&self.u_prev, &self.u, &mut self.u_next);
        for j in 1..n - 1 {
            un[j] = u[j + 1] + u[j - 1] - up[j];
        }
        // left end: transparent, injecting the incident wave; w = u - u_inc outgoing
        un[0] = self.f[2] + u[1] - self.f[0];
        let a = self.a;
        un[a] = 2.0 * u[a - 1] - up[a];
        if self.two {
            let b = a + 1;
            un[b] = 2.0 * u[b + 1] - up[b];
            // right end: transparent
            un[n - 1] = u[n - 2];
            un[b] - un[a]
        } else {
            -un[a]
        }
    }

    /// Compliance of the gap, m/Pa.
    fn chi(&self) -> f64 {
        self.chi_a + self.chi_b
    }

    /// Apply the dynamic interface stress `s` (Pa) over the step.
    fn apply(&mut self, s: f64) {
        let a = self.a;
        self.u_next[a] += self.chi_a * s;
        if self.two {
            self.u_next[a + 1] -= self.chi_b * s;
        }
    }

    /// Outgoing displacement at the left end and displacement at the right end, new level.
    fn ends(&self) -> (f64, f64) {
        let right = if self.two {
            self.u_next[self.u_next.len() - 1]
        } else {
            0.0
        };
        (self.u_next[0] - self.f[2], right)
    }

    fn rotate(&mut self) {
        std::mem::swap(&mut self.u_prev, &mut self.u);
        std::mem::swap(&mut self.u, &mut self.u_next);
        self.m += 1;
        let next = self.f[2] + self.f_step(self.m);
        self.f = [self.f[1], self.f[2], next];
    }
}

/// Recorded histories at every level.
#[derive(Default)]
struct Rec {
    t: Vec<f64>,
    gap: [Vec<f64>; 2],
    stress: [Vec<f64>; 2],
    beta: Vec<f64>,
    slip: Vec<f64>,
    slider: Vec<f64>,
    limit: Vec<f64>,
    state: Vec<f64>,
    left: [Vec<f64>; 2],
    right: [Vec<f64>; 2],
}

impl Rec {
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        t: f64,
        gap: f64,
        stress: f64,
        beta: f64,
        sh: &ShearState,
        limit: f64,
        normal_ends: (f64, f64),
        shear_ends: (f64, f64),
    ) {
        self.t.push(t);
        self.gap[0].push(gap);
        self.gap[1].push(sh.gap);
        self.stress[0].push(stress);
        self.stress[1].push(sh.dynamic_stress);
        self.beta.push(beta);
        self.slip.push(sh.slip);
        self.slider.push(sh.slider);
        self.limit.push(limit);
        self.state.push(sh.state);
        self.left[0].push(normal_ends.0);
        self.left[1].push(shear_ends.0);
        self.right[0].push(normal_ends.1);
        self.right[1].push(shear_ends.1);
    }

    fn with_capacity(n: usize) -> Self {
        let v = || Vec::with_capacity(n);
        Rec {
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
    let mut normal = Line::new(hs.z1, hs.z2, &*hs.incident, dt);
    let mut shear = Line::new(p.z1t, p.z2t, &*p.shear_incident, dt);
    let p0 = law.static_pressure;
    let mut rec = Rec::with_capacity(steps + 1);
    let mut beta = 1.0;
    let kt = tl.branch.stick_stiffness();
    let mut sh = ShearState::at_rest(tl, p0);
    let (mut s_prev, mut s_cur) = (0.0, 0.0);
    let (mut t_prev, mut t_cur) = (0.0, 0.0);
    rec.push(
        t0,
        0.0,
        0.0,
        beta,
        &sh,
        tl.friction_limit(p0),
        (0.0, 0.0),
        (0.0, 0.0),
    );
    for step in 0..steps {
        if step % 4096 == 4095 {
            crate::interrupt::check()?;
        }
        let t1 = t0 + (step + 1) as f64 * dt;
        let gn = normal.predict();
        let gt = shear.predict();
        let input = CoupledStepInput {
            scheme: settings.interface_scheme,
            chi_n: normal.chi(),
            chi_t: shear.chi(),
            beta_old: beta,
            s_old: s_prev,
            t_old: t_prev,
            dt,
            t: t1,
        };
        let upd = coupled_step(law, tl, gn, gt, &sh, &input)?;
        normal.apply(upd.normal_applied);
        shear.apply(upd.shear.applied);
        s_prev = s_cur;
        s_cur = upd.normal.dynamic_stress;
        t_prev = t_cur;
        t_cur = upd.shear.new.dynamic_stress;
        beta = upd.normal.adhesion;
        let gap_n = upd.normal.gap;
        sh = upd.shear.new;
        rec.push(
            t1,
            gap_n,
            s_cur,
            beta,
            &sh,
            tl.friction_limit(if kt.is_infinite() {
                upd.pressure_applied
            } else {
                upd.pressure
            }),
            normal.ends(),
            shear.ends(),
        );
        if !(gap_n.is_finite() && sh.gap.is_finite()) {
            return Err(Error::numerical(
                t1,
                "coupled FD: non-finite gap",
                format!("gaps = ({gap_n:e}, {:e}) m, beta = {beta}", sh.gap),
            ));
        }
        normal.rotate();
        shear.rotate();
    }
    Ok(assemble(p, &rec, dt, duration, n_out))
}

/// Interface-time histories and the energy audit from the recorded levels.
fn assemble(
    p: &CoupledHalfSpace,
    rec: &Rec,
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
            o.t.push(t);
            o.gap.push(rec.gap[c][i]);
            o.contact_stress.push(s + statics[c]);
            o.beta.push(rec.beta[i]);
            o.incident_stress.push(s_inc);
            o.reflected_stress.push(s - s_inc);
            o.transmitted_stress.push(s);
            o.reflected_displacement.push(rec.left[c][j]);
            o.incident_displacement.push(inc_disp);
            o.transmitted_displacement.push(rec.right[c][j]);
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

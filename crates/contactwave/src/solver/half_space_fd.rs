//! The half-space problem solved by the bar-stack finite-difference scheme (the thesis'
//! method, section 2.4): medium 1 is a bar ending in a transparent boundary that injects
//! the incident wave, the interface is an obstacle (rigid wall) or an interface to a
//! second bar with a transparent far end. Every segment runs at Courant number 1, so the
//! only discretisation error is in time at the interface (first order where the contact
//! opens and closes within a step). The reflected wave is read where it leaves the bar
//! (the outgoing part of the displacement at the transparent end): at Courant 1 a wave
//! crosses the bar unchanged, so this equals the reflection at any probe, delayed. Results
//! come back in the same form as the exact solver's, so the two solvers check each other.

use super::bar_stack::{BarStack, End, FdRun, InterfaceScheme, Segment};
use super::half_space::{HalfSpace, HalfSpaceOutput};
use super::Solver;
use crate::error::Result;
use crate::numeric::gauss4;

/// The FD scheme as a solver of the half-space problem.
#[derive(Debug, Clone, Copy)]
pub struct FdSolver {
    /// Time steps per period of the highest input frequency; cell sizes follow
    /// (`dx = c dt`).
    pub samples_per_period: usize,
    /// Time simulated after the burst, periods of f0 (`None`: 100).
    pub tail_periods: Option<f64>,
    /// Interface time discretisation.
    pub interface_scheme: InterfaceScheme,
}

impl Solver for FdSolver {
    type Problem = HalfSpace;
    /// (nothing kept from run to run)
    type Workspace = ();
    type Output = HalfSpaceOutput;
    /// (the run records into the bar stack's recorder, whose interface series become the
    /// output: the recorder given is replaced)
    fn run_in(&self, problem: &HalfSpace, _: &mut (), out: &mut HalfSpaceOutput) -> Result<()> {
        *out = solve(problem, self)?;
        Ok(())
    }
}

/// Solve the half-space problem with the FD scheme. Output times are interface times
/// (t = 0 when the incident front reaches the interface), as for the exact solver.
fn solve(problem: &HalfSpace, settings: &FdSolver) -> Result<HalfSpaceOutput> {
    let inc = problem.incident.clone();
    let spp = settings.samples_per_period as f64;
    let dt = 1.0 / (inc.highest_frequency() * spp);
    let m1 = problem.medium;
    let c1 = m1.wave_speed();
    let z1 = m1.impedance();
    let dx1 = c1 * dt;
    let cells = 16usize;
    let len1 = cells as f64 * dx1;
    let law = problem.law.clone();
    let mut segments = vec![Segment {
        name: "medium 1".into(),
        length: len1,
        material: m1,
        damping: 0.0,
    }];
    let (interfaces, right) = match problem.counterpart {
        None => (vec![], End::Obstacle(law)),
        Some(m2) => {
            segments.push(Segment {
                name: "medium 2".into(),
                length: 16.0 * m2.wave_speed() * dt,
                material: m2,
                damping: 0.0,
            });
            (vec![law], End::Transparent)
        }
    };
    let stack = BarStack {
        area: 1.0,
        segments,
        interfaces,
        left: End::Transparent,
        right,
        incident: Some(inc.clone()),
        shear: None,
    };
    let period = 1.0 / inc.fundamental();
    let tail = settings.tail_periods.unwrap_or(100.0) * period;
    let t_end = inc.duration() + tail + len1 / c1;
    let t0 = -len1 / c1;
    let steps = ((t_end - t0) / dt).ceil() as usize;
    let mesh = stack.mesh(dt);
    let probe = mesh.offset[0];
    let run = FdRun {
        dt,
        t0,
        steps,
        record_every: 1,
        probes: vec![probe],
        forces: vec![],
        imposed: None,
        progress: None,
        interface_scheme: settings.interface_scheme,
        shear_probes: vec![],
    };
    let fd = stack.run(&run)?;
    // back to interface time: the left end sees the reflection len1/c1 later
    let delay = len1 / c1;
    let k0 = fd.t.iter().position(|&t| t >= -1e-12 * dt).unwrap_or(0);
    let kd = (delay / dt).round() as usize;
    let n = fd.t.len().saturating_sub(k0 + kd);
    let mut out = HalfSpaceOutput {
        dt,
        burst_duration: inc.duration(),
        ..Default::default()
    };
    // incident displacement at the probe: F(t + xp/c1), F(tau) = -(1/Z) int_0^tau s_inc
    let mut f_acc = 0.0;
    let mut prev = 0.0f64;
    let f_at = |tau: f64, acc: &mut f64, prev: &mut f64| {
        if tau > *prev {
            *acc += gauss4(*prev, tau, |s| inc.stress(s));
            *prev = tau;
        }
        -*acc / z1
    };
    let mut open_time = 0.0;
    let mut max_gap = 0.0f64;
    let mut inc_disp = 0.0;
    for k in 0..n {
        let t = fd.t[k0 + k];
        let gap = fd.gap[0][k0 + k];
        let sigma = fd.stress[0][k0 + k];
        let beta = fd.beta[0][k0 + k];
        let s_inc = inc.stress(t);
        let s = sigma + problem.law.static_pressure;
        // reflected (outgoing) displacement at the left end at time t + delay
        let tp = fd.t[k0 + kd + k];
        let u_inc = f_at(tp + delay, &mut f_acc, &mut prev);
        let u_ref = fd.displacement[0][k0 + kd + k] - u_inc;
        if k > 0 {
            inc_disp -= gauss4(t - dt, t, |x| inc.stress(x)) / z1;
        }
        out.push_summary(t, beta, u_ref);
        out.push_fields(gap, sigma, s_inc, s, [inc_disp, 0.0]);
        if gap > problem.law.critical_gap() && t <= inc.duration() {
            open_time += dt;
        }
        max_gap = max_gap.max(gap);
    }
    out.open_time_in_burst = open_time;
    out.max_gap = max_gap;
    out.energy.incident = f64::NAN;
    out.energy.reflected = f64::NAN;
    out.energy.transmitted = f64::NAN;
    out.energy.stored = f64::NAN;
    out.energy.damage = f64::NAN;
    out.energy.adhesion_decrease = f64::NAN;
    Ok(out)
}

//! Explicit finite-difference solver of a stack of elastic bars separated by contact
//! interfaces (model.md section 5; thesis sections 2.3.1-2.3.5, eqs. 2.2, 2.18-2.37).
//!
//! Each segment is meshed with `n_i = floor(L_i / (c_i dt))` cells, so its Courant number
//! `r_i = c_i dt / dx_i <= 1` and equals 1 (dispersion-free in 1D) when the length is a
//! multiple of `c_i dt`. The scheme is the lumped-mass form of the thesis' centred scheme:
//! interior nodes `u+ = 2u - u- + r^2 (u_{j+1} - 2u_j + u_{j-1})` (eq. 2.18 at the
//! Courant number r), end nodes with half mass, viscous damping `h` (eq. 2.2) centred in
//! time. Displacements are relative to the pre-loaded static equilibrium (gravity and
//! static forces are balanced by the static stress field, reported by the static step),
//! so an interface transmits the dynamic stress `S = sigma(gap) + p0`. Interfaces are
//! updated implicitly each step ([`super::interface::update`]): the law holds exactly.
//! Ends: free, fixed, transparent (first-order absorbing, exact at Courant 1) with an
//! optional injected incident wave, or a rigid obstacle through an interface.
//! The time loop allocates nothing; state lives in flat `Vec<f64>`s.

use super::interface;
pub use super::output::FdOutput;
use super::Solver;
use crate::error::{Error, Result};
use crate::law::ContactLaw;
use crate::material::Material;
use crate::numeric::gauss4;
use std::sync::Arc;

/// An elastic bar segment.
#[derive(Debug, Clone)]
pub struct Segment {
    /// Name (for reports).
    pub name: String,
    /// Length, m.
    pub length: f64,
    /// Material (E, rho) at the common cross-section.
    pub material: Material,
    /// Viscous damping h of eq. 2.2, 1/s.
    pub damping: f64,
}

/// Condition at an end of the stack.
#[derive(Debug, Clone)]
pub enum End {
    /// Traction-free end.
    Free,
    /// Fixed end (u = 0).
    Fixed,
    /// Transparent (absorbing) end; at the left end an incident wave may be injected.
    Transparent,
    /// Rigid obstacle in contact through an interface law.
    Obstacle(Arc<ContactLaw>),
}

/// A time signal (force, N, or incident stress, Pa).
pub trait Signal: Send + Sync + std::fmt::Debug {
    /// Value at time t.
    fn value(&self, t: f64) -> f64;
}

impl<T: crate::excitation::Excitation + ?Sized> Signal for T {
    fn value(&self, t: f64) -> f64 {
        self.stress(t)
    }
}

/// A force applied at a node, N (positive along +x).
#[derive(Debug, Clone)]
pub struct ForceSource {
    /// Global node index.
    pub node: usize,
    /// Force signal, N.
    pub signal: Arc<dyn Signal>,
}

/// The bar stack.
#[derive(Debug, Clone)]
pub struct BarStack {
    /// Common cross-section, m^2.
    pub area: f64,
    /// Segments from left (x = 0) to right.
    pub segments: Vec<Segment>,
    /// Interfaces between consecutive segments (`segments.len() - 1` of them).
    pub interfaces: Vec<Arc<ContactLaw>>,
    /// Left end.
    pub left: End,
    /// Right end.
    pub right: End,
    /// Incident stress wave injected at a transparent left end: `s_inc(t)` is its stress
    /// at the right end of the first segment (the wave front arrives there at t = 0).
    pub incident: Option<Arc<dyn crate::excitation::Excitation>>,
}

/// The mesh of a stack for a time step.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Time step, s.
    pub dt: f64,
    /// First global node of each segment.
    pub offset: Vec<usize>,
    /// Cells per segment.
    pub cells: Vec<usize>,
    /// Cell size per segment, m.
    pub dx: Vec<f64>,
    /// Courant number per segment.
    pub courant: Vec<f64>,
    /// Total number of nodes.
    pub nodes: usize,
}

impl BarStack {
    /// Mesh every segment at Courant number <= 1 for time step `dt` (s).
    pub fn mesh(&self, dt: f64) -> Mesh {
        let mut offset = Vec::new();
        let mut cells = Vec::new();
        let mut dx = Vec::new();
        let mut courant = Vec::new();
        let mut n = 0;
        for s in &self.segments {
            let c = s.material.wave_speed();
            let k = ((s.length / (c * dt)) * (1.0 + 1e-12)).floor().max(1.0) as usize;
            offset.push(n);
            cells.push(k);
            dx.push(s.length / k as f64);
            courant.push(c * dt / (s.length / k as f64));
            n += k + 1;
        }
        Mesh {
            dt,
            offset,
            cells,
            dx,
            courant,
            nodes: n,
        }
    }

    /// Global node index at position `x` (m, from the left end of `segment`).
    pub fn node_at(&self, mesh: &Mesh, segment: usize, x: f64) -> usize {
        let k = (x / mesh.dx[segment])
            .round()
            .clamp(0.0, mesh.cells[segment] as f64) as usize;
        mesh.offset[segment] + k
    }
}

/// How the interface force enters the step (the law itself holds exactly at the new time
/// level in both).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum InterfaceScheme {
    /// The interface stress of the new time level acts over the whole step (backward,
    /// as thesis eqs. 2.27-2.31): first order, and it dissipates energy (a linear spring
    /// interface loses a fraction of order `K chi` of its vibration energy per step).
    Backward,
    /// The mean of the interface stresses at the new and the previous-but-one level
    /// replaces the stress at the current level in the centred scheme (trapezoidal /
    /// average acceleration): second order, no numerical dissipation for a linear spring,
    /// unconditionally stable. Rigid (Signorini, bonded) branches keep the backward
    /// projection, which enforces the constraint at the new level.
    #[default]
    Average,
}

/// Settings of a run.
#[derive(Debug, Clone, Default)]
pub struct FdRun {
    /// Time step, s.
    pub dt: f64,
    /// Start time, s.
    pub t0: f64,
    /// Number of steps.
    pub steps: usize,
    /// Record every n-th step.
    pub record_every: usize,
    /// Probe nodes (global indices).
    pub probes: Vec<usize>,
    /// Force sources.
    pub forces: Vec<ForceSource>,
    /// Imposed displacement of node 0 (from the static equilibrium), m: thesis eq. 2.39,
    /// `u_1^{m+1} = f((m + 1) dt)`; the left end must then be `Free`.
    pub imposed: Option<Arc<dyn Signal>>,
    /// Called with (steps done, steps) every 4096 steps (long runs report progress).
    pub progress: Option<StepProgress>,
    /// Interface time discretisation.
    pub interface_scheme: InterfaceScheme,
}

/// What every interface update of one time step shares.
#[derive(Debug, Clone, Copy)]
struct StepContext {
    scheme: InterfaceScheme,
    /// Time step, s.
    dt: f64,
    /// The new time level, s (for error messages).
    t: f64,
}

/// One interface update: `s_old` is the dynamic stress two levels back (Pa); returns the
/// update (its `dynamic_stress` the stress of the new level) and the stress to apply over
/// the step.
#[inline]
fn interface_step(
    ctx: StepContext,
    law: &ContactLaw,
    gt: f64,
    chi: f64,
    beta_old: f64,
    s_old: f64,
) -> Result<(interface::InterfaceUpdate, f64)> {
    let StepContext { scheme, dt, t } = ctx;
    if scheme == InterfaceScheme::Average {
        // g = g~ - chi (S_new + S_old) / 2: the update with compliance chi/2 from the
        // shifted prediction g~ - chi S_old / 2
        let upd = interface::update(law, gt - 0.5 * chi * s_old, 0.5 * chi, beta_old, dt, t)?;
        let uc = law.critical_gap();
        let on_constraint = (upd.gap <= uc && law.compression.is_rigid())
            || (upd.gap >= uc && law.traction.is_rigid());
        if !on_constraint {
            return Ok((upd, 0.5 * (upd.dynamic_stress + s_old)));
        }
    }
    let upd = interface::update(law, gt, chi, beta_old, dt, t)?;
    Ok((upd, upd.dynamic_stress))
}

/// A progress callback of a run: `(steps done, total steps)`.
#[derive(Clone)]
pub struct StepProgress(pub Arc<dyn Fn(usize, usize) + Send + Sync>);

impl std::fmt::Debug for StepProgress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("StepProgress")
    }
}

/// Largest time step that keeps every interface update well-conditioned and every segment
/// at Courant <= 1 is not a constraint of this implicit interface update; the bulk
/// stability limit is Courant <= 1, which the mesh guarantees by construction.
pub fn check_stability(mesh: &Mesh) -> Result<()> {
    for (i, r) in mesh.courant.iter().enumerate() {
        if !(*r <= 1.0 + 1e-9) {
            return Err(Error::invalid(
                "<mesh>",
                format!("segment[{i}]"),
                r,
                "Courant number c dt / dx must be <= 1",
            ));
        }
    }
    Ok(())
}

impl BarStack {
    /// Run the explicit scheme.
    pub fn run(&self, run: &FdRun) -> Result<FdOutput> {
        let mesh = self.mesh(run.dt);
        check_stability(&mesh)?;
        let dt = run.dt;
        let n = mesh.nodes;
        let nseg = self.segments.len();
        if self.interfaces.len() + 1 != nseg {
            return Err(Error::invalid(
                "<model>",
                "interfaces",
                self.interfaces.len(),
                format!(
                    "a stack of {nseg} segments needs {} interfaces",
                    nseg.saturating_sub(1)
                ),
            ));
        }
        // per-node coefficients (flat arrays)
        let mut damp_p = vec![1.0; n]; // 1 + h dt / 2
        let mut inv_mass = vec![0.0; n]; // dt^2 / (rho dx A) (interior), doubled at ends
        for (s, seg) in self.segments.iter().enumerate() {
            let o = mesh.offset[s];
            let k = mesh.cells[s];
            let rho = seg.material.density;
            for j in 0..=k {
                damp_p[o + j] = 1.0 + 0.5 * seg.damping * dt;
                let m = rho * mesh.dx[s] * self.area * if j == 0 || j == k { 0.5 } else { 1.0 };
                inv_mass[o + j] = dt * dt / m;
            }
        }
        let mut u_prev = vec![0.0; n];
        let mut u = vec![0.0; n];
        let mut u_next = vec![0.0; n];
        let mut force = vec![0.0; run.forces.len()];
        let forced: Vec<usize> = run.forces.iter().map(|f| f.node.min(n - 1)).collect();
        // per-segment stencil coefficients: u+ = a u + b (u_l + u_r) - c u- (interior),
        // end nodes with half mass: u+ = a_end u + b_end u_neighbour - c u-
        let coef: Vec<Coef> = (0..nseg)
            .map(|s| {
                let r2 = mesh.courant[s] * mesh.courant[s];
                let h = self.segments[s].damping * dt;
                let dp = 1.0 + 0.5 * h;
                let dm = 1.0 - 0.5 * h;
                Coef {
                    a: 2.0 * (1.0 - r2) / dp,
                    b: r2 / dp,
                    c: dm / dp,
                    a_end: 2.0 * (1.0 - r2) / dp,
                    b_end: 2.0 * r2 / dp,
                    exact: r2 == 1.0 && h == 0.0,
                }
            })
            .collect();
        let n_if = self.interfaces.len()
            + usize::from(matches!(self.left, End::Obstacle(_)))
            + usize::from(matches!(self.right, End::Obstacle(_)));
        let mut beta = vec![1.0; n_if];
        let n_rec = run.steps / run.record_every.max(1) + 1;
        let mut out = FdOutput {
            t: Vec::with_capacity(n_rec),
            displacement: vec![Vec::with_capacity(n_rec); run.probes.len()],
            gap: vec![Vec::with_capacity(n_rec); n_if],
            stress: vec![Vec::with_capacity(n_rec); n_if],
            beta: vec![Vec::with_capacity(n_rec); n_if],
            node_updates: 0,
        };
        let mut gaps = vec![0.0; n_if];
        // dynamic interface stress at the previous two levels (0 at the static equilibrium)
        let mut s_prev = vec![0.0; n_if];
        let mut s_cur = vec![0.0; n_if];
        let scheme = run.interface_scheme;
        let mut stresses: Vec<f64> = self.interfaces.iter().map(|l| -l.static_pressure).collect();
        if let End::Obstacle(l) = &self.right {
            stresses.push(-l.static_pressure);
        }
        if let End::Obstacle(l) = &self.left {
            stresses.push(-l.static_pressure);
        }
        // incident displacement table F(k dt) = -(1/Z) int_0^{k dt} s_inc, for a transparent
        // left end; the wave front reaches the right end of segment 0 at t = 0.
        let inc_table = self.incident_table(&mesh, run)?;
        let c0 = self.segments[0].material.wave_speed();
        let len0 = self.segments[0].length;
        let record = |out: &mut FdOutput,
                      t: f64,
                      u: &[f64],
                      gaps: &[f64],
                      stresses: &[f64],
                      beta: &[f64]| {
            out.t.push(t);
            for (p, &node) in run.probes.iter().enumerate() {
                out.displacement[p].push(u[node]);
            }
            for i in 0..gaps.len() {
                out.gap[i].push(gaps[i]);
                out.stress[i].push(stresses[i]);
                out.beta[i].push(beta[i]);
            }
        };
        record(&mut out, run.t0, &u, &gaps, &stresses, &beta);
        for step in 0..run.steps {
            if step % 4096 == 0 {
                crate::interrupt::check()?;
                if let Some(p) = &run.progress {
                    (p.0)(step, run.steps);
                }
            }
            let t = run.t0 + step as f64 * dt;
            let t1 = t + dt;
            let ctx = StepContext { scheme, dt, t: t1 };
            for (f, src) in force.iter_mut().zip(&run.forces) {
                *f = src.signal.value(t);
            }
            // bulk and end nodes, interface force excluded (predictor); the interior
            // stencil has constant coefficients per segment, so it auto-vectorises
            for s in 0..nseg {
                let o = mesh.offset[s];
                let k = mesh.cells[s];
                let (up, uc, un) = (&u_prev[o..=o + k], &u[o..=o + k], &mut u_next[o..=o + k]);
                let c = &coef[s];
                // equal-length slices: no bounds checks, SIMD
                let (left, mid, right) = (&uc[..k - 1], &uc[1..k], &uc[2..]);
                let prev = &up[1..k];
                let out = &mut un[1..k];
                if c.exact {
                    // Courant 1, no damping: u+ = u_{j+1} + u_{j-1} - u-
                    for (((o, l), r), p) in out.iter_mut().zip(left).zip(right).zip(prev) {
                        *o = l + r - p;
                    }
                } else {
                    let (a, b, cc) = (c.a, c.b, c.c);
                    for ((((o, l), m), r), p) in
                        out.iter_mut().zip(left).zip(mid).zip(right).zip(prev)
                    {
                        *o = a * m + b * (l + r) - cc * p;
                    }
                }
                // end nodes (half mass): internal force from the one neighbour
                un[0] = c.a_end * uc[0] + c.b_end * uc[1] - c.c * up[0];
                un[k] = c.a_end * uc[k] + c.b_end * uc[k - 1] - c.c * up[k];
            }
            // external forces (few nodes)
            for (node, f) in forced.iter().zip(force.iter()) {
                u_next[*node] += inv_mass[*node] / damp_p[*node] * f;
            }
            out.node_updates += n as u64;
            // left end
            let last = n - 1;
            match &self.left {
                End::Free => {}
                End::Fixed => u_next[0] = 0.0,
                End::Transparent => {
                    let r = mesh.courant[0];
                    let (a, b, c) = match &inc_table {
                        Some(tab) => (
                            tab.at(t1 + len0 / c0),
                            tab.at(t + len0 / c0),
                            tab.at(t + (len0 - mesh.dx[0]) / c0),
                        ),
                        None => (0.0, 0.0, 0.0),
                    };
                    // outgoing part w = u - u_inc obeys w0+ = w0 + r (w1 - w0)
                    let w0 = u[0] - b;
                    let w1 = u[1] - c;
                    u_next[0] = a + w0 + r * (w1 - w0);
                }
                End::Obstacle(law) => {
                    let i = n_if - 1;
                    let chi = inv_mass[0] / damp_p[0] * self.area;
                    let (upd, s_app) =
                        interface_step(ctx, law, u_next[0], chi, beta[i], s_prev[i])?;
                    u_next[0] -= chi * s_app;
                    s_prev[i] = s_cur[i];
                    s_cur[i] = upd.dynamic_stress;
                    gaps[i] = upd.gap;
                    stresses[i] = upd.dynamic_stress - law.static_pressure;
                    beta[i] = upd.adhesion;
                }
            }
            if let Some(d) = &run.imposed {
                u_next[0] = d.value(t1);
            }
            match &self.right {
                End::Free => {}
                End::Fixed => u_next[last] = 0.0,
                End::Transparent => {
                    let s = nseg - 1;
                    let r = mesh.courant[s];
                    u_next[last] = u[last] + r * (u[last - 1] - u[last]);
                }
                End::Obstacle(law) => {
                    let i = self.interfaces.len();
                    let chi = inv_mass[last] / damp_p[last] * self.area;
                    let (upd, s_app) =
                        interface_step(ctx, law, -u_next[last], chi, beta[i], s_prev[i])?;
                    u_next[last] += chi * s_app;
                    s_prev[i] = s_cur[i];
                    s_cur[i] = upd.dynamic_stress;
                    gaps[i] = upd.gap;
                    stresses[i] = upd.dynamic_stress - law.static_pressure;
                    beta[i] = upd.adhesion;
                }
            }
            // interfaces between segments
            for (i, law) in self.interfaces.iter().enumerate() {
                let a = mesh.offset[i] + mesh.cells[i];
                let b = mesh.offset[i + 1];
                let chi_a = inv_mass[a] / damp_p[a] * self.area;
                let chi_b = inv_mass[b] / damp_p[b] * self.area;
                let (upd, s_app) = interface_step(
                    ctx,
                    law,
                    u_next[b] - u_next[a],
                    chi_a + chi_b,
                    beta[i],
                    s_prev[i],
                )?;
                u_next[a] += chi_a * s_app;
                u_next[b] -= chi_b * s_app;
                s_prev[i] = s_cur[i];
                s_cur[i] = upd.dynamic_stress;
                gaps[i] = upd.gap;
                stresses[i] = upd.dynamic_stress - law.static_pressure;
                beta[i] = upd.adhesion;
            }
            if (step % 4096 == 4095 || step + 1 == run.steps)
                && !u_next.iter().all(|v| v.is_finite())
            {
                return Err(Error::numerical(
                    t1,
                    "non-finite displacement",
                    format!("gaps = {gaps:?}"),
                ));
            }
            if (step + 1) % run.record_every.max(1) == 0 {
                record(&mut out, t1, &u_next, &gaps, &stresses, &beta);
            }
            std::mem::swap(&mut u_prev, &mut u);
            std::mem::swap(&mut u, &mut u_next);
        }
        Ok(out)
    }

    fn incident_table(&self, mesh: &Mesh, run: &FdRun) -> Result<Option<IncidentTable>> {
        let Some(inc) = &self.incident else {
            return Ok(None);
        };
        if !matches!(self.left, End::Transparent) {
            return Err(Error::invalid(
                "<model>",
                "left",
                "not transparent",
                "an incident wave enters through a transparent left end",
            ));
        }
        let z = self.segments[0].material.impedance();
        let dt = mesh.dt;
        let len0 = self.segments[0].length;
        let c0 = self.segments[0].material.wave_speed();
        let tau_max = run.t0 + (run.steps + 2) as f64 * dt + len0 / c0;
        // fine table at dt / 4 (exact GL integrals), linear between
        let h = dt / 4.0;
        let m = (tau_max / h).ceil().max(1.0) as usize + 2;
        let mut v = Vec::with_capacity(m + 1);
        let mut acc = 0.0;
        v.push(0.0);
        for k in 0..m {
            acc += gauss4(k as f64 * h, (k + 1) as f64 * h, |s| inc.stress(s));
            v.push(-acc / z);
        }
        Ok(Some(IncidentTable { h, v }))
    }
}

/// Stencil coefficients of a segment.
#[derive(Debug, Clone, Copy)]
struct Coef {
    a: f64,
    b: f64,
    c: f64,
    a_end: f64,
    b_end: f64,
    exact: bool,
}

/// Incident displacement F(tau) at the right end of segment 0, tabulated.
#[derive(Debug)]
struct IncidentTable {
    h: f64,
    v: Vec<f64>,
}

impl IncidentTable {
    #[inline]
    fn at(&self, tau: f64) -> f64 {
        if tau <= 0.0 {
            return 0.0;
        }
        let x = tau / self.h;
        let i = x.floor() as usize;
        if i + 1 >= self.v.len() {
            return *self.v.last().unwrap_or(&0.0);
        }
        let f = x - i as f64;
        self.v[i] * (1.0 - f) + self.v[i + 1] * f
    }
}

impl Solver for FdRun {
    type Problem = BarStack;
    type Output = FdOutput;
    fn solve(&self, problem: &BarStack) -> Result<FdOutput> {
        problem.run(self)
    }
}

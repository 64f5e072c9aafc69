//! Explicit finite-difference solver of a stack of elastic bars separated by contact
//! interfaces (model.md section 9; thesis sections 2.3.1-2.3.5, eqs. 2.2, 2.18-2.37).
//!
//! Each segment is meshed with `n_i = floor(L_i / (c_i dt))` cells, so its Courant number
//! `r_i = c_i dt / dx_i <= 1` and equals 1 (dispersion-free in 1D) when the length is a
//! multiple of `c_i dt`. The scheme is the lumped-mass form of the thesis' centred scheme:
//! interior nodes `u+ = 2u - u- + r^2 (u_{j+1} - 2u_j + u_{j-1})` (eq. 2.18 at the
//! Courant number r), end nodes with half mass, viscous damping `h` (eq. 2.2) centred in
//! time. Displacements are relative to the pre-loaded static equilibrium (gravity and
//! static forces are balanced by the static stress field, reported by the static step),
//! so an interface transmits the dynamic stress `S = sigma(gap) + p0`. Interfaces are
//! updated implicitly each step ([`crate::law::contact::update_point`]): the law holds exactly.
//! Ends: free, fixed, transparent (first-order absorbing, exact at Courant 1) with an
//! optional injected incident wave, or a rigid obstacle through an interface.
//! The time loop allocates nothing; state lives in flat `Vec<f64>`s.

mod field;
mod joint;

pub use super::output::{FdOutput, FdShearOutput};
use super::stepping::{self, Recorder, Schedule, Scheme};
use super::Solver;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
pub use crate::law::contact::InterfaceScheme;
use crate::law::contact::{PointState, StepContext};
use crate::law::{ContactLaw, TangentialLaw};
use crate::material::Material;
pub(crate) use field::Field;
pub(crate) use joint::Joint;
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
    /// The transverse (shear) field, when the stack carries one.
    pub shear: Option<ShearStack>,
}

/// The transverse field of a stack (model.md sections 9.7 and 13): plane shear waves along
/// the stack, every segment at its shear wave speed `c_T = sqrt(G / rho)`, the interfaces
/// updated by the coupled normal/tangential law each step. The ends are those of the
/// longitudinal field: free, fixed, transparent (injecting `incident`) or the obstacle
/// contact through `obstacle`.
#[derive(Debug, Clone)]
pub struct ShearStack {
    /// Tangential law of each interface between segments, in order.
    pub interfaces: Vec<Arc<TangentialLaw>>,
    /// Tangential law of the obstacle contact (needed with an obstacle end).
    pub obstacle: Option<Arc<TangentialLaw>>,
    /// Incident shear wave through a transparent left end: `tau_inc(t)` is its shear
    /// stress at the right end of the first segment (front there at t = 0), Pa.
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
    /// Mesh every segment at Courant number <= 1 for time step `dt` (s), at its
    /// longitudinal wave speed.
    pub fn mesh(&self, dt: f64) -> Mesh {
        let speeds: Vec<f64> = self
            .segments
            .iter()
            .map(|s| s.material.wave_speed())
            .collect();
        mesh_with(&self.segments, &speeds, dt, |_| false)
    }

    /// The mesh of the transverse field at time step `dt` (s), when the stack has one
    /// (see [`BarStack::run`]): `None` without a shear field or a shear modulus.
    pub fn shear_mesh(&self, dt: f64) -> Option<Mesh> {
        self.shear.as_ref()?;
        let speeds: Option<Vec<f64>> = self
            .segments
            .iter()
            .map(|s| s.material.shear_wave_speed())
            .collect();
        let n = self.segments.len();
        Some(mesh_with(&self.segments, &speeds?, dt, |i| {
            (i == 0 && matches!(self.left, End::Transparent))
                || (i + 1 == n && matches!(self.right, End::Transparent))
        }))
    }

    /// Global node index at position `x` (m, from the left end of `segment`).
    pub fn node_at(&self, mesh: &Mesh, segment: usize, x: f64) -> usize {
        let k = (x / mesh.dx[segment])
            .round()
            .clamp(0.0, mesh.cells[segment] as f64) as usize;
        mesh.offset[segment] + k
    }
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
    /// Probe nodes of the transverse field (global indices of [`BarStack::shear_mesh`];
    /// recorded only when the stack has a shear field).
    pub shear_probes: Vec<usize>,
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
                format!("segment.{i}"),
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
        let mut scheme = self.scheme(run)?;
        let n_rec = run.steps / run.record_every.max(1) + 1;
        let mut rec = StackRecorder {
            run,
            out: FdOutput::with_capacity(
                n_rec,
                run.probes.len(),
                scheme.laws.len(),
                scheme.shear.as_ref().map(|_| run.shear_probes.len()),
            ),
        };
        let schedule = Schedule {
            t0: run.t0,
            dt: run.dt,
            steps: run.steps,
            record_every: run.record_every,
            check_every: 0,
            progress: run.progress.as_ref().map(|p| &*p.0),
        };
        stepping::run(&schedule, &mut scheme, &mut rec)?;
        let mut out = rec.out;
        out.node_updates = scheme.node_updates;
        if let Some(sh) = out.shear.as_mut() {
            let state = &scheme.contacts.state;
            sh.friction_dissipation = state.iter().map(|s| s.friction).collect();
            sh.damage_dissipation = state.iter().map(|s| s.damage).collect();
        }
        Ok(out)
    }

    /// The stack's fields, contacts and sources set up for `run` (checked: Courant
    /// numbers, one law per interface, an incident wave only through a transparent end).
    fn scheme<'a>(&'a self, run: &'a FdRun) -> Result<StackScheme<'a>> {
        let mesh = self.mesh(run.dt);
        check_stability(&mesh)?;
        let dt = run.dt;
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
        let tau_max = run.t0 + (run.steps + 2) as f64 * dt;
        let incident = self.incident_wave(self.incident.as_deref(), |m| m.impedance())?;
        let seg0 = &self.segments[0];
        let normal = Field::new(
            self,
            mesh,
            (seg0.material.wave_speed(), seg0.length),
            incident,
            tau_max,
        );
        let shear = self.shear_field(dt, tau_max)?;
        let n = normal.nodes();
        // interfaces between segments, then the obstacle(s): right, left
        let laws = self.contact_laws();
        let contacts = Contacts::new(
            &laws,
            self.tangential_laws()?,
            self.joints(&normal.mesh),
            shear
                .as_ref()
                .map_or_else(Vec::new, |f| self.joints(&f.mesh)),
        );
        Ok(StackScheme {
            stack: self,
            run,
            force: vec![0.0; run.forces.len()],
            forced: run.forces.iter().map(|f| f.node.min(n - 1)).collect(),
            laws,
            normal,
            shear,
            contacts,
            node_updates: 0,
        })
    }

    /// The incident wave of a transparent first end and the first segment's impedance
    /// for its wave type (`z` of a material, Pa s/m); an error with another first end.
    fn incident_wave<'a>(
        &self,
        incident: Option<&'a dyn Excitation>,
        z: impl Fn(&Material) -> f64,
    ) -> Result<Option<(&'a dyn Excitation, f64)>> {
        let Some(inc) = incident else {
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
        Ok(Some((inc, z(&self.segments[0].material))))
    }

    /// The contact laws in the order of the interface state: between segments, then the
    /// obstacle of the last end, then that of the first end.
    fn contact_laws(&self) -> Vec<Arc<ContactLaw>> {
        let mut laws = self.interfaces.clone();
        for end in [&self.right, &self.left] {
            if let End::Obstacle(l) = end {
                laws.push(l.clone());
            }
        }
        laws
    }

    /// The tangential laws in the order of [`BarStack::contact_laws`] (empty without a
    /// shear field).
    fn tangential_laws(&self) -> Result<Vec<Arc<TangentialLaw>>> {
        let Some(sh) = &self.shear else {
            return Ok(Vec::new());
        };
        if sh.interfaces.len() != self.interfaces.len() {
            return Err(Error::invalid(
                "<model>",
                "shear.interfaces",
                sh.interfaces.len(),
                format!(
                    "one tangential law per interface ({})",
                    self.interfaces.len()
                ),
            ));
        }
        let mut laws = sh.interfaces.clone();
        for end in [&self.right, &self.left] {
            if let End::Obstacle(_) = end {
                laws.push(sh.obstacle.clone().ok_or_else(|| {
                    Error::invalid(
                        "<model>",
                        "shear.obstacle",
                        "(missing)",
                        "an obstacle end of a stack with a shear field needs a tangential law",
                    )
                })?);
            }
        }
        Ok(laws)
    }

    /// The transverse field of a stack with a shear field: every segment at its shear
    /// wave speed; a segment that ends in a transparent end is a buffer whose length only
    /// delays the waves, and is meshed at Courant number 1 (`dx = c_T dt`, the nearest
    /// whole number of cells) so that the end absorbs exactly.
    fn shear_field(&self, dt: f64, tau_max: f64) -> Result<Option<Field>> {
        let Some(sh) = &self.shear else {
            return Ok(None);
        };
        let missing = |i: usize| {
            Error::invalid(
                "<model>",
                format!("segment.{i}.shear_modulus"),
                "(missing)",
                "a stack with a shear field needs the shear modulus of every segment",
            )
        };
        if let Some(i) = self.segments.iter().position(|s| {
            !s.material
                .shear_wave_speed()
                .is_some_and(|c| c.is_finite() && c > 0.0)
        }) {
            return Err(missing(i));
        }
        let mesh = self.shear_mesh(dt).ok_or_else(|| missing(0))?;
        check_stability(&mesh)?;
        let incident = self.incident_wave(sh.incident.as_deref(), |m| {
            m.shear_impedance().unwrap_or(f64::NAN)
        })?;
        let len0 = self.segments[0].length;
        Ok(Some(Field::new(
            self,
            mesh,
            (
                self.segments[0]
                    .material
                    .shear_wave_speed()
                    .unwrap_or(f64::NAN),
                len0,
            ),
            incident,
            tau_max,
        )))
    }

    /// The nodes each contact joins on `mesh`, in the order of [`BarStack::contact_laws`].
    fn joints(&self, mesh: &Mesh) -> Vec<Joint> {
        let last = mesh.nodes - 1;
        let mut joints: Vec<Joint> = (0..self.interfaces.len())
            .map(|i| Joint {
                a: Some(mesh.offset[i] + mesh.cells[i]),
                b: Some(mesh.offset[i + 1]),
            })
            .collect();
        if matches!(self.right, End::Obstacle(_)) {
            joints.push(Joint {
                a: Some(last),
                b: None,
            });
        }
        if matches!(self.left, End::Obstacle(_)) {
            joints.push(Joint {
                a: None,
                b: Some(0),
            });
        }
        joints
    }
}

/// Every contact of the stack (between segments, then the obstacles) as the time loop
/// updates it: its nodes in each field, its tangential law with a shear field, its state.
struct Contacts {
    joints: Vec<Joint>,
    shear_joints: Vec<Joint>,
    tangential: Vec<Arc<TangentialLaw>>,
    state: Vec<PointState>,
}

impl Contacts {
    fn new(
        laws: &[Arc<ContactLaw>],
        tangential: Vec<Arc<TangentialLaw>>,
        joints: Vec<Joint>,
        shear_joints: Vec<Joint>,
    ) -> Self {
        let state = laws
            .iter()
            .enumerate()
            .map(|(i, l)| PointState::at_rest(&**l, tangential.get(i).map(|t| &**t)))
            .collect();
        Contacts {
            joints,
            shear_joints,
            tangential,
            state,
        }
    }

    /// Update contact `i` (law `law`) at the new level on the longitudinal field and, when
    /// there is one, the shear field.
    #[inline]
    fn update(
        &mut self,
        i: usize,
        ctx: StepContext,
        law: &ContactLaw,
        normal: &mut Field,
        shear: Option<&mut Field>,
    ) -> Result<()> {
        let side = shear.map(|f| (f, self.shear_joints[i], &*self.tangential[i]));
        joint::update(ctx, law, self.joints[i], &mut self.state[i], normal, side)
    }
}

/// A stack in the time loop: its fields, contacts and sources for one run.
struct StackScheme<'a> {
    stack: &'a BarStack,
    run: &'a FdRun,
    /// External forces of the step, N, and the nodes they act on.
    force: Vec<f64>,
    forced: Vec<usize>,
    /// Contact laws in the order of the contacts' state.
    laws: Vec<Arc<ContactLaw>>,
    normal: Field,
    shear: Option<Field>,
    contacts: Contacts,
    /// Node updates performed (of both fields).
    node_updates: u64,
}

impl Scheme for StackScheme<'_> {
    fn step(&mut self, t: f64, t1: f64) -> Result<()> {
        let (stack, run) = (self.stack, self.run);
        let (normal, contacts) = (&mut self.normal, &mut self.contacts);
        let mut shear = self.shear.as_mut();
        let n = normal.nodes();
        let ctx = StepContext {
            scheme: run.interface_scheme,
            dt: run.dt,
            t: t1,
        };
        for (f, src) in self.force.iter_mut().zip(&run.forces) {
            *f = src.signal.value(t);
        }
        normal.bulk();
        // external forces (few nodes)
        for (node, f) in self.forced.iter().zip(self.force.iter()) {
            normal.u_next[*node] += normal.force_gain(*node) * f;
        }
        self.node_updates += n as u64;
        if let Some(sf) = shear.as_deref_mut() {
            sf.bulk();
            self.node_updates += sf.nodes() as u64;
        }
        // first end
        match &stack.left {
            End::Free => {}
            End::Fixed => {
                normal.u_next[0] = 0.0;
                if let Some(sf) = shear.as_deref_mut() {
                    sf.u_next[0] = 0.0;
                }
            }
            End::Transparent => {
                normal.transparent_first(t, t1);
                if let Some(sf) = shear.as_deref_mut() {
                    sf.transparent_first(t, t1);
                }
            }
            End::Obstacle(law) => {
                let i = self.laws.len() - 1;
                contacts.update(i, ctx, law, normal, shear.as_deref_mut())?;
            }
        }
        if let Some(d) = &run.imposed {
            normal.u_next[0] = d.value(t1);
        }
        match &stack.right {
            End::Free => {}
            End::Fixed => {
                normal.u_next[n - 1] = 0.0;
                if let Some(sf) = shear.as_deref_mut() {
                    let last = sf.nodes() - 1;
                    sf.u_next[last] = 0.0;
                }
            }
            End::Transparent => {
                normal.transparent_last();
                if let Some(sf) = shear.as_deref_mut() {
                    sf.transparent_last();
                }
            }
            End::Obstacle(law) => {
                let i = stack.interfaces.len();
                contacts.update(i, ctx, law, normal, shear.as_deref_mut())?;
            }
        }
        for (i, law) in stack.interfaces.iter().enumerate() {
            contacts.update(i, ctx, law, normal, shear.as_deref_mut())?;
        }
        Ok(())
    }

    fn check_finite(&self, t1: f64) -> Result<()> {
        if self.normal.finite() && self.shear.as_ref().is_none_or(|f| f.finite()) {
            return Ok(());
        }
        let gaps: Vec<f64> = self.contacts.state.iter().map(|s| s.gap).collect();
        Err(Error::numerical(
            t1,
            "non-finite displacement",
            format!("gaps = {gaps:?}"),
        ))
    }

    fn advance(&mut self) {
        self.normal.rotate();
        if let Some(sf) = self.shear.as_mut() {
            sf.rotate();
        }
    }
}

/// Records a stack's levels into an [`FdOutput`].
struct StackRecorder<'a> {
    run: &'a FdRun,
    out: FdOutput,
}

impl Recorder<StackScheme<'_>> for StackRecorder<'_> {
    fn record(&mut self, t: f64, s: &StackScheme<'_>) {
        let shear = s.shear.as_ref().map(|f| &f.u[..]);
        record_level(
            &mut self.out,
            self.run,
            t,
            (&s.normal.u, shear),
            &s.contacts,
        );
    }
}

/// Record one level: the probes' displacements and every interface's state (and the
/// shear field's, when there is one).
fn record_level(
    out: &mut FdOutput,
    run: &FdRun,
    t: f64,
    (normal, shear): (&[f64], Option<&[f64]>),
    contacts: &Contacts,
) {
    let (state, tangential) = (&contacts.state, &contacts.tangential);
    out.t.push(t);
    for (p, &node) in run.probes.iter().enumerate() {
        out.displacement[p].push(normal[node]);
    }
    for (i, st) in state.iter().enumerate() {
        out.gap[i].push(st.gap);
        out.stress[i].push(st.stress);
        out.beta[i].push(st.beta);
    }
    if let (Some(sh), Some(u)) = (out.shear.as_mut(), shear) {
        for (p, &node) in run.shear_probes.iter().enumerate() {
            sh.displacement[p].push(u[node.min(u.len() - 1)]);
        }
        for (i, (st, tl)) in state.iter().zip(tangential).enumerate() {
            sh.gap[i].push(st.shear.gap);
            sh.stress[i].push(st.shear_stress(&**tl));
            sh.slip[i].push(st.shear.slip);
            sh.state[i].push(st.shear.state);
        }
    }
}

/// Mesh segments of wave speeds `speed` (m/s) at Courant number <= 1 for time step `dt`
/// (s); a segment `i` with `exact(i)` is meshed at Courant 1 with the nearest whole number
/// of cells of size `speed dt` (its meshed length then differs from its length by less than
/// half a cell).
fn mesh_with(segments: &[Segment], speed: &[f64], dt: f64, exact: impl Fn(usize) -> bool) -> Mesh {
    let mut m = Mesh {
        dt,
        offset: Vec::new(),
        cells: Vec::new(),
        dx: Vec::new(),
        courant: Vec::new(),
        nodes: 0,
    };
    for (i, (s, &c)) in segments.iter().zip(speed).enumerate() {
        let (k, dx, r) = if exact(i) {
            let k = (s.length / (c * dt)).round().max(1.0) as usize;
            (k, c * dt, 1.0)
        } else {
            let k = ((s.length / (c * dt)) * (1.0 + 1e-12)).floor().max(1.0) as usize;
            let dx = s.length / k as f64;
            (k, dx, c * dt / dx)
        };
        m.offset.push(m.nodes);
        m.cells.push(k);
        m.dx.push(dx);
        m.courant.push(r);
        m.nodes += k + 1;
    }
    m
}

impl Solver for FdRun {
    type Problem = BarStack;
    /// (nothing kept from run to run)
    type Workspace = ();
    type Output = FdOutput;
    /// (the records are sized for the run's probes and levels and replace the recorder
    /// given)
    fn run_in(&self, problem: &BarStack, _: &mut (), out: &mut FdOutput) -> Result<()> {
        *out = problem.run(self)?;
        Ok(())
    }
}

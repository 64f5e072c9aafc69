//! Finite cracks in 2D (model.md section 9): plane-strain P-SV or antiplane SH waves in a
//! rectangle of horizontal elastic layers, spectral elements of GLL order 2 to 8 on a
//! structured mesh (diagonal mass), explicit central differences in time, and cracks as
//! split-node boundary objects ([`crack::CrackNodes`]) whose every node is updated exactly at
//! the new level by the per-point contact update of `law/`.
//!
//! The pieces: [`mesh`] (element edges through every layer boundary and crack line, the
//! node grid, the split twins), [`kernel`] (the internal forces `-K u`, parallel and
//! deterministic), [`crack`] (the split nodes), and here the problem, its plan (mass,
//! time step, sources, receivers) and the time loop with its energy audit.
//!
//! Time stepping (leapfrog on the displacement, the velocity at half levels):
//!
//! ```text
//! v~ = v^{n-1/2} + dt M^-1 (f^n - K u^n)           predicted, no crack traction
//! crack update: U = U~ - chi S at each split node  (the law at the new level)
//! v^{n+1/2} = v~ + dt M^-1 B (S n + T t) (face 1; minus on face 2)
//! u^{n+1} = u^n + dt v^{n+1/2}
//! ```
//!
//! The discrete energy `E^{n+1/2} = v^{n+1/2} M v^{n+1/2} / 2 + u^n K u^{n+1} / 2` then
//! changes by exactly the work of the sources, `f^n (u^{n+1} - u^{n-1}) / 2`, less the
//! crack's `B S (U^{n+1} - U^{n-1}) / 2`: the audit closes at round-off in a closed domain.
//! Stable for `dt < 2 / omega_max` (the highest eigenfrequency of `M^-1 K`, found by power
//! iteration); the crack's update is implicit and does not reduce the step.

mod backend;
pub mod crack;
pub mod dispersion;
mod energy;
mod estimate;
#[cfg(feature = "gpu")]
mod gpu;
pub mod kernel;
mod lines;
pub mod mesh;
pub mod plane_wave;
pub mod pml;
pub mod probe;
pub mod quad;
pub mod region;
mod registers;
mod simd;
pub mod snapshot;
mod stepping;
mod strip;

#[cfg(all(test, feature = "gpu"))]
mod gpu_tests;
#[cfg(test)]
mod plane_wave_tests;
#[cfg(test)]
mod surface_tests;
#[cfg(test)]
mod tests;

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::contact::PointState;
use crate::law::{NormalPart, TangentialPart};
pub use backend::Backend;

/// The GLL orders of the elements the kernels take.
pub const ORDERS: std::ops::RangeInclusive<usize> = 2..=8;
use crack::CrackNodes;
pub use energy::Energy2d;
pub use estimate::MemoryEstimate;
use kernel::{max_frequency, ElementData, NodeRows, Stiffness};
use mesh::{aperture_faces, edge_weight, CrackLine, Mesh};
pub use plane_wave::Incidence;
pub use pml::Pml;
use probe::{nearest, StressProbe};
use std::sync::Arc;

/// An isotropic elastic solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Density rho, kg/m^3.
    pub density: f64,
    /// P-wave speed c_P, m/s.
    pub p_speed: f64,
    /// S-wave speed c_S, m/s.
    pub s_speed: f64,
}

impl Elastic {
    /// Shear modulus mu = rho c_S^2, Pa.
    pub fn mu(&self) -> f64 {
        self.density * self.s_speed * self.s_speed
    }
    /// Lame's lambda = rho c_P^2 - 2 mu, Pa.
    pub fn lambda(&self) -> f64 {
        self.density * self.p_speed * self.p_speed - 2.0 * self.mu()
    }
}

/// The wave type of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WaveType {
    /// Plane strain, `(u_x, u_z)`.
    PSv,
    /// Antiplane, `u_y`.
    Sh,
}

/// What a side of the rectangle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Traction free (the spectral elements' natural condition).
    Free,
    /// Fixed: zero displacement.
    Rigid,
    /// Periodic (the x sides only, both together).
    Periodic,
    /// Absorbing: a perfectly matched layer ([`pml`]) of [`Solid2d::pml`]'s thickness
    /// added outside the rectangle along the side (its outer edge fixed); its reflection
    /// against angle is measured in docs/model.md section 15.7.
    Absorbing,
}

/// A horizontal layer: its material down to `bottom` (m, z of its lower boundary).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    /// z of the lower boundary, m (the last layer's is the depth).
    pub bottom: f64,
    /// Material.
    pub material: Elastic,
}

/// A straight crack along x or z between two points `[x, z]` (m), with the law of every
/// point.
#[derive(Debug, Clone)]
pub struct Crack<L> {
    /// Start `[x, z]`, m.
    pub start: [f64; 2],
    /// End `[x, z]`, m (same z as the start: horizontal; same x: vertical).
    pub end: [f64; 2],
    /// Across the whole width of a periodic rectangle (start and end ignored but z).
    pub full_width: bool,
    /// The contact law of its points (normal and tangential).
    pub law: L,
    /// The static state varying along the crack (a closure table): each point's law and
    /// initial gap from its position; `None`: `law` at every point, closed at rest.
    pub profile: Option<Arc<dyn CrackProfile<L>>>,
}

impl<L> Crack<L> {
    /// A plane interface across the whole width `width` (m) of a periodic rectangle at
    /// depth `z` (m), with `law` at every point.
    pub fn across(width: f64, z: f64, law: L) -> Self {
        Crack {
            start: [0.0, z],
            end: [width, z],
            full_width: true,
            law,
            profile: None,
        }
    }
}

/// A crack's static state along its length (docs/model.md section 15.2): the law of the
/// point at `position` (m from the crack's start, along +x or +z) and its initial normal
/// gap (m, >= 0; a point with a gap is traction-free at rest).
pub trait CrackProfile<L>: std::fmt::Debug + Send + Sync {
    /// The law and the initial gap (m) of the point at `position` (m).
    fn at(&self, position: f64) -> Result<(L, f64)>;
}

/// Where a source acts and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SourceKind {
    /// A line force (N/m per unit of the signal) at the node nearest `at = [x, z]` (m),
    /// along `direction` (`[x, z]`, unit; ignored in antiplane runs: along y).
    Force {
        /// Position, m.
        at: [f64; 2],
        /// Direction.
        direction: [f64; 2],
    },
    /// A traction (Pa per unit of the signal) over `[x0, x1]` (m) of the top (`top`) or
    /// bottom surface, normal (`normal`: along +z, i.e. a pull on the top surface... see
    /// [`Source`]) or shear (along +x; along y in antiplane runs), each point delayed by
    /// `delay_per_m * (x - x0)` (s/m: an angled beam by a linear delay law).
    Traction {
        /// On the top surface (z = 0) or the bottom one.
        top: bool,
        /// Aperture start, m.
        x0: f64,
        /// Aperture end, m.
        x1: f64,
        /// Normal traction (else shear).
        normal: bool,
        /// Linear delay law, s/m.
        delay_per_m: f64,
    },
    /// A plane wave injected across the horizontal line `z` (m, an element edge strictly
    /// inside the rectangle) by total-field/scattered-field ([`plane_wave`]): it travels
    /// down at `angle` (rad from +z, toward +x; 0 with periodic sides) in the total field
    /// below the line, the field above holds only what is scattered. Its signal is the
    /// wave's stress (Pa): particle velocity `-s / (rho c)` along its polarisation.
    PlaneWave {
        /// P, SV (P-SV runs) or SH (SH runs).
        incidence: Incidence,
        /// Angle from the z axis, rad, in (-pi/2, pi/2).
        angle: f64,
        /// Depth of the total-field/scattered-field line, m.
        z: f64,
    },
}

/// A source: where, and its time function.
#[derive(Debug, Clone)]
pub struct Source {
    /// Where and how. A normal traction `s(t)` on a surface is the stress `sigma_zz = s`
    /// there (tension positive: a compressive burst pushes into the solid).
    pub kind: SourceKind,
    /// The time function (its `stress(t)`: Pa for a traction, N/m for a force).
    pub signal: Arc<dyn Excitation>,
}

/// The problem of a 2D run.
#[derive(Debug, Clone)]
pub struct Solid2d<L> {
    /// Width along x, m.
    pub width: f64,
    /// Layers from the top down; the last one's bottom is the depth.
    pub layers: Vec<Layer>,
    /// Wave type.
    pub wave: WaveType,
    /// Top, bottom, and the x sides.
    pub top: Side,
    /// Bottom side.
    pub bottom: Side,
    /// Left and right sides (periodic: both).
    pub sides: Side,
    /// Largest element size, m.
    pub element_size: f64,
    /// GLL order of the elements (2 to 8).
    pub order: usize,
    /// Fraction of the stability limit `2 / omega_max` the time step takes (0 to 1).
    pub courant: f64,
    /// Largest time step, s (`f64::INFINITY`: the stability limit alone). The central
    /// differences' phase error at angular frequency omega is about `(omega dt)^2 / 24`:
    /// `0.12 / omega` keeps it below 6e-4 (a scenario bounds it at its highest analysed
    /// harmonic).
    pub max_time_step: f64,
    /// Cracks.
    pub cracks: Vec<Crack<L>>,
    /// Sources.
    pub sources: Vec<Source>,
    /// Velocity receivers `[x, z]`, m (the nearest node; on a crack, its face-1 node).
    pub receivers: Vec<[f64; 2]>,
    /// Duration, s.
    pub duration: f64,
    /// Record the crack fields every this many steps.
    pub crack_every: usize,
    /// The absorbing sides' perfectly matched layers.
    pub pml: Pml,
}

/// A force applied at one node component: `(index into u, weight, source, delay s)`.
#[derive(Debug, Clone, Copy)]
struct Load {
    index: usize,
    weight: f64,
    source: usize,
    delay: f64,
}

/// The built run: mesh, operator, masses, step, cracks, loads and receivers.
#[derive(Debug, Clone)]
pub struct Plan<L> {
    /// The mesh.
    pub mesh: Mesh,
    stiffness: Stiffness,
    /// The grid node rows the kernel advances, and the nodes outside them (split twins,
    /// absorbing layers) that the step advances after it.
    rows: (NodeRows, Vec<u32>),
    /// Inverse lumped mass per node, 1/(kg/m) (0 on rigid sides).
    inv_mass: Vec<f64>,
    /// Lumped mass per node, kg/m.
    mass: Vec<f64>,
    /// Time step, s.
    pub dt: f64,
    /// Steps of the run.
    pub steps: usize,
    /// Components per node (1 antiplane, 2 plane strain).
    pub components: usize,
    /// The cracks at rest, as planned (each run starts from a copy).
    cracks: Vec<CrackNodes<L>>,
    loads: Vec<Load>,
    /// The absorbing sides' perfectly matched layers (their elements and fields at rest;
    /// each run starts from a copy; none without).
    band: pml::Band,
    signals: Vec<Arc<dyn Excitation>>,
    /// Receiver nodes.
    pub receiver_nodes: Vec<usize>,
    /// Stress receivers ([`Plan::add_stress_receivers`]).
    pub stress_probes: Vec<StressProbe>,
    crack_every: usize,
    /// The plane-wave sources (at rest: each run starts from a copy).
    pub plane_waves: Vec<plane_wave::Injection>,
    /// Steps after which the whole velocity field is kept ([`Plan::capture_at`]).
    snapshot_steps: Vec<usize>,
}

/// One crack's recorded fields, `[record][point]` flattened point-fastest: every field of
/// a record at the record's time level (the gaps and a compliant law's stresses of the
/// level; a constraint's reaction, the normal stress of a closed rigid or bonded point and
/// a rigid-stick slider's stress, the force of the step that starts at the level,
/// [`crack`]).
#[derive(Debug, Clone, Default)]
pub struct CrackRecord {
    /// Position of each point along the crack, m.
    pub position: Vec<f64>,
    /// Each point's `[x, z]`, m, where the crack is not a straight line from its start
    /// (a mesh's crack); empty for the rectangle's (its start plus `position` along it).
    pub points: Vec<[f64; 2]>,
    /// Times of the records, s: the levels `k dt` for k = 1, 1 + `crack_every`,
    /// 1 + 2 `crack_every`, ... and the last complete level `(N - 1) dt` of a run of N
    /// steps (its reactions are those of the last step).
    pub time: Vec<f64>,
    /// Normal gap, m.
    pub normal_gap: Vec<f64>,
    /// Tangential gap, m.
    pub tangential_gap: Vec<f64>,
    /// Normal contact stress sigma (tension positive, -p0 at rest), Pa.
    pub normal_stress: Vec<f64>,
    /// Shear stress tau, Pa.
    pub shear_stress: Vec<f64>,
    /// Adhesion beta.
    pub adhesion: Vec<f64>,
    /// Contact state: 0 open (the normal gap beyond the law's contact-loss gap `[u]_c`:
    /// 0 for Signorini, positive for a compliant compression branch, whose faces still
    /// press at a positive gap from rest), 1 stick, 2 slip (sliding, or closed without
    /// friction); a rigid-stick slider's state is that of the step whose stress is
    /// recorded.
    pub state: Vec<f64>,
    /// The largest normal gap of any point at any step (every step, not only the
    /// recorded ones; 0 if it never opens), m.
    pub peak_normal_gap: f64,
    /// The largest |tangential gap| of any point at any step, m.
    pub peak_slip: f64,
    /// The smallest adhesion of any point at any step (1 where nothing is damaged).
    pub least_adhesion: f64,
}

/// What a 2D run returns.
#[derive(Debug, Clone, Default)]
pub struct Solid2dOutput {
    /// Time step, s.
    pub dt: f64,
    /// Times of the receiver samples (half levels `(n + 1/2) dt`), s.
    pub time: Vec<f64>,
    /// Receiver velocities, `[receiver][component][sample]` flattened: receiver r,
    /// component c at `(r * components + c) * n_t + k`, m/s.
    pub receivers: Vec<f64>,
    /// Components per receiver.
    pub components: usize,
    /// Stress receivers' stresses at the same times, `[receiver][component][sample]`
    /// flattened like `receivers`, Pa (dynamic: the static closure is not in the bulk).
    pub stresses: Vec<f64>,
    /// Components per stress receiver: 3 in plane strain (`xx`, `zz`, `xz`), 2 in
    /// antiplane runs (`yx`, `yz`).
    pub stress_components: usize,
    /// Each crack's fields.
    pub cracks: Vec<CrackRecord>,
    /// Energy audit.
    pub energy: Energy2d,
    /// The velocity fields kept at the plan's snapshot steps ([`Plan::capture_at`]).
    pub snapshots: snapshot::Capture,
}

impl Solid2dOutput {
    /// The trace of receiver `r`, component `c`.
    pub fn trace(&self, r: usize, c: usize) -> &[f64] {
        let n = self.time.len();
        let i = (r * self.components + c) * n;
        &self.receivers[i..i + n]
    }

    /// The trace of stress receiver `r`, component `c`, Pa.
    pub fn stress_trace(&self, r: usize, c: usize) -> &[f64] {
        let n = self.time.len();
        let i = (r * self.stress_components + c) * n;
        &self.stresses[i..i + n]
    }
}

impl<L: NormalPart + TangentialPart + Clone> Solid2d<L> {
    /// Depth, m.
    pub fn depth(&self) -> f64 {
        self.layers.last().map_or(0.0, |l| l.bottom)
    }

    /// The absorbing layers' thicknesses (m; 0 where a side is not absorbing): top,
    /// bottom, and each x side.
    pub fn pml_thicknesses(&self) -> (f64, f64, f64) {
        let l = |s: Side| {
            if s == Side::Absorbing {
                self.pml.thickness
            } else {
                0.0
            }
        };
        (l(self.top), l(self.bottom), l(self.sides))
    }

    /// Check the problem without building anything: sizes, materials, cracks inside the
    /// rectangle and along x or z, and the mesh against the memory budget. Returns the x
    /// and z lines the element edges must follow.
    pub fn validate(&self, file: &str) -> Result<(Vec<f64>, Vec<f64>)> {
        let (xs, zs) = self.lines(file)?;
        let (nodes, bytes) = self.mesh_bytes(xs.len(), zs.len());
        let (key, value, change) = self.mesh_key(nodes);
        let what = format!("a mesh of about {nodes:.3e} nodes");
        crate::budget::check_or(file, key, value, bytes, &what, change)?;
        Ok((xs, zs))
    }

    /// [`Solid2d::validate`] without the memory check: the lines the element edges follow.
    fn lines(&self, file: &str) -> Result<(Vec<f64>, Vec<f64>)> {
        let bad = |field: &str, value: String, allowed: &str| {
            Err(Error::invalid(file, field, value, allowed))
        };
        let depth = self.depth();
        if !(self.width > 0.0 && self.width.is_finite() && depth > 0.0 && depth.is_finite()) {
            return bad(
                "model.width",
                format!("{} m x {} m", self.width, depth),
                "a rectangle of positive, finite size",
            );
        }
        if !ORDERS.contains(&self.order) {
            return bad(
                "model.order",
                self.order.to_string(),
                &format!("{} to {}", ORDERS.start(), ORDERS.end()),
            );
        }
        if !(self.courant > 0.0 && self.courant < 1.0) {
            return bad("model.courant", self.courant.to_string(), "in (0, 1)");
        }
        if !(self.max_time_step > 0.0) {
            return bad(
                "model.max_time_step",
                self.max_time_step.to_string(),
                "> 0 s",
            );
        }
        if !(self.element_size > 0.0) {
            return bad("model.element_size", self.element_size.to_string(), "> 0 m");
        }
        if self.top == Side::Periodic || self.bottom == Side::Periodic {
            return bad(
                "model.top",
                "periodic".into(),
                "free or rigid (only the x sides may be periodic)",
            );
        }
        if !(self.duration > 0.0 && self.duration.is_finite()) {
            return bad("model.duration", self.duration.to_string(), "> 0 s, finite");
        }
        if [self.top, self.bottom, self.sides].contains(&Side::Absorbing) {
            let l = self.pml.thickness;
            if !(l > 0.0 && l.is_finite()) {
                return bad("model.pml_thickness", l.to_string(), "> 0 m, finite");
            }
            let r = self.pml.reflection;
            if !(r > 0.0 && r < 1.0) {
                return bad("model.pml_reflection", r.to_string(), "in (0, 1)");
            }
        }
        let region = region::Region::new(self.width, depth);
        for (i, r) in self.receivers.iter().enumerate() {
            if !region.contains(*r) {
                return bad(
                    &format!("receiver.{i}.at"),
                    format!("{r:?}"),
                    &region.describe(),
                );
            }
        }
        for (i, s) in self.sources.iter().enumerate() {
            if let SourceKind::Force { at, .. } = s.kind
                && !region.contains(at)
            {
                return bad(
                    &format!("source.{i}.at"),
                    format!("{at:?}"),
                    &region.describe(),
                );
            }
        }
        for (i, l) in self.layers.iter().enumerate() {
            let m = l.material;
            if !(m.density > 0.0 && m.s_speed > 0.0 && m.p_speed > m.s_speed * 2f64.sqrt()) {
                return bad(
                    &format!("layer.{i}"),
                    format!("rho {}, c_P {}, c_S {}", m.density, m.p_speed, m.s_speed),
                    "rho > 0, c_S > 0 and c_P > sqrt(2) c_S (a Poisson ratio in (0, 0.5))",
                );
            }
        }
        // the lines every element edge must follow
        let mut xs = Vec::new();
        let mut zs: Vec<f64> = self.layers.iter().map(|l| l.bottom).collect();
        for (i, c) in self.cracks.iter().enumerate() {
            if c.full_width {
                zs.push(c.start[1]);
                continue;
            }
            let horizontal = c.start[1] == c.end[1];
            if !horizontal && c.start[0] != c.end[0] {
                return bad(
                    &format!("crack.{i}.end"),
                    format!("{:?}", c.end),
                    "a horizontal or vertical crack (same z or same x as the start)",
                );
            }
            for p in [c.start, c.end] {
                let z_ok = p[1] > 0.0 && p[1] < depth || !horizontal && self.mouth(p, false);
                if !(p[0] >= 0.0 && p[0] <= self.width && z_ok) {
                    return bad(
                        &format!("crack.{i}.start"),
                        format!("{p:?}"),
                        "inside the rectangle (only a vertical crack may end on its top or \
                         bottom side, where that side is free)",
                    );
                }
            }
            let seam = self.sides == Side::Periodic;
            if !horizontal && !seam && (c.start[0] <= 0.0 || c.start[0] >= self.width) {
                return bad(
                    &format!("crack.{i}.start"),
                    format!("{:?}", c.start),
                    &format!(
                        "a vertical crack off the x sides, 0 < x < {} m (a crack on a side is \
                         half a crack; only periodic sides join there)",
                        self.width
                    ),
                );
            }
            xs.extend([c.start[0], c.end[0]]);
            zs.extend([c.start[1], c.end[1]]);
        }
        for (i, s) in self.sources.iter().enumerate() {
            match s.kind {
                SourceKind::Traction { x0, x1, .. } => xs.extend([x0, x1]),
                SourceKind::PlaneWave {
                    incidence,
                    angle,
                    z,
                } => {
                    self.check_plane_wave(file, i, incidence, angle, z)?;
                    zs.push(z);
                }
                SourceKind::Force { .. } => {}
            }
        }
        Ok((xs, zs))
    }

    /// Check the problem and build its plan: the mesh, masses, the stable time step,
    /// the cracks' split nodes, the loads and the receivers. Errors name `file` and the
    /// scenario key (`model.width`, `crack.0.end`, ...); the mesh and the recorded series
    /// are checked against the memory budget ([`crate::budget`]) before they are
    /// allocated.
    pub fn plan(&self, file: &str) -> Result<Plan<L>> {
        let bad = |field: &str, value: String, allowed: &str| {
            Err(Error::invalid(file, field, value, allowed))
        };
        let (xs, zs) = self.validate(file)?;
        let depth = self.depth();
        let n = self.order;
        let comps = if self.wave == WaveType::Sh { 1.0 } else { 2.0 };
        // the physical rectangle's edges, and the absorbing layers' bands outside it
        let (lt, lb, ls) = self.pml_thicknesses();
        let h = self.element_size;
        let x_in = mesh::edges(self.width, &xs, h);
        let z_in = mesh::edges(depth, &zs, h);
        let (nx_in, nz_in) = (x_in.len() - 1, z_in.len() - 1);
        let (x_edges, bx) = pml::extend(x_in, ls, ls, h);
        let (z_edges, bz) = pml::extend(z_in, lt, lb, h);
        let periodic = self.sides == Side::Periodic;
        let mut lines = Vec::new();
        for (i, c) in self.cracks.iter().enumerate() {
            let line = if c.full_width {
                let iz = mesh::edge_index(&z_edges, c.start[1]) * n;
                CrackLine {
                    horizontal: true,
                    line: iz,
                    tips: (0, 0),
                    open: (false, false),
                    full_width: true,
                }
            } else if c.start[1] == c.end[1] {
                let iz = mesh::edge_index(&z_edges, c.start[1]) * n;
                let a = mesh::edge_index(&x_edges, c.start[0]) * n;
                let b = mesh::edge_index(&x_edges, c.end[0]) * n;
                CrackLine {
                    horizontal: true,
                    line: iz,
                    tips: (a, b),
                    open: (self.mouth(c.start, true), self.mouth(c.end, true)),
                    full_width: false,
                }
            } else {
                let ix = mesh::edge_index(&x_edges, c.start[0]) * n;
                let a = mesh::edge_index(&z_edges, c.start[1]) * n;
                let b = mesh::edge_index(&z_edges, c.end[1]) * n;
                CrackLine {
                    horizontal: false,
                    line: ix,
                    tips: (a, b),
                    open: (self.mouth(c.start, false), self.mouth(c.end, false)),
                    full_width: false,
                }
            };
            if c.full_width && !periodic {
                return bad(
                    &format!("crack.{i}.full_width"),
                    "true".into(),
                    "periodic x sides",
                );
            }
            lines.push(line);
        }
        let mesh = Mesh::new(n, x_edges, z_edges, periodic, &lines).map_err(|e| match e {
            Error::Invalid {
                field,
                value,
                allowed,
                ..
            } => Error::invalid(file, field, value, allowed),
            e => e,
        })?;
        crate::interrupt::check()?; // (Ctrl-C between the stages of a large plan)
        let (nex, nez) = mesh.element_dims();
        let layer_of = |zmid: f64| {
            self.layers
                .iter()
                .position(|l| zmid < l.bottom)
                .unwrap_or(self.layers.len() - 1)
        };
        let mut elements = Vec::with_capacity(nex * nez);
        for ez in 0..nez {
            let (z0, z1) = (mesh.z_edges[ez], mesh.z_edges[ez + 1]);
            let mat = self.layers[layer_of(0.5 * (z0 + z1))].material;
            for ex in 0..nex {
                elements.push(ElementData {
                    hx: mesh.x_edges[ex + 1] - mesh.x_edges[ex],
                    hz: z1 - z0,
                    lambda: mat.lambda(),
                    mu: mat.mu(),
                });
            }
        }
        let m = n + 1;
        let w = &mesh.gll.weights;
        let mut mass = vec![0.0; mesh.n_nodes];
        for ez in 0..nez {
            let rho = self.layers[layer_of(0.5 * (mesh.z_edges[ez] + mesh.z_edges[ez + 1]))]
                .material
                .density;
            for ex in 0..nex {
                let e = ez * nex + ex;
                let el = &elements[e];
                for b in 0..m {
                    for a in 0..m {
                        mass[mesh.conn[e * m * m + b * m + a] as usize] +=
                            rho * w[a] * w[b] * el.hx * el.hz / 4.0;
                    }
                }
            }
        }
        let (nxn, nzn) = mesh.grid_dims();
        // (0 for the grid nodes no element takes: the periodic images of column 0)
        let mut inv_mass: Vec<f64> = mass
            .iter()
            .map(|&m| if m > 0.0 { 1.0 / m } else { 0.0 })
            .collect();
        // (rigid sides, and the absorbing layers' outer edges)
        let fixed = |s: Side| s == Side::Rigid || (s == Side::Absorbing && pml::RIGID_EDGE);
        let mut fix = |ix: usize, iz: usize| inv_mass[mesh.grid_node(ix, iz)] = 0.0;
        for ix in 0..nxn {
            if fixed(self.top) {
                fix(ix, 0);
            }
            if fixed(self.bottom) {
                fix(ix, nzn - 1);
            }
        }
        if fixed(self.sides) {
            for iz in 0..nzn {
                fix(0, iz);
                fix(nxn - 1, iz);
            }
        }
        let components = if self.wave == WaveType::Sh { 1 } else { 2 };
        let stiffness = Stiffness {
            order: n,
            dims: (nex, nez),
            elements,
            conn: mesh.conn.clone(),
            weights: mesh.gll.weights.clone(),
            derivative: mesh.gll.derivative.clone(),
            antiplane: components == 1,
            regular: Vec::new(),
            coefs: Vec::new(),
        };
        let densities: Vec<f64> = (0..nez)
            .flat_map(|ez| {
                let rho = self.layers[layer_of(0.5 * (mesh.z_edges[ez] + mesh.z_edges[ez + 1]))]
                    .material
                    .density;
                std::iter::repeat_n(rho, nex)
            })
            .collect();
        let omega_max = max_frequency(&stiffness, &densities);
        crate::interrupt::check()?;
        let dt = (self.courant * 2.0 / omega_max).min(self.max_time_step);
        // the interior's operator and the absorbing layers' elements
        let c_max = self
            .layers
            .iter()
            .map(|l| l.material.p_speed)
            .fold(0.0, f64::max);
        let profile = |lo: f64, hi: f64, l_lo: f64, l_hi: f64| pml::Profile {
            lo,
            hi,
            l_lo,
            l_hi,
            c: c_max,
            r0: self.pml.reflection,
        };
        let (stiffness, band) = pml::split(
            stiffness,
            (bx, nx_in, bz, nz_in),
            &densities,
            &mesh.x,
            &mesh.z,
            mesh.grid_dims(),
            &profile(0.0, self.width, ls, ls),
            &profile(0.0, depth, lt, lb),
            &mut mass,
        );
        let rows = NodeRows {
            stride: nxn,
            row0: bz * n,
            col0: bx * n,
            len: nx_in * n + 1,
        };
        let rows = (rows, rows.outside(nz_in * n + 1, mesh.n_nodes));
        let steps = (self.duration / dt).ceil();
        // the recorded series: receivers and the cracks' fields
        let crack_points: usize = mesh.splits.iter().map(Vec::len).sum();
        let series = self.receivers.len() as f64 * comps * steps
            + 5.0 * crack_points as f64 * (steps / self.crack_every.max(1) as f64 + 1.0);
        crate::budget::check(
            file,
            "model.duration",
            self.duration,
            series * 8.0,
            &format!(
                "{steps:.3e} time steps of {} receivers and {crack_points} crack nodes",
                self.receivers.len()
            ),
        )?;
        let steps = steps as usize;
        // cracks
        let mut cracks = Vec::new();
        for (ci, c) in self.cracks.iter().enumerate() {
            let line = &lines[ci];
            let (normal, tangent) = if line.horizontal {
                ([0.0, 1.0], [1.0, 0.0])
            } else {
                ([1.0, 0.0], [0.0, 1.0])
            };
            let pairs = &mesh.splits[ci];
            let mut nodes = CrackNodes {
                normal: vec![normal; pairs.len()],
                tangent: vec![tangent; pairs.len()],
                faces: Vec::with_capacity(pairs.len()),
                position: Vec::new(),
                weight: Vec::new(),
                kick: Vec::new(),
                compliance: Vec::new(),
                law: Vec::new(),
                initial_gap: Vec::new(),
                state: Vec::new(),
                gaps: Vec::new(),
                applied: Vec::new(),
                fields: Vec::new(),
                work: 0.0,
                tangential_work: 0.0,
            };
            for &(g, twin) in pairs {
                if inv_mass[g] == 0.0 || inv_mass[twin] == 0.0 {
                    return bad(
                        &format!("crack.{ci}"),
                        "on a rigid side".into(),
                        "a crack away from rigid sides",
                    );
                }
                let (ix, iz) = (g % nxn, g / nxn);
                // boundary weight: the GLL weights of the element edges along the line
                let (k, edges) = if line.horizontal {
                    (ix, &mesh.x_edges)
                } else {
                    (iz, &mesh.z_edges)
                };
                let bw = edge_weight(edges, &mesh.gll.weights, n, k, line.full_width);
                let pos = if line.horizontal {
                    mesh.x[ix] - c.start[0].min(c.end[0])
                } else {
                    mesh.z[iz] - c.start[1].min(c.end[1])
                };
                nodes.faces.push((g, twin));
                nodes.position.push(pos);
                nodes.weight.push(bw);
                nodes
                    .kick
                    .push((dt * bw * inv_mass[g], dt * bw * inv_mass[twin]));
                nodes
                    .compliance
                    .push(dt * dt * bw * (inv_mass[g] + inv_mass[twin]));
                let (law, g0) = match &c.profile {
                    Some(p) => p.at(pos)?,
                    None => (c.law.clone(), 0.0),
                };
                let mut state = PointState::at_rest(&law, Some(&law));
                state.gap = g0;
                nodes.fields.push(crack::PointFields::at_rest(&law, &state));
                nodes.state.push(state);
                nodes.law.push(law);
                nodes.initial_gap.push(g0);
                nodes.gaps.push([[g0, 0.0]; 2]);
                nodes.applied.push([0.0; 2]);
            }
            cracks.push(nodes);
        }
        // loads
        let mut loads = Vec::new();
        let mut signals = Vec::new();
        let mut plane_waves = Vec::new();
        for (si, s) in self.sources.iter().enumerate() {
            signals.push(s.signal.clone());
            match s.kind {
                SourceKind::Force { at, direction } => {
                    let g = mesh.grid_node(nearest(&mesh.x, at[0]), nearest(&mesh.z, at[1]));
                    if components == 1 {
                        loads.push(Load {
                            index: g,
                            weight: 1.0,
                            source: si,
                            delay: 0.0,
                        });
                    } else {
                        for c in 0..2 {
                            if direction[c] != 0.0 {
                                loads.push(Load {
                                    index: 2 * g + c,
                                    weight: direction[c],
                                    source: si,
                                    delay: 0.0,
                                });
                            }
                        }
                    }
                }
                SourceKind::PlaneWave {
                    incidence,
                    angle,
                    z,
                } => {
                    let iz = mesh::edge_index(&mesh.z_edges, z).max(1);
                    let zmid = 0.5 * (mesh.z_edges[iz - 1] + mesh.z_edges[iz]);
                    plane_waves.push(plane_wave::Injection::new(
                        &mesh,
                        &stiffness,
                        (bx, bz),
                        self.layers[layer_of(zmid)].material,
                        incidence,
                        angle,
                        z,
                        &s.signal,
                        si,
                        dt,
                        self.duration,
                        file,
                        &format!("source.{si}"),
                    )?);
                }
                SourceKind::Traction {
                    top,
                    x0,
                    x1,
                    normal,
                    delay_per_m,
                } => {
                    let iz = if top { bz * n } else { (bz + nz_in) * n };
                    // a traction t on the top surface (outward normal -z) is sigma_zz = -t_z... the
                    // force on the surface node is B times the traction vector sigma . n_out;
                    // for sigma_zz = s on the top surface: f_z = -s B (pull up for s > 0)
                    let sign = if top { -1.0 } else { 1.0 };
                    for ix in 0..nxn {
                        let x = mesh.x[ix];
                        if x < x0.min(x1) - 1e-12 || x > x0.max(x1) + 1e-12 {
                            continue;
                        }
                        let delay = delay_per_m * (x - x0);
                        // (a crack's mouth: each face takes its own element's share)
                        for (g, bw) in aperture_faces(&mesh, ix, iz, x0.min(x1), x0.max(x1)) {
                            let index = match (components, normal) {
                                (1, _) => g,
                                (_, true) => 2 * g + 1,
                                (_, false) => 2 * g,
                            };
                            loads.push(Load {
                                index,
                                weight: sign * bw,
                                source: si,
                                delay,
                            });
                        }
                    }
                }
            }
        }
        let receiver_nodes = self
            .receivers
            .iter()
            .map(|r| mesh.grid_node(nearest(&mesh.x, r[0]), nearest(&mesh.z, r[1])))
            .collect();
        Ok(Plan {
            mesh,
            stiffness,
            rows,
            inv_mass,
            mass,
            dt,
            steps,
            components,
            cracks,
            loads,
            band,
            signals,
            receiver_nodes,
            stress_probes: Vec::new(),
            crack_every: self.crack_every.max(1),
            plane_waves,
            snapshot_steps: Vec::new(),
        })
    }
}

//! Finite cracks in 2D on any quadrilateral mesh (docs/model.md section 15.13): the mesh is
//! data ([`input::QuadInput`], from the Gmsh reader [`gmsh`] or the structured generator
//! [`input::QuadInput::grid`]) turned into GLL nodes and per-point geometry
//! ([`geometry::Mesh`]); cracks and contact interfaces are named curves split into node
//! pairs with their own normals ([`split`]) and updated by the same split-node boundary
//! object as the rectangle's ([`super::crack::CrackNodes`]: the per-point contact update of
//! `law/`, exact at the new level); the internal forces come from the per-point-metric
//! kernel ([`kernel`]; axis-aligned rectangles on its constant-factor path), assembled by
//! colour; sources are point forces (located and spread by the element's Lagrange basis)
//! and tractions on named curves; receivers are interpolated; sides are free (natural),
//! rigid, absorbing (Lysmer's dashpots, eq. 15.13d) or framed by the rectangle's PML
//! ([`frame`], eq. 15.13i). The time loop is the rectangle's
//! (eqs. 15.2-15.5), its energy audit closing at round-off in a closed domain.
//!
//! A plan is immutable: [`QuadPlan::run`] starts every run from rest with fresh crack
//! states, so running it twice gives the same bits.

mod frame;
pub mod geometry;
pub mod gmsh;
pub mod input;
pub mod kernel;
mod lanes;
pub mod locate;
pub mod periodic;
pub mod raster;
pub mod refine;
pub mod split;
mod stepping;
mod tfsf;

#[cfg(test)]
mod frame_tests;
#[cfg(test)]
mod periodic_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tfsf_tests;

use super::crack::{CrackNodes, PointFields};
use super::plane_wave::{Incidence, Injection};
use super::pml::{Band, Pml};
use super::probe::StressProbe;
use super::{CrackProfile, Elastic, Load, WaveType};
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::contact::PointState;
use crate::law::{NormalPart, TangentialPart};
use geometry::Mesh;
use input::QuadInput;
use kernel::Operator;
use std::sync::Arc;

/// What a named curve of the mesh is, where it is not a crack.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// Traction free (natural; every curve not named otherwise).
    Free,
    /// Fixed: zero displacement.
    Rigid,
    /// Absorbing: Lysmer's dashpots `t = -rho (c_P v_n n + c_S v_t t)` (eq. 15.13d), exact at
    /// normal incidence.
    Absorbing,
    /// Absorbing by a Cartesian PML frame outside the mesh ([`QuadSolid::pml`]; the
    /// rectangle's layers of section 15.7, eq. 15.13i): the curve must be straight, on the
    /// mesh's bounding box.
    Pml,
}

/// A crack or contact interface along a named curve, with its law.
#[derive(Debug, Clone)]
pub struct QuadCrack<L> {
    /// The curve's name.
    pub curve: String,
    /// The law of its points.
    pub law: L,
    /// The static state along its arc length (from the chain's start), or `None`: `law`
    /// everywhere, closed at rest.
    pub profile: Option<Arc<dyn CrackProfile<L>>>,
}

/// Where a source acts.
#[derive(Debug, Clone, PartialEq)]
pub enum QuadSourceKind {
    /// A line force (N/m per unit of the signal) at `at = [x, z]` (m), spread over its
    /// element's nodes by the Lagrange basis, along `direction` (unit; antiplane: y).
    Force {
        /// Position, m.
        at: [f64; 2],
        /// Direction `[x, z]`.
        direction: [f64; 2],
    },
    /// A traction (Pa per unit of the signal) on a named boundary curve: normal (`sigma_nn
    /// = s`, tension positive) or shear (the force `B s (n_z, -n_x)` for the outward
    /// normal n: `sigma_xz = s` on a top or bottom surface, as the rectangle's), each point
    /// delayed by `delay_per_m` (s/m) times its distance from the curve's first end (the
    /// one of smaller x, then z) along the chord to the other (an angled beam).
    Traction {
        /// The curve's name.
        curve: String,
        /// Normal traction (else shear).
        normal: bool,
        /// Linear delay law, s/m.
        delay_per_m: f64,
    },
    /// A plane wave injected across a named curve of element edges that cuts the mesh in
    /// two (total-field/scattered-field, eq. 15.13j: [`tfsf`]), travelling at `angle` (rad
    /// from +z toward +x); the signal is the wave's stress at its front (Pa).
    PlaneWave {
        /// The curve's name.
        curve: String,
        /// P, SV or SH.
        incidence: Incidence,
        /// Angle from +z toward +x, rad.
        angle: f64,
    },
}

/// A source: where, and its time function.
#[derive(Debug, Clone)]
pub struct QuadSource {
    /// Where and how.
    pub kind: QuadSourceKind,
    /// The time function (Pa for a traction, N/m for a force).
    pub signal: Arc<dyn Excitation>,
}

/// A 2D problem on a quadrilateral mesh.
#[derive(Debug, Clone)]
pub struct QuadSolid<L> {
    /// The mesh as generated.
    pub input: Arc<QuadInput>,
    /// GLL order of the elements (2 to 8).
    pub order: usize,
    /// The material of each of the input's material tags.
    pub materials: Vec<Elastic>,
    /// Wave type.
    pub wave: WaveType,
    /// Fraction of the stability limit the time step takes (0 to 1).
    pub courant: f64,
    /// Largest time step, s.
    pub max_time_step: f64,
    /// Named curves that are not free sides.
    pub boundaries: Vec<(String, Boundary)>,
    /// Periodic sides: pairs of named boundary curves, the second the first moved by a
    /// translation, joined node by node ([`periodic`]).
    pub periodic: Vec<(String, String)>,
    /// Cracks and contact interfaces.
    pub cracks: Vec<QuadCrack<L>>,
    /// Sources.
    pub sources: Vec<QuadSource>,
    /// Velocity receivers `[x, z]`, m (interpolated).
    pub receivers: Vec<[f64; 2]>,
    /// Stress receivers `[x, z]`, m (the gradient of the element's basis at the point).
    pub stress_receivers: Vec<[f64; 2]>,
    /// Duration, s.
    pub duration: f64,
    /// Record the crack fields every this many steps.
    pub crack_every: usize,
    /// The PML frame of the [`Boundary::Pml`] curves: thickness (m) and target reflection;
    /// `None`: [`super::pml::DEFAULT_ELEMENTS`] of the mesh's largest element edge thick,
    /// the default reflection.
    pub pml: Option<Pml>,
}

/// An absorbing side's node: its damping `C` (`[c_xx, c_xz, c_zx, c_zz]`, or `[c]` in
/// antiplane runs; kg/(m s)).
#[derive(Debug, Clone, Copy)]
struct Dashpot {
    node: usize,
    c: [f64; 4],
    /// The node's mass (a periodic group's summed mass), kg/m.
    mass: f64,
}

/// The built run.
#[derive(Debug, Clone)]
pub struct QuadPlan<L> {
    /// The mesh (split).
    pub mesh: Mesh,
    op: Operator,
    inv_mass: Vec<f64>,
    mass: Vec<f64>,
    /// Time step, s.
    pub dt: f64,
    /// Steps.
    pub steps: usize,
    /// Components per node.
    pub components: usize,
    /// The cracks at rest (each run starts from a copy).
    cracks: Vec<CrackNodes<L>>,
    /// Each crack's ends, `[x, z]`, m.
    pub crack_ends: Vec<[[f64; 2]; 2]>,
    loads: Vec<Load>,
    signals: Vec<Arc<dyn Excitation>>,
    /// The plane waves' injections at rest (each run starts from a copy).
    plane_waves: Vec<Injection>,
    dashpots: Vec<Dashpot>,
    /// The PML frame's elements and fields at rest (each run starts from a copy; empty
    /// without one).
    band: Band,
    /// Nodes of the state: the mesh's, then the frame's.
    pub nodes: usize,
    /// Layers of elements across the PML frame (0: none).
    pub frame_layers: usize,
    /// The periodic sides' joined nodes: each mirror with its primary.
    mirrors: periodic::Mirrors,
    /// Each receiver's nodes and weights.
    pub receivers: Vec<Vec<(usize, f64)>>,
    /// The stress receivers.
    pub stress_probes: Vec<StressProbe>,
    crack_every: usize,
    /// Steps after which the whole velocity field is kept ([`QuadPlan::capture_at`]).
    snapshot_steps: Vec<usize>,
}

/// Bytes per GLL node of a quadrilateral-mesh run (state, masses, positions, the
/// element map and per-point geometry held by the mesh and by the kernel's batches, what
/// the build holds meanwhile), at GLL order `n` with `components` per node.
pub fn bytes_per_node(n: usize, components: usize) -> f64 {
    let per_point = ((n + 1) * (n + 1)) as f64 / (n * n) as f64;
    3.0 * 8.0 * components as f64 + 16.0 + 16.0 + per_point * 2.0 * (4.0 + 40.0) + per_point * 16.0
}

impl<L: NormalPart + TangentialPart + Clone> QuadSolid<L> {
    /// About how many GLL nodes the mesh has (`elements n^2`).
    pub fn node_estimate(&self) -> f64 {
        self.input.quads.len() as f64 * (self.order * self.order) as f64
    }

    /// The mesh built with its cracks split (in the order of `cracks`).
    fn split_mesh(&self, file: &str) -> Result<(Mesh, Vec<split::SplitCrack>)> {
        let _ = file;
        let mut mesh = Mesh::build(&self.input, self.order)?;
        crate::interrupt::check()?;
        let mut done = vec![false; mesh.n_nodes()];
        let mut splits = Vec::new();
        for (i, c) in self.cracks.iter().enumerate() {
            splits.push(split::split(
                &mut mesh,
                &c.curve,
                &format!("crack.{i}.group"),
                &mut done,
            )?);
        }
        Ok((mesh, splits))
    }

    /// The PML frame of the [`Boundary::Pml`] curves of the split `mesh` (none without
    /// one), refused where a curve meets a periodic side (`mirrors`).
    fn frame(
        &self,
        mesh: &Mesh,
        mirrors: &periodic::Mirrors,
        file: &str,
    ) -> Result<Option<frame::Frame>> {
        let curves: Vec<&str> = self
            .boundaries
            .iter()
            .filter(|(_, k)| *k == Boundary::Pml)
            .map(|(n, _)| n.as_str())
            .collect();
        if curves.is_empty() {
            return Ok(None);
        }
        let h = self.input.side_lengths().fold(0.0, f64::max);
        let pml = self
            .pml
            .unwrap_or_else(|| Pml::elements(super::pml::DEFAULT_ELEMENTS, h));
        let fr = frame::build(
            mesh,
            &curves,
            pml,
            h,
            &self.materials,
            self.wave == WaveType::Sh,
            file,
        )?;
        let inner = &fr.band.nodes[..fr.band.n_inner];
        let joined = |g: usize| inner.contains(&(g as u32));
        if let Some(&(q, _)) = mirrors.iter().find(|(q, r)| joined(*q) || joined(*r)) {
            let p = mesh.position[q];
            return Err(Error::invalid(
                file,
                "boundary",
                format!(
                    "a pml side meeting a periodic side at x = {:.4e} m, z = {:.4e} m",
                    p[0], p[1]
                ),
                "pml sides apart from periodic ones",
            ));
        }
        Ok(Some(fr))
    }

    /// Check the geometry without building the operator: the mesh, its cracks, the sides'
    /// and apertures' curves on the boundary, the PML frame, every force and receiver
    /// inside the mesh (what a scenario checks when it is loaded; [`QuadSolid::plan`] does
    /// it again); the split mesh, for the caller's own checks.
    pub fn check(&self, file: &str) -> Result<Mesh> {
        let (mesh, splits) = self.split_mesh(file)?;
        let mirrors = periodic::join(&mesh, &self.periodic, file)?;
        for (ci, sp) in splits.into_iter().enumerate() {
            periodic::fold_crack(sp, &mirrors, &format!("crack.{ci}"), file)?;
        }
        self.frame(&mesh, &mirrors, file)?;
        for (name, _) in &self.boundaries {
            on_boundary(&mesh, name, &format!("boundary `{name}`"), file)?;
        }
        for (i, s) in self.sources.iter().enumerate() {
            match &s.kind {
                QuadSourceKind::Traction { curve, .. } => {
                    on_boundary(&mesh, curve, &format!("source.{i}.group"), file)?;
                }
                QuadSourceKind::PlaneWave { curve, angle, .. } => {
                    let key = format!("source.{i}");
                    tfsf::line(&mesh, curve, *angle, &self.materials, &mirrors, file, &key)?;
                }
                QuadSourceKind::Force { at, .. } => {
                    if mesh.locate(*at).is_none() {
                        return Err(Error::invalid(
                            file,
                            format!("source.{i}.at"),
                            format!("{at:?}"),
                            "a point inside the mesh",
                        ));
                    }
                }
            }
        }
        for (i, r) in self.receivers.iter().enumerate() {
            if mesh.locate(*r).is_none() {
                return Err(Error::invalid(
                    file,
                    format!("receiver.{i}.at"),
                    format!("{r:?}"),
                    "a point inside the mesh",
                ));
            }
        }
        for (i, r) in self.stress_receivers.iter().enumerate() {
            if mesh.locate(*r).is_none() {
                return Err(Error::invalid(
                    file,
                    format!("stress_receivers.{i}"),
                    format!("{r:?}"),
                    "a point inside the mesh",
                ));
            }
        }
        Ok(mesh)
    }

    /// Check the problem and build its plan (errors name `file` and the key or entity).
    pub fn plan(&self, file: &str) -> Result<QuadPlan<L>> {
        let bad = |field: &str, value: String, allowed: &str| {
            Err(Error::invalid(file, field, value, allowed))
        };
        if !super::ORDERS.contains(&self.order) {
            return bad("mesh.order", self.order.to_string(), "2 to 8");
        }
        if !(self.courant > 0.0 && self.courant < 1.0) {
            return bad("model.courant", self.courant.to_string(), "in (0, 1)");
        }
        if !(self.duration > 0.0 && self.duration.is_finite()) {
            return bad("model.duration", self.duration.to_string(), "> 0 s, finite");
        }
        if !(self.max_time_step > 0.0) {
            return bad(
                "model.max_time_step",
                self.max_time_step.to_string(),
                "> 0 s",
            );
        }
        for (i, m) in self.materials.iter().enumerate() {
            if !(m.density > 0.0 && m.s_speed > 0.0 && m.p_speed > m.s_speed * 2f64.sqrt()) {
                return bad(
                    &format!("material.{i}"),
                    format!("rho {}, c_P {}, c_S {}", m.density, m.p_speed, m.s_speed),
                    "rho > 0, c_S > 0 and c_P > sqrt(2) c_S",
                );
            }
        }
        if self.materials.len() < self.input.materials.len() {
            return bad(
                "material",
                format!("{} materials", self.materials.len()),
                &format!(
                    "one for each physical surface: {}",
                    self.input.materials.join(", ")
                ),
            );
        }
        let components = if self.wave == WaveType::Sh { 1 } else { 2 };
        let bytes = self.node_estimate() * bytes_per_node(self.order, components);
        crate::budget::check_or(
            file,
            "mesh.file",
            &self.input.source,
            bytes,
            &format!("a mesh of about {:.3e} nodes", self.node_estimate()),
            "a coarser mesh or a lower `mesh.order`",
        )?;
        let (mut mesh, splits) = self.split_mesh(file)?;
        mesh.colour();
        let mm = mesh.per_element();
        let lame: Vec<[f64; 2]> = mesh
            .material
            .iter()
            .map(|&t| {
                let m = self.materials[t as usize];
                [m.lambda(), m.mu()]
            })
            .collect();
        let mut mass = vec![0.0; mesh.n_nodes()];
        for e in 0..mesh.n_elements() {
            let rho = self.materials[mesh.material[e] as usize].density;
            for l in 0..mm {
                mass[mesh.conn[e * mm + l] as usize] += rho * mesh.metric[e * mm + l][4];
            }
        }
        let mut inv_mass: Vec<f64> = mass
            .iter()
            .map(|&m| if m > 0.0 { 1.0 / m } else { 0.0 })
            .collect();
        let mut dashpots: Vec<Dashpot> = Vec::new();
        for (name, kind) in &self.boundaries {
            let field = format!("boundary `{name}`");
            let set = on_boundary(&mesh, name, &field, file)?;
            for (_, on) in &set.segments {
                let (e, s) = on[0];
                for k in 0..=mesh.gll.order {
                    let (g, normal, bw) = mesh.side_point(e as usize, s, k);
                    match kind {
                        Boundary::Free | Boundary::Pml => {}
                        Boundary::Rigid => inv_mass[g] = 0.0,
                        Boundary::Absorbing => {
                            let mat = self.materials[mesh.material[e as usize] as usize];
                            let (zp, zs) = (mat.density * mat.p_speed, mat.density * mat.s_speed);
                            let [nx, nz] = normal;
                            let c = if components == 1 {
                                [bw * zs, 0.0, 0.0, 0.0]
                            } else {
                                let (tx, tz) = (nz, -nx);
                                [
                                    bw * (zp * nx * nx + zs * tx * tx),
                                    bw * (zp * nx * nz + zs * tx * tz),
                                    bw * (zp * nz * nx + zs * tz * tx),
                                    bw * (zp * nz * nz + zs * tz * tz),
                                ]
                            };
                            match dashpots.iter_mut().find(|d| d.node == g) {
                                Some(d) => (0..4).for_each(|i| d.c[i] += c[i]),
                                None => dashpots.push(Dashpot {
                                    node: g,
                                    c,
                                    mass: 0.0,
                                }),
                            }
                        }
                    }
                }
            }
        }
        let op = Operator::new(&mesh, lame, components == 1);
        // (the nodes apart: the joined system's largest eigenvalue is not above theirs)
        let lambda = op.max_eigenvalue(&inv_mass);
        crate::interrupt::check()?;
        let mirrors = periodic::join(&mesh, &self.periodic, file)?;
        let step_mass = join_masses(&mirrors, &mass, &mut inv_mass, &mut dashpots);
        dashpots.retain(|d| inv_mass[d.node] > 0.0);
        for d in &mut dashpots {
            d.mass = step_mass[d.node];
        }
        // the PML frame: its nodes after the mesh's, its mass added to the side's nodes
        let mut omega = lambda.sqrt();
        let (band, frame_layers) = match self.frame(&mesh, &mirrors, file)? {
            None => (Band::default(), 0),
            Some(fr) => {
                let n_mesh = mesh.n_nodes();
                inv_mass.resize(n_mesh + fr.added, 0.0);
                for (g, &mb) in fr.mass.iter().enumerate() {
                    if g >= n_mesh {
                        inv_mass[g] = 1.0 / mb;
                    } else if mb > 0.0 && inv_mass[g] > 0.0 {
                        inv_mass[g] = 1.0 / (step_mass[g] + mb);
                    }
                }
                for &g in &fr.fixed {
                    inv_mass[g] = 0.0;
                }
                for d in &mut dashpots {
                    d.mass += fr.mass[d.node];
                }
                omega = omega.max(fr.omega);
                (fr.band, fr.layers)
            }
        };
        let dt = (self.courant * 2.0 / omega).min(self.max_time_step);
        let steps = (self.duration / dt).ceil();
        let crack_points: usize = splits.iter().map(|s| s.faces.len()).sum();
        let stress_components = if components == 1 { 2.0 } else { 3.0 };
        let series = self.receivers.len() as f64 * components as f64 * steps
            + self.stress_receivers.len() as f64 * stress_components * steps
            + 6.0 * crack_points as f64 * (steps / self.crack_every.max(1) as f64 + 1.0);
        crate::budget::check(
            file,
            "model.duration",
            self.duration,
            series * 8.0,
            &format!(
                "{steps:.3e} time steps of {} receivers and {crack_points} crack nodes",
                self.receivers.len() + self.stress_receivers.len()
            ),
        )?;
        let steps = steps as usize;
        // the cracks' boundary objects
        let mut cracks = Vec::new();
        let splits: Vec<split::SplitCrack> = splits
            .into_iter()
            .enumerate()
            .map(|(ci, sp)| periodic::fold_crack(sp, &mirrors, &format!("crack.{ci}"), file))
            .collect::<Result<_>>()?;
        for (ci, (c, sp)) in self.cracks.iter().zip(&splits).enumerate() {
            let k = sp.faces.len();
            let mut nodes = CrackNodes {
                normal: sp.normal.clone(),
                tangent: sp.tangent.clone(),
                faces: sp.faces.clone(),
                position: sp.position.clone(),
                weight: sp.weight.clone(),
                kick: Vec::with_capacity(k),
                compliance: Vec::with_capacity(k),
                law: Vec::with_capacity(k),
                initial_gap: Vec::with_capacity(k),
                state: Vec::with_capacity(k),
                gaps: Vec::with_capacity(k),
                applied: Vec::with_capacity(k),
                fields: Vec::with_capacity(k),
                work: 0.0,
                tangential_work: 0.0,
            };
            for (j, &(g, twin)) in sp.faces.iter().enumerate() {
                if inv_mass[g] == 0.0 || inv_mass[twin] == 0.0 {
                    return bad(
                        &format!("crack.{ci}"),
                        "on a rigid side".into(),
                        "a crack away from rigid sides",
                    );
                }
                let bw = sp.weight[j];
                nodes
                    .kick
                    .push((dt * bw * inv_mass[g], dt * bw * inv_mass[twin]));
                nodes
                    .compliance
                    .push(dt * dt * bw * (inv_mass[g] + inv_mass[twin]));
                let (law, g0) = match &c.profile {
                    Some(p) => p.at(sp.position[j])?,
                    None => (c.law.clone(), 0.0),
                };
                let mut state = PointState::at_rest(&law, Some(&law));
                state.gap = g0;
                nodes.fields.push(PointFields::at_rest(&law, &state));
                nodes.state.push(state);
                nodes.law.push(law);
                nodes.initial_gap.push(g0);
                nodes.gaps.push([[g0, 0.0]; 2]);
                nodes.applied.push([0.0; 2]);
            }
            cracks.push(nodes);
        }
        // sources
        let mut loads = Vec::new();
        let mut signals = Vec::new();
        let mut plane_waves = Vec::new();
        for (si, s) in self.sources.iter().enumerate() {
            signals.push(s.signal.clone());
            match &s.kind {
                QuadSourceKind::PlaneWave {
                    curve,
                    incidence,
                    angle,
                } => {
                    let key = format!("source.{si}");
                    let line =
                        tfsf::line(&mesh, curve, *angle, &self.materials, &mirrors, file, &key)?;
                    plane_waves.push(tfsf::injection(
                        &mesh,
                        &op,
                        &line,
                        *incidence,
                        *angle,
                        &s.signal,
                        si,
                        (dt, self.duration),
                        file,
                        &key,
                    )?);
                }
                QuadSourceKind::Force { at, direction } => {
                    let Some(loc) = mesh.locate(*at) else {
                        return bad(
                            &format!("source.{si}.at"),
                            format!("{at:?}"),
                            "a point inside the mesh",
                        );
                    };
                    for (g, w) in loc.weights {
                        for c in 0..components {
                            let dir = if components == 1 { 1.0 } else { direction[c] };
                            if dir != 0.0 {
                                loads.push(Load {
                                    index: components * g + c,
                                    weight: w * dir,
                                    source: si,
                                    delay: 0.0,
                                });
                            }
                        }
                    }
                }
                QuadSourceKind::Traction {
                    curve,
                    normal,
                    delay_per_m,
                } => {
                    let field = format!("source.{si}.group");
                    let set = on_boundary(&mesh, curve, &field, file)?;
                    let (p0, dir) = chord(&mesh, set);
                    for (_, on) in &set.segments {
                        let (e, sd) = on[0];
                        for k in 0..=mesh.gll.order {
                            let (g, [nx, nz], bw) = mesh.side_point(e as usize, sd, k);
                            let p = mesh.position[g];
                            let delay =
                                delay_per_m * ((p[0] - p0[0]) * dir[0] + (p[1] - p0[1]) * dir[1]);
                            let f = if components == 1 {
                                [1.0, 0.0]
                            } else if *normal {
                                [nx, nz]
                            } else {
                                [nz, -nx]
                            };
                            for c in 0..components {
                                if f[c] != 0.0 {
                                    loads.push(Load {
                                        index: components * g + c,
                                        weight: bw * f[c],
                                        source: si,
                                        delay,
                                    });
                                }
                            }
                        }
                    }
                }
            }
        }
        let mut receivers = Vec::new();
        for (i, r) in self.receivers.iter().enumerate() {
            let Some(loc) = mesh.locate(*r) else {
                return bad(
                    &format!("receiver.{i}.at"),
                    format!("{r:?}"),
                    "a point inside the mesh",
                );
            };
            receivers.push(loc.weights);
        }
        let lame = |tag: u16| {
            let m = &self.materials[tag as usize];
            (m.lambda(), m.mu())
        };
        let mut stress_probes = Vec::with_capacity(self.stress_receivers.len());
        for (i, r) in self.stress_receivers.iter().enumerate() {
            let Some(probe) = mesh.stress_probe(*r, lame) else {
                return bad(
                    &format!("stress_receivers.{i}"),
                    format!("{r:?}"),
                    "a point inside the mesh",
                );
            };
            stress_probes.push(probe);
        }
        let nodes = inv_mass.len();
        Ok(QuadPlan {
            crack_ends: splits.iter().map(|s| s.ends).collect(),
            mesh,
            op,
            inv_mass,
            mass,
            dt,
            steps,
            components,
            cracks,
            loads,
            signals,
            plane_waves,
            dashpots,
            nodes,
            band,
            frame_layers,
            mirrors,
            receivers,
            stress_probes,
            crack_every: self.crack_every.max(1),
            snapshot_steps: Vec::new(),
        })
    }
}

/// Join the periodic groups' masses: each primary moves with its group's summed mass (held
/// fixed where any node of the group is rigid), each mirror not at all (it takes the
/// primary's motion after the step); a mirror's dashpot acts on its primary. Returns the
/// mass each node moves with, kg/m.
fn join_masses(
    mirrors: &periodic::Mirrors,
    mass: &[f64],
    inv_mass: &mut [f64],
    dashpots: &mut Vec<Dashpot>,
) -> Vec<f64> {
    let mut step = mass.to_vec();
    for &(q, p) in mirrors {
        step[p] += mass[q];
        step[q] = 0.0;
    }
    let mut fixed: Vec<usize> = Vec::new();
    for &(q, p) in mirrors {
        if inv_mass[q] == 0.0 || inv_mass[p] == 0.0 {
            fixed.push(p);
        }
    }
    for &(q, p) in mirrors {
        inv_mass[q] = 0.0;
        inv_mass[p] = if step[p] > 0.0 { 1.0 / step[p] } else { 0.0 };
    }
    for p in fixed {
        inv_mass[p] = 0.0;
    }
    // the mirrors' dashpots moved onto their primaries, in the mirrors' order
    let primary: std::collections::HashMap<usize, usize> = mirrors.iter().copied().collect();
    let mut moved: Vec<Dashpot> = Vec::with_capacity(dashpots.len());
    for d in dashpots.drain(..) {
        let node = primary.get(&d.node).copied().unwrap_or(d.node);
        match moved.iter_mut().find(|m| m.node == node) {
            Some(m) => (0..4).for_each(|i| m.c[i] += d.c[i]),
            None => moved.push(Dashpot { node, ..d }),
        }
    }
    *dashpots = moved;
    step
}

/// The curve `name` of `mesh` (its key `field`), refused unless every segment is on the
/// mesh's boundary (a side or an aperture).
fn on_boundary<'m>(
    mesh: &'m Mesh,
    name: &str,
    field: &str,
    file: &str,
) -> Result<&'m geometry::EdgeSet> {
    let set = mesh.set(name, field)?;
    if let Some((ends, _)) = set.segments.iter().find(|(_, on)| on.len() != 1) {
        let p = mesh.position[ends[0] as usize];
        return Err(Error::invalid(
            file,
            field,
            format!(
                "`{name}` inside the mesh at x = {:.4e} m, z = {:.4e} m",
                p[0], p[1]
            ),
            "a curve on the mesh's boundary (a side or an aperture)",
        ));
    }
    Ok(set)
}

/// A curve's first end (smaller x, then z, of its chain's ends; any node of a closed
/// curve) and the unit chord to its other end (`[0, 0]` for a closed one).
fn chord(mesh: &Mesh, set: &geometry::EdgeSet) -> ([f64; 2], [f64; 2]) {
    match periodic::ends(mesh, set).as_slice() {
        [a, b, ..] => {
            let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
            let l = dx.hypot(dz);
            (*a, [dx / l, dz / l])
        }
        _ => (
            set.segments
                .first()
                .map_or([0.0; 2], |s| mesh.position[s.0[0] as usize]),
            [0.0; 2],
        ),
    }
}

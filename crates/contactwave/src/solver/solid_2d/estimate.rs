//! What a 2D run will need, before anything is built: the mesh's size and the memory it
//! takes (checked against the budget by [`Solid2d::validate`]), and the whole run's memory
//! ([`Solid2d::memory_estimate`]: the mesh, the time step the plan will take and the
//! recorded series), so that a caller that hands the run to another machine (a Dask worker)
//! can check it against that machine's memory first.

use super::kernel::{max_frequency, ElementData, Stiffness};
use super::{mesh, pml, Solid2d, WaveType};
use crate::error::{Error, Result};
use crate::law::{NormalPart, TangentialPart};
use crate::numeric::gll::Gll;

/// The memory a 2D run needs, bytes, by part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemoryEstimate {
    /// Nodes of the mesh.
    pub nodes: f64,
    /// Time steps of the run.
    pub steps: f64,
    /// The longest stable step times `courant` (s): the step the run takes unless
    /// `max_time_step` is shorter.
    pub stable_time_step: f64,
    /// The mesh, its operator and the stepping state (u, v, f and the masses per node; the
    /// map and data per element; the absorbing layers' fields), bytes.
    pub mesh: f64,
    /// The recorded series (receivers, the cracks' fields, the time axis), their analysis
    /// and their files (`receivers.csv`, `crack.csv`), bytes.
    pub series: f64,
}

impl MemoryEstimate {
    /// Everything, bytes.
    pub fn total(&self) -> f64 {
        self.mesh + self.series
    }
}

impl<L: NormalPart + TangentialPart + Clone> Solid2d<L> {
    /// Nodes of the mesh and the bytes of the mesh and its stepping state, from the number
    /// of lines the element edges must follow along x and z (each may add one element).
    pub(super) fn mesh_bytes(&self, x_lines: usize, z_lines: usize) -> (f64, f64) {
        let n = self.order;
        let (lt, lb, ls) = self.pml_thicknesses();
        let count = |len: f64, lines: usize| (len / self.element_size).ceil() + lines as f64 + 1.0;
        let (ex, ez) = (count(self.width, x_lines), count(self.depth(), z_lines));
        // the absorbing layers' elements (each holds its stresses, forces and damping)
        let bands = |l: f64| if l > 0.0 { count(l, 0) } else { 0.0 };
        let (bx, bz) = (2.0 * bands(ls), bands(lt) + bands(lb));
        let band = (ex + bx) * (ez + bz) - ex * ez;
        let (ex, ez) = (ex + bx, ez + bz);
        let nodes = (ex * n as f64 + 1.0) * (ez * n as f64 + 1.0);
        let comps = if self.wave == WaveType::Sh { 1.0 } else { 2.0 };
        let bytes = nodes * (3.0 * comps + 2.0) * 8.0
            + ex * ez * ((n + 1) * (n + 1) * 4 + 32) as f64
            + band * ((n + 1) * (n + 1) * 14 * 8) as f64;
        (nodes, bytes)
    }

    /// The key to name when a mesh of `nodes` is too large, its value and what to do:
    /// `model.pml_thickness` where the absorbing layers hold more nodes than the rectangle
    /// itself (a thickness in mm given in m), else `model.element_size`.
    pub fn mesh_key(&self, nodes: f64) -> (&'static str, f64, &'static str) {
        let per = |len: f64| (len / self.element_size).ceil() * self.order as f64 + 1.0;
        let inner = per(self.width) * per(self.depth());
        if nodes > 2.0 * inner {
            (
                "model.pml_thickness",
                self.pml.thickness,
                "lower `model.pml_thickness` (the absorbing layers hold most of the mesh; \
                 the default is 4 elements)",
            )
        } else {
            (
                "model.element_size",
                self.element_size,
                "raise `model.element_size` (larger elements: fewer nodes; by default the \
                 size that resolves `model.harmonic` f0), or check the units of `model.width` \
                 and the layers' `thickness` (m)",
            )
        }
    }

    /// The memory the run needs, bytes, without building the mesh: the problem is checked
    /// as [`Solid2d::validate`] does (errors name `file` and the key), the element edges are
    /// laid out (two short vectors), and the time step is the plan's, from the eigenvalue
    /// bound of each distinct element (sizes equal to 1e-9 relative are taken as one).
    /// Steps and crack nodes are those of the plan (within one of each); the result is an
    /// estimate of what the run holds at once (not counting snapshots, checked on their
    /// own).
    ///
    /// ```
    /// use contactwave::model;
    /// use contactwave::scenario::solid_2d::Solid2dScenario;
    /// let t = model::from_toml_str(r#"
    ///     [model]
    ///     kind = "solid_2d"
    ///     width = 10e-3           # m
    ///     duration = 2e-6         # s
    ///     [[layer]]
    ///     thickness = 4e-3
    ///     material = "aluminium"
    ///     [[crack]]
    ///     start = [4e-3, 2e-3]
    ///     end = [6e-3, 2e-3]
    ///     [[source]]
    ///     x0 = 3e-3
    ///     x1 = 7e-3
    ///     signal = { frequency = 2e6, cycles = 3, amplitude = 1e6 }
    ///     [[receiver]]
    ///     name = "top"
    ///     at = [5e-3, 0.0]
    /// "#, "small.toml").unwrap();
    /// let m = t.base().unwrap();
    /// let s = m.as_any().downcast_ref::<Solid2dScenario>().unwrap();
    /// let e = s.problem.memory_estimate("small.toml").unwrap();
    /// let plan = s.problem.plan("small.toml").unwrap();
    /// // the estimate's nodes and steps are the plan's (the node count is a bound: one
    /// // element more for every mesh line, a large share with few large elements)
    /// assert!(e.nodes >= plan.mesh.n_nodes as f64 && e.nodes < 2.0 * plan.mesh.n_nodes as f64);
    /// assert!((e.steps - plan.steps as f64).abs() <= 1.0);
    /// assert!(e.total() > 0.0);
    /// ```
    pub fn memory_estimate(&self, file: &str) -> Result<MemoryEstimate> {
        let (xs, zs) = self.lines(file)?;
        let (nodes, mesh_bytes) = self.mesh_bytes(xs.len(), zs.len());
        let n = self.order;
        let (lt, lb, ls) = self.pml_thicknesses();
        let h = self.element_size;
        let (x_edges, _) = pml::extend(mesh::edges(self.width, &xs, h), ls, ls, h);
        let (z_edges, _) = pml::extend(mesh::edges(self.depth(), &zs, h), lt, lb, h);
        let distinct = |edges: &[f64]| {
            let mut d: Vec<f64> = edges.windows(2).map(|w| w[1] - w[0]).collect();
            d.sort_by(f64::total_cmp);
            d.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
            d
        };
        let (hxs, hzs) = (distinct(&x_edges), distinct(&z_edges));
        // one element of each distinct size and material: the plan's bound
        let gll = Gll::new(n).ok_or_else(|| {
            Error::invalid(file, "model.order", n.to_string(), "2 to 8 (a GLL rule)")
        })?;
        let mut elements = Vec::new();
        let mut densities = Vec::new();
        for l in &self.layers {
            let m = l.material;
            for &hx in &hxs {
                for &hz in &hzs {
                    elements.push(ElementData {
                        hx,
                        hz,
                        lambda: m.lambda(),
                        mu: m.mu(),
                    });
                    densities.push(m.density);
                }
            }
        }
        let one = Stiffness {
            order: n,
            dims: (elements.len(), 1),
            elements,
            conn: Vec::new(),
            weights: gll.weights.clone(),
            derivative: gll.derivative.clone(),
            antiplane: self.wave == WaveType::Sh,
            regular: Vec::new(),
            coefs: Vec::new(),
        };
        let omega_max = max_frequency(&one, &densities);
        let stable_time_step = self.courant * 2.0 / omega_max;
        let dt = stable_time_step.min(self.max_time_step);
        let steps = (self.duration / dt).ceil();
        // the nodes along each crack (its split pairs)
        let along = |a: f64, b: f64, edges: &[f64]| {
            let (lo, hi) = (a.min(b), a.max(b));
            let e = edges
                .windows(2)
                .filter(|w| w[0] >= lo - 1e-12 && w[1] <= hi + 1e-12)
                .count();
            (e * n + 1) as f64
        };
        let crack_points: f64 = self
            .cracks
            .iter()
            .map(|c| {
                if c.full_width {
                    (x_edges.len().saturating_sub(1) * n) as f64
                } else if c.start[1] == c.end[1] {
                    along(c.start[0], c.end[0], &x_edges)
                } else {
                    along(c.start[1], c.end[1], &z_edges)
                }
            })
            .sum();
        let comps = if self.wave == WaveType::Sh { 1.0 } else { 2.0 };
        let records = steps / self.crack_every.max(1) as f64 + 1.0;
        // each receiver's trace, its gated copy and the analysis' padded transforms (four
        // series in all); the cracks' five fields and state per record; the time axis
        let series = 8.0
            * (4.0 * self.receivers.len() as f64 * comps * steps
                + 6.0 * crack_points * records
                + steps)
            // and the files, rendered whole before the first is written: receivers.csv
            // (about 24 bytes a value) and crack.csv (about 130 bytes a point and record)
            + 24.0 * (self.receivers.len() as f64 * comps + 1.0) * steps
            + 130.0 * crack_points * records;
        Ok(MemoryEstimate {
            nodes,
            steps,
            stable_time_step,
            mesh: mesh_bytes,
            series,
        })
    }
}

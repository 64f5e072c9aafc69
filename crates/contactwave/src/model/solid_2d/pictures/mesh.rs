//! Pictures of a run on a mesh: the snapshots over the mesh's box (pixels outside the
//! specimen drawn grey), its outline and curved cracks drawn, the transducers on their
//! curves, and the frames at the GLL nodes for ParaView (`snapshots/frame_NNNN.vtu`, the
//! GLL sub-cells).

use super::{Geometry, Snapshots2d};
use crate::error::Result;
use crate::scenario::solid_2d::Solid2dScenario;
use crate::solver::solid_2d::quad::{raster, QuadPlan, QuadSourceKind};
use crate::solver::solid_2d::snapshot::Capture;
use crate::solver::solid_2d::Solid2dOutput;

/// A mesh run's frames at its nodes, for ParaView.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeFrames {
    /// Node positions `[x, z]`, m (split twins after the others).
    pub points: Vec<[f64; 2]>,
    /// The GLL sub-cells (four node indices each).
    pub cells: Vec<[u32; 4]>,
    /// Velocity components per node (2: `vx, vz`; 1: `vy`).
    pub components: usize,
    /// The frames, frame-major, each node-major with its components together, m/s.
    pub frames: Vec<f64>,
}

/// Bytes of a `.vtu` frame per field value held (the node's coordinates, its velocity
/// vector and the drawn value in base64 of float64, the cells' connectivity, offsets and
/// types): an upper bound for the budget.
const VTU_BYTES_PER_VALUE: f64 = 120.0;

impl Solid2dScenario {
    /// Before a run on a mesh: check the snapshots' memory against the budget and have
    /// `plan` keep the fields at their steps.
    pub(crate) fn prepare_mesh_snapshots<L>(&self, plan: &mut QuadPlan<L>) -> Result<()> {
        let len = plan.components * plan.mesh.n_nodes();
        let (lo, hi) = raster::bounds(&plan.mesh);
        let size = [hi[0] - lo[0], hi[1] - lo[1]];
        let vtu = VTU_BYTES_PER_VALUE + 8.0;
        if let Some(steps) = self.snapshot_steps(plan.dt, plan.steps, len, size, vtu)? {
            plan.capture_at(steps);
        }
        Ok(())
    }

    /// After a run on a mesh: the kept fields on the pixel grid over its box (NaN outside
    /// the specimen), and at its nodes where the VTK files are asked for.
    pub(crate) fn mesh_snapshots_of<L>(
        &self,
        plan: &QuadPlan<L>,
        capture: Capture,
    ) -> Option<Snapshots2d> {
        let s = self.snapshots.as_ref()?;
        let (lo, hi) = raster::bounds(&plan.mesh);
        let c = plan.components;
        let r = raster::raster(&plan.mesh, c, &capture, s.field, s.pixels, lo, hi);
        let nodes = s.vtk.then(|| NodeFrames {
            points: plan.mesh.position.clone(),
            cells: raster::sub_cells(&plan.mesh),
            components: c,
            frames: capture.frames,
        });
        Some(Self::snapshots_2d(s, capture.times, r, nodes))
    }
}

impl Geometry {
    /// What the pictures of a run on a mesh draw: its box, outline, cracks from end to
    /// end through their points, receivers and the transducers' curves.
    pub(crate) fn of_mesh<L>(
        s: &Solid2dScenario,
        plan: &QuadPlan<L>,
        output: &Solid2dOutput,
    ) -> Geometry {
        let (lo, hi) = raster::bounds(&plan.mesh);
        let mut g = Geometry::of(s);
        g.origin = lo;
        g.width = hi[0] - lo[0];
        g.depth = hi[1] - lo[1];
        g.layer_boundaries.clear();
        g.outline = raster::outline(&plan.mesh);
        g.cracks = plan
            .crack_ends
            .iter()
            .map(|[a, b]| [a[0], a[1], b[0], b[1]])
            .collect();
        g.crack_paths = (plan.crack_ends.iter().zip(&output.cracks))
            .map(|(ends, rec)| {
                let mut path = Vec::with_capacity(rec.points.len() + 2);
                let far = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) > 0.0;
                // the welded tips are no crack points: the path starts and ends at them
                if rec.points.first().is_none_or(|&p| far(p, ends[0])) {
                    path.push(ends[0]);
                }
                path.extend_from_slice(&rec.points);
                if rec.points.last().is_none_or(|&p| far(p, ends[1])) {
                    path.push(ends[1]);
                }
                path
            })
            .collect();
        g.sources = (s.mesh.iter().flat_map(|q| &q.sources))
            .filter_map(|src| match &src.kind {
                QuadSourceKind::Traction { curve, .. } => plan.mesh.set(curve, "").ok(),
                QuadSourceKind::Force { .. } | QuadSourceKind::PlaneWave { .. } => None,
            })
            .flat_map(|set| &set.segments)
            .map(|(ends, _)| {
                let (a, b) = (
                    plan.mesh.position[ends[0] as usize],
                    plan.mesh.position[ends[1] as usize],
                );
                [a[0], a[1], b[0], b[1]]
            })
            .collect();
        g
    }
}

/// The `.vtu` text of frame `k` of `n` (VTK's y is up: `y = -z`): the drawn value `field`
/// and, in plane strain, the velocity vector `(vx, -vz, 0)`.
#[cfg(feature = "plot")]
pub(super) fn vtu(file: &str, s: &Snapshots2d, n: &NodeFrames, k: usize) -> Result<String> {
    let c = n.components;
    let len = c * n.points.len();
    let v = &n.frames[k * len..(k + 1) * len];
    let points: Vec<[f64; 2]> = n.points.iter().map(|p| [p[0], -p[1]]).collect();
    let drawn: Vec<f64> = v
        .chunks_exact(c)
        .map(|q| match s.field.as_str() {
            "magnitude" => q.iter().map(|a| a * a).sum::<f64>().sqrt(),
            "vz" => q[c - 1],
            _ => q[0],
        })
        .collect();
    let mut fields = vec![(s.field.as_str(), 1, drawn)];
    if c == 2 {
        let vec3 = v.chunks_exact(2).flat_map(|q| [q[0], -q[1], 0.0]).collect();
        fields.push(("velocity", 3, vec3));
    }
    crate::render::vtk::unstructured(file, &points, &n.cells, fields)
}

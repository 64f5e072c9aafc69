//! Stress receivers: the stress at a node from the displacements of the element it
//! belongs to (the element to its lower right where it is shared; on a crack, the face of
//! that element), by the element's GLL derivative along the node's row and column
//! (docs/model.md section 15.1); on a mesh, at the point itself by the gradient of its
//! element's basis (`Mesh::stress_probe`). Plain data built once; evaluating allocates nothing.

use super::mesh::Mesh;
use super::{Elastic, Layer, Plan};
use crate::error::{Error, Result};

/// One stress receiver.
#[derive(Debug, Clone)]
pub struct StressProbe {
    /// The taps of d/dx at the receiver, `(node, 1/m)`: on the rectangle the nodes of the
    /// element's row through the receiver's node, on a mesh every node of its element.
    pub row: Vec<(usize, f64)>,
    /// The taps of d/dz at the receiver (the element's column through it on the
    /// rectangle).
    pub column: Vec<(usize, f64)>,
    /// Lame's lambda and mu of the element, Pa.
    pub lame: (f64, f64),
}

impl StressProbe {
    /// The probe of grid node `(ix, iz)` of `mesh` (order `n`), in the material that
    /// `material(ez)` gives for element row `ez`.
    pub fn new(mesh: &Mesh, ix: usize, iz: usize, material: impl Fn(usize) -> Elastic) -> Self {
        let n = mesh.gll.order;
        let (nex, nez) = mesh.element_dims();
        let ex = (ix / n).min(nex - 1);
        let ez = (iz / n).min(nez - 1);
        let (a, b) = (ix - ex * n, iz - ez * n);
        let e = ez * nex + ex;
        let m = n + 1;
        let node = |i: usize, j: usize| mesh.conn[e * m * m + j * m + i] as usize;
        let d = &mesh.gll.derivative;
        let hx = mesh.x_edges[ex + 1] - mesh.x_edges[ex];
        let hz = mesh.z_edges[ez + 1] - mesh.z_edges[ez];
        let mat = material(ez);
        StressProbe {
            row: (0..m)
                .map(|k| (node(k, b), 2.0 / hx * d[a * m + k]))
                .collect(),
            column: (0..m)
                .map(|k| (node(a, k), 2.0 / hz * d[b * m + k]))
                .collect(),
            lame: (mat.lambda(), mat.mu()),
        }
    }

    /// Stress components of the displacements `u` (m; `components` per node): plane
    /// strain `[sigma_xx, sigma_zz, sigma_xz]`, antiplane `[sigma_yx, sigma_yz]`, Pa, into
    /// `out`.
    pub fn stress(&self, u: &[f64], components: usize, out: &mut [f64]) {
        let (lambda, mu) = self.lame;
        let grad = |taps: &[(usize, f64)], c: usize| -> f64 {
            taps.iter().map(|&(g, w)| w * u[components * g + c]).sum()
        };
        if components == 1 {
            out[0] = mu * grad(&self.row, 0);
            out[1] = mu * grad(&self.column, 0);
        } else {
            let (uxx, uzx) = (grad(&self.row, 0), grad(&self.row, 1));
            let (uxz, uzz) = (grad(&self.column, 0), grad(&self.column, 1));
            out[0] = (lambda + 2.0 * mu) * uxx + lambda * uzz;
            out[1] = lambda * uxx + (lambda + 2.0 * mu) * uzz;
            out[2] = mu * (uxz + uzx);
        }
    }
}

impl<L> Plan<L> {
    /// Add stress receivers at `points` (`[x, z]`, m; the nearest node, in the element to
    /// its lower right), recorded at the receivers' times as the mean of the two levels
    /// around each (Pa); their series' memory is checked against the budget first.
    pub fn add_stress_receivers(
        &mut self,
        points: &[[f64; 2]],
        layers: &[Layer],
        file: &str,
    ) -> Result<()> {
        let sc = if self.components == 1 { 2 } else { 3 };
        crate::budget::check(
            file,
            "receiver",
            points.len() as f64,
            (points.len() * sc) as f64 * self.steps as f64 * 8.0,
            &format!(
                "{} time steps of {} stress receivers",
                self.steps,
                points.len()
            ),
        )?;
        let Some(last) = layers.last() else {
            return Err(Error::invalid(
                file,
                "layer",
                "none",
                "at least one [[layer]]",
            ));
        };
        let mesh = &self.mesh;
        let layer_of = |ez: usize| {
            let zmid = 0.5 * (mesh.z_edges[ez] + mesh.z_edges[ez + 1]);
            layers
                .iter()
                .find(|l| zmid < l.bottom)
                .unwrap_or(last)
                .material
        };
        for p in points {
            let (ix, iz) = (nearest(&mesh.x, p[0]), nearest(&mesh.z, p[1]));
            self.stress_probes
                .push(StressProbe::new(mesh, ix, iz, layer_of));
        }
        Ok(())
    }
}

impl<L> Plan<L> {
    /// The position of the grid node nearest `p = [x, z]` (m), where a receiver or a point
    /// source asked for at `p` records or loads, m.
    pub fn node_position(&self, p: [f64; 2]) -> [f64; 2] {
        let m = &self.mesh;
        [m.x[nearest(&m.x, p[0])], m.z[nearest(&m.z, p[1])]]
    }
}

/// Index of the value of `values` nearest `v`.
pub(super) fn nearest(values: &[f64], v: f64) -> usize {
    let mut best = 0;
    for (i, x) in values.iter().enumerate() {
        if (x - v).abs() < (values[best] - v).abs() {
            best = i;
        }
    }
    best
}

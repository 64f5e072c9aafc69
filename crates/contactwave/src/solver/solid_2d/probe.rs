//! Stress receivers: the stress at a node from the displacements of the element it
//! belongs to (the element to its lower right where it is shared; on a crack, the face of
//! that element), by the element's GLL derivative along the node's row and column
//! (docs/model.md section 15.1). Plain data built once; evaluating allocates nothing.

use super::mesh::Mesh;
use super::Elastic;

/// One stress receiver.
#[derive(Debug, Clone)]
pub struct StressProbe {
    /// The nodes of the element's row through the receiver's node with the weights of
    /// d/dx there, `(node, 1/m)`.
    pub row: Vec<(usize, f64)>,
    /// The nodes of the element's column through it with the weights of d/dz.
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

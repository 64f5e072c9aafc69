//! Points located in their element and interpolated by its Lagrange basis (docs/model.md
//! section 15.13): the element whose map reaches the point (Newton on the GLL interpolant
//! of its node positions, exact for elements of order up to the GLL order), and the
//! weights `l_a(xi) l_b(eta)` of its nodes: a receiver's velocity is the weighted sum, a
//! point force is spread over the nodes by the same weights (its work is the same).

use super::geometry::Mesh;

/// The Lagrange basis of the GLL `points` at `s` and its derivative.
fn basis(points: &[f64], s: f64, l: &mut [f64], dl: &mut [f64]) {
    let m = points.len();
    for j in 0..m {
        let mut v = 1.0;
        let mut d = 0.0;
        for k in 0..m {
            if k == j {
                continue;
            }
            let den = points[j] - points[k];
            // product rule: d/ds prod = sum over k of (1/den) prod of the others
            let mut others = 1.0 / den;
            for q in 0..m {
                if q != j && q != k {
                    others *= (s - points[q]) / (points[j] - points[q]);
                }
            }
            d += others;
            v *= (s - points[k]) / den;
        }
        l[j] = v;
        dl[j] = d;
    }
}

/// A located point: its element, reference coordinates and node weights.
#[derive(Debug, Clone)]
pub struct Located {
    /// Element.
    pub element: usize,
    /// `(xi, eta)` in [-1, 1]^2.
    pub reference: [f64; 2],
    /// `(node, weight)` of the element's nodes (weights summing to 1).
    pub weights: Vec<(usize, f64)>,
}

impl Mesh {
    /// The element containing `p = [x, z]` (m) and its interpolation weights, or `None`
    /// outside the mesh (beyond a millionth of the element's size). The first element in
    /// the mesh's order that contains it (a point on a crack: the element that comes
    /// first, either face).
    pub fn locate(&self, p: [f64; 2]) -> Option<Located> {
        let n = self.gll.order;
        let m = n + 1;
        let mm = m * m;
        let pts = &self.gll.points;
        let (mut lx, mut dlx, mut lz, mut dlz) =
            (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        for e in 0..self.n_elements() {
            let nodes = &self.conn[e * mm..(e + 1) * mm];
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for &g in nodes {
                let q = self.position[g as usize];
                for c in 0..2 {
                    lo[c] = lo[c].min(q[c]);
                    hi[c] = hi[c].max(q[c]);
                }
            }
            let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
            // (a pre-filter only: a curved edge bulges past its nodes' box)
            let tol = 0.05 * size;
            if p[0] < lo[0] - tol || p[0] > hi[0] + tol || p[1] < lo[1] - tol || p[1] > hi[1] + tol
            {
                continue;
            }
            // Newton from the centre
            let mut r = [0.0f64, 0.0];
            let mut ok = false;
            for _ in 0..50 {
                basis(pts, r[0], &mut lx, &mut dlx);
                basis(pts, r[1], &mut lz, &mut dlz);
                let (mut x, mut j) = ([0.0; 2], [0.0; 4]);
                for b in 0..m {
                    for a in 0..m {
                        let q = self.position[nodes[b * m + a] as usize];
                        let (f, fa, fb) = (lx[a] * lz[b], dlx[a] * lz[b], lx[a] * dlz[b]);
                        for c in 0..2 {
                            x[c] += f * q[c];
                            j[2 * c] += fa * q[c];
                            j[2 * c + 1] += fb * q[c];
                        }
                    }
                }
                let (rx, rz) = (p[0] - x[0], p[1] - x[1]);
                let det = j[0] * j[3] - j[1] * j[2];
                if det == 0.0 || !det.is_finite() {
                    break;
                }
                let dxi = (j[3] * rx - j[1] * rz) / det;
                let deta = (-j[2] * rx + j[0] * rz) / det;
                r[0] = (r[0] + dxi).clamp(-1.5, 1.5);
                r[1] = (r[1] + deta).clamp(-1.5, 1.5);
                if rx.hypot(rz) <= 1e-12 * size {
                    ok = true;
                    break;
                }
            }
            let inside = 1.0 + 1e-6;
            if !ok || r[0].abs() > inside || r[1].abs() > inside {
                continue;
            }
            let r = [r[0].clamp(-1.0, 1.0), r[1].clamp(-1.0, 1.0)];
            basis(pts, r[0], &mut lx, &mut dlx);
            basis(pts, r[1], &mut lz, &mut dlz);
            let mut weights = Vec::with_capacity(mm);
            for b in 0..m {
                for a in 0..m {
                    let w = lx[a] * lz[b];
                    if w != 0.0 {
                        weights.push((nodes[b * m + a] as usize, w));
                    }
                }
            }
            return Some(Located {
                element: e,
                reference: r,
                weights,
            });
        }
        None
    }
}

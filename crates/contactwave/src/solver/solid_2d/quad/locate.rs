//! Points located in their element and interpolated by its Lagrange basis (docs/model.md
//! section 15.13): the element whose map reaches the point (Newton on the GLL interpolant
//! of its node positions, exact for elements of order up to the GLL order), and the
//! weights `l_a(xi) l_b(eta)` of its nodes: a receiver's velocity is the weighted sum, a
//! point force is spread over the nodes by the same weights (its work is the same).

use super::geometry::Mesh;
use crate::solver::solid_2d::probe::StressProbe;

/// The Lagrange basis of the GLL `points` at `s` and its derivative.
pub(super) fn basis(points: &[f64], s: f64, l: &mut [f64], dl: &mut [f64]) {
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
        let mut s = Scratch::new(self.gll.order + 1);
        (0..self.n_elements()).find_map(|e| self.located_in(e, p, &mut s))
    }

    /// [`Mesh::locate`] in element `e` only.
    fn located_in(&self, e: usize, p: [f64; 2], s: &mut Scratch) -> Option<Located> {
        let r = self.reference_in(e, p, s)?;
        let m = self.gll.order + 1;
        let mm = m * m;
        let nodes = &self.conn[e * mm..(e + 1) * mm];
        let pts = &self.gll.points;
        basis(pts, r[0], &mut s.lx, &mut s.dlx);
        basis(pts, r[1], &mut s.lz, &mut s.dlz);
        let mut weights = Vec::with_capacity(mm);
        for b in 0..m {
            for a in 0..m {
                let w = s.lx[a] * s.lz[b];
                if w != 0.0 {
                    weights.push((nodes[b * m + a] as usize, w));
                }
            }
        }
        Some(Located {
            element: e,
            reference: r,
            weights,
        })
    }

    /// A stress receiver at `p = [x, z]` (m) in the element [`Mesh::locate`] finds, of
    /// Lame constants `lame(material tag)` (Pa), or `None` outside the mesh: the taps of
    /// d/dx and d/dz of every node of the element at the point, the gradient of
    /// `l_a(xi) l_b(eta)` by the inverse of the map's Jacobian there (the map the GLL
    /// interpolant of the element's node positions, as in [`Mesh::locate`]).
    pub fn stress_probe(
        &self,
        p: [f64; 2],
        lame: impl Fn(u16) -> (f64, f64),
    ) -> Option<StressProbe> {
        let loc = self.locate(p)?;
        let e = loc.element;
        let m = self.gll.order + 1;
        let mm = m * m;
        let mut s = Scratch::new(m);
        let pts = &self.gll.points;
        basis(pts, loc.reference[0], &mut s.lx, &mut s.dlx);
        basis(pts, loc.reference[1], &mut s.lz, &mut s.dlz);
        let nodes = &self.conn[e * mm..(e + 1) * mm];
        // the Jacobian of the map at the point
        let (mut x_xi, mut x_eta, mut z_xi, mut z_eta) = (0.0, 0.0, 0.0, 0.0);
        for b in 0..m {
            for a in 0..m {
                let q = self.position[nodes[b * m + a] as usize];
                let (d_xi, d_eta) = (s.dlx[a] * s.lz[b], s.lx[a] * s.dlz[b]);
                x_xi += d_xi * q[0];
                z_xi += d_xi * q[1];
                x_eta += d_eta * q[0];
                z_eta += d_eta * q[1];
            }
        }
        let j = x_xi * z_eta - x_eta * z_xi;
        let (xi_x, xi_z, eta_x, eta_z) = (z_eta / j, -x_eta / j, -z_xi / j, x_xi / j);
        let mut row = Vec::with_capacity(mm);
        let mut column = Vec::with_capacity(mm);
        for b in 0..m {
            for a in 0..m {
                let g = nodes[b * m + a] as usize;
                let (d_xi, d_eta) = (s.dlx[a] * s.lz[b], s.lx[a] * s.dlz[b]);
                row.push((g, xi_x * d_xi + eta_x * d_eta));
                column.push((g, xi_z * d_xi + eta_z * d_eta));
            }
        }
        Some(StressProbe {
            row,
            column,
            lame: lame(self.material[e]),
        })
    }

    /// The node box of element `e`, `([x, z] lowest, [x, z] highest)`, m.
    fn element_box(&self, e: usize) -> ([f64; 2], [f64; 2]) {
        let mm = self.per_element();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &g in &self.conn[e * mm..(e + 1) * mm] {
            let q = self.position[g as usize];
            for c in 0..2 {
                lo[c] = lo[c].min(q[c]);
                hi[c] = hi[c].max(q[c]);
            }
        }
        (lo, hi)
    }

    /// The reference coordinates `(xi, eta)` of `p` in element `e` (clamped onto
    /// [-1, 1]^2), or `None` where the element does not reach it: Newton from the centre on
    /// the GLL interpolant of its node positions.
    fn reference_in(&self, e: usize, p: [f64; 2], s: &mut Scratch) -> Option<[f64; 2]> {
        let m = self.gll.order + 1;
        let mm = m * m;
        let pts = &self.gll.points;
        let nodes = &self.conn[e * mm..(e + 1) * mm];
        let (lo, hi) = self.element_box(e);
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        // (a pre-filter only: a curved edge bulges past its nodes' box)
        let tol = 0.05 * size;
        if p[0] < lo[0] - tol || p[0] > hi[0] + tol || p[1] < lo[1] - tol || p[1] > hi[1] + tol {
            return None;
        }
        let mut r = [0.0f64, 0.0];
        let mut ok = false;
        for _ in 0..50 {
            basis(pts, r[0], &mut s.lx, &mut s.dlx);
            basis(pts, r[1], &mut s.lz, &mut s.dlz);
            let (mut x, mut j) = ([0.0; 2], [0.0; 4]);
            for b in 0..m {
                for a in 0..m {
                    let q = self.position[nodes[b * m + a] as usize];
                    let (f, fa, fb) = (s.lx[a] * s.lz[b], s.dlx[a] * s.lz[b], s.lx[a] * s.dlz[b]);
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
            return None;
        }
        Some([r[0].clamp(-1.0, 1.0), r[1].clamp(-1.0, 1.0)])
    }

    /// A bucket grid of the elements' boxes for locating many points.
    pub fn finder(&self) -> Finder {
        let ne = self.n_elements();
        let boxes: Vec<_> = (0..ne).map(|e| self.element_box(e)).collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut size = 0.0f64;
        for (a, b) in &boxes {
            for c in 0..2 {
                lo[c] = lo[c].min(a[c]);
                hi[c] = hi[c].max(b[c]);
            }
            size = size.max((b[0] - a[0]).max(b[1] - a[1]));
        }
        // about one element a cell, at most 4 million cells
        let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        let cell = size
            .max((span[0] * span[1] / ne.max(1) as f64).sqrt())
            .max((span[0] * span[1] / 4e6).sqrt())
            .max(1e-300);
        let nx = ((span[0] / cell).ceil() as usize).max(1);
        let nz = ((span[1] / cell).ceil() as usize).max(1);
        let mut cells = vec![Vec::new(); nx * nz];
        let index = |v: f64, c: usize, n: usize| {
            (((v - lo[c]) / cell).floor().max(0.0) as usize).min(n - 1)
        };
        for (e, (a, b)) in boxes.iter().enumerate() {
            let tol = 0.05 * (b[0] - a[0]).max(b[1] - a[1]);
            for iz in index(a[1] - tol, 1, nz)..=index(b[1] + tol, 1, nz) {
                for ix in index(a[0] - tol, 0, nx)..=index(b[0] + tol, 0, nx) {
                    cells[iz * nx + ix].push(e as u32);
                }
            }
        }
        Finder {
            lo,
            cell,
            nx,
            nz,
            cells,
            scratch: Scratch::new(self.gll.order + 1),
        }
    }
}

/// Work room of the Newton iteration.
#[derive(Debug, Clone)]
struct Scratch {
    lx: Vec<f64>,
    dlx: Vec<f64>,
    lz: Vec<f64>,
    dlz: Vec<f64>,
}

impl Scratch {
    fn new(m: usize) -> Scratch {
        Scratch {
            lx: vec![0.0; m],
            dlx: vec![0.0; m],
            lz: vec![0.0; m],
            dlz: vec![0.0; m],
        }
    }
}

/// The elements whose boxes meet each cell of a uniform grid ([`Mesh::finder`]).
#[derive(Debug, Clone)]
pub struct Finder {
    lo: [f64; 2],
    cell: f64,
    nx: usize,
    nz: usize,
    cells: Vec<Vec<u32>>,
    scratch: Scratch,
}

impl Finder {
    /// The element of `mesh` holding `p` (m) and its reference coordinates, or `None`
    /// outside: the lowest-numbered element of `p`'s cell that contains it, as
    /// [`Mesh::locate`] finds.
    pub fn reference(&mut self, mesh: &Mesh, p: [f64; 2]) -> Option<(usize, [f64; 2])> {
        let ix = ((p[0] - self.lo[0]) / self.cell).floor();
        let iz = ((p[1] - self.lo[1]) / self.cell).floor();
        if !(ix >= 0.0 && iz >= 0.0 && (ix as usize) < self.nx && (iz as usize) < self.nz) {
            return None;
        }
        let k = iz as usize * self.nx + ix as usize;
        let s = &mut self.scratch;
        self.cells[k]
            .iter()
            .find_map(|&e| Some((e as usize, mesh.reference_in(e as usize, p, s)?)))
    }
}

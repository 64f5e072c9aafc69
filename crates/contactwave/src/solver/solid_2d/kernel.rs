//! The bulk kernel: the internal forces `F = -K u` of the spectral elements (model.md
//! section 9), plane-strain P-SV (`u = (u_x, u_z)`) or antiplane SH (`u_y`), on flat
//! arrays. Per element: gather the displacements of its `(n + 1)^2` GLL nodes, take the
//! gradients with the derivative matrix, the stresses by Hooke's law, and scatter
//! `-integral sigma : grad phi` back (GLL quadrature, rectangular elements: constant
//! Jacobian). The kernel knows nothing of cracks: a split node is just another node.
//!
//! Parallel and deterministic: element rows of one parity share no node (a row's nodes
//! are its own node rows and the twins of the crack lines inside them), so the rows of
//! one parity run in parallel and each node sums its contributions in the same order
//! (even rows, then odd rows; along a row, left to right) for any thread count.

use rayon::prelude::*;

/// What the kernel needs of one element: its size and its Lame constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementData {
    /// Width along x, m.
    pub hx: f64,
    /// Height along z, m.
    pub hz: f64,
    /// Lame's first parameter lambda, Pa.
    pub lambda: f64,
    /// Shear modulus mu, Pa.
    pub mu: f64,
}

/// The operator: element data, the element-to-node map and the GLL rule.
#[derive(Debug, Clone)]
pub struct Stiffness {
    /// Order of the elements.
    pub order: usize,
    /// Elements along x and z.
    pub dims: (usize, usize),
    /// Per element.
    pub elements: Vec<ElementData>,
    /// Element-to-node map (see [`super::mesh::Mesh::conn`]).
    pub conn: Vec<u32>,
    /// GLL weights.
    pub weights: Vec<f64>,
    /// GLL derivative matrix, row-major.
    pub derivative: Vec<f64>,
    /// Antiplane (one component) or plane strain (two, interleaved `[x, z]` per node).
    pub antiplane: bool,
}

/// A pointer that may be shared by the threads of one parity (see the module comment).
#[derive(Clone, Copy)]
struct Shared(*mut f64);
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

impl Shared {
    /// The pointer (a method, so that a closure captures the whole `Shared`).
    fn get(&self) -> *mut f64 {
        self.0
    }
}

impl Stiffness {
    /// `force = -K u` (plus nothing: `force` is overwritten). `u` and `force` hold one
    /// value per node (antiplane) or two interleaved (plane strain), m and N/m.
    pub fn apply(&self, u: &[f64], force: &mut [f64]) {
        force.fill(0.0);
        match self.order {
            2 => self.apply_m::<3>(u, force),
            3 => self.apply_m::<4>(u, force),
            4 => self.apply_m::<5>(u, force),
            5 => self.apply_m::<6>(u, force),
            6 => self.apply_m::<7>(u, force),
            7 => self.apply_m::<8>(u, force),
            8 => self.apply_m::<9>(u, force),
            _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
        }
    }

    /// [`Stiffness::apply`] on the calling thread only (small operators).
    pub fn apply_serial(&self, u: &[f64], force: &mut [f64]) {
        force.fill(0.0);
        let m = self.order + 1;
        for e in 0..self.elements.len() {
            let conn = &self.conn[e * m * m..(e + 1) * m * m];
            macro_rules! go {
                ($M:literal) => {
                    if self.antiplane {
                        self.element_sh::<$M>(&self.elements[e], conn, u, force)
                    } else {
                        self.element_psv::<$M>(&self.elements[e], conn, u, force)
                    }
                };
            }
            match m {
                3 => go!(3),
                4 => go!(4),
                5 => go!(5),
                6 => go!(6),
                7 => go!(7),
                8 => go!(8),
                9 => go!(9),
                _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
            }
        }
    }

    fn apply_m<const M: usize>(&self, u: &[f64], force: &mut [f64]) {
        let (nex, nez) = self.dims;
        let out = Shared(force.as_mut_ptr());
        let len = force.len();
        for parity in 0..2 {
            let rows: Vec<usize> = (parity..nez).step_by(2).collect();
            rows.par_iter().for_each(|&ez| {
                for ex in 0..nex {
                    let e = ez * nex + ex;
                    let conn = &self.conn[e * M * M..(e + 1) * M * M];
                    // SAFETY: rows of one parity write disjoint nodes (module comment);
                    // every index is below `len` (the map is built over the nodes).
                    let out = unsafe { std::slice::from_raw_parts_mut(out.get(), len) };
                    if self.antiplane {
                        self.element_sh::<M>(&self.elements[e], conn, u, out);
                    } else {
                        self.element_psv::<M>(&self.elements[e], conn, u, out);
                    }
                }
            });
        }
    }

    #[inline(always)]
    fn element_psv<const M: usize>(
        &self,
        el: &ElementData,
        conn: &[u32],
        u: &[f64],
        out: &mut [f64],
    ) {
        let d = &self.derivative;
        let w = &self.weights;
        let (mut ux, mut uz) = ([[0.0f64; M]; M], [[0.0f64; M]; M]);
        for b in 0..M {
            for a in 0..M {
                let g = conn[b * M + a] as usize;
                ux[b][a] = u[2 * g];
                uz[b][a] = u[2 * g + 1];
            }
        }
        let (sx, sz) = (2.0 / el.hx, 2.0 / el.hz);
        let l2m = el.lambda + 2.0 * el.mu;
        // stresses weighted for the divergence: the x-flux `(hz/2) w_b w_a sigma_ix` and
        // the z-flux `(hx/2) w_a w_b sigma_iz` of each component i
        let (mut fxx, mut fxz, mut fzx, mut fzz) = (
            [[0.0f64; M]; M],
            [[0.0f64; M]; M],
            [[0.0f64; M]; M],
            [[0.0f64; M]; M],
        );
        for b in 0..M {
            for a in 0..M {
                let (mut dux_dx, mut duz_dx, mut dux_dz, mut duz_dz) = (0.0, 0.0, 0.0, 0.0);
                for k in 0..M {
                    let da = d[a * M + k];
                    let db = d[b * M + k];
                    dux_dx += da * ux[b][k];
                    duz_dx += da * uz[b][k];
                    dux_dz += db * ux[k][a];
                    duz_dz += db * uz[k][a];
                }
                let (exx, ezz) = (dux_dx * sx, duz_dz * sz);
                let exz = dux_dz * sz + duz_dx * sx;
                let sxx = l2m * exx + el.lambda * ezz;
                let szz = el.lambda * exx + l2m * ezz;
                let sxz = el.mu * exz;
                // dA sx = (hx hz / 4) w_a w_b (2 / hx), and alike along z
                let wx = 0.5 * el.hz * w[b] * w[a];
                let wz = 0.5 * el.hx * w[a] * w[b];
                fxx[b][a] = wx * sxx;
                fzx[b][a] = wx * sxz;
                fxz[b][a] = wz * sxz;
                fzz[b][a] = wz * szz;
            }
        }
        for b in 0..M {
            for a in 0..M {
                let (mut gx, mut gz) = (0.0, 0.0);
                for k in 0..M {
                    // sum over the quadrature points of the row (x) and the column (z)
                    let dka = d[k * M + a];
                    let dkb = d[k * M + b];
                    gx += dka * fxx[b][k] + dkb * fxz[k][a];
                    gz += dka * fzx[b][k] + dkb * fzz[k][a];
                }
                let g = conn[b * M + a] as usize;
                out[2 * g] -= gx;
                out[2 * g + 1] -= gz;
            }
        }
    }

    #[inline(always)]
    fn element_sh<const M: usize>(
        &self,
        el: &ElementData,
        conn: &[u32],
        u: &[f64],
        out: &mut [f64],
    ) {
        let d = &self.derivative;
        let w = &self.weights;
        let mut uy = [[0.0f64; M]; M];
        for b in 0..M {
            for a in 0..M {
                uy[b][a] = u[conn[b * M + a] as usize];
            }
        }
        let (sx, sz) = (2.0 / el.hx, 2.0 / el.hz);
        let (mut fx, mut fz) = ([[0.0f64; M]; M], [[0.0f64; M]; M]);
        for b in 0..M {
            for a in 0..M {
                let (mut dx, mut dz) = (0.0, 0.0);
                for k in 0..M {
                    dx += d[a * M + k] * uy[b][k];
                    dz += d[b * M + k] * uy[k][a];
                }
                fx[b][a] = 0.5 * el.hz * w[b] * w[a] * (el.mu * dx * sx);
                fz[b][a] = 0.5 * el.hx * w[a] * w[b] * (el.mu * dz * sz);
            }
        }
        for b in 0..M {
            for a in 0..M {
                let mut g = 0.0;
                for k in 0..M {
                    g += d[k * M + a] * fx[b][k] + d[k * M + b] * fz[k][a];
                }
                out[conn[b * M + a] as usize] -= g;
            }
        }
    }
}

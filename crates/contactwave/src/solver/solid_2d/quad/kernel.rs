//! The internal forces `-K u` on any quadrilateral mesh (docs/model.md eq. 15.13b): per
//! element, the reference derivatives by the GLL derivative matrix, the physical ones by
//! each point's metric (`xi_x, xi_z, eta_x, eta_z`), the stresses of the element's
//! isotropic material, and the weak divergence back to the nodes (SPECFEM2D's loop). An
//! axis-aligned rectangle takes the fast path: its metric is two constants and the cross
//! terms vanish. Elements are assembled tile by tile and colour by colour
//! ([`super::geometry::Mesh::colour`]), the tiles of a colour in parallel: no two of them
//! share a node, so every node sums its elements in one fixed order and the forces are the
//! same bits for any number of threads. The production path runs eight elements at a time
//! ([`super::lanes`]); the element loop here is its reference. Nothing is allocated per
//! call.

use super::geometry::Mesh;
use super::lanes::{portable, Batches, Isa};
#[cfg(target_arch = "x86_64")]
use super::lanes::{tile_avx2, tile_avx512};
use crate::solver::solid_2d::lines::Rule;
use rayon::prelude::*;

/// Largest GLL order the kernel's stack buffers hold.
pub const MAX_ORDER: usize = 8;
const MM: usize = (MAX_ORDER + 1) * (MAX_ORDER + 1);

/// The operator of a mesh: what the kernel reads.
#[derive(Debug, Clone)]
pub struct Operator {
    n: usize,
    /// `d[i (n+1) + j] = l_j'(x_i)`.
    derivative: Vec<f64>,
    weights: Vec<f64>,
    /// Per element: `Some([xi_x, eta_z, J])` for an axis-aligned rectangle.
    rectangle: Vec<Option<[f64; 3]>>,
    /// Lame's lambda and mu of each element, Pa.
    lame: Vec<[f64; 2]>,
    /// The production path's batches ([`super::lanes`]).
    batches: Batches,
    /// One component per node (antiplane `u_y`), else two (`u_x, u_z`).
    pub antiplane: bool,
    /// The instruction set the batches run on.
    isa: Isa,
}

/// A pointer to the force vector shared by the elements of one colour (they write
/// disjoint nodes).
#[derive(Clone, Copy)]
struct Shared(*mut f64);
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

impl Shared {
    /// The pointer (a method, so that a closure captures the whole `Shared`).
    fn ptr(self) -> *mut f64 {
        self.0
    }
}

impl Operator {
    /// The operator of `mesh` with each element's `[lambda, mu]` (Pa).
    pub fn new(mesh: &Mesh, lame: Vec<[f64; 2]>, antiplane: bool) -> Operator {
        Operator::on(Isa::detect(), mesh, lame, antiplane)
    }

    /// [`Operator::new`] on the instruction set `isa` (the CPU must have it).
    pub fn on(isa: Isa, mesh: &Mesh, lame: Vec<[f64; 2]>, antiplane: bool) -> Operator {
        let mm = mesh.per_element();
        let w = &mesh.gll.weights;
        let m = mesh.gll.order + 1;
        let rectangle: Vec<Option<[f64; 3]>> = (0..mesh.n_elements())
            .map(|e| {
                mesh.rectangle[e].then(|| {
                    let [xx, _, _, ez, wj] = mesh.metric[e * mm];
                    [xx, ez, wj / (w[0] * w[0])]
                })
            })
            .collect();
        debug_assert_eq!(m * m, mm);
        let batches = Batches::new(
            isa,
            m,
            &mesh.tiles,
            &mesh.colours,
            &mesh.conn,
            &mesh.metric,
            &rectangle,
            &lame,
        );
        Operator {
            batches,
            n: mesh.gll.order,
            derivative: mesh.gll.derivative.clone(),
            weights: mesh.gll.weights.clone(),
            rectangle,
            lame,
            antiplane,
            isa,
        }
    }

    /// The instruction set the batches run on.
    pub fn isa(&self) -> Isa {
        self.isa
    }

    /// Elements of the mesh.
    pub fn elements(&self) -> usize {
        self.lame.len()
    }

    /// Add the elements' forces `-K u` to `f` (N/m): each colour's tiles in parallel
    /// ([`super::lanes`]), the colours one after another.
    pub fn add_forces(&self, u: &[f64], f: &mut [f64]) {
        match self.n {
            2 => self.forces::<3>(u, f),
            3 => self.forces::<4>(u, f),
            4 => self.forces::<5>(u, f),
            5 => self.forces::<6>(u, f),
            6 => self.forces::<7>(u, f),
            7 => self.forces::<8>(u, f),
            _ => self.forces::<9>(u, f),
        }
    }

    /// [`Operator::add_forces`] at `M` GLL points per edge.
    fn forces<const M: usize>(&self, u: &[f64], f: &mut [f64]) {
        let out = Shared(f.as_mut_ptr());
        let (b, d, w) = (&self.batches, &self.derivative[..], &self.weights[..]);
        let rule = Rule::<M>::new(w, d);
        let tile = |&t: &u32| {
            let range = b.tiles[t as usize].clone();
            let (anti, f) = (self.antiplane, out.ptr());
            // SAFETY: the tiles of a colour share no node, so no two threads write the
            // same entries of `f` (the last colour's tiles run one after another); every
            // index is a node of the mesh; each kernel runs on the CPU that has it.
            unsafe {
                match self.isa {
                    #[cfg(target_arch = "x86_64")]
                    Isa::Avx512 => tile_avx512::<M>(b, range, &rule, anti, u, f),
                    #[cfg(target_arch = "x86_64")]
                    Isa::Avx2 => tile_avx2::<M>(b, range, &rule, anti, u, f),
                    _ => portable::<M>(b, range, d, w, anti, u, f),
                }
            }
        };
        for (c, tiles) in b.colours.iter().enumerate() {
            if c == super::geometry::SERIAL_COLOUR {
                tiles.iter().for_each(tile);
            } else {
                tiles.par_iter().for_each(tile);
            }
        }
    }

    /// Add the elements' forces to `f`, one element after another (no threads, no
    /// batches: the reference the batched path is tested against).
    pub fn add_forces_serial(&self, mesh: &Mesh, u: &[f64], f: &mut [f64]) {
        let out = f.as_mut_ptr();
        for e in 0..self.elements() {
            // SAFETY: as in add_forces, one element at a time.
            unsafe { self.element(mesh, e, u, out) };
        }
    }

    /// Element `e`'s forces `-K_e u` added to `f` at its nodes (one element on this
    /// thread: the probe of an element's operator). `f` is as long as `u`.
    pub fn add_element_forces(&self, mesh: &Mesh, e: usize, u: &[f64], f: &mut [f64]) {
        debug_assert_eq!(u.len(), f.len());
        if e < self.elements() && f.len() == u.len() {
            // SAFETY: f as long as u, written by this thread alone
            unsafe { self.element(mesh, e, u, f.as_mut_ptr()) };
        }
    }

    /// Element `e`'s forces added at its nodes.
    ///
    /// # Safety
    /// `f` points to a vector as long as `u`, and no other thread writes the element's
    /// nodes meanwhile.
    #[inline]
    unsafe fn element(&self, mesh: &Mesh, e: usize, u: &[f64], f: *mut f64) {
        if self.antiplane {
            unsafe { self.element_sh(mesh, e, u, f) }
        } else {
            unsafe { self.element_psv(mesh, e, u, f) }
        }
    }

    /// The P-SV element: `(u_x, u_z)` per node.
    #[inline]
    unsafe fn element_psv(&self, mesh: &Mesh, e: usize, u: &[f64], f: *mut f64) {
        let m = self.n + 1;
        let mm = m * m;
        let d = &self.derivative[..mm];
        let w = &self.weights[..m];
        let conn = &mesh.conn[e * mm..(e + 1) * mm];
        let [lambda, mu] = self.lame[e];
        let l2m = lambda + 2.0 * mu;
        let mut ux = [0.0; MM];
        let mut uz = [0.0; MM];
        for l in 0..mm {
            let g = conn[l] as usize;
            ux[l] = u[2 * g];
            uz[l] = u[2 * g + 1];
        }
        let (mut f1x, mut f1z, mut f2x, mut f2z) = ([0.0; MM], [0.0; MM], [0.0; MM], [0.0; MM]);
        let rect = self.rectangle[e];
        for b in 0..m {
            for a in 0..m {
                let l = b * m + a;
                let (mut xi_x, mut xi_z, mut e_x, mut e_z) = (0.0, 0.0, 0.0, 0.0);
                for k in 0..m {
                    let da = d[a * m + k];
                    let db = d[b * m + k];
                    xi_x += da * ux[b * m + k];
                    xi_z += da * uz[b * m + k];
                    e_x += db * ux[k * m + a];
                    e_z += db * uz[k * m + a];
                }
                if let Some([cx, cz, j]) = rect {
                    let (dux_dx, duz_dz) = (xi_x * cx, e_z * cz);
                    let shear = mu * (e_x * cz + xi_z * cx);
                    let sxx = l2m * dux_dx + lambda * duz_dz;
                    let szz = lambda * dux_dx + l2m * duz_dz;
                    let wj = w[a] * w[b] * j;
                    f1x[l] = wj * sxx * cx;
                    f1z[l] = wj * shear * cx;
                    f2x[l] = wj * shear * cz;
                    f2z[l] = wj * szz * cz;
                } else {
                    let [xx, xz, ex, ez, wj] = mesh.metric[e * mm + l];
                    let dux_dx = xi_x * xx + e_x * ex;
                    let dux_dz = xi_x * xz + e_x * ez;
                    let duz_dx = xi_z * xx + e_z * ex;
                    let duz_dz = xi_z * xz + e_z * ez;
                    let sxx = l2m * dux_dx + lambda * duz_dz;
                    let szz = lambda * dux_dx + l2m * duz_dz;
                    let sxz = mu * (dux_dz + duz_dx);
                    f1x[l] = wj * (sxx * xx + sxz * xz);
                    f1z[l] = wj * (sxz * xx + szz * xz);
                    f2x[l] = wj * (sxx * ex + sxz * ez);
                    f2z[l] = wj * (sxz * ex + szz * ez);
                }
            }
        }
        for b in 0..m {
            for a in 0..m {
                let (mut fx, mut fz) = (0.0, 0.0);
                for k in 0..m {
                    let da = d[k * m + a];
                    let db = d[k * m + b];
                    fx += da * f1x[b * m + k] + db * f2x[k * m + a];
                    fz += da * f1z[b * m + k] + db * f2z[k * m + a];
                }
                let g = conn[b * m + a] as usize;
                // SAFETY: the caller's contract
                unsafe {
                    *f.add(2 * g) -= fx;
                    *f.add(2 * g + 1) -= fz;
                }
            }
        }
    }

    /// The antiplane element: `u_y` per node.
    #[inline]
    unsafe fn element_sh(&self, mesh: &Mesh, e: usize, u: &[f64], f: *mut f64) {
        let m = self.n + 1;
        let mm = m * m;
        let d = &self.derivative[..mm];
        let w = &self.weights[..m];
        let conn = &mesh.conn[e * mm..(e + 1) * mm];
        let mu = self.lame[e][1];
        let mut uy = [0.0; MM];
        for l in 0..mm {
            uy[l] = u[conn[l] as usize];
        }
        let (mut f1, mut f2) = ([0.0; MM], [0.0; MM]);
        let rect = self.rectangle[e];
        for b in 0..m {
            for a in 0..m {
                let l = b * m + a;
                let (mut dxi, mut deta) = (0.0, 0.0);
                for k in 0..m {
                    dxi += d[a * m + k] * uy[b * m + k];
                    deta += d[b * m + k] * uy[k * m + a];
                }
                if let Some([cx, cz, j]) = rect {
                    let wj = w[a] * w[b] * j;
                    f1[l] = wj * mu * dxi * cx * cx;
                    f2[l] = wj * mu * deta * cz * cz;
                } else {
                    let [xx, xz, ex, ez, wj] = mesh.metric[e * mm + l];
                    let syx = mu * (dxi * xx + deta * ex);
                    let syz = mu * (dxi * xz + deta * ez);
                    f1[l] = wj * (syx * xx + syz * xz);
                    f2[l] = wj * (syx * ex + syz * ez);
                }
            }
        }
        for b in 0..m {
            for a in 0..m {
                let mut fy = 0.0;
                for k in 0..m {
                    fy += d[k * m + a] * f1[b * m + k] + d[k * m + b] * f2[k * m + a];
                }
                let g = conn[b * m + a] as usize;
                // SAFETY: the caller's contract
                unsafe { *f.add(g) -= fy };
            }
        }
    }

    /// The largest eigenvalue of `M^-1 K` (1/s^2; `inv_mass` per node, 0 where a node is
    /// fixed) by Lanczos iteration on `M^-1/2 K M^-1/2` (the Ritz value converges from
    /// below; the iteration stops when its residual bound is under 1e-9 of it or after
    /// 400 steps), for the stability limit `dt < 2 / omega_max`.
    pub fn max_eigenvalue(&self, inv_mass: &[f64]) -> f64 {
        let c = if self.antiplane { 1 } else { 2 };
        let len = c * inv_mass.len();
        let s: Vec<f64> = (0..len).map(|i| inv_mass[i / c].sqrt()).collect();
        // a start with every mode in it (deterministic)
        let mut q: Vec<f64> = (0..len)
            .map(|i| {
                s[i] * (1.0 + ((i * 7919) % 13) as f64 * 0.1) * if i % 3 == 0 { -1.0 } else { 1.0 }
            })
            .collect();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let n0 = norm(&q);
        if n0 == 0.0 {
            return 0.0;
        }
        q.iter_mut().for_each(|x| *x /= n0);
        let mut q_prev = vec![0.0; len];
        let mut w = vec![0.0; len];
        let mut tmp = vec![0.0; len];
        let (mut alpha, mut beta) = (Vec::new(), Vec::new());
        let mut theta = 0.0;
        for _ in 0..400 {
            // w = A q = -S f(S q)
            for i in 0..len {
                tmp[i] = s[i] * q[i];
            }
            w.iter_mut().for_each(|x| *x = 0.0);
            self.add_forces(&tmp, &mut w);
            for i in 0..len {
                w[i] *= -s[i];
            }
            let b_prev = beta.last().copied().unwrap_or(0.0);
            let a: f64 = w.iter().zip(&q).map(|(x, y)| x * y).sum();
            for i in 0..len {
                w[i] -= a * q[i] + b_prev * q_prev[i];
            }
            alpha.push(a);
            let b = norm(&w);
            let (t, last) = tridiagonal_max(&alpha, &beta);
            theta = t;
            if b * last.abs() <= 1e-9 * theta || b == 0.0 {
                break;
            }
            beta.push(b);
            std::mem::swap(&mut q_prev, &mut q);
            for i in 0..len {
                q[i] = w[i] / b;
            }
        }
        theta
    }
}

/// The largest eigenvalue of the symmetric tridiagonal matrix (diagonal `a`, off-diagonal
/// `b`, `b.len() == a.len() - 1`) by bisection on its Sturm sequence, and the last
/// component of its unit eigenvector (the Lanczos residual bound's factor).
fn tridiagonal_max(a: &[f64], b: &[f64]) -> (f64, f64) {
    let k = a.len();
    let bound = (0..k)
        .map(|i| {
            a[i].abs()
                + if i > 0 { b[i - 1].abs() } else { 0.0 }
                + if i + 1 < k { b[i].abs() } else { 0.0 }
        })
        .fold(0.0, f64::max);
    // number of eigenvalues below x
    let below = |x: f64| {
        let mut count = 0;
        let mut d = 1.0;
        for i in 0..k {
            let bb = if i > 0 { b[i - 1] * b[i - 1] } else { 0.0 };
            d = a[i] - x - if i > 0 { bb / d } else { 0.0 };
            if d == 0.0 {
                d = -1e-300;
            }
            if d < 0.0 {
                count += 1;
            }
        }
        count
    };
    let (mut lo, mut hi) = (-bound, bound);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if below(mid) >= k {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo <= 1e-15 * hi.abs() {
            break;
        }
    }
    let theta = hi;
    // eigenvector by the recurrence, normalised
    let mut v = vec![0.0; k];
    v[0] = 1.0;
    if k > 1 {
        v[1] = (theta - a[0]) / b[0];
        for i in 1..k - 1 {
            v[i + 1] = ((theta - a[i]) * v[i] - b[i - 1] * v[i - 1]) / b[i];
        }
    }
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (
        theta,
        if n.is_finite() && n > 0.0 {
            v[k - 1] / n
        } else {
            1.0
        },
    )
}

//! Perfectly matched layers (docs/model.md section 15.7): bands of spectral elements added
//! outside the physical rectangle on every absorbing side (corners where two meet), in
//! which the split-field velocity-stress PML of Festa and Vilotte (GJI 161, 2005; as in
//! SEM2DPACK) runs on the same staggered levels as the interior's leapfrog:
//!
//! ```text
//! (d/dt + d_x) sigma^x = C : sym(dv/dx (x) e_x),   (d/dt + d_z) sigma^z = C : sym(dv/dz (x) e_z)
//! (d/dt + d_x) M v^x = F^x(sigma),                 (d/dt + d_z) M v^z = F^z(sigma)
//! sigma = sigma^x + sigma^z,  v = v^x + v^z,  d(s) = d0 (s / L)^2,  d0 = 3 c_P ln(1/R0) / (2 L)
//! ```
//!
//! `F^x` (`F^z`) is the part of the elements' internal force taken by the x (z) derivative
//! of the test functions; each direction's damping also takes [`MULTIAXIAL`] times the
//! other's (a multiaxial PML: the classical one lets a P-SV mode grow in long runs); the
//! layers' outer edges are fixed. The damping terms are taken by the midpoint rule
//! (`y+ = ((1 - a) y- + dt r) / (1 + a)`, `a = d dt / 2`). Without damping the stresses
//! `sigma^{n+1} = sigma^n + dt C grad v^{n+1/2}` are exactly `C grad u^{n+1}`: the band is
//! the interior's scheme continued. The nodes on the inner boundary (`d = 0`) are the
//! interior's own nodes, advanced by the interior's leapfrog with the band's forces added;
//! the work of those forces (less the band's share of their mass) is the flux into the
//! band (`absorbed`). The stresses live at the elements' GLL points (one set per element);
//! the element loops run in parallel with a fixed assembly order (bit-identical for any
//! thread count) and allocate nothing.

use super::kernel::ElementData;
use rayon::prelude::*;

/// Default thickness of the layers, in elements of the largest element size: -48 dB or
/// less at normal incidence at the default resolution (docs/model.md section 15.7).
/// (Named in the messages of `estimate.rs` and `scenario/plausible.rs`: "the default is 4
/// elements".)
pub const DEFAULT_ELEMENTS: f64 = 4.0;
/// Default target reflection `R0` of the damping profile (the continuum's reflection at
/// normal incidence of a wave at c_P).
pub const DEFAULT_REFLECTION: f64 = 1e-3;
/// Power of the damping profile `d(s) = d0 (s / L)^POWER`.
pub const POWER: i32 = 2;
/// The layers' outer edges are fixed (else free).
pub const RIGID_EDGE: bool = true;
/// Ratio of the damping along a layer to the damping across it (multiaxial PML): the
/// classical split PML (0) lets a P-SV mode grow after about 50 crossing times on these
/// meshes (0.01 still in one of three geometries); 0.03 is stable over 200 (the test
/// `layers_are_stable_over_long_runs`) at some cost in oblique reflection (section 15.7).
pub const MULTIAXIAL: f64 = 0.03;
/// Elements of one parallel task of the band's element loops.
const TASK: usize = 16;

/// The absorbing layers of a problem: thickness (m) and target reflection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pml {
    /// Thickness of every layer, m (rounded up to whole elements of at most the
    /// problem's element size).
    pub thickness: f64,
    /// Target reflection `R0` at normal incidence in the continuum, in (0, 1).
    pub reflection: f64,
}

impl Pml {
    /// `elements` elements of size `h` (m) thick, the default target reflection.
    pub fn elements(elements: f64, h: f64) -> Pml {
        Pml {
            thickness: elements * h,
            reflection: DEFAULT_REFLECTION,
        }
    }
}

/// The peak damping `d0 = (POWER + 1) c ln(1/R0) / (2 L)`, 1/s, of a layer of thickness
/// `l` (m) for waves of speed `c` (m/s).
pub fn peak_damping(c: f64, l: f64, r0: f64) -> f64 {
    (POWER as f64 + 1.0) * c * (1.0 / r0).ln() / (2.0 * l)
}

/// The damping profile across the physical rectangle's edges: `d(s)` of the distance `s`
/// into a band below `lo` or above `hi` (m), zero between.
#[derive(Debug, Clone, Copy)]
pub(super) struct Profile {
    pub lo: f64,
    pub hi: f64,
    /// Thickness of the band before `lo` (0: none), m.
    pub l_lo: f64,
    /// Thickness of the band after `hi` (0: none), m.
    pub l_hi: f64,
    pub c: f64,
    pub r0: f64,
}

impl Profile {
    pub fn at(&self, x: f64) -> f64 {
        let d = |s: f64, l: f64| peak_damping(self.c, l, self.r0) * (s / l).powi(POWER);
        if x < self.lo && self.l_lo > 0.0 {
            d(self.lo - x, self.l_lo)
        } else if x > self.hi && self.l_hi > 0.0 {
            d(x - self.hi, self.l_hi)
        } else {
            0.0
        }
    }
}

/// The elements of the absorbing bands and their fields.
#[derive(Debug, Clone, Default)]
pub(super) struct Band {
    /// Points per element side (order + 1).
    pub(super) m: usize,
    pub(super) antiplane: bool,
    /// Per element.
    pub(super) data: Vec<ElementData>,
    /// Per element point: its global node.
    pub(super) conn: Vec<u32>,
    /// Per element point: its band node (index into the per-node arrays).
    pub(super) local: Vec<u32>,
    /// Per element point: `(d_x, d_z)`, 1/s.
    pub(super) damp: Vec<[f64; 2]>,
    /// Per element point: the split stresses (P-SV: `xx, zz, xz` of `sigma^x`, then of
    /// `sigma^z`; SH: `sigma_yx`, `sigma_yz`), Pa.
    stress: Vec<f64>,
    /// Per element point: the x and z parts of its force (P-SV: `F^x_x, F^x_z, F^z_x,
    /// F^z_z`; SH: `F^x, F^z`), N/m.
    part: Vec<f64>,
    /// Per band node: global node; the first `n_inner` are on the inner boundary.
    pub(super) nodes: Vec<u32>,
    pub(super) n_inner: usize,
    /// Per band node: `(d_x, d_z)`, 1/s.
    pub(super) node_damp: Vec<[f64; 2]>,
    /// Per inner node: the band elements' share of its lumped mass, kg/m.
    pub(super) band_mass: Vec<f64>,
    /// Per band node and component: assembled x and z parts of the force, N/m.
    fx: Vec<f64>,
    fz: Vec<f64>,
    /// Per band node and component: split velocities, m/s (pure band nodes only).
    vx: Vec<f64>,
    vz: Vec<f64>,
    /// Per inner node and component: the velocity of the previous half level, m/s.
    v_old: Vec<f64>,
}

impl Band {
    /// The band of `elements` (element data, `(n + 1)^2` global nodes each, the GLL
    /// points' damping), `inner` telling which global nodes the interior's elements also
    /// take, `mass_band` the lumped mass the band's elements give each global node.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        order: usize,
        antiplane: bool,
        data: Vec<ElementData>,
        conn: Vec<u32>,
        damp: Vec<[f64; 2]>,
        inner: &[bool],
        mass_band: &[f64],
        node_damp: impl Fn(usize) -> [f64; 2],
    ) -> Band {
        let m = order + 1;
        let comps = if antiplane { 1 } else { 2 };
        let n_global = inner.len();
        // band nodes: inner ones first, then the pure band nodes, each in global order
        let mut seen = vec![false; n_global];
        for &g in &conn {
            seen[g as usize] = true;
        }
        let mut nodes: Vec<u32> = (0..n_global)
            .filter(|&g| seen[g] && inner[g])
            .map(|g| g as u32)
            .collect();
        let n_inner = nodes.len();
        nodes.extend(
            (0..n_global)
                .filter(|&g| seen[g] && !inner[g])
                .map(|g| g as u32),
        );
        let mut index = vec![u32::MAX; n_global];
        for (i, &g) in nodes.iter().enumerate() {
            index[g as usize] = i as u32;
        }
        let local = conn.iter().map(|&g| index[g as usize]).collect();
        let per_point = if antiplane { 2 } else { 6 };
        let points = conn.len();
        let np = nodes.len();
        Band {
            m,
            antiplane,
            stress: vec![0.0; points * per_point],
            part: vec![0.0; points * 2 * comps],
            node_damp: nodes.iter().map(|&g| node_damp(g as usize)).collect(),
            band_mass: nodes[..n_inner]
                .iter()
                .map(|&g| mass_band[g as usize])
                .collect(),
            fx: vec![0.0; np * comps],
            fz: vec![0.0; np * comps],
            vx: vec![0.0; np * comps],
            vz: vec![0.0; np * comps],
            v_old: vec![0.0; n_inner * comps],
            data,
            conn,
            local,
            damp,
            nodes,
            n_inner,
        }
    }

    fn comps(&self) -> usize {
        if self.antiplane {
            1
        } else {
            2
        }
    }

    /// Whether there is no absorbing layer (no absorbing side).
    #[cfg(feature = "gpu")]
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The band's forces of level n (from its stresses): assembled per band node, added to
    /// `f` at the inner nodes, whose velocities `v` (level n - 1/2) are kept for the flux.
    pub fn forces(&mut self, weights: &[f64], derivative: &[f64], v: &[f64], f: &mut [f64]) {
        if self.data.is_empty() {
            return;
        }
        match self.m {
            3 => self.forces_m::<3>(weights, derivative),
            4 => self.forces_m::<4>(weights, derivative),
            5 => self.forces_m::<5>(weights, derivative),
            6 => self.forces_m::<6>(weights, derivative),
            7 => self.forces_m::<7>(weights, derivative),
            8 => self.forces_m::<8>(weights, derivative),
            9 => self.forces_m::<9>(weights, derivative),
            _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
        }
        // assembly in element order (the same sums for any thread count)
        let c = self.comps();
        self.fx.fill(0.0);
        self.fz.fill(0.0);
        for (p, &i) in self.local.iter().enumerate() {
            let i = i as usize;
            let part = &self.part[p * 2 * c..(p + 1) * 2 * c];
            for k in 0..c {
                self.fx[i * c + k] += part[k];
                self.fz[i * c + k] += part[c + k];
            }
        }
        for (i, &g) in self.nodes[..self.n_inner].iter().enumerate() {
            for k in 0..c {
                let j = g as usize * c + k;
                f[j] += self.fx[i * c + k] + self.fz[i * c + k];
                self.v_old[i * c + k] = v[j];
            }
        }
    }

    fn forces_m<const M: usize>(&mut self, weights: &[f64], derivative: &[f64]) {
        let (w, d) = rule::<M>(weights, derivative);
        let antiplane = self.antiplane;
        let (sp, fp) = if antiplane { (2, 2) } else { (6, 4) };
        let mm = M * M;
        self.part
            .par_chunks_mut(TASK * mm * fp)
            .zip(self.stress.par_chunks(TASK * mm * sp))
            .zip(self.data.par_chunks(TASK))
            .for_each(|((part, stress), data)| {
                for (e, el) in data.iter().enumerate() {
                    let s = &stress[e * mm * sp..(e + 1) * mm * sp];
                    let out = &mut part[e * mm * fp..(e + 1) * mm * fp];
                    let (cx, cz) = (0.5 * el.hz, 0.5 * el.hx);
                    for b in 0..M {
                        for a in 0..M {
                            let q = b * M + a;
                            if antiplane {
                                // F^x = -(hz/2) w_b sum_k w_k D[k][a] s_yx(k, b), F^z alike
                                let (mut gx, mut gz) = (0.0, 0.0);
                                for k in 0..M {
                                    gx += w[k] * d[k][a] * s[(b * M + k) * 2];
                                    gz += w[k] * d[k][b] * s[(k * M + a) * 2 + 1];
                                }
                                out[q * 2] = -cx * w[b] * gx;
                                out[q * 2 + 1] = -cz * w[a] * gz;
                            } else {
                                let (mut xx, mut xz, mut zx, mut zz) = (0.0, 0.0, 0.0, 0.0);
                                for k in 0..M {
                                    let sx = &s[(b * M + k) * 6..(b * M + k) * 6 + 6];
                                    let sz = &s[(k * M + a) * 6..(k * M + a) * 6 + 6];
                                    let (wa, wb) = (w[k] * d[k][a], w[k] * d[k][b]);
                                    // sigma_xx, sigma_xz at (k, b); sigma_xz, sigma_zz at (a, k)
                                    xx += wa * (sx[0] + sx[3]);
                                    xz += wa * (sx[2] + sx[5]);
                                    zx += wb * (sz[2] + sz[5]);
                                    zz += wb * (sz[1] + sz[4]);
                                }
                                out[q * 4] = -cx * w[b] * xx;
                                out[q * 4 + 1] = -cx * w[b] * xz;
                                out[q * 4 + 2] = -cz * w[a] * zx;
                                out[q * 4 + 3] = -cz * w[a] * zz;
                            }
                        }
                    }
                }
            });
    }

    /// After the interior's node update: the pure band nodes' split velocities (their
    /// level n + 1/2 into `v`, the displacement `u` moved along), and the work done on the
    /// band through the inner nodes over the step (returned, J/m).
    pub fn nodes(&mut self, u: &mut [f64], v: &mut [f64], inv_mass: &[f64], dt: f64) -> f64 {
        let c = self.comps();
        let mut work = 0.0;
        // the inner nodes: the band's force F and its mass share m_b; the interior's
        // equation is M_int a = -K u + f + (F - m_b a), whose work over the step is
        // dt (v+ + v-) / 2 . (F - m_b a): the flux into the band is its opposite
        for (i, &g) in self.nodes[..self.n_inner].iter().enumerate() {
            let mb = self.band_mass[i];
            for k in 0..c {
                let j = g as usize * c + k;
                let (vn, vo) = (v[j], self.v_old[i * c + k]);
                let force = self.fx[i * c + k] + self.fz[i * c + k];
                work -= 0.5 * dt * (vn + vo) * force - 0.5 * mb * (vn * vn - vo * vo);
            }
        }
        for i in self.n_inner..self.nodes.len() {
            let g = self.nodes[i] as usize;
            let im = inv_mass[g];
            let [dx, dz] = self.node_damp[i];
            let (ax, az) = (0.5 * dt * dx, 0.5 * dt * dz);
            for k in 0..c {
                let (j, l) = (g * c + k, i * c + k);
                let vx = ((1.0 - ax) * self.vx[l] + dt * im * self.fx[l]) / (1.0 + ax);
                let vz = ((1.0 - az) * self.vz[l] + dt * im * self.fz[l]) / (1.0 + az);
                self.vx[l] = vx;
                self.vz[l] = vz;
                // (the interior's update moved u by dt v with the old v: take it back)
                let new = vx + vz;
                u[j] += dt * (new - v[j]);
                v[j] = new;
            }
        }
        work
    }

    /// The stresses of level n + 1 from the velocities `v` of level n + 1/2.
    pub fn stresses(&mut self, weights: &[f64], derivative: &[f64], v: &[f64], dt: f64) {
        if self.data.is_empty() {
            return;
        }
        match self.m {
            3 => self.stresses_m::<3>(weights, derivative, v, dt),
            4 => self.stresses_m::<4>(weights, derivative, v, dt),
            5 => self.stresses_m::<5>(weights, derivative, v, dt),
            6 => self.stresses_m::<6>(weights, derivative, v, dt),
            7 => self.stresses_m::<7>(weights, derivative, v, dt),
            8 => self.stresses_m::<8>(weights, derivative, v, dt),
            9 => self.stresses_m::<9>(weights, derivative, v, dt),
            _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
        }
    }

    fn stresses_m<const M: usize>(
        &mut self,
        weights: &[f64],
        derivative: &[f64],
        v: &[f64],
        dt: f64,
    ) {
        let (_, d) = rule::<M>(weights, derivative);
        let antiplane = self.antiplane;
        let sp = if antiplane { 2 } else { 6 };
        let mm = M * M;
        self.stress
            .par_chunks_mut(TASK * mm * sp)
            .zip(self.data.par_chunks(TASK))
            .zip(self.conn.par_chunks(TASK * mm))
            .zip(self.damp.par_chunks(TASK * mm))
            .for_each(|(((stress, data), conn), damp)| {
                for (e, el) in data.iter().enumerate() {
                    let s = &mut stress[e * mm * sp..(e + 1) * mm * sp];
                    let conn = &conn[e * mm..(e + 1) * mm];
                    let damp = &damp[e * mm..(e + 1) * mm];
                    let (sx, sz) = (2.0 / el.hx, 2.0 / el.hz);
                    let (lam, mu) = (el.lambda, el.mu);
                    let mut vx = [[0.0f64; M]; M];
                    let mut vz = [[0.0f64; M]; M];
                    for q in 0..mm {
                        let g = conn[q] as usize;
                        if antiplane {
                            vx[q / M][q % M] = v[g];
                        } else {
                            vx[q / M][q % M] = v[2 * g];
                            vz[q / M][q % M] = v[2 * g + 1];
                        }
                    }
                    for b in 0..M {
                        for a in 0..M {
                            let q = b * M + a;
                            let [dx, dz] = damp[q];
                            let (ax, az) = (0.5 * dt * dx, 0.5 * dt * dz);
                            let (px, pz) = ((1.0 - ax) / (1.0 + ax), dt / (1.0 + ax));
                            let (qx, qz) = ((1.0 - az) / (1.0 + az), dt / (1.0 + az));
                            let (mut xx, mut xz, mut zx, mut zz) = (0.0, 0.0, 0.0, 0.0);
                            for k in 0..M {
                                xx += d[a][k] * vx[b][k];
                                zx += d[b][k] * vx[k][a];
                                xz += d[a][k] * vz[b][k];
                                zz += d[b][k] * vz[k][a];
                            }
                            // dv_x/dx, dv_x/dz, dv_z/dx, dv_z/dz
                            let (vxx, vxz, vzx, vzz) = (sx * xx, sz * zx, sx * xz, sz * zz);
                            let s = &mut s[q * sp..(q + 1) * sp];
                            if antiplane {
                                s[0] = px * s[0] + pz * mu * vxx;
                                s[1] = qx * s[1] + qz * mu * vxz;
                            } else {
                                let l2m = lam + 2.0 * mu;
                                s[0] = px * s[0] + pz * l2m * vxx;
                                s[1] = px * s[1] + pz * lam * vxx;
                                s[2] = px * s[2] + pz * mu * vzx;
                                s[3] = qx * s[3] + qz * lam * vzz;
                                s[4] = qx * s[4] + qz * l2m * vzz;
                                s[5] = qx * s[5] + qz * mu * vxz;
                            }
                        }
                    }
                }
            });
    }
}

/// The GLL weights and the derivative matrix (`d[i][j] = l_j'(x_i)`) as fixed arrays.
fn rule<const M: usize>(weights: &[f64], derivative: &[f64]) -> ([f64; M], [[f64; M]; M]) {
    let mut w = [0.0; M];
    let mut d = [[0.0; M]; M];
    for i in 0..M {
        w[i] = weights[i];
        for j in 0..M {
            d[i][j] = derivative[i * M + j];
        }
    }
    (w, d)
}

/// The multiaxial damping (Meza-Fajardo and Papageorgiou, BSSA 98, 2008) of a point
/// whose profiles give `dx`, `dz` (1/s): each direction also takes [`MULTIAXIAL`] times
/// the other's.
pub(super) fn multiaxial(dx: f64, dz: f64) -> [f64; 2] {
    [dx + MULTIAXIAL * dz, dz + MULTIAXIAL * dx]
}

/// `edges` (from 0 to their last value) with a band of thickness `lo` before 0 and `hi`
/// after the end (m; 0: none), each cut into equal elements no longer than `h`; and the
/// number of band elements before 0.
pub(super) fn extend(edges: Vec<f64>, lo: f64, hi: f64, h: f64) -> (Vec<f64>, usize) {
    let count = |l: f64| ((l / h) - 1e-9).ceil().max(1.0) as usize;
    let end = *edges.last().unwrap_or(&0.0);
    let mut out = Vec::with_capacity(edges.len() + 8);
    let n_lo = if lo > 0.0 { count(lo) } else { 0 };
    for k in (1..=n_lo).rev() {
        out.push(-lo * k as f64 / n_lo as f64);
    }
    out.extend(edges);
    if hi > 0.0 {
        let n_hi = count(hi);
        for k in 1..=n_hi {
            out.push(if k == n_hi {
                end + hi
            } else {
                end + hi * k as f64 / n_hi as f64
            });
        }
    }
    (out, n_lo)
}

/// The interior's operator and the band, split out of the operator of every element
/// (`all`, on a mesh whose interior elements are `x0..x0 + nx` by `z0..z0 + nz`):
/// `mass` (the lumped mass of every element, kg/m) becomes the interior elements' share
/// (what the energy of the solid counts), `densities` are per element (kg/m^3), and the
/// damping of a point at `(x, z)` is `(dx(x), dz(z))`.
#[allow(clippy::too_many_arguments)]
pub(super) fn split(
    all: super::kernel::Stiffness,
    interior: (usize, usize, usize, usize),
    densities: &[f64],
    x: &[f64],
    z: &[f64],
    grid: (usize, usize),
    dx: &Profile,
    dz: &Profile,
    mass: &mut [f64],
) -> (super::kernel::Stiffness, Band) {
    let (x0, nx, z0, nz) = interior;
    let (nex, nez) = all.dims;
    let n = all.order;
    let m = n + 1;
    let mm = m * m;
    let w = &all.weights;
    let is_interior = |ex: usize, ez: usize| ex >= x0 && ex < x0 + nx && ez >= z0 && ez < z0 + nz;
    let mut elements = Vec::with_capacity(nx * nz);
    let mut conn = Vec::with_capacity(nx * nz * mm);
    let mut b_data = Vec::new();
    let mut b_conn = Vec::new();
    let mut b_damp = Vec::new();
    let mut inner = vec![false; mass.len()];
    let mut mass_band = vec![0.0; mass.len()];
    let nxn = grid.0;
    for ez in 0..nez {
        for ex in 0..nex {
            let e = ez * nex + ex;
            let el = all.elements[e];
            let c = &all.conn[e * mm..(e + 1) * mm];
            if is_interior(ex, ez) {
                elements.push(el);
                conn.extend_from_slice(c);
                for &g in c {
                    inner[g as usize] = true;
                }
            } else {
                b_data.push(el);
                b_conn.extend_from_slice(c);
                for b in 0..m {
                    for a in 0..m {
                        let (ix, iz) = (ex * n + a, ez * n + b);
                        b_damp.push(multiaxial(dx.at(x[ix]), dz.at(z[iz])));
                        mass_band[c[b * m + a] as usize] +=
                            densities[e] * w[a] * w[b] * el.hx * el.hz / 4.0;
                    }
                }
            }
        }
    }
    // the interior's share of the mass (exactly 0 on the pure band nodes)
    for ((mi, &mb), &inside) in mass.iter_mut().zip(&mass_band).zip(&inner) {
        *mi = if inside { *mi - mb } else { 0.0 };
    }
    let node_damp = |g: usize| {
        let (ix, iz) = (g % nxn, g / nxn);
        multiaxial(dx.at(x[ix]), dz.at(z[iz.min(z.len() - 1)]))
    };
    let band = Band::new(
        n,
        all.antiplane,
        b_data,
        b_conn,
        b_damp,
        &inner,
        &mass_band,
        node_damp,
    );
    let interior = super::kernel::Stiffness {
        dims: (nx, nz),
        elements,
        conn,
        regular: Vec::new(),
        ..all
    }
    .with_blocks();
    (interior, band)
}

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

use super::lines::{Params, Rule};
#[cfg(target_arch = "x86_64")]
use super::registers;
use super::simd;
use multiversion::multiversion;
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
    /// Each block of eight elements along a row (row by row, the last partial block
    /// included), where it is regular (see [`super::simd`]): its first node and the node
    /// stride between its node rows (so that the time loop does not read the map); filled
    /// by [`Stiffness::with_blocks`]; empty, or of another length, means none is.
    pub regular: Vec<Option<(usize, usize)>>,
    /// Per element, the constants of [`Params`] (`2 / hx`, `2 / hz`, `lambda + 2 mu`,
    /// `lambda`, `mu`, `hx / 2`, `hz / 2`): filled by [`Stiffness::with_blocks`] so that
    /// the time loop divides nothing; empty means computed per block (the same values).
    pub coefs: Vec<[f64; 7]>,
}

/// Where the elements from `ex0` on (of a row whose block marks are `marks`, see
/// [`Stiffness::with_blocks`]) start when their block is regular: the first node of
/// element `ex0` and the node stride between its node rows (order `M - 1`); none otherwise.
#[inline(always)]
fn block_start<const M: usize>(
    marks: &[Option<(usize, usize)>],
    ex0: usize,
) -> Option<(usize, usize)> {
    marks
        .get(ex0 / simd::W)
        .copied()
        .flatten()
        .map(|(first, stride)| (first + (ex0 % simd::W) * (M - 1), stride))
}

/// The constants of [`Params`] of one element (see [`Stiffness::coefs`]).
#[inline(always)]
fn coefs_of(el: &ElementData) -> [f64; 7] {
    [
        2.0 / el.hx,
        2.0 / el.hz,
        el.lambda + 2.0 * el.mu,
        el.lambda,
        el.mu,
        0.5 * el.hx,
        0.5 * el.hz,
    ]
}

/// The grid node rows of the operator's elements, advanced by [`Stiffness::step`] as soon
/// as their forces are complete: node row `r` (`0..rows`, from the top of the operator's
/// first element row) holds the nodes `(row0 + r) stride + col0 .. + len`. The other
/// nodes (split twins, absorbing layers) are the caller's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeRows {
    /// Nodes per grid row of the mesh.
    pub stride: usize,
    /// Grid row of the first node row.
    pub row0: usize,
    /// Grid column of the first node of each row.
    pub col0: usize,
    /// Nodes per row.
    pub len: usize,
}

impl NodeRows {
    /// The nodes `0..n_nodes` outside the `n_rows` node rows, increasing: those
    /// [`Stiffness::step`] leaves to its caller.
    pub fn outside(&self, n_rows: usize, n_nodes: usize) -> Vec<u32> {
        let inside = |g: usize| {
            let (iz, ix) = (g / self.stride, g % self.stride);
            iz >= self.row0
                && iz < self.row0 + n_rows
                && ix >= self.col0
                && ix < self.col0 + self.len
        };
        (0..n_nodes)
            .filter(|&g| !inside(g))
            .map(|g| g as u32)
            .collect()
    }
}

/// The node-wise update of one node `i` of `C` components: `v += dt f / m`, `u += dt v`,
/// then `f = 0` (velocities at half levels, eq. 15.2).
#[inline(always)]
fn advance_node<const C: usize>(
    u: &mut [f64],
    v: &mut [f64],
    f: &mut [f64],
    inv_mass: f64,
    dt: f64,
) {
    for k in 0..C {
        v[k] += dt * inv_mass * f[k];
        u[k] += dt * v[k];
        f[k] = 0.0;
    }
}

/// [`advance_node`] over consecutive nodes (`inv_mass` one per node), compiled for
/// AVX-512 and AVX2 where the CPU has them (the same operations: the same bits).
#[multiversion(targets("x86_64+avx512f+avx2+avx", "x86_64+avx2+avx"))]
fn advance<const C: usize>(u: &mut [f64], v: &mut [f64], f: &mut [f64], inv_mass: &[f64], dt: f64) {
    for (((un, vn), fnode), &im) in u
        .chunks_exact_mut(C)
        .zip(v.chunks_exact_mut(C))
        .zip(f.chunks_exact_mut(C))
        .zip(inv_mass)
    {
        advance_node::<C>(un, vn, fnode, im, dt);
    }
}

/// [`advance`] over the nodes `nodes` of arrays of `comps` components per node (1 or 2).
pub(super) fn advance_nodes(
    comps: usize,
    u: &mut [f64],
    v: &mut [f64],
    f: &mut [f64],
    inv_mass: &[f64],
    nodes: std::ops::Range<usize>,
    dt: f64,
) {
    let span = comps * nodes.start..comps * nodes.end;
    let (u, v, f) = (&mut u[span.clone()], &mut v[span.clone()], &mut f[span]);
    if comps == 2 {
        advance::<2>(u, v, f, &inv_mass[nodes], dt);
    } else {
        advance::<1>(u, v, f, &inv_mass[nodes], dt);
    }
}

/// What [`Stiffness::step`] advances besides the forces: velocities, inverse masses, the
/// time step and the node rows.
#[derive(Clone, Copy)]
struct Advance<'a> {
    u: Shared,
    v: Shared,
    len: usize,
    inv_mass: &'a [f64],
    dt: f64,
    rows: NodeRows,
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

/// Elements computed together, one per SIMD lane (along a row of elements): four doubles
/// fill an AVX2 register, eight an AVX-512 one. The lanes never mix, so any width gives
/// the same bits.
const LANES: usize = 4;
/// [`LANES`] where the CPU has AVX-512.
#[cfg(target_arch = "x86_64")]
const LANES_512: usize = 8;

/// The forces `g = integral sigma : grad phi` of a block of `L` plane-strain elements from
/// their displacements (`[b][a][lane]`): the gradients along x-lines and z-lines (even-odd
/// derivative), Hooke's law and the quadrature weights at each point, the divergence by
/// the transposed derivative along x-lines plus along z-lines. [`registers`] does the same
/// operations in the same order on AVX-512 and AVX2 registers (the same bits). `d`: the
/// four gradients' scratch, overwritten (the caller's, once per row: zeroing it per block
/// took 4 % of a thread).
#[inline(always)]
fn psv_block<const M: usize, const L: usize>(
    r: &Rule<M>,
    ux: &[[[f64; L]; M]; M],
    uz: &[[[f64; L]; M]; M],
    p: &Params<L>,
    d: &mut [[[[f64; L]; M]; M]; 4],
    gx: &mut [[[f64; L]; M]; M],
    gz: &mut [[[f64; L]; M]; M],
) {
    let w = &r.w;
    let [dxx, dxz, dzx, dzz] = d;
    for b in 0..M {
        r.grad.apply(&ux[b], &mut dxx[b]);
        r.grad.apply(&uz[b], &mut dxz[b]);
    }
    r.grad.apply_rows::<L, false>(ux, dzx);
    r.grad.apply_rows::<L, false>(uz, dzz);
    // the x-flux `(hz/2) w_a w_b sigma_ix` and the z-flux `(hx/2) w_a w_b sigma_iz` of
    // each component i at each quadrature point (dA sx = (hx hz / 4) w_a w_b (2 / hx),
    // and alike along z); the fluxes overwrite the gradients
    for b in 0..M {
        for a in 0..M {
            let wab = w[a] * w[b];
            for l in 0..L {
                let (exx, ezz) = (dxx[b][a][l] * p.sx[l], dzz[b][a][l] * p.sz[l]);
                let exz = dzx[b][a][l] * p.sz[l] + dxz[b][a][l] * p.sx[l];
                let sxx = p.l2m[l] * exx + p.lam[l] * ezz;
                let szz = p.lam[l] * exx + p.l2m[l] * ezz;
                let sxz = p.mu[l] * exz;
                let (wx, wz) = (p.hz2[l] * wab, p.hx2[l] * wab);
                dxx[b][a][l] = wx * sxx;
                dxz[b][a][l] = wx * sxz;
                dzx[b][a][l] = wz * sxz;
                dzz[b][a][l] = wz * szz;
            }
        }
    }
    // the divergence: the transposed derivative along x-lines, then along z-lines
    for b in 0..M {
        r.div.apply(&dxx[b], &mut gx[b]);
        r.div.apply(&dxz[b], &mut gz[b]);
    }
    r.div.apply_rows::<L, true>(dzx, gx);
    r.div.apply_rows::<L, true>(dzz, gz);
}

/// A block's lane arrays as `W`-lane arrays ([`simd::Block`], the register kernels'; `L`
/// = `W`, checked).
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
#[inline(always)]
fn block<const M: usize, const L: usize, const W: usize>(
    x: &[[[f64; L]; M]; M],
) -> &[[[f64; W]; M]; M] {
    assert!(L == W);
    // SAFETY: the same type (asserted sizes)
    unsafe { &*(x as *const [[[f64; L]; M]; M] as *const [[[f64; W]; M]; M]) }
}

/// [`block`], mutable.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
#[inline(always)]
fn block_mut<const M: usize, const L: usize, const W: usize>(
    x: &mut [[[f64; L]; M]; M],
) -> &mut [[[f64; W]; M]; M] {
    assert!(L == W);
    // SAFETY: the same type (asserted sizes)
    unsafe { &mut *(x as *mut [[[f64; L]; M]; M] as *mut [[[f64; W]; M]; M]) }
}

/// The vector extensions of the CPU the kernel runs on.
#[derive(Clone, Copy)]
struct Cpu {
    avx512: bool,
    avx2: bool,
}

impl Cpu {
    fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        return Cpu {
            avx512: std::is_x86_feature_detected!("avx512f"),
            avx2: std::is_x86_feature_detected!("avx2"),
        };
        #[cfg(not(target_arch = "x86_64"))]
        Cpu {
            avx512: false,
            avx2: false,
        }
    }
}

impl Stiffness {
    /// The operator with its regular blocks marked (those whose nodes every CPU path
    /// addresses by node rows, and AVX-512 gathers and scatters row by row) and its
    /// elements' constants computed ([`Stiffness::coefs`]).
    pub fn with_blocks(mut self) -> Self {
        self.coefs = self.elements.iter().map(coefs_of).collect();
        let (nex, nez) = self.dims;
        let (m, w) = (self.order + 1, simd::W);
        let per_row = nex.div_ceil(w);
        self.regular = vec![None; per_row * nez];
        if nex < w {
            return self;
        }
        for ez in 0..nez {
            let c = &self.conn[ez * nex * m * m..];
            let offsets = simd::block_offsets(m, c[m].wrapping_sub(c[0]));
            for blk in 0..nex / w {
                let e0 = ez * nex + blk * w;
                if simd::is_regular(&self.conn[e0 * m * m..(e0 + w) * m * m], &offsets) {
                    self.regular[ez * per_row + blk] = Some(self.block_rows(e0));
                }
            }
        }
        self
    }

    /// `force = -K u` (plus nothing: `force` is overwritten). `u` and `force` hold one
    /// value per node (antiplane) or two interleaved (plane strain), m and N/m.
    pub fn apply(&self, u: &[f64], force: &mut [f64]) {
        self.dispatch(u, force, true);
    }

    /// [`Stiffness::apply`] on the calling thread only (small operators); the same bits.
    pub fn apply_serial(&self, u: &[f64], force: &mut [f64]) {
        self.dispatch(u, force, false);
    }

    /// One leapfrog step of the node rows `rows` (eq. 15.2): `force -= K u` and, each node
    /// row as soon as its forces are complete (its element rows done), `v += dt force / m`,
    /// `u += dt v`, `force = 0`, while the row is still in the cache. `force` holds the
    /// other forces of level n on entry (sources, absorbing layers); the nodes outside
    /// `rows` keep their forces for the caller. The same bits for any thread count: a node
    /// row is advanced once, after both element rows around it, by the row of odd parity
    /// (or the only one), and no row reads another's node rows.
    pub fn step(
        &self,
        u: &mut [f64],
        v: &mut [f64],
        force: &mut [f64],
        inv_mass: &[f64],
        dt: f64,
        rows: NodeRows,
    ) {
        let comps = if self.antiplane { 1 } else { 2 };
        let n = self.order;
        let (nex, nez) = self.dims;
        // (the rows must lie inside the arrays: checked here once, not per row)
        let last = (rows.row0 + nez * n) * rows.stride + rows.col0 + rows.len;
        assert!(
            rows.len <= nex * n + 1
                && last <= inv_mass.len()
                && comps * inv_mass.len() == u.len()
                && u.len() == v.len()
                && v.len() == force.len(),
            "node rows outside the arrays"
        );
        let adv = Advance {
            u: Shared(u.as_mut_ptr()),
            v: Shared(v.as_mut_ptr()),
            len: u.len(),
            inv_mass,
            dt,
            rows,
        };
        self.kernel(u, force, true, Some(adv), Cpu::detect());
    }

    fn dispatch(&self, u: &[f64], force: &mut [f64], parallel: bool) {
        force.fill(0.0);
        self.kernel(u, force, parallel, None, Cpu::detect());
    }

    /// [`Stiffness::apply`] by the portable kernel (no AVX2, no AVX-512): the same bits
    /// (the test `every_cpu_path_gives_the_same_bits`).
    #[cfg(test)]
    pub(super) fn apply_portable(&self, u: &[f64], force: &mut [f64]) {
        force.fill(0.0);
        let cpu = Cpu {
            avx512: false,
            avx2: false,
        };
        self.kernel(u, force, true, None, cpu);
    }

    fn kernel(
        &self,
        u: &[f64],
        force: &mut [f64],
        parallel: bool,
        adv: Option<Advance<'_>>,
        cpu: Cpu,
    ) {
        match self.order {
            2 => self.apply_m::<3>(u, force, parallel, adv, cpu),
            3 => self.apply_m::<4>(u, force, parallel, adv, cpu),
            4 => self.apply_m::<5>(u, force, parallel, adv, cpu),
            5 => self.apply_m::<6>(u, force, parallel, adv, cpu),
            6 => self.apply_m::<7>(u, force, parallel, adv, cpu),
            7 => self.apply_m::<8>(u, force, parallel, adv, cpu),
            8 => self.apply_m::<9>(u, force, parallel, adv, cpu),
            _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
        }
    }

    /// Advance the node rows of element row `ez` whose forces are complete after it, in
    /// pass `parity` (see [`Stiffness::step`]).
    fn advance_rows(&self, ez: usize, parity: usize, out: &mut [f64], a: &Advance<'_>) {
        let n = self.order;
        let nez = self.dims.1;
        let top = if parity == 1 || ez == 0 { 0 } else { 1 };
        let bottom = if parity == 1 || ez + 1 == nez {
            n
        } else {
            n - 1
        };
        let r = a.rows;
        let comps = if self.antiplane { 1 } else { 2 };
        for b in top..=bottom {
            let first = (r.row0 + ez * n + b) * r.stride + r.col0;
            // SAFETY: the node rows advanced here are read and written by this element row
            // alone in this pass (`step`), and lie inside the arrays (asserted in `step`)
            let (u, v) = unsafe {
                (
                    std::slice::from_raw_parts_mut(a.u.get(), a.len),
                    std::slice::from_raw_parts_mut(a.v.get(), a.len),
                )
            };
            advance_nodes(comps, u, v, out, a.inv_mass, first..first + r.len, a.dt);
        }
    }

    fn rule<const M: usize>(&self) -> Rule<M> {
        Rule::new(&self.weights, &self.derivative)
    }

    fn apply_m<const M: usize>(
        &self,
        u: &[f64],
        force: &mut [f64],
        parallel: bool,
        adv: Option<Advance<'_>>,
        cpu: Cpu,
    ) {
        let nez = self.dims.1;
        let rule = self.rule::<M>();
        let out = Shared(force.as_mut_ptr());
        let len = force.len();
        let u_ptr = Shared(u.as_ptr() as *mut f64);
        let row = |ez: usize, parity: usize| {
            // SAFETY: rows of one parity write disjoint nodes (module comment), and the
            // rows of a parity finish before the other parity starts; every index is
            // below `len` (the map is built over the nodes). The displacements a row reads
            // are advanced only by that row, after it (`step`).
            let out = unsafe { std::slice::from_raw_parts_mut(out.get(), len) };
            let u = unsafe { std::slice::from_raw_parts(u_ptr.get() as *const f64, len) };
            self.row_any::<M>(&rule, ez, u, out, cpu);
            if let Some(a) = &adv {
                self.advance_rows(ez, parity, out, a);
            }
        };
        for parity in 0..2 {
            let n = (nez + 1 - parity) / 2;
            if parallel {
                (0..n)
                    .into_par_iter()
                    .for_each(|i| row(parity + 2 * i, parity));
            } else {
                (0..n).for_each(|i| row(parity + 2 * i, parity));
            }
        }
    }

    /// The forces of element row `ez` by the widest kernel the CPU runs.
    #[inline(always)]
    fn row_any<const M: usize>(
        &self,
        rule: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
        cpu: Cpu,
    ) {
        #[cfg(target_arch = "x86_64")]
        if cpu.avx512 {
            // SAFETY: the CPU has AVX-512F (`Cpu::detect`)
            unsafe { self.row_avx512::<M>(rule, ez, u, out) };
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if cpu.avx2 {
            // SAFETY: the CPU has AVX2 (`Cpu::detect`)
            unsafe { self.row_avx2::<M>(rule, ez, u, out) };
            return;
        }
        self.row::<M, LANES>(rule, ez, u, out, cpu);
    }

    /// The forces of element row `ez`.
    #[inline(always)]
    fn row<const M: usize, const L: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
        cpu: Cpu,
    ) {
        if self.antiplane {
            self.row_sh::<M, L>(r, ez, u, out);
        } else {
            self.row_psv::<M, L>(r, ez, u, out, cpu);
        }
    }

    /// [`Stiffness::row`] compiled for AVX2, four elements at a time, the element forces
    /// in registers ([`super::registers`]): the same operations in the same order (no
    /// fused multiply-add: Rust does not contract `a * b + c`), so the same bits as the
    /// baseline build.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn row_avx2<const M: usize>(&self, r: &Rule<M>, ez: usize, u: &[f64], out: &mut [f64]) {
        let cpu = Cpu {
            avx512: false,
            avx2: true,
        };
        self.row::<M, LANES>(r, ez, u, out, cpu);
    }

    /// [`Stiffness::row`] compiled for AVX-512, eight elements at a time: the same
    /// operations on each element in the same order, so the same bits (the kernel alone on
    /// one thread, CPU time: 25 % more node-updates per second than AVX2's four lanes on
    /// the AMD EPYC of docs/performance.md section 2a).
    ///
    /// # Safety
    /// The CPU must support AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2")]
    unsafe fn row_avx512<const M: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
    ) {
        let cpu = Cpu {
            avx512: true,
            avx2: true,
        };
        self.row::<M, LANES_512>(r, ez, u, out, cpu);
    }

    /// The forces of element row `ez`, `LANES` elements at a time; `cpu`: what the caller
    /// is compiled for: AVX-512F, whose element forces ([`super::registers`]) take every
    /// block and whose gather and scatter ([`super::simd`]) take the regular ones, or AVX2,
    /// whose element forces take every block of four.
    #[inline(always)]
    fn row_psv<const M: usize, const LANES: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
        cpu: Cpu,
    ) {
        let nex = self.dims.0;
        let mut ex0 = 0;
        // the regular blocks of this row (marked by `with_blocks`)
        #[cfg(target_arch = "x86_64")]
        let wide = cpu.avx512 && M <= simd::MAX_POINTS && LANES == simd::W;
        #[cfg(target_arch = "x86_64")]
        let narrow = !wide && cpu.avx2 && LANES == registers::avx2::W;
        #[cfg(not(target_arch = "x86_64"))]
        let (wide, narrow) = (false && cpu.avx512, false);
        // (AVX-512 takes the marked blocks of eight, the others their halves)
        let marks = self.row_marks(ez);
        // the element block's scratch, once per row (no clearing per block: the lanes past
        // the row's end keep the last block's finite values, computed and never scattered)
        let mut ux = [[[0.0f64; LANES]; M]; M];
        let mut uz = [[[0.0f64; LANES]; M]; M];
        let mut gx = [[[0.0f64; LANES]; M]; M];
        let mut gz = [[[0.0f64; LANES]; M]; M];
        let mut grads = [[[[0.0f64; LANES]; M]; M]; 4];
        while ex0 < nex {
            let nl = LANES.min(nex - ex0);
            let e0 = ez * nex + ex0;
            // a regular block (of eight, or of four: half of one) starts at node `first`
            // (its node rows `stride` apart)
            let start = block_start::<M>(marks, ex0);
            let regular = start.is_some();
            // a regular block of four (AVX2, portable): each element's node rows are runs
            // of `M` nodes at `first + b stride + (M - 1) l` (its map, without reading it)
            let runs = if wide { None } else { start };
            let (mut sx, mut sz, mut l2m, mut lam, mut mu, mut hx2, mut hz2) = (
                [1.0; LANES],
                [1.0; LANES],
                [0.0; LANES],
                [0.0; LANES],
                [0.0; LANES],
                [0.0; LANES],
                [0.0; LANES],
            );
            for l in 0..nl {
                [sx[l], sz[l], l2m[l], lam[l], mu[l], hx2[l], hz2[l]] = self.coefs_at(e0 + l);
                if let Some((first, stride)) = runs {
                    for b in 0..M {
                        let at = 2 * (first + b * stride + (M - 1) * l);
                        let run = &u[at..at + 2 * M];
                        for a in 0..M {
                            ux[b][a][l] = run[2 * a];
                            uz[b][a][l] = run[2 * a + 1];
                        }
                    }
                    continue;
                }
                if regular {
                    continue;
                }
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        let g = conn[b * M + a] as usize;
                        ux[b][a][l] = u[2 * g];
                        uz[b][a][l] = u[2 * g + 1];
                    }
                }
            }
            #[cfg(target_arch = "x86_64")]
            if let (true, Some(rows)) = (wide, start) {
                // SAFETY: the caller runs on AVX-512F (`wide`); the block is regular
                unsafe { simd::gather_block::<M>(u, rows, block_mut(&mut ux), block_mut(&mut uz)) };
            }
            let par = Params {
                sx,
                sz,
                l2m,
                lam,
                mu,
                hx2,
                hz2,
            };
            #[cfg(target_arch = "x86_64")]
            if wide {
                assert!(LANES == simd::W);
                // SAFETY: the caller runs on AVX-512F (`wide`); LANES = 8 (asserted), so
                // the constants are those of `simd`
                unsafe {
                    let par = &*(&par as *const Params<LANES> as *const Params<{ simd::W }>);
                    let (gx, gz) = (block_mut(&mut gx), block_mut(&mut gz));
                    registers::avx512::psv_block::<M>(r, block(&ux), block(&uz), par, gx, gz);
                }
            }
            #[cfg(target_arch = "x86_64")]
            if narrow {
                const W: usize = registers::avx2::W;
                assert!(LANES == W);
                // SAFETY: the caller runs on AVX2 (`narrow`); LANES = 4 (asserted)
                unsafe {
                    let par = &*(&par as *const Params<LANES> as *const Params<W>);
                    let (gx, gz) = (block_mut(&mut gx), block_mut(&mut gz));
                    registers::avx2::psv_block::<M>(r, block(&ux), block(&uz), par, gx, gz);
                }
            }
            if !wide && !narrow {
                psv_block::<M, LANES>(r, &ux, &uz, &par, &mut grads, &mut gx, &mut gz);
            }
            // scatter element by element, left to right (the order of every run)
            #[cfg(target_arch = "x86_64")]
            if let (true, Some(rows)) = (wide, start) {
                // SAFETY: as for the gather
                unsafe { simd::scatter_block::<M>(out, rows, block(&gx), block(&gz)) };
                ex0 += LANES;
                continue;
            }
            if let Some((first, stride)) = runs {
                for l in 0..nl {
                    for b in 0..M {
                        let at = 2 * (first + b * stride + (M - 1) * l);
                        let run = &mut out[at..at + 2 * M];
                        for a in 0..M {
                            run[2 * a] -= gx[b][a][l];
                            run[2 * a + 1] -= gz[b][a][l];
                        }
                    }
                }
                ex0 += LANES;
                continue;
            }
            for l in 0..nl {
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        let g = conn[b * M + a] as usize;
                        out[2 * g] -= gx[b][a][l];
                        out[2 * g + 1] -= gz[b][a][l];
                    }
                }
            }
            ex0 += LANES;
        }
    }

    /// The marks of element row `ez` (one per block of [`simd::W`] elements, set by
    /// [`Stiffness::with_blocks`]); none where the blocks were not marked.
    #[inline(always)]
    fn row_marks(&self, ez: usize) -> &[Option<(usize, usize)>] {
        let per_row = self.dims.0.div_ceil(simd::W);
        match self.regular.get(ez * per_row..(ez + 1) * per_row) {
            Some(m) if self.regular.len() == per_row * self.dims.1 => m,
            _ => &[],
        }
    }

    /// Element `e`'s constants ([`coefs_of`]): kept in `coefs` where it was filled,
    /// computed otherwise.
    #[inline(always)]
    fn coefs_at(&self, e: usize) -> [f64; 7] {
        match self.coefs.get(e) {
            Some(c) if self.coefs.len() == self.elements.len() => *c,
            _ => coefs_of(&self.elements[e]),
        }
    }

    /// The first node of the regular block starting at element `e0` and the node stride
    /// between its node rows (the map's regular pattern).
    #[inline(always)]
    fn block_rows(&self, e0: usize) -> (usize, usize) {
        let m = self.order + 1;
        let (first, second) = (self.conn[e0 * m * m], self.conn[e0 * m * m + m]);
        (first as usize, (second - first) as usize)
    }

    /// The antiplane forces of element row `ez`, `LANES` elements at a time.
    #[inline(always)]
    fn row_sh<const M: usize, const LANES: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
    ) {
        let nex = self.dims.0;
        let w = &r.w;
        let mut ex0 = 0;
        // the block's scratch, once per row (as in [`Stiffness::row_psv`])
        let mut uy = [[[0.0f64; LANES]; M]; M];
        let (mut dx, mut dz) = ([[[0.0f64; LANES]; M]; M], [[[0.0f64; LANES]; M]; M]);
        let mut fx = [[[0.0f64; LANES]; M]; M];
        let mut fz = [[[0.0f64; LANES]; M]; M];
        let mut g = [[[0.0f64; LANES]; M]; M];
        // the regular blocks of this row (as in [`Stiffness::row_psv`])
        let marks = self.row_marks(ez);
        while ex0 < nex {
            let nl = LANES.min(nex - ex0);
            let e0 = ez * nex + ex0;
            // a regular block's element node rows: runs of `M` nodes (see `row_psv`)
            let runs = block_start::<M>(marks, ex0);
            let (mut cx, mut cz) = ([0.0; LANES], [0.0; LANES]);
            for l in 0..nl {
                let [sx, sz, _, _, mu, hx2, hz2] = self.coefs_at(e0 + l);
                // (hz/2) mu sx and (hx/2) mu sz
                cx[l] = hz2 * mu * sx;
                cz[l] = hx2 * mu * sz;
                if let Some((first, stride)) = runs {
                    for b in 0..M {
                        let at = first + b * stride + (M - 1) * l;
                        let run = &u[at..at + M];
                        for a in 0..M {
                            uy[b][a][l] = run[a];
                        }
                    }
                    continue;
                }
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        uy[b][a][l] = u[conn[b * M + a] as usize];
                    }
                }
            }
            for b in 0..M {
                r.grad.apply(&uy[b], &mut dx[b]);
            }
            r.grad.apply_rows::<LANES, false>(&uy, &mut dz);
            for b in 0..M {
                for a in 0..M {
                    let wab = w[a] * w[b];
                    for l in 0..LANES {
                        fx[b][a][l] = wab * cx[l] * dx[b][a][l];
                        fz[b][a][l] = wab * cz[l] * dz[b][a][l];
                    }
                }
            }
            for b in 0..M {
                r.div.apply(&fx[b], &mut g[b]);
            }
            r.div.apply_rows::<LANES, true>(&fz, &mut g);
            if let Some((first, stride)) = runs {
                for l in 0..nl {
                    for b in 0..M {
                        let at = first + b * stride + (M - 1) * l;
                        let run = &mut out[at..at + M];
                        for a in 0..M {
                            run[a] -= g[b][a][l];
                        }
                    }
                }
                ex0 += LANES;
                continue;
            }
            for l in 0..nl {
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        out[conn[b * M + a] as usize] -= g[b][a][l];
                    }
                }
            }
            ex0 += LANES;
        }
    }
}

/// An upper bound of the highest eigenfrequency of `M^-1 K` (rad/s): the largest of the
/// elements' own (Fried's bound: with a lumped mass assembled from the elements',
/// `x K x = sum x_e K_e x_e <= max_e lambda_e sum x_e M_e x_e = max_e lambda_e x M x`),
/// each by power iteration on the element alone (elements of one size and material
/// share it). Rigid sides and split nodes only lower the true value.
pub(super) fn max_frequency(k: &Stiffness, densities: &[f64]) -> f64 {
    let m = k.order + 1;
    let comps = if k.antiplane { 1 } else { 2 };
    let mut seen: Vec<([u64; 5], f64)> = Vec::new();
    let mut lambda_max = 0.0f64;
    for (e, el) in k.elements.iter().enumerate() {
        let rho = densities[e];
        let key = [el.hx, el.hz, el.lambda, el.mu, rho].map(f64::to_bits);
        if let Some((_, l)) = seen.iter().find(|(kk, _)| *kk == key) {
            lambda_max = lambda_max.max(*l);
            continue;
        }
        // the element alone: nodes 0..m*m, its own lumped mass
        let one = Stiffness {
            order: k.order,
            dims: (1, 1),
            elements: vec![*el],
            conn: (0..(m * m) as u32).collect(),
            weights: k.weights.clone(),
            derivative: k.derivative.clone(),
            antiplane: k.antiplane,
            regular: Vec::new(),
            coefs: Vec::new(),
        };
        let w = &k.weights;
        let mass: Vec<f64> = (0..m * m)
            .map(|i| rho * w[i % m] * w[i / m] * el.hx * el.hz / 4.0)
            .collect();
        let len = comps * m * m;
        let mut x: Vec<f64> = (0..len)
            .map(|i| 1.0 + ((i * 7919) % 13) as f64 * 0.1 * if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let mut y = vec![0.0; len];
        let mut l = 0.0;
        for _ in 0..5000 {
            one.apply_serial(&x, &mut y);
            let (mut xy, mut xx) = (0.0, 0.0);
            for i in 0..len {
                let mi = mass[i / comps];
                y[i] /= -mi;
                xy += mi * x[i] * y[i];
                xx += mi * x[i] * x[i];
            }
            let new = xy / xx;
            let norm = y.iter().map(|v| v * v).sum::<f64>().sqrt();
            for (a, b) in x.iter_mut().zip(&y) {
                *a = b / norm;
            }
            let done = (new - l).abs() <= 1e-13 * new;
            l = new;
            if done {
                break;
            }
        }
        seen.push((key, l));
        lambda_max = lambda_max.max(l);
    }
    // (the power iteration approaches the element's value from below: a margin of 1e-6)
    (lambda_max * (1.0 + 1e-6)).sqrt()
}

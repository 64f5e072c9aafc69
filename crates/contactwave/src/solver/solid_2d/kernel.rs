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

/// Elements computed together, one per SIMD lane (along a row of elements): four doubles
/// fill an AVX2 register, eight an AVX-512 one. The lanes never mix, so any width gives
/// the same bits.
const LANES: usize = 4;
/// [`LANES`] where the CPU has AVX-512.
#[cfg(target_arch = "x86_64")]
const LANES_512: usize = 8;

/// The derivative matrix and the weights of order `M - 1` as fixed-size arrays.
struct Rule<const M: usize> {
    /// `d[i][j] = l_j'(x_i)`.
    d: [[f64; M]; M],
    w: [f64; M],
}

impl Stiffness {
    /// `force = -K u` (plus nothing: `force` is overwritten). `u` and `force` hold one
    /// value per node (antiplane) or two interleaved (plane strain), m and N/m.
    pub fn apply(&self, u: &[f64], force: &mut [f64]) {
        self.dispatch(u, force, true);
    }

    /// [`Stiffness::apply`] on the calling thread only (small operators); the same bits.
    pub fn apply_serial(&self, u: &[f64], force: &mut [f64]) {
        self.dispatch(u, force, false);
    }

    /// `force -= K u`: [`Stiffness::apply`] without clearing `force` first (the time loop
    /// clears it as it reads it, saving a pass over memory). The same bits as `apply`
    /// when `force` is zero.
    pub fn accumulate(&self, u: &[f64], force: &mut [f64]) {
        self.kernel(u, force, true);
    }

    fn dispatch(&self, u: &[f64], force: &mut [f64], parallel: bool) {
        force.fill(0.0);
        self.kernel(u, force, parallel);
    }

    fn kernel(&self, u: &[f64], force: &mut [f64], parallel: bool) {
        match self.order {
            2 => self.apply_m::<3>(u, force, parallel),
            3 => self.apply_m::<4>(u, force, parallel),
            4 => self.apply_m::<5>(u, force, parallel),
            5 => self.apply_m::<6>(u, force, parallel),
            6 => self.apply_m::<7>(u, force, parallel),
            7 => self.apply_m::<8>(u, force, parallel),
            8 => self.apply_m::<9>(u, force, parallel),
            _ => unreachable!("orders 2 to 8 are checked when the problem is built"),
        }
    }

    fn rule<const M: usize>(&self) -> Rule<M> {
        let mut r = Rule {
            d: [[0.0; M]; M],
            w: [0.0; M],
        };
        for i in 0..M {
            r.w[i] = self.weights[i];
            for j in 0..M {
                r.d[i][j] = self.derivative[i * M + j];
            }
        }
        r
    }

    fn apply_m<const M: usize>(&self, u: &[f64], force: &mut [f64], parallel: bool) {
        let nez = self.dims.1;
        let rule = self.rule::<M>();
        let out = Shared(force.as_mut_ptr());
        let len = force.len();
        #[cfg(target_arch = "x86_64")]
        let avx512 = std::is_x86_feature_detected!("avx512f");
        #[cfg(target_arch = "x86_64")]
        let avx2 = std::is_x86_feature_detected!("avx2");
        let row = |ez: usize| {
            // SAFETY: rows of one parity write disjoint nodes (module comment), and the
            // rows of a parity finish before the other parity starts; every index is
            // below `len` (the map is built over the nodes).
            let out = unsafe { std::slice::from_raw_parts_mut(out.get(), len) };
            #[cfg(target_arch = "x86_64")]
            if avx512 {
                // SAFETY: the CPU has AVX-512F (checked at run time above)
                unsafe { self.row_avx512::<M>(&rule, ez, u, out) };
                return;
            }
            #[cfg(target_arch = "x86_64")]
            if avx2 {
                // SAFETY: the CPU has AVX2 (checked at run time above)
                unsafe { self.row_avx2::<M>(&rule, ez, u, out) };
                return;
            }
            self.row::<M, LANES>(&rule, ez, u, out);
        };
        for parity in 0..2 {
            let n = (nez + 1 - parity) / 2;
            if parallel {
                (0..n).into_par_iter().for_each(|i| row(parity + 2 * i));
            } else {
                (0..n).for_each(|i| row(parity + 2 * i));
            }
        }
    }

    /// The forces of element row `ez`.
    #[inline(always)]
    fn row<const M: usize, const L: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
    ) {
        if self.antiplane {
            self.row_sh::<M, L>(r, ez, u, out);
        } else {
            self.row_psv::<M, L>(r, ez, u, out);
        }
    }

    /// [`Stiffness::row`] compiled for AVX2: the same operations in the same order on
    /// wider vectors (no fused multiply-add: Rust does not contract `a * b + c`), so the
    /// same bits as the baseline build.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn row_avx2<const M: usize>(&self, r: &Rule<M>, ez: usize, u: &[f64], out: &mut [f64]) {
        self.row::<M, LANES>(r, ez, u, out);
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
        self.row::<M, LANES_512>(r, ez, u, out);
    }

    /// The forces of element row `ez`, `LANES` elements at a time.
    #[inline(always)]
    fn row_psv<const M: usize, const LANES: usize>(
        &self,
        r: &Rule<M>,
        ez: usize,
        u: &[f64],
        out: &mut [f64],
    ) {
        let nex = self.dims.0;
        let (d, w) = (&r.d, &r.w);
        let mut ex0 = 0;
        // the element block's scratch, once per row (no clearing per block: the lanes past
        // the row's end keep the last block's finite values, computed and never scattered)
        let mut ux = [[[0.0f64; LANES]; M]; M];
        let mut uz = [[[0.0f64; LANES]; M]; M];
        let mut fxx = [[[0.0f64; LANES]; M]; M];
        let mut fxz = [[[0.0f64; LANES]; M]; M];
        let mut fzx = [[[0.0f64; LANES]; M]; M];
        let mut fzz = [[[0.0f64; LANES]; M]; M];
        let mut gx = [[[0.0f64; LANES]; M]; M];
        let mut gz = [[[0.0f64; LANES]; M]; M];
        while ex0 < nex {
            let nl = LANES.min(nex - ex0);
            let e0 = ez * nex + ex0;
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
                let el = &self.elements[e0 + l];
                sx[l] = 2.0 / el.hx;
                sz[l] = 2.0 / el.hz;
                l2m[l] = el.lambda + 2.0 * el.mu;
                lam[l] = el.lambda;
                mu[l] = el.mu;
                hx2[l] = 0.5 * el.hx;
                hz2[l] = 0.5 * el.hz;
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        let g = conn[b * M + a] as usize;
                        ux[b][a][l] = u[2 * g];
                        uz[b][a][l] = u[2 * g + 1];
                    }
                }
            }
            // the x-flux `(hz/2) w_a w_b sigma_ix` and the z-flux `(hx/2) w_a w_b sigma_iz`
            // of each component i at each quadrature point (dA sx = (hx hz / 4) w_a w_b
            // (2 / hx), and alike along z)
            for b in 0..M {
                for a in 0..M {
                    let (mut dux_dx, mut duz_dx, mut dux_dz, mut duz_dz) =
                        ([0.0; LANES], [0.0; LANES], [0.0; LANES], [0.0; LANES]);
                    for k in 0..M {
                        let (da, db) = (d[a][k], d[b][k]);
                        for l in 0..LANES {
                            dux_dx[l] += da * ux[b][k][l];
                            duz_dx[l] += da * uz[b][k][l];
                            dux_dz[l] += db * ux[k][a][l];
                            duz_dz[l] += db * uz[k][a][l];
                        }
                    }
                    let wab = w[a] * w[b];
                    for l in 0..LANES {
                        let (exx, ezz) = (dux_dx[l] * sx[l], duz_dz[l] * sz[l]);
                        let exz = dux_dz[l] * sz[l] + duz_dx[l] * sx[l];
                        let sxx = l2m[l] * exx + lam[l] * ezz;
                        let szz = lam[l] * exx + l2m[l] * ezz;
                        let sxz = mu[l] * exz;
                        let (wx, wz) = (hz2[l] * wab, hx2[l] * wab);
                        fxx[b][a][l] = wx * sxx;
                        fzx[b][a][l] = wx * sxz;
                        fxz[b][a][l] = wz * sxz;
                        fzz[b][a][l] = wz * szz;
                    }
                }
            }
            for b in 0..M {
                for a in 0..M {
                    let (mut sx, mut sz) = ([0.0f64; LANES], [0.0f64; LANES]);
                    for k in 0..M {
                        let (dka, dkb) = (d[k][a], d[k][b]);
                        for l in 0..LANES {
                            sx[l] += dka * fxx[b][k][l] + dkb * fxz[k][a][l];
                            sz[l] += dka * fzx[b][k][l] + dkb * fzz[k][a][l];
                        }
                    }
                    gx[b][a] = sx;
                    gz[b][a] = sz;
                }
            }
            // scatter element by element, left to right (the order of every run)
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
        let (d, w) = (&r.d, &r.w);
        let mut ex0 = 0;
        // the block's scratch, once per row (as in [`Stiffness::row_psv`])
        let mut uy = [[[0.0f64; LANES]; M]; M];
        let mut fx = [[[0.0f64; LANES]; M]; M];
        let mut fz = [[[0.0f64; LANES]; M]; M];
        let mut g = [[[0.0f64; LANES]; M]; M];
        while ex0 < nex {
            let nl = LANES.min(nex - ex0);
            let e0 = ez * nex + ex0;
            let (mut cx, mut cz) = ([0.0; LANES], [0.0; LANES]);
            for l in 0..nl {
                let el = &self.elements[e0 + l];
                // (hz/2) mu sx and (hx/2) mu sz
                cx[l] = 0.5 * el.hz * el.mu * (2.0 / el.hx);
                cz[l] = 0.5 * el.hx * el.mu * (2.0 / el.hz);
                let conn = &self.conn[(e0 + l) * M * M..(e0 + l + 1) * M * M];
                for b in 0..M {
                    for a in 0..M {
                        uy[b][a][l] = u[conn[b * M + a] as usize];
                    }
                }
            }
            for b in 0..M {
                for a in 0..M {
                    let (mut dx, mut dz) = ([0.0; LANES], [0.0; LANES]);
                    for k in 0..M {
                        let (da, db) = (d[a][k], d[b][k]);
                        for l in 0..LANES {
                            dx[l] += da * uy[b][k][l];
                            dz[l] += db * uy[k][a][l];
                        }
                    }
                    let wab = w[a] * w[b];
                    for l in 0..LANES {
                        fx[b][a][l] = wab * cx[l] * dx[l];
                        fz[b][a][l] = wab * cz[l] * dz[l];
                    }
                }
            }
            for b in 0..M {
                for a in 0..M {
                    let mut sum = [0.0f64; LANES];
                    for k in 0..M {
                        let (dka, dkb) = (d[k][a], d[k][b]);
                        for l in 0..LANES {
                            sum[l] += dka * fx[b][k][l] + dkb * fz[k][a][l];
                        }
                    }
                    g[b][a] = sum;
                }
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

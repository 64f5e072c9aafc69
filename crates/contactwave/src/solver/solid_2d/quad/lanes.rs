//! The production path of the quadrilateral kernel: [`W`] consecutive elements of a tile at a
//! time, one per vector lane. A batch holds elements of one kind (axis-aligned rectangles:
//! a few constants a lane; general: the per-point metric, stored lane-fastest so that it
//! loads as vectors). Its nodes' displacements are gathered into lane blocks, the element
//! forces computed on registers by [`crate::solver::solid_2d::registers`] (the rectangle
//! kernel's even-odd derivative and column-in-registers order; a rectangle batch takes the
//! rectangle solver's own element forces), and the lanes scatter one after another, each
//! element's points in order (the element loop's order of assembly). AVX-512 takes a batch
//! in one block of eight, AVX2 in two of four; without either, [`portable`] runs the
//! element loop's arithmetic on the batch's data. The forces are the element loop's
//! ([`super::kernel`]) to round-off.

use crate::solver::solid_2d::lines::Rule;

/// Elements per batch (lanes of an AVX-512 register of doubles).
pub const W: usize = 8;

/// The batches of one operator: lane-fastest copies of what the element loop reads.
#[derive(Debug, Clone, Default)]
pub struct Batches {
    /// Per batch: how many lanes are elements (the rest repeat the last, not scattered).
    pub count: Vec<u8>,
    /// Per batch: rectangles (else general).
    pub rect: Vec<bool>,
    /// Per batch: `[l][lane]` node indices, `m^2 W` a batch.
    pub conn: Vec<u32>,
    /// Per batch: `lambda + 2 mu`, `lambda`, `mu` per lane (Pa), `3 W` a batch.
    pub lame: Vec<f64>,
    /// Per batch: general: the metric (`5 m^2 W`: `xi_x, xi_z, eta_x, eta_z` in 1/m, `w
    /// J` in m^2) in the order the kernel reads it, `[block][a][b][5][lane]` (blocks of
    /// `block` lanes, each point's column `a` outermost: one stream a batch); rectangle:
    /// `[RECT_COEFS][lane]` (`xi_x, eta_z` in 1/m, `J` in m^2, `J eta_z = hx / 2`, `J
    /// xi_x = hz / 2` in m), at `offset[batch]`.
    pub geometry: Vec<f64>,
    /// Start of each batch's geometry in `geometry`.
    pub offset: Vec<usize>,
    /// The batches of each tile (consecutive).
    pub tiles: Vec<std::ops::Range<usize>>,
    /// The tiles of each colour.
    pub colours: Vec<Vec<u32>>,
    /// Lanes of a block of the general metric (the instruction set's vector).
    pub block: usize,
}

impl Batches {
    /// Where the metric component `c` of point `(a, b)` (column `a`, row `b`) of lane `j`
    /// sits in a general batch's geometry, at `M` points per edge.
    #[inline(always)]
    pub fn metric_at<const M: usize>(&self, a: usize, b: usize, c: usize, j: usize) -> usize {
        let (h, jj) = (j / self.block, j % self.block);
        ((((h * M + a) * M + b) * 5 + c) * self.block) + jj
    }
}

/// Constants a lane of a rectangle batch.
const RECT_COEFS: usize = 5;

impl Batches {
    /// Batch each tile's elements, [`W`] consecutive ones a batch (a batch of rectangles
    /// only takes their fast path; one with a general element takes the metric of all),
    /// from the element data: `conn` (`m^2` an element), `metric` (per point), `rect`
    /// (per element `Some([xi_x, eta_z, J])`), `lame` (`[lambda, mu]`, Pa), for `isa`.
    /// Lanes of a batch may share nodes: they scatter one after another.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        isa: Isa,
        m: usize,
        tiles: &[std::ops::Range<u32>],
        colours: &[Vec<u32>],
        conn: &[u32],
        metric: &[[f64; 5]],
        rect: &[Option<[f64; 3]>],
        lame: &[[f64; 2]],
    ) -> Batches {
        let mm = m * m;
        let block = match isa {
            Isa::Avx512 => 8,
            Isa::Avx2 | Isa::Portable => 4,
        };
        let mut b = Batches {
            colours: colours.to_vec(),
            block,
            ..Default::default()
        };
        for tile in tiles {
            let start = b.count.len();
            let elems: Vec<u32> = (tile.start..tile.end).collect();
            for chunk in elems.chunks(W) {
                let lane = |j: usize| chunk[j.min(chunk.len() - 1)] as usize;
                let all_rect = chunk.iter().all(|&e| rect[e as usize].is_some());
                b.count.push(chunk.len() as u8);
                b.rect.push(all_rect);
                for l in 0..mm {
                    for j in 0..W {
                        b.conn.push(conn[lane(j) * mm + l]);
                    }
                }
                let lambda: [f64; W] = std::array::from_fn(|j| lame[lane(j)][0]);
                let mu: [f64; W] = std::array::from_fn(|j| lame[lane(j)][1]);
                b.lame.extend((0..W).map(|j| lambda[j] + 2.0 * mu[j]));
                b.lame.extend(lambda);
                b.lame.extend(mu);
                b.offset.push(b.geometry.len());
                if all_rect {
                    let coefs = |j: usize| {
                        let [cx, cz, jac] = rect[lane(j)].unwrap_or([1.0, 1.0, 0.0]);
                        [cx, cz, jac, jac * cz, jac * cx]
                    };
                    for c in 0..RECT_COEFS {
                        b.geometry.extend((0..W).map(|j| coefs(j)[c]));
                    }
                } else {
                    for h in 0..W / block {
                        for a in 0..m {
                            for bb in 0..m {
                                for c in 0..5 {
                                    b.geometry.extend(
                                        (h * block..(h + 1) * block)
                                            .map(|j| metric[lane(j) * mm + bb * m + a][c]),
                                    );
                                }
                            }
                        }
                    }
                }
            }
            b.tiles.push(start..b.count.len());
        }
        b
    }
}

/// The instruction set the batches run on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// One block of eight lanes a batch.
    Avx512,
    /// Two blocks of four.
    Avx2,
    /// [`portable`]: the element loop's arithmetic on each lane.
    Portable,
}

impl Isa {
    /// The best this CPU has.
    pub fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx512f") {
                return Isa::Avx512;
            }
            if std::is_x86_feature_detected!("avx2") {
                return Isa::Avx2;
            }
        }
        Isa::Portable
    }
}

/// The forces of the batches `range` (one tile) added to `f` (`-K u`, N/m), on the block
/// kernels of one instruction set (`$isa`, `$feature`): each batch in blocks of
/// `$isa::W` lanes, gathered, computed on registers, scattered lane after lane.
macro_rules! tile_kernel {
    ($name:ident, $isa:ident, $feature:literal) => {
        /// The batches `range` of `b` on the module's instruction set.
        ///
        /// # Safety
        /// The CPU has the instruction set; `f` points to a vector as long as `u`
        /// (`components` values a node), and no other thread writes the tile's nodes.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $feature)]
        pub unsafe fn $name<const M: usize>(
            b: &Batches,
            range: std::ops::Range<usize>,
            r: &Rule<M>,
            antiplane: bool,
            u: &[f64],
            f: *mut f64,
        ) {
            use crate::solver::solid_2d::lines::Params;
            use crate::solver::solid_2d::registers::$isa as k;
            const H: usize = k::W;
            let mm = M * M;
            // the scratch, once per tile (lanes past a batch's count repeat its last
            // element: finite values, computed and never scattered)
            let zero = [[[0.0f64; H]; M]; M];
            let (mut ux, mut uz, mut gx, mut gz) = (zero, zero, zero, zero);
            for i in range {
                let conn = &b.conn[i * mm * W..(i + 1) * mm * W];
                let lame = &b.lame[i * 3 * W..(i + 1) * 3 * W];
                let geo = &b.geometry[b.offset[i]..];
                let count = b.count[i] as usize;
                for h in 0..W / H {
                    let lanes = h * H..(h + 1) * H;
                    if count <= lanes.start {
                        break;
                    }
                    let per = |s: &[f64], c: usize| -> [f64; H] {
                        std::array::from_fn(|j| s[c * W + h * H + j])
                    };
                    let node = |l: usize, j: usize| conn[l * W + h * H + j] as usize;
                    if antiplane {
                        for j in 0..H {
                            for l in 0..mm {
                                ux[l / M][l % M][j] = u[node(l, j)];
                            }
                        }
                        // SAFETY: the caller's CPU; a general batch holds 5 m^2 W metric
                        // values from its offset, its blocks of H lanes one after another
                        // (`Batches::block` is H: the operator's instruction set)
                        unsafe {
                            if b.rect[i] {
                                let coefs = [per(geo, 0), per(geo, 1), per(geo, 2), per(lame, 2)];
                                k::sh_rectangle::<M>(r, &ux, &coefs, &mut gx);
                            } else {
                                let metric = geo[h * 5 * mm * H..(h + 1) * 5 * mm * H].as_ptr();
                                k::sh_general::<M>(r, &ux, metric, &per(lame, 2), &mut gx);
                            }
                        }
                        for j in 0..count.min(lanes.end) - lanes.start {
                            for l in 0..mm {
                                // SAFETY: the caller's contract
                                unsafe { *f.add(node(l, j)) -= gx[l / M][l % M][j] };
                            }
                        }
                        continue;
                    }
                    for j in 0..H {
                        for l in 0..mm {
                            let g = node(l, j);
                            ux[l / M][l % M][j] = u[2 * g];
                            uz[l / M][l % M][j] = u[2 * g + 1];
                        }
                    }
                    // SAFETY: as above
                    unsafe {
                        if b.rect[i] {
                            let p = Params {
                                sx: per(geo, 0),
                                sz: per(geo, 1),
                                l2m: per(lame, 0),
                                lam: per(lame, 1),
                                mu: per(lame, 2),
                                hx2: per(geo, 3),
                                hz2: per(geo, 4),
                            };
                            k::psv_block::<M>(r, &ux, &uz, &p, &mut gx, &mut gz);
                        } else {
                            let metric = geo[h * 5 * mm * H..(h + 1) * 5 * mm * H].as_ptr();
                            let lame = [per(lame, 0), per(lame, 1), per(lame, 2)];
                            k::psv_general::<M>(r, &ux, &uz, metric, &lame, &mut gx, &mut gz);
                        }
                    }
                    for j in 0..count.min(lanes.end) - lanes.start {
                        for l in 0..mm {
                            let g = node(l, j);
                            // SAFETY: the caller's contract
                            unsafe {
                                *f.add(2 * g) -= gx[l / M][l % M][j];
                                *f.add(2 * g + 1) -= gz[l / M][l % M][j];
                            }
                        }
                    }
                }
            }
        }
    };
}

tile_kernel!(tile_avx512, avx512, "avx512f,avx2");
tile_kernel!(tile_avx2, avx2, "avx2");

/// The batches `range` of `b` without vector extensions: each lane by the element loop's
/// arithmetic (`d`: the derivative matrix, `w`: the GLL weights of order `M - 1`).
///
/// # Safety
/// As the vector kernels' (`tile_avx2`), less the instruction set.
pub unsafe fn portable<const M: usize>(
    b: &Batches,
    range: std::ops::Range<usize>,
    d: &[f64],
    w: &[f64],
    antiplane: bool,
    u: &[f64],
    f: *mut f64,
) {
    let mm = M * M;
    let c = if antiplane { 1 } else { 2 };
    let mut uu = [[[0.0f64; M]; M]; 2];
    let mut flux = [[[0.0f64; M]; M]; 4];
    for i in range {
        let conn = &b.conn[i * mm * W..(i + 1) * mm * W];
        let lame = &b.lame[i * 3 * W..(i + 1) * 3 * W];
        let geo = &b.geometry[b.offset[i]..];
        for j in 0..b.count[i] as usize {
            let node = |l: usize| conn[l * W + j] as usize;
            for l in 0..mm {
                for k in 0..c {
                    uu[k][l / M][l % M] = u[c * node(l) + k];
                }
            }
            let (l2m, lam, mu) = (lame[j], lame[W + j], lame[2 * W + j]);
            for bb in 0..M {
                for a in 0..M {
                    // the reference gradients of each component
                    let mut grad = [[0.0; 2]; 2];
                    for k in 0..M {
                        for (cc, g) in grad.iter_mut().enumerate().take(c) {
                            g[0] += d[a * M + k] * uu[cc][bb][k];
                            g[1] += d[bb * M + k] * uu[cc][k][a];
                        }
                    }
                    let [xx, xz, ex, ez, wj] = if b.rect[i] {
                        let at = |c: usize| geo[c * W + j];
                        [at(0), 0.0, 0.0, at(1), w[a] * w[bb] * at(2)]
                    } else {
                        std::array::from_fn(|cc| geo[b.metric_at::<M>(a, bb, cc, j)])
                    };
                    let phys = |g: [f64; 2]| [g[0] * xx + g[1] * ex, g[0] * xz + g[1] * ez];
                    let along =
                        |s: [f64; 2]| [wj * (s[0] * xx + s[1] * xz), wj * (s[0] * ex + s[1] * ez)];
                    if antiplane {
                        let [dx, dz] = phys(grad[0]);
                        let [f1, f2] = along([mu * dx, mu * dz]);
                        (flux[0][bb][a], flux[2][bb][a]) = (f1, f2);
                    } else {
                        let ([dux_dx, dux_dz], [duz_dx, duz_dz]) = (phys(grad[0]), phys(grad[1]));
                        let sxx = l2m * dux_dx + lam * duz_dz;
                        let szz = lam * dux_dx + l2m * duz_dz;
                        let sxz = mu * (dux_dz + duz_dx);
                        let ([f1x, f2x], [f1z, f2z]) = (along([sxx, sxz]), along([sxz, szz]));
                        (flux[0][bb][a], flux[1][bb][a]) = (f1x, f1z);
                        (flux[2][bb][a], flux[3][bb][a]) = (f2x, f2z);
                    }
                }
            }
            for bb in 0..M {
                for a in 0..M {
                    let g = node(bb * M + a);
                    for k in 0..c {
                        let mut s = 0.0;
                        for q in 0..M {
                            s += d[q * M + a] * flux[k][bb][q] + d[q * M + bb] * flux[2 + k][q][a];
                        }
                        // SAFETY: the caller's contract
                        unsafe { *f.add(c * g + k) -= s };
                    }
                }
            }
        }
    }
}

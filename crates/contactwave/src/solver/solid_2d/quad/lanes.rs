//! The production path of the quadrilateral kernel: [`W`] consecutive elements of a tile at a time,
//! one per vector lane (the element loop of [`super::kernel`] with every operation done on
//! `W` elements at once, compiled for AVX-512 and AVX2 where the CPU has them), the GLL
//! order a compile-time constant so that the small loops unroll. A batch holds elements of
//! one kind (axis-aligned rectangles: two constants a lane; general: the per-point metric,
//! stored lane-fastest so that it loads as vectors). Each lane does the scalar element's
//! operations in the scalar's order, and the lanes scatter one after another (they may
//! share nodes), so the forces are the element loop's to round-off (its bits where a
//! batch's elements are all of one kind).

use multiversion::multiversion;

/// Elements per batch (lanes of an AVX-512 register of doubles).
pub const W: usize = 8;
/// Largest GLL points per element the buffers hold (order 8).
const MM: usize = 81;

/// The batches of one operator: lane-fastest copies of what the element loop reads.
#[derive(Debug, Clone, Default)]
pub struct Batches {
    /// Per batch: how many lanes are elements (the rest repeat the last, not scattered).
    pub count: Vec<u8>,
    /// Per batch: rectangles (else general).
    pub rect: Vec<bool>,
    /// Per batch: `[l][lane]` node indices, `m^2 W` a batch.
    pub conn: Vec<u32>,
    /// Per batch: lambda and mu per lane, `2 W` a batch.
    pub lame: Vec<f64>,
    /// Per batch: general: `[l][5][lane]` metric (`5 m^2 W`); rectangle: `[3][lane]`
    /// (`xi_x, eta_z, J`), at `offset[batch]`.
    pub geometry: Vec<f64>,
    /// Start of each batch's geometry in `geometry`.
    pub offset: Vec<usize>,
    /// The batches of each tile (consecutive).
    pub tiles: Vec<std::ops::Range<usize>>,
    /// The tiles of each colour.
    pub colours: Vec<Vec<u32>>,
}

impl Batches {
    /// Batch each tile's elements, [`W`] consecutive ones a batch (a batch of rectangles
    /// only takes their fast path; one with a general element takes the metric of all),
    /// from the element data: `conn` (`m^2` an element), `metric` (per point), `rect`
    /// (per element `Some([xi_x, eta_z, J])`), `lame`. Lanes of a batch may share nodes:
    /// they scatter one after another.
    pub fn new(
        m: usize,
        tiles: &[std::ops::Range<u32>],
        colours: &[Vec<u32>],
        conn: &[u32],
        metric: &[[f64; 5]],
        rect: &[Option<[f64; 3]>],
        lame: &[[f64; 2]],
    ) -> Batches {
        let mm = m * m;
        let mut b = Batches {
            colours: colours.to_vec(),
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
                for c in 0..2 {
                    for j in 0..W {
                        b.lame.push(lame[lane(j)][c]);
                    }
                }
                b.offset.push(b.geometry.len());
                if all_rect {
                    for c in 0..3 {
                        for j in 0..W {
                            b.geometry.push(rect[lane(j)].map_or(0.0, |r| r[c]));
                        }
                    }
                } else {
                    for l in 0..mm {
                        for c in 0..5 {
                            for j in 0..W {
                                b.geometry.push(metric[lane(j) * mm + l][c]);
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

/// The P-SV forces of batch `i` added to `f` (`u`, `f`: two components a node).
///
/// # Safety
/// `f` points to a vector as long as `u`, and no other thread writes the batch's nodes.
#[multiversion(targets("x86_64+avx512f+avx2+avx", "x86_64+avx2+avx"))]
pub unsafe fn batch_psv<const M: usize, const RECT: bool>(
    b: &Batches,
    i: usize,
    d: &[f64],
    w: &[f64],
    u: &[f64],
    f: *mut f64,
) {
    let mm = M * M;
    let d = &d[..mm];
    let w = &w[..M];
    let conn = &b.conn[i * mm * W..(i + 1) * mm * W];
    let lame = &b.lame[i * 2 * W..(i + 1) * 2 * W];
    let (mut ux, mut uz) = ([[0.0f64; W]; MM], [[0.0f64; W]; MM]);
    for l in 0..mm {
        for j in 0..W {
            let g = conn[l * W + j] as usize;
            ux[l][j] = u[2 * g];
            uz[l][j] = u[2 * g + 1];
        }
    }
    let mut lambda = [0.0; W];
    let mut mu = [0.0; W];
    let mut l2m = [0.0; W];
    for j in 0..W {
        lambda[j] = lame[j];
        mu[j] = lame[W + j];
        l2m[j] = lambda[j] + 2.0 * mu[j];
    }
    let (mut f1x, mut f1z, mut f2x, mut f2z) = (
        [[0.0f64; W]; MM],
        [[0.0f64; W]; MM],
        [[0.0f64; W]; MM],
        [[0.0f64; W]; MM],
    );
    let geo = &b.geometry[b.offset[i]..];
    for bb in 0..M {
        for a in 0..M {
            let l = bb * M + a;
            let (mut xi_x, mut xi_z, mut e_x, mut e_z) = ([0.0; W], [0.0; W], [0.0; W], [0.0; W]);
            for k in 0..M {
                let da = d[a * M + k];
                let db = d[bb * M + k];
                let (p, q) = (bb * M + k, k * M + a);
                for j in 0..W {
                    xi_x[j] += da * ux[p][j];
                    xi_z[j] += da * uz[p][j];
                    e_x[j] += db * ux[q][j];
                    e_z[j] += db * uz[q][j];
                }
            }
            if RECT {
                let (cx, cz, jac) = (&geo[..W], &geo[W..2 * W], &geo[2 * W..3 * W]);
                for j in 0..W {
                    let (dux_dx, duz_dz) = (xi_x[j] * cx[j], e_z[j] * cz[j]);
                    let shear = mu[j] * (e_x[j] * cz[j] + xi_z[j] * cx[j]);
                    let sxx = l2m[j] * dux_dx + lambda[j] * duz_dz;
                    let szz = lambda[j] * dux_dx + l2m[j] * duz_dz;
                    let wj = w[a] * w[bb] * jac[j];
                    f1x[l][j] = wj * sxx * cx[j];
                    f1z[l][j] = wj * shear * cx[j];
                    f2x[l][j] = wj * shear * cz[j];
                    f2z[l][j] = wj * szz * cz[j];
                }
            } else {
                let g = &geo[l * 5 * W..(l + 1) * 5 * W];
                for j in 0..W {
                    let (xx, xz, ex, ez, wj) =
                        (g[j], g[W + j], g[2 * W + j], g[3 * W + j], g[4 * W + j]);
                    let dux_dx = xi_x[j] * xx + e_x[j] * ex;
                    let dux_dz = xi_x[j] * xz + e_x[j] * ez;
                    let duz_dx = xi_z[j] * xx + e_z[j] * ex;
                    let duz_dz = xi_z[j] * xz + e_z[j] * ez;
                    let sxx = l2m[j] * dux_dx + lambda[j] * duz_dz;
                    let szz = lambda[j] * dux_dx + l2m[j] * duz_dz;
                    let sxz = mu[j] * (dux_dz + duz_dx);
                    f1x[l][j] = wj * (sxx * xx + sxz * xz);
                    f1z[l][j] = wj * (sxz * xx + szz * xz);
                    f2x[l][j] = wj * (sxx * ex + sxz * ez);
                    f2z[l][j] = wj * (sxz * ex + szz * ez);
                }
            }
        }
    }
    let count = b.count[i] as usize;
    for bb in 0..M {
        for a in 0..M {
            // (each sum in its own loop over the lanes: vectors across the elements)
            let (mut fx, mut fz) = ([0.0; W], [0.0; W]);
            for k in 0..M {
                let (da, row_x, row_z) = (d[k * M + a], &f1x[bb * M + k], &f1z[bb * M + k]);
                for j in 0..W {
                    fx[j] += da * row_x[j];
                }
                for j in 0..W {
                    fz[j] += da * row_z[j];
                }
            }
            for k in 0..M {
                let (db, col_x, col_z) = (d[k * M + bb], &f2x[k * M + a], &f2z[k * M + a]);
                for j in 0..W {
                    fx[j] += db * col_x[j];
                }
                for j in 0..W {
                    fz[j] += db * col_z[j];
                }
            }
            let l = bb * M + a;
            for j in 0..count {
                let g = conn[l * W + j] as usize;
                // SAFETY: the caller's contract
                unsafe {
                    *f.add(2 * g) -= fx[j];
                    *f.add(2 * g + 1) -= fz[j];
                }
            }
        }
    }
}

/// The antiplane forces of batch `i` added to `f` (one component a node).
///
/// # Safety
/// As [`batch_psv`].
#[multiversion(targets("x86_64+avx512f+avx2+avx", "x86_64+avx2+avx"))]
pub unsafe fn batch_sh<const M: usize, const RECT: bool>(
    b: &Batches,
    i: usize,
    d: &[f64],
    w: &[f64],
    u: &[f64],
    f: *mut f64,
) {
    let mm = M * M;
    let d = &d[..mm];
    let w = &w[..M];
    let conn = &b.conn[i * mm * W..(i + 1) * mm * W];
    let mu = &b.lame[i * 2 * W + W..(i + 1) * 2 * W];
    let mut uy = [[0.0f64; W]; MM];
    for l in 0..mm {
        for j in 0..W {
            uy[l][j] = u[conn[l * W + j] as usize];
        }
    }
    let (mut f1, mut f2) = ([[0.0f64; W]; MM], [[0.0f64; W]; MM]);
    let geo = &b.geometry[b.offset[i]..];
    for bb in 0..M {
        for a in 0..M {
            let l = bb * M + a;
            let (mut dxi, mut deta) = ([0.0; W], [0.0; W]);
            for k in 0..M {
                let (da, db) = (d[a * M + k], d[bb * M + k]);
                let (p, q) = (bb * M + k, k * M + a);
                for j in 0..W {
                    dxi[j] += da * uy[p][j];
                    deta[j] += db * uy[q][j];
                }
            }
            if RECT {
                let (cx, cz, jac) = (&geo[..W], &geo[W..2 * W], &geo[2 * W..3 * W]);
                for j in 0..W {
                    let wj = w[a] * w[bb] * jac[j];
                    f1[l][j] = wj * mu[j] * dxi[j] * cx[j] * cx[j];
                    f2[l][j] = wj * mu[j] * deta[j] * cz[j] * cz[j];
                }
            } else {
                let g = &geo[l * 5 * W..(l + 1) * 5 * W];
                for j in 0..W {
                    let (xx, xz, ex, ez, wj) =
                        (g[j], g[W + j], g[2 * W + j], g[3 * W + j], g[4 * W + j]);
                    let syx = mu[j] * (dxi[j] * xx + deta[j] * ex);
                    let syz = mu[j] * (dxi[j] * xz + deta[j] * ez);
                    f1[l][j] = wj * (syx * xx + syz * xz);
                    f2[l][j] = wj * (syx * ex + syz * ez);
                }
            }
        }
    }
    let count = b.count[i] as usize;
    for bb in 0..M {
        for a in 0..M {
            let mut fy = [0.0; W];
            for k in 0..M {
                let (da, row) = (d[k * M + a], &f1[bb * M + k]);
                for j in 0..W {
                    fy[j] += da * row[j];
                }
            }
            for k in 0..M {
                let (db, col) = (d[k * M + bb], &f2[k * M + a]);
                for j in 0..W {
                    fy[j] += db * col[j];
                }
            }
            let l = bb * M + a;
            for j in 0..count {
                let g = conn[l * W + j] as usize;
                // SAFETY: the caller's contract
                unsafe { *f.add(g) -= fy[j] };
            }
        }
    }
}

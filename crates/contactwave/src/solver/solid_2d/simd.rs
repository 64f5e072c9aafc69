//! The AVX-512 gather, scatter and element forces of the bulk kernel ([`super::kernel`])
//! for plane-strain elements of any order (`M` GLL points a side), eight elements at a
//! time (one per lane), where the eight elements of a row block sit on the node grid
//! without split nodes or a periodic wrap ("regular"): each node row of the block is then
//! `8 (M - 1) + 1` consecutive nodes (`[x, z]` interleaved), lane `l` starting at node
//! `(M - 1) l`. Its first `M - 1` nodes (`2 (M - 1)` doubles) come in chunks of eight
//! doubles, one (masked) load per lane and an 8 x 8 transpose per chunk giving the lane
//! vectors `u_x(a)`, `u_z(a)` of local columns `a = 0..M-2`; a lane shift and one more
//! masked load give column `M - 1` (the next element's column 0). The scatter is the same
//! backwards, subtracting in the order of the element-by-element scatter (left to right:
//! a node shared by two elements of the row gets the left one's contribution first), so
//! the bits are those of the scalar gather and scatter.

#[cfg(target_arch = "x86_64")]
pub(super) use super::registers::avx512::Block;
#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// Elements per block (AVX-512 lanes).
pub(super) const W: usize = 8;

/// The offsets `b R + (M - 1) l + a` of the nodes of a regular block from its first node,
/// in the order of the element-to-node map (element `l`, row `b`, column `a`), for a node
/// row stride `r` and `m` GLL points a side.
pub(super) fn block_offsets(m: usize, r: u32) -> Vec<u32> {
    let mut o = Vec::with_capacity(W * m * m);
    for l in 0..W {
        for b in 0..m {
            for a in 0..m {
                o.push((b as u32).wrapping_mul(r) + ((m - 1) * l + a) as u32);
            }
        }
    }
    o
}

/// Whether the block's map `conn` (eight elements' `m^2` nodes) is `first + offsets`:
/// regular (no early exit, so that it vectorises).
pub(super) fn is_regular(conn: &[u32], offsets: &[u32]) -> bool {
    let first = conn[0];
    conn.len() == offsets.len()
        && conn
            .iter()
            .zip(offsets)
            .fold(true, |ok, (&c, &o)| ok & (c == first.wrapping_add(o)))
}

/// `columns[k][l] = rows[l][k]`.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn transpose(r: [__m512d; 8]) -> [__m512d; 8] {
    // pairs of rows: even and odd columns
    let t0 = _mm512_unpacklo_pd(r[0], r[1]);
    let t1 = _mm512_unpackhi_pd(r[0], r[1]);
    let t2 = _mm512_unpacklo_pd(r[2], r[3]);
    let t3 = _mm512_unpackhi_pd(r[2], r[3]);
    let t4 = _mm512_unpacklo_pd(r[4], r[5]);
    let t5 = _mm512_unpackhi_pd(r[4], r[5]);
    let t6 = _mm512_unpacklo_pd(r[6], r[7]);
    let t7 = _mm512_unpackhi_pd(r[6], r[7]);
    // quadruples of rows: columns {0, 4}, {2, 6} (from the even) and {1, 5}, {3, 7}
    let lo = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
    let hi = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
    let u0 = _mm512_permutex2var_pd(t0, lo, t2);
    let u2 = _mm512_permutex2var_pd(t0, hi, t2);
    let u1 = _mm512_permutex2var_pd(t1, lo, t3);
    let u3 = _mm512_permutex2var_pd(t1, hi, t3);
    let u4 = _mm512_permutex2var_pd(t4, lo, t6);
    let u6 = _mm512_permutex2var_pd(t4, hi, t6);
    let u5 = _mm512_permutex2var_pd(t5, lo, t7);
    let u7 = _mm512_permutex2var_pd(t5, hi, t7);
    // the eight rows: the low and high 256 bits of the quadruples
    [
        _mm512_shuffle_f64x2::<0x44>(u0, u4),
        _mm512_shuffle_f64x2::<0x44>(u1, u5),
        _mm512_shuffle_f64x2::<0x44>(u2, u6),
        _mm512_shuffle_f64x2::<0x44>(u3, u7),
        _mm512_shuffle_f64x2::<0xEE>(u0, u4),
        _mm512_shuffle_f64x2::<0xEE>(u1, u5),
        _mm512_shuffle_f64x2::<0xEE>(u2, u6),
        _mm512_shuffle_f64x2::<0xEE>(u3, u7),
    ]
}

/// The mask of the first `n` (at most 8) doubles of a chunk.
#[inline(always)]
const fn chunk_mask(n: usize) -> u8 {
    if n >= 8 {
        0xFF
    } else {
        ((1u16 << n) - 1) as u8
    }
}

/// The first `n` doubles of a chunk at `p` (the rest zero): a plain load of 8, 4 or 2
/// doubles where `n` is one of them (masked loads and stores are slower on some CPUs), a
/// masked one otherwise.
///
/// # Safety
/// The CPU must have AVX-512F; `p` must be valid for `min(n, 8)` reads.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
unsafe fn load_chunk(p: *const f64, n: usize) -> __m512d {
    // SAFETY: `min(n, 8)` doubles from p (the caller's contract)
    unsafe {
        match n {
            8.. => _mm512_loadu_pd(p),
            4 => _mm512_zextpd256_pd512(_mm256_loadu_pd(p)),
            2 => _mm512_zextpd128_pd512(_mm_loadu_pd(p)),
            _ => _mm512_maskz_loadu_pd(chunk_mask(n), p),
        }
    }
}

/// Store the first `n` doubles of `v` at `p` ([`load_chunk`]'s counterpart).
///
/// # Safety
/// The CPU must have AVX-512F; `p` must be valid for `min(n, 8)` writes.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
unsafe fn store_chunk(p: *mut f64, n: usize, v: __m512d) {
    // SAFETY: `min(n, 8)` doubles from p (the caller's contract)
    unsafe {
        match n {
            8.. => _mm512_storeu_pd(p, v),
            4 => _mm256_storeu_pd(p, _mm512_castpd512_pd256(v)),
            2 => _mm_storeu_pd(p, _mm512_castpd512_pd128(v)),
            _ => _mm512_mask_storeu_pd(p, chunk_mask(n), v),
        }
    }
}

/// One node row of a regular block: the lane vectors `x[a]`, `z[a]` (`a = 0..M`) of the
/// `8 (M - 1) + 1` nodes starting at double `src` (`[x, z]` interleaved).
///
/// # Safety
/// The CPU must have AVX-512F; `src` must be valid for `2 (8 (M - 1) + 1)` reads.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn gather_row<const M: usize>(
    src: *const f64,
    x: &mut [[f64; W]; M],
    z: &mut [[f64; W]; M],
) {
    let d = 2 * (M - 1);
    for c in 0..d.div_ceil(8) {
        // SAFETY: lane l's chunk lies inside its 2 (M - 1) doubles
        let rows = [0, 1, 2, 3, 4, 5, 6, 7]
            .map(|l| unsafe { load_chunk(src.add(d * l + 8 * c), d - 8 * c) });
        let t = transpose(rows);
        for (j, tj) in t.iter().enumerate().take((d - 8 * c).min(8)) {
            let k = 8 * c + j;
            let dst = if k % 2 == 0 {
                &mut x[k / 2]
            } else {
                &mut z[k / 2]
            };
            // SAFETY: eight doubles
            unsafe { _mm512_storeu_pd(dst.as_mut_ptr(), *tj) };
        }
    }
    // column M - 1: the next element's column 0, the last lane's from node 8 (M - 1)
    // SAFETY: the row's last node
    let last = unsafe { load_chunk(src.add(8 * d), 2) };
    let shift_x = _mm512_set_epi64(8, 7, 6, 5, 4, 3, 2, 1);
    let shift_z = _mm512_set_epi64(9, 7, 6, 5, 4, 3, 2, 1);
    // SAFETY: eight doubles each
    unsafe {
        let (x0, z0) = (
            _mm512_loadu_pd(x[0].as_ptr()),
            _mm512_loadu_pd(z[0].as_ptr()),
        );
        _mm512_storeu_pd(
            x[M - 1].as_mut_ptr(),
            _mm512_permutex2var_pd(x0, shift_x, last),
        );
        _mm512_storeu_pd(
            z[M - 1].as_mut_ptr(),
            _mm512_permutex2var_pd(z0, shift_z, last),
        );
    }
}

/// One node row of a regular block: subtract the lane vectors `x[a]`, `z[a]` from the
/// `8 (M - 1) + 1` nodes starting at double `dst`, a node shared by lanes `l - 1` (its
/// column `M - 1`) and `l` (its column 0) taking lane `l - 1`'s first.
///
/// # Safety
/// The CPU must have AVX-512F; `dst` must be valid for `2 (8 (M - 1) + 1)` reads and
/// writes.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter_row<const M: usize>(
    dst: *mut f64,
    x: &[[f64; W]; M],
    z: &[[f64; W]; M],
) {
    let d = 2 * (M - 1);
    let chunks = d.div_ceil(8);
    // per chunk, per lane: the lane's doubles of the chunk (transposed columns)
    // (at most two chunks: M <= 9)
    let mut lanes = [[_mm512_setzero_pd(); 8]; 2];
    for c in 0..chunks {
        let cols = [0, 1, 2, 3, 4, 5, 6, 7].map(|j| {
            let k = 8 * c + j;
            if k >= d {
                _mm512_setzero_pd()
            } else {
                let g = if k % 2 == 0 { &x[k / 2] } else { &z[k / 2] };
                // SAFETY: eight doubles
                unsafe { _mm512_loadu_pd(g.as_ptr()) }
            }
        });
        lanes[c] = transpose(cols);
    }
    // SAFETY: eight doubles each
    let (xl, zl) = unsafe {
        (
            _mm512_loadu_pd(x[M - 1].as_ptr()),
            _mm512_loadu_pd(z[M - 1].as_ptr()),
        )
    };
    for l in 0..W {
        for c in 0..chunks {
            // SAFETY: lane l's chunk lies inside its 2 (M - 1) doubles
            let p = unsafe { dst.add(d * l + 8 * c) };
            let mut o = unsafe { load_chunk(p, d - 8 * c) };
            if c == 0 && l > 0 {
                // lane l - 1's column M - 1 into this lane's first node, zeros elsewhere
                let i = (l - 1) as i64;
                let idx = _mm512_set_epi64(0, 0, 0, 0, 0, 0, 8 + i, i);
                o = _mm512_sub_pd(o, _mm512_maskz_permutex2var_pd(0b11, xl, idx, zl));
            }
            // SAFETY: as the load
            unsafe { store_chunk(p, d - 8 * c, _mm512_sub_pd(o, lanes[c][l])) };
        }
    }
    // SAFETY: the row's last node
    let p = unsafe { dst.add(8 * d) };
    let idx = _mm512_set_epi64(0, 0, 0, 0, 0, 0, 15, 7);
    let o = unsafe { load_chunk(p, 2) };
    let o = _mm512_sub_pd(o, _mm512_maskz_permutex2var_pd(0b11, xl, idx, zl));
    unsafe { store_chunk(p, 2, o) };
}

/// The largest number of GLL points a side the row gather and scatter take (two chunks).
pub(super) const MAX_POINTS: usize = 9;

/// The nodes of one node row of a regular block.
const fn row_nodes(m: usize) -> usize {
    W * (m - 1) + 1
}

/// The gather of a regular block whose first node and node-row stride are `rows`: its
/// lane arrays `ux`, `uz` from `u` (`[x, z]` per node), row by row ([`gather_row`]).
///
/// # Safety
/// The CPU must have AVX-512F; `M <= MAX_POINTS`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn gather_block<const M: usize>(
    u: &[f64],
    rows: (usize, usize),
    ux: &mut Block<M>,
    uz: &mut Block<M>,
) {
    let n = 2 * row_nodes(M);
    for b in 0..M {
        let node = rows.0 + b * rows.1;
        assert!(2 * node + n <= u.len());
        // SAFETY: the row's values from node (asserted)
        unsafe { gather_row::<M>(u.as_ptr().add(2 * node), &mut ux[b], &mut uz[b]) };
    }
}

/// The scatter of a regular block ([`gather_block`], [`scatter_row`]).
///
/// # Safety
/// The CPU must have AVX-512F; `M <= MAX_POINTS`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter_block<const M: usize>(
    out: &mut [f64],
    rows: (usize, usize),
    gx: &Block<M>,
    gz: &Block<M>,
) {
    let n = 2 * row_nodes(M);
    for b in 0..M {
        let node = rows.0 + b * rows.1;
        assert!(2 * node + n <= out.len());
        // SAFETY: the row's values from node (asserted)
        unsafe { scatter_row::<M>(out.as_mut_ptr().add(2 * node), &gx[b], &gz[b]) };
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// The gather reads what the scalar map reads, and the scatter subtracts in the
    /// scalar order, bit for bit, for every order the solver takes.
    #[test]
    fn gather_and_scatter_match_the_scalar_map() {
        if !std::is_x86_feature_detected!("avx512f") {
            return;
        }
        fn check<const M: usize>() {
            let s = M - 1;
            let u: Vec<f64> = (0..2 * (row_nodes(M) + 4))
                .map(|i| (i as f64 * 0.37).sin() * 1e-3)
                .collect();
            let (mut x, mut z) = ([[0.0; W]; M], [[0.0; W]; M]);
            // SAFETY: AVX-512F checked; the row's values from node 2
            unsafe { gather_row::<M>(u.as_ptr().add(4), &mut x, &mut z) };
            for l in 0..W {
                for a in 0..M {
                    let node = 2 + s * l + a;
                    assert_eq!(x[a][l], u[2 * node], "{M}");
                    assert_eq!(z[a][l], u[2 * node + 1], "{M}");
                }
            }
            let g = |a: usize, l: usize, c: usize| ((a * 31 + l * 7 + c) as f64 * 0.91).cos();
            let (mut gx, mut gz) = ([[0.0; W]; M], [[0.0; W]; M]);
            for a in 0..M {
                for l in 0..W {
                    gx[a][l] = g(a, l, 0);
                    gz[a][l] = g(a, l, 1);
                }
            }
            let mut scalar = u.clone();
            for l in 0..W {
                for a in 0..M {
                    let node = 2 + s * l + a;
                    scalar[2 * node] -= gx[a][l];
                    scalar[2 * node + 1] -= gz[a][l];
                }
            }
            let mut fast = u.clone();
            // SAFETY: AVX-512F checked; the row's values from node 2
            unsafe { scatter_row::<M>(fast.as_mut_ptr().add(4), &gx, &gz) };
            assert_eq!(
                fast.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                scalar.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                "{M}"
            );
        }
        super::super::lines::for_every_order!(check);
    }
}

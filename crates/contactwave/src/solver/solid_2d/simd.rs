//! The AVX-512 gather and scatter of the bulk kernel ([`super::kernel`]) for plane-strain
//! elements of order 4 (five GLL points a side), eight elements at a time (one per lane),
//! where the eight elements of a row block sit on the node grid without split nodes or a
//! periodic wrap ("regular"): each node row of the block is then 33 consecutive nodes
//! (66 doubles, `[x, z]` interleaved), so that eight 8-double loads and an 8 x 8 transpose
//! give the lane vectors `u_x(a)`, `u_z(a)` of local columns `a = 0..3`, and one more
//! masked load and a lane shift give column 4 (the next element's column 0). The scatter
//! is the same backwards, subtracting in the order of the element-by-element scatter
//! (left to right: a node shared by two elements of the row gets the left one's
//! contribution first), so the bits are those of the scalar gather and scatter.

use super::lines::{EvenOdd, Params, Rule};
#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;
#[cfg(target_arch = "x86_64")]
use std::mem::MaybeUninit;

/// Elements per block (AVX-512 lanes).
pub(super) const W: usize = 8;
/// GLL points per element side (order 4).
pub(super) const P: usize = 5;

/// The offsets `b R + 4 l + a` of the nodes of a regular block from its first node, in
/// the order of the element-to-node map (element `l`, row `b`, column `a`), for a node
/// row stride `r`.
pub(super) fn block_offsets(r: u32) -> [u32; W * P * P] {
    let mut o = [0u32; W * P * P];
    for l in 0..W {
        for b in 0..P {
            for a in 0..P {
                o[(l * P + b) * P + a] = (b as u32).wrapping_mul(r) + (4 * l + a) as u32;
            }
        }
    }
    o
}

/// Whether the block's map `conn` (eight elements' `25` nodes) is `first + offsets`:
/// regular (no early exit, so that it vectorises).
pub(super) fn is_regular(conn: &[u32], offsets: &[u32; W * P * P]) -> bool {
    let first = conn[0];
    conn.len() == W * P * P
        && conn
            .iter()
            .zip(offsets)
            .fold(true, |ok, (&c, &o)| ok & (c == first.wrapping_add(o)))
}

/// `columns[k][l] = rows[l][k]`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn transpose(r: [__m512d; 8]) -> [__m512d; 8] {
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

/// One node row of a regular block: the lane vectors `x[a]`, `z[a]` (`a = 0..4`) of the
/// 33 nodes starting at double `src` (`[x, z]` interleaved).
///
/// # Safety
/// The CPU must have AVX-512F; `src` must be valid for 66 reads.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn gather_row(src: *const f64, x: &mut [[f64; W]; P], z: &mut [[f64; W]; P]) {
    let rows = [0, 1, 2, 3, 4, 5, 6, 7].map(|l| _mm512_loadu_pd(src.add(8 * l)));
    let c = transpose(rows);
    for a in 0..4 {
        _mm512_storeu_pd(x[a].as_mut_ptr(), c[2 * a]);
        _mm512_storeu_pd(z[a].as_mut_ptr(), c[2 * a + 1]);
    }
    // column 4: the next element's column 0, the last lane's from node 32
    let last = _mm512_maskz_loadu_pd(0b11, src.add(64));
    let shift_x = _mm512_set_epi64(8, 7, 6, 5, 4, 3, 2, 1);
    let shift_z = _mm512_set_epi64(9, 7, 6, 5, 4, 3, 2, 1);
    _mm512_storeu_pd(
        x[4].as_mut_ptr(),
        _mm512_permutex2var_pd(c[0], shift_x, last),
    );
    _mm512_storeu_pd(
        z[4].as_mut_ptr(),
        _mm512_permutex2var_pd(c[1], shift_z, last),
    );
}

/// One node row of a regular block: subtract the lane vectors `x[a]`, `z[a]` from the 33
/// nodes starting at double `dst`, a node shared by lanes `l - 1` (its column 4) and `l`
/// (its column 0) taking lane `l - 1`'s first.
///
/// # Safety
/// The CPU must have AVX-512F; `dst` must be valid for 66 reads and writes.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter_row(dst: *mut f64, x: &[[f64; W]; P], z: &[[f64; W]; P]) {
    let rows = [0, 1, 2, 3, 4, 5, 6, 7].map(|k| {
        let g = if k % 2 == 0 { &x[k / 2] } else { &z[k / 2] };
        _mm512_loadu_pd(g.as_ptr())
    });
    let c = transpose(rows);
    let (x4, z4) = (
        _mm512_loadu_pd(x[4].as_ptr()),
        _mm512_loadu_pd(z[4].as_ptr()),
    );
    for (l, cl) in c.iter().enumerate() {
        let p = dst.add(8 * l);
        let mut o = _mm512_loadu_pd(p);
        if l > 0 {
            // lane l - 1's column 4 into this chunk's first node, zeros elsewhere
            let i = (l - 1) as i64;
            let idx = _mm512_set_epi64(0, 0, 0, 0, 0, 0, 8 + i, i);
            o = _mm512_sub_pd(o, _mm512_maskz_permutex2var_pd(0b11, x4, idx, z4));
        }
        _mm512_storeu_pd(p, _mm512_sub_pd(o, *cl));
    }
    let p = dst.add(64);
    let idx = _mm512_set_epi64(0, 0, 0, 0, 0, 0, 15, 7);
    let o = _mm512_maskz_loadu_pd(0b11, p);
    let o = _mm512_sub_pd(o, _mm512_maskz_permutex2var_pd(0b11, x4, idx, z4));
    _mm512_mask_storeu_pd(p, 0b11, o);
}

/// The gather of a regular block whose first node and node-row stride are `rows`: its
/// lane arrays `ux`, `uz` from `u` (`[x, z]` per node), row by row ([`gather_row`]).
///
/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn gather_block(u: &[f64], rows: (usize, usize), ux: &mut Block, uz: &mut Block) {
    for b in 0..P {
        let node = rows.0 + b * rows.1;
        assert!(2 * node + 66 <= u.len());
        // SAFETY: 66 values from node (asserted)
        unsafe { gather_row(u.as_ptr().add(2 * node), &mut ux[b], &mut uz[b]) };
    }
}

/// The scatter of a regular block ([`gather_block`], [`scatter_row`]).
///
/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter_block(out: &mut [f64], rows: (usize, usize), gx: &Block, gz: &Block) {
    for b in 0..P {
        let node = rows.0 + b * rows.1;
        assert!(2 * node + 66 <= out.len());
        // SAFETY: 66 values from node (asserted)
        unsafe { scatter_row(out.as_mut_ptr().add(2 * node), &gx[b], &gz[b]) };
    }
}

/// An element block's lane arrays: `[b][a][lane]`.
pub(super) type Block = [[[f64; W]; P]; P];

/// `x (op) y` on eight lanes.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn add(x: __m512d, y: __m512d) -> __m512d {
    _mm512_add_pd(x, y)
}
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn sub(x: __m512d, y: __m512d) -> __m512d {
    _mm512_sub_pd(x, y)
}
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn mul(x: __m512d, y: __m512d) -> __m512d {
    _mm512_mul_pd(x, y)
}
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn splat(x: f64) -> __m512d {
    _mm512_set1_pd(x)
}

/// [`EvenOdd::apply`] of order 4 on registers: the same operations in the same order.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn even_odd(c: &EvenOdd<P>, x: [__m512d; P]) -> [__m512d; P] {
    let (s0, o0) = (add(x[0], x[4]), sub(x[0], x[4]));
    let (s1, o1) = (add(x[1], x[3]), sub(x[1], x[3]));
    let mut y = [x[2]; P];
    for a in 0..2 {
        let mut e = mul(splat(c.p[a][0]), s0);
        let mut od = mul(splat(c.q[a][0]), o0);
        e = add(e, mul(splat(c.p[a][1]), s1));
        od = add(od, mul(splat(c.q[a][1]), o1));
        e = add(e, mul(splat(c.mid[a]), x[2]));
        y[a] = add(e, od);
        y[4 - a] = sub(od, e);
    }
    let m = mul(splat(c.q[2][0]), o0);
    y[2] = add(m, mul(splat(c.q[2][1]), o1));
    y
}

/// [`super::kernel`]'s `psv_block` for order 4 on eight lanes, in AVX-512 registers: the
/// same operations in the same order (the same bits; the test below compares them).
///
/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn psv_block(
    r: &Rule<P>,
    ux: &Block,
    uz: &Block,
    p: &Params<W>,
    gx: &mut Block,
    gz: &mut Block,
) {
    // the x-gradients along the rows
    let dxx = [0, 1, 2, 3, 4].map(|b| even_odd(&r.grad, row(&ux[b])));
    let dxz = [0, 1, 2, 3, 4].map(|b| even_odd(&r.grad, row(&uz[b])));
    let (sx, sz) = (load(&p.sx), load(&p.sz));
    let (l2m, lam, mu) = (load(&p.l2m), load(&p.lam), load(&p.mu));
    let (hx2, hz2) = (load(&p.hx2), load(&p.hz2));
    let w = &r.w;
    // the x-fluxes of each row, filled column by column
    let mut fxx = [[MaybeUninit::<__m512d>::uninit(); P]; P];
    let mut fzx = [[MaybeUninit::<__m512d>::uninit(); P]; P];
    for a in 0..P {
        // the z-gradients of column a, Hooke's law at its points, and the z-divergence
        // of its z-fluxes (kept in g until the x-divergence is added)
        let dzx = even_odd(&r.grad, column(ux, a));
        let dzz = even_odd(&r.grad, column(uz, a));
        let (mut fxz, mut fzz) = ([splat(0.0); P], [splat(0.0); P]);
        for b in 0..P {
            let wab = splat(w[a] * w[b]);
            let (exx, ezz) = (mul(dxx[b][a], sx), mul(dzz[b], sz));
            let exz = add(mul(dzx[b], sz), mul(dxz[b][a], sx));
            let sxx = add(mul(l2m, exx), mul(lam, ezz));
            let szz = add(mul(lam, exx), mul(l2m, ezz));
            let sxz = mul(mu, exz);
            let (wx, wz) = (mul(hz2, wab), mul(hx2, wab));
            fxx[b][a].write(mul(wx, sxx));
            fzx[b][a].write(mul(wx, sxz));
            fxz[b] = mul(wz, sxz);
            fzz[b] = mul(wz, szz);
        }
        let tx = even_odd(&r.div, fxz);
        let tz = even_odd(&r.div, fzz);
        for b in 0..P {
            _mm512_storeu_pd(gx[b][a].as_mut_ptr(), tx[b]);
            _mm512_storeu_pd(gz[b][a].as_mut_ptr(), tz[b]);
        }
    }
    // the x-divergence of each row, added to the z-divergence (x + z = z + x exactly)
    for b in 0..P {
        // SAFETY: every (b, a) was written in the column loop
        let ox = even_odd(&r.div, fxx[b].map(|v| v.assume_init()));
        let oz = even_odd(&r.div, fzx[b].map(|v| v.assume_init()));
        for a in 0..P {
            let (px, pz) = (gx[b][a].as_mut_ptr(), gz[b][a].as_mut_ptr());
            _mm512_storeu_pd(px, add(ox[a], _mm512_loadu_pd(px)));
            _mm512_storeu_pd(pz, add(oz[a], _mm512_loadu_pd(pz)));
        }
    }
}

/// Eight lanes from memory.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn load(x: &[f64; W]) -> __m512d {
    // SAFETY: eight doubles
    unsafe { _mm512_loadu_pd(x.as_ptr()) }
}

/// Row `[a]` of a block's row `b`.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn row(x: &[[f64; W]; P]) -> [__m512d; P] {
    [
        load(&x[0]),
        load(&x[1]),
        load(&x[2]),
        load(&x[3]),
        load(&x[4]),
    ]
}

/// Column `[k]` of a block at `a`.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx512f")]
fn column(x: &Block, a: usize) -> [__m512d; P] {
    [
        load(&x[0][a]),
        load(&x[1][a]),
        load(&x[2][a]),
        load(&x[3][a]),
        load(&x[4][a]),
    ]
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// The gather reads what the scalar map reads, and the scatter subtracts in the
    /// scalar order, bit for bit.
    #[test]
    fn gather_and_scatter_match_the_scalar_map() {
        if !std::is_x86_feature_detected!("avx512f") {
            return;
        }
        let u: Vec<f64> = (0..80).map(|i| (i as f64 * 0.37).sin() * 1e-3).collect();
        let (mut x, mut z) = ([[0.0; W]; P], [[0.0; W]; P]);
        // SAFETY: AVX-512F checked; 66 values from 4
        unsafe { gather_row(u.as_ptr().add(4), &mut x, &mut z) };
        for l in 0..W {
            for a in 0..P {
                let node = 2 + 4 * l + a;
                assert_eq!(x[a][l], u[2 * node]);
                assert_eq!(z[a][l], u[2 * node + 1]);
            }
        }
        let g = |a: usize, l: usize, c: usize| ((a * 31 + l * 7 + c) as f64 * 0.91).cos();
        let (mut gx, mut gz) = ([[0.0; W]; P], [[0.0; W]; P]);
        for a in 0..P {
            for l in 0..W {
                gx[a][l] = g(a, l, 0);
                gz[a][l] = g(a, l, 1);
            }
        }
        let mut scalar = u.clone();
        for l in 0..W {
            for a in 0..P {
                let node = 2 + 4 * l + a;
                scalar[2 * node] -= gx[a][l];
                scalar[2 * node + 1] -= gz[a][l];
            }
        }
        let mut fast = u.clone();
        // SAFETY: AVX-512F checked; 66 values from 4
        unsafe { scatter_row(fast.as_mut_ptr().add(4), &gx, &gz) };
        assert_eq!(
            fast.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            scalar.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
    }
}

//! The element forces of the bulk kernel ([`super::kernel`]'s `psv_block`) on vector
//! registers, one element a lane: the gradients along rows and columns by the even-odd
//! derivative, Hooke's law and the quadrature weights at each point, the divergence, with
//! each column's values kept in registers from its gradient to its z-divergence. One
//! macro body, two instruction sets: AVX-512 (eight lanes, [`avx512`]) and AVX2 (four,
//! [`avx2`]); both do the portable kernel's operations in its order (no fused
//! multiply-add), so every path gives the same bits.

/// A module `$name` of the element forces on `$lanes` lanes of vector type `$v` under
/// target feature `$feature`, with its intrinsics.
macro_rules! element_forces {
    ($name:ident, $feature:literal, $v:ty, $lanes:expr_2021,
     $add:ident, $sub:ident, $mul:ident, $set1:ident, $loadu:ident, $storeu:ident) => {
        #[cfg(target_arch = "x86_64")]
        pub(super) mod $name {
            use crate::solver::solid_2d::lines::{EvenOdd, Params, Rule};
            use std::arch::x86_64::*;
            use std::mem::MaybeUninit;

            /// Elements per block (lanes).
            pub(in crate::solver::solid_2d) const W: usize = $lanes;

            /// An element block's lane arrays: `[b][a][lane]`.
            pub(in crate::solver::solid_2d) type Block<const M: usize> = [[[f64; W]; M]; M];

            /// `x (op) y` on the lanes.
            #[inline]
            #[target_feature(enable = $feature)]
            fn add(x: $v, y: $v) -> $v {
                $add(x, y)
            }
            #[inline]
            #[target_feature(enable = $feature)]
            fn sub(x: $v, y: $v) -> $v {
                $sub(x, y)
            }
            #[inline]
            #[target_feature(enable = $feature)]
            fn mul(x: $v, y: $v) -> $v {
                $mul(x, y)
            }
            #[inline]
            #[target_feature(enable = $feature)]
            fn splat(x: f64) -> $v {
                $set1(x)
            }

            /// [`EvenOdd::apply`] on registers: the same operations in the same order.
            #[inline]
            #[target_feature(enable = $feature)]
            fn even_odd<const M: usize>(c: &EvenOdd<M>, x: [$v; M]) -> [$v; M] {
                let h = M / 2;
                let mut s = [splat(0.0); M];
                let mut o = [splat(0.0); M];
                for k in 0..h {
                    s[k] = add(x[k], x[M - 1 - k]);
                    o[k] = sub(x[k], x[M - 1 - k]);
                }
                let mut y = [splat(0.0); M];
                for a in 0..h {
                    let mut e = mul(splat(c.p[a][0]), s[0]);
                    let mut od = mul(splat(c.q[a][0]), o[0]);
                    for k in 1..h {
                        e = add(e, mul(splat(c.p[a][k]), s[k]));
                        od = add(od, mul(splat(c.q[a][k]), o[k]));
                    }
                    if M % 2 == 1 {
                        e = add(e, mul(splat(c.mid[a]), x[h]));
                    }
                    y[a] = add(e, od);
                    y[M - 1 - a] = sub(od, e);
                }
                if M % 2 == 1 {
                    let mut m = mul(splat(c.q[h][0]), o[0]);
                    for k in 1..h {
                        m = add(m, mul(splat(c.q[h][k]), o[k]));
                    }
                    y[h] = m;
                }
                y
            }

            /// [`super::super::kernel`]'s `psv_block` on the lanes, in registers: the same
            /// operations in the same order (the same bits; the test
            /// `every_cpu_path_gives_the_same_bits` compares them).
            ///
            /// # Safety
            /// The CPU must have the module's instruction set.
            #[target_feature(enable = $feature)]
            pub(in crate::solver::solid_2d) unsafe fn psv_block<const M: usize>(
                r: &Rule<M>,
                ux: &Block<M>,
                uz: &Block<M>,
                p: &Params<W>,
                gx: &mut Block<M>,
                gz: &mut Block<M>,
            ) {
                // the x-gradients along the rows
                let dxx: [[$v; M]; M] = std::array::from_fn(|b| even_odd(&r.grad, row(&ux[b])));
                let dxz: [[$v; M]; M] = std::array::from_fn(|b| even_odd(&r.grad, row(&uz[b])));
                let (sx, sz) = (load(&p.sx), load(&p.sz));
                let (l2m, lam, mu) = (load(&p.l2m), load(&p.lam), load(&p.mu));
                let (hx2, hz2) = (load(&p.hx2), load(&p.hz2));
                let w = &r.w;
                // the x-fluxes of each row, filled column by column
                let mut fxx = [[MaybeUninit::<$v>::uninit(); M]; M];
                let mut fzx = [[MaybeUninit::<$v>::uninit(); M]; M];
                for a in 0..M {
                    // the z-gradients of column a, Hooke's law at its points, and the z-divergence
                    // of its z-fluxes (kept in g until the x-divergence is added)
                    let dzx = even_odd(&r.grad, column(ux, a));
                    let dzz = even_odd(&r.grad, column(uz, a));
                    let (mut fxz, mut fzz) = ([splat(0.0); M], [splat(0.0); M]);
                    for b in 0..M {
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
                    for b in 0..M {
                        // SAFETY: W doubles each
                        unsafe {
                            $storeu(gx[b][a].as_mut_ptr(), tx[b]);
                            $storeu(gz[b][a].as_mut_ptr(), tz[b]);
                        }
                    }
                }
                // the x-divergence of each row, added to the z-divergence (x + z = z + x exactly)
                for b in 0..M {
                    // SAFETY: every (b, a) was written in the column loop
                    let ox = even_odd(&r.div, fxx[b].map(|v| unsafe { v.assume_init() }));
                    let oz = even_odd(&r.div, fzx[b].map(|v| unsafe { v.assume_init() }));
                    for a in 0..M {
                        let (px, pz) = (gx[b][a].as_mut_ptr(), gz[b][a].as_mut_ptr());
                        // SAFETY: W doubles each
                        unsafe {
                            $storeu(px, add(ox[a], $loadu(px)));
                            $storeu(pz, add(oz[a], $loadu(pz)));
                        }
                    }
                }
            }

            /// The lanes from memory.
            #[inline]
            #[target_feature(enable = $feature)]
            fn load(x: &[f64; W]) -> $v {
                // SAFETY: W doubles
                unsafe { $loadu(x.as_ptr()) }
            }

            /// Row `[a]` of a block's row `b`.
            #[inline]
            #[target_feature(enable = $feature)]
            fn row<const M: usize>(x: &[[f64; W]; M]) -> [$v; M] {
                std::array::from_fn(|a| load(&x[a]))
            }

            /// Column `[k]` of a block at `a`.
            #[inline]
            #[target_feature(enable = $feature)]
            fn column<const M: usize>(x: &Block<M>, a: usize) -> [$v; M] {
                std::array::from_fn(|b| load(&x[b][a]))
            }
        }
    };
}

element_forces!(
    avx512,
    "avx512f",
    __m512d,
    8,
    _mm512_add_pd,
    _mm512_sub_pd,
    _mm512_mul_pd,
    _mm512_set1_pd,
    _mm512_loadu_pd,
    _mm512_storeu_pd
);
element_forces!(
    avx2,
    "avx2",
    __m256d,
    4,
    _mm256_add_pd,
    _mm256_sub_pd,
    _mm256_mul_pd,
    _mm256_set1_pd,
    _mm256_loadu_pd,
    _mm256_storeu_pd
);

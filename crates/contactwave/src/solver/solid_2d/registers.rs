//! The element forces of the bulk kernels on vector registers, one element a lane: the
//! gradients along rows and columns by the even-odd derivative, the point-wise law at each
//! point, the divergence, with each column's values kept in registers from its gradient to
//! its z-divergence (`psv_with`, `sh_with`). The laws: the rectangle kernel's
//! ([`super::kernel`]'s `psv_block`: two constants a lane), and the quadrilateral mesh's
//! general elements (`psv_general`, `sh_general`: the per-point metric) and rectangles
//! (`sh_rectangle`). One macro body, two instruction sets: AVX-512 (eight lanes, [`avx512`])
//! and AVX2 (four, [`avx2`]); both do the portable kernel's operations in its order (no
//! fused multiply-add), so every path gives the same bits.

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
                let (sx, sz) = (load(&p.sx), load(&p.sz));
                let (l2m, lam, mu) = (load(&p.l2m), load(&p.lam), load(&p.mu));
                let (hx2, hz2) = (load(&p.hx2), load(&p.hz2));
                let w = &r.w;
                psv_with(r, ux, uz, gx, gz, |a, b, [dxx, dxz, dzx, dzz]| {
                    let wab = splat(w[a] * w[b]);
                    let (exx, ezz) = (mul(dxx, sx), mul(dzz, sz));
                    let exz = add(mul(dzx, sz), mul(dxz, sx));
                    let sxx = add(mul(l2m, exx), mul(lam, ezz));
                    let szz = add(mul(lam, exx), mul(l2m, ezz));
                    let sxz = mul(mu, exz);
                    let (wx, wz) = (mul(hz2, wab), mul(hx2, wab));
                    [mul(wx, sxx), mul(wx, sxz), mul(wz, sxz), mul(wz, szz)]
                });
            }

            /// The P-SV forces of `W` general quadrilaterals (docs/model.md eq. 15.13b): at
            /// point `(a, b)` (column `a`, row `b`) the physical gradient by the point's
            /// metric, read at `metric[(5 (a M + b) + c) W + lane]` for `c` = `xi_x, xi_z,
            /// eta_x, eta_z, w J` (in the order the points are visited), Hooke's law with the lanes'
            /// `lame` (`lambda + 2 mu`, `lambda`, `mu`, Pa) and the fluxes along `xi` and
            /// `eta`; `gx`, `gz`: the forces `K u` at the element's points.
            ///
            /// # Safety
            /// The CPU must have the module's instruction set; `metric` holds `5 M^2 W`
            /// values.
            #[target_feature(enable = $feature)]
            pub(in crate::solver::solid_2d) unsafe fn psv_general<const M: usize>(
                r: &Rule<M>,
                ux: &Block<M>,
                uz: &Block<M>,
                metric: *const f64,
                lame: &[[f64; W]; 3],
                gx: &mut Block<M>,
                gz: &mut Block<M>,
            ) {
                let (l2m, lam, mu) = (load(&lame[0]), load(&lame[1]), load(&lame[2]));
                psv_with(r, ux, uz, gx, gz, |a, b, [dxx, dxz, dzx, dzz]| {
                    // SAFETY: the caller's contract (the point's five components)
                    let [xx, xz, ex, ez, wj] = unsafe { point_metric::<M>(metric, a, b) };
                    let dux_dx = add(mul(dxx, xx), mul(dzx, ex));
                    let dux_dz = add(mul(dxx, xz), mul(dzx, ez));
                    let duz_dx = add(mul(dxz, xx), mul(dzz, ex));
                    let duz_dz = add(mul(dxz, xz), mul(dzz, ez));
                    let sxx = add(mul(l2m, dux_dx), mul(lam, duz_dz));
                    let szz = add(mul(lam, dux_dx), mul(l2m, duz_dz));
                    let sxz = mul(mu, add(dux_dz, duz_dx));
                    [
                        mul(wj, add(mul(sxx, xx), mul(sxz, xz))),
                        mul(wj, add(mul(sxz, xx), mul(szz, xz))),
                        mul(wj, add(mul(sxx, ex), mul(sxz, ez))),
                        mul(wj, add(mul(sxz, ex), mul(szz, ez))),
                    ]
                });
            }

            /// The antiplane forces of `W` general quadrilaterals: [`psv_general`] with one
            /// component (`mu` the lanes' shear moduli, Pa).
            ///
            /// # Safety
            /// As [`psv_general`].
            #[target_feature(enable = $feature)]
            pub(in crate::solver::solid_2d) unsafe fn sh_general<const M: usize>(
                r: &Rule<M>,
                uy: &Block<M>,
                metric: *const f64,
                mu: &[f64; W],
                gy: &mut Block<M>,
            ) {
                let mu = load(mu);
                sh_with(r, uy, gy, |a, b, dxi, deta| {
                    // SAFETY: the caller's contract (the point's five components)
                    let [xx, xz, ex, ez, wj] = unsafe { point_metric::<M>(metric, a, b) };
                    let syx = mul(mu, add(mul(dxi, xx), mul(deta, ex)));
                    let syz = mul(mu, add(mul(dxi, xz), mul(deta, ez)));
                    [
                        mul(wj, add(mul(syx, xx), mul(syz, xz))),
                        mul(wj, add(mul(syx, ex), mul(syz, ez))),
                    ]
                });
            }

            /// The antiplane forces of `W` axis-aligned rectangles: `cx`, `cz` = `xi_x`,
            /// `eta_z` (1/m), `jac` = `J` (m^2) and `mu` (Pa) per lane.
            ///
            /// # Safety
            /// The CPU must have the module's instruction set.
            #[target_feature(enable = $feature)]
            pub(in crate::solver::solid_2d) unsafe fn sh_rectangle<const M: usize>(
                r: &Rule<M>,
                uy: &Block<M>,
                coefs: &[[f64; W]; 4],
                gy: &mut Block<M>,
            ) {
                let (cx, cz, jac, mu) = (
                    load(&coefs[0]),
                    load(&coefs[1]),
                    load(&coefs[2]),
                    load(&coefs[3]),
                );
                let (kx, kz) = (mul(mul(mu, cx), cx), mul(mul(mu, cz), cz));
                let w = &r.w;
                sh_with(r, uy, gy, |a, b, dxi, deta| {
                    let wj = mul(splat(w[a] * w[b]), jac);
                    [mul(mul(wj, kx), dxi), mul(mul(wj, kz), deta)]
                });
            }

            /// The P-SV element forces given the point-wise law `point(a, b, [d_xi u_x,
            /// d_xi u_z, d_eta u_x, d_eta u_z]) -> [xi-flux of x, xi-flux of z, eta-flux of
            /// x, eta-flux of z]`: the gradients along rows and columns by the even-odd
            /// derivative, each column's values kept in registers from its gradient to its
            /// eta-divergence, then the xi-divergence of each row added.
            #[inline]
            #[target_feature(enable = $feature)]
            fn psv_with<const M: usize, F: Fn(usize, usize, [$v; 4]) -> [$v; 4]>(
                r: &Rule<M>,
                ux: &Block<M>,
                uz: &Block<M>,
                gx: &mut Block<M>,
                gz: &mut Block<M>,
                point: F,
            ) {
                // the xi-gradients along the rows
                let dxx: [[$v; M]; M] = std::array::from_fn(|b| even_odd(&r.grad, row(&ux[b])));
                let dxz: [[$v; M]; M] = std::array::from_fn(|b| even_odd(&r.grad, row(&uz[b])));
                // the xi-fluxes of each row, filled column by column
                let mut fxx = [[MaybeUninit::<$v>::uninit(); M]; M];
                let mut fzx = [[MaybeUninit::<$v>::uninit(); M]; M];
                for a in 0..M {
                    // the eta-gradients of column a, the law at its points, and the
                    // eta-divergence of its eta-fluxes (kept in g until the xi-divergence is
                    // added)
                    let dzx = even_odd(&r.grad, column(ux, a));
                    let dzz = even_odd(&r.grad, column(uz, a));
                    let (mut fxz, mut fzz) = ([splat(0.0); M], [splat(0.0); M]);
                    for b in 0..M {
                        let [xx, zx, xz, zz] = point(a, b, [dxx[b][a], dxz[b][a], dzx[b], dzz[b]]);
                        fxx[b][a].write(xx);
                        fzx[b][a].write(zx);
                        fxz[b] = xz;
                        fzz[b] = zz;
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
                // the xi-divergence of each row, added to the eta-divergence (x + z = z + x
                // exactly)
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

            /// [`psv_with`] for one component: `point(a, b, d_xi u_y, d_eta u_y) ->
            /// [xi-flux, eta-flux]`.
            #[inline]
            #[target_feature(enable = $feature)]
            fn sh_with<const M: usize, F: Fn(usize, usize, $v, $v) -> [$v; 2]>(
                r: &Rule<M>,
                uy: &Block<M>,
                gy: &mut Block<M>,
                point: F,
            ) {
                let dxi: [[$v; M]; M] = std::array::from_fn(|b| even_odd(&r.grad, row(&uy[b])));
                let mut f1 = [[MaybeUninit::<$v>::uninit(); M]; M];
                for a in 0..M {
                    let deta = even_odd(&r.grad, column(uy, a));
                    let mut f2 = [splat(0.0); M];
                    for b in 0..M {
                        let [x, z] = point(a, b, dxi[b][a], deta[b]);
                        f1[b][a].write(x);
                        f2[b] = z;
                    }
                    let t = even_odd(&r.div, f2);
                    for b in 0..M {
                        // SAFETY: W doubles
                        unsafe { $storeu(gy[b][a].as_mut_ptr(), t[b]) };
                    }
                }
                for b in 0..M {
                    // SAFETY: every (b, a) was written in the column loop
                    let o = even_odd(&r.div, f1[b].map(|v| unsafe { v.assume_init() }));
                    for a in 0..M {
                        let p = gy[b][a].as_mut_ptr();
                        // SAFETY: W doubles
                        unsafe { $storeu(p, add(o[a], $loadu(p))) };
                    }
                }
            }

            /// The metric of point `(a, b)` (`xi_x, xi_z, eta_x, eta_z, w J`) from a
            /// general batch's block (`metric[(5 (a M + b) + c) W + lane]`).
            ///
            /// # Safety
            /// `metric` holds `5 M^2 W` values.
            #[inline]
            #[target_feature(enable = $feature)]
            unsafe fn point_metric<const M: usize>(
                metric: *const f64,
                a: usize,
                b: usize,
            ) -> [$v; 5] {
                // SAFETY: the caller's contract
                std::array::from_fn(|c| unsafe { $loadu(metric.add((5 * (a * M + b) + c) * W)) })
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

//! A contact point's own law as plain data: the static pressure and shear and the three
//! branches by value ([`PointLaw`]), `Copy` when the branch types are. The contact update
//! ([`super::contact::update_point`]) takes it as it takes a shared [`super::ContactLaw`]
//! (both implement [`NormalPart`] and [`TangentialPart`]), so that an array of points, each
//! with its own parameters and its own [`super::contact::PointState`], is updated in one
//! loop with the branches called directly, without dynamic dispatch per point (and in a
//! form that could be moved to a GPU).
//!
//! The branches of the analytic laws are `Copy` (compression `rigid`, `linear`,
//! `quadratic`, `power`; every traction branch; every tangential branch). The tabulated
//! compression laws (`modified_power`, `table`) hold a table per static pressure and are
//! shared per interface as a [`super::ContactLaw`].
//!
//! ```
//! use contactwave::law::compression::Linear;
//! use contactwave::law::contact::{update_point, PointState, StepContext, Trial};
//! use contactwave::law::point::PointLaw;
//! use contactwave::law::tangential::Free as FreeSliding;
//! use contactwave::law::traction::Free;
//! use contactwave::law::contact::InterfaceScheme;
//! // 1000 points along a crack, each with its own closure pressure (Pa)
//! let laws: Vec<_> = (0..1000)
//!     .map(|i| {
//!         let p0 = 1e5 * (1.0 + i as f64 / 1000.0);
//!         PointLaw::normal(p0, Linear { static_pressure: p0, stiffness: 1e12 }, Free, FreeSliding)
//!     })
//!     .collect();
//! let mut states: Vec<_> = laws.iter().map(|l| PointState::at_rest(l, None::<&PointLaw<Linear, Free, FreeSliding>>)).collect();
//! let ctx = StepContext { scheme: InterfaceScheme::Backward, dt: 1e-8, t: 1e-8 };
//! // a trial gap that closes every point by 1 nm under a compliance of 1e-12 m/Pa
//! let trial = Trial { normal_gap: -1e-9, normal_compliance: 1e-12, ..Trial::default() };
//! for (law, st) in laws.iter().zip(&mut states) {
//!     update_point(law, None::<&PointLaw<Linear, Free, FreeSliding>>, &trial, ctx, st).unwrap();
//! }
//! // g = g~ - chi S with S = K g (linear spring): g = g~ / (1 + chi K)
//! let g = -1e-9 / (1.0 + 1e-12 * 1e12);
//! assert!(states.iter().all(|s| (s.gap - g).abs() < 1e-12 * g.abs()));
//! // and the contact stress -p0 + K g of each point's own p0
//! assert!(laws.iter().zip(&states).all(|(l, s)| (s.stress - (-l.static_pressure + 1e12 * g)).abs() < 1e-6));
//! ```

use super::{CompressionBranch, NormalPart, TangentialBranch, TangentialPart, TractionBranch};

/// A point's contact law by value: static pressure p0 (Pa) and shear q0 (Pa), and its
/// compression, traction and tangential branches (`C`, `T`, `B`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLaw<C, T, B> {
    /// Static pressure p0, Pa (compression positive; the compression branch is built for
    /// the same p0).
    pub static_pressure: f64,
    /// Static shear stress q0, Pa.
    pub static_shear: f64,
    /// Compression branch.
    pub compression: C,
    /// Traction branch.
    pub traction: T,
    /// Tangential branch.
    pub tangential: B,
}

impl<C, T, B> PointLaw<C, T, B> {
    /// The law of a point at static pressure `p0` (Pa) without static shear.
    pub fn normal(p0: f64, compression: C, traction: T, tangential: B) -> Self {
        PointLaw {
            static_pressure: p0,
            static_shear: 0.0,
            compression,
            traction,
            tangential,
        }
    }
}

impl<C: CompressionBranch, T: TractionBranch, B> NormalPart for PointLaw<C, T, B> {
    type Compression = C;
    type Traction = T;
    #[inline]
    fn static_pressure(&self) -> f64 {
        self.static_pressure
    }
    #[inline]
    fn compression(&self) -> &C {
        &self.compression
    }
    #[inline]
    fn traction(&self) -> &T {
        &self.traction
    }
}

impl<C, T, B: TangentialBranch> TangentialPart for PointLaw<C, T, B> {
    type Branch = B;
    #[inline]
    fn static_shear(&self) -> f64 {
        self.static_shear
    }
    #[inline]
    fn branch(&self) -> &B {
        &self.tangential
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::compression::Linear;
    use crate::law::contact::{update_point, InterfaceScheme, PointState, StepContext, Trial};
    use crate::law::tangential::Rccm as RccmTangential;
    use crate::law::traction::Rccm;
    use crate::law::{ContactLaw, TangentialLaw};

    /// A crack of 64 points, each with its own closure pressure, stiffnesses and decohesion
    /// energy (full RCCM: damage driven by both gaps, Coulomb slip), driven through
    /// opening, closing, slip and damage: the points' own `Copy` laws, updated in one loop
    /// with the branches called directly, give bit for bit what the shared laws (boxed
    /// branches, vtable calls) give point by point, in both time discretisations.
    #[test]
    fn point_laws_update_like_shared_laws_bit_for_bit() {
        const N: usize = 64;
        let params = |i: usize| {
            let x = i as f64 / N as f64;
            let p0 = 0.5e6 * (1.0 + x);
            (p0, 1e13 * (1.0 + 0.5 * x), 0.05 + 0.1 * x, 0.3 + 0.4 * x)
        };
        let points: Vec<_> = (0..N)
            .map(|i| {
                let (p0, k, w, mu) = params(i);
                PointLaw {
                    static_pressure: p0,
                    static_shear: 0.1 * mu * p0,
                    compression: Linear {
                        static_pressure: p0,
                        stiffness: k,
                    },
                    traction: Rccm {
                        stiffness: k,
                        energy: w,
                        viscosity: 0.0,
                    },
                    tangential: RccmTangential {
                        stiffness: 0.5 * k,
                        friction: mu,
                    },
                }
            })
            .collect();
        let shared: Vec<(ContactLaw, TangentialLaw)> = points
            .iter()
            .map(|p| {
                (
                    ContactLaw {
                        static_pressure: p.static_pressure,
                        compression: Box::new(p.compression),
                        traction: Box::new(p.traction),
                    },
                    TangentialLaw {
                        static_shear: p.static_shear,
                        branch: Box::new(p.tangential),
                    },
                )
            })
            .collect();
        for scheme in [InterfaceScheme::Average, InterfaceScheme::Backward] {
            let mut own: Vec<PointState> = points
                .iter()
                .map(|p| PointState::at_rest(p, Some(p)))
                .collect();
            let mut reference: Vec<PointState> = shared
                .iter()
                .map(|(n, t)| PointState::at_rest(n, Some(t)))
                .collect();
            let (mut damaged, mut slipped, mut opened) = (false, false, false);
            for k in 1..=400 {
                let t = k as f64 * 1e-8;
                let ctx = StepContext {
                    scheme,
                    dt: 1e-8,
                    t,
                };
                let phase = 2.0 * std::f64::consts::PI * k as f64 / 100.0;
                // a drive growing over a period to gaps of a few critical gaps
                // (`p0 / K` = 5e-8 to 1e-7 m) and damage openings (`sqrt(w / C_N)` ~ 1e-7 m)
                let amp = (k as f64 / 100.0).min(1.0);
                for (i, p) in points.iter().enumerate() {
                    let trial = Trial {
                        normal_gap: amp * 3e-7 * phase.sin(),
                        normal_compliance: 1e-15,
                        tangential_gap: amp * 2e-7 * phase.cos(),
                        tangential_compliance: 1e-15,
                    };
                    update_point(p, Some(p), &trial, ctx, &mut own[i]).unwrap();
                    let (n, tl) = &shared[i];
                    update_point(n, Some(tl), &trial, ctx, &mut reference[i]).unwrap();
                    assert_eq!(
                        format!("{:?}", own[i]),
                        format!("{:?}", reference[i]),
                        "point {i}, step {k}, {scheme:?}"
                    );
                    damaged |= own[i].beta < 1.0;
                    slipped |= own[i].shear.state.abs() == 1.0;
                    opened |= own[i].gap > p.static_pressure / 1e13 * 1.5;
                }
            }
            assert!(damaged && slipped && opened, "{damaged} {slipped} {opened}");
            // beta never increases: at the end it is at most 1 everywhere, below 1 somewhere
            assert!(own.iter().all(|s| (0.0..=1.0).contains(&s.beta)));
        }
    }
}

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
//! compression laws (`modified_power`, `table`) hold a table per static pressure (some
//! 80 KB): a crack tabulates each distinct static pressure of its points once in a
//! [`CurveStore`], and each point holds a reference to its curve (`&StiffnessCurve`, a
//! compression branch like the curve itself, and `Copy`).
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

use super::compression::{StiffnessCurve, StiffnessPressure};
use super::{
    CompressionBranch, NormalPart, TangentialBranch, TangentialPart, TractionBranch, WarmStart,
};
use crate::error::{Error, Result};

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

/// A point's law shared with every point of an interface: the normal law and the
/// tangential law by reference (`Clone` is two reference counts). What a scenario builds
/// from its law tables, whose branches are chosen at run time (the branches are then
/// called through their vtables; [`PointLaw`] calls them directly).
#[derive(Debug, Clone)]
pub struct SharedLaw {
    /// Normal law (static pressure, compression and traction branches).
    pub normal: std::sync::Arc<super::ContactLaw>,
    /// Tangential law (static shear and branch).
    pub tangential: std::sync::Arc<super::TangentialLaw>,
}

impl NormalPart for SharedLaw {
    type Compression = dyn CompressionBranch;
    type Traction = dyn TractionBranch;
    #[inline]
    fn static_pressure(&self) -> f64 {
        self.normal.static_pressure
    }
    #[inline]
    fn compression(&self) -> &(dyn CompressionBranch + 'static) {
        &*self.normal.compression
    }
    #[inline]
    fn traction(&self) -> &(dyn TractionBranch + 'static) {
        &*self.normal.traction
    }
}

impl TangentialPart for SharedLaw {
    type Branch = dyn TangentialBranch;
    #[inline]
    fn static_shear(&self) -> f64 {
        self.tangential.static_shear
    }
    #[inline]
    fn branch(&self) -> &(dyn TangentialBranch + 'static) {
        &*self.tangential.branch
    }
}

/// A compression branch shared by reference is a compression branch (every method
/// forwarded), so that a point can hold its tabulated curve as a `Copy` reference into a
/// [`CurveStore`].
impl<C: CompressionBranch + ?Sized> CompressionBranch for &C {
    #[inline]
    fn name(&self) -> &'static str {
        (**self).name()
    }
    #[inline]
    fn is_rigid(&self) -> bool {
        (**self).is_rigid()
    }
    #[inline]
    fn critical_gap(&self) -> f64 {
        (**self).critical_gap()
    }
    #[inline]
    fn stress(&self, gap: f64) -> f64 {
        (**self).stress(gap)
    }
    #[inline]
    fn tangent(&self, gap: f64) -> f64 {
        (**self).tangent(gap)
    }
    #[inline]
    fn stress_tangent(&self, gap: f64) -> (f64, f64) {
        (**self).stress_tangent(gap)
    }
    #[inline]
    fn energy(&self, gap: f64) -> f64 {
        (**self).energy(gap)
    }
    #[inline]
    fn is_affine(&self) -> bool {
        (**self).is_affine()
    }
    #[inline]
    fn stiffness_at_rest(&self) -> f64 {
        (**self).stiffness_at_rest()
    }
    #[inline]
    fn tangent_at(&self, gap: f64, stress: f64) -> f64 {
        (**self).tangent_at(gap, stress)
    }
    #[inline]
    fn solve_compressed(&self, shifted_gap: f64, chi: f64, warm: &mut WarmStart) -> Option<f64> {
        (**self).solve_compressed(shifted_gap, chi, warm)
    }
}

/// The tabulated compression curves of a crack, one per distinct static pressure of its
/// points: built once before the time loop, read by reference from the points' laws
/// (`PointLaw<&StiffnessCurve<K>, T, B>`, `Copy`).
#[derive(Debug)]
pub struct CurveStore<K: StiffnessPressure> {
    /// Distinct static pressures, Pa, increasing.
    pressures: Vec<f64>,
    /// The curve of each.
    curves: Vec<StiffnessCurve<K>>,
}

impl<K: StiffnessPressure + Clone> CurveStore<K> {
    /// Memory of one tabulated curve of `law`, bytes (an upper estimate: 1025 uniform
    /// nodes, a geometric tail of at most 450 nodes to 1e10 Pa, a node at each kink of the
    /// relation, four arrays per node and 4096 buckets).
    pub fn curve_bytes(law: &K) -> usize {
        (1025 + 450 + 2 + law.kinks().len()) * 4 * 8 + 4096 * 4
    }

    /// Tabulate the relation `law` (named `name` in reports) at each distinct pressure of
    /// `static_pressures` (Pa, finite and >= 0), refusing more than `max_bytes` of tables
    /// (the crack's memory budget).
    pub fn new(
        law: &K,
        static_pressures: &[f64],
        name: &'static str,
        max_bytes: usize,
    ) -> Result<Self> {
        let mut pressures: Vec<f64> = Vec::with_capacity(static_pressures.len());
        for &p in static_pressures {
            if !(p.is_finite() && p >= 0.0) {
                return Err(Error::invalid(
                    "",
                    "static_pressure",
                    p,
                    "a finite pressure >= 0 Pa",
                ));
            }
            pressures.push(p);
        }
        pressures.sort_by(f64::total_cmp);
        pressures.dedup();
        let one = Self::curve_bytes(law);
        let need = pressures.len().saturating_mul(one);
        if need > max_bytes {
            return Err(Error::invalid(
                "",
                "static_pressure",
                format!(
                    "{} distinct values ({need} bytes of tables)",
                    pressures.len()
                ),
                format!("at most {} distinct static pressures", max_bytes / one),
            ));
        }
        let curves = pressures
            .iter()
            .map(|&p0| StiffnessCurve::new(law.clone(), p0, name))
            .collect();
        Ok(CurveStore { pressures, curves })
    }

    /// The curve tabulated for static pressure `p0` (Pa), if `p0` was one of the store's.
    pub fn curve(&self, p0: f64) -> Option<&StiffnessCurve<K>> {
        self.pressures
            .binary_search_by(|p| p.total_cmp(&p0))
            .ok()
            .map(|i| &self.curves[i])
    }

    /// Number of distinct curves.
    pub fn len(&self) -> usize {
        self.curves.len()
    }

    /// `true` when the store holds no curve.
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::compression::modified_power::ModifiedPowerStiffness;
    use crate::law::compression::{Linear, ModifiedPower, StiffnessCurve};
    use crate::law::contact::{update_point, InterfaceScheme, PointState, StepContext, Trial};
    use crate::law::tangential::Rccm as RccmTangential;
    use crate::law::traction::Rccm;
    use crate::law::{ContactLaw, TangentialLaw};

    /// Drive every point through `steps` steps of a growing two-gap drive (amplitudes
    /// `gap_n`, `gap_t`, m; compliance `chi`, m/Pa) in both time discretisations, once with
    /// the points' own laws in one loop and once with the shared laws point by point,
    /// asserting identical states bit for bit at every step. Returns whether some point
    /// damaged, slipped and opened (beyond 1.5 critical gaps).
    fn drive_against_shared<C, T, B>(
        points: &[PointLaw<C, T, B>],
        shared: &[(ContactLaw, TangentialLaw)],
        (gap_n, gap_t, chi): (f64, f64, f64),
    ) -> (bool, bool, bool)
    where
        C: CompressionBranch,
        T: TractionBranch,
        B: TangentialBranch,
    {
        let (mut damaged, mut slipped, mut opened) = (false, false, false);
        for scheme in [InterfaceScheme::Average, InterfaceScheme::Backward] {
            let mut own: Vec<PointState> = points
                .iter()
                .map(|p| PointState::at_rest(p, Some(p)))
                .collect();
            let mut reference: Vec<PointState> = shared
                .iter()
                .map(|(n, t)| PointState::at_rest(n, Some(t)))
                .collect();
            for k in 1..=400 {
                let t = k as f64 * 1e-8;
                let ctx = StepContext {
                    scheme,
                    dt: 1e-8,
                    t,
                };
                let phase = 2.0 * std::f64::consts::PI * k as f64 / 100.0;
                let amp = (k as f64 / 100.0).min(1.0);
                for (i, p) in points.iter().enumerate() {
                    let trial = Trial {
                        normal_gap: amp * gap_n * phase.sin(),
                        normal_compliance: chi,
                        tangential_gap: amp * gap_t * phase.cos(),
                        tangential_compliance: chi,
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
                    opened |= own[i].gap > p.critical_gap() * 1.5;
                }
            }
            // beta never increases: at the end it is at most 1 everywhere
            assert!(own.iter().all(|s| (0.0..=1.0).contains(&s.beta)));
        }
        (damaged, slipped, opened)
    }

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
        // gaps of a few critical gaps (`p0 / K` = 5e-8 to 1e-7 m) and damage openings
        // (`sqrt(w / C_N)` ~ 1e-7 m)
        let (damaged, slipped, opened) =
            drive_against_shared(&points, &shared, (3e-7, 2e-7, 1e-15));
        assert!(damaged && slipped && opened, "{damaged} {slipped} {opened}");
    }

    /// The tabulated modified power law (thesis section 4.2) on a crack of 64 points with 8
    /// distinct closure pressures: the store tabulates 8 curves, each point's `Copy` law
    /// holds a reference to its own, and the one-loop update gives bit for bit what the
    /// shared laws (a curve tabulated per point, boxed) give, through closing (the curve's
    /// own warm-started solver), opening (RCCM traction with damage) and Coulomb slip.
    #[test]
    fn tabulated_point_laws_share_curves_and_update_like_shared_laws() {
        const N: usize = 64;
        let law = ModifiedPowerStiffness::new(1.81e10, 0.35, 0.2e6, 0.3);
        let p0 = |i: usize| 0.2e6 * (1.0 + (i % 8) as f64);
        let pressures: Vec<f64> = (0..N).map(p0).collect();
        let store = CurveStore::new(&law, &pressures, "modified_power", 64 << 20).unwrap();
        assert_eq!(store.len(), 8);
        // a budget too small for the 8 tables is refused before tabulating
        let one = CurveStore::<ModifiedPowerStiffness>::curve_bytes(&law);
        assert!(CurveStore::new(&law, &pressures, "modified_power", 7 * one).is_err());
        assert!(CurveStore::new(&law, &[f64::NAN], "modified_power", 1 << 30).is_err());
        let traction = Rccm {
            stiffness: 2e13,
            energy: 0.08,
            viscosity: 0.0,
        };
        let tangential = RccmTangential {
            stiffness: 1e13,
            friction: 0.4,
        };
        let points: Vec<PointLaw<&ModifiedPower, Rccm, RccmTangential>> = pressures
            .iter()
            .map(|&p| PointLaw {
                static_pressure: p,
                static_shear: 0.05 * p,
                compression: store.curve(p).unwrap(),
                traction,
                tangential,
            })
            .collect();
        let shared: Vec<(ContactLaw, TangentialLaw)> = pressures
            .iter()
            .map(|&p| {
                (
                    ContactLaw {
                        static_pressure: p,
                        compression: Box::new(StiffnessCurve::new(law, p, "modified_power")),
                        traction: Box::new(traction),
                    },
                    TangentialLaw {
                        static_shear: 0.05 * p,
                        branch: Box::new(tangential),
                    },
                )
            })
            .collect();
        // critical gaps of the curve: G(p0), about 1e-5 m at these pressures
        let uc = points.iter().map(|p| p.critical_gap()).fold(0.0, f64::max);
        assert!(uc > 0.0);
        let (damaged, slipped, opened) =
            drive_against_shared(&points, &shared, (3.0 * uc, 3.0 * uc, 1e-12));
        assert!(damaged && slipped && opened, "{damaged} {slipped} {opened}");
    }
}

//! Contact laws: one *compression branch* joined to one *traction branch* at the gap
//! `[u]_c` where the interface stress reaches zero (model.md section 2; thesis eqs.
//! 2.10-2.17, 1.3, 4.4, 5.4).
//!
//! Conventions: stress `sigma` is tension-positive, the gap `[u]` is opening-positive and
//! measured from the pre-loaded equilibrium, so `sigma(0) = -p0`. Every branch is one file
//! behind one trait ([`CompressionBranch`], [`TractionBranch`]); the solvers ask a branch
//! for its stress, tangent, energy and state update and never for its name. A new law is
//! one new file plus one line in [`registry`].

pub mod compression;
pub mod contact;
pub mod param;
pub mod point;
pub mod registry;
pub mod scheme;
pub mod spec;
pub mod tangential;
pub mod traction;

use std::fmt::Debug;

/// A compression branch: the interface stress for `[u] <= [u]_c`, with `sigma(0) = -p0`
/// and `sigma([u]_c) = 0`.
pub trait CompressionBranch: Debug + Send + Sync {
    /// Short name, for reports.
    fn name(&self) -> &'static str;
    /// `true` for a rigid (Signorini) branch: `[u] >= 0` is a constraint, no stress function.
    fn is_rigid(&self) -> bool {
        false
    }
    /// Gap at contact loss `[u]_c`, m (0 for a rigid branch).
    fn critical_gap(&self) -> f64;
    /// Stress `sigma([u])`, Pa, for `[u] <= [u]_c` (tension positive, so <= 0 here).
    fn stress(&self, gap: f64) -> f64;
    /// Tangent stiffness `d sigma / d[u]`, Pa/m (>= 0).
    fn tangent(&self, gap: f64) -> f64;
    /// Stress and tangent stiffness together (Pa, Pa/m): what a Newton iteration needs;
    /// branches whose stress is found numerically override it to solve once.
    fn stress_tangent(&self, gap: f64) -> (f64, f64) {
        (self.stress(gap), self.tangent(gap))
    }
    /// Energy stored from rest, `integral_0^[u] (sigma + p0) d[u]`, J/m^2.
    fn energy(&self, gap: f64) -> f64;
    /// `true` when the stress is affine in the gap over the whole branch (constant
    /// [`CompressionBranch::tangent`]): a solver may then integrate the branch's phase
    /// without iterating. Default `false`.
    fn is_affine(&self) -> bool {
        false
    }
    /// Tangent stiffness at rest K(p0), Pa/m (`f64::INFINITY` for rigid); enters xi.
    fn stiffness_at_rest(&self) -> f64 {
        self.tangent(0.0)
    }
    /// Tangent stiffness `d sigma / d[u]` at `gap` whose stress `stress` (Pa) is known as
    /// well (a solver's record of both), Pa/m: [`CompressionBranch::tangent`]; a branch
    /// that finds its stress numerically reads it at the stress instead of solving again.
    fn tangent_at(&self, gap: f64, _stress: f64) -> f64 {
        self.tangent(gap)
    }
    /// The implicit interface update on the compressed side, for branches that solve it
    /// faster than a Newton iteration on the gap: the gap `[u] <= [u]_c` (m) with
    /// `sigma([u]) + ([u] - q)/chi = 0` for a shifted prediction `q <= [u]_c` (m) and a
    /// compliance `chi > 0` (m/Pa), warm-started from (and updating) what the previous
    /// updates of the same interface left in `warm`. `None` (the default): no solver of
    /// its own.
    fn solve_compressed(&self, _shifted_gap: f64, _chi: f64, _warm: &mut WarmStart) -> Option<f64> {
        None
    }
}

/// What a compression branch's own interface solver
/// ([`CompressionBranch::solve_compressed`]) carries from one update of an interface to
/// the next: the last two points it evaluated, three numbers each (for a stiffness
/// curve: pressure, Pa, `G(p) = integral_0^p dp'/K`, m, and `1/K(p)`, m/Pa), oldest first.
/// Start from `WarmStart::default()` (none).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WarmStart {
    /// The points, oldest first (the first `len` of them from the newest backwards).
    pub points: [[f64; 3]; 2],
    /// How many are set: 0, 1 or 2.
    pub len: usize,
}

impl WarmStart {
    /// Add the newest point (the oldest is dropped).
    pub fn push(&mut self, point: [f64; 3]) {
        self.points[0] = self.points[1];
        self.points[1] = point;
        self.len = (self.len + 1).min(2);
    }
}

/// A traction branch: the interface stress for an opening `d = [u] - [u]_c > 0`, possibly
/// with an adhesion intensity `beta in [0, 1]` that damage can only decrease.
///
/// Damage evolves as `b dbeta/dt = min(phi(d, beta), 0)` (thesis eq. 2.12 for RCCM), with
/// the driving force `phi` and the viscosity `b` given by the branch; `b = 0` is the
/// rate-independent limit `phi = 0` while damaging.
pub trait TractionBranch: Debug + Send + Sync {
    /// Short name, for reports.
    fn name(&self) -> &'static str;
    /// `true` for a bonded branch: `d = 0` is a constraint (bilateral contact).
    fn is_rigid(&self) -> bool {
        false
    }
    /// `true` when the branch carries no stress at any opening (traction-free faces):
    /// an open point then carries exactly nothing over the step, in every time scheme.
    fn is_free(&self) -> bool {
        false
    }
    /// Stress `sigma(d, beta)`, Pa (>= 0).
    fn stress(&self, opening: f64, adhesion: f64) -> f64;
    /// `d sigma / d d`, Pa/m.
    fn tangent(&self, opening: f64, adhesion: f64) -> f64;
    /// `d sigma / d beta`, Pa.
    fn stress_d_adhesion(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    /// Elastic energy `psi(d, beta) = integral_0^d sigma dd`, J/m^2.
    fn energy(&self, opening: f64, adhesion: f64) -> f64;
    /// `true` when, at fixed adhesion, the stress is linear in the opening `d >= 0`
    /// (constant [`TractionBranch::tangent`]): a solver may then integrate a phase without
    /// damage growth without iterating. Default `false`.
    fn is_affine(&self) -> bool {
        false
    }
    /// `d psi / d beta`, J/m^2: energy released per unit decrease of beta.
    fn energy_d_adhesion(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    /// Whether the branch has a damage variable at all.
    fn has_damage(&self) -> bool {
        false
    }
    /// Damage driving force `phi(d, beta)`, J/m^2; beta decreases while `phi < 0`.
    fn damage_driving_force(&self, _opening: f64, _adhesion: f64) -> f64 {
        f64::INFINITY
    }
    /// An opening (m) below which the damage driving force is positive at adhesion
    /// `adhesion` (no damage): `phi(d, beta) > 0` for every `0 <= d < damage_onset(beta)`,
    /// with a margin that covers the round-off of evaluating `phi`. A solver may then skip
    /// evaluating `phi` below it. Default 0 (nothing known: always evaluate).
    fn damage_onset(&self, _adhesion: f64) -> f64 {
        0.0
    }
    /// `(d phi / d d, d phi / d beta)`.
    fn damage_driving_force_gradient(&self, _opening: f64, _adhesion: f64) -> (f64, f64) {
        (0.0, 0.0)
    }
    /// Damage viscosity b, J s/m^2 (0: rate-independent).
    fn damage_viscosity(&self) -> f64 {
        0.0
    }
    /// Implicit (backward-Euler) update of beta over `dt` at fixed opening: unconditionally
    /// stable, never increases beta; `dt = f64::INFINITY` gives the rate-independent limit.
    fn update_adhesion(&self, _opening: f64, adhesion: f64, _dt: f64) -> f64 {
        adhesion
    }
    /// Adhesion energy term `w beta`, J/m^2: its decrease is the energy damage consumes in
    /// the rate-independent limit.
    fn adhesion_energy(&self, _adhesion: f64) -> f64 {
        0.0
    }
    /// Tangent stiffness at `d = 0, beta = 1`, Pa/m (for relaxation-time estimates).
    fn stiffness_at_contact(&self) -> f64 {
        self.tangent(0.0, 1.0)
    }
}

/// A tangential branch (model.md section 13): a reversible spring `k(beta) [u]_T` in
/// parallel with a Coulomb slider (`|tau_f| <= mu N`, `N` the normal contact pressure),
/// the slider sticking rigidly or through a stick stiffness `k_t` in series. The defaults
/// describe a branch with none of them (free sliding).
pub trait TangentialBranch: Debug + Send + Sync {
    /// Short name, for reports.
    fn name(&self) -> &'static str;
    /// Stiffness of the reversible spring at adhesion `beta`, Pa/m.
    fn spring_stiffness(&self, _adhesion: f64) -> f64 {
        0.0
    }
    /// `d k / d beta`, Pa/m: the spring's energy `k [u]_T^2 / 2` then adds
    /// `(dk/dbeta) [u]_T^2 / 2` to the energy released per unit decrease of beta.
    fn spring_stiffness_d_adhesion(&self, _adhesion: f64) -> f64 {
        0.0
    }
    /// Energy of the reversible spring, `k(beta) [u]_T^2 / 2`, J/m^2, at adhesion `beta`
    /// and tangential gap `u_t` (m).
    fn spring_energy(&self, adhesion: f64, u_t: f64) -> f64 {
        0.5 * self.spring_stiffness(adhesion) * u_t * u_t
    }
    /// The spring's share of the energy released per unit decrease of beta,
    /// `(dk/dbeta) [u]_T^2 / 2`, J/m^2, at adhesion `beta` and tangential gap `u_t` (m):
    /// added to the traction branch's damage driving force in the coupled RCCM law
    /// (model.md section 13).
    fn spring_energy_d_adhesion(&self, adhesion: f64, u_t: f64) -> f64 {
        0.5 * self.spring_stiffness_d_adhesion(adhesion) * u_t * u_t
    }
    /// Coulomb friction coefficient mu (0: no slider); with a slip-dependent coefficient,
    /// its value before any slip (the static coefficient).
    fn friction(&self) -> f64 {
        0.0
    }
    /// Friction coefficient after a slip path `path = integral |ds|` (m): constant by
    /// default ([`TangentialBranch::friction`]); a branch whose coefficient evolves with
    /// slip (slip weakening) overrides it. Such a branch sticks rigidly.
    fn friction_at(&self, _path: f64) -> f64 {
        self.friction()
    }
    /// Stick stiffness `k_t` of the slider, Pa/m (`f64::INFINITY`: rigid stick).
    fn stick_stiffness(&self) -> f64 {
        f64::INFINITY
    }
    /// Whether the branch takes its adhesion from a damaging traction branch (RCCM).
    fn needs_adhesion(&self) -> bool {
        false
    }
}

/// The tangential part of a contact law: static shear and a tangential branch.
#[derive(Debug)]
pub struct TangentialLaw {
    /// Static shear stress q0, Pa (carried by the slider at rest: `|q0| <= mu p0`).
    pub static_shear: f64,
    /// Tangential branch.
    pub branch: Box<dyn TangentialBranch>,
}

impl TangentialLaw {
    /// Whether the branch carries no tangential stress at all (free sliding, no static
    /// shear): a normally incident longitudinal wave then never moves the interface
    /// tangentially.
    pub fn is_free(&self) -> bool {
        self.static_shear == 0.0
            && self.branch.friction() == 0.0
            && self.branch.spring_stiffness(1.0) == 0.0
    }

    /// Monotone tangential loading from rest at the static pressure (the interface held
    /// closed, `N = p0`): `n` tangential gaps from 0 to `gap_max` (m) and the shear stress at
    /// each (Pa), the adhesion of a full RCCM law damaging in its rate-independent limit.
    /// A rigid-stick slider jumps from `q0` to `mu p0` at zero gap (two points at 0).
    pub fn curve(&self, normal: &ContactLaw, gap_max: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let n = n.max(2);
        let br = &*self.branch;
        let p0 = normal.static_pressure;
        let kt = br.stick_stiffness();
        let slider = br.friction() > 0.0;
        let mut gaps = vec![0.0];
        let mut stress = vec![self.static_shear];
        let mut beta = 1.0f64;
        for i in 1..n {
            let u = gap_max * i as f64 / (n - 1) as f64;
            if normal.traction.has_damage() && br.needs_adhesion() {
                // rate-independent damage, interface closed (d = 0): phi affine in beta
                let phi = |b: f64| {
                    normal.traction.damage_driving_force(0.0, b) - br.spring_energy_d_adhesion(b, u)
                };
                let (a0, a1) = (phi(0.0), phi(beta));
                if a1 < 0.0 && beta > 0.0 {
                    beta = (a0 * beta / (a0 - a1)).clamp(0.0, beta);
                }
            }
            // slip path: the gap past the static limit (all of it for a rigid stick)
            let path = if kt.is_finite() {
                (u - (self.friction_limit(p0, 0.0) - self.static_shear) / kt).max(0.0)
            } else {
                u
            };
            let limit = self.friction_limit(p0, path);
            let tau_f = if !slider {
                self.static_shear
            } else if kt.is_finite() {
                (self.static_shear + kt * u).min(limit)
            } else {
                if i == 1 {
                    gaps.push(0.0);
                    stress.push(self.friction_limit(p0, 0.0));
                }
                limit
            };
            gaps.push(u);
            stress.push(br.spring_stiffness(beta) * u + tau_f);
        }
        (gaps, stress)
    }

    /// A tangential gap range that shows the branch: a few times the gap at which the
    /// slider saturates, the spring reaches the friction stress or damage sets in, m.
    pub fn curve_gap_range(&self, normal: &ContactLaw) -> f64 {
        let br = &*self.branch;
        let s = self
            .friction_limit(normal.static_pressure, 0.0)
            .max(self.static_shear.abs())
            .max(normal.static_pressure)
            .max(1e5);
        let mut g: f64 = 0.0;
        for k in [br.stick_stiffness(), br.spring_stiffness(1.0)] {
            if k.is_finite() && k > 0.0 {
                g = g.max(3.0 * s / k);
            }
        }
        let c_t = br.spring_stiffness(1.0);
        if normal.traction.has_damage() && br.needs_adhesion() && c_t > 0.0 {
            let w = normal.traction.damage_driving_force(0.0, 1.0).max(0.0);
            g = g.max(4.0 * (w / c_t).sqrt());
        }
        if g > 0.0 {
            g
        } else {
            3.0 * s / 1e13
        }
    }

    /// Friction limit `mu(path) N`, Pa, at normal contact pressure `N` (Pa, >= 0) after a
    /// slip path `path` (m; see [`TangentialBranch::friction_at`]).
    pub fn friction_limit(&self, pressure: f64, path: f64) -> f64 {
        TangentialPart::friction_limit(self, pressure, path)
    }
}

/// What the contact update ([`contact`]) reads of a point's normal law: its static
/// pressure and its two branches. [`ContactLaw`] implements it with branches shared by
/// every point of an interface (called through their vtables); [`point::PointLaw`] with a
/// point's own parameters, plain `Copy` data of concrete branch types (called directly:
/// an array of points, each with its own parameters, is updated in one loop without
/// dynamic dispatch per point).
pub trait NormalPart {
    /// The compression branch's type.
    type Compression: CompressionBranch + ?Sized;
    /// The traction branch's type.
    type Traction: TractionBranch + ?Sized;
    /// Static pressure p0, Pa (compression positive).
    fn static_pressure(&self) -> f64;
    /// The compression branch.
    fn compression(&self) -> &Self::Compression;
    /// The traction branch.
    fn traction(&self) -> &Self::Traction;
    /// Gap at contact loss `[u]_c`, m.
    #[inline]
    fn critical_gap(&self) -> f64 {
        self.compression().critical_gap()
    }
}

/// What the contact update reads of a point's tangential law: its static shear and its
/// branch ([`NormalPart`] for the normal law; implemented by [`TangentialLaw`] and
/// [`point::PointLaw`]).
pub trait TangentialPart {
    /// The branch's type.
    type Branch: TangentialBranch + ?Sized;
    /// Static shear stress q0, Pa.
    fn static_shear(&self) -> f64;
    /// The tangential branch.
    fn branch(&self) -> &Self::Branch;
    /// Friction limit `mu(path) N`, Pa, at normal contact pressure `N` (Pa, >= 0) after a
    /// slip path `path` (m; see [`TangentialBranch::friction_at`]).
    #[inline]
    fn friction_limit(&self, pressure: f64, path: f64) -> f64 {
        let mu = self.branch().friction_at(path);
        if mu == 0.0 {
            0.0
        } else {
            mu * pressure.max(0.0)
        }
    }
}

impl TangentialPart for TangentialLaw {
    type Branch = dyn TangentialBranch;
    #[inline]
    fn static_shear(&self) -> f64 {
        self.static_shear
    }
    #[inline]
    fn branch(&self) -> &(dyn TangentialBranch + 'static) {
        &*self.branch
    }
}

impl NormalPart for ContactLaw {
    type Compression = dyn CompressionBranch;
    type Traction = dyn TractionBranch;
    #[inline]
    fn static_pressure(&self) -> f64 {
        self.static_pressure
    }
    #[inline]
    fn compression(&self) -> &(dyn CompressionBranch + 'static) {
        &*self.compression
    }
    #[inline]
    fn traction(&self) -> &(dyn TractionBranch + 'static) {
        &*self.traction
    }
}

/// A complete contact law: static pressure, a compression and a traction branch.
#[derive(Debug)]
pub struct ContactLaw {
    /// Static pressure p0, Pa (compression positive).
    pub static_pressure: f64,
    /// Compression branch.
    pub compression: Box<dyn CompressionBranch>,
    /// Traction branch.
    pub traction: Box<dyn TractionBranch>,
}

impl ContactLaw {
    /// Gap at contact loss `[u]_c`, m.
    pub fn critical_gap(&self) -> f64 {
        self.compression.critical_gap()
    }

    /// Stress at gap `[u]` for adhesion `beta` on the compliant parts of the law, Pa.
    /// On a rigid compression branch, `[u] <= 0` gives `-p0` (the stress is then set by
    /// the constraint, not by the law).
    pub fn stress(&self, gap: f64, adhesion: f64) -> f64 {
        let uc = self.critical_gap();
        if gap <= uc {
            if self.compression.is_rigid() {
                -self.static_pressure
            } else {
                self.compression.stress(gap)
            }
        } else if self.traction.is_rigid() {
            0.0
        } else {
            self.traction.stress(gap - uc, adhesion)
        }
    }

    /// Energy stored in the interface from rest, J/m^2 (`integral (sigma + p0) d[u]` plus
    /// the elastic energy of the traction branch at the current adhesion).
    pub fn stored_energy(&self, gap: f64, adhesion: f64) -> f64 {
        let uc = self.critical_gap();
        if gap <= uc {
            if self.compression.is_rigid() {
                0.0
            } else {
                self.compression.energy(gap)
            }
        } else {
            let d = gap - uc;
            let base = if self.compression.is_rigid() {
                0.0
            } else {
                self.compression.energy(uc)
            };
            let t = if self.traction.is_rigid() {
                0.0
            } else {
                self.traction.energy(d, adhesion)
            };
            base + self.static_pressure * d + t
        }
    }

    /// Monotone-loading stress-gap curve: `n` gaps from `gap_min` to `gap_max` (m) and the
    /// stress at each (Pa), damage evolving in its rate-independent limit. Rigid branches
    /// are drawn as vertical segments (two points at the same gap).
    ///
    /// ```
    /// use contactwave::law::registry::build_law;
    /// use contactwave::law::spec::{CompressionSpec, TractionSpec};
    /// // p0 = 1 MPa; linear compression K = 1e12 Pa/m; RCCM traction C_N = 2e13 Pa/m,
    /// // w = 0.1 J/m^2, rate-independent damage
    /// let law = build_law(
    ///     1e6,
    ///     &CompressionSpec::Linear(contactwave::law::compression::linear::Spec { stiffness: 1e12 }),
    ///     &TractionSpec::Rccm(contactwave::law::traction::rccm::Spec { stiffness: 2e13, energy: 0.1, viscosity: 0.0 }),
    ///     "<doc>",
    ///     "interface",
    /// )
    /// .unwrap();
    /// let uc = law.critical_gap(); // p0 / K = 1 µm
    /// assert!((uc - 1e-6).abs() < 1e-18);
    /// let (gap, stress) = law.curve(0.0, uc + 0.5e-6, 20001);
    /// assert_eq!((gap.len(), stress.len()), (20001, 20001));
    /// assert_eq!(stress[0], -1e6); // sigma(0) = -p0
    /// // the traction peaks at sqrt(w C_N) = 1.414 MPa (opening sqrt(w / C_N) = 70.7 nm),
    /// // then damage softens it to w^2 / (C_N d^3) = 4 kPa at d = 0.5 µm
    /// let peak = stress.iter().copied().fold(f64::MIN, f64::max);
    /// assert!((peak / (0.1f64 * 2e13).sqrt() - 1.0).abs() < 1e-3);
    /// assert!((stress[20000] / 4e3 - 1.0).abs() < 1e-6);
    /// ```
    pub fn curve(&self, gap_min: f64, gap_max: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let uc = self.critical_gap();
        let p0 = self.static_pressure;
        let mut gaps = Vec::with_capacity(n + 4);
        let mut stress = Vec::with_capacity(n + 4);
        let mut beta = 1.0;
        let n = n.max(2);
        let span_stress = if p0 > 0.0 { p0 } else { 1e5 };
        if self.compression.is_rigid() {
            gaps.push(0.0);
            stress.push(-p0 - span_stress);
        }
        for i in 0..n {
            let g = gap_min + (gap_max - gap_min) * i as f64 / (n - 1) as f64;
            if self.compression.is_rigid() && g < 0.0 {
                continue;
            }
            if g > uc && self.traction.is_rigid() {
                gaps.push(uc);
                stress.push(span_stress);
                break;
            }
            if g > uc {
                beta = self.traction.update_adhesion(g - uc, beta, f64::INFINITY);
            }
            gaps.push(g);
            stress.push(self.stress(g, beta));
        }
        (gaps, stress)
    }
}

//! The contact update of one point (model.md sections 2, 9 and 13): given the trial normal
//! and tangential gaps the point's two faces would reach at the new time level with no
//! interface force, their compliances (gap change per unit dynamic stress) and the point's
//! law state, find the tractions and the new state that satisfy the law exactly at the new
//! level. Every time-stepping solver calls it (the bar stack through its joints, the
//! half-space FD cross-checks, and a grid of split nodes alike); it is this project's
//! `computeCohesiveForces` (uguca) or fault-law module (SEM2DPACK).
//!
//! One step solves
//!
//! ```text
//! g_N = g~_N - chi_N S_N,   S_N = sigma(g_N, beta) + p0
//! g_T = g~_T - chi_T T,     T   = k(beta) g_T + tau_f - q0,   |tau_f| <= mu N
//! ```
//!
//! with `N = max(-sigma, 0)` the normal contact pressure of the same (new) time level and
//! beta the adhesion of the new level, updated by the unconditionally stable backward-Euler
//! step of `b dbeta/dt = min(phi, 0)`, `phi = phi_traction(d, beta) - k'(beta) g_T^2 / 2`
//! (the RCCM energy of both gaps, [`crate::law::TangentialBranch::spring_energy_d_adhesion`]).
//! The normal half ([`normal`]): Signorini with no penetration and no penalty, bonded
//! locking, compliant branches by a safeguarded root-finder, damage by the law's stable
//! update. The tangential half is the slider's return mapping
//! ([`crate::law::tangential::coulomb::return_map`]): a stick predictor (rigid: slip
//! frozen; elastic: `tau_f = q0 + k_t (g_T - s)`), and if `|tau_f| > mu N` the Coulomb
//! projection. The halves are coupled only through beta (N does not depend on `g_T`);
//! [`coupled_step`] iterates them to a fixed point. Nothing allocates.
//!
//! A point's state ([`PointState`]) and its step input ([`Trial`], [`StepContext`]) are
//! plain `Copy` data: an array of points, each with its own state, is updated in one loop
//! ([`update_point`]) with the law's branches shared.
//!
//! In the `Average` [`InterfaceScheme`] the mean of the new and the previous-but-one
//! stresses acts over the step (trapezoidal, no numerical dissipation for springs), and
//! rigid constraints (Signorini, bonded, rigid stick) keep the backward projection that
//! enforces them at the new level.

pub mod normal;

use crate::error::{Error, Result};
use crate::law::tangential::coulomb::{return_map, ShearState, ShearUpdate};
use crate::law::{
    CompressionBranch, NormalPart, TangentialBranch, TangentialLaw, TangentialPart, TractionBranch,
    WarmStart,
};
use crate::numeric::root::brent_past;
use normal::InterfaceUpdate;

pub use super::scheme::InterfaceScheme;

/// Backward-Euler update of the adhesion over `dt` (s) at opening `d` (m) and tangential
/// gap `ut` (m), from `beta_old`: `b (beta - beta_old) = dt min(phi(beta), 0)` with
/// `phi = phi_traction(d, beta) - k'(beta) ut^2 / 2`; `b = 0` or `dt = inf` is the
/// rate-independent limit `phi(beta) = 0`. Never increases beta.
pub fn adhesion_update<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    law: &N,
    tangential: &G,
    opening: f64,
    ut: f64,
    beta_old: f64,
    dt: f64,
) -> f64 {
    let tr = law.traction();
    if !tr.has_damage() {
        return beta_old;
    }
    let br = tangential.branch();
    if ut == 0.0 || !br.needs_adhesion() {
        return tr.update_adhesion(opening, beta_old, dt);
    }
    let phi = |b: f64| tr.damage_driving_force(opening, b) - br.spring_energy_d_adhesion(b, ut);
    if phi(beta_old) >= 0.0 {
        return beta_old;
    }
    let visc = tr.damage_viscosity();
    let rate_independent = visc == 0.0 || dt.is_infinite();
    // G(beta) = b (beta - beta_old) - dt phi(beta): G(beta_old) > 0, root below it
    let g = |b: f64| {
        if rate_independent {
            -phi(b)
        } else {
            visc * (b - beta_old) - dt * phi(b)
        }
    };
    let (g0, g1) = (g(0.0), g(beta_old));
    if g0 >= 0.0 {
        return 0.0;
    }
    brent_past(g, 0.0, beta_old, g0, g1, 200)
        .unwrap_or(0.0)
        .clamp(0.0, beta_old)
}

/// Normal interface update with the damage driven by both gaps (the tangential gap `ut`,
/// m, held): [`normal::update`] (with the compression branch's warm start `warm`, when
/// given) when there is no tangential law or its branch takes no adhesion (the result is
/// then the normal-only update, bit for bit).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn normal_update<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    law: &N,
    tangential: Option<&G>,
    predicted_gap: f64,
    chi: f64,
    beta_old: f64,
    ut: f64,
    warm: Option<&mut WarmStart>,
    dt: f64,
    t: f64,
) -> Result<InterfaceUpdate> {
    let tangential = match tangential {
        Some(tl) if tl.branch().needs_adhesion() && law.traction().has_damage() => tl,
        _ => return normal::update(law, predicted_gap, chi, beta_old, warm, dt, t),
    };
    let uc = law.critical_gap();
    let p0 = law.static_pressure();
    let gt = predicted_gap;
    let f_uc = p0 + (uc - gt) / chi;
    if f_uc >= 0.0 || law.traction().is_rigid() {
        // closed (or bonded): the stress does not depend on beta; damage from the shear gap
        let upd = normal::update(law, gt, chi, beta_old, None, dt, t)?;
        let d = (upd.gap - uc).max(0.0);
        return Ok(InterfaceUpdate {
            adhesion: adhesion_update(law, tangential, d, ut, beta_old, dt),
            ..upd
        });
    }
    let s_of = |g: f64| {
        let d = g - uc;
        let b = adhesion_update(law, tangential, d, ut, beta_old, dt);
        (law.traction().stress(d, b) + p0, b)
    };
    normal::traction_side(gt, chi, uc, f_uc, s_of, || {
        Error::numerical(
            t,
            "coupled interface update (traction) failed",
            format!("predicted gap = {gt:e} m, beta = {beta_old}, [u]_T = {ut:e} m"),
        )
    })
}

/// The normal update in the time discretisation `scheme`: returns the update (its
/// `dynamic_stress` that of the new level) and the dynamic stress to apply over the step
/// (Pa); `s_old` is the dynamic stress of the previous-but-one level. `warm`: as in
/// [`normal_update`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn normal_step<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    scheme: InterfaceScheme,
    law: &N,
    tangential: Option<&G>,
    gt: f64,
    chi: f64,
    beta_old: f64,
    s_old: f64,
    ut: f64,
    mut warm: Option<&mut WarmStart>,
    dt: f64,
    t: f64,
) -> Result<(InterfaceUpdate, f64)> {
    if scheme == InterfaceScheme::Average {
        // g = g~ - chi (S_new + S_old) / 2: the update with compliance chi/2 from the
        // shifted prediction g~ - chi S_old / 2
        let upd = normal_update(
            law,
            tangential,
            gt - 0.5 * chi * s_old,
            0.5 * chi,
            beta_old,
            ut,
            warm.as_deref_mut(),
            dt,
            t,
        )?;
        let uc = law.critical_gap();
        let p0 = law.static_pressure();
        // on a constraint (rigid contact, a bond), or open on traction-free faces (the
        // mean with an earlier contact stress would push the faces apart while they
        // open, work that the stress-free branch cannot do): the new level's stress
        let on_constraint = (upd.gap <= uc && law.compression().is_rigid())
            || (upd.gap >= uc && (law.traction().is_rigid() || law.traction().is_free()));
        // nor the mean of a spring's stress with a constraint's reaction of the
        // previous-but-one level (S <= p0 closed on a rigid compression branch, S >= p0
        // bonded): at each opening of a rigid contact onto an adhesive spring the mean
        // would do the same work on the faces, which builds up, point against point, as a
        // growing mode along a crack (model.md section 9.2)
        let from_constraint = (s_old < p0 && law.compression().is_rigid())
            || (s_old > p0 && law.traction().is_rigid());
        if !on_constraint && !from_constraint {
            return Ok((upd, 0.5 * (upd.dynamic_stress + s_old)));
        }
    }
    let upd = normal_update(law, tangential, gt, chi, beta_old, ut, warm, dt, t)?;
    Ok((upd, upd.dynamic_stress))
}

/// Result of one coupled interface step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledUpdate {
    /// Normal update of the new level.
    pub normal: InterfaceUpdate,
    /// Normal dynamic stress applied over the step, Pa.
    pub normal_applied: f64,
    /// Normal contact pressure N of the new level, Pa.
    pub pressure: f64,
    /// Contact pressure of the normal stress applied over the step, Pa.
    pub pressure_applied: f64,
    /// Tangential update.
    pub shear: ShearUpdate,
    /// Fixed-point iterations used.
    pub iterations: usize,
}

/// What one coupled step takes besides the predicted gaps.
#[derive(Debug, Clone, Copy)]
pub struct CoupledStepInput {
    /// Time discretisation.
    pub scheme: InterfaceScheme,
    /// Normal compliance, m/Pa.
    pub chi_n: f64,
    /// Tangential compliance, m/Pa.
    pub chi_t: f64,
    /// Adhesion of the current level.
    pub beta_old: f64,
    /// Normal dynamic stress of the previous-but-one level, Pa.
    pub s_old: f64,
    /// Tangential dynamic stress of the previous-but-one level, Pa.
    pub t_old: f64,
    /// Time step, s.
    pub dt: f64,
    /// The new time level, s (error messages).
    pub t: f64,
}

/// One coupled interface step: the normal update with the damage driven by the
/// tangential gap, the tangential return mapping with the adhesion and the contact
/// pressure of the new level, iterated to a fixed point on `[u]_T` (one pass when the
/// tangential branch takes no adhesion: the normal update then ignores `[u]_T`).
pub fn coupled_step<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    normal_law: &N,
    tangential: &G,
    gn: f64,
    gt: f64,
    old: &ShearState,
    input: &CoupledStepInput,
) -> Result<CoupledUpdate> {
    let CoupledStepInput {
        scheme,
        chi_n,
        chi_t,
        beta_old,
        s_old,
        t_old,
        dt,
        t,
    } = *input;
    let p0 = normal_law.static_pressure();
    let coupled = tangential.branch().needs_adhesion() && normal_law.traction().has_damage();
    let mut ut = old.gap;
    for it in 1..=100 {
        let (nu, n_app) = normal_step(
            scheme,
            normal_law,
            Some(tangential),
            gn,
            chi_n,
            beta_old,
            s_old,
            ut,
            None,
            dt,
            t,
        )?;
        let pressure = if nu.gap > normal_law.critical_gap() {
            0.0
        } else {
            (p0 - nu.dynamic_stress).max(0.0)
        };
        let pressure_applied = if nu.gap > normal_law.critical_gap() {
            0.0
        } else {
            (p0 - n_app).max(0.0)
        };
        let su = return_map(
            scheme,
            tangential,
            gt,
            chi_t,
            old,
            t_old,
            nu.adhesion,
            pressure,
            pressure_applied,
        );
        let done = !coupled
            || su.new.gap == ut
            || (su.new.gap - ut).abs() <= 1e-14 * su.new.gap.abs().max(ut.abs());
        if done {
            return Ok(CoupledUpdate {
                normal: nu,
                normal_applied: n_app,
                pressure,
                pressure_applied,
                shear: su,
                iterations: it,
            });
        }
        ut = su.new.gap;
    }
    Err(Error::numerical(
        t,
        "coupled interface update: the normal/tangential fixed point did not converge \
         in 100 iterations",
        format!("predicted gaps = ({gn:e}, {gt:e}) m, beta = {beta_old}"),
    ))
}

/// What every point update of one time step shares.
#[derive(Debug, Clone, Copy)]
pub struct StepContext {
    /// Time discretisation of the interface force.
    pub scheme: InterfaceScheme,
    /// Time step, s.
    pub dt: f64,
    /// The new time level, s (for error messages).
    pub t: f64,
}

/// A point's trial: what its faces would reach at the new level with no interface force.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Trial {
    /// Trial normal gap `g~_N`, m.
    pub normal_gap: f64,
    /// Normal compliance `chi_N` (gap change per unit dynamic normal stress), m/Pa.
    pub normal_compliance: f64,
    /// Trial tangential gap `g~_T`, m (unused without a tangential law).
    pub tangential_gap: f64,
    /// Tangential compliance `chi_T`, m/Pa (unused without a tangential law).
    pub tangential_compliance: f64,
}

/// The state of one contact point carried between steps: plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// Adhesion of the current level.
    pub beta: f64,
    /// Normal dynamic stress `S = sigma + p0` of the previous-but-one level, Pa.
    pub s_prev: f64,
    /// Normal dynamic stress of the current level, Pa.
    pub s_cur: f64,
    /// Normal gap, m.
    pub gap: f64,
    /// Normal contact stress sigma (tension positive, -p0 at rest), Pa.
    pub stress: f64,
    /// Warm start of the compression branch's own solver (normal law alone).
    pub warm: WarmStart,
    /// Tangential state (with a tangential law).
    pub shear: ShearState,
    /// Tangential dynamic stress `T = tau - q0` of the previous-but-one level, Pa.
    pub t_prev: f64,
    /// Tangential dynamic stress of the current level, Pa.
    pub t_cur: f64,
    /// Frictional dissipation so far, `sum tau_f Delta s`, J/m^2 (with a tangential law).
    pub friction: f64,
    /// Energy released by damage so far, `sum (dpsi/dbeta) (-Delta beta)`, J/m^2 (with a
    /// tangential law).
    pub damage: f64,
}

impl PointState {
    /// At rest at the pre-loaded equilibrium of `law`; the slider of `tangential` (when
    /// given) holds the static shear.
    pub fn at_rest<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
        law: &N,
        tangential: Option<&G>,
    ) -> Self {
        PointState {
            beta: 1.0,
            s_prev: 0.0,
            s_cur: 0.0,
            gap: 0.0,
            stress: -law.static_pressure(),
            warm: WarmStart::default(),
            shear: tangential.map_or_else(ShearState::default, |tl| {
                ShearState::at_rest(tl, law.static_pressure())
            }),
            t_prev: 0.0,
            t_cur: 0.0,
            friction: 0.0,
            damage: 0.0,
        }
    }

    /// Contact shear stress tau = T + q0 of the current level, Pa.
    pub fn shear_stress<G: TangentialPart + ?Sized>(&self, tangential: &G) -> f64 {
        self.shear.dynamic_stress + tangential.static_shear()
    }

    fn finish_normal<N: NormalPart + ?Sized>(&mut self, upd: InterfaceUpdate, law: &N) {
        self.s_prev = self.s_cur;
        self.s_cur = upd.dynamic_stress;
        self.gap = upd.gap;
        self.stress = upd.dynamic_stress - law.static_pressure();
        self.beta = upd.adhesion;
    }
}

/// The dynamic stresses (Pa) a point update applies to its faces over the step:
/// `[normal, tangential]` (tangential 0 without a tangential law). A stress `S` (tension
/// positive) pulls the first face forward and the second back, each by its compliance.
pub type Applied = [f64; 2];

/// Update one contact point to the new level: the normal law alone (`tangential` `None`),
/// or the coupled normal/tangential step. Returns the stresses to apply over the step; the
/// state `st` becomes the new level's.
#[inline]
pub fn update_point<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    law: &N,
    tangential: Option<&G>,
    trial: &Trial,
    ctx: StepContext,
    st: &mut PointState,
) -> Result<Applied> {
    match tangential {
        None => update_normal_point(law, trial, ctx, st),
        Some(tl) => update_coupled_point(law, tl, trial, ctx, st),
    }
}

/// [`update_point`] without a tangential law: inlined into the caller's loop (the normal
/// update of a bar stack's joint is a tenth of its step; measured, the call cost 13% of
/// the Tribobrake benchmark when it was not).
#[inline(always)]
fn update_normal_point<N: NormalPart + ?Sized>(
    law: &N,
    trial: &Trial,
    ctx: StepContext,
    st: &mut PointState,
) -> Result<Applied> {
    let StepContext { scheme, dt, t } = ctx;
    let (upd, s_app) = normal_step(
        scheme,
        law,
        None::<&TangentialLaw>,
        trial.normal_gap,
        trial.normal_compliance,
        st.beta,
        st.s_prev,
        0.0,
        Some(&mut st.warm),
        dt,
        t,
    )?;
    st.finish_normal(upd, law);
    Ok([s_app, 0.0])
}

/// [`update_point`] with a tangential law: the coupled normal/tangential step.
fn update_coupled_point<N: NormalPart + ?Sized, G: TangentialPart + ?Sized>(
    law: &N,
    tl: &G,
    trial: &Trial,
    ctx: StepContext,
    st: &mut PointState,
) -> Result<Applied> {
    let StepContext { scheme, dt, t } = ctx;
    let input = CoupledStepInput {
        scheme,
        chi_n: trial.normal_compliance,
        chi_t: trial.tangential_compliance,
        beta_old: st.beta,
        s_old: st.s_prev,
        t_old: st.t_prev,
        dt,
        t,
    };
    let upd = coupled_step(
        law,
        tl,
        trial.normal_gap,
        trial.tangential_gap,
        &st.shear,
        &input,
    )?;
    let new = upd.shear.new;
    st.friction += new.slider * (new.slip - st.shear.slip);
    let b = upd.normal.adhesion;
    if b != st.beta {
        let d = (upd.normal.gap - law.critical_gap()).max(0.0);
        let psi_beta = law.traction().energy_d_adhesion(d, b)
            + tl.branch().spring_energy_d_adhesion(b, new.gap);
        st.damage += psi_beta * (st.beta - b);
    }
    st.t_prev = st.t_cur;
    st.t_cur = new.dynamic_stress;
    st.shear = new;
    st.finish_normal(upd.normal, law);
    Ok([upd.normal_applied, upd.shear.applied])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::registry::{build_law, build_tangential};
    use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};

    /// Faces that open on a traction-free branch carry exactly nothing over the step in
    /// the average scheme too: the dynamic stress applied is the new level's (p0: no
    /// total stress), not its mean with the contact stress of the previous-but-one level,
    /// which would push the opening faces apart (energy the free branch cannot give).
    /// Faces that open onto a spring take the new level's stress too while the
    /// previous-but-one level was closed (its stress a rigid contact's reaction), and the
    /// mean (second order) once both levels lie on the spring.
    #[test]
    fn opening_free_faces_carry_nothing_over_the_step_in_the_average_scheme() {
        let p0 = 1e5;
        let chi = 1e-16; // m/Pa: chi p0 = 1e-11 m, below the opening
        let s_old = -2e6; // dynamic stress of the previous-but-one level: in contact, Pa
        let opening = 1e-9; // the predicted gap, m: the faces separate
        for traction in [
            TractionSpec::Free(Default::default()),
            TractionSpec::Linear(crate::law::traction::linear::Spec { stiffness: 1e13 }),
        ] {
            let law = build_law(
                p0,
                &CompressionSpec::Rigid(Default::default()),
                &traction,
                "<t>",
                "i",
            )
            .unwrap();
            let (upd, applied) = normal_step(
                InterfaceScheme::Average,
                &law,
                None::<&TangentialLaw>,
                opening,
                chi,
                1.0,
                s_old,
                0.0,
                None,
                1e-9,
                1e-9,
            )
            .unwrap();
            assert!(upd.gap > 0.0, "{traction:?}: {upd:?}");
            if matches!(traction, TractionSpec::Free(_)) {
                let total = upd.dynamic_stress - p0;
                assert!(total.abs() < 1e-9 * p0, "total stress {total:e} while open");
                assert_eq!(applied, upd.dynamic_stress);
            } else {
                assert_eq!(applied, upd.dynamic_stress);
                // both levels on the spring: the mean
                let s_spring = p0 + 1e13 * 0.5e-9;
                let (upd, applied) = normal_step(
                    InterfaceScheme::Average,
                    &law,
                    None::<&TangentialLaw>,
                    opening,
                    chi,
                    1.0,
                    s_spring,
                    0.0,
                    None,
                    1e-9,
                    1e-9,
                )
                .unwrap();
                assert!(upd.gap > 0.0, "{upd:?}");
                assert_eq!(applied, 0.5 * (upd.dynamic_stress + s_spring));
            }
        }
    }

    #[test]
    fn adhesion_update_matches_the_traction_update_without_shear_and_the_closed_form_with() {
        let law = build_law(
            1e6,
            &CompressionSpec::Rigid(Default::default()),
            &TractionSpec::Rccm(crate::law::traction::rccm::Spec {
                stiffness: 2e13,
                energy: 0.1,
                viscosity: 1e-8,
            }),
            "<t>",
            "i",
        )
        .unwrap();
        let tl = build_tangential(
            &TangentialSpec::Rccm(crate::law::tangential::rccm::Spec {
                stiffness: 1e13,
                friction: 0.4,
            }),
            0.0,
            &law,
            "<t>",
            "i",
        )
        .unwrap();
        let d = 1e-7;
        let a = adhesion_update(&law, &tl, d, 0.0, 0.9, 1e-9);
        assert_eq!(a, law.traction.update_adhesion(d, 0.9, 1e-9));
        // RCCM: b (beta - beta_old) = dt (w - beta (C_N d^2 + C_T ut^2))
        let ut = 1.5e-7;
        let (b, dt, w) = (1e-8, 1e-9, 0.1);
        let a2 = 2e13 * d * d + 1e13 * ut * ut;
        let closed = (b * 0.9 + dt * w) / (b + dt * a2);
        let got = adhesion_update(&law, &tl, d, ut, 0.9, dt);
        assert!((got - closed).abs() < 1e-12, "{got} vs {closed}");
        // rate-independent limit, closed interface, shear alone
        let got = adhesion_update(&law, &tl, 0.0, ut, 1.0, f64::INFINITY);
        assert!((got - w / (1e13 * ut * ut)).abs() < 1e-12);
    }
}

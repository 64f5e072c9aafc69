//! Per-step update of an interface with a normal and a tangential degree of freedom, for
//! the explicit finite-difference solvers (model.md section 13): the normal update of
//! [`super::interface`] with the damage also driven by the tangential gap, and a
//! tangential return mapping for the spring and the Coulomb slider.
//!
//! Given the predicted gaps `g~_N`, `g~_T` the interface nodes would reach with no
//! interface force and the compliances `chi_N`, `chi_T` (gap change per unit dynamic
//! stress; `chi = 2 dt / Z` per side at Courant 1), one step solves
//!
//! ```text
//! g_N = g~_N - chi_N S_N,   S_N = sigma(g_N, beta) + p0
//! g_T = g~_T - chi_T T,     T   = k(beta) g_T + tau_f - q0,   |tau_f| <= mu N
//! ```
//!
//! with `N = max(-sigma, 0)` the normal contact pressure of the same (new) time level and
//! beta the adhesion of the new level, updated by the unconditionally stable backward-Euler
//! step of `b dbeta/dt = min(phi, 0)`, `phi = phi_traction(d, beta) - k'(beta) g_T^2 / 2`
//! (the RCCM energy of both gaps). The slider is a return mapping: a stick predictor
//! (rigid: slip frozen; elastic: `tau_f = q0 + k_t (g_T - s)`), and if `|tau_f| > mu N`
//! the Coulomb projection `tau_f = sign(tau_f) mu N` with the slip that follows. The
//! normal and tangential halves are coupled only through beta (N does not depend on
//! `g_T`); [`coupled_step`] iterates the two halves to a fixed point. Nothing allocates.
//!
//! As in [`super::interface::InterfaceScheme`], the `Average` scheme applies the mean of
//! the new and the previous-but-one stresses over the step (trapezoidal, no numerical
//! dissipation for springs), and rigid constraints (Signorini, bonded, rigid stick) keep
//! the backward projection that enforces them at the new level.

use super::interface::{self, InterfaceScheme, InterfaceUpdate};
use crate::error::{Error, Result};
use crate::law::{ContactLaw, TangentialLaw};
use crate::numeric::root::brent_past;

/// Backward-Euler update of the adhesion over `dt` (s) at opening `d` (m) and tangential
/// gap `ut` (m), from `beta_old`: `b (beta - beta_old) = dt min(phi(beta), 0)` with
/// `phi = phi_traction(d, beta) - k'(beta) ut^2 / 2`; `b = 0` or `dt = inf` is the
/// rate-independent limit `phi(beta) = 0`. Never increases beta.
pub fn adhesion_update(
    law: &ContactLaw,
    tangential: &TangentialLaw,
    opening: f64,
    ut: f64,
    beta_old: f64,
    dt: f64,
) -> f64 {
    let tr = &*law.traction;
    if !tr.has_damage() {
        return beta_old;
    }
    let br = &*tangential.branch;
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
/// m, held): as [`interface::update`], which it calls when the tangential branch takes no
/// adhesion (the result is then the normal-only update, bit for bit).
#[allow(clippy::too_many_arguments)]
pub fn normal_update(
    law: &ContactLaw,
    tangential: &TangentialLaw,
    predicted_gap: f64,
    chi: f64,
    beta_old: f64,
    ut: f64,
    dt: f64,
    t: f64,
) -> Result<InterfaceUpdate> {
    if !tangential.branch.needs_adhesion() || !law.traction.has_damage() {
        return interface::update(law, predicted_gap, chi, beta_old, None, dt, t);
    }
    let uc = law.critical_gap();
    let p0 = law.static_pressure;
    let gt = predicted_gap;
    let f_uc = p0 + (uc - gt) / chi;
    if f_uc >= 0.0 || law.traction.is_rigid() {
        // closed (or bonded): the stress does not depend on beta; damage from the shear gap
        let upd = interface::update(law, gt, chi, beta_old, None, dt, t)?;
        let d = (upd.gap - uc).max(0.0);
        return Ok(InterfaceUpdate {
            adhesion: adhesion_update(law, tangential, d, ut, beta_old, dt),
            ..upd
        });
    }
    let s_of = |g: f64| {
        let d = g - uc;
        let b = adhesion_update(law, tangential, d, ut, beta_old, dt);
        (law.traction.stress(d, b) + p0, b)
    };
    let f = |g: f64| s_of(g).0 + (g - gt) / chi;
    let hi = gt.max(uc);
    let fhi = f(hi);
    if fhi <= 0.0 {
        let (s, b) = s_of(hi);
        return Ok(InterfaceUpdate {
            gap: hi,
            dynamic_stress: s,
            adhesion: b,
        });
    }
    let g = brent_past(f, uc, hi, f_uc, fhi, 300).ok_or_else(|| {
        Error::numerical(
            t,
            "coupled interface update (traction) failed",
            format!("predicted gap = {gt:e} m, beta = {beta_old}, [u]_T = {ut:e} m"),
        )
    })?;
    let (_s, b) = s_of(g);
    Ok(InterfaceUpdate {
        gap: g,
        dynamic_stress: (gt - g) / chi,
        adhesion: b,
    })
}

/// The normal update in the time discretisation `scheme`: returns the update (its
/// `dynamic_stress` that of the new level) and the dynamic stress to apply over the step
/// (Pa); `s_old` is the dynamic stress of the previous-but-one level.
#[allow(clippy::too_many_arguments)]
pub fn normal_step(
    scheme: InterfaceScheme,
    law: &ContactLaw,
    tangential: &TangentialLaw,
    gt: f64,
    chi: f64,
    beta_old: f64,
    s_old: f64,
    ut: f64,
    dt: f64,
    t: f64,
) -> Result<(InterfaceUpdate, f64)> {
    if scheme == InterfaceScheme::Average {
        let upd = normal_update(
            law,
            tangential,
            gt - 0.5 * chi * s_old,
            0.5 * chi,
            beta_old,
            ut,
            dt,
            t,
        )?;
        let uc = law.critical_gap();
        let on_constraint = (upd.gap <= uc && law.compression.is_rigid())
            || (upd.gap >= uc && law.traction.is_rigid());
        if !on_constraint {
            return Ok((upd, 0.5 * (upd.dynamic_stress + s_old)));
        }
    }
    let upd = normal_update(law, tangential, gt, chi, beta_old, ut, dt, t)?;
    Ok((upd, upd.dynamic_stress))
}

/// Tangential state carried from step to step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ShearState {
    /// Tangential gap `[u]_T`, m.
    pub gap: f64,
    /// Accumulated slip s of the slider, m.
    pub slip: f64,
    /// Dynamic shear stress `T = tau - q0` of the level, Pa.
    pub dynamic_stress: f64,
    /// Slider stress tau_f, Pa.
    pub slider: f64,
    /// Slider state: 0 stick, +1 / -1 slipping, NaN free (no friction load possible).
    pub state: f64,
}

impl ShearState {
    /// At rest under the static shear of `law` and the normal pre-load `p0` (Pa): with
    /// friction and `p0 > 0` the slider sticks and carries `q0`; otherwise it is free and
    /// an elastic stick spring carries `q0` through its slip.
    pub fn at_rest(law: &TangentialLaw, p0: f64) -> Self {
        let q0 = law.static_shear;
        let sticking = law.branch.friction() > 0.0 && p0 > 0.0;
        let kt = law.branch.stick_stiffness();
        ShearState {
            slider: if sticking { q0 } else { 0.0 },
            state: if sticking { 0.0 } else { f64::NAN },
            slip: if kt.is_finite() && !sticking {
                q0 / kt
            } else {
                0.0
            },
            ..ShearState::default()
        }
    }
}

/// Result of one tangential update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearUpdate {
    /// State of the new level.
    pub new: ShearState,
    /// Dynamic shear stress applied over the step, Pa.
    pub applied: f64,
}

/// Linear solve of one tangential update with the slider stress `tau_f` given:
/// `g = g~ - w chi (k g + tau_f - q0) - (1 - w) chi T_old`, `w` = 1 (backward) or 1/2
/// (average). Returns `(g, T_new, T_applied)`.
#[inline]
fn given_slider(gt: f64, chi: f64, w: f64, k: f64, tau_f: f64, q0: f64, t_old: f64) -> [f64; 3] {
    let c = w * chi;
    let g = (gt - c * (tau_f - q0) - (1.0 - w) * chi * t_old) / (1.0 + c * k);
    let t_new = k * g + tau_f - q0;
    [g, t_new, w * t_new + (1.0 - w) * t_old]
}

/// Tangential update (return mapping) for predicted gap `gt` (m), compliance `chi`
/// (m/Pa), adhesion `beta` and normal contact pressure `pressure` (Pa) of the new level,
/// from the state `old` of the current level; `t_old` is the dynamic shear stress of the
/// previous-but-one level (Pa, used by the `Average` scheme). A rigid-stick slider is a
/// constraint and takes the backward projection in both schemes, with the friction limit
/// on `pressure_applied`, the contact pressure of the normal stress applied over the same
/// step (Pa): its stress, like the normal constraint reaction, is the one acting over the
/// step (first order in time where it switches).
#[allow(clippy::too_many_arguments)]
pub fn shear_step(
    scheme: InterfaceScheme,
    law: &TangentialLaw,
    gt: f64,
    chi: f64,
    old: &ShearState,
    t_old: f64,
    beta: f64,
    pressure: f64,
    pressure_applied: f64,
) -> ShearUpdate {
    let br = &*law.branch;
    let q0 = law.static_shear;
    let k = br.spring_stiffness(beta);
    let kt = br.stick_stiffness();
    let limit = law.friction_limit(pressure);
    let limit_applied = law.friction_limit(pressure_applied);
    let avg = scheme == InterfaceScheme::Average;
    let w_compliant = if avg { 0.5 } else { 1.0 };
    let finish = |[g, t_new, applied]: [f64; 3], tau_f: f64, slip: f64, state: f64| ShearUpdate {
        new: ShearState {
            gap: g,
            slip,
            dynamic_stress: t_new,
            slider: tau_f,
            state,
        },
        applied,
    };
    if (if kt.is_infinite() {
        limit_applied
    } else {
        limit
    }) <= 0.0
    {
        // free: no slider load; the slip follows the gap through the (unloaded) stick spring
        let r = given_slider(gt, chi, w_compliant, k, 0.0, q0, t_old);
        let slip = if kt.is_finite() { r[0] + q0 / kt } else { r[0] };
        return finish(r, 0.0, slip, f64::NAN);
    }
    if kt.is_infinite() {
        // rigid stick: a constraint, backward for stick and slip alike (a consistent return
        // mapping). The reaction `(g~ - g_old)/chi` is the stress acting over the step,
        // checked against the friction limit of the normal stress acting over the same step.
        let g = old.gap;
        let t_new = (gt - g) / chi;
        let tau_f = t_new + q0 - k * g;
        if tau_f.abs() <= limit_applied {
            return finish([g, t_new, t_new], tau_f, g, 0.0);
        }
        let tau_f = limit_applied.copysign(tau_f);
        let r = given_slider(gt, chi, 1.0, k, tau_f, q0, t_old);
        return finish(r, tau_f, r[0], tau_f.signum());
    }
    // elastic stick predictor: tau_f = q0 + k_t (g - s_old), compliant (both schemes)
    let w = w_compliant;
    let c = w * chi;
    let s_old = old.slip;
    let g = (gt - c * (kt * (-s_old)) - (1.0 - w) * chi * t_old) / (1.0 + c * (k + kt));
    let tau_f = q0 + kt * (g - s_old);
    if tau_f.abs() <= limit {
        let t_new = k * g + tau_f - q0;
        return finish([g, t_new, w * t_new + (1.0 - w) * t_old], tau_f, s_old, 0.0);
    }
    let tau_f = limit.copysign(tau_f);
    let r = given_slider(gt, chi, w, k, tau_f, q0, t_old);
    let slip = r[0] - (tau_f - q0) / kt;
    finish(r, tau_f, slip, tau_f.signum())
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
pub fn coupled_step(
    normal_law: &ContactLaw,
    tangential: &TangentialLaw,
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
    let p0 = normal_law.static_pressure;
    let coupled = tangential.branch.needs_adhesion() && normal_law.traction.has_damage();
    let mut ut = old.gap;
    for it in 1..=100 {
        let (nu, n_app) = normal_step(
            scheme, normal_law, tangential, gn, chi_n, beta_old, s_old, ut, dt, t,
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
        let su = shear_step(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::registry::{build_law, build_tangential};
    use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};

    #[test]
    fn adhesion_update_matches_the_traction_update_without_shear_and_the_closed_form_with() {
        let law = build_law(
            1e6,
            &CompressionSpec::Rigid,
            &TractionSpec::Rccm {
                stiffness: 2e13,
                energy: 0.1,
                viscosity: 1e-8,
            },
            "<t>",
            "i",
        )
        .unwrap();
        let tl = build_tangential(
            &TangentialSpec::Rccm {
                stiffness: 1e13,
                friction: 0.4,
            },
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

    #[test]
    fn rigid_stick_return_mapping_clips_at_mu_n_and_slips_forward() {
        let law = build_law(
            1e6,
            &CompressionSpec::Rigid,
            &TractionSpec::Free,
            "<t>",
            "i",
        )
        .unwrap();
        let tl = build_tangential(
            &TangentialSpec::Coulomb {
                friction: 0.5,
                stiffness: None,
            },
            0.0,
            &law,
            "<t>",
            "i",
        )
        .unwrap();
        let chi = 1e-13;
        let old = ShearState::default();
        // below the limit: sticks, the stress is the constraint reaction
        let u = shear_step(
            InterfaceScheme::Average,
            &tl,
            0.3e6 * chi,
            chi,
            &old,
            0.0,
            1.0,
            1e6,
            1e6,
        );
        assert_eq!(u.new.state, 0.0);
        assert_eq!(u.new.gap, 0.0);
        assert!((u.new.dynamic_stress - 0.3e6).abs() < 1e-6);
        // above: slips forward with tau = mu N
        for scheme in [InterfaceScheme::Average, InterfaceScheme::Backward] {
            let u = shear_step(scheme, &tl, 2e6 * chi, chi, &old, 0.0, 1.0, 1e6, 1e6);
            assert_eq!(u.new.state, 1.0);
            assert!(u.new.gap > 0.0);
            assert_eq!(u.new.slider, 0.5e6);
            assert_eq!(u.new.dynamic_stress, 0.5e6);
        }
    }
}

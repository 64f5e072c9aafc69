//! Coulomb friction: `|tau_f| <= mu N` with `N` the normal contact pressure (zero when the
//! interface is open). Before sliding the contact sticks, rigidly (`[u]_T` frozen) or
//! elastically through a stick stiffness `k_t` in series with the slider
//! (`tau_f = q0 + k_t ([u]_T - s)`, `s` the accumulated slip).
//!
//! Besides the branch, this file holds the slider every tangential branch owns (model.md
//! section 13): its state ([`ShearState`]), its stress in each phase of the exact solvers
//! ([`SliderPhase`], [`slider_stress`]) and its return mapping in the time-stepping ones
//! ([`return_map`]). The friction coefficient may depend on the slip path (the branch's
//! [`TangentialBranch::friction_at`], e.g. slip weakening); every branch's slider is this one.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{non_negative, positive, stiffness_at_most, ParamMut};
use crate::law::scheme::InterfaceScheme;
use crate::law::{TangentialBranch, TangentialPart};

/// Coulomb friction branch.
#[derive(Debug, Clone, Copy)]
pub struct Coulomb {
    /// Friction coefficient mu (>= 0).
    pub friction: f64,
    /// Stick stiffness k_t, Pa/m; `f64::INFINITY` for rigid stick.
    pub stick_stiffness: f64,
}

impl TangentialBranch for Coulomb {
    fn name(&self) -> &'static str {
        "coulomb"
    }
    fn friction(&self) -> f64 {
        self.friction
    }
    fn stick_stiffness(&self) -> f64 {
        self.stick_stiffness
    }
}

/// Parameters of `law = "coulomb"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Friction coefficient mu (>= 0); the key `mu` is read as this one.
    #[serde(alias = "mu")]
    pub friction: f64,
    /// Stick stiffness k_t, Pa/m (> 0; default: rigid stick).
    #[serde(default)]
    pub stiffness: Option<f64>,
}

impl LawSpec for Spec {
    type Branch = dyn TangentialBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>> {
        non_negative(file, &format!("{prefix}.friction"), self.friction)?;
        if let Some(k) = self.stiffness {
            positive(file, &format!("{prefix}.stiffness"), k)?;
            stiffness_at_most(file, &format!("{prefix}.stiffness"), k)?;
        }
        Ok(Box::new(Coulomb {
            friction: self.friction,
            stick_stiffness: self.stiffness.unwrap_or(f64::INFINITY),
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "friction" | "mu" => Some(ParamMut::F64(&mut self.friction)),
            "stiffness" => Some(ParamMut::OptF64(&mut self.stiffness)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        (name == "stiffness").then_some("Pa/m")
    }
}

/// Phase of the slider in the exact (event-located) solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SliderPhase {
    /// No slider load possible: no friction or no normal contact; `tau_f = 0`.
    Free,
    /// Slider sticking.
    Stick,
    /// Slider slipping in the direction of the sign (+1 or -1), `tau_f = sign mu N`.
    Slip(f64),
}

/// The slider's stress `tau_f` (Pa) in `phase` (not rigid stick, whose stress is the
/// constraint's reaction): elastic stick `q0 + k_t ([u]_T - s)` at tangential gap `u_t` (m)
/// and frozen slip `slip` (m); slip `sign mu(path) N` at slip path `path` (m) and contact
/// pressure `pressure` (Pa); free: the static shear `q0` when there is no slider at all
/// (a spring carries it), else 0.
pub fn slider_stress<G: TangentialPart + ?Sized>(
    law: &G,
    phase: SliderPhase,
    u_t: f64,
    slip: f64,
    path: f64,
    pressure: f64,
) -> f64 {
    let br = law.branch();
    match phase {
        SliderPhase::Stick => law.static_shear() + br.stick_stiffness() * (u_t - slip),
        SliderPhase::Slip(sg) => sg * law.friction_limit(pressure, path),
        SliderPhase::Free if br.friction() == 0.0 => law.static_shear(),
        SliderPhase::Free => 0.0,
    }
}

/// Tangential state carried from step to step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ShearState {
    /// Tangential gap `[u]_T`, m.
    pub gap: f64,
    /// Accumulated slip s of the slider, m.
    pub slip: f64,
    /// Slip path `integral |ds|`, m: what a slip-dependent friction coefficient reads.
    pub path: f64,
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
    pub fn at_rest<G: TangentialPart + ?Sized>(law: &G, p0: f64) -> Self {
        let q0 = law.static_shear();
        let sticking = law.branch().friction() > 0.0 && p0 > 0.0;
        let kt = law.branch().stick_stiffness();
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
pub fn return_map<G: TangentialPart + ?Sized>(
    scheme: InterfaceScheme,
    law: &G,
    gt: f64,
    chi: f64,
    old: &ShearState,
    t_old: f64,
    beta: f64,
    pressure: f64,
    pressure_applied: f64,
) -> ShearUpdate {
    let br = law.branch();
    let q0 = law.static_shear();
    let k = br.spring_stiffness(beta);
    let kt = br.stick_stiffness();
    // the coefficient at the slip path of the current level (explicit in the path: a
    // slip-dependent coefficient lags one step, first order in dt)
    let limit = law.friction_limit(pressure, old.path);
    let limit_applied = law.friction_limit(pressure_applied, old.path);
    let avg = scheme == InterfaceScheme::Average;
    let w_compliant = if avg { 0.5 } else { 1.0 };
    let finish = |[g, t_new, applied]: [f64; 3], tau_f: f64, slip: f64, state: f64| ShearUpdate {
        new: ShearState {
            gap: g,
            slip,
            path: old.path + (slip - old.slip).abs(),
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
        // free: no slider load; the slip follows the gap through the (unloaded) stick
        // spring. Faces that carry nothing (no tangential spring either) take the new
        // level's stress, as open traction-free faces do in the normal update: the mean
        // with an earlier stick or slip stress would do work that no branch of the law can
        let w = if k == 0.0 { 1.0 } else { w_compliant };
        let r = given_slider(gt, chi, w, k, 0.0, q0, t_old);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::registry::{build_law, build_tangential};
    use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};

    #[test]
    fn rigid_stick_return_mapping_clips_at_mu_n_and_slips_forward() {
        let law = build_law(
            1e6,
            &CompressionSpec::Rigid(Default::default()),
            &TractionSpec::Free(Default::default()),
            "<t>",
            "i",
        )
        .unwrap();
        let tl = build_tangential(
            &TangentialSpec::Coulomb(crate::law::tangential::coulomb::Spec {
                friction: 0.5,
                stiffness: None,
            }),
            0.0,
            &law,
            "<t>",
            "i",
        )
        .unwrap();
        let chi = 1e-13;
        let old = ShearState::default();
        // below the limit: sticks, the stress is the constraint reaction
        let u = return_map(
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
            let u = return_map(scheme, &tl, 2e6 * chi, chi, &old, 0.0, 1.0, 1e6, 1e6);
            assert_eq!(u.new.state, 1.0);
            assert!(u.new.gap > 0.0);
            assert_eq!(u.new.slider, 0.5e6);
            assert_eq!(u.new.dynamic_stress, 0.5e6);
        }
    }
}

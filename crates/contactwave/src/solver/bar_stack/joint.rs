//! The interfaces of the stack as the time loop sees them: which nodes a contact joins
//! (a rigid obstacle is a missing side), the state it carries from step to step, and its
//! implicit update: the normal law alone ([`super::super::interface::update`] in the
//! chosen [`InterfaceScheme`]), or the coupled normal and tangential law
//! ([`coupled_step`]) when the stack carries a shear field.

use super::field::Field;
use super::InterfaceScheme;
use crate::error::Result;
use crate::law::{ContactLaw, TangentialLaw, WarmStart};
use crate::solver::interface;
use crate::solver::interface_shear::{coupled_step, CoupledStepInput, ShearState};

/// The two nodes an interface joins, `a` on its first side and `b` on its second; `None`
/// is a rigid obstacle. The gap is `u_b - u_a`; a dynamic stress `S` (tension positive)
/// pulls `a` forward and `b` back.
#[derive(Debug, Clone, Copy)]
pub(super) struct Joint {
    pub a: Option<usize>,
    pub b: Option<usize>,
}

impl Joint {
    #[inline]
    fn gap(&self, u: &[f64]) -> f64 {
        match (self.a, self.b) {
            (Some(a), Some(b)) => u[b] - u[a],
            (None, Some(b)) => u[b],
            (Some(a), None) => -u[a],
            (None, None) => 0.0,
        }
    }

    /// Compliances of the two sides in `field`, m/Pa (0 for an obstacle).
    #[inline]
    fn compliances(&self, field: &Field) -> (f64, f64) {
        (
            self.a.map_or(0.0, |a| field.compliance(a)),
            self.b.map_or(0.0, |b| field.compliance(b)),
        )
    }

    #[inline]
    fn apply(&self, u: &mut [f64], (chi_a, chi_b): (f64, f64), s: f64) {
        if let Some(a) = self.a {
            u[a] += chi_a * s;
        }
        if let Some(b) = self.b {
            u[b] -= chi_b * s;
        }
    }
}

/// What every interface update of one time step shares.
#[derive(Debug, Clone, Copy)]
pub(super) struct StepContext {
    pub scheme: InterfaceScheme,
    /// Time step, s.
    pub dt: f64,
    /// The new time level, s (for error messages).
    pub t: f64,
}

/// The state of one interface carried between steps.
#[derive(Debug, Clone, Copy)]
pub(super) struct JointState {
    /// Adhesion of the current level.
    pub beta: f64,
    /// Normal dynamic stress of the previous-but-one and the current level, Pa.
    pub s_prev: f64,
    pub s_cur: f64,
    /// Normal gap, m.
    pub gap: f64,
    /// Normal contact stress sigma (tension positive, -p0 at rest), Pa.
    pub stress: f64,
    /// Warm start of the compression branch's own interface solver.
    pub warm: WarmStart,
    /// Tangential state (with a shear field).
    pub shear: ShearState,
    /// Tangential dynamic stress of the previous-but-one and the current level, Pa.
    pub t_prev: f64,
    pub t_cur: f64,
    /// Frictional dissipation so far, `sum tau_f Delta s`, J/m^2 (with a shear field).
    pub friction: f64,
    /// Energy released by damage so far, `sum (dpsi/dbeta) (-Delta beta)`, J/m^2 (with a
    /// shear field).
    pub damage: f64,
}

impl JointState {
    /// At rest at the pre-loaded equilibrium of `law`; the slider of `tangential` (when
    /// given) holds the static shear.
    pub fn at_rest(law: &ContactLaw, tangential: Option<&TangentialLaw>) -> Self {
        JointState {
            beta: 1.0,
            s_prev: 0.0,
            s_cur: 0.0,
            gap: 0.0,
            stress: -law.static_pressure,
            warm: WarmStart::default(),
            shear: tangential.map_or_else(ShearState::default, |tl| {
                ShearState::at_rest(tl, law.static_pressure)
            }),
            t_prev: 0.0,
            t_cur: 0.0,
            friction: 0.0,
            damage: 0.0,
        }
    }

    /// Contact shear stress tau = T + q0 of the current level, Pa.
    pub fn shear_stress(&self, tangential: &TangentialLaw) -> f64 {
        self.shear.dynamic_stress + tangential.static_shear
    }

    fn finish_normal(&mut self, upd: interface::InterfaceUpdate, law: &ContactLaw) {
        self.s_prev = self.s_cur;
        self.s_cur = upd.dynamic_stress;
        self.gap = upd.gap;
        self.stress = upd.dynamic_stress - law.static_pressure;
        self.beta = upd.adhesion;
    }
}

/// One interface update of the normal law alone from the state `st` (adhesion, the
/// dynamic stress two levels back, the compression branch's warm start); returns the
/// update (its `dynamic_stress` the stress of the new level) and the stress to apply over
/// the step.
#[inline]
fn interface_step(
    ctx: StepContext,
    law: &ContactLaw,
    gt: f64,
    chi: f64,
    st: &mut JointState,
) -> Result<(interface::InterfaceUpdate, f64)> {
    let StepContext { scheme, dt, t } = ctx;
    let (beta_old, s_old) = (st.beta, st.s_prev);
    let warm = &mut st.warm;
    if scheme == InterfaceScheme::Average {
        // g = g~ - chi (S_new + S_old) / 2: the update with compliance chi/2 from the
        // shifted prediction g~ - chi S_old / 2
        let gs = gt - 0.5 * chi * s_old;
        let upd = interface::update(law, gs, 0.5 * chi, beta_old, Some(warm), dt, t)?;
        let uc = law.critical_gap();
        let on_constraint = (upd.gap <= uc && law.compression.is_rigid())
            || (upd.gap >= uc && law.traction.is_rigid());
        if !on_constraint {
            return Ok((upd, 0.5 * (upd.dynamic_stress + s_old)));
        }
    }
    let upd = interface::update(law, gt, chi, beta_old, Some(warm), dt, t)?;
    Ok((upd, upd.dynamic_stress))
}

/// Update the interface `joint` at the new level: the normal law on `normal` alone, or,
/// with a shear field and the interface's tangential law, the coupled normal/tangential
/// step on both fields. The forces are applied to the fields' next level.
pub(super) fn update(
    ctx: StepContext,
    law: &ContactLaw,
    joint: Joint,
    st: &mut JointState,
    normal: &mut Field,
    shear: Option<(&mut Field, Joint, &TangentialLaw)>,
) -> Result<()> {
    let chi = joint.compliances(normal);
    let gn = joint.gap(&normal.u_next);
    let Some((sf, joint_t, tl)) = shear else {
        let (upd, s_app) = interface_step(ctx, law, gn, chi.0 + chi.1, st)?;
        joint.apply(&mut normal.u_next, chi, s_app);
        st.finish_normal(upd, law);
        return Ok(());
    };
    let chi_t = joint_t.compliances(sf);
    let input = CoupledStepInput {
        scheme: ctx.scheme,
        chi_n: chi.0 + chi.1,
        chi_t: chi_t.0 + chi_t.1,
        beta_old: st.beta,
        s_old: st.s_prev,
        t_old: st.t_prev,
        dt: ctx.dt,
        t: ctx.t,
    };
    let upd = coupled_step(law, tl, gn, joint_t.gap(&sf.u_next), &st.shear, &input)?;
    joint.apply(&mut normal.u_next, chi, upd.normal_applied);
    joint_t.apply(&mut sf.u_next, chi_t, upd.shear.applied);
    let new = upd.shear.new;
    st.friction += new.slider * (new.slip - st.shear.slip);
    let b = upd.normal.adhesion;
    if b != st.beta {
        let d = (upd.normal.gap - law.critical_gap()).max(0.0);
        let psi_beta =
            law.traction.energy_d_adhesion(d, b) + tl.branch.spring_energy_d_adhesion(b, new.gap);
        st.damage += psi_beta * (st.beta - b);
    }
    st.t_prev = st.t_cur;
    st.t_cur = new.dynamic_stress;
    st.shear = new;
    st.finish_normal(upd.normal, law);
    Ok(())
}

//! The interfaces of the stack as the time loop sees them: which nodes a contact joins
//! (a rigid obstacle is a missing side), and how a contact point's update
//! ([`crate::law::contact::update_point`]: the normal law alone, or the coupled normal and
//! tangential law when the stack carries a shear field) reads its trial gaps and
//! compliances from the fields and applies its stresses back to them.

use super::field::Field;
use crate::error::Result;
use crate::law::contact::{update_point, PointState, StepContext, Trial};
use crate::law::{ContactLaw, TangentialLaw};

/// The two nodes an interface joins, `a` on its first side and `b` on its second; `None`
/// is a rigid obstacle. The gap is `u_b - u_a`; a dynamic stress `S` (tension positive)
/// pulls `a` forward and `b` back.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Joint {
    pub a: Option<usize>,
    pub b: Option<usize>,
}

impl Joint {
    /// The gap `u_b - u_a` on the displacements `u`, m.
    #[inline]
    pub(crate) fn gap(&self, u: &[f64]) -> f64 {
        match (self.a, self.b) {
            (Some(a), Some(b)) => u[b] - u[a],
            (None, Some(b)) => u[b],
            (Some(a), None) => -u[a],
            (None, None) => 0.0,
        }
    }

    /// Compliances of the two sides in `field`, m/Pa (0 for an obstacle).
    #[inline]
    pub(crate) fn compliances(&self, field: &Field) -> (f64, f64) {
        (
            self.a.map_or(0.0, |a| field.compliance(a)),
            self.b.map_or(0.0, |b| field.compliance(b)),
        )
    }

    /// Apply the dynamic stress `s` (Pa) over the step with the sides' compliances.
    #[inline]
    pub(crate) fn apply(&self, u: &mut [f64], (chi_a, chi_b): (f64, f64), s: f64) {
        if let Some(a) = self.a {
            u[a] += chi_a * s;
        }
        if let Some(b) = self.b {
            u[b] -= chi_b * s;
        }
    }
}

/// Update the interface `joint` at the new level ([`update_point`]): the normal law on
/// `normal` alone, or, with a shear field and the interface's tangential law, the coupled
/// normal/tangential step on both fields. The forces are applied to the fields' next level.
pub(super) fn update(
    ctx: StepContext,
    law: &ContactLaw,
    joint: Joint,
    st: &mut PointState,
    normal: &mut Field,
    shear: Option<(&mut Field, Joint, &TangentialLaw)>,
) -> Result<()> {
    let chi = joint.compliances(normal);
    let mut trial = Trial {
        normal_gap: joint.gap(&normal.u_next),
        normal_compliance: chi.0 + chi.1,
        ..Trial::default()
    };
    let Some((sf, joint_t, tl)) = shear else {
        let [s_app, _] = update_point(law, None::<&TangentialLaw>, &trial, ctx, st)?;
        joint.apply(&mut normal.u_next, chi, s_app);
        return Ok(());
    };
    let chi_t = joint_t.compliances(sf);
    trial.tangential_gap = joint_t.gap(&sf.u_next);
    trial.tangential_compliance = chi_t.0 + chi_t.1;
    let [s_app, t_app] = update_point(law, Some(tl), &trial, ctx, st)?;
    joint.apply(&mut normal.u_next, chi, s_app);
    joint_t.apply(&mut sf.u_next, chi_t, t_app);
    Ok(())
}

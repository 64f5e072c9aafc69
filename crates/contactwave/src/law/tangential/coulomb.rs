//! Coulomb friction: `|tau| <= mu N` with `N` the normal contact pressure (zero when the
//! interface is open). Before sliding the contact sticks, rigidly (`[u]_T` frozen) or
//! elastically through a stick stiffness `k_t` in series with the slider
//! (`tau = q0 + k_t ([u]_T - s)`, `s` the accumulated slip).

use crate::law::TangentialBranch;

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

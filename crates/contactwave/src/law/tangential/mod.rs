//! Tangential branches, one per file (model.md section 13): the shear stress an interface
//! carries as a function of the tangential gap `[u]_T` (slip-positive along +y), the
//! adhesion `beta` shared with the traction branch, and the normal contact pressure `N`
//! through Coulomb friction.
//!
//! Every branch is a reversible spring `k(beta) [u]_T` in parallel with a Coulomb slider
//! (friction coefficient `mu`, possibly falling with the slip path; optional stick
//! stiffness `k_t` in series: rigid stick when infinite); the slider itself (state, phase
//! stresses, return mapping) is in [`coulomb`]. The solvers only ask for these numbers,
//! never for a branch's name.
//!
//! A law is one file: its branch, and its parameters as scenario files give them (a
//! `Spec` implementing [`crate::law::param::LawSpec`]: validation, building, names for
//! `[set]` and sweeps, units); and one line in the table at the end of this file, which
//! makes it a `law = "..."` of [`TangentialSpec`].

pub mod coulomb;
pub mod free;
pub mod linear;
pub mod rccm;
pub mod slip_weakening;

pub use coulomb::Coulomb;
pub use free::Free;
pub use linear::Linear;
pub use rccm::Rccm;
pub use slip_weakening::SlipWeakening;

use super::param::law_table;
use super::TangentialBranch;

law_table! {
    /// Tangential branch of the contact law (model.md section 13), as a scenario gives it:
    /// `{ law = "<name>", <parameters> }`.
    TangentialSpec: dyn TangentialBranch {
        /// No shear stress (free sliding).
        Free(free::Spec),
        /// `tau - q0 = C_T [u]_T`, open or closed.
        Linear(linear::Spec),
        /// Coulomb friction `|tau| <= mu N`; rigid stick, or elastic stick with `stiffness`.
        Coulomb(coulomb::Spec),
        /// Full RCCM: adhesive spring `beta^2 C_T [u]_T` and Coulomb friction; needs the RCCM
        /// traction branch (its `C_N`, `w`, `b` and adhesion).
        Rccm(rccm::Spec),
        /// Linear slip weakening: Coulomb friction (rigid stick) whose coefficient falls from
        /// `mu_s` to `mu_d` over the slip path `d_c`.
        SlipWeakening(slip_weakening::Spec),
    }
}

impl Default for TangentialSpec {
    fn default() -> Self {
        TangentialSpec::Free(free::Spec {})
    }
}

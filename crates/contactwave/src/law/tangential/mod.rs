//! Tangential branches, one per file (model.md section 13): the shear stress an interface
//! carries as a function of the tangential gap `[u]_T` (slip-positive along +y), the
//! adhesion `beta` shared with the traction branch, and the normal contact pressure `N`
//! through Coulomb friction.
//!
//! Every branch is a reversible spring `k(beta) [u]_T` in parallel with a Coulomb slider
//! (friction coefficient `mu`, optional stick stiffness `k_t` in series: rigid stick when
//! infinite). The solvers only ask for these numbers, never for a branch's name.

pub mod coulomb;
pub mod free;
pub mod linear;
pub mod rccm;

pub use coulomb::Coulomb;
pub use free::Free;
pub use linear::Linear;
pub use rccm::Rccm;

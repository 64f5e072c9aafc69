//! Traction branches, one per file (model.md section 2, second table).

pub mod bonded;
pub mod free;
pub mod linear;
pub mod rccm;

pub use bonded::Bonded;
pub use free::Free;
pub use linear::Linear;
pub use rccm::Rccm;

use super::param::law_table;
use super::TractionBranch;

law_table! {
    /// Traction branch of the contact law (model.md section 2), as a scenario gives it:
    /// `{ law = "<name>", <parameters> }`. A law is one file of this folder (its branch and
    /// its `Spec`) and one line of this table.
    TractionSpec: dyn TractionBranch {
        /// `sigma = 0` (unilateral contact, clapping).
        Free(free::Spec),
        /// `sigma = K_t d`, `d = [u] - [u]_c`.
        Linear(linear::Spec),
        /// RCCM adhesion with damage: `sigma = beta^2 C_N d`,
        /// `b dbeta/dt = min(w - beta C_N d^2, 0)`.
        Rccm(rccm::Spec),
        /// Perfect bond: d = 0 (bilateral contact, the linear reference).
        Bonded(bonded::Spec),
    }
}

impl Default for TractionSpec {
    fn default() -> Self {
        TractionSpec::Free(free::Spec {})
    }
}

//! Compression branches, one per file (model.md section 2, first table).

pub mod curve;
pub mod linear;
pub mod modified_power;
pub mod power;
pub mod quadratic;
pub mod rigid;
pub mod table;

pub use curve::{StiffnessCurve, StiffnessPressure};
pub use linear::Linear;
pub use modified_power::ModifiedPower;
pub use power::Power;
pub use quadratic::Quadratic;
pub use rigid::Rigid;
pub use table::Table;

use super::param::law_table;
use super::CompressionBranch;

law_table! {
    /// Compression branch of the contact law (model.md section 2), as a scenario gives it:
    /// `{ law = "<name>", <parameters> }`. A law is one file of this folder (its branch
    /// and its `Spec`) and one line of this table.
    CompressionSpec: dyn CompressionBranch {
        /// Signorini: no penetration, no penalty.
        Rigid(rigid::Spec),
        /// `sigma = -p0 + K [u]`.
        Linear(linear::Spec),
        /// `sigma = -p0 + K0 [u] - K1 [u]^2` (thesis eq. 1.3).
        Quadratic(quadratic::Spec),
        /// Stiffness `dp/d(closure) = C p^m` (thesis eq. 4.4).
        Power(power::Spec),
        /// Power law above `transition_pressure`, a smooth branch with an inflection below
        /// (thesis section 4.2, Figure 63).
        ModifiedPower(modified_power::Spec),
        /// Stiffness tabulated against pressure, monotone (PCHIP) interpolation.
        Table(table::Spec),
    }
}

impl Default for CompressionSpec {
    fn default() -> Self {
        CompressionSpec::Rigid(rigid::Spec {})
    }
}

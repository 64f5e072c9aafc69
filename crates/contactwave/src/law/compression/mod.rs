//! Compression branches, one per file (model.md section 3, first table).

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

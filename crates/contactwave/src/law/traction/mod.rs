//! Traction branches, one per file (model.md section 3, second table).

pub mod bonded;
pub mod free;
pub mod linear;
pub mod rccm;

pub use bonded::Bonded;
pub use free::Free;
pub use linear::Linear;
pub use rccm::Rccm;

//! The parameters of each law branch, as scenario files give them: the tables of the three
//! kinds (each law's own `Spec` in its file, registered by one line of its kind's table:
//! `law::param::law_table!`). The scenario format embeds them under `[interface]`;
//! [`super::registry`] builds whole laws from them. Units in the doc comments; every key is
//! documented in `docs/scenario.md`.

pub use super::compression::CompressionSpec;
pub use super::tangential::TangentialSpec;
pub use super::traction::TractionSpec;

//! Solvers. [`halfspace`]: the exact solver of the half-space problem (model.md section 4).

pub mod halfspace;
pub mod radau;

//! Solvers. [`halfspace`]: the exact solver of the half-space problem (model.md section 4).

pub mod barstack;
pub mod halfspace;
pub mod halfspace_fd;
pub mod interface;
pub mod radau;

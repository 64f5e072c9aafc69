//! Linear tangential spring `tau - q0 = C_T [u]_T`, acting whether the interface is open or
//! closed (a bonded interface of finite shear stiffness; the shear analogue of the
//! spring-interface model).

use crate::law::TangentialBranch;

/// Linear tangential branch.
#[derive(Debug, Clone, Copy)]
pub struct Linear {
    /// Tangential stiffness C_T, Pa/m.
    pub stiffness: f64,
}

impl TangentialBranch for Linear {
    fn name(&self) -> &'static str {
        "linear"
    }
    fn spring_stiffness(&self, _adhesion: f64) -> f64 {
        self.stiffness
    }
}

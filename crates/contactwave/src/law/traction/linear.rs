//! Linear traction spring `sigma = K_t d`, `d = [u] - [u]_c` (the traction side of the
//! bilinear law of chapter 5, in its continuous form; model.md section 4).

use crate::law::TractionBranch;

/// Linear traction branch.
#[derive(Debug, Clone, Copy)]
pub struct Linear {
    /// Stiffness K_t, Pa/m.
    pub stiffness: f64,
}

impl TractionBranch for Linear {
    fn name(&self) -> &'static str {
        "linear"
    }
    fn stress(&self, opening: f64, _adhesion: f64) -> f64 {
        self.stiffness * opening
    }
    fn tangent(&self, _opening: f64, _adhesion: f64) -> f64 {
        self.stiffness
    }
    fn energy(&self, opening: f64, _adhesion: f64) -> f64 {
        0.5 * self.stiffness * opening * opening
    }
    fn is_affine(&self) -> bool {
        true
    }
}

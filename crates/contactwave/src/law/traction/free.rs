//! Traction-free opening: `sigma = 0` (unilateral contact, clapping; thesis eq. 2.15).

use crate::law::TractionBranch;

/// Free traction branch.
#[derive(Debug, Clone, Copy, Default)]
pub struct Free;

impl TractionBranch for Free {
    fn name(&self) -> &'static str {
        "free"
    }
    fn stress(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    fn tangent(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    fn energy(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    fn is_affine(&self) -> bool {
        true
    }
}

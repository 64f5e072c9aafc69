//! Linear compression spring: `sigma = -p0 + K [u]`, `[u]_c = p0 / K` (thesis eq. 5.4,
//! the compression side of the bilinear law of chapter 5).

use crate::law::CompressionBranch;

/// Linear compression branch.
#[derive(Debug, Clone, Copy)]
pub struct Linear {
    /// Static pressure p0, Pa.
    pub static_pressure: f64,
    /// Stiffness K, Pa/m.
    pub stiffness: f64,
}

impl CompressionBranch for Linear {
    fn name(&self) -> &'static str {
        "linear"
    }
    fn critical_gap(&self) -> f64 {
        self.static_pressure / self.stiffness
    }
    fn stress(&self, gap: f64) -> f64 {
        -self.static_pressure + self.stiffness * gap
    }
    fn tangent(&self, _gap: f64) -> f64 {
        self.stiffness
    }
    fn energy(&self, gap: f64) -> f64 {
        0.5 * self.stiffness * gap * gap
    }
    fn is_affine(&self) -> bool {
        true
    }
}

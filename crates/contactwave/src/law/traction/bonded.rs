//! Bonded traction: the opening is locked, `d = 0` (bilateral perfect contact, the linear
//! reference). The stress is whatever the constraint needs.

use crate::law::TractionBranch;

/// Bonded (rigid) traction branch.
#[derive(Debug, Clone, Copy, Default)]
pub struct Bonded;

impl TractionBranch for Bonded {
    fn name(&self) -> &'static str {
        "bonded"
    }
    fn is_rigid(&self) -> bool {
        true
    }
    fn stress(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    fn tangent(&self, _opening: f64, _adhesion: f64) -> f64 {
        f64::INFINITY
    }
    fn energy(&self, _opening: f64, _adhesion: f64) -> f64 {
        0.0
    }
    fn stiffness_at_contact(&self) -> f64 {
        f64::INFINITY
    }
}

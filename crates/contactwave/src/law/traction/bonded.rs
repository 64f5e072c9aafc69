//! Bonded traction: the opening is locked, `d = 0` (bilateral perfect contact, the linear
//! reference). The stress is whatever the constraint needs.

use crate::error::Result;
use crate::law::param::LawSpec;
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

/// Parameters of `law = "bonded"`: none.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {}

impl LawSpec for Spec {
    type Branch = dyn TractionBranch;
    fn build(&self, _p0: f64, _file: &str, _prefix: &str) -> Result<Box<dyn TractionBranch>> {
        Ok(Box::new(Bonded))
    }
}

//! Traction-free opening: `sigma = 0` (unilateral contact, clapping; thesis eq. 2.15).

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::TractionBranch;

/// Free traction branch.
#[derive(Debug, Clone, Copy, Default)]
pub struct Free;

impl TractionBranch for Free {
    fn name(&self) -> &'static str {
        "free"
    }
    fn is_free(&self) -> bool {
        true
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

/// Parameters of `law = "free"`: none.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {}

impl LawSpec for Spec {
    type Branch = dyn TractionBranch;
    fn build(&self, _p0: f64, _file: &str, _prefix: &str) -> Result<Box<dyn TractionBranch>> {
        Ok(Box::new(Free))
    }
}

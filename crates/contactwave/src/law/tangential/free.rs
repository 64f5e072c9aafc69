//! No tangential stress: the faces slide freely (`tau = 0`), the interface reflects a
//! normally incident shear wave completely.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::TangentialBranch;

/// Free tangential branch.
#[derive(Debug, Clone, Copy)]
pub struct Free;

impl TangentialBranch for Free {
    fn name(&self) -> &'static str {
        "free"
    }
}

/// Parameters of `law = "free"`: none.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {}

impl LawSpec for Spec {
    type Branch = dyn TangentialBranch;
    fn build(&self, _p0: f64, _file: &str, _prefix: &str) -> Result<Box<dyn TangentialBranch>> {
        Ok(Box::new(Free))
    }
}

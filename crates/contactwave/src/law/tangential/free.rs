//! No tangential stress: the faces slide freely (`tau = 0`), the interface reflects a
//! normally incident shear wave completely.

use crate::law::TangentialBranch;

/// Free tangential branch.
#[derive(Debug, Clone, Copy)]
pub struct Free;

impl TangentialBranch for Free {
    fn name(&self) -> &'static str {
        "free"
    }
}

//! Linear traction spring `sigma = K_t d`, `d = [u] - [u]_c` (the traction side of the
//! bilinear law of chapter 5, in its continuous form; model.md section 2).

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{positive, stiffness_at_most, ParamMut};
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

/// Parameters of `law = "linear"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// K_t, Pa/m (> 0).
    pub stiffness: f64,
}

impl LawSpec for Spec {
    type Branch = dyn TractionBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TractionBranch>> {
        positive(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        stiffness_at_most(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        Ok(Box::new(Linear {
            stiffness: self.stiffness,
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        (name == "stiffness").then_some(ParamMut::F64(&mut self.stiffness))
    }
    fn unit(name: &str) -> Option<&'static str> {
        (name == "stiffness").then_some("Pa/m")
    }
}

//! Linear compression spring: `sigma = -p0 + K [u]`, `[u]_c = p0 / K` (thesis eq. 5.4,
//! the compression side of the bilinear law of chapter 5).

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{positive, stiffness_at_most, ParamMut};
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

/// Parameters of `law = "linear"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// K, Pa/m (> 0).
    pub stiffness: f64,
}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        positive(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        stiffness_at_most(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        Ok(Box::new(Linear {
            static_pressure: p0,
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

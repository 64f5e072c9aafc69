//! Rigid compression: Signorini's conditions `[u] >= 0, sigma <= 0, [u] sigma = 0`
//! (thesis section 1.2, eq. 2.10), exact, with no penalty and no regularisation.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::CompressionBranch;

/// Signorini (rigid) compression branch; `[u]_c = 0`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rigid {
    /// Static pressure p0, Pa.
    pub static_pressure: f64,
}

impl CompressionBranch for Rigid {
    fn name(&self) -> &'static str {
        "rigid"
    }
    fn is_rigid(&self) -> bool {
        true
    }
    fn critical_gap(&self) -> f64 {
        0.0
    }
    fn stress(&self, _gap: f64) -> f64 {
        -self.static_pressure
    }
    fn tangent(&self, _gap: f64) -> f64 {
        f64::INFINITY
    }
    fn energy(&self, _gap: f64) -> f64 {
        0.0
    }
    fn stiffness_at_rest(&self) -> f64 {
        f64::INFINITY
    }
}

/// Parameters of `law = "rigid"`: none.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, _file: &str, _prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        Ok(Box::new(Rigid {
            static_pressure: p0,
        }))
    }
}

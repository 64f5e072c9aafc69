//! Linear tangential spring `tau - q0 = C_T [u]_T`, acting whether the interface is open or
//! closed (a bonded interface of finite shear stiffness; the shear analogue of the
//! spring-interface model).

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{positive, stiffness_at_most, ParamMut};
use crate::law::TangentialBranch;

/// Linear tangential branch.
#[derive(Debug, Clone, Copy)]
pub struct Linear {
    /// Tangential stiffness C_T, Pa/m.
    pub stiffness: f64,
}

impl TangentialBranch for Linear {
    fn name(&self) -> &'static str {
        "linear"
    }
    fn spring_stiffness(&self, _adhesion: f64) -> f64 {
        self.stiffness
    }
}

/// Parameters of `law = "linear"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// C_T, Pa/m (> 0).
    pub stiffness: f64,
}

impl LawSpec for Spec {
    type Branch = dyn TangentialBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>> {
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

//! The tangential half of the full RCCM law (Raous-Cangemi-Cocu-Monerie; thesis chapter 1,
//! "The constitutive parameters", Figure 5): an adhesive spring `beta^2 C_T [u]_T` in
//! parallel with rigid-stick Coulomb friction on the non-adhesive part of the normal
//! reaction, `|tau - q0 - beta^2 C_T [u]_T| <= mu N`. The adhesion `beta` is the traction
//! branch's (RCCM): its free energy gains `beta^2 C_T [u]_T^2 / 2`, so that damage is
//! driven by `w - beta (C_N d^2 + C_T [u]_T^2)`. With the adhesion gone the law is
//! Signorini (or the compression branch) with Coulomb friction.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{non_negative, stiffness_at_most, ParamMut};
use crate::law::TangentialBranch;

/// Tangential RCCM branch.
#[derive(Debug, Clone, Copy)]
pub struct Rccm {
    /// Initial tangential stiffness C_T, Pa/m (>= 0).
    pub stiffness: f64,
    /// Friction coefficient mu (>= 0).
    pub friction: f64,
}

impl TangentialBranch for Rccm {
    fn name(&self) -> &'static str {
        "rccm"
    }
    fn spring_stiffness(&self, adhesion: f64) -> f64 {
        adhesion * adhesion * self.stiffness
    }
    fn spring_stiffness_d_adhesion(&self, adhesion: f64) -> f64 {
        2.0 * adhesion * self.stiffness
    }
    fn friction(&self) -> f64 {
        self.friction
    }
    fn needs_adhesion(&self) -> bool {
        true
    }
}

/// Parameters of `law = "rccm"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// C_T, Pa/m (>= 0).
    pub stiffness: f64,
    /// Friction coefficient mu (>= 0); the key `mu` is read as this one.
    #[serde(alias = "mu")]
    pub friction: f64,
}

impl LawSpec for Spec {
    type Branch = dyn TangentialBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>> {
        non_negative(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        stiffness_at_most(file, &format!("{prefix}.stiffness"), self.stiffness)?;
        non_negative(file, &format!("{prefix}.friction"), self.friction)?;
        Ok(Box::new(Rccm {
            stiffness: self.stiffness,
            friction: self.friction,
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "stiffness" => Some(ParamMut::F64(&mut self.stiffness)),
            "friction" | "mu" => Some(ParamMut::F64(&mut self.friction)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        (name == "stiffness").then_some("Pa/m")
    }
}

//! Modified power law (thesis section 4.2, Figure 63): the power law `K = C p^m` above a
//! transition pressure `p_t` (0.2 MPa in the thesis) and, below it, a smooth branch with an
//! inflection point, as reported for low contact pressures.
//!
//! The thesis gives the shape only graphically; contactwave uses the cubic Hermite branch
//! on `[0, p_t]` with `K(0) = phi K(p_t)` (`zero_pressure_fraction`, default 0.2),
//! `K'(0) = 0`, and value and slope matching the power law at `p_t` (C1 joint). The cubic
//! is convex near 0 and concave near `p_t`: one inflection point in between.

use super::curve::{StiffnessCurve, StiffnessPressure};
use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{exponent, positive, ParamMut};
use crate::law::CompressionBranch;

/// Stiffness-pressure relation of the modified power law.
#[derive(Debug, Clone, Copy)]
pub struct ModifiedPowerStiffness {
    /// C, Pa^(1-m)/m.
    pub c: f64,
    /// m in (0, 1).
    pub m: f64,
    /// Transition pressure p_t, Pa.
    pub transition_pressure: f64,
    /// K(0) / K(p_t), in (0, 1).
    pub zero_pressure_fraction: f64,
    /// K(p_t) = C p_t^m, Pa/m (cached by [`ModifiedPowerStiffness::new`]).
    kt: f64,
    /// dK/dp at p_t, m K(p_t) / p_t, 1/m (cached by [`ModifiedPowerStiffness::new`]).
    dkt: f64,
}

impl ModifiedPowerStiffness {
    /// The relation with parameters C (Pa^(1-m)/m), m, p_t (Pa) and K(0)/K(p_t).
    pub fn new(c: f64, m: f64, transition_pressure: f64, zero_pressure_fraction: f64) -> Self {
        let kt = c * transition_pressure.powf(m);
        ModifiedPowerStiffness {
            c,
            m,
            transition_pressure,
            zero_pressure_fraction,
            kt,
            dkt: m * kt / transition_pressure,
        }
    }
}

impl StiffnessPressure for ModifiedPowerStiffness {
    fn stiffness(&self, p: f64) -> f64 {
        let pt = self.transition_pressure;
        if p >= pt {
            return self.c * p.powf(self.m);
        }
        let kt = self.kt;
        let dkt = self.dkt; // slope at p_t
        let k0 = self.zero_pressure_fraction * kt;
        let s = (p / pt).max(0.0);
        // Hermite basis on [0, 1], slopes scaled by pt
        let h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
        let h01 = s * s * (3.0 - 2.0 * s);
        let h11 = s * s * (s - 1.0);
        h00 * k0 + h01 * kt + h11 * pt * dkt
    }
    fn kinks(&self) -> Vec<f64> {
        vec![self.transition_pressure]
    }
}

/// The modified power law compression branch.
pub type ModifiedPower = StiffnessCurve<ModifiedPowerStiffness>;

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn continuous_with_power_law_and_has_inflection() {
        let k = ModifiedPowerStiffness::new(1.81e10, 0.35, 0.2e6, 0.3);
        let pt = 0.2e6;
        let below = k.stiffness(pt * (1.0 - 1e-9));
        let above = k.stiffness(pt);
        assert!((below - above).abs() < 1e-6 * above);
        // second difference changes sign on (0, pt): an inflection
        let d2 = |p: f64| k.stiffness(p + 1e3) - 2.0 * k.stiffness(p) + k.stiffness(p - 1e3);
        assert!(d2(0.02e6) > 0.0);
        assert!(d2(0.18e6) < 0.0);
        // positive everywhere
        for i in 0..100 {
            assert!(k.stiffness(i as f64 * 3e3) > 0.0);
        }
    }
}

/// Parameters of `law = "modified_power"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// C, Pa^(1-m)/m (> 0).
    pub c: f64,
    /// m, in (0, 1).
    pub m: f64,
    /// Transition pressure p_t, Pa (> 0; default 0.2e6).
    #[serde(default = "default_transition_pressure")]
    pub transition_pressure: f64,
    /// Stiffness at zero pressure K(0) as a fraction of K(p_t), in (0, 1) (default 0.2);
    /// the branch has one inflection point for fractions below `1 - 2m/3`.
    #[serde(default = "default_zero_pressure_fraction")]
    pub zero_pressure_fraction: f64,
}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        let key = |k: &str| format!("{prefix}.{k}");
        positive(file, &key("c"), self.c)?;
        exponent(file, &key("m"), self.m)?;
        positive(file, &key("transition_pressure"), self.transition_pressure)?;
        exponent(
            file,
            &key("zero_pressure_fraction"),
            self.zero_pressure_fraction,
        )?;
        let k = ModifiedPowerStiffness::new(
            self.c,
            self.m,
            self.transition_pressure,
            self.zero_pressure_fraction,
        );
        let b: ModifiedPower = StiffnessCurve::new(k, p0, "modified_power");
        Ok(Box::new(b))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "c" => Some(ParamMut::F64(&mut self.c)),
            "m" => Some(ParamMut::F64(&mut self.m)),
            "transition_pressure" => Some(ParamMut::F64(&mut self.transition_pressure)),
            "zero_pressure_fraction" => Some(ParamMut::F64(&mut self.zero_pressure_fraction)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        (name == "transition_pressure").then_some("Pa")
    }
}

/// Default transition pressure of the modified power law, Pa.
pub fn default_transition_pressure() -> f64 {
    0.2e6
}

/// Default K(0)/K(p_t) of the modified power law: with it the Tribobrake model gives the
/// thesis' chapter-4 trends (first mode 780-900 Hz at 32 N, close to a constant 8.5e11
/// Pa/m; a frequency drop from 9 N to 32 N of about 5%, larger than with the plain power
/// law; minimum contact pressures near the thesis' Figure 70).
pub fn default_zero_pressure_fraction() -> f64 {
    0.2
}

//! Modified power law (thesis section 4.2, Figure 63): the power law `K = C p^m` above a
//! transition pressure `p_t` (0.2 MPa in the thesis) and, below it, a smooth branch with an
//! inflection point, as reported for low contact pressures.
//!
//! The thesis gives the shape only graphically; contactwave uses the cubic Hermite branch
//! on `[0, p_t]` with `K(0) = phi K(p_t)` (`zero_pressure_fraction`, default 0.2),
//! `K'(0) = 0`, and value and slope matching the power law at `p_t` (C1 joint). The cubic
//! is convex near 0 and concave near `p_t`: one inflection point in between.

use super::curve::{StiffnessCurve, StiffnessPressure};

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

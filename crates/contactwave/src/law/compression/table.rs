//! Tabulated compression stiffness: `K(p)` given at pressures, interpolated by monotone
//! cubics (PCHIP), constant beyond the table ends; `[u](p) = -integral_p0^p dp'/K(p')`
//! (model.md section 3), inverted numerically by [`super::StiffnessCurve`].

use super::curve::{StiffnessCurve, StiffnessPressure};
use crate::numeric::pchip::Pchip;

/// Tabulated stiffness-pressure relation.
#[derive(Debug, Clone)]
pub struct TableStiffness {
    interp: Pchip,
}

impl TableStiffness {
    /// From pressures (Pa, strictly increasing) and stiffnesses (Pa/m, > 0).
    pub fn new(pressure: &[f64], stiffness: &[f64]) -> Option<Self> {
        Pchip::new(pressure, stiffness).map(|interp| TableStiffness { interp })
    }
}

impl StiffnessPressure for TableStiffness {
    fn stiffness(&self, p: f64) -> f64 {
        self.interp.eval(p)
    }
    fn kinks(&self) -> Vec<f64> {
        self.interp.knots().to_vec()
    }
}

/// The tabulated compression branch.
pub type Table = StiffnessCurve<TableStiffness>;

//! Tabulated compression stiffness: `K(p)` given at pressures, interpolated by monotone
//! cubics (PCHIP), constant beyond the table ends; `[u](p) = -integral_p0^p dp'/K(p')`
//! (model.md section 2), inverted numerically by [`super::StiffnessCurve`].

use super::curve::{StiffnessCurve, StiffnessPressure};
use crate::error::Error;
use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{non_negative, positive, stiffness_at_most};
use crate::law::CompressionBranch;
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

/// Parameters of `law = "table"`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Pressures, Pa, strictly increasing, >= 0 (at least 2).
    pub pressure: Vec<f64>,
    /// Stiffnesses at those pressures, Pa/m, > 0.
    pub stiffness: Vec<f64>,
}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        let (pressure, stiffness) = (&self.pressure, &self.stiffness);
        let key = |k: &str| format!("{prefix}.{k}");
        if pressure.len() < 2 || pressure.len() != stiffness.len() {
            return Err(Error::invalid(
                file,
                key("pressure"),
                format!("{} values (stiffness: {})", pressure.len(), stiffness.len()),
                "pressure and stiffness need the same length, at least 2",
            ));
        }
        for (i, p) in pressure.iter().enumerate() {
            non_negative(file, &format!("{}.{i}", key("pressure")), *p)?;
            if i > 0 && !(*p > pressure[i - 1]) {
                return Err(Error::invalid(
                    file,
                    format!("{}.{i}", key("pressure")),
                    p,
                    "pressures must be strictly increasing",
                ));
            }
        }
        for (i, k) in stiffness.iter().enumerate() {
            positive(file, &format!("{}.{i}", key("stiffness")), *k)?;
            stiffness_at_most(file, &format!("{}.{i}", key("stiffness")), *k)?;
        }
        let t = TableStiffness::new(pressure, stiffness)
            .ok_or_else(|| Error::invalid(file, key("pressure"), "table", "invalid table"))?;
        Ok(Box::new(StiffnessCurve::new(t, p0, "table")))
    }
}

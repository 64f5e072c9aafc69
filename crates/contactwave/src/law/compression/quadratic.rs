//! Quadratic compression law `sigma = -p0 + K0 [u] - K1 [u]^2` (thesis eq. 1.3, the
//! classical weakly nonlinear interface). `[u]_c` is the smaller positive root of
//! `sigma = 0`; for gaps where the law would soften below zero tangent (far in
//! compression when K1 < 0) the tangent is clamped at zero.

use crate::error::Error;
use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{positive, stiffness_at_most, ParamMut};
use crate::law::CompressionBranch;

/// Quadratic compression branch.
#[derive(Debug, Clone, Copy)]
pub struct Quadratic {
    /// Static pressure p0, Pa.
    pub static_pressure: f64,
    /// Linear stiffness K0, Pa/m.
    pub k0: f64,
    /// Quadratic coefficient K1, Pa/m^2.
    pub k1: f64,
}

impl Quadratic {
    /// Validate-free constructor; returns `None` if the stress never reaches zero
    /// (`K0^2 < 4 K1 p0`).
    pub fn new(static_pressure: f64, k0: f64, k1: f64) -> Option<Quadratic> {
        let q = Quadratic {
            static_pressure,
            k0,
            k1,
        };
        q.root().map(|_| q)
    }

    fn root(&self) -> Option<f64> {
        let p0 = self.static_pressure;
        if self.k1 == 0.0 {
            return Some(p0 / self.k0);
        }
        let disc = self.k0 * self.k0 - 4.0 * self.k1 * p0;
        if disc < 0.0 {
            return None;
        }
        // smaller positive root of -k1 u^2 + k0 u - p0 = 0, written stably
        Some(2.0 * p0 / (self.k0 + disc.sqrt()))
    }
}

impl CompressionBranch for Quadratic {
    fn name(&self) -> &'static str {
        "quadratic"
    }
    fn critical_gap(&self) -> f64 {
        self.root().unwrap_or(f64::INFINITY)
    }
    fn stress(&self, gap: f64) -> f64 {
        -self.static_pressure + self.k0 * gap - self.k1 * gap * gap
    }
    fn tangent(&self, gap: f64) -> f64 {
        (self.k0 - 2.0 * self.k1 * gap).max(0.0)
    }
    fn energy(&self, gap: f64) -> f64 {
        0.5 * self.k0 * gap * gap - self.k1 * gap * gap * gap / 3.0
    }
}

/// Parameters of `law = "quadratic"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// K0, Pa/m (> 0).
    pub k0: f64,
    /// K1, Pa/m^2 (at most `K0^2 / (4 p0)`, so that the stress reaches zero).
    pub k1: f64,
}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        let (k0, k1) = (self.k0, self.k1);
        positive(file, &format!("{prefix}.k0"), k0)?;
        stiffness_at_most(file, &format!("{prefix}.k0"), k0)?;
        if !k1.is_finite() {
            return Err(Error::invalid(
                file,
                format!("{prefix}.k1"),
                k1,
                "must be finite",
            ));
        }
        let branch = Quadratic::new(p0, k0, k1).ok_or_else(|| {
            Error::invalid(
                file,
                format!("{prefix}.k1"),
                k1,
                format!(
                    "must be <= k0^2 / (4 p0) = {:e} so that the stress reaches zero",
                    k0 * k0 / (4.0 * p0)
                ),
            )
        })?;
        Ok(Box::new(branch))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "k0" => Some(ParamMut::F64(&mut self.k0)),
            "k1" => Some(ParamMut::F64(&mut self.k1)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        match name {
            "k0" => Some("Pa/m"),
            "k1" => Some("Pa/m^2"),
            _ => None,
        }
    }
}

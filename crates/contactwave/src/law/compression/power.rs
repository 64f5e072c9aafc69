//! Power-law compression stiffness `dp/d(closure) = C p^m`, p = -sigma (thesis eq. 4.4;
//! C = 1.81e10, m = 0.35 for the Al-Al data of Table 2). Closed form:
//! `p([u]) = (p0^(1-m) - (1-m) C [u])^(1/(1-m))`, `[u]_c = p0^(1-m) / ((1-m) C)`.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{exponent, positive, ParamMut};
use crate::law::CompressionBranch;

/// Power-law compression branch (closed form).
#[derive(Debug, Clone, Copy)]
pub struct Power {
    /// Static pressure p0, Pa.
    pub static_pressure: f64,
    /// Coefficient C, Pa^(1-m)/m.
    pub c: f64,
    /// Exponent m in (0, 1).
    pub m: f64,
}

impl Power {
    #[inline]
    fn base(&self, gap: f64) -> f64 {
        let q = 1.0 - self.m;
        (self.static_pressure.powf(q) - q * self.c * gap).max(0.0)
    }
    /// Pressure `p([u]) >= 0`, Pa.
    #[inline]
    pub fn pressure(&self, gap: f64) -> f64 {
        self.base(gap).powf(1.0 / (1.0 - self.m))
    }
}

impl CompressionBranch for Power {
    fn name(&self) -> &'static str {
        "power"
    }
    fn critical_gap(&self) -> f64 {
        let q = 1.0 - self.m;
        self.static_pressure.powf(q) / (q * self.c)
    }
    fn stress(&self, gap: f64) -> f64 {
        -self.pressure(gap)
    }
    fn tangent(&self, gap: f64) -> f64 {
        // K = C p^m = C base^(m/(1-m))
        self.c * self.base(gap).powf(self.m / (1.0 - self.m))
    }
    fn energy(&self, gap: f64) -> f64 {
        // integral_0^u (p0 - p(v)) dv with p = base^(1/q), d base = -q C dv
        let q = 1.0 - self.m;
        let e = 1.0 / q + 1.0;
        let b0 = self.static_pressure.powf(q);
        let b = self.base(gap);
        let int_p = (b0.powf(e) - b.powf(e)) / (e * q * self.c);
        self.static_pressure * gap - int_p
    }
}

/// Parameters of `law = "power"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// C, Pa^(1-m)/m (> 0).
    pub c: f64,
    /// m, dimensionless, in (0, 1).
    pub m: f64,
}

impl LawSpec for Spec {
    type Branch = dyn CompressionBranch;
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<dyn CompressionBranch>> {
        positive(file, &format!("{prefix}.c"), self.c)?;
        exponent(file, &format!("{prefix}.m"), self.m)?;
        Ok(Box::new(Power {
            static_pressure: p0,
            c: self.c,
            m: self.m,
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "c" => Some(ParamMut::F64(&mut self.c)),
            "m" => Some(ParamMut::F64(&mut self.m)),
            _ => None,
        }
    }
}

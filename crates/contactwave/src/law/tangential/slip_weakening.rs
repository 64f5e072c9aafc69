//! Linear slip-weakening friction (Ida 1972, Andrews 1976; the law of the SCEC/USGS
//! TPV205-2D benchmark): Coulomb friction whose coefficient falls linearly with the slip
//! path `D = integral |ds|` from the static value `mu_s` to the dynamic value `mu_d` over
//! the slip-weakening distance `d_c`, and stays at `mu_d` beyond:
//!
//! ```text
//! mu(D) = mu_s - (mu_s - mu_d) min(D, d_c) / d_c
//! ```
//!
//! The slider sticks rigidly. Slipping at a constant contact pressure `N` from rest, the
//! energy dissipated is `N (mu_s D - (mu_s - mu_d) D^2 / (2 d_c))` for `D <= d_c`, and
//! `N (mu_d D + (mu_s - mu_d) d_c / 2)` beyond (the fracture energy
//! `N (mu_s - mu_d) d_c / 2` above the residual friction work).
//!
//! ```
//! use contactwave::law::tangential::SlipWeakening;
//! use contactwave::law::TangentialBranch;
//! let sw = SlipWeakening { static_friction: 0.677, dynamic_friction: 0.525, weakening_slip: 0.4 };
//! assert_eq!(sw.friction_at(0.0), 0.677);
//! assert!((sw.friction_at(0.2) - 0.601).abs() < 1e-12); // half-way
//! assert_eq!(sw.friction_at(1.0), 0.525);
//! // the work against friction at N = 1 Pa up to D = 1 m: 0.525 + 0.152 * 0.4 / 2
//! assert!((sw.dissipation(1.0, 1.0) - 0.5554).abs() < 1e-12);
//! ```

use crate::error::{Error, Result};
use crate::law::param::LawSpec;
use crate::law::param::{non_negative, positive, ParamMut};
use crate::law::TangentialBranch;

/// Linear slip-weakening branch (rigid stick).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipWeakening {
    /// Static friction coefficient mu_s (>= mu_d).
    pub static_friction: f64,
    /// Dynamic friction coefficient mu_d (>= 0).
    pub dynamic_friction: f64,
    /// Slip-weakening distance d_c, m (> 0).
    pub weakening_slip: f64,
}

impl SlipWeakening {
    /// Energy dissipated by friction (J/m^2) over a slip path `path` (m) from rest at a
    /// constant contact pressure `pressure` (Pa): `N integral_0^D mu(D') dD'`.
    pub fn dissipation(&self, path: f64, pressure: f64) -> f64 {
        let (ms, md, dc) = (
            self.static_friction,
            self.dynamic_friction,
            self.weakening_slip,
        );
        let p = path.max(0.0);
        let work = if p <= dc {
            ms * p - (ms - md) * p * p / (2.0 * dc)
        } else {
            md * p + (ms - md) * dc / 2.0
        };
        pressure * work
    }
}

impl TangentialBranch for SlipWeakening {
    fn name(&self) -> &'static str {
        "slip_weakening"
    }
    fn friction(&self) -> f64 {
        self.static_friction
    }
    fn friction_at(&self, path: f64) -> f64 {
        let (ms, md) = (self.static_friction, self.dynamic_friction);
        if path >= self.weakening_slip {
            md
        } else {
            ms - (ms - md) * path.max(0.0) / self.weakening_slip
        }
    }
}

/// Parameters of `law = "slip_weakening"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Static friction coefficient mu_s (>= mu_d).
    pub mu_s: f64,
    /// Dynamic friction coefficient mu_d (>= 0).
    pub mu_d: f64,
    /// Slip-weakening distance d_c, m (> 0).
    pub d_c: f64,
}

impl LawSpec for Spec {
    type Branch = dyn TangentialBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>> {
        let Spec { mu_s, mu_d, d_c } = *self;
        non_negative(file, &format!("{prefix}.mu_d"), mu_d)?;
        if !(mu_s.is_finite() && mu_s >= mu_d) {
            return Err(Error::invalid(
                file,
                format!("{prefix}.mu_s"),
                mu_s,
                format!("must be a finite number >= mu_d = {mu_d}"),
            ));
        }
        positive(file, &format!("{prefix}.d_c"), d_c)?;
        Ok(Box::new(SlipWeakening {
            static_friction: mu_s,
            dynamic_friction: mu_d,
            weakening_slip: d_c,
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "mu_s" => Some(ParamMut::F64(&mut self.mu_s)),
            "mu_d" => Some(ParamMut::F64(&mut self.mu_d)),
            "d_c" => Some(ParamMut::F64(&mut self.d_c)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        (name == "d_c").then_some("m")
    }
}

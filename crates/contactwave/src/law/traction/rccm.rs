//! RCCM adhesion with damage (Raous-Cangemi-Cocu-Monerie, normal part; thesis eqs.
//! 2.11-2.12): `sigma = beta^2 C_N d`, free energy `psi = beta^2 C_N d^2 / 2 - w beta`,
//! damage `b dbeta/dt = min(w - beta C_N d^2, 0)`.
//!
//! beta never increases; damage starts at `sigma_lim = sqrt(C_N w)` for `beta = 1`. The
//! thesis writes the open-state stress as `C_N [u] beta^2 - p0`; contactwave uses the
//! continuous form (stress zero at contact loss; model.md section 2). The backward-Euler
//! update of beta is closed form and unconditionally stable, and `b = 0` is the
//! rate-independent limit `beta = min(beta, w / (C_N d^2))`.

use crate::error::Result;
use crate::law::param::LawSpec;
use crate::law::param::{non_negative, positive, stiffness_at_most, ParamMut};
use crate::law::TractionBranch;

/// RCCM traction branch.
#[derive(Debug, Clone, Copy)]
pub struct Rccm {
    /// Initial stiffness C_N, Pa/m.
    pub stiffness: f64,
    /// Decohesion energy w, J/m^2.
    pub energy: f64,
    /// Viscosity b, J s/m^2 (0 = rate-independent).
    pub viscosity: f64,
}

impl TractionBranch for Rccm {
    fn name(&self) -> &'static str {
        "rccm"
    }
    fn stress(&self, d: f64, beta: f64) -> f64 {
        beta * beta * self.stiffness * d
    }
    fn tangent(&self, _d: f64, beta: f64) -> f64 {
        beta * beta * self.stiffness
    }
    fn stress_d_adhesion(&self, d: f64, beta: f64) -> f64 {
        2.0 * beta * self.stiffness * d
    }
    fn energy(&self, d: f64, beta: f64) -> f64 {
        0.5 * beta * beta * self.stiffness * d * d
    }
    fn is_affine(&self) -> bool {
        true
    }
    fn energy_d_adhesion(&self, d: f64, beta: f64) -> f64 {
        beta * self.stiffness * d * d
    }
    fn has_damage(&self) -> bool {
        true
    }
    fn damage_driving_force(&self, d: f64, beta: f64) -> f64 {
        self.energy - beta * self.stiffness * d * d
    }
    /// `sqrt(w / (beta C_N))` less a relative 2e-9 (`phi` is then at least `4e-9 w`, far
    /// above its round-off); infinite at `beta = 0` with `w > 0`, and 0 where `w = 0`.
    fn damage_onset(&self, beta: f64) -> f64 {
        let d = (self.energy / (beta * self.stiffness)).sqrt() * (1.0 - 2e-9);
        if d >= 0.0 {
            d
        } else {
            0.0
        }
    }
    fn damage_driving_force_gradient(&self, d: f64, beta: f64) -> (f64, f64) {
        (-2.0 * beta * self.stiffness * d, -self.stiffness * d * d)
    }
    fn damage_viscosity(&self) -> f64 {
        self.viscosity
    }
    fn update_adhesion(&self, d: f64, beta: f64, dt: f64) -> f64 {
        let cd2 = self.stiffness * d * d;
        if beta * cd2 <= self.energy {
            return beta;
        }
        // backward Euler: b (beta_new - beta) = dt (w - beta_new C d^2)
        let new = if self.viscosity == 0.0 || dt.is_infinite() {
            self.energy / cd2
        } else {
            (self.viscosity * beta + dt * self.energy) / (self.viscosity + dt * cd2)
        };
        new.clamp(0.0, beta)
    }
    fn adhesion_energy(&self, beta: f64) -> f64 {
        self.energy * beta
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn update_never_increases_and_respects_threshold() {
        let law = Rccm {
            stiffness: 2e13,
            energy: 0.1,
            viscosity: 1e-8,
        };
        let d_lim = (law.energy / law.stiffness).sqrt();
        assert_eq!(law.update_adhesion(0.99 * d_lim, 1.0, 1e-6), 1.0);
        let mut beta = 1.0;
        for k in 1..100 {
            let nb = law.update_adhesion(d_lim * (1.0 + 0.05 * k as f64), beta, 1e-9);
            assert!(nb <= beta && nb >= 0.0);
            beta = nb;
        }
        // below the onset the driving force is positive, at and above it zero or less
        for beta in [1.0, 0.37, 1e-6] {
            let on = law.damage_onset(beta);
            assert!(law.damage_driving_force(on, beta) > 0.0);
            assert!(law.damage_driving_force(on * (1.0 + 1e-8), beta) <= 0.0);
        }
        assert_eq!(law.damage_onset(0.0), f64::INFINITY);
        // rate-independent limit
        let b = law.update_adhesion(2.0 * d_lim, 1.0, f64::INFINITY);
        assert!((b - 0.25).abs() < 1e-12);
    }
}

/// Parameters of `law = "rccm"`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// C_N, Pa/m (> 0).
    pub stiffness: f64,
    /// Decohesion energy w, J/m^2 (>= 0).
    pub energy: f64,
    /// Viscosity b, J s/m^2 (>= 0; 0, the default, is the rate-independent limit).
    #[serde(default)]
    pub viscosity: f64,
}

impl LawSpec for Spec {
    type Branch = dyn TractionBranch;
    fn build(&self, _p0: f64, file: &str, prefix: &str) -> Result<Box<dyn TractionBranch>> {
        let key = |k: &str| format!("{prefix}.{k}");
        positive(file, &key("stiffness"), self.stiffness)?;
        stiffness_at_most(file, &key("stiffness"), self.stiffness)?;
        non_negative(file, &key("energy"), self.energy)?;
        non_negative(file, &key("viscosity"), self.viscosity)?;
        Ok(Box::new(Rccm {
            stiffness: self.stiffness,
            energy: self.energy,
            viscosity: self.viscosity,
        }))
    }
    fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
        match name {
            "stiffness" => Some(ParamMut::F64(&mut self.stiffness)),
            "energy" => Some(ParamMut::F64(&mut self.energy)),
            "viscosity" => Some(ParamMut::F64(&mut self.viscosity)),
            _ => None,
        }
    }
    fn unit(name: &str) -> Option<&'static str> {
        match name {
            "stiffness" => Some("Pa/m"),
            "energy" => Some("J/m^2"),
            "viscosity" => Some("J s/m^2"),
            _ => None,
        }
    }
}

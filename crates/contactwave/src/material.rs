//! Linear elastic materials of the bars and half-spaces (thesis Tables 1 and 4), with an
//! optional shear modulus for shear waves (model.md section 13).

use serde::{Deserialize, Serialize};

/// A linear elastic material: the longitudinal modulus of the 1D model (Young's modulus
/// E for bars; `rho c_L^2` when built from a wave speed), the density and, for shear waves,
/// the shear modulus G.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Mass density rho, kg/m^3.
    pub density: f64,
    /// Shear modulus G, Pa (`None`: shear waves unavailable).
    #[serde(default)]
    pub shear_modulus: Option<f64>,
}

impl Material {
    /// PMMA of thesis Table 4: E = 5 GPa, rho = 1190 kg/m^3; Poisson's ratio 0.35.
    pub const PMMA: Material = Material {
        youngs_modulus: 5e9,
        density: 1190.0,
        shear_modulus: Some(5e9 / (2.0 * (1.0 + 0.35))),
    };
    /// Aluminium of thesis Table 1: E = 71 GPa, rho = 2710 kg/m^3; Poisson's ratio 0.33.
    pub const ALUMINIUM: Material = Material {
        youngs_modulus: 71e9,
        density: 2710.0,
        shear_modulus: Some(71e9 / (2.0 * (1.0 + 0.33))),
    };
    /// Structural steel: E = 210 GPa, rho = 7850 kg/m^3; Poisson's ratio 0.3.
    pub const STEEL: Material = Material {
        youngs_modulus: 210e9,
        density: 7850.0,
        shear_modulus: Some(210e9 / (2.0 * (1.0 + 0.3))),
    };

    /// Names of the presets accepted by [`Material::preset`].
    pub const PRESETS: &'static [&'static str] = &["pmma", "aluminium", "aluminum", "steel"];

    /// A preset by name (`pmma`, `aluminium`/`aluminum`, `steel`).
    pub fn preset(name: &str) -> Option<Material> {
        match name {
            "pmma" => Some(Self::PMMA),
            "aluminium" | "aluminum" => Some(Self::ALUMINIUM),
            "steel" => Some(Self::STEEL),
            _ => None,
        }
    }

    /// Longitudinal bar wave speed c = sqrt(E/rho), m/s.
    pub fn wave_speed(&self) -> f64 {
        (self.youngs_modulus / self.density).sqrt()
    }

    /// Acoustic impedance Z = rho c, Pa s/m.
    pub fn impedance(&self) -> f64 {
        self.density * self.wave_speed()
    }

    /// Shear wave speed `c_T = sqrt(G/rho)`, m/s (`None` without a shear modulus).
    pub fn shear_wave_speed(&self) -> Option<f64> {
        self.shear_modulus.map(|g| (g / self.density).sqrt())
    }

    /// Shear impedance `Z_T = rho c_T`, Pa s/m (`None` without a shear modulus).
    pub fn shear_impedance(&self) -> Option<f64> {
        self.shear_wave_speed().map(|c| self.density * c)
    }
}

/// Admittance `1/Z` of an impedance `z` (Pa s/m), m/(Pa s): 0 for a rigid wall (`z` infinite).
#[inline]
pub fn admittance(z: f64) -> f64 {
    if z.is_finite() {
        1.0 / z
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn pmma_impedance() {
        let z = Material::PMMA.impedance();
        // rho c = sqrt(E rho)
        assert!((z - (5e9f64 * 1190.0).sqrt()).abs() < 1e-6 * z);
        assert!((Material::PMMA.wave_speed() - 2049.80).abs() < 0.01);
    }
    #[test]
    fn aluminium_shear_speed() {
        // G = E / (2 (1 + nu)) = 26.7 GPa, c_T = 3138 m/s
        let c = Material::ALUMINIUM.shear_wave_speed().unwrap();
        assert!((c - (71e9 / 2.66 / 2710.0f64).sqrt()).abs() < 1e-9);
        assert!((c - 3138.3).abs() < 0.1);
    }
}

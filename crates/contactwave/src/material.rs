//! Linear elastic materials of the bars and half-spaces (thesis Tables 1 and 4).

use serde::{Deserialize, Serialize};

/// A linear elastic material for longitudinal waves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Mass density rho, kg/m^3.
    pub density: f64,
}

impl Material {
    /// PMMA of thesis Table 4: E = 5 GPa, rho = 1190 kg/m^3.
    pub const PMMA: Material = Material {
        youngs_modulus: 5e9,
        density: 1190.0,
    };
    /// Aluminium of thesis Table 1: E = 71 GPa, rho = 2710 kg/m^3.
    pub const ALUMINIUM: Material = Material {
        youngs_modulus: 71e9,
        density: 2710.0,
    };
    /// Structural steel: E = 210 GPa, rho = 7850 kg/m^3.
    pub const STEEL: Material = Material {
        youngs_modulus: 210e9,
        density: 7850.0,
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
}

//! Linear elastic materials of the bars and half-spaces (thesis Tables 1 and 4), with an
//! optional shear modulus for shear waves (model.md section 13).

use serde::{Deserialize, Serialize};

/// A linear elastic material as a solver sees it: the longitudinal modulus of its 1D
/// model, the density and, for shear waves, the shear modulus G.
///
/// The longitudinal modulus depends on the geometry: Young's modulus E for a bar (the
/// presets, and `Material::PMMA` etc. here), the P-wave modulus
/// `M = E (1 - nu) / ((1 + nu) (1 - 2 nu))` for a plane wave in a half-space built from a
/// preset ([`Material::half_space`]), `rho c_L^2` when built from a wave speed, or the
/// modulus a scenario states (the thesis' 1D convention: E in a half-space).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Longitudinal modulus of the 1D model, Pa: Young's modulus E for a bar, the P-wave
    /// modulus for a half-space built from a preset (see the type's doc).
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

    /// Poisson's ratio `nu = E / (2 G) - 1` of a material whose longitudinal modulus is
    /// Young's modulus (a preset, a bar), `None` without a shear modulus.
    pub fn poisson_ratio(&self) -> Option<f64> {
        self.shear_modulus
            .map(|g| self.youngs_modulus / (2.0 * g) - 1.0)
    }

    /// The material of a plane wave in a half-space: the longitudinal modulus becomes the
    /// P-wave modulus `M = E (1 - nu) / ((1 + nu) (1 - 2 nu))` (Pa) of Young's modulus E
    /// and Poisson's ratio `nu` in (-1, 0.5); density and shear modulus are kept. `self`
    /// holds Young's modulus (a preset).
    pub fn half_space(&self, nu: f64) -> Material {
        let e = self.youngs_modulus;
        Material {
            youngs_modulus: e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            ..*self
        }
    }

    /// Longitudinal wave speed `c = sqrt(E/rho)` of the modulus in effect, m/s (the bar
    /// speed for a bar, the P-wave speed in a half-space built from a preset).
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
    fn half_space_presets_carry_the_p_wave_speed() {
        // aluminium: E = 71 GPa, nu = 0.33, rho = 2710: c_P = 6230 m/s, not the bar
        // speed 5118 m/s; the shear speed is unchanged
        let al = Material::ALUMINIUM;
        let nu = al.poisson_ratio().unwrap();
        assert!((nu - 0.33).abs() < 1e-12);
        let hs = al.half_space(nu);
        let m = 71e9 * 0.67 / (1.33 * 0.34);
        assert!((hs.wave_speed() - (m / 2710.0f64).sqrt()).abs() < 1e-9);
        assert!(
            (hs.wave_speed() - 6230.4).abs() < 0.1,
            "{}",
            hs.wave_speed()
        );
        assert!((al.wave_speed() - 5118.5).abs() < 0.5);
        assert_eq!(hs.shear_wave_speed(), al.shear_wave_speed());
    }
    #[test]
    fn aluminium_shear_speed() {
        // G = E / (2 (1 + nu)) = 26.7 GPa, c_T = 3138 m/s
        let c = Material::ALUMINIUM.shear_wave_speed().unwrap();
        assert!((c - (71e9 / 2.66 / 2710.0f64).sqrt()).abs() < 1e-9);
        assert!((c - 3138.3).abs() < 0.1);
    }
}

//! The parameters of each law branch, as scenario files give them (the law's own
//! parameter types: the scenario format embeds them under `[interface]`, and
//! [`super::registry`] validates them and builds the branches). Units in the doc comments;
//! every key is documented in `docs/scenario.md`.

use serde::{Deserialize, Serialize};

/// Compression branch of the contact law (model.md section 3).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum CompressionSpec {
    /// Signorini: no penetration, no penalty.
    #[default]
    Rigid,
    /// `sigma = -p0 + K [u]`.
    Linear {
        /// K, Pa/m.
        stiffness: f64,
    },
    /// `sigma = -p0 + K0 [u] - K1 [u]^2` (thesis eq. 1.3).
    Quadratic {
        /// K0, Pa/m.
        k0: f64,
        /// K1, Pa/m^2.
        k1: f64,
    },
    /// Stiffness `dp/d(closure) = C p^m` (thesis eq. 4.4).
    Power {
        /// C, Pa^(1-m)/m.
        c: f64,
        /// m, dimensionless, in (0, 1).
        m: f64,
    },
    /// Power law above `transition_pressure`, a smooth branch with an inflection below
    /// (thesis section 4.2, Figure 63).
    ModifiedPower {
        /// C, Pa^(1-m)/m.
        c: f64,
        /// m, in (0, 1).
        m: f64,
        /// Transition pressure p_t, Pa (default 0.2e6).
        #[serde(default = "default_transition_pressure")]
        transition_pressure: f64,
        /// Stiffness at zero pressure K(0) as a fraction of K(p_t) (default 0.2), in (0, 1);
        /// the branch has one inflection point for fractions below `1 - 2m/3`.
        #[serde(default = "default_zero_pressure_fraction")]
        zero_pressure_fraction: f64,
    },
    /// Stiffness tabulated against pressure, monotone (PCHIP) interpolation.
    Table {
        /// Pressures, Pa, strictly increasing, >= 0.
        pressure: Vec<f64>,
        /// Stiffnesses at those pressures, Pa/m, > 0.
        stiffness: Vec<f64>,
    },
}

/// Default transition pressure of the modified power law, Pa.
pub fn default_transition_pressure() -> f64 {
    0.2e6
}
/// Default K(0)/K(p_t) of the modified power law: with it the Tribobrake model gives the
/// thesis' chapter-4 trends (first mode 780-900 Hz at 32 N, close to a constant 8.5e11
/// Pa/m; a frequency drop from 9 N to 32 N of about 5%, larger than with the plain power
/// law; minimum contact pressures near the thesis' Figure 70).
pub fn default_zero_pressure_fraction() -> f64 {
    0.2
}

/// Traction branch of the contact law (model.md section 3).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum TractionSpec {
    /// `sigma = 0` (unilateral contact, clapping).
    #[default]
    Free,
    /// `sigma = K_t d`, `d = [u] - [u]_c`.
    Linear {
        /// K_t, Pa/m.
        stiffness: f64,
    },
    /// RCCM adhesion with damage: `sigma = beta^2 C_N d`, `b dbeta/dt = min(w - beta C_N d^2, 0)`.
    Rccm {
        /// C_N, Pa/m.
        stiffness: f64,
        /// Decohesion energy w, J/m^2 (>= 0).
        energy: f64,
        /// Viscosity b, J s/m^2; 0 = rate-independent limit.
        #[serde(default)]
        viscosity: f64,
    },
    /// Perfect bond: d = 0 (bilateral contact, the linear reference).
    Bonded,
}

pub use super::tangential::TangentialSpec;

//! The scenario file format (the contract with users; extend it, never rename keys).
//!
//! These are the raw, serde-level structures of a TOML scenario. [`super::Scenario`] is the
//! validated, resolved form the solvers run. Every key is documented in `docs/scenario.md`.

use serde::{Deserialize, Serialize};

pub use crate::analysis::AnalysisMethod;

pub use crate::law::compression::modified_power::{
    default_transition_pressure, default_zero_pressure_fraction,
};
pub use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};

/// A whole scenario file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Medium 1, where the incident wave travels (x < 0).
    pub medium: MaterialSpec,
    /// What lies beyond the interface (x > 0). Default: a rigid wall.
    #[serde(default)]
    pub counterpart: CounterpartSpec,
    /// The contact interface at x = 0.
    pub interface: InterfaceSpec,
    /// The incident longitudinal wave (may be left out when `shear_incident` is given).
    #[serde(default)]
    pub incident: IncidentSpec,
    /// An incident shear wave (model.md section 13), alone or with `incident`.
    #[serde(default)]
    pub shear_incident: Option<IncidentSpec>,
    /// Where the reflected wave is recorded.
    #[serde(default)]
    pub probe: ProbeSpec,
    /// Numerical method and resolution.
    #[serde(default)]
    pub solver: SolverSpec,
    /// How harmonic amplitudes are extracted (model.md section 6.1).
    #[serde(default)]
    pub analysis: AnalysisSpec,
}

/// The `[analysis]` table.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// `band_peak` (default), `pulse_inversion`, `linear_reference` or `plateau_fit`.
    #[serde(default)]
    pub method: AnalysisMethod,
}

/// A material: a preset name or explicit `youngs_modulus` and `density`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Preset name: `pmma`, `aluminium`, `steel`.
    pub material: Option<String>,
    /// Young's modulus, Pa (overrides the preset's).
    pub youngs_modulus: Option<f64>,
    /// Density, kg/m^3 (overrides the preset's).
    pub density: Option<f64>,
    /// Poisson's ratio nu in (-1, 0.5): shear modulus `E / (2 (1 + nu))`.
    pub poisson_ratio: Option<f64>,
    /// Shear modulus G, Pa (instead of `poisson_ratio` or `ct`).
    pub shear_modulus: Option<f64>,
    /// Longitudinal wave speed, m/s: sets the modulus `rho cl^2` (instead of
    /// `youngs_modulus`).
    pub cl: Option<f64>,
    /// Shear wave speed, m/s: sets `G = rho ct^2`.
    pub ct: Option<f64>,
}

/// Kind of counterpart beyond the interface.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CounterpartKind {
    /// Rigid wall (Z2 -> infinity).
    #[default]
    Rigid,
    /// A second elastic half-space (medium 2).
    Medium,
}

/// The counterpart: a rigid wall or a second half-space.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterpartSpec {
    /// `rigid` (default) or `medium`.
    #[serde(default)]
    pub kind: CounterpartKind,
    /// Preset of medium 2 (with `kind = "medium"`).
    pub material: Option<String>,
    /// Young's modulus of medium 2, Pa.
    pub youngs_modulus: Option<f64>,
    /// Density of medium 2, kg/m^3.
    pub density: Option<f64>,
    /// Poisson's ratio nu in (-1, 0.5): shear modulus `E / (2 (1 + nu))`.
    pub poisson_ratio: Option<f64>,
    /// Shear modulus G, Pa (instead of `poisson_ratio` or `ct`).
    pub shear_modulus: Option<f64>,
    /// Longitudinal wave speed, m/s: sets the modulus `rho cl^2` (instead of
    /// `youngs_modulus`).
    pub cl: Option<f64>,
    /// Shear wave speed, m/s: sets `G = rho ct^2`.
    pub ct: Option<f64>,
}

/// The interface: static pressure and the two branches of the contact law.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// Static pressure p0, Pa, compression positive (interface stress at rest is -p0).
    pub static_pressure: f64,
    /// Compression branch (default: rigid, Signorini).
    #[serde(default)]
    pub compression: CompressionSpec,
    /// Traction branch (default: free, unilateral contact).
    #[serde(default)]
    pub traction: TractionSpec,
    /// Static shear stress q0, Pa (default 0; `|q0| <= mu p0` with friction).
    #[serde(default)]
    pub static_shear: f64,
    /// Tangential branch (default: free sliding).
    #[serde(default)]
    pub tangential: TangentialSpec,
}

/// Kind of incident wave.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IncidentKind {
    /// Windowed sinusoid.
    #[default]
    ToneBurst,
    /// Windowed sum of two sinusoids (f1, f2).
    TwoTone,
    /// Arbitrary waveform from a CSV file (time, stress).
    File,
}

/// Window of a tone burst.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WindowKind {
    /// Flat top with half-Hann ramps, each `ramp_fraction` of the burst (chapter 5).
    #[default]
    HannRamps,
    /// Full Hann window.
    Hann,
    /// Rectangular (no window).
    Rectangular,
}

/// The incident wave.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IncidentSpec {
    /// `tone_burst` (default), `two_tone` or `file`.
    #[serde(default)]
    pub kind: IncidentKind,
    /// Frequency f0 (f1 for two-tone; analysis fundamental for file), Hz.
    pub frequency: Option<f64>,
    /// Second frequency f2 of a two-tone burst, Hz.
    pub frequency2: Option<f64>,
    /// Amplitude of the f2 component relative to the f1 component (two-tone), default 1.
    pub amplitude_ratio: Option<f64>,
    /// Number of cycles of f0 in the burst (default 15).
    pub cycles: Option<f64>,
    /// Peak incident stress-wave amplitude |s_inc|, Pa. Give this or `xi`.
    pub amplitude: Option<f64>,
    /// Load ratio xi (model.md section 2). Give this or `amplitude`.
    pub xi: Option<f64>,
    /// Window (default `hann_ramps`).
    #[serde(default)]
    pub window: WindowKind,
    /// Fraction of the burst covered by each ramp of `hann_ramps`, in (0, 0.5], default 0.25.
    pub ramp_fraction: Option<f64>,
    /// CSV file (time s, stress Pa) for `kind = "file"`, relative to the scenario file.
    pub path: Option<String>,
    /// Arrival of the wave's front at the interface, s (default 0).
    pub delay: Option<f64>,
    /// Angle of incidence from the interface normal, degrees, in [0, 90) (default 0): a P
    /// wave for `[incident]`, an SV wave for `[shear_incident]` (model.md section 14).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
}

impl IncidentSpec {
    /// Whether the table gives no wave at all (every key left out).
    pub fn is_absent(&self) -> bool {
        self.frequency.is_none()
            && self.amplitude.is_none()
            && self.xi.is_none()
            && self.path.is_none()
            && self.cycles.is_none()
    }
}

/// The probe where the reflected wave is recorded.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Position x, m (must be < 0: in medium 1). Default -0.03.
    #[serde(default = "default_probe_x")]
    pub x: f64,
}

impl Default for ProbeSpec {
    fn default() -> Self {
        ProbeSpec {
            x: default_probe_x(),
        }
    }
}

fn default_probe_x() -> f64 {
    -0.03
}

/// Numerical method.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Exact half-space solver (gap ODE with events).
    #[default]
    Exact,
    /// Explicit finite differences (bar-stack scheme at Courant number 1), the thesis'
    /// method: an independent check of the exact solver.
    Fd,
}

/// Solver settings.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// `exact` (default) or `fd`.
    #[serde(default)]
    pub method: Method,
    /// Time samples per period of the highest input frequency (default 200 for `exact`,
    /// 1000 for `fd`, which is first order in time at a clapping interface).
    pub samples_per_period: Option<usize>,
    /// Time simulated after the burst has passed, in periods of f0 (default: automatic,
    /// until the interface is back at rest, at least 3 and at most 400 periods; 100 for fd).
    pub tail_periods: Option<f64>,
    /// Interface time discretisation of the `fd` method (default `average`).
    #[serde(default)]
    pub interface_update: InterfaceUpdate,
}

impl Default for SolverSpec {
    fn default() -> Self {
        SolverSpec {
            method: Method::Exact,
            samples_per_period: None,
            tail_periods: None,
            interface_update: InterfaceUpdate::default(),
        }
    }
}

/// How the finite-difference schemes advance an interface (model.md section 9.2).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InterfaceUpdate {
    /// Mean of the interface stresses at the new and the previous-but-one time level:
    /// second order and free of numerical dissipation for compliant laws.
    #[default]
    Average,
    /// The stress of the new time level over the whole step (the thesis' eqs. 2.27-2.31):
    /// first order, numerically dissipative.
    Backward,
}

impl From<InterfaceUpdate> for crate::solver::bar_stack::InterfaceScheme {
    fn from(u: InterfaceUpdate) -> Self {
        match u {
            InterfaceUpdate::Average => crate::solver::bar_stack::InterfaceScheme::Average,
            InterfaceUpdate::Backward => crate::solver::bar_stack::InterfaceScheme::Backward,
        }
    }
}

pub use crate::excitation::MAX_AMPLITUDE;

/// Default samples per period of the exact solver.
pub const DEFAULT_SPP_EXACT: usize = 200;
/// The samples per period a scenario may ask for (half-space `solver.samples_per_period`,
/// bar stack `model.samples_per_period`).
pub const SAMPLES_PER_PERIOD: std::ops::RangeInclusive<usize> = 16..=100_000;
/// Default samples per period of the FD solver.
pub const DEFAULT_SPP_FD: usize = 1000;

impl SolverSpec {
    /// Samples per period in effect (the default depends on the method).
    pub fn samples_per_period(&self) -> usize {
        self.samples_per_period.unwrap_or(match self.method {
            Method::Exact => DEFAULT_SPP_EXACT,
            Method::Fd => DEFAULT_SPP_FD,
        })
    }
}

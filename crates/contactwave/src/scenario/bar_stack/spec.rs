//! The serde-level form of a bar-stack file: the TOML tables as written, before
//! validation, and the defaults they fall back on.

use crate::scenario::spec::{
    CompressionSpec, IncidentSpec, InterfaceUpdate, TangentialSpec, TractionSpec,
};
use serde::{Deserialize, Serialize};

/// Default hammer pulse duration, s: with the Tribobrake example at 32 N both interfaces
/// stay closed with a minimum contact pressure of about 0.025 MPa (thesis Figure 70).
pub const DEFAULT_PULSE_DURATION: f64 = 1.135e-3;

/// The whole bar-stack file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarStackSpec {
    /// Model settings.
    pub model: ModelSpec,
    /// Segments from the first end (x = 0, e.g. the top) to the last.
    #[serde(rename = "segment")]
    pub segments: Vec<SegmentSpec>,
    /// Interfaces between consecutive segments, and the obstacle interface.
    #[serde(rename = "interface", default)]
    pub interfaces: Vec<InterfaceSpec>,
    /// The hammer (force at the first node) or an imposed displacement of the first end.
    /// Required unless `[incident]` is given.
    pub excitation: Option<ForceSpec>,
    /// An incident wave entering through a transparent first end (`model.first_end =
    /// "transparent"`): the keys of the half-space `[incident]` (tone burst, two-tone or
    /// file; `amplitude` in Pa or `xi` relative to the first interface). `s_inc(t)` is its
    /// stress at x = 0, where its front arrives at t = 0.
    pub incident: Option<IncidentSpec>,
    /// An incident shear wave entering through the transparent first end (model.md
    /// sections 9.7 and 13), alone or with `[incident]`: the keys of the half-space
    /// `[shear_incident]` (`amplitude` in Pa, no xi; `delay` in s). `tau_inc(t)` is its
    /// shear stress at x = 0, where its front arrives at t = `delay`. It gives the stack a
    /// transverse field: every segment then needs a shear modulus.
    pub shear_incident: Option<IncidentSpec>,
    /// Analysis settings.
    #[serde(default)]
    pub analysis: AnalysisSpec,
    /// Probes: displacement, velocity, acceleration and stress histories at points of the
    /// stack (written to `probes.csv`).
    #[serde(rename = "probe", default)]
    pub probes: Vec<ProbeSpec>,
}

/// `[[probe]]`: a point of the stack where histories are recorded.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Name (column prefix in `probes.csv`; letters, digits, `_`).
    pub name: String,
    /// Position along the stack from its first end, m (0 <= x <= total length; the nearest
    /// node is used, on the first segment at a shared boundary).
    pub x: f64,
}

/// `[model]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// Must be `bar_stack`.
    pub kind: String,
    /// Common cross-section S, m^2.
    pub area: f64,
    /// Gravity along +x (from the first segment towards the last), m/s^2 (default 0).
    #[serde(default)]
    pub gravity: f64,
    /// Static force on the first node along +x, N (default 0).
    #[serde(default)]
    pub static_force: f64,
    /// Static transverse force on the first node, N (default 0): every interface then
    /// carries the static shear stress `q0 = static_shear_force / area`, balanced by the
    /// obstacle's friction or a fixed far end (`|q0| <= mu p0` at each frictional
    /// interface). Gives the stack a transverse field.
    #[serde(default)]
    pub static_shear_force: f64,
    /// End condition at x = 0: `free` (default), `fixed`, `transparent`.
    #[serde(default = "free")]
    pub first_end: String,
    /// End condition at the far end: `free`, `fixed`, `transparent`, `obstacle` (default;
    /// needs an interface `between = [last segment, "obstacle"]`).
    #[serde(default = "obstacle")]
    pub last_end: String,
    /// Simulated time, s. Default 0.2 with `[excitation]`; with `[incident]` the burst,
    /// four travel times of the stack and 100 periods of the fundamental.
    pub duration: Option<f64>,
    /// Time steps per period of the incident wave's highest frequency (only with
    /// `[incident]`), default 1000, in [16, 100000].
    pub samples_per_period: Option<usize>,
    /// Interface time discretisation: `average` (default; second order, no numerical
    /// dissipation) or `backward` (the thesis' scheme; first order, dissipative).
    #[serde(default)]
    pub interface_update: InterfaceUpdate,
    /// Target cell size, m (default: the shortest segment / 4).
    pub cell_size: Option<f64>,
    /// Time step, s (default: `cell_size` over the largest wave speed). Every segment is
    /// meshed at Courant number <= 1 for it; the stability limit is the smallest
    /// `length / wave speed` of the segments (one cell at Courant 1).
    pub time_step: Option<f64>,
}

fn free() -> String {
    "free".into()
}
fn obstacle() -> String {
    "obstacle".into()
}
/// Default simulated time of a hammer run, s (5 Hz FRF resolution).
pub const DEFAULT_HAMMER_DURATION: f64 = 0.2;

/// Default time steps per period of an incident wave (as `method = "fd"` half-space runs).
pub const DEFAULT_INCIDENT_SPP: usize = crate::scenario::spec::DEFAULT_SPP_FD;

/// `[[segment]]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// Name.
    pub name: String,
    /// Length, m.
    pub length: f64,
    /// Material preset.
    pub material: Option<String>,
    /// Young's modulus, Pa.
    pub youngs_modulus: Option<f64>,
    /// Density, kg/m^3.
    pub density: Option<f64>,
    /// Poisson's ratio nu in (-1, 0.5): shear modulus `E / (2 (1 + nu))` (needed with a
    /// transverse field unless the preset gives it).
    pub poisson_ratio: Option<f64>,
    /// Shear modulus G, Pa (instead of `poisson_ratio` or `ct`).
    pub shear_modulus: Option<f64>,
    /// Shear wave speed, m/s: sets `G = rho ct^2`.
    pub ct: Option<f64>,
    /// Mass, kg: sets an equivalent density `mass / (area length)` at the common
    /// cross-section, with E and G scaled by the same factor (the wave speeds are kept).
    pub mass: Option<f64>,
    /// Viscous damping h of eq. 2.2, 1/s (default 0).
    #[serde(default)]
    pub damping: f64,
}

/// `[[interface]]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// The two segment names it joins, in order (`"obstacle"` for the rigid obstacle).
    pub between: [String; 2],
    /// Compression branch.
    #[serde(default)]
    pub compression: CompressionSpec,
    /// Traction branch.
    #[serde(default)]
    pub traction: TractionSpec,
    /// Tangential branch (model.md section 13): `free` (default), `linear`, `coulomb` or
    /// `rccm`, as the half-space `interface.tangential`. Any other than `free` gives the
    /// stack a transverse field.
    #[serde(default)]
    pub tangential: TangentialSpec,
}

/// `[excitation]`: a half-sine force pulse or a force file, at the first node.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceSpec {
    /// `force_pulse` (default), `force_file`, or an imposed displacement of the first end
    /// (thesis eq. 2.39): `displacement_pulse` (half-sine, `peak` in m) or
    /// `displacement_file` (CSV: time s, displacement m).
    #[serde(default = "pulse")]
    pub kind: String,
    /// Peak force, N (positive: along +x, into the stack).
    pub peak: Option<f64>,
    /// Pulse duration, s (default [`DEFAULT_PULSE_DURATION`]).
    pub duration: Option<f64>,
    /// CSV file (time s, force N), relative to the scenario file.
    pub path: Option<String>,
}

fn pulse() -> String {
    "force_pulse".into()
}

/// `[analysis]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// Lowest frequency searched for the first mode, Hz (default 100).
    #[serde(default = "fmin")]
    pub first_mode_min: f64,
    /// Highest frequency searched for the first mode, Hz (default 3000).
    #[serde(default = "fmax")]
    pub first_mode_max: f64,
}

impl Default for AnalysisSpec {
    fn default() -> Self {
        AnalysisSpec {
            first_mode_min: fmin(),
            first_mode_max: fmax(),
        }
    }
}
fn fmin() -> f64 {
    100.0
}
fn fmax() -> f64 {
    3000.0
}

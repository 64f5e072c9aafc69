//! 2D scenarios (`[model] kind = "solid_2d"`, model.md section 9): a rectangle of
//! horizontal layers, plane-strain P-SV or antiplane SH waves, cracks with any law of the
//! library, transducer, point-force and plane-wave sources, velocity receivers. The serde-level spec
//! ([`Solid2dSpec`]) and its validation into the solver's problem
//! ([`crate::solver::solid_2d::Solid2d`]) with every crack's law built once.

mod closure;
mod gate;
mod material;
pub mod mesh;
mod parse;
use parse::foreign_key;
mod receivers;
pub mod resolution;

use crate::analysis::{AnalysisMethod, Gate};
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::point::SharedLaw;
use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use crate::scenario::spec::IncidentSpec;
use crate::scenario::BuildCache;
use crate::solver::solid_2d::dispersion::element_size_for;
use crate::solver::solid_2d::Backend;
use crate::solver::solid_2d::{
    pml, Crack, CrackProfile, Elastic, Layer, Pml, Side, Solid2d, Source, SourceKind, WaveType,
};
use closure::ClosureProfile;
pub use closure::{ClosureSpec, PrestressSpec};
use material::material;
pub use receivers::{component_names, Receiver2d, ReceiverSpec};
pub use resolution::{CrackResolution, CRACK_ELEMENT_SIZES};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// Default GLL order of the elements: at the default accuracy order 6 needs 38 % fewer
/// nodes than order 4 (model.md section 15.4), and its kernel runs at the same node rate.
pub const DEFAULT_ORDER: usize = 6;
/// Default highest analysed harmonic (`model.harmonic`) of the first source's frequency.
pub const DEFAULT_HARMONIC: f64 = 3.0;
/// The phase velocity error the default element size allows at the highest analysed
/// harmonic (`model.harmonic` times the first source's frequency), for every wave of every
/// layer in every direction, with the time step bound and any smaller step: the largest
/// elements within it by the Bloch analysis of the scheme (model.md eq. 15.6a; order 6 in
/// aluminium: 1.18 elements per S wavelength, order 4: 1.625).
pub const DISPERSION_BUDGET: f64 = 9e-4;
/// Default bound of `omega dt` at the highest analysed harmonic: the central differences'
/// phase error `(omega dt)^2 / 24` stays below 6e-4.
pub const PHASE_STEP: f64 = 0.12;

/// The whole 2D scenario file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solid2dSpec {
    /// Model settings.
    pub model: ModelSpec,
    /// Layers from the top surface (z = 0) down (the rectangle; none with `[mesh]`).
    #[serde(rename = "layer", default)]
    pub layers: Vec<LayerSpec>,
    /// A mesh file instead of the rectangle (`[mesh]`, docs/mesh.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<mesh::MeshSpec>,
    /// The materials of the mesh's physical surfaces (`[[material]]`, with `[mesh]`).
    #[serde(rename = "material", default, skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<mesh::MaterialSpec>,
    /// The mesh's physical curves that are not free sides (`[[boundary]]`, with `[mesh]`).
    #[serde(rename = "boundary", default, skip_serializing_if = "Vec::is_empty")]
    pub boundaries: Vec<mesh::BoundarySpec>,
    /// Cracks.
    #[serde(rename = "crack", default)]
    pub cracks: Vec<CrackSpec>,
    /// Sources.
    #[serde(rename = "source")]
    pub sources: Vec<SourceSpec>,
    /// Velocity receivers.
    #[serde(rename = "receiver", default)]
    pub receivers: Vec<ReceiverSpec>,
    /// Wavefield pictures (`[snapshots]`; none without the table).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<crate::scenario::snapshots::SnapshotsSpec>,
    /// How the receivers' harmonics are extracted.
    #[serde(default)]
    pub analysis: AnalysisSpec,
}

/// `[analysis]` of a 2D scenario: the method (model.md section 6.1) and an optional time
/// gate around the echo of interest.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// `band_peak` (default), `pulse_inversion` (a second run with every source's signal
    /// negated), `linear_reference` (a second run with every crack's law linearised at its
    /// static state: a Signorini crack bonded) or `plateau_fit` (needs `gate`: the fit
    /// window).
    #[serde(default)]
    pub method: AnalysisMethod,
    /// `[start, end]` of the time gate applied to every receiver's record before its
    /// analysis, s (default: none, the whole record).
    pub gate: Option<[f64; 2]>,
    /// Half-cosine ramps at the gate's edges, inside it, s (default 0).
    #[serde(default)]
    pub taper: f64,
}

/// `[model]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// Must be `solid_2d`.
    pub kind: String,
    /// `p_sv` (plane strain, default) or `sh` (antiplane).
    #[serde(default = "p_sv")]
    pub wave: String,
    /// Width along x, m (the rectangle; not with `[mesh]`).
    #[serde(default)]
    pub width: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// GLL order of the elements, 2 to 8 (default [`DEFAULT_ORDER`]).
    pub order: Option<usize>,
    /// Largest element size, m (default: the largest that keeps the phase velocity
    /// error at the highest analysed harmonic within [`DISPERSION_BUDGET`]).
    pub element_size: Option<f64>,
    /// Highest analysed harmonic of the first source's frequency (default 3): sets the
    /// default element size and time step.
    pub harmonic: Option<f64>,
    /// Fraction of the stability limit the time step takes, in (0, 1) (default 0.9).
    pub courant: Option<f64>,
    /// Time step, s (default: the smaller of the stability limit times `courant` and
    /// [`PHASE_STEP`] over the angular frequency of the highest analysed harmonic).
    pub time_step: Option<f64>,
    /// Top side: `free` (default), `rigid` or `absorbing` (a perfectly matched layer
    /// outside the rectangle).
    #[serde(default = "free")]
    pub top: String,
    /// Bottom side: `free` (default), `rigid` or `absorbing`.
    #[serde(default = "free")]
    pub bottom: String,
    /// The x sides: `free` (default), `rigid`, `absorbing` or `periodic`.
    #[serde(default = "free")]
    pub sides: String,
    /// Record the cracks' fields every this many time steps (default 10).
    pub crack_every: Option<usize>,
    /// Thickness of the absorbing sides' perfectly matched layers, m (default
    /// [`pml::DEFAULT_ELEMENTS`] element sizes).
    pub pml_thickness: Option<f64>,
    /// Target reflection R0 of the layers' damping profile, in (0, 1) (default
    /// [`pml::DEFAULT_REFLECTION`]).
    pub pml_reflection: Option<f64>,
    /// Where the time loop runs: `cpu` (default) or `gpu` (a build with the feature `gpu`
    /// and an NVIDIA GPU).
    pub backend: Option<String>,
    /// A uniform far-field pre-stress whose traction on each crack is its static state
    /// (instead of the cracks' own `static_pressure`, `static_shear`).
    pub prestress: Option<PrestressSpec>,
}

fn p_sv() -> String {
    "p_sv".into()
}
fn free() -> String {
    "free".into()
}

/// `[[layer]]`: a horizontal layer and its material (a preset, or E / nu / rho, or
/// c_P / c_S / rho).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerSpec {
    /// Thickness, m.
    pub thickness: f64,
    /// Material preset (`aluminium`, `steel`, `pmma`).
    pub material: Option<String>,
    /// Young's modulus E, Pa (with `poisson_ratio` and `density`).
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio nu in (-1, 0.5).
    pub poisson_ratio: Option<f64>,
    /// Density rho, kg/m^3.
    pub density: Option<f64>,
    /// P-wave speed c_P, m/s (with `s_speed` and `density`).
    pub p_speed: Option<f64>,
    /// S-wave speed c_S, m/s.
    pub s_speed: Option<f64>,
}

/// `[[crack]]`: a straight horizontal or vertical crack with its law and static state.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrackSpec {
    /// Start `[x, z]`, m (the rectangle's cracks).
    #[serde(default = "mesh::unset_point")]
    pub start: [f64; 2],
    /// The mesh's physical curve that is the crack or contact interface (with `[mesh]`,
    /// instead of start and end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// End `[x, z]`, m: the same z (horizontal) or the same x (vertical). Give this or
    /// `length`.
    pub end: Option<[f64; 2]>,
    /// Length from the start, m, along +x (or +z with `vertical`): instead of `end`.
    pub length: Option<f64>,
    /// With `length`: the crack runs down from its start (default false: along +x).
    #[serde(default)]
    pub vertical: bool,
    /// Across the whole width (periodic sides): a plane interface at the start's z.
    #[serde(default)]
    pub full_width: bool,
    /// Static closure pressure p0, Pa (default 0).
    #[serde(default)]
    pub static_pressure: f64,
    /// Static shear stress q0, Pa (default 0).
    #[serde(default)]
    pub static_shear: f64,
    /// Compression branch (default rigid: Signorini).
    #[serde(default)]
    pub compression: CompressionSpec,
    /// Traction branch (default free).
    #[serde(default)]
    pub traction: TractionSpec,
    /// Tangential branch (default free sliding).
    #[serde(default)]
    pub tangential: TangentialSpec,
    /// The static state along the crack as a table (instead of the uniform
    /// `static_pressure` and `static_shear`).
    pub closure: Option<ClosureSpec>,
}

/// The narrowest transducer aperture, as a fraction of the element size.
pub const MIN_APERTURE: f64 = 1e-3;

/// `[[source]]`: a transducer (a traction over an aperture of the top or bottom surface),
/// a point force or a plane wave (total-field/scattered-field), with its time function.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceSpec {
    /// `transducer` (default), `force` or `plane_wave`.
    #[serde(default = "transducer")]
    pub kind: String,
    /// On a mesh (`[mesh]`): a transducer's physical curve of its aperture (instead of
    /// x0, x1 and surface), or a plane wave's curve inside the mesh (instead of z).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// Transducer: aperture start and end along x, m.
    pub x0: Option<f64>,
    /// Transducer: aperture end, m.
    pub x1: Option<f64>,
    /// Transducer: `top` (default) or `bottom` surface.
    pub surface: Option<String>,
    /// Transducer: `normal` (default) or `shear` traction (shear is along y in SH runs).
    pub component: Option<String>,
    /// Transducer: beam angle from the surface normal, degrees in (-90, 90) (default 0): a
    /// linear delay law `sin(angle) / c` along the aperture (c_P of the top layer for a
    /// normal traction, c_S for a shear one).
    #[serde(default)]
    pub angle: f64,
    /// Force: position `[x, z]`, m (the nearest node).
    pub at: Option<[f64; 2]>,
    /// Force: direction `[x, z]` (normalised; ignored in SH runs), default `[0, 1]`.
    pub direction: Option<[f64; 2]>,
    /// Plane wave: `P` (default in P-SV runs), `SV`, or `SH` (SH runs).
    pub wave: Option<String>,
    /// Plane wave: depth of the total-field/scattered-field line, m (an element edge is
    /// put there; the wave travels down from it at `angle` from the z axis).
    pub z: Option<f64>,
    /// The time function: the keys of a half-space `[incident]` (tone burst, two-tone or
    /// file; `amplitude` in Pa for a transducer, N/m for a force; no xi).
    pub signal: IncidentSpec,
}

fn transducer() -> String {
    "transducer".into()
}

/// A validated 2D scenario.
#[derive(Debug, Clone)]
pub struct Solid2dScenario {
    /// The spec.
    pub spec: Solid2dSpec,
    /// File it came from.
    pub file: String,
    /// The solver's problem.
    pub problem: Solid2d<SharedLaw>,
    /// Fundamental of the analysis (the first source's), Hz.
    pub f0: f64,
    /// The receiver points, in the order of the file (a line's points in a row).
    pub receivers: Vec<Receiver2d>,
    /// Positions of the stress receivers, `[x, z]`, m.
    pub stress_points: Vec<[f64; 2]>,
    /// The time gate of the receivers' analysis (`[analysis] gate`).
    pub gate: Option<Gate>,
    /// The checked `[snapshots]`, if any.
    pub snapshots: Option<crate::scenario::snapshots::Snapshots>,
    /// Where the time loop runs (`model.backend`).
    pub backend: Backend,
    /// The problem on a mesh (`[mesh]`): its cracks' laws and sources' signals are taken
    /// from `problem` when it runs (a twin changes them there), `problem` standing for
    /// the mesh's bounding box, materials and largest element.
    pub mesh: Option<crate::solver::solid_2d::quad::QuadSolid<SharedLaw>>,
}

pub(super) fn inv(
    file: &str,
    field: impl Into<String>,
    v: impl std::fmt::Display,
    allowed: &str,
) -> Error {
    Error::invalid(file, field, v, allowed)
}

fn positive(file: &str, field: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(inv(file, field, v, "must be a finite number > 0"))
    }
}

fn side(file: &str, field: &str, v: &str, periodic: bool) -> Result<Side> {
    match (v, periodic) {
        ("free", _) => Ok(Side::Free),
        ("rigid", _) => Ok(Side::Rigid),
        ("absorbing", _) => Ok(Side::Absorbing),
        ("periodic", true) => Ok(Side::Periodic),
        _ => Err(inv(
            file,
            field,
            v,
            if periodic {
                "free, rigid, absorbing or periodic"
            } else {
                "free, rigid or absorbing"
            },
        )),
    }
}

impl Solid2dScenario {
    /// The simulations one run holds at once: two where its analysis method needs a twin
    /// (pulse inversion, linear reference), else one.
    pub fn runs(&self) -> f64 {
        match self.spec.analysis.method {
            AnalysisMethod::PulseInversion | AnalysisMethod::LinearReference => 2.0,
            AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit => 1.0,
        }
    }

    /// The memory a run needs, bytes ([`Solid2d::memory_estimate`] and the stress
    /// receivers' series, [`Self::stress_bytes`], times [`Self::runs`]).
    pub fn memory_bytes(&self) -> Result<f64> {
        if let Some(q) = &self.mesh {
            // the mesh and its state, and the receivers' series (as the rectangle's: four
            // copies of each trace and its text)
            let c = if q.wave == WaveType::Sh { 1.0 } else { 2.0 };
            let nodes = q.node_estimate();
            let mesh = nodes * crate::solver::solid_2d::quad::bytes_per_node(q.order, c as usize);
            return Ok(self.runs() * mesh);
        }
        let e = self.problem.memory_estimate(&self.file)?;
        Ok(self.runs() * (e.total() + self.stress_bytes(e.steps)))
    }

    /// The stress receivers' series over `steps` steps, bytes: each component's trace, its
    /// gated copy and the analysis' transforms (four series, as the velocity receivers' in
    /// [`Solid2d::memory_estimate`]) and its text in `receivers.csv` (about 24 bytes a
    /// value).
    pub fn stress_bytes(&self, steps: f64) -> f64 {
        let components = if self.problem.wave == WaveType::Sh {
            2.0
        } else {
            3.0
        };
        self.stress_points.len() as f64 * components * steps * (4.0 * 8.0 + 24.0)
    }

    /// The key that sets the stress receivers' number, its value, and the way to fewer:
    /// the longest stress line's `receiver.<i>.count`, or the first stress point's
    /// `receiver.<i>.quantity`.
    pub fn stress_receiver_key(&self) -> (String, String, String) {
        let stress = self
            .spec
            .receivers
            .iter()
            .enumerate()
            .filter(|(_, r)| r.quantity == "stress");
        match stress
            .clone()
            .filter(|(_, r)| r.count.is_some())
            .max_by_key(|(_, r)| r.count)
        {
            Some((i, r)) => (
                format!("receiver.{i}.count"),
                r.count.unwrap_or(0).to_string(),
                format!("lower `receiver.{i}.count` (or record velocity there)"),
            ),
            None => {
                let i = stress.map(|(i, _)| i).next().unwrap_or(0);
                (
                    format!("receiver.{i}.quantity"),
                    "stress".to_string(),
                    "record fewer stresses (`quantity = \"velocity\"`)".to_string(),
                )
            }
        }
    }

    /// Does this TOML table describe a 2D scenario?
    pub fn is_solid_2d(table: &toml::Table) -> bool {
        table
            .get("model")
            .and_then(|m| m.get("kind"))
            .and_then(|k| k.as_str())
            == Some("solid_2d")
    }

    /// Validate a spec (`dir`: the folder that relative file paths refer to), building
    /// the laws and reading waveform files through `cache`.
    pub fn from_spec(
        spec: Solid2dSpec,
        file: &str,
        dir: &Path,
        cache: &BuildCache,
    ) -> Result<Self> {
        if spec.mesh.is_some() {
            return mesh::from_spec(spec, file, dir, cache);
        }
        for (i, c) in spec.cracks.iter().enumerate() {
            if c.group.is_some() || c.start[0].is_nan() {
                return Err(inv(
                    file,
                    format!(
                        "crack.{i}.{}",
                        if c.group.is_some() { "group" } else { "start" }
                    ),
                    if c.group.is_some() {
                        "given"
                    } else {
                        "missing"
                    },
                    "a rectangle's crack takes start and end (group: a curve of a `[mesh]`)",
                ));
            }
        }
        for (i, s) in spec.sources.iter().enumerate() {
            if s.group.is_some() {
                return Err(inv(
                    file,
                    format!("source.{i}.group"),
                    "given",
                    "a rectangle's transducer takes x0, x1 and surface (group: a curve of a `[mesh]`)",
                ));
            }
        }
        if !spec.materials.is_empty() || !spec.boundaries.is_empty() {
            let key = if spec.materials.is_empty() {
                "boundary"
            } else {
                "material"
            };
            return Err(inv(
                file,
                key,
                "given",
                "with a `[mesh]` (a rectangle has [[layer]] and model.top, bottom, sides)",
            ));
        }
        let m = &spec.model;
        let wave = match m.wave.as_str() {
            "p_sv" => WaveType::PSv,
            "sh" => WaveType::Sh,
            w => return Err(inv(file, "model.wave", w, "p_sv or sh")),
        };
        // an inclined crack is said first: the checks of its position, law and static
        // state below read a crack that is not horizontal as a vertical one
        for (i, c) in spec.cracks.iter().enumerate() {
            if let Some(end) = c.end
                && !c.full_width
                && end.iter().chain(&c.start).all(|v| v.is_finite())
                && end[0] != c.start[0]
                && end[1] != c.start[1]
            {
                return Err(inv(
                    file,
                    format!("crack.{i}.end"),
                    format!("[{}, {}]", end[0], end[1]),
                    &format!(
                        "cracks are horizontal or vertical: an end at the start's z = {} m \
                         (horizontal) or at its x = {} m (vertical); the mesh follows a \
                         crack along its elements' edges, so an inclined one cannot be \
                         meshed",
                        c.start[1], c.start[0]
                    ),
                ));
            }
        }
        if m.width == 0.0 {
            return Err(inv(file, "model.width", "(missing)", "required: the rectangle's width along x, m (> 0), or a `[mesh]` file instead of the rectangle"));
        }
        positive(file, "model.width", m.width)?;
        positive(file, "model.duration", m.duration)?;
        if spec.layers.is_empty() {
            return Err(inv(file, "layer", "(missing)", "required: at least one [[layer]] table, from the top: thickness (m) and a material (or a `[mesh]` file instead of the rectangle)"));
        }
        let mut layers = Vec::new();
        let mut bottom = 0.0;
        for (i, l) in spec.layers.iter().enumerate() {
            bottom += positive(file, &format!("layer.{i}.thickness"), l.thickness)?;
            layers.push(Layer {
                bottom,
                material: material(l, file, &format!("layer.{i}"))?,
            });
        }
        if spec.sources.is_empty() {
            return Err(inv(file, "source", "none", "at least one [[source]]"));
        }
        let mut sources = Vec::new();
        let mut f0 = 0.0;
        for (i, s) in spec.sources.iter().enumerate() {
            let key = format!("source.{i}");
            if let Some(x) = s.signal.xi {
                return Err(inv(
                    file,
                    format!("{key}.signal.xi"),
                    x,
                    "a source takes `amplitude` (Pa or N/m), not xi",
                ));
            }
            if let Some(a) = s.signal.angle {
                return Err(inv(
                    file,
                    format!("{key}.signal.angle"),
                    a,
                    "not a key of a 2D source's signal: give the angle as the source's own \
                     `angle` (plane wave, transducer)",
                ));
            }
            let signal: Arc<dyn Excitation> = crate::scenario::build_wave(
                &s.signal,
                &format!("{key}.signal"),
                file,
                dir,
                None,
                cache,
                Some(m.duration),
            )?
            .0;
            if i == 0 {
                f0 = signal.fundamental();
            }
            if let Some((name, own)) = foreign_key(s) {
                return Err(inv(
                    file,
                    format!("{key}.{name}"),
                    "given",
                    &format!(
                        "not a key of a `{}` source (it takes kind, signal, {own})",
                        s.kind
                    ),
                ));
            }
            let top = &layers[0].material;
            let kind = match s.kind.as_str() {
                "transducer" => {
                    let x0 = s.x0.ok_or_else(|| {
                        inv(
                            file,
                            format!("{key}.x0"),
                            "missing",
                            "the aperture start, m",
                        )
                    })?;
                    let x1 = s.x1.ok_or_else(|| {
                        inv(file, format!("{key}.x1"), "missing", "the aperture end, m")
                    })?;
                    if !(x0 >= 0.0 && x1 > x0 && x1 <= m.width) {
                        return Err(inv(
                            file,
                            format!("{key}.x1"),
                            format!("[{x0}, {x1}]"),
                            "0 <= x0 < x1 <= model.width",
                        ));
                    }
                    let on_top = match s.surface.as_deref().unwrap_or("top") {
                        "top" => true,
                        "bottom" => false,
                        v => return Err(inv(file, format!("{key}.surface"), v, "top or bottom")),
                    };
                    let (side_key, side) = if on_top {
                        ("model.top", &m.top)
                    } else {
                        ("model.bottom", &m.bottom)
                    };
                    if side == "rigid" {
                        return Err(inv(
                            file,
                            format!("{key}.surface"),
                            s.surface.as_deref().unwrap_or("top"),
                            &format!(
                                "a surface that can move: `{side_key}` is rigid (a traction \
                                 there does no work)"
                            ),
                        ));
                    }
                    let normal = match s.component.as_deref().unwrap_or("normal") {
                        "normal" => true,
                        "shear" => false,
                        v => {
                            return Err(inv(
                                file,
                                format!("{key}.component"),
                                v,
                                "normal or shear",
                            ));
                        }
                    };
                    if normal && wave == WaveType::Sh {
                        return Err(inv(
                            file,
                            format!("{key}.component"),
                            "normal",
                            "shear (an SH run has no normal motion)",
                        ));
                    }
                    if !(s.angle.abs() < 90.0) {
                        return Err(inv(
                            file,
                            format!("{key}.angle"),
                            s.angle,
                            "in (-90, 90) degrees",
                        ));
                    }
                    let c = if normal { top.p_speed } else { top.s_speed };
                    SourceKind::Traction {
                        top: on_top,
                        x0,
                        x1,
                        normal,
                        delay_per_m: s.angle.to_radians().sin() / c,
                    }
                }
                "force" => {
                    let at = s.at.ok_or_else(|| {
                        inv(
                            file,
                            format!("{key}.at"),
                            "missing",
                            "the force's position [x, z], m",
                        )
                    })?;
                    let d = s.direction.unwrap_or([0.0, 1.0]);
                    let n = (d[0] * d[0] + d[1] * d[1]).sqrt();
                    if !(n > 0.0 && n.is_finite()) {
                        return Err(inv(
                            file,
                            format!("{key}.direction"),
                            format!("{d:?}"),
                            "a non-zero direction [x, z]",
                        ));
                    }
                    SourceKind::Force {
                        at,
                        direction: [d[0] / n, d[1] / n],
                    }
                }
                "plane_wave" => {
                    // (the wave's name in any case: "P", "p", "Sv", ...)
                    let incidence = parse::incidence(s, wave, file, &key)?;
                    let z = s.z.ok_or_else(|| {
                        inv(
                            file,
                            format!("{key}.z"),
                            "missing",
                            "the depth of the total-field/scattered-field line, m",
                        )
                    })?;
                    SourceKind::PlaneWave {
                        incidence,
                        angle: s.angle.to_radians(),
                        z,
                    }
                }
                v => {
                    return Err(inv(
                        file,
                        format!("{key}.kind"),
                        v,
                        "transducer, force or plane_wave",
                    ));
                }
            };
            sources.push(Source { kind, signal });
        }
        let harmonic = m.harmonic.unwrap_or(DEFAULT_HARMONIC);
        // (the elements must resolve the fundamental itself)
        if !(harmonic.is_finite() && harmonic >= 1.0) {
            return Err(inv(
                file,
                "model.harmonic",
                harmonic,
                "a finite number >= 1 (a multiple of f0: the elements resolve f0 at least)",
            ));
        }
        let cs_min = layers
            .iter()
            .map(|l| l.material.s_speed)
            .fold(f64::INFINITY, f64::min);
        let f_max = harmonic * f0;
        let max_time_step = match m.time_step {
            Some(dt) => positive(file, "model.time_step", dt)?,
            None => PHASE_STEP / (2.0 * std::f64::consts::PI * f_max),
        };
        let element_size = match m.element_size {
            Some(h) => positive(file, "model.element_size", h)?,
            None => {
                let materials: Vec<Elastic> = layers.iter().map(|l| l.material).collect();
                let order = m.order.unwrap_or(DEFAULT_ORDER);
                let size = |dt: f64| {
                    element_size_for(order, dt, &materials, wave, f_max, DISPERSION_BUDGET)
                };
                // a step too long for the budget: the elements' share alone; then 16
                // points per S wavelength
                size(max_time_step)
                    .or_else(|| size(0.0))
                    .unwrap_or(cs_min / f_max * order as f64 / 16.0)
            }
        };
        // (the elements follow a transducer's edges: a sliver of an aperture would make
        // slivers of elements, and of the time step)
        // (the mesh's columns are no wider than the rectangle: a frequency in the wrong
        // unit makes elements of metres, which the plausibility warnings name)
        let column = element_size.min(m.width);
        for (i, src) in sources.iter().enumerate() {
            if let SourceKind::Traction { x0, x1, .. } = src.kind
                && x1 - x0 < MIN_APERTURE * column
            {
                return Err(inv(
                    file,
                    format!("source.{i}.x1"),
                    format!("[{x0}, {x1}]"),
                    &format!(
                        "an aperture x1 - x0 of at least {:e} of the element size ({:.3e} \
                             m); a narrower source is a point force (kind = \"force\")",
                        MIN_APERTURE,
                        MIN_APERTURE * column
                    ),
                ));
            }
        }
        let depth = bottom;
        if let Some(pre) = &m.prestress {
            pre.check(wave == WaveType::Sh, file)?;
        }
        let mut cracks = Vec::new();
        for (i, c) in spec.cracks.iter().enumerate() {
            let key = format!("crack.{i}");
            if c.vertical && c.length.is_none() {
                return Err(inv(
                    file,
                    format!("{key}.vertical"),
                    true,
                    "only with `length` (an `end` gives the direction itself; a full-width \
                     crack is horizontal)",
                ));
            }
            let end = match (c.end, c.length, c.full_width) {
                (None, None, true) => [m.width, c.start[1]],
                (_, _, true) => {
                    return Err(inv(
                        file,
                        format!("{key}.full_width"),
                        true,
                        "full_width = true or an `end` / `length`, not both",
                    ));
                }
                (Some(_), Some(l), false) => {
                    return Err(inv(
                        file,
                        format!("{key}.length"),
                        l,
                        "give `end` or `length`, not both",
                    ));
                }
                (Some(e), None, false) => e,
                (None, Some(l), false) => {
                    positive(file, &format!("{key}.length"), l)?;
                    if c.vertical {
                        [c.start[0], c.start[1] + l]
                    } else {
                        [c.start[0] + l, c.start[1]]
                    }
                }
                (None, None, false) => {
                    return Err(inv(
                        file,
                        format!("{key}.end"),
                        "missing",
                        "the crack's end [x, z] or its length, m (or full_width = true)",
                    ));
                }
            };
            if end == c.start {
                return Err(inv(
                    file,
                    format!("{key}.end"),
                    format!("[{}, {}]", end[0], end[1]),
                    "a point other than the start (a crack of positive length)",
                ));
            }
            // a vertical crack may end on a free top or bottom side (surface-breaking)
            let vertical = !c.full_width && end[0] == c.start[0] && end[1] != c.start[1];
            let mouth = |z: f64, side: &str| vertical && (z == 0.0 || z == depth) && side == "free";
            for (p, what) in [(c.start, "start"), (end, "end")] {
                let z_ok = p[1] > 0.0 && p[1] < depth
                    || mouth(p[1], if p[1] == 0.0 { &m.top } else { &m.bottom });
                if !(p[0] >= 0.0 && p[0] <= m.width && z_ok) {
                    return Err(inv(
                        file,
                        format!("{key}.{what}"),
                        format!("[{}, {}]", p[0], p[1]),
                        &format!(
                            "inside the rectangle: 0 <= x <= {} m, 0 < z < {depth} m \
                             (z = 0 or {depth} m: a vertical crack open to a free side)",
                            m.width
                        ),
                    ));
                }
            }
            let length = if c.full_width {
                m.width
            } else {
                (end[0] - c.start[0]).abs() + (end[1] - c.start[1]).abs()
            };
            let horizontal = end[1] == c.start[1];
            let resolved = closure::with_prestress(
                c,
                m.prestress.as_ref(),
                horizontal,
                wave == WaveType::Sh,
                file,
                &key,
            )?;
            let c = &resolved;
            let normal = cache.law(c.static_pressure, &c.compression, &c.traction, file, &key)?;
            let tangential = crate::law::registry::build_tangential(
                &c.tangential,
                c.static_shear,
                &normal,
                file,
                &key,
            )
            .map_err(|e| {
                e.renamed_field(
                    &format!("{key}.static_shear"),
                    &closure::static_shear_key(
                        m.prestress.as_ref(),
                        horizontal,
                        wave == WaveType::Sh,
                        &key,
                    ),
                )
            })?;
            let profile = match &c.closure {
                Some(t) => Some(ClosureProfile::new(c, t, length, file, &key)?),
                None => None,
            };
            cracks.push(Crack {
                start: c.start,
                end,
                full_width: c.full_width,
                law: SharedLaw {
                    normal,
                    tangential: Arc::new(tangential),
                },
                profile: profile.map(|p| Arc::new(p) as Arc<dyn CrackProfile<SharedLaw>>),
            });
        }
        let receivers::Checked {
            points,
            receivers,
            stress_points,
        } = receivers::check(&spec.receivers, wave, m.width, depth, file)?;
        let problem = Solid2d {
            width: m.width,
            layers,
            wave,
            top: side(file, "model.top", &m.top, false)?,
            bottom: side(file, "model.bottom", &m.bottom, false)?,
            sides: side(file, "model.sides", &m.sides, true)?,
            element_size,
            order: m.order.unwrap_or(DEFAULT_ORDER),
            courant: m.courant.unwrap_or(0.9),
            max_time_step,
            cracks,
            sources,
            receivers: points,
            duration: m.duration,
            crack_every: match m.crack_every.unwrap_or(10) {
                0 => {
                    return Err(inv(
                        file,
                        "model.crack_every",
                        0,
                        "a whole number >= 1 (steps)",
                    ));
                }
                n => n,
            },
            pml: Pml {
                thickness: match m.pml_thickness {
                    Some(l) => positive(file, "model.pml_thickness", l)?,
                    None => pml::DEFAULT_ELEMENTS * element_size,
                },
                reflection: m.pml_reflection.unwrap_or(pml::DEFAULT_REFLECTION),
            },
        };
        problem.validate(file)?;
        if let Some(dt) = m.time_step {
            // a step the scheme cannot take is an error, not silently shortened
            let stable = problem.memory_estimate(file)?.stable_time_step;
            if dt > stable * (1.0 + 1e-12) {
                return Err(inv(
                    file,
                    "model.time_step",
                    dt,
                    &format!(
                        "(0, {stable:.4e}] s: the stability limit of this mesh times \
                         model.courant (leave it out for the default step)"
                    ),
                ));
            }
        }
        let backend = match m.backend.as_deref() {
            None => Backend::Cpu,
            Some(name) => match Backend::parse(name) {
                Some(Backend::Gpu) if !Backend::GPU_BUILT => {
                    return Err(inv(
                        file,
                        "model.backend",
                        name,
                        "`cpu` (this build has no GPU backend: build with `--features gpu`)",
                    ));
                }
                Some(b) => b,
                None => return Err(inv(file, "model.backend", name, "`cpu` or `gpu`")),
            },
        };
        let gate = gate::analysis_gate(&spec.analysis, file, m.duration, f0)?;
        let mut receivers = receivers;
        gate::receiver_gates(&spec, &mut receivers, gate, file, m.duration, f0)?;
        let snapshots = match &spec.snapshots {
            Some(s) => Some(s.check(file, m.duration, wave)?),
            None => None,
        };
        Ok(Solid2dScenario {
            spec,
            file: file.to_string(),
            problem,
            f0,
            receivers,
            stress_points,
            gate,
            snapshots,
            backend,
            mesh: None,
        })
    }
}

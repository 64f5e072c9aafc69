//! Bar-stack scenarios (`[model] kind = "bar_stack"`, model.md section 5; thesis sections
//! 2.3.1-2.3.5 and chapter 4): segments, interfaces with any law of the library, end
//! conditions, gravity, damping, a hammer force, and the static step that computes the
//! pre-loaded interface pressures before the dynamics start.

use super::spec::{CompressionSpec, IncidentSpec, InterfaceUpdate, MaterialSpec, TractionSpec};
use crate::error::{Error, Result};
use crate::excitation::{Delayed, Excitation};
use crate::law::{registry, ContactLaw};
use crate::numeric::pchip::Pchip;
use crate::solver::barstack::{BarStack, End, InterfaceScheme, Segment, Signal};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

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

/// A probe resolved to the mesh.
#[derive(Debug, Clone)]
pub struct BarProbe {
    /// Name.
    pub name: String,
    /// Requested position, m.
    pub x: f64,
    /// Global node recorded.
    pub node: usize,
    /// The neighbouring node of the same segment used for the strain, and the signed
    /// distance to it (m): stress = E (u[other] - u[node]) / distance.
    pub other: usize,
    /// Signed distance from `node` to `other`, m.
    pub distance: f64,
    /// Young's modulus of the probe's segment, Pa.
    pub youngs_modulus: f64,
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
pub const DEFAULT_INCIDENT_SPP: usize = super::spec::DEFAULT_SPP_FD;

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
    /// Mass, kg: sets an equivalent density `mass / (area length)` at the common
    /// cross-section, with E scaled by the same factor (the wave speed is kept).
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

/// Half-sine force pulse, N.
#[derive(Debug, Clone, Copy)]
pub struct HalfSine {
    /// Peak, N.
    pub peak: f64,
    /// Duration, s.
    pub duration: f64,
}

impl Signal for HalfSine {
    fn value(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.duration {
            0.0
        } else {
            self.peak * (std::f64::consts::PI * t / self.duration).sin()
        }
    }
}

/// Force interpolated from samples (PCHIP), N.
#[derive(Debug, Clone)]
pub struct ForceFile(Pchip, f64);

impl Signal for ForceFile {
    fn value(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.1 {
            0.0
        } else {
            self.0.eval(t)
        }
    }
}

/// A validated bar-stack scenario.
#[derive(Debug, Clone)]
pub struct BarStackScenario {
    /// The spec.
    pub spec: BarStackSpec,
    /// File it came from.
    pub file: String,
    /// Probes resolved to mesh nodes.
    pub probes: Vec<BarProbe>,
    /// The stack, interfaces built at the static pressures.
    pub stack: BarStack,
    /// Static interface pressures (between segments, then the obstacle), Pa.
    pub static_pressure: Vec<f64>,
    /// The force signal at node 0, N (zero with an incident wave).
    pub force: Arc<dyn Signal>,
    /// `true` when `force` is an imposed displacement of the first node (m), not a force.
    pub imposed_displacement: bool,
    /// Pulse duration of the hammer or imposed displacement, s (the free response is
    /// analysed from twice it); 0 with an incident wave.
    pub pulse_duration: f64,
    /// The incident wave at x = 0 (front at t = 0), when the source is `[incident]`.
    pub incident: Option<Arc<dyn Excitation>>,
    /// Load ratio xi of the incident wave at the first interface (0 without one).
    pub xi: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// Interface time discretisation.
    pub interface_scheme: InterfaceScheme,
}

/// No force.
#[derive(Debug, Clone, Copy)]
struct NoForce;

impl Signal for NoForce {
    fn value(&self, _t: f64) -> f64 {
        0.0
    }
}

fn inv(file: &str, field: impl Into<String>, v: impl std::fmt::Display, allowed: &str) -> Error {
    Error::invalid(file, field, v, allowed)
}

fn pos(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(inv(file, field, v, "must be a finite number > 0"))
    }
}

impl BarStackScenario {
    /// Does this TOML table describe a bar stack?
    pub fn is_bar_stack(table: &toml::Table) -> bool {
        table
            .get("model")
            .and_then(|m| m.get("kind"))
            .and_then(|k| k.as_str())
            == Some("bar_stack")
    }

    /// Validate a parsed table.
    pub fn from_table(table: toml::Table, path: &Path) -> Result<Self> {
        let file = path.display().to_string();
        let spec: BarStackSpec = serde_path_to_error::deserialize(toml::Value::Table(table))
            .map_err(|e| {
                let p = e.path().to_string();
                Error::Parse {
                    file: file.clone(),
                    message: format!(
                        "field `{p}`: {}",
                        e.into_inner().to_string().replace('\n', " ")
                    ),
                }
            })?;
        Self::from_spec(spec, &file, path.parent().unwrap_or(Path::new(".")))
    }

    /// Validate a spec.
    pub fn from_spec(spec: BarStackSpec, file: &str, dir: &Path) -> Result<Self> {
        let m = &spec.model;
        pos(file, "model.area", m.area)?;
        if !m.gravity.is_finite() {
            return Err(inv(
                file,
                "model.gravity",
                m.gravity,
                "must be finite (m/s^2)",
            ));
        }
        if !m.static_force.is_finite() {
            return Err(inv(
                file,
                "model.static_force",
                m.static_force,
                "must be finite (N)",
            ));
        }
        if spec.segments.is_empty() {
            return Err(inv(file, "segment", "none", "at least one [[segment]]"));
        }
        let mut segments = Vec::new();
        for (i, s) in spec.segments.iter().enumerate() {
            let key = |k: &str| format!("segment[{i}].{k}");
            pos(file, &key("length"), s.length)?;
            let mut mat = super::material_of(
                &MaterialSpec {
                    material: s.material.clone(),
                    youngs_modulus: s.youngs_modulus,
                    density: s.density,
                },
                file,
                &format!("segment[{i}]"),
            )?;
            if let Some(mass) = s.mass {
                pos(file, &key("mass"), mass)?;
                let rho_eq = mass / (m.area * s.length);
                mat.youngs_modulus *= rho_eq / mat.density;
                mat.density = rho_eq;
            }
            if !(s.damping.is_finite() && s.damping >= 0.0) {
                return Err(inv(file, key("damping"), s.damping, "must be >= 0 (1/s)"));
            }
            if spec.segments[..i].iter().any(|o| o.name == s.name) || s.name == "obstacle" {
                return Err(inv(
                    file,
                    key("name"),
                    &s.name,
                    "segment names must be unique and not `obstacle`",
                ));
            }
            segments.push(Segment {
                name: s.name.clone(),
                length: s.length,
                material: mat,
                damping: s.damping,
            });
        }
        // static step: pressure at each interface = (static force + weight above) / area
        let weight_above = |k: usize| -> f64 {
            segments[..=k]
                .iter()
                .map(|s| s.material.density * s.length * m.area * m.gravity)
                .sum::<f64>()
        };
        let n = segments.len();
        let mut laws: Vec<Option<Arc<ContactLaw>>> = vec![None; n];
        let mut pressures = vec![0.0; n];
        for (j, itf) in spec.interfaces.iter().enumerate() {
            let [a, b] = &itf.between;
            let ia = spec.segments.iter().position(|s| &s.name == a);
            let ib = if b == "obstacle" {
                Some(n)
            } else {
                spec.segments.iter().position(|s| &s.name == b)
            };
            let (ia, ib) = match (ia, ib) {
                (Some(x), Some(y)) if y == x + 1 => (x, y),
                _ => {
                    return Err(inv(
                        file,
                        format!("interface[{j}].between"),
                        format!("[\"{a}\", \"{b}\"]"),
                        "must name two consecutive segments in order (or the last segment and \"obstacle\")",
                    ))
                }
            };
            let _ = ib;
            if laws[ia].is_some() {
                return Err(inv(
                    file,
                    format!("interface[{j}].between"),
                    a,
                    "one interface per pair of segments",
                ));
            }
            let p = (m.static_force + weight_above(ia)) / m.area;
            if p < 0.0 {
                return Err(inv(
                    file,
                    format!("interface[{j}]"),
                    p,
                    "the static step gives a tensile interface load: the stack would fall apart",
                ));
            }
            let law = registry::build_law(
                p,
                &itf.compression,
                &itf.traction,
                file,
                &format!("interface[{j}]"),
            )?;
            pressures[ia] = p;
            laws[ia] = Some(Arc::new(law));
        }
        let mut interfaces = Vec::new();
        let mut static_pressure = Vec::new();
        for k in 0..n - 1 {
            match &laws[k] {
                Some(l) => {
                    interfaces.push(l.clone());
                    static_pressure.push(pressures[k]);
                }
                None => {
                    return Err(inv(
                        file,
                        "interface",
                        format!("{} / {}", segments[k].name, segments[k + 1].name),
                        "every pair of consecutive segments needs an [[interface]]",
                    ))
                }
            }
        }
        let mut end = |s: &str, key: &str, last: bool| -> Result<End> {
            Ok(match s {
                "free" => End::Free,
                "fixed" => End::Fixed,
                "transparent" => End::Transparent,
                "obstacle" if last => match &laws[n - 1] {
                    Some(l) => {
                        static_pressure.push(pressures[n - 1]);
                        End::Obstacle(l.clone())
                    }
                    None => return Err(inv(file, key, s, "an obstacle end needs an [[interface]] with between = [last segment, \"obstacle\"]")),
                },
                _ => return Err(inv(file, key, s, if last { "free, fixed, transparent or obstacle" } else { "free, fixed or transparent" })),
            })
        };
        let left = end(&m.first_end, "model.first_end", false)?;
        let right = end(&m.last_end, "model.last_end", true)?;
        // an obstacle interface with another far end would be silently unused
        if laws[n - 1].is_some() && !matches!(right, End::Obstacle(_)) {
            return Err(inv(
                file,
                "model.last_end",
                &m.last_end,
                "\"obstacle\": an [[interface]] joins the last segment to the obstacle",
            ));
        }
        let (force, pulse_duration): (Arc<dyn Signal>, f64) =
            match (&spec.excitation, &spec.incident) {
                (Some(ex), None) => hammer(ex, file, dir)?,
                (None, Some(_)) => (Arc::new(NoForce), 0.0),
                (Some(_), Some(_)) => {
                    return Err(inv(
                        file,
                        "incident",
                        "[incident] and [excitation]",
                        "give one source: [excitation] (force or displacement) or [incident]",
                    ))
                }
                (None, None) => {
                    return Err(inv(
                        file,
                        "excitation",
                        "(missing)",
                        "a source: [excitation] (force or displacement at the first end), or \
                     [incident] with model.first_end = \"transparent\"",
                    ))
                }
            };
        // an incident wave through the transparent first end; xi refers to the first
        // interface (or the obstacle of a one-segment stack)
        let incident = match &spec.incident {
            None => {
                if let Some(spp) = m.samples_per_period {
                    return Err(inv(
                        file,
                        "model.samples_per_period",
                        spp,
                        "only with [incident] (time steps per period of the incident wave)",
                    ));
                }
                None
            }
            Some(inc) => {
                if m.first_end != "transparent" {
                    return Err(inv(
                        file,
                        "model.first_end",
                        &m.first_end,
                        "\"transparent\": an [incident] wave enters through the first end",
                    ));
                }
                let first_law: Option<(&ContactLaw, f64)> = if n >= 2 {
                    Some((&interfaces[0], segments[1].material.impedance()))
                } else {
                    match &right {
                        End::Obstacle(l) => Some((l, f64::INFINITY)),
                        _ => None,
                    }
                };
                let xi_ref = first_law.map(|(law, z2)| super::XiReference {
                    law,
                    static_pressure: static_pressure[0],
                    z1: segments[0].material.impedance(),
                    z2,
                    pressure_key: "model.static_force / model.gravity",
                });
                Some(super::build_incident(inc, file, dir, xi_ref.as_ref())?)
            }
        };
        let shortest = segments
            .iter()
            .map(|s| s.length)
            .fold(f64::INFINITY, f64::min);
        let dx = m.cell_size.unwrap_or(shortest / 4.0);
        pos(file, "model.cell_size", dx)?;
        let cmax = segments
            .iter()
            .map(|s| s.material.wave_speed())
            .fold(0.0, f64::max);
        let mut dt = dx / cmax;
        if let Some((exc, _)) = &incident {
            let spp = m.samples_per_period.unwrap_or(DEFAULT_INCIDENT_SPP);
            if !(16..=100_000).contains(&spp) {
                return Err(inv(
                    file,
                    "model.samples_per_period",
                    spp,
                    "must lie in [16, 100000]",
                ));
            }
            let d = dt.min(1.0 / (exc.highest_frequency() * spp as f64));
            // the first segment at Courant number 1: its transparent end then absorbs the
            // outgoing wave exactly
            let c0 = segments[0].material.wave_speed();
            let cells0 = (segments[0].length / (c0 * d) * (1.0 - 1e-12))
                .ceil()
                .max(1.0);
            dt = segments[0].length / (c0 * cells0);
        }
        if let Some(ts) = m.time_step {
            // explicit scheme: a segment needs one cell of size >= c dt (Courant <= 1)
            let (limit, name) = segments
                .iter()
                .map(|s| (s.length / s.material.wave_speed(), s.name.as_str()))
                .fold((f64::INFINITY, ""), |a, b| if b.0 < a.0 { b } else { a });
            if !(ts.is_finite() && ts > 0.0 && ts <= limit) {
                return Err(inv(
                    file,
                    "model.time_step",
                    ts,
                    &format!(
                        "in (0, {limit:.4e}] s: above it segment `{name}` cannot hold one cell \
                         at Courant number <= 1 (stability limit of the explicit scheme)"
                    ),
                ));
            }
            dt = ts;
        }
        let travel: f64 = segments
            .iter()
            .map(|s| s.length / s.material.wave_speed())
            .sum();
        let duration = match (m.duration, &incident) {
            (Some(d), _) => {
                pos(file, "model.duration", d)?;
                d
            }
            (None, Some((exc, _))) => exc.duration() + 4.0 * travel + 100.0 / exc.fundamental(),
            (None, None) => DEFAULT_HAMMER_DURATION,
        };
        let steps = duration / dt;
        if steps > 5e8 {
            return Err(inv(
                file,
                "model.duration",
                duration,
                &format!("too many time steps ({steps:.2e}); raise model.cell_size"),
            ));
        }
        let a = &spec.analysis;
        if !(a.first_mode_min > 0.0 && a.first_mode_max > a.first_mode_min) {
            return Err(inv(
                file,
                "analysis.first_mode_max",
                a.first_mode_max,
                "must exceed analysis.first_mode_min > 0",
            ));
        }
        let stack = BarStack {
            area: m.area,
            segments: segments.clone(),
            interfaces: interfaces.clone(),
            left: left.clone(),
            right: right.clone(),
            incident: None,
        };
        let mesh = stack.mesh(dt);
        let total: f64 = segments.iter().map(|s| s.length).sum();
        let mut probes = Vec::with_capacity(spec.probes.len());
        for (k, p) in spec.probes.iter().enumerate() {
            let ok_name = !p.name.is_empty()
                && p.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_');
            if !ok_name || spec.probes[..k].iter().any(|q| q.name == p.name) {
                return Err(inv(
                    file,
                    format!("probe[{k}].name"),
                    &p.name,
                    "a unique name of letters, digits and _",
                ));
            }
            if !(p.x.is_finite() && p.x >= 0.0 && p.x <= total) {
                return Err(inv(
                    file,
                    format!("probe[{k}].x"),
                    p.x,
                    &format!("in [0, {total}] m (the length of the stack)"),
                ));
            }
            let mut start = 0.0;
            let mut seg = segments.len() - 1;
            for (i, sg) in segments.iter().enumerate() {
                if p.x <= start + sg.length {
                    seg = i;
                    break;
                }
                start += sg.length;
            }
            let node = stack.node_at(&mesh, seg, p.x - start);
            let last = mesh.offset[seg] + mesh.cells[seg];
            let (other, distance) = if node < last {
                (node + 1, mesh.dx[seg])
            } else {
                (node - 1, -mesh.dx[seg])
            };
            probes.push(BarProbe {
                name: p.name.clone(),
                x: p.x,
                node,
                other,
                distance,
                youngs_modulus: segments[seg].material.youngs_modulus,
            });
        }
        let imposed_displacement = spec
            .excitation
            .as_ref()
            .is_some_and(|e| e.kind.starts_with("displacement"));
        if imposed_displacement && m.first_end != "free" {
            return Err(inv(
                file,
                "model.first_end",
                &m.first_end,
                "\"free\": an imposed displacement (excitation.kind) drives the first end",
            ));
        }
        // the solver takes the incident stress where the wave meets the first interface, one
        // travel time of the first segment after it enters at x = 0
        let at_first_interface = incident.as_ref().map(|(exc, _)| -> Arc<dyn Excitation> {
            let c0 = segments[0].material.wave_speed();
            Arc::new(Delayed::new(exc.clone(), segments[0].length / c0))
        });
        Ok(BarStackScenario {
            imposed_displacement,
            probes,
            stack: BarStack {
                area: m.area,
                segments,
                interfaces,
                left,
                right,
                incident: at_first_interface,
            },
            static_pressure,
            force,
            pulse_duration,
            xi: incident.as_ref().map_or(0.0, |(_, xi)| *xi),
            incident: incident.map(|(exc, _)| exc),
            duration,
            dt,
            interface_scheme: m.interface_update.into(),
            file: file.to_string(),
            spec,
        })
    }
}

/// The `[excitation]` signal at the first node (force, N, or imposed displacement, m) and
/// its pulse duration, s.
fn hammer(ex: &ForceSpec, file: &str, dir: &Path) -> Result<(Arc<dyn Signal>, f64)> {
    let half_sine = |unit: &str, what: &str| -> Result<(Arc<dyn Signal>, f64)> {
        let peak = ex
            .peak
            .ok_or_else(|| inv(file, "excitation.peak", "(missing)", what))?;
        if !peak.is_finite() {
            return Err(inv(
                file,
                "excitation.peak",
                peak,
                &format!("must be finite ({unit})"),
            ));
        }
        let d = ex.duration.unwrap_or(DEFAULT_PULSE_DURATION);
        pos(file, "excitation.duration", d)?;
        Ok((Arc::new(HalfSine { peak, duration: d }), d))
    };
    match ex.kind.as_str() {
        "force_pulse" => half_sine("N", "peak force in N"),
        "displacement_pulse" => half_sine("m", "peak displacement in m"),
        "force_file" | "displacement_file" => {
            let rel = ex.path.as_ref().ok_or_else(|| {
                inv(
                    file,
                    "excitation.path",
                    "(missing)",
                    "a CSV file (time s, force N)",
                )
            })?;
            let (t, f) = crate::excitation::FileWaveform::read(&dir.join(rel), "excitation.path")?;
            let t0 = t[0];
            let ts: Vec<f64> = t.iter().map(|v| v - t0).collect();
            let p = Pchip::new(&ts, &f)
                .ok_or_else(|| inv(file, "excitation.path", rel, "invalid force samples"))?;
            let d = *ts.last().unwrap_or(&0.0);
            Ok((
                Arc::new(ForceFile(p, d)),
                ex.duration.unwrap_or(DEFAULT_PULSE_DURATION),
            ))
        }
        other => Err(inv(
            file,
            "excitation.kind",
            other,
            "force_pulse, force_file, displacement_pulse or displacement_file",
        )),
    }
}

impl BarStackSpec {
    /// Deserialize a table into a spec, naming the field path on failure.
    pub fn from_table(table: toml::Table, file: &str) -> Result<Self> {
        serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
            let p = e.path().to_string();
            Error::Parse {
                file: file.to_string(),
                message: format!(
                    "field `{p}`: {}",
                    e.into_inner().to_string().replace('\n', " ")
                ),
            }
        })
    }
}

impl BarStackScenario {
    /// [`BarStackScenario::from_spec`] taking laws and files from `cache` when their
    /// inputs are unchanged (what a template does for each point).
    pub fn from_spec_cached(
        spec: BarStackSpec,
        file: &str,
        dir: &Path,
        _cache: &super::BuildCache,
    ) -> Result<Self> {
        Self::from_spec(spec, file, dir)
    }
}

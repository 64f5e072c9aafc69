//! Bar-stack scenarios (`[model] kind = "bar_stack"`, model.md section 9; thesis sections
//! 2.3.1-2.3.5 and chapter 4): segments, interfaces with any law of the library, end
//! conditions, gravity, damping, a hammer force, and the static step that computes the
//! pre-loaded interface pressures before the dynamics start.
//!
//! [`BarStackScenario::from_spec`] validates a [`BarStackSpec`] step by step: the stack
//! (`stack.rs`: model keys, segments, interfaces, static step, end conditions), the source
//! (`source.rs`: hammer, imposed displacement or incident wave), the discretisation and
//! analysis settings (`settings.rs`) and the probes (`probes.rs`). Each step reports the
//! first invalid value it meets, in the order of the steps.

mod probes;
mod settings;
mod source;
mod spec;
mod stack;

pub use probes::{BarProbe, ShearProbe};
pub use source::{ForceFile, HalfSine};
pub use spec::{
    AnalysisSpec, BarStackSpec, ForceSpec, InterfaceSpec, ModelSpec, ProbeSpec, SegmentSpec,
    DEFAULT_HAMMER_DURATION, DEFAULT_INCIDENT_SPP, DEFAULT_PULSE_DURATION,
};

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::scenario::BuildCache;
use crate::solver::bar_stack::{BarStack, InterfaceScheme, Signal};
use std::path::Path;
use std::sync::Arc;

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
    /// The incident shear wave at x = 0 (front at t = its delay), when the source has a
    /// `[shear_incident]`.
    pub shear_incident: Option<Arc<dyn Excitation>>,
    /// Load ratio xi of the incident wave at the first interface (0 without one).
    pub xi: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// Interface time discretisation.
    pub interface_scheme: InterfaceScheme,
}

/// The validation error of `field` in `file`: its value and what is allowed.
fn inv(file: &str, field: impl Into<String>, v: impl std::fmt::Display, allowed: &str) -> Error {
    Error::invalid(file, field, v, allowed)
}

/// Check that `field` is a finite number > 0.
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
        let spec = BarStackSpec::from_table(table, &file)?;
        Self::from_spec(spec, &file, path.parent().unwrap_or(Path::new(".")))
    }

    /// Validate a spec (`dir`: the folder that relative file paths refer to). The steps
    /// run in this order, so a file with several invalid values always reports the same
    /// first one.
    pub fn from_spec(spec: BarStackSpec, file: &str, dir: &Path) -> Result<Self> {
        Self::from_spec_cached(spec, file, dir, &BuildCache::new())
    }

    /// [`BarStackScenario::from_spec`] taking laws and files from `cache` when their
    /// inputs are unchanged (what a template does for each point).
    pub fn from_spec_cached(
        spec: BarStackSpec,
        file: &str,
        dir: &Path,
        cache: &BuildCache,
    ) -> Result<Self> {
        let m = &spec.model;
        stack::validate_model(m, file)?;
        let segments = stack::build_segments(&spec.segments, m.area, file)?;
        let laws = stack::build_interface_laws(&spec, &segments, file, cache)?;
        let interfaces = laws.between_segments(&segments, file)?;
        let (left, right) = laws.end_conditions(m, file)?;
        let static_pressure = laws.static_pressure(&right);
        let mut stack = BarStack {
            area: m.area,
            segments,
            interfaces,
            left,
            right,
            incident: None,
            shear: None,
        };
        let (force, pulse_duration) = source::force_source(&spec, file, dir, cache)?;
        let incident = source::incident_wave(&spec, &stack, &static_pressure, file, dir, cache)?;
        let shear_incident = source::shear_wave(&spec, file, dir, cache)?;
        stack.shear = laws.shear_stack(&spec, &stack.right, shear_incident.clone(), file)?;
        if stack.shear.is_some() {
            stack::require_shear_moduli(&stack.segments, file)?;
        }
        let wave = incident.as_ref().map(|(exc, _)| exc);
        let waves: Vec<&Arc<dyn Excitation>> = wave.into_iter().chain(&shear_incident).collect();
        let dt = settings::time_step(m, &stack.segments, &waves, file)?;
        let duration =
            settings::duration(m, &stack.segments, &waves, stack.shear.is_some(), dt, file)?;
        settings::validate_analysis(&spec.analysis, file)?;
        check_size(&spec, &stack, dt, duration, file)?;
        let probes = probes::resolve_probes(&spec.probes, &stack, dt, file)?;
        let imposed_displacement = source::imposed_displacement(&spec, file)?;
        stack.incident = source::incident_at_first_interface(wave, &stack.segments);
        if let Some(sh) = stack.shear.as_mut() {
            sh.incident =
                source::shear_at_first_interface(shear_incident.as_ref(), &stack.segments);
        }
        Ok(BarStackScenario {
            imposed_displacement,
            probes,
            stack,
            static_pressure,
            force,
            pulse_duration,
            xi: incident.as_ref().map_or(0.0, |(_, xi)| *xi),
            incident: incident.map(|(exc, _)| exc),
            shear_incident,
            duration,
            dt,
            interface_scheme: m.interface_update.into(),
            file: file.to_string(),
            spec,
        })
    }
}

/// Refuse, before the mesh is built, a stack whose mesh or recorded histories exceed the
/// memory budget ([`crate::budget`]).
fn check_size(
    spec: &BarStackSpec,
    stack: &BarStack,
    dt: f64,
    duration: f64,
    file: &str,
) -> Result<()> {
    let cells = |c: f64, l: f64| (l / (c * dt)).max(1.0) + 1.0;
    let mut nodes: f64 = stack
        .segments
        .iter()
        .map(|s| cells(s.material.wave_speed(), s.length))
        .sum();
    if stack.shear.is_some() {
        nodes += stack
            .segments
            .iter()
            .filter_map(|s| Some(cells(s.material.shear_wave_speed()?, s.length)))
            .sum::<f64>();
    }
    let cmax = stack
        .segments
        .iter()
        .map(|s| s.material.wave_speed())
        .fold(0.0, f64::max);
    let (field, value) = match spec.model.time_step {
        Some(ts) => ("model.time_step", ts),
        None => ("model.cell_size", cmax * dt),
    };
    let mut series = (3 + 5 * spec.probes.len() + 3 * (stack.interfaces.len() + 2)) as f64;
    if stack.shear.is_some() {
        // transverse ends, probes and per-interface gap, stress, slip and state
        series += (2 + 3 * spec.probes.len() + 4 * (stack.interfaces.len() + 1)) as f64;
    }
    crate::scenario::budget::check_bar_stack(
        file,
        nodes,
        field,
        value,
        duration / dt,
        series,
        duration,
    )
}

impl BarStackSpec {
    /// Deserialize a table into a spec, naming the field path on failure. Unit strings
    /// (`length = "5 mm"`) are converted to SI first ([`crate::scenario::units`]).
    pub fn from_table(table: toml::Table, file: &str) -> Result<Self> {
        crate::scenario::value::deserialize_scenario(table, file, hint)
    }
}

/// What a bar-stack scenario's key takes where serde's own message would not say it.
fn hint(key: &str, problem: crate::scenario::value::FieldProblem) -> Option<String> {
    use crate::scenario::value::FieldProblem::{Missing, Wrong};
    Some(match (key, problem) {
        ("model", Missing) => {
            "a [model] table with kind = \"bar_stack\" and the cross-section area (m^2)".into()
        }
        ("segment", Missing) => {
            "at least one [[segment]] table: name, length (m) and a material".into()
        }
        ("model.samples_per_period", Wrong) => {
            crate::scenario::value::whole_numbers(crate::scenario::spec::SAMPLES_PER_PERIOD)
        }
        _ => return None,
    })
}

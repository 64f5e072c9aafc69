//! Validation steps for the source: the hammer force or imposed displacement of
//! `[excitation]`, or the incident wave of `[incident]`, and the signals they produce.

use super::spec::{BarStackSpec, ForceSpec, DEFAULT_PULSE_DURATION};
use super::{inv, pos};
use crate::error::Result;
use crate::excitation::{Delayed, Excitation};
use crate::law::ContactLaw;
use crate::numeric::pchip::Pchip;
use crate::scenario::BuildCache;
use crate::solver::bar_stack::{BarStack, End, Segment, Signal};
use std::path::Path;
use std::sync::Arc;

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

/// No force.
#[derive(Debug, Clone, Copy)]
struct NoForce;

impl Signal for NoForce {
    fn value(&self, _t: f64) -> f64 {
        0.0
    }
}

/// The force/hammer source: the `[excitation]` signal and its pulse duration, s, or no
/// force (duration 0) with an `[incident]` wave; exactly one of the two must be given.
pub(super) fn force_source(
    spec: &BarStackSpec,
    file: &str,
    dir: &Path,
    cache: &BuildCache,
) -> Result<(Arc<dyn Signal>, f64)> {
    if spec.excitation.is_some() && spec.shear_incident.is_some() {
        return Err(inv(
            file,
            "shear_incident",
            "[shear_incident] and [excitation]",
            "a shear wave enters through a transparent first end: give [shear_incident] \
             (and [incident]) without [excitation]",
        ));
    }
    match (&spec.excitation, &spec.incident) {
        (Some(ex), None) => hammer(ex, spec.model.duration, file, dir, cache),
        (None, Some(_)) => Ok((Arc::new(NoForce), 0.0)),
        (None, None) if spec.shear_incident.is_some() => Ok((Arc::new(NoForce), 0.0)),
        (Some(_), Some(_)) => Err(inv(
            file,
            "incident",
            "[incident] and [excitation]",
            "give one source: [excitation] (force or displacement) or [incident]",
        )),
        (None, None) => Err(inv(
            file,
            "excitation",
            "(missing)",
            "a source: [excitation] (force or displacement at the first end), or \
                     [incident] with model.first_end = \"transparent\"",
        )),
    }
}

/// The `[excitation]` signal at the first node (force, N, or imposed displacement, m) and
/// its pulse duration, s; a file is read over the simulated time (`model.duration`) only.
fn hammer(
    ex: &ForceSpec,
    duration: Option<f64>,
    file: &str,
    dir: &Path,
    cache: &BuildCache,
) -> Result<(Arc<dyn Signal>, f64)> {
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
            // only the simulated window is read: a file much longer than the run is
            // truncated, not loaded (the cache key holds the window)
            let window = duration.unwrap_or(super::DEFAULT_HAMMER_DURATION);
            let cols = cache.columns(
                &dir.join(rel),
                &format!("excitation.path@{window:e}"),
                |p, _| {
                    crate::excitation::FileWaveform::read_window(
                        p,
                        "excitation.path",
                        window.is_finite().then_some(window),
                    )
                },
            )?;
            let (t, f) = (&cols.0, &cols.1);
            let t0 = t[0];
            let ts: Vec<f64> = t.iter().map(|v| v - t0).collect();
            let p = Pchip::new(&ts, f)
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

/// The incident wave through the transparent first end, and its load ratio xi, which
/// refers to the first interface (or the obstacle of a one-segment stack);
/// `model.samples_per_period` is an error without one.
pub(super) fn incident_wave(
    spec: &BarStackSpec,
    stack: &BarStack,
    static_pressure: &[f64],
    file: &str,
    dir: &Path,
    cache: &BuildCache,
) -> Result<Option<(Arc<dyn Excitation>, f64)>> {
    let m = &spec.model;
    let segments = &stack.segments;
    match &spec.incident {
        None => {
            if let (Some(spp), None) = (m.samples_per_period, &spec.shear_incident) {
                return Err(inv(
                    file,
                    "model.samples_per_period",
                    spp,
                    "only with [incident] or [shear_incident] (time steps per period of the \
                     incident wave)",
                ));
            }
            Ok(None)
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
            let first_law: Option<(&ContactLaw, f64)> = if segments.len() >= 2 {
                Some((&stack.interfaces[0], segments[1].material.impedance()))
            } else {
                match &stack.right {
                    End::Obstacle(l) => Some((l, f64::INFINITY)),
                    _ => None,
                }
            };
            let xi_ref = first_law.map(|(law, z2)| crate::scenario::XiReference {
                law,
                static_pressure: static_pressure[0],
                z1: segments[0].material.impedance(),
                z2,
                pressure_key: "model.static_force / model.gravity",
            });
            // an explicit model.duration bounds the read of a waveform file
            Ok(Some(crate::scenario::build_incident_window(
                inc,
                file,
                dir,
                xi_ref.as_ref(),
                cache,
                m.duration,
            )?))
        }
    }
}

/// The incident shear wave of `[shear_incident]`, which enters through the transparent
/// first end like `[incident]`.
pub(super) fn shear_wave(
    spec: &BarStackSpec,
    file: &str,
    dir: &Path,
    cache: &BuildCache,
) -> Result<Option<Arc<dyn Excitation>>> {
    let Some(inc) = &spec.shear_incident else {
        return Ok(None);
    };
    if spec.model.first_end != "transparent" {
        return Err(inv(
            file,
            "model.first_end",
            &spec.model.first_end,
            "\"transparent\": a [shear_incident] wave enters through the first end",
        ));
    }
    // an explicit model.duration bounds the read of a waveform file
    crate::scenario::build_shear_wave(inc, file, dir, cache, spec.model.duration).map(Some)
}

/// The incident wave as the solver takes it: its stress where it meets the first
/// interface, one travel time of the first segment after it enters at x = 0.
pub(super) fn incident_at_first_interface(
    incident: Option<&Arc<dyn Excitation>>,
    segments: &[Segment],
) -> Option<Arc<dyn Excitation>> {
    incident.map(|exc| -> Arc<dyn Excitation> {
        let c0 = segments[0].material.wave_speed();
        Arc::new(Delayed::new(exc.clone(), segments[0].length / c0))
    })
}

/// [`incident_at_first_interface`] for the shear wave, which crosses the first segment at
/// its shear wave speed.
pub(super) fn shear_at_first_interface(
    incident: Option<&Arc<dyn Excitation>>,
    segments: &[Segment],
) -> Option<Arc<dyn Excitation>> {
    incident.map(|exc| -> Arc<dyn Excitation> {
        let ct = segments[0].material.shear_wave_speed().unwrap_or(f64::NAN);
        Arc::new(Delayed::new(exc.clone(), segments[0].length / ct))
    })
}

/// The imposed displacement: whether `[excitation]` drives the first end's displacement
/// rather than a force, which needs a free first end.
pub(super) fn imposed_displacement(spec: &BarStackSpec, file: &str) -> Result<bool> {
    let m = &spec.model;
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
    Ok(imposed_displacement)
}

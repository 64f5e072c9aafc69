//! The periodic strip: one element wide, free top and bottom, driven by a uniform traction
//! over its whole top, so that a plane wave travels down it along z (P from a normal
//! traction, SV or SH from a shear one). The dispersion measurements, the 1D reductions and
//! the stability tests start from it. Its plane-wave twin has absorbing top and bottom and
//! a plane wave injected across a line (total-field/scattered-field): the 1D reductions
//! and the injection's leakage use it.

use super::Elastic;
use super::{pml, Incidence, Layer, Pml, Side, Solid2d, Source, SourceKind, WaveType};
use crate::excitation::Excitation;
use std::sync::Arc;

impl<L> Solid2d<L> {
    /// A periodic strip of `material`, `h` wide (one element of `h`, m) and `depth` deep
    /// (m), free top and bottom, order 4, courant 0.5, no cap on the time step, driven by a
    /// traction over the whole top (`traction.0`: normal, else shear) with the signal
    /// `traction.1` (Pa) for `duration` s; no crack, no receiver (struct update syntax
    /// changes the rest).
    pub fn periodic_strip(
        material: Elastic,
        wave: WaveType,
        h: f64,
        depth: f64,
        traction: (bool, Arc<dyn Excitation>),
        duration: f64,
    ) -> Self {
        let (normal, signal) = traction;
        Solid2d {
            width: h,
            layers: vec![Layer {
                bottom: depth,
                material,
            }],
            wave,
            top: Side::Free,
            bottom: Side::Free,
            sides: Side::Periodic,
            element_size: h,
            order: 4,
            courant: 0.5,
            max_time_step: f64::INFINITY,
            cracks: vec![],
            sources: vec![Source {
                kind: SourceKind::Traction {
                    top: true,
                    x0: 0.0,
                    x1: h,
                    normal,
                    delay_per_m: 0.0,
                },
                signal,
            }],
            receivers: vec![],
            duration,
            crack_every: 1,
            pml: Pml::elements(pml::DEFAULT_ELEMENTS, h),
        }
    }

    /// The same strip (`h` wide, `depth` deep, m) with absorbing top and bottom and a
    /// plane wave of `incidence` at normal incidence injected across `z_line` (m) with
    /// `signal` (Pa) for `duration` (s): the layers two P wavelengths (at the signal's
    /// fundamental) thick with a 1e-6 target, so that their reflection stays below what a
    /// fine mesh resolves (the default layers' -57 dB would be its error floor).
    #[allow(clippy::too_many_arguments)]
    pub fn plane_wave_strip(
        material: Elastic,
        wave: WaveType,
        incidence: Incidence,
        h: f64,
        depth: f64,
        z_line: f64,
        signal: Arc<dyn Excitation>,
        duration: f64,
    ) -> Self {
        let wavelength = material.p_speed / signal.fundamental();
        Solid2d {
            top: Side::Absorbing,
            bottom: Side::Absorbing,
            pml: Pml {
                thickness: 2.0 * wavelength,
                reflection: 1e-6,
            },
            sources: vec![Source {
                kind: SourceKind::PlaneWave {
                    incidence,
                    angle: 0.0,
                    z: z_line,
                },
                signal: signal.clone(),
            }],
            ..Self::periodic_strip(material, wave, h, depth, (true, signal), duration)
        }
    }
}

//! The periodic strip: one element wide, free top and bottom, driven by a uniform traction
//! over its whole top, so that a plane wave travels down it along z (P from a normal
//! traction, SV or SH from a shear one). The dispersion measurements, the 1D reductions and
//! the stability tests start from it.

use super::Elastic;
use super::{pml, Layer, Pml, Side, Solid2d, Source, SourceKind, WaveType};
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
}

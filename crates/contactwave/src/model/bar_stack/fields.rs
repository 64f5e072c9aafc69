//! Typed access to the numbers of a bar-stack spec by dotted key (`segment.1.mass`,
//! `interface.0.compression.c`, `excitation.peak`, ...).

use crate::model::{Fields, Slot};
use crate::scenario::bar_stack::{
    AnalysisSpec, BarStackSpec, ForceSpec, InterfaceSpec, ModelSpec, ProbeSpec, SegmentSpec,
};

/// The item of an array of tables named by a decimal index.
fn item<'a, T>(items: &'a mut [T], index: &str) -> Option<&'a mut T> {
    index.parse::<usize>().ok().and_then(|i| items.get_mut(i))
}

impl Fields for BarStackSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["model", rest @ ..] => self.model.slot(rest),
            ["segment", i, rest @ ..] => item(&mut self.segments, i)?.slot(rest),
            ["interface", i, rest @ ..] => item(&mut self.interfaces, i)?.slot(rest),
            ["probe", i, rest @ ..] => item(&mut self.probes, i)?.slot(rest),
            ["excitation", rest @ ..] => self.excitation.as_mut()?.slot(rest),
            ["incident", rest @ ..] => self.incident.as_mut()?.slot(rest),
            ["analysis", rest @ ..] => self.analysis.slot(rest),
            _ => None,
        }
    }
}

impl Fields for ModelSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["area"] => Some(Slot::F64(&mut self.area)),
            ["gravity"] => Some(Slot::F64(&mut self.gravity)),
            ["static_force"] => Some(Slot::F64(&mut self.static_force)),
            ["duration"] => Some(Slot::OptF64(&mut self.duration)),
            ["samples_per_period"] => Some(Slot::OptUsize(
                &mut self.samples_per_period,
                crate::scenario::spec::SAMPLES_PER_PERIOD,
            )),
            ["cell_size"] => Some(Slot::OptF64(&mut self.cell_size)),
            ["time_step"] => Some(Slot::OptF64(&mut self.time_step)),
            _ => None,
        }
    }
}

impl Fields for SegmentSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["length"] => Some(Slot::F64(&mut self.length)),
            ["youngs_modulus"] => Some(Slot::OptF64(&mut self.youngs_modulus)),
            ["density"] => Some(Slot::OptF64(&mut self.density)),
            ["mass"] => Some(Slot::OptF64(&mut self.mass)),
            ["damping"] => Some(Slot::F64(&mut self.damping)),
            _ => None,
        }
    }
}

impl Fields for InterfaceSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["compression", rest @ ..] => self.compression.slot(rest),
            ["traction", rest @ ..] => self.traction.slot(rest),
            _ => None,
        }
    }
}

impl Fields for ProbeSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["x"] => Some(Slot::F64(&mut self.x)),
            _ => None,
        }
    }
}

impl Fields for ForceSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["peak"] => Some(Slot::OptF64(&mut self.peak)),
            ["duration"] => Some(Slot::OptF64(&mut self.duration)),
            _ => None,
        }
    }
}

impl Fields for AnalysisSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["first_mode_min"] => Some(Slot::F64(&mut self.first_mode_min)),
            ["first_mode_max"] => Some(Slot::F64(&mut self.first_mode_max)),
            _ => None,
        }
    }
}

//! Typed access to the numbers of a scenario spec by dotted key: the setters that sweeps
//! and identification use on a planned template (no TOML round trip per point).

use crate::error::{Error, Result};
use crate::law::param::ParamMut;
use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use crate::scenario::spec::{
    CounterpartSpec, IncidentSpec, InterfaceSpec, MaterialSpec, ProbeSpec, ScenarioSpec, SolverSpec,
};

/// A number of a spec, by reference.
#[derive(Debug)]
pub enum Slot<'a> {
    /// A required number.
    F64(&'a mut f64),
    /// An optional number.
    OptF64(&'a mut Option<f64>),
    /// An optional count and the range it takes (checked again when the spec is).
    OptUsize(&'a mut Option<usize>, std::ops::RangeInclusive<usize>),
}

impl Slot<'_> {
    /// Write `v` (SI units); a count takes only whole numbers in its range.
    pub fn set(self, v: f64, file: &str, key: &str) -> Result<()> {
        match self {
            Slot::F64(x) => *x = v,
            Slot::OptF64(x) => *x = Some(v),
            Slot::OptUsize(x, range) => {
                let n = v as usize;
                if !(v.is_finite() && v.fract() == 0.0 && v >= 0.0 && range.contains(&n)) {
                    return Err(Error::invalid(
                        file,
                        key,
                        v,
                        crate::scenario::whole_numbers(range),
                    ));
                }
                *x = Some(n)
            }
        }
        Ok(())
    }
}

/// Specs whose numbers can be reached by a dotted path.
pub trait Fields {
    /// The number at `path` (e.g. `["incident", "xi"]`), or `None` if the path names no
    /// number of this spec as it stands (an unknown key, a table, a key of another law
    /// variant).
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>>;
}

/// `match` arms from field names to slots: `fields!(self, path; f64: a, b; opt: c)`.
macro_rules! leaf {
    ($path:expr_2021; $($kind:ident $name:literal => $field:expr_2021),* $(,)?) => {
        match $path {
            $([$name] => Some(Slot::$kind($field)),)*
            _ => None,
        }
    };
}

impl Fields for ScenarioSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        let (head, rest) = path.split_first()?;
        match *head {
            "medium" => self.medium.slot(rest),
            "counterpart" => self.counterpart.slot(rest),
            "interface" => self.interface.slot(rest),
            "incident" => self.incident.slot(rest),
            "shear_incident" => self.shear_incident.as_mut()?.slot(rest),
            "probe" => self.probe.slot(rest),
            "solver" => self.solver.slot(rest),
            _ => None,
        }
    }
}

impl Fields for MaterialSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        leaf!(path; OptF64 "youngs_modulus" => &mut self.youngs_modulus,
                    OptF64 "density" => &mut self.density,
                    OptF64 "poisson_ratio" => &mut self.poisson_ratio,
                    OptF64 "shear_modulus" => &mut self.shear_modulus,
                    OptF64 "cl" => &mut self.cl,
                    OptF64 "ct" => &mut self.ct)
    }
}

impl Fields for CounterpartSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        leaf!(path; OptF64 "youngs_modulus" => &mut self.youngs_modulus,
                    OptF64 "density" => &mut self.density,
                    OptF64 "poisson_ratio" => &mut self.poisson_ratio,
                    OptF64 "shear_modulus" => &mut self.shear_modulus,
                    OptF64 "cl" => &mut self.cl,
                    OptF64 "ct" => &mut self.ct)
    }
}

impl Fields for InterfaceSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["static_pressure"] => Some(Slot::F64(&mut self.static_pressure)),
            ["static_shear"] => Some(Slot::F64(&mut self.static_shear)),
            ["tangential", rest @ ..] => self.tangential.slot(rest),
            ["compression", rest @ ..] => self.compression.slot(rest),
            ["traction", rest @ ..] => self.traction.slot(rest),
            _ => None,
        }
    }
}

/// The slot of a law parameter by its own name (each law file's `param_mut`).
fn law_slot<'a>(
    path: &[&str],
    param: impl FnOnce(&str) -> Option<ParamMut<'a>>,
) -> Option<Slot<'a>> {
    match path {
        [name] => param(name).map(|p| match p {
            ParamMut::F64(x) => Slot::F64(x),
            ParamMut::OptF64(x) => Slot::OptF64(x),
        }),
        _ => None,
    }
}

impl Fields for CompressionSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        law_slot(path, |name| self.param_mut(name))
    }
}

impl Fields for TractionSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        law_slot(path, |name| self.param_mut(name))
    }
}

impl Fields for TangentialSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        law_slot(path, |name| self.param_mut(name))
    }
}

impl Fields for IncidentSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        // `amplitude` and `xi` are two ways to give the same quantity: setting one
        // removes the other
        match path {
            ["xi"] => {
                self.amplitude = None;
                Some(Slot::OptF64(&mut self.xi))
            }
            ["amplitude"] => {
                self.xi = None;
                Some(Slot::OptF64(&mut self.amplitude))
            }
            _ => leaf!(path; OptF64 "frequency" => &mut self.frequency,
                             OptF64 "frequency2" => &mut self.frequency2,
                             OptF64 "amplitude_ratio" => &mut self.amplitude_ratio,
                             OptF64 "cycles" => &mut self.cycles,
                             OptF64 "ramp_fraction" => &mut self.ramp_fraction,
                             OptF64 "delay" => &mut self.delay,
                             OptF64 "angle" => &mut self.angle),
        }
    }
}

impl Fields for ProbeSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        leaf!(path; F64 "x" => &mut self.x)
    }
}

impl Fields for SolverSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["samples_per_period"] => Some(Slot::OptUsize(
                &mut self.samples_per_period,
                crate::scenario::spec::SAMPLES_PER_PERIOD,
            )),
            ["tail_periods"] => Some(Slot::OptF64(&mut self.tail_periods)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_reach_law_parameters_of_the_variant_only() {
        let mut i = InterfaceSpec {
            static_pressure: 1.0,
            compression: CompressionSpec::Power(crate::law::compression::power::Spec {
                c: 1.0,
                m: 0.5,
            }),
            traction: TractionSpec::Free(Default::default()),
            static_shear: 0.0,
            tangential: TangentialSpec::Coulomb(crate::law::tangential::coulomb::Spec {
                friction: 0.3,
                stiffness: None,
            }),
        };
        i.slot(&["tangential", "friction"])
            .unwrap()
            .set(0.5, "f", "k")
            .unwrap();
        assert!(matches!(i.tangential, TangentialSpec::Coulomb(s) if s.friction == 0.5));
        i.slot(&["compression", "m"])
            .unwrap()
            .set(0.3, "f", "k")
            .unwrap();
        assert_eq!(
            i.compression,
            CompressionSpec::Power(crate::law::compression::power::Spec { c: 1.0, m: 0.3 })
        );
        assert!(i.slot(&["compression", "k0"]).is_none());
        assert!(i.slot(&["traction", "stiffness"]).is_none());
        let mut inc = IncidentSpec {
            amplitude: Some(1.0),
            ..Default::default()
        };
        inc.slot(&["xi"]).unwrap().set(0.5, "f", "k").unwrap();
        assert_eq!((inc.amplitude, inc.xi), (None, Some(0.5)));
        let mut s = SolverSpec::default();
        let e = s.slot(&["samples_per_period"]).unwrap().set(2.5, "f", "k");
        assert!(e.is_err());
    }
}

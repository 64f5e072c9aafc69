//! The extra solves of the analysis methods (model.md section 6.1): the response to the
//! phase-inverted burst (pulse inversion) and the response of the interface linearised at
//! its static state (linear reference, and the floor every run reports).

use crate::analysis::methods::{method_bands, method_floor, plateau, Quantity, Records, Signal};
use crate::analysis::{AnalysisMethod, BandAmplitudes};
use crate::error::{Error, Result};
use crate::excitation::Scaled;
use crate::law::compression::{Linear, Rigid};
use crate::law::tangential::{Coulomb, Linear as LinearTangential};
use crate::law::traction::{Bonded, Linear as LinearTraction};
use crate::law::{ContactLaw, TangentialBranch, TangentialLaw};
use crate::scenario::Scenario;
use crate::solver::half_space::HalfSpaceOutput;
use std::sync::Arc;

/// Harmonic amplitudes of the reflected velocity by the scenario's method, and its floor.
#[derive(Debug, Clone, Copy)]
pub struct Analysis {
    /// The method used.
    pub method: AnalysisMethod,
    /// Band amplitudes of the reflected velocity, m/s.
    pub bands: BandAmplitudes,
    /// The same analysis of the linearised interface's response, m/s (NaN where the
    /// interface has no linearisation: `K(p0) = 0`).
    pub floor: BandAmplitudes,
}

/// The contact law linearised at its static state: `sigma = -p0 + K(p0) [u]` on both sides
/// of `[u]_c` (no contact loss), or a bonded interface where `K(p0)` is infinite (rigid
/// compression). `None` when `K(p0)` is 0 or not a number (a power law at `p0 = 0`).
pub fn linearised_law(law: &ContactLaw) -> Option<ContactLaw> {
    let p0 = law.static_pressure;
    let k0 = law.compression.stiffness_at_rest();
    if linearises_locked(law) {
        Some(ContactLaw {
            static_pressure: p0,
            compression: Box::new(Rigid {
                static_pressure: p0,
            }),
            traction: Box::new(Bonded),
        })
    } else if k0.is_finite() && k0 > 0.0 {
        Some(ContactLaw {
            static_pressure: p0,
            compression: Box::new(Linear {
                static_pressure: p0,
                stiffness: k0,
            }),
            traction: Box::new(LinearTraction { stiffness: k0 }),
        })
    } else {
        None
    }
}

/// Whether the law linearises to a locked interface (rigid x bonded): its compression
/// branch is rigid or infinitely stiff at rest.
fn linearises_locked(law: &ContactLaw) -> bool {
    law.compression.is_rigid() || law.compression.stiffness_at_rest() == f64::INFINITY
}

/// A tangential law linearised at its static state (normal pressure `p0`, Pa; adhesion 1):
/// a slider that sticks at rest (`mu > 0`, `p0 > 0`) is its stick stiffness `k_t` in
/// parallel with the reversible spring `k(1)`, so a linear spring `k(1) + k_t`, or, where
/// `k_t` is infinite, a rigid stick with `mu = 1e12` (no wave slides it while the interface
/// is in contact); without a sticking slider, the
/// spring `k(1)` alone (0: free). The static shear `q0` is kept.
pub fn linearised_tangential(law: &TangentialLaw, p0: f64) -> TangentialLaw {
    let br = &*law.branch;
    let k = br.spring_stiffness(1.0);
    let sticking = br.friction() > 0.0 && p0 > 0.0;
    let branch: Box<dyn TangentialBranch> = match (sticking, br.stick_stiffness()) {
        (true, kt) if kt.is_infinite() => Box::new(Coulomb {
            // a limit `mu N` no wave reaches while the interface is in contact (finite:
            // the solvers' stick/slip tests stay in finite numbers)
            friction: 1e12,
            stick_stiffness: f64::INFINITY,
        }),
        (true, kt) => Box::new(LinearTangential { stiffness: k + kt }),
        (false, _) => Box::new(LinearTangential { stiffness: k }),
    };
    TangentialLaw {
        static_shear: law.static_shear,
        branch,
    }
}

/// The scenario with its interface linearised ([`linearised_law`]; a tangential part by
/// [`linearised_tangential`]).
pub fn linearised(scenario: &Scenario) -> Option<Scenario> {
    let law = linearised_law(&scenario.law)?;
    let mut s = scenario.clone();
    s.law = Arc::new(law);
    if let Some(sh) = &mut s.shear {
        let p0 = scenario.law.static_pressure;
        sh.tangential = Arc::new(linearised_tangential(&sh.tangential, p0));
    }
    Some(s)
}

/// The scenario with its burst phase-inverted.
pub fn inverted(scenario: &Scenario) -> Scenario {
    let mut s = scenario.clone();
    s.incident = Arc::new(Scaled::negated(scenario.incident.clone()));
    // at oblique incidence the wave's tangential traction is inverted with it
    if scenario.oblique.is_some()
        && let Some(sh) = &mut s.shear
    {
        sh.incident = Arc::new(Scaled::negated(sh.incident.clone()));
    }
    s
}

/// What the analysis needs to know about a scenario's signals on the grid of `out` (the
/// plateau is the whole burst unless the method is `plateau_fit`, the only one reading it).
pub fn signal(scenario: &Scenario, out: &HalfSpaceOutput) -> Signal {
    let inc = &scenario.incident;
    let f0 = inc.fundamental();
    Signal {
        quantity: Quantity::Displacement,
        dt: out.dt,
        t0: out.t.first().copied().unwrap_or(0.0),
        f0,
        f2: inc.second_frequency(),
        // only `plateau_fit` reads the plateau: the other methods skip its 64 samples per
        // period of the burst
        plateau: if scenario.spec.analysis.method == AnalysisMethod::PlateauFit {
            plateau(|t| inc.stress(t), inc.duration(), f0)
        } else {
            (0.0, inc.duration())
        },
    }
}

/// Analyse the reflected wave of `out` (the scenario's solution) by the scenario's method,
/// with the floor when `with_floor` (without it the floor is NaN and the linearised solve
/// is made only if the method needs it); `solve` runs the solver on the derived scenarios;
/// a locked interface's floor comes from `floors` where it is there.
pub fn analyse(
    scenario: &Scenario,
    out: &HalfSpaceOutput,
    mut solve: impl FnMut(&Scenario) -> Result<HalfSpaceOutput>,
    with_floor: bool,
    floors: &mut Floors,
) -> Result<Analysis> {
    analyse_keeping(
        scenario,
        out,
        |s| solve(s).map(|o| (o, ())),
        with_floor,
        floors,
    )
    .map(|(a, _)| a)
}

/// The derived solves of an analysis, kept with what the solver returned beside the normal
/// histories (at oblique incidence the tangential ones, to analyse each outgoing wave by the
/// same method).
#[derive(Debug, Clone)]
pub struct Derived<T> {
    /// The interface linearised at its static state ([`linearised`]), where it has one.
    pub linear: Option<(HalfSpaceOutput, T)>,
    /// The phase-inverted burst ([`inverted`]), for pulse inversion.
    pub inverse: Option<(HalfSpaceOutput, T)>,
}

/// [`analyse`], keeping the derived solves: `solve` returns the normal histories and `T`.
pub fn analyse_keeping<T>(
    scenario: &Scenario,
    out: &HalfSpaceOutput,
    mut solve: impl FnMut(&Scenario) -> Result<(HalfSpaceOutput, T)>,
    with_floor: bool,
    floors: &mut Floors,
) -> Result<(Analysis, Derived<T>)> {
    let method = scenario.spec.analysis.method;
    let sig = signal(scenario, out);
    // a locked interface's floor, once per burst shape (no linearised solve here)
    let locked = if with_floor {
        locked_floor(scenario, &sig, |s| solve(s).map(|o| o.0), floors).transpose()?
    } else {
        None
    };
    let need_linear = (with_floor && locked.is_none()) || method == AnalysisMethod::LinearReference;
    let linear = match linearised(scenario) {
        Some(s) if need_linear => Some(solve(&s)?),
        _ => None,
    };
    let inverse = match method {
        AnalysisMethod::PulseInversion => Some(solve(&inverted(scenario))?),
        _ => None,
    };
    if method == AnalysisMethod::LinearReference && linear.is_none() {
        return Err(Error::invalid(
            &scenario.file,
            "analysis.method",
            "linear_reference",
            "needs a compression stiffness K(p0) > 0 at the static pressure (a power law \
             at p0 = 0 has none); use pulse_inversion",
        ));
    }
    let lin = linear
        .as_ref()
        .map(|o| o.0.reflected_displacement.as_slice());
    let records = Records {
        response: &out.reflected_displacement,
        inverse: inverse
            .as_ref()
            .map(|o| o.0.reflected_displacement.as_slice()),
        linear: lin,
    };
    let bands = method_bands(method, &records, &sig)
        .ok_or_else(|| Error::numerical(0.0, "a record of the analysis is missing", ""))?;
    let floor = match (locked, lin) {
        (Some(f), _) => f,
        (None, Some(l)) if with_floor => method_floor(method, l, &sig),
        _ => {
            let nan = f64::NAN;
            BandAmplitudes {
                harmonic: [nan; 6],
                subharmonic: nan,
                f2: nan,
                sum: nan,
                difference: nan,
            }
        }
    };
    Ok((
        Analysis {
            method,
            bands,
            floor,
        },
        Derived { linear, inverse },
    ))
}

/// Most floors a [`Floors`] keeps ([`locked_floor`]).
const MAX_FLOORS: usize = 8;

/// What fixes the floor of a locked interface, apart from the amplitude: the burst's
/// shape ([`crate::excitation::UnitShape::key`]) and, as bits, `Z1`, `Z2`, the samples
/// per period, the tail, the analysis method and the signal's step, start and plateau.
type FloorKey = (Vec<u64>, [u64; 9]);

/// The analysis floors at unit incident peak of the locked interfaces a worker solved
/// last, oldest first (at most `MAX_FLOORS`, 8; `locked_floor`): a plan cache owned by
/// the caller with its other workspaces ([`crate::model::Workspace`]), never a result.
#[derive(Debug, Default, Clone)]
pub struct Floors(Vec<(FloorKey, BandAmplitudes)>);

impl Floors {
    /// Forget the kept floors: the next run solves its linearised interface again (what a
    /// first run does; for benchmarks of a cold run).
    pub fn clear(&mut self) {
        self.0.clear();
    }

    /// Whether no floor is kept.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The analysis floor of a scenario whose interface linearises to a locked one (rigid
/// compression: [`linearised_law`] is rigid x bonded), from the floor at unit incident peak,
/// computed once per burst shape and kept in `floors`, scaled by the peak. The locked interface's
/// response is linear in the burst and its record length does not depend on the amplitude,
/// so this is the floor of the scenario's own linearised solve (up to round-off), and the
/// same whichever point of a sweep computed it first. `None` where that does not hold or
/// the burst cannot give its shape (the caller then solves): `linear_reference` (which
/// reads the linear record itself), a tangential or oblique part, the FD solver, a
/// compliant compression branch, a file or two-tone burst.
fn locked_floor(
    scenario: &Scenario,
    sig: &Signal,
    solve: impl FnOnce(&Scenario) -> Result<HalfSpaceOutput>,
    floors: &mut Floors,
) -> Option<Result<BandAmplitudes>> {
    use crate::scenario::spec::Method;
    let method = scenario.spec.analysis.method;
    if !linearises_locked(&scenario.law)
        || method == AnalysisMethod::LinearReference
        || scenario.shear.is_some()
        || scenario.oblique.is_some()
        || scenario.spec.solver.method != Method::Exact
    {
        return None;
    }
    let shape = scenario.incident.unit_shape()?;
    let solver = &scenario.spec.solver;
    let tail = solver.tail_periods;
    let key: FloorKey = (
        shape.key,
        [
            scenario.medium.impedance().to_bits(),
            scenario
                .counterpart
                .map_or(f64::INFINITY, |m| m.impedance())
                .to_bits(),
            solver.samples_per_period() as u64,
            tail.map_or(u64::MAX, f64::to_bits),
            method.code().to_bits(),
            sig.dt.to_bits(),
            sig.t0.to_bits(),
            sig.plateau.0.to_bits(),
            sig.plateau.1.to_bits(),
        ],
    );
    let peak = scenario.incident.peak();
    let hit = floors.0.iter().find(|(k, _)| *k == key).map(|e| e.1);
    let unit = match hit {
        Some(u) => u,
        None => {
            let mut s = linearised(scenario)?;
            s.incident = shape.unit;
            let out = match solve(&s) {
                Ok(o) => o,
                Err(e) => return Some(Err(e)),
            };
            let u = method_floor(method, &out.reflected_displacement, sig);
            if floors.0.len() >= MAX_FLOORS {
                floors.0.remove(0);
            }
            floors.0.push((key, u));
            u
        }
    };
    Some(Ok(scaled(&unit, peak)))
}

/// Every amplitude of `b` times `factor`.
fn scaled(b: &BandAmplitudes, factor: f64) -> BandAmplitudes {
    BandAmplitudes {
        harmonic: b.harmonic.map(|a| a * factor),
        subharmonic: b.subharmonic * factor,
        f2: b.f2 * factor,
        sum: b.sum * factor,
        difference: b.difference * factor,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario(traction: &str, amplitude: f64) -> Scenario {
        let text = format!(
            "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
             traction = {traction}\n[incident]\nfrequency = 1e6\ncycles = 8\n\
             amplitude = {amplitude:e}\n[solver]\nsamples_per_period = 64\n"
        );
        Scenario::from_toml_str(&text, "floor.toml").unwrap()
    }

    /// The floor of the scenario's own linearised solve, without the cache.
    fn solved_floor(s: &Scenario) -> BandAmplitudes {
        let lin = linearised(s).unwrap();
        let out = super::super::simulate::solve(&lin).unwrap();
        let r = super::super::simulate::solve(s).unwrap();
        method_floor(
            s.spec.analysis.method,
            &out.reflected_displacement,
            &signal(s, &r),
        )
    }

    fn floor_of(s: &Scenario, floors: &mut Floors) -> BandAmplitudes {
        let out = super::super::simulate::solve(s).unwrap();
        analyse(s, &out, super::super::simulate::solve, true, floors)
            .unwrap()
            .floor
    }

    /// A locked interface's floor from the cache at unit peak is the floor of its own
    /// linearised solve, at every amplitude, to round-off.
    #[test]
    fn cached_locked_floor_is_the_linearised_solve_floor() {
        let mut floors = Floors::default();
        for amplitude in [0.82e6, 2.5e4, 3.3e6] {
            let s = scenario(
                "{ law = \"rccm\", stiffness = 2e13, energy = 0.1 }",
                amplitude,
            );
            let (cached, solved) = (floor_of(&s, &mut floors), solved_floor(&s));
            for n in 1..=5 {
                let (a, b) = (cached.harmonic[n], solved.harmonic[n]);
                assert!(
                    b > 0.0 && (a - b).abs() <= 1e-11 * b,
                    "A{n}: {a:e} vs {b:e}"
                );
            }
            let (a, b) = (cached.subharmonic, solved.subharmonic);
            assert!((a - b).abs() <= 1e-11 * b, "A_sub: {a:e} vs {b:e}");
        }
    }

    /// The floor does not depend on which point of a sweep filled the cache: two
    /// amplitudes in either order give the same bits.
    #[test]
    fn cached_floor_does_not_depend_on_the_order_of_the_runs() {
        let free = "{ law = \"free\" }";
        let (a, b) = (scenario(free, 1e4), scenario(free, 7.7e4));
        let mut floors = Floors::default();
        let (fa, fb) = (floor_of(&a, &mut floors), floor_of(&b, &mut floors));
        floors.clear();
        let (gb, ga) = (floor_of(&b, &mut floors), floor_of(&a, &mut floors));
        assert_eq!(fa, ga);
        assert_eq!(fb, gb);
        // a second burst shape is a second entry, not a wrong hit
        let other = Scenario::from_toml_str(
            "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
             [incident]\nfrequency = 1e6\ncycles = 5\namplitude = 1e4\n\
             [solver]\nsamples_per_period = 64\n",
            "floor.toml",
        )
        .unwrap();
        let fo = floor_of(&other, &mut floors);
        assert_ne!(fo.harmonic[2], fa.harmonic[2]);
        let so = solved_floor(&other);
        assert!((fo.harmonic[2] - so.harmonic[2]).abs() <= 1e-11 * so.harmonic[2]);
    }
}

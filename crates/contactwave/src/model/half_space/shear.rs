//! Runs with a tangential degree of freedom (model.md section 13): the scenario's coupled
//! problem on the exact 2-DOF solver (or, with `solver.method = "fd"`, the FD scheme with
//! a shear field, model.md section 9.6), the harmonics of the reflected and transmitted shear
//! waves by the scenario's analysis method, friction dissipation and slip.

use super::methods;
use crate::analysis::methods::{method_bands, plateau, Quantity, Records, Signal};
use crate::analysis::{set_shear_harmonics, AnalysisMethod, BandAmplitudes, Summary};
use crate::error::{Error, Result};
use crate::excitation::Scaled;
use crate::scenario::spec::Method;
use crate::scenario::{Scenario, ShearSetup};
use crate::solver::coupled::{CoupledHalfSpace, CoupledOutput, CoupledSolver};
use crate::solver::half_space::{HalfSpace, HalfSpaceOutput, HalfSpaceSettings};
use crate::solver::half_space_fd_shear::FdCoupledSolver;
use crate::solver::Solver;
use std::sync::Arc;

/// The tangential results of a run.
#[derive(Debug, Clone, Default)]
pub struct ShearResult {
    /// Interface histories of the shear component: `gap` is `[u]_T` (m), `contact_stress`
    /// the shear stress tau (Pa), incident/reflected/transmitted shear stresses (Pa) and
    /// particle displacements (m).
    pub interface: HalfSpaceOutput,
    /// Accumulated slip s, m.
    pub slip: Vec<f64>,
    /// Friction limit `mu N`, Pa.
    pub friction_limit: Vec<f64>,
    /// Slider state: 0 stick, +1/-1 slipping in that direction, NaN free.
    pub slip_state: Vec<f64>,
    /// Incident shear velocity amplitude `A_inc,T = max|tau_inc| / Z1T`, m/s.
    pub a_inc: f64,
    /// Band amplitudes of the reflected shear velocity by the scenario's analysis method
    /// (zero until [`analyse`]), m/s.
    pub reflected_bands: BandAmplitudes,
    /// Band amplitudes of the transmitted shear velocity by the scenario's analysis method
    /// (zero for a rigid wall, and until [`analyse`]), m/s.
    pub transmitted_bands: BandAmplitudes,
    /// Energy dissipated by friction, J/m^2.
    pub friction_dissipation: f64,
    /// Relative closure error of the coupled energy audit.
    pub closure_error: f64,
    /// Time slipping while a burst was at the interface, s.
    pub slip_time_in_burst: f64,
    /// Stick/slip switches.
    pub slip_events: usize,
    /// At oblique incidence, the energies of the reflected P, SV and transmitted P, SV
    /// waves, J/m^2 (zero at normal incidence).
    pub wave_energy: [f64; 4],
}

/// The coupled problem of a scenario with a tangential part.
pub fn coupled_problem(scenario: &Scenario, shear: &ShearSetup) -> CoupledHalfSpace {
    CoupledHalfSpace {
        normal: HalfSpace::new(
            scenario.medium,
            scenario.counterpart,
            scenario.law.clone(),
            scenario.incident.clone(),
        ),
        z1t: shear.z1t,
        z2t: shear.z2t,
        tangential: shear.tangential.clone(),
        shear_incident: shear.incident.clone(),
        oblique: scenario
            .oblique
            .as_ref()
            .map(|o| crate::solver::coupled::ObliqueCoupling::new(&o.geometry)),
    }
}

/// Solve a scenario with a tangential part: the normal histories and the shear results.
pub fn solve(scenario: &Scenario, shear: &ShearSetup) -> Result<(HalfSpaceOutput, ShearResult)> {
    let problem = coupled_problem(scenario, shear);
    let sp = &scenario.spec.solver;
    let out: CoupledOutput = match sp.method {
        Method::Exact => CoupledSolver {
            settings: HalfSpaceSettings {
                samples_per_period: sp.samples_per_period(),
                tail_periods: sp.tail_periods,
                summary_only: false,
            },
        }
        .solve(&problem)?,
        Method::Fd => FdCoupledSolver {
            samples_per_period: sp.samples_per_period(),
            tail_periods: sp.tail_periods,
            interface_scheme: sp.interface_update.into(),
        }
        .solve(&problem)?,
    };
    let closure_error = out.closure_error();
    let result = ShearResult {
        a_inc: shear.incident.peak() / shear.z1t,
        // filled by `analyse`, by the scenario's analysis method
        reflected_bands: BandAmplitudes::default(),
        transmitted_bands: BandAmplitudes::default(),
        friction_dissipation: out.friction_dissipation,
        closure_error,
        slip_time_in_burst: out.slip_time_in_burst,
        slip_events: out.slip_events,
        wave_energy: out.wave_energy,
        slip: out.slip,
        friction_limit: out.friction_limit,
        slip_state: out.slip_state,
        interface: out.shear,
    };
    Ok((out.normal, result))
}

/// The scenario with its shear burst phase-inverted (the normal burst kept): the second
/// record of pulse inversion for the shear wave at normal incidence.
fn shear_inverted(scenario: &Scenario) -> Scenario {
    let mut s = scenario.clone();
    if let Some(sh) = &mut s.shear {
        sh.incident = Arc::new(Scaled::negated(sh.incident.clone()));
    }
    s
}

/// The derived solves the scenario's analysis method needs for the shear wave at normal
/// incidence, `(inverse, linear)`: the response to the phase-inverted shear burst (pulse
/// inversion) and the response of the interface linearised at its static state (linear
/// reference; [`methods::linearised`], or only the tangential law linearised where the
/// normal one has no linearisation). None for a run without a shear wave.
pub fn derived_solves(
    scenario: &Scenario,
    shear: &ShearSetup,
) -> Result<(Option<ShearResult>, Option<ShearResult>)> {
    if shear.incident.peak() <= 0.0 {
        return Ok((None, None));
    }
    let solved = |s: Scenario| -> Result<ShearResult> {
        let sh = s.shear.as_ref().unwrap_or(shear);
        Ok(solve(&s, sh)?.1)
    };
    let inverse = match scenario.spec.analysis.method {
        AnalysisMethod::PulseInversion => Some(solved(shear_inverted(scenario))?),
        _ => None,
    };
    let linear = match scenario.spec.analysis.method {
        AnalysisMethod::LinearReference => {
            let s = methods::linearised(scenario).unwrap_or_else(|| {
                let mut s = scenario.clone();
                let p0 = scenario.law.static_pressure;
                if let Some(sh) = &mut s.shear {
                    sh.tangential = Arc::new(methods::linearised_tangential(&sh.tangential, p0));
                }
                s
            });
            Some(solved(s)?)
        }
        _ => None,
    };
    Ok((inverse, linear))
}

/// Fill the band amplitudes of the reflected and transmitted shear velocities of `r` by the
/// scenario's analysis method (model.md section 6.1), from the derived solves' tangential
/// results `inverse` (pulse inversion) and `linear` (linear reference). A run without a
/// shear wave is analysed by band peak (its ratios are 0: no incident amplitude).
pub fn analyse(
    scenario: &Scenario,
    shear: &ShearSetup,
    r: &mut ShearResult,
    inverse: Option<&ShearResult>,
    linear: Option<&ShearResult>,
) -> Result<()> {
    let inc = &shear.incident;
    let f0 = inc.fundamental();
    let method = if inc.peak() > 0.0 {
        scenario.spec.analysis.method
    } else {
        AnalysisMethod::BandPeak
    };
    let o = &r.interface;
    let sig = Signal {
        quantity: Quantity::Displacement,
        dt: o.dt,
        t0: o.t.first().copied().unwrap_or(0.0),
        f0,
        f2: None,
        plateau: if method == AnalysisMethod::PlateauFit {
            plateau(|t| inc.stress(t), inc.duration(), f0)
        } else {
            (0.0, inc.duration())
        },
    };
    let bands = |record: fn(&HalfSpaceOutput) -> &[f64]| {
        let records = Records {
            response: record(o),
            inverse: inverse.map(|d| record(&d.interface)),
            linear: linear.map(|d| record(&d.interface)),
        };
        method_bands(method, &records, &sig).ok_or_else(|| {
            Error::numerical(0.0, "a record of the shear wave's analysis is missing", "")
        })
    };
    r.reflected_bands = bands(|o| &o.reflected_displacement)?;
    if shear.z2t.is_finite() {
        r.transmitted_bands = bands(|o| &o.transmitted_displacement)?;
    }
    Ok(())
}

fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        a / b
    } else {
        0.0
    }
}

/// The shear keys of a run's summary (docs/scenario.md, outputs).
pub fn set_summary(s: &mut Summary, scenario: &Scenario, shear: &ShearSetup, r: &ShearResult) {
    let p0 = scenario.law.static_pressure;
    let mu = shear.tangential.branch.friction();
    let amp = shear.incident.peak();
    s.set("shear_amplitude", amp);
    s.set("static_shear", shear.tangential.static_shear);
    s.set("friction_coefficient", mu);
    s.set("friction_ratio", ratio(mu * p0, amp));
    s.set("shear_frequency", shear.incident.fundamental());
    s.set("shear_A_inc", r.a_inc);
    set_shear_harmonics(s, "shear_", &r.reflected_bands, r.a_inc);
    if shear.z2t.is_finite() {
        set_shear_harmonics(s, "shear_tr_", &r.transmitted_bands, r.a_inc);
    }
    let e = &r.interface.energy;
    let total = e.incident + s.get("energy_incident").unwrap_or(0.0);
    s.set("shear_energy_incident", e.incident);
    s.set("shear_energy_reflected", e.reflected);
    s.set("shear_energy_transmitted", e.transmitted);
    s.set("friction_dissipation", r.friction_dissipation);
    s.set(
        "friction_dissipation_fraction",
        ratio(r.friction_dissipation, total),
    );
    let delay = scenario
        .spec
        .shear_incident
        .as_ref()
        .and_then(|i| i.delay)
        .unwrap_or(0.0);
    let cycles = (shear.incident.duration() - delay) * shear.incident.fundamental();
    s.set(
        "friction_dissipation_per_cycle",
        ratio(r.friction_dissipation, cycles),
    );
    s.set(
        "slip_fraction",
        ratio(r.slip_time_in_burst, r.interface.burst_duration),
    );
    s.set("slip_events", r.slip_events as f64);
    s.set("final_slip", r.slip.last().copied().unwrap_or(0.0));
    s.set(
        "max_slip",
        r.slip.iter().fold(0.0f64, |m, v| m.max(v.abs())),
    );
    s.set("energy_closure_error", r.closure_error);
}

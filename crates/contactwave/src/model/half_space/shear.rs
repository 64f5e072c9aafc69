//! Runs with a tangential degree of freedom (model.md section 13): the scenario's coupled
//! problem on the exact 2-DOF solver (or, with `solver.method = "fd"`, the FD scheme with
//! a shear field, model.md section 9.6), the harmonics of the reflected and transmitted shear
//! waves, friction dissipation and slip.

use crate::analysis::{set_shear_harmonics, velocity_bands, BandAmplitudes, Summary};
use crate::error::Result;
use crate::scenario::spec::Method;
use crate::scenario::{Scenario, ShearSetup};
use crate::solver::coupled::{CoupledHalfSpace, CoupledOutput, CoupledSolver};
use crate::solver::halfspace::{HalfSpace, HalfSpaceOutput, HalfSpaceSettings};
use crate::solver::halfspace_fd_shear::FdCoupledSolver;
use crate::solver::Solver;

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
    /// Band amplitudes of the reflected shear velocity, m/s.
    pub reflected_bands: BandAmplitudes,
    /// Band amplitudes of the transmitted shear velocity (zero for a rigid wall), m/s.
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
    let f0 = shear.incident.fundamental();
    let sh = &out.shear;
    let reflected_bands = velocity_bands(&sh.reflected_displacement, sh.dt, f0, None);
    let transmitted_bands = if shear.z2t.is_finite() {
        velocity_bands(&sh.transmitted_displacement, sh.dt, f0, None)
    } else {
        BandAmplitudes::default()
    };
    let closure_error = out.closure_error();
    let result = ShearResult {
        a_inc: shear.incident.peak() / shear.z1t,
        reflected_bands,
        transmitted_bands,
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

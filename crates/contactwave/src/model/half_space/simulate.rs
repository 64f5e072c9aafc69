//! One simulation of a half-space scenario: solve, record the probe, analyse, summarise.

use super::methods::{self, Analysis};
use crate::analysis::{
    cell_velocity, set_analysis_keys, set_reflected_harmonics, velocity_bands, with_analyzer,
    BandAmplitudes, Spectrum, Summary,
};
use crate::error::Result;
use crate::model::Workspace;
use crate::scenario::spec::Method;
use crate::scenario::Scenario;
use crate::solver::half_space::{
    ExactSolver, HalfSpace, HalfSpaceOutput, HalfSpaceSettings, Workspace as SolverWorkspace,
};
use crate::solver::half_space_fd::FdSolver;
use crate::solver::Solver;

/// Signals at the probe x < 0 (pure delays of the interface signals; model.md section 4).
#[derive(Debug, Clone, Default)]
pub struct ProbeSeries {
    /// Probe position, m.
    pub x: f64,
    /// Probe times, s (same origin as the interface times: the incident front reaches the
    /// probe at `t = x / c1 < 0`).
    pub t: Vec<f64>,
    /// Incident stress at the probe, Pa.
    pub incident_stress: Vec<f64>,
    /// Reflected stress at the probe, Pa.
    pub reflected_stress: Vec<f64>,
    /// Incident particle velocity, m/s (`-s_inc / Z1`).
    pub incident_velocity: Vec<f64>,
    /// Reflected particle velocity, m/s (`s_ref / Z1`).
    pub reflected_velocity: Vec<f64>,
    /// Total particle displacement at the probe, m.
    pub displacement: Vec<f64>,
    /// Start and end of the incident gate, s.
    pub incident_gate: (f64, f64),
    /// Start and end of the reflected gate, s.
    pub reflected_gate: (f64, f64),
}

/// Everything one run produces.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// File of the scenario.
    pub file: String,
    /// Fundamental frequency f0 of the incident wave, Hz.
    pub fundamental: f64,
    /// Whether the incident wave is a two-tone burst.
    pub two_tone: bool,
    /// Incident particle-velocity amplitude `A_inc`, m/s (at oblique incidence the
    /// incident wave's, along its polarisation).
    pub a_inc: f64,
    /// Interface histories (x = 0).
    pub interface: HalfSpaceOutput,
    /// Probe histories.
    pub probe: ProbeSeries,
    /// Amplitude spectrum of the incident particle velocity.
    pub incident_spectrum: Spectrum,
    /// Amplitude spectrum of the reflected particle velocity.
    pub reflected_spectrum: Spectrum,
    /// Band amplitudes of the incident velocity (at oblique incidence the incident wave's
    /// particle velocity along its polarisation), m/s.
    pub incident_bands: BandAmplitudes,
    /// Band amplitudes of the reflected velocity by the scenario's analysis method (at
    /// oblique incidence its normal component at the interface), m/s.
    pub reflected_bands: BandAmplitudes,
    /// The analysis floor of each component (the method on the linear response), m/s.
    pub floor_bands: BandAmplitudes,
    /// The analysis method of the harmonic amplitudes.
    pub method: crate::analysis::AnalysisMethod,
    /// Scalars of `summary.json`.
    pub summary: Summary,
    /// The tangential results, for scenarios with a tangential part (model.md section 13).
    pub shear: Option<super::shear::ShearResult>,
    /// The wave speeds (m/s) and impedances (Pa s/m) used ([`Scenario::wave_table`]),
    /// written to `summary.json` after the summary keys (not sweep columns).
    pub waves: Vec<(String, f64)>,
}

/// The half-space problem of a scenario.
pub fn half_space(scenario: &Scenario) -> HalfSpace {
    HalfSpace::new(
        scenario.medium,
        scenario.counterpart,
        scenario.law.clone(),
        scenario.incident.clone(),
    )
}

/// Interface histories by the scenario's method (`exact` or `fd`), on a new workspace
/// (the tests' reference solves).
#[cfg(test)]
pub fn solve(scenario: &Scenario) -> Result<HalfSpaceOutput> {
    solve_with(scenario, false, &mut SolverWorkspace::new())
}

/// The scenario's problem on the FD scheme.
fn solve_fd(scenario: &Scenario, problem: &HalfSpace) -> Result<HalfSpaceOutput> {
    FdSolver {
        samples_per_period: scenario.spec.solver.samples_per_period(),
        tail_periods: scenario.spec.solver.tail_periods,
        interface_scheme: scenario.spec.solver.interface_update.into(),
    }
    .solve(problem)
}

/// Solver settings of a scenario.
pub fn settings(scenario: &Scenario) -> HalfSpaceSettings {
    HalfSpaceSettings {
        samples_per_period: scenario.spec.solver.samples_per_period(),
        tail_periods: scenario.spec.solver.tail_periods,
        summary_only: false,
    }
}

/// Run a scenario only through the solver and the harmonic analysis (what sweeps need):
/// no probe series and no spectra.
/// The summary has the keys of [`simulate`]'s except the incident burst's own ratios
/// (`incident_A*_over_Ainc`).
pub fn simulate_summary(scenario: &Scenario) -> Result<Summary> {
    simulate_summary_in(scenario, &mut Workspace::new())
}

/// [`simulate_summary`] on the caller's workspace `ws` (one per worker: the incident table
/// and the locked interfaces' floors of its last runs are used again; the same summary).
pub fn simulate_summary_in(scenario: &Scenario, ws: &mut Workspace) -> Result<Summary> {
    simulate_summary_with(scenario, true, ws)
}

/// [`simulate_summary`], with the analysis floor (`A*_floor_over_Ainc`,
/// `harmonic_floor_warning`) only when `with_floor`: without it those keys are NaN or 0 and
/// the linearised solve that gives them is skipped (an identification that observes no
/// floor key saves a third of each forward run). Every other key is the same.
/// On the caller's workspace `ws`.
pub fn simulate_summary_with(
    scenario: &Scenario,
    with_floor: bool,
    ws: &mut Workspace,
) -> Result<Summary> {
    if let Some(sh) = &scenario.shear {
        let (out, mut shear) = super::shear::solve(scenario, sh)?;
        if let Some(o) = &scenario.oblique {
            let (analysis, derived) = analyse_oblique(scenario, &out, with_floor, ws)?;
            analyse_shear_oblique(scenario, sh, &mut shear, &derived)?;
            let mut s = summarise(scenario, &out, None, &analysis);
            super::shear::set_summary(&mut s, scenario, sh, &shear);
            super::oblique::set_summary(&mut s, scenario, o, (&out, &shear), &derived);
            return Ok(s);
        }
        let analysis = analyse(scenario, &out, with_floor, ws)?;
        analyse_shear(scenario, sh, &mut shear)?;
        let mut s = summarise(scenario, &out, None, &analysis);
        super::shear::set_summary(&mut s, scenario, sh, &shear);
        return Ok(s);
    }
    let out = solve_with(scenario, true, &mut ws.solver)?;
    let analysis = analyse(scenario, &out, with_floor, ws)?;
    Ok(summarise(scenario, &out, None, &analysis))
}

/// The normal histories of a scenario (through the coupled solver when it has a
/// tangential part), recording only what the analysis reads.
fn solve_normal(scenario: &Scenario, ws: &mut SolverWorkspace) -> Result<HalfSpaceOutput> {
    match &scenario.shear {
        Some(sh) => Ok(super::shear::solve(scenario, sh)?.0),
        None => solve_with(scenario, true, ws),
    }
}

/// Interface histories by the scenario's method on the solver's workspace `ws`; with
/// `summary_only` the exact solver records only what [`simulate_summary`] reads (`t`,
/// `beta`, `reflected_displacement`).
fn solve_with(
    scenario: &Scenario,
    summary_only: bool,
    ws: &mut SolverWorkspace,
) -> Result<HalfSpaceOutput> {
    let problem = half_space(scenario);
    match scenario.spec.solver.method {
        Method::Exact => {
            let plan = ExactSolver {
                settings: HalfSpaceSettings {
                    summary_only,
                    ..settings(scenario)
                },
            }
            .plan(&problem)?;
            let mut out = plan.recorder();
            plan.run(ws, &mut out)?;
            Ok(out)
        }
        Method::Fd => solve_fd(scenario, &problem),
    }
}

/// The reflected longitudinal wave analysed by the scenario's method (nothing to analyse
/// when the scenario has only a shear wave).
fn analyse(
    scenario: &Scenario,
    out: &HalfSpaceOutput,
    with_floor: bool,
    ws: &mut Workspace,
) -> Result<methods::Analysis> {
    if scenario.incident.peak() > 0.0 {
        let Workspace { solver, floors } = ws;
        methods::analyse(
            scenario,
            out,
            |s| solve_normal(s, solver),
            with_floor,
            floors,
        )
    } else {
        Ok(methods::Analysis {
            method: scenario.spec.analysis.method,
            bands: BandAmplitudes::default(),
            floor: BandAmplitudes::default(),
        })
    }
}

/// At oblique incidence: the reflected normal wave analysed by the scenario's method, and
/// the derived solves with their tangential histories, to analyse each outgoing P and SV
/// wave by the same method (model.md section 14.3). The derived solves run even for an SV
/// wave at 0 degrees (no normal traction), where the waves need them.
fn analyse_oblique(
    scenario: &Scenario,
    out: &HalfSpaceOutput,
    with_floor: bool,
    ws: &mut Workspace,
) -> Result<(
    methods::Analysis,
    methods::Derived<super::shear::ShearResult>,
)> {
    methods::analyse_keeping(
        scenario,
        out,
        |s| match &s.shear {
            Some(sh) => super::shear::solve(s, sh),
            None => Err(crate::error::Error::numerical(
                0.0,
                "an oblique scenario without its tangential part",
                "",
            )),
        },
        with_floor,
        &mut ws.floors,
    )
}

/// The shear wave's harmonics at normal incidence by the scenario's method, with the
/// derived solves it needs ([`super::shear::derived_solves`]).
fn analyse_shear(
    scenario: &Scenario,
    sh: &crate::scenario::ShearSetup,
    shear: &mut super::shear::ShearResult,
) -> Result<()> {
    let (inverse, linear) = super::shear::derived_solves(scenario, sh)?;
    super::shear::analyse(scenario, sh, shear, inverse.as_ref(), linear.as_ref())
}

/// The tangential traction's harmonics at oblique incidence by the scenario's method, from
/// the derived solves of the wave ([`analyse_oblique`]: the whole wave inverted, the whole
/// interface linearised).
fn analyse_shear_oblique(
    scenario: &Scenario,
    sh: &crate::scenario::ShearSetup,
    shear: &mut super::shear::ShearResult,
    derived: &methods::Derived<super::shear::ShearResult>,
) -> Result<()> {
    super::shear::analyse(
        scenario,
        sh,
        shear,
        derived.inverse.as_ref().map(|d| &d.1),
        derived.linear.as_ref().map(|d| &d.1),
    )
}

fn bands(scenario: &Scenario, displacement: &[f64], dt: f64) -> BandAmplitudes {
    let f0 = scenario.incident.fundamental();
    let f2 = scenario.incident.second_frequency();
    velocity_bands(displacement, dt, f0, f2)
}

/// Run a scenario: solve, probe, spectra, summary.
///
/// ```
/// use contactwave::{scenario::Scenario, simulate};
/// let s = Scenario::from_toml_str(r#"
///     [medium]
///     material = "pmma"
///     [interface]
///     static_pressure = 0.1e6
///     [incident]
///     frequency = 1e6
///     cycles = 10
///     xi = 0.35
/// "#, "example.toml").unwrap();
/// let r = simulate(&s).unwrap();
/// // unilateral contact clapping at xi = 0.35 gives a strong second harmonic
/// assert!(r.summary.get("A2_over_Ainc").unwrap() > 0.05);
/// ```
pub fn simulate(scenario: &Scenario) -> Result<RunResult> {
    simulate_in(scenario, &mut Workspace::new())
}

/// [`simulate`] on the caller's workspace `ws` (one per worker: the incident table and the
/// locked interfaces' floors of its last runs are used again; the same result).
pub fn simulate_in(scenario: &Scenario, ws: &mut Workspace) -> Result<RunResult> {
    let (out, mut shear) = match &scenario.shear {
        Some(sh) => {
            let (out, r) = super::shear::solve(scenario, sh)?;
            (out, Some(r))
        }
        None => (solve_with(scenario, false, &mut ws.solver)?, None),
    };
    // at oblique incidence the incident wave's own bands (along its polarisation)
    let inc = match (&scenario.oblique, &shear) {
        (Some(o), Some(r)) => super::oblique::incident_wave_bands(o, &out, &r.interface),
        _ => bands(scenario, &out.incident_displacement, out.dt),
    };
    let (analysis, derived) = match (&scenario.oblique, &scenario.shear, &mut shear) {
        (Some(_), Some(sh), Some(r)) => {
            let (a, d) = analyse_oblique(scenario, &out, true, ws)?;
            analyse_shear_oblique(scenario, sh, r, &d)?;
            (a, Some(d))
        }
        (_, Some(sh), Some(r)) => {
            analyse_shear(scenario, sh, r)?;
            (analyse(scenario, &out, true, ws)?, None)
        }
        _ => (analyse(scenario, &out, true, ws)?, None),
    };
    let mut summary = summarise(scenario, &out, Some(&inc), &analysis);
    if let (Some(sh), Some(r)) = (&scenario.shear, &shear) {
        super::shear::set_summary(&mut summary, scenario, sh, r);
        if let (Some(o), Some(d)) = (&scenario.oblique, &derived) {
            super::oblique::set_summary(&mut summary, scenario, o, (&out, r), d);
            super::oblique::set_incident(&mut summary, o, &inc);
        }
    }
    let f_max = 6.0 * scenario.incident.highest_frequency();
    let vr = cell_velocity(&out.reflected_displacement, out.dt);
    let vi = cell_velocity(&out.incident_displacement, out.dt);
    let (incident_spectrum, reflected_spectrum) = with_analyzer(|a| {
        (
            a.spectrum(&vi, out.dt, f_max),
            a.spectrum(&vr, out.dt, f_max),
        )
    });
    let probe = probe(scenario, &out);
    Ok(RunResult {
        file: scenario.file.clone(),
        fundamental: scenario.incident.fundamental(),
        two_tone: scenario.incident.second_frequency().is_some(),
        a_inc: match &scenario.oblique {
            Some(o) => o.burst.peak() / o.geometry.incident.impedance,
            None => scenario.incident.peak() / scenario.medium.impedance(),
        },
        interface: out,
        probe,
        incident_spectrum,
        reflected_spectrum,
        incident_bands: inc,
        reflected_bands: analysis.bands,
        floor_bands: analysis.floor,
        method: analysis.method,
        summary,
        shear,
        waves: scenario.wave_table(),
    })
}

/// Probe series: the reflected wave is the interface's delayed by |x|/c1 (exact on the
/// probe grid), the incident wave is evaluated at the matching times.
///
/// Between the incident wave's passage (it ends at probe time `w - |x|/c1`, `w` the
/// incident duration) and the reflected wave's arrival (`|x|/c1`) both waves are zero; a
/// probe far enough for that silence to last longer than the burst (`|x|/c1 > w`) keeps
/// only half a burst of it after the incident wave and half a burst before the reflected
/// one: the rows in between are left out (a jump in `t`), so that a probe metres away
/// records its two waves, not millions of zeros.
fn probe(scenario: &Scenario, out: &HalfSpaceOutput) -> ProbeSeries {
    let x = scenario.probe_x;
    let c1 = scenario.medium.wave_speed();
    let z1 = scenario.medium.impedance();
    let delay = x.abs() / c1;
    let dt = out.dt;
    let m = (2.0 * delay / dt).ceil() as usize;
    let n = out.t.len();
    let mut p = ProbeSeries {
        x,
        incident_gate: (-delay, out.burst_duration - delay),
        reflected_gate: (delay, out.t.last().copied().unwrap_or(0.0) + delay),
        ..Default::default()
    };
    let inc = &scenario.incident;
    // the burst: the longer of the incident wave and the shear wave (a shear run's
    // compressional incident wave is silent)
    let w = scenario
        .shear
        .as_ref()
        .map_or(0.0, |sh| sh.incident.duration())
        .max(inc.duration());
    // probe times left out: (start, end) of the silence beyond half a burst at each side
    let silent = (delay > w).then_some((w - delay + 0.5 * w, delay - 0.5 * w));
    let mut disp_inc = 0.0;
    let mut prev_t = None;
    for k in 0..(m + n) {
        let kk = k as isize - m as isize;
        let t = kk as f64 * dt + delay; // probe time
        let t_inc = t + delay; // incident argument
        if silent.is_some_and(|(a, b)| t > a && t < b) {
            // both waves are zero here: the incident displacement stays as it is
            continue;
        }
        let s_inc = inc.stress(t_inc);
        let (s_ref, d_ref) = if kk >= 0 {
            let i = kk as usize;
            (out.reflected_stress[i], out.reflected_displacement[i])
        } else {
            (0.0, 0.0)
        };
        if let Some(tp) = prev_t {
            disp_inc -= crate::numeric::gauss4(tp, t_inc, |s| inc.stress(s)) / z1;
        }
        prev_t = Some(t_inc);
        p.t.push(t);
        p.incident_stress.push(s_inc);
        p.reflected_stress.push(s_ref);
        p.incident_velocity.push(-s_inc / z1);
        p.reflected_velocity.push(s_ref / z1);
        p.displacement.push(disp_inc + d_ref);
    }
    p
}

fn summarise(
    scenario: &Scenario,
    out: &HalfSpaceOutput,
    inc: Option<&BandAmplitudes>,
    analysis: &Analysis,
) -> Summary {
    let refl = &analysis.bands;
    let z1 = scenario.medium.impedance();
    let a_inc = scenario.incident.peak() / z1;
    let mut s = Summary::new();
    s.set("xi", scenario.xi);
    s.set("amplitude", scenario.incident.peak());
    s.set("static_pressure", scenario.law.static_pressure);
    s.set("frequency", scenario.incident.fundamental());
    s.set("A_inc", a_inc);
    let two_tone = scenario.incident.second_frequency().is_some();
    if a_inc > 0.0 {
        set_reflected_harmonics(&mut s, refl, a_inc, two_tone, inc);
    }
    s.set("beta_end", out.beta.last().copied().unwrap_or(1.0));
    s.set("max_gap", out.max_gap);
    s.set(
        "contact_loss_fraction",
        out.open_time_in_burst / out.burst_duration.max(f64::MIN_POSITIVE),
    );
    let e = &out.energy;
    s.set("energy_closure_error", e.closure_error());
    s.set("energy_incident", e.incident);
    s.set("energy_reflected", e.reflected);
    s.set("energy_transmitted", e.transmitted);
    s.set("energy_stored_end", e.stored);
    s.set("energy_damage", e.damage);
    s.set("adhesion_energy_decrease", e.adhesion_decrease);
    s.set("events", out.events as f64);
    s.set("duration_simulated", out.t.last().copied().unwrap_or(0.0));
    if a_inc > 0.0 {
        set_analysis_keys(&mut s, analysis.method, refl, &analysis.floor, a_inc);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sweep on one workspace (its incident table and locked floor kept from point to
    /// point, in either order) gives every point's summary bit for bit as a cold run.
    #[test]
    fn a_used_workspace_gives_the_summary_of_a_new_one() {
        let scenario = |xi: f64, traction: &str| {
            let text = format!(
                "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
                 traction = {traction}\n[incident]\nfrequency = 1e6\ncycles = 6\nxi = {xi}\n\
                 [solver]\nsamples_per_period = 64\n"
            );
            Scenario::from_toml_str(&text, "ws.toml").unwrap()
        };
        let points: Vec<Scenario> = [0.3, 0.9, 0.3, 1.4]
            .iter()
            .flat_map(|&xi| {
                [
                    scenario(xi, "{ law = \"free\" }"),
                    scenario(xi, "{ law = \"rccm\", stiffness = 2e13, energy = 0.1 }"),
                ]
            })
            .collect();
        let bits = |s: &Summary| -> Vec<(String, u64)> {
            s.iter()
                .map(|(k, v)| (k.to_string(), v.to_bits()))
                .collect()
        };
        let mut ws = Workspace::new();
        for order in [false, true] {
            for i in 0..points.len() {
                let p = &points[if order { points.len() - 1 - i } else { i }];
                let warm = simulate_summary_in(p, &mut ws).unwrap();
                let cold = simulate_summary(p).unwrap();
                assert_eq!(bits(&warm), bits(&cold), "point {i}, reversed {order}");
            }
        }
        // (the floor and the table were there to be used)
        assert!(!ws.floors.is_empty());
    }

    fn run_at(x: f64) -> RunResult {
        let text = format!(
            "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
             [incident]\nfrequency = 1e6\ncycles = 5\namplitude = 0.82e6\n\
             [probe]\nx = {x}\n[solver]\nsamples_per_period = 64\n"
        );
        simulate(&Scenario::from_toml_str(&text, "probe.toml").unwrap()).unwrap()
    }

    /// A probe 3 m away (a silence of 2.2 ms between its two waves, 40 times the 5 us
    /// burst) records the same incident and reflected waves as one 3 mm away, and the
    /// same final displacement, in about as many rows: not 2 |x| / c1 of zeros.
    #[test]
    fn a_far_probe_records_its_two_waves_not_the_silence_between() {
        let (near, far) = (run_at(-0.003), run_at(-3.0));
        let nonzero = |v: &[f64]| v.iter().copied().filter(|s| *s != 0.0).collect::<Vec<_>>();
        let (pn, pf) = (&near.probe, &far.probe);
        // the incident wave on two grids offset by a fraction of a step: same energy
        let energy = |v: &[f64]| v.iter().map(|s| s * s).sum::<f64>();
        let (en, ef) = (energy(&pn.incident_stress), energy(&pf.incident_stress));
        assert!((en / ef - 1.0).abs() < 1e-3, "{en:e} vs {ef:e}");
        assert_eq!(nonzero(&pn.reflected_stress), nonzero(&pf.reflected_stress));
        let (dn, df) = (
            pn.displacement.last().unwrap(),
            pf.displacement.last().unwrap(),
        );
        let scale = pn.displacement.iter().fold(0.0f64, |a, d| a.max(d.abs()));
        assert!(
            (dn - df).abs() <= 1e-6 * scale,
            "{dn:e} vs {df:e} (max {scale:e})"
        );
        let dt = near.interface.dt;
        let burst_rows = 5e-6 / dt;
        assert!(
            (pf.t.len() as f64) < pn.t.len() as f64 + 2.0 * burst_rows,
            "{} rows far, {} near",
            pf.t.len(),
            pn.t.len()
        );
        // the rows left out lie between the incident wave and the reflected one
        let jump = pf.t.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        assert!(jump > 2e-3, "largest step {jump:e} s");
        assert!(pn.t.windows(2).all(|w| w[1] - w[0] < 1.5 * dt));
    }
}

//! One bar-stack simulation (model.md section 9.3, thesis chapter 4): the hammer test, the
//! frequency response functions (H1 estimate of receptance and accelerance, thesis
//! section 2.2), the first mode and its second harmonic from the free response after the
//! pulse, the next (guide) mode from a small linear impulse, the mean contact stiffness
//! over the response (eq. 4.2) and the contact pressures.

use super::shear::{self, BarShear, ShearProbeHistory};
use super::waves::{wave_analysis, WaveHistories};
use crate::analysis::{spectral_peak, with_analyzer, Summary};
use crate::error::Result;
use crate::scenario::bar_stack::{BarStackScenario, HalfSine};
use crate::solver::bar_stack::{End, FdOutput, FdRun, ForceSource, StepProgress};
use std::sync::Arc;

/// Level of the force spectrum, in dB re its peak, below which an FRF bin is masked: there
/// the force carries almost no energy (near the zeros of a half-sine at (2k+1)/(2 tau),
/// k >= 1, and above its main lobes) and X/F divides the response by almost nothing.
pub const FRF_FORCE_FLOOR_DB: f64 = -40.0;

/// Frequency response of the first node (where the force acts). Bins where the force
/// spectrum is below [`FRF_FORCE_FLOOR_DB`] of its peak are masked: their receptance, phase
/// and accelerance are NaN (`force_db` says why).
#[derive(Debug, Clone, Default)]
pub struct Frf {
    /// Frequencies, Hz.
    pub frequency: Vec<f64>,
    /// |receptance| = |displacement / force|, m/N (NaN where masked).
    pub receptance: Vec<f64>,
    /// Phase of the receptance, rad (NaN where masked).
    pub phase: Vec<f64>,
    /// |accelerance| = |acceleration / force|, (m/s^2)/N (NaN where masked).
    pub accelerance: Vec<f64>,
    /// Level of the force spectrum |F(f)| re its peak, dB (20 log10 |F| / max |F|).
    pub force_db: Vec<f64>,
}

impl Frf {
    /// Whether bin `k` is masked (force below [`FRF_FORCE_FLOOR_DB`]).
    pub fn masked(&self, k: usize) -> bool {
        !self
            .force_db
            .get(k)
            .is_some_and(|db| *db >= FRF_FORCE_FLOOR_DB)
    }

    /// The highest frequency where the force reaches [`FRF_FORCE_FLOOR_DB`], Hz (0 for an
    /// empty FRF): the FRF holds below it only.
    pub fn band_limit(&self) -> f64 {
        (0..self.frequency.len())
            .rev()
            .find(|&k| !self.masked(k))
            .map_or(0.0, |k| self.frequency[k])
    }
}

/// Histories at one `[[probe]]` of a bar-stack scenario.
#[derive(Debug, Clone)]
pub struct ProbeHistory {
    /// Probe name.
    pub name: String,
    /// Position along the stack, m.
    pub x: f64,
    /// Displacement from the static equilibrium, m.
    pub displacement: Vec<f64>,
    /// Velocity (centred differences), m/s.
    pub velocity: Vec<f64>,
    /// Acceleration (second differences), m/s^2.
    pub acceleration: Vec<f64>,
    /// Dynamic axial stress E du/dx over the adjacent cell, Pa (tension positive).
    pub stress: Vec<f64>,
    /// Transverse histories, when the stack has a shear field.
    pub shear: Option<ShearProbeHistory>,
}

/// Everything a bar-stack run produces.
#[derive(Debug, Clone)]
pub struct BarStackResult {
    /// File of the scenario.
    pub file: String,
    /// Time step, s.
    pub dt: f64,
    /// Static contact pressure of each interface from the static step, Pa.
    pub static_pressure: Vec<f64>,
    /// Times, s.
    pub t: Vec<f64>,
    /// Force at the first node, N.
    pub force: Vec<f64>,
    /// Displacement of the first node (from the static equilibrium), m.
    pub displacement: Vec<f64>,
    /// Acceleration of the first node, m/s^2.
    pub acceleration: Vec<f64>,
    /// Gap of each interface, m.
    pub gap: Vec<Vec<f64>>,
    /// Contact pressure (-sigma) of each interface, Pa.
    pub pressure: Vec<Vec<f64>>,
    /// Adhesion beta of each interface.
    pub beta: Vec<Vec<f64>>,
    /// Tangent stiffness of each interface's law at its gap (and beta), Pa/m
    /// (`inf` for a rigid branch while closed).
    pub stiffness: Vec<Vec<f64>>,
    /// Histories at the scenario's `[[probe]]` points.
    pub probes: Vec<ProbeHistory>,
    /// FRF (empty for an incident-wave run: there is no force).
    pub frf: Frf,
    /// Incident, reflected and transmitted waves of an `[incident]` run.
    pub waves: Option<WaveHistories>,
    /// The transverse field, when the stack has one (model.md section 13).
    pub shear: Option<BarShear>,
    /// Summary scalars (per-interface values as `key_0`, `key_1`, ...).
    pub summary: Summary,
}

/// Run the hammer test of a bar-stack scenario.
pub fn simulate_bar_stack(s: &BarStackScenario) -> Result<BarStackResult> {
    simulate_bar_stack_with_progress(s, None)
}

/// [`simulate_bar_stack`] reporting `(steps done, steps)` of the main run every 4096 steps.
pub fn simulate_bar_stack_with_progress(
    s: &BarStackScenario,
    progress: Option<StepProgress>,
) -> Result<BarStackResult> {
    if s.incident.is_some() || s.shear_incident.is_some() {
        return simulate_incident(s, progress);
    }
    let dt = s.dt;
    let steps = (s.duration / dt).ceil() as usize;
    let run = FdRun {
        dt,
        t0: 0.0,
        steps,
        record_every: 1,
        probes: recorded_nodes(s, 1),
        forces: if s.imposed_displacement {
            vec![]
        } else {
            vec![ForceSource {
                node: 0,
                signal: s.force.clone(),
            }]
        },
        imposed: s.imposed_displacement.then(|| s.force.clone()),
        progress,
        interface_scheme: s.interface_scheme,
        shear_probes: s
            .stack
            .shear_mesh(dt)
            .map_or_else(Vec::new, |m| shear::recorded_nodes(s, &m)),
    };
    let out = s.stack.run(&run)?;
    let probes = probe_histories(s, &out);
    let u = &out.displacement[0];
    let n = u.len();
    let mut acc = vec![0.0; n];
    for k in 1..n.saturating_sub(1) {
        acc[k] = (u[k + 1] - 2.0 * u[k] + u[k - 1]) / (dt * dt);
    }
    let force: Vec<f64> = if s.imposed_displacement {
        // reaction of the imposed end (thesis eq. 2.39): the force that moves the half
        // cell of node 0, m0 a0 = F + S E (u1 - u0) / dx (damping neglected), N
        let mesh = s.stack.mesh(dt);
        let mat = s.stack.segments[0].material;
        let dx = mesh.dx[0];
        let m0 = 0.5 * mat.density * s.stack.area * dx;
        let u1 = &out.displacement[out.displacement.len() - 1];
        (0..n)
            .map(|k| m0 * acc[k] - s.stack.area * mat.youngs_modulus * (u1[k] - u[k]) / dx)
            .collect()
    } else {
        out.t.iter().map(|&t| s.force.value(t)).collect()
    };
    // FRF (H1 = X F* / |F|^2) over the whole record; regularised where the force spectrum
    // vanishes, and masked (NaN) where it is below FRF_FORCE_FLOOR_DB of its peak (zeros of
    // the half-sine at (2k+1)/(2 tau), k >= 1, and above its lobes): no estimate holds there
    let (fx, ff) = with_analyzer(|a| -> Result<_> {
        Ok((a.dft_padded(u, false)?, a.dft_padded(&force, false)?))
    })?;
    let nfft = (u.len().next_power_of_two() * 2) as f64;
    let df = 1.0 / (nfft * dt);
    let fmax_out = 20_000.0f64.min(0.5 / dt);
    let kmax = ((fmax_out / df) as usize).min(ff.len());
    let fpow_max = ff.iter().fold(0.0f64, |m, c| m.max(c.norm_sqr()));
    let mut frf = Frf::default();
    for k in 1..kmax {
        let h = fx[k] * ff[k].conj() / (ff[k].norm_sqr() + 1e-8 * fpow_max);
        let f = k as f64 * df;
        // 0 / 0 (no force at all) is NaN: masked
        let db = 10.0 * (ff[k].norm_sqr() / fpow_max).log10();
        let held = db >= FRF_FORCE_FLOOR_DB;
        let or_nan = |v: f64| if held { v } else { f64::NAN };
        frf.frequency.push(f);
        frf.receptance.push(or_nan(h.norm()));
        frf.phase.push(or_nan(h.arg()));
        frf.accelerance
            .push(or_nan(h.norm() * (2.0 * std::f64::consts::PI * f).powi(2)));
        frf.force_db.push(db);
    }
    // free response after the pulse: first mode and its second harmonic
    let pulse_end = s.pulse_duration;
    let k0 = ((2.0 * pulse_end / dt) as usize).min(n.saturating_sub(16));
    // with an imposed displacement the driven end is held after the pulse: the free
    // response is in its reaction force
    let response = if s.imposed_displacement { &force } else { &acc };
    let free = with_analyzer(|a| a.dft_padded(&response[k0..n.saturating_sub(1)], true))?;
    let nf = ((n - 1 - k0).next_power_of_two() * 2) as f64;
    let dff = 1.0 / (nf * dt);
    let mag: Vec<f64> = free.iter().map(|c| c.norm()).collect();
    let an = &s.spec.analysis;
    let (f1, a1) = spectral_peak(&mag, dff, an.first_mode_min, an.first_mode_max);
    let (f2, a2) = spectral_peak(&mag, dff, 1.8 * f1, 2.2 * f1);
    // next mode from a small, short linear impulse
    let probe_run = FdRun {
        forces: vec![ForceSource {
            node: 0,
            signal: Arc::new(HalfSine {
                peak: 1e-3,
                duration: 20.0 * dt,
            }),
        }],
        steps: ((0.05 / dt) as usize).min(steps),
        imposed: None,
        progress: None,
        // only the first node's displacement is read
        probes: vec![0],
        shear_probes: Vec::new(),
        ..run.clone()
    };
    let lin = s.stack.run(&probe_run)?;
    let ul = &lin.displacement[0];
    // displacement spectrum (the acceleration one over-weights the high modes)
    let sl = with_analyzer(|a| a.dft_padded(ul, true))?;
    let magl: Vec<f64> = sl.iter().map(|c| c.norm()).collect();
    let dfl = 1.0 / (((ul.len()).next_power_of_two() * 2) as f64 * dt);
    let (fg, _) = spectral_peak(&magl, dfl, (3.0 * f1).max(2000.0), 0.45 / dt);
    let mut summary = Summary::new();
    summary.set("first_mode_hz", f1);
    summary.set("second_harmonic_hz", f2);
    // amplitude of the equivalent steady sinusoid over the Hann-windowed free response:
    // 2 |X(f1)| / sum(w), with sum(w) = (M - 1) / 2 for M samples (m/s^2)
    let m_free = (n - 1).saturating_sub(k0) as f64;
    summary.set("A1", 2.0 * a1 / (0.5 * (m_free - 1.0)).max(1.0));
    summary.set("A2_over_A1", if a1 > 0.0 { a2 / a1 } else { 0.0 });
    summary.set("guide_mode_hz", fg);
    summary.set(
        "peak_force",
        if s.imposed_displacement {
            force.iter().fold(0.0f64, |m, f| m.max(f.abs()))
        } else {
            s.force_peak()
        },
    );
    let (pressure, stiffness) = interface_histories(s, &out, &mut summary);
    let shear = shear::analyse(s, &out, &mut summary);
    let mut out = out;
    let displacement = std::mem::take(&mut out.displacement[0]);
    Ok(BarStackResult {
        file: s.file.clone(),
        dt: s.dt,
        static_pressure: s.static_pressure.clone(),
        t: out.t,
        force,
        displacement,
        acceleration: acc,
        gap: out.gap,
        pressure,
        beta: out.beta,
        stiffness,
        probes,
        frf,
        waves: None,
        shear,
        summary,
    })
}

/// The nodes a run records: node 0, each `[[probe]]`'s node and its neighbour (read by
/// [`probe_histories`]), then `extra` (last).
fn recorded_nodes(s: &BarStackScenario, extra: usize) -> Vec<usize> {
    std::iter::once(0)
        .chain(s.probes.iter().flat_map(|p| [p.node, p.other]))
        .chain(std::iter::once(extra))
        .collect()
}

/// Displacement, velocity, acceleration and stress at the `[[probe]]` points: the run
/// records each probe's node and its neighbour, after the first node (index 0).
fn probe_histories(s: &BarStackScenario, out: &FdOutput) -> Vec<ProbeHistory> {
    let dt = s.dt;
    s.probes
        .iter()
        .zip(shear::probe_histories(s, out))
        .enumerate()
        .map(|(k, (p, shear))| {
            let (u, w) = (&out.displacement[1 + 2 * k], &out.displacement[2 + 2 * k]);
            let n = u.len();
            let mut vel = vec![0.0; n];
            let mut acc = vec![0.0; n];
            for i in 1..n.saturating_sub(1) {
                vel[i] = (u[i + 1] - u[i - 1]) / (2.0 * dt);
                acc[i] = (u[i + 1] - 2.0 * u[i] + u[i - 1]) / (dt * dt);
            }
            ProbeHistory {
                name: p.name.clone(),
                x: p.x,
                displacement: u.clone(),
                velocity: vel,
                acceleration: acc,
                stress: u
                    .iter()
                    .zip(w)
                    .map(|(a, b)| p.youngs_modulus * (b - a) / p.distance)
                    .collect(),
                shear,
            }
        })
        .collect()
}

/// Pressure and tangent-stiffness histories of every interface (obstacle last), and their
/// summary values: static pressure and closure, mean contact stiffness (eq. 4.2), minimum pressure,
/// final adhesion and largest gap, per interface (`key_i`) and the minimum pressure over
/// all (`min_contact_pressure`).
fn interface_histories(
    s: &BarStackScenario,
    out: &FdOutput,
    summary: &mut Summary,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let mut min_p = f64::INFINITY;
    let laws: Vec<_> = s
        .stack
        .interfaces
        .iter()
        .cloned()
        .chain(match &s.stack.right {
            End::Obstacle(l) => Some(l.clone()),
            _ => None,
        })
        .collect();
    let mut pressure = Vec::new();
    let mut stiffness = Vec::new();
    for (i, law) in laws.iter().enumerate() {
        let uc = law.critical_gap();
        let k: Vec<f64> = out.gap[i]
            .iter()
            .zip(&out.beta[i])
            .zip(&out.stress[i])
            .map(|((&g, &b), &sigma)| {
                if g <= uc {
                    if law.compression.is_rigid() {
                        f64::INFINITY
                    } else {
                        law.compression.tangent_at(g, sigma)
                    }
                } else {
                    law.traction.tangent(g - uc, b)
                }
            })
            .collect();
        let p: Vec<f64> = out.stress[i].iter().map(|x| -x).collect();
        let pmin = p.iter().cloned().fold(f64::INFINITY, f64::min);
        min_p = min_p.min(pmin);
        // eq. 4.2: mean of the tangent stiffness over the response (closed instants)
        let (mut sum, mut cnt) = (0.0, 0usize);
        if !law.compression.is_rigid() {
            for (&g, &kg) in out.gap[i].iter().zip(&k) {
                if g <= uc {
                    sum += kg;
                    cnt += 1;
                }
            }
        }
        stiffness.push(k);
        summary.set(
            &format!("static_interface_pressure_{i}"),
            s.static_pressure.get(i).copied().unwrap_or(f64::NAN),
        );
        // the static step's gap: the closure of the interface under p0, i.e. the opening
        // from the pre-loaded state at which contact is lost (0 for a rigid branch)
        summary.set(&format!("static_interface_closure_{i}"), uc);
        summary.set(
            &format!("mean_contact_stiffness_{i}"),
            if cnt > 0 { sum / cnt as f64 } else { f64::NAN },
        );
        summary.set(&format!("min_contact_pressure_{i}"), pmin);
        summary.set(
            &format!("beta_end_{i}"),
            out.beta[i].last().copied().unwrap_or(1.0),
        );
        summary.set(
            &format!("max_gap_{i}"),
            out.gap[i].iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        );
        pressure.push(p);
    }
    summary.set("min_contact_pressure", min_p);
    (pressure, stiffness)
}

/// An `[incident]` and/or `[shear_incident]` run: the waves enter through the transparent
/// first end, meet the interfaces, and the reflected waves leave where they came in (and
/// the transmitted ones through a transparent far end). Harmonics of both as in the
/// half-space analysis (velocity band amplitudes over the incident velocity amplitude
/// `A_inc = peak / Z_0`), energy fractions, and the interface histories.
fn simulate_incident(
    s: &BarStackScenario,
    progress: Option<StepProgress>,
) -> Result<BarStackResult> {
    let dt = s.dt;
    let steps = (s.duration / dt).ceil() as usize;
    let mesh = s.stack.mesh(dt);
    let last = mesh.nodes - 1;
    let shear_mesh = s.stack.shear_mesh(dt);
    let run = FdRun {
        dt,
        t0: 0.0,
        steps,
        record_every: 1,
        probes: recorded_nodes(s, last),
        forces: vec![],
        imposed: None,
        progress,
        interface_scheme: s.interface_scheme,
        shear_probes: shear_mesh
            .as_ref()
            .map_or_else(Vec::new, |m| shear::recorded_nodes(s, m)),
    };
    let out = s.stack.run(&run)?;
    let probes = probe_histories(s, &out);
    let u0 = &out.displacement[0];
    let n = u0.len();
    let mut summary = Summary::new();
    summary.set("xi", s.xi);
    let waves = match &s.incident {
        Some(inc) => {
            let z0 = s.stack.segments[0].material.impedance();
            let zn = s.stack.segments[s.stack.segments.len() - 1]
                .material
                .impedance();
            let far = out.displacement[out.displacement.len() - 1].as_slice();
            let w = wave_analysis(s, inc, (z0, zn), u0, far, &out.t);
            summary.set("amplitude", inc.peak());
            summary.set("frequency", inc.fundamental());
            summary.set("A_inc", w.a_inc);
            let f2 = inc.second_frequency();
            crate::analysis::set_reflected_harmonics(
                &mut summary,
                &w.reflected_bands,
                w.a_inc,
                f2.is_some(),
                None,
            );
            summary.set("energy_incident", w.energy[0]);
            summary.set("energy_reflected_fraction", w.energy[1] / w.energy[0]);
            if let Some(bt) = &w.transmitted_bands {
                for k in 1..=5 {
                    summary.set(
                        &format!("transmitted_A{k}_over_Ainc"),
                        bt.harmonic[k] / w.a_inc,
                    );
                }
                summary.set("energy_transmitted_fraction", w.energy[2] / w.energy[0]);
            }
            Some(w.histories)
        }
        None => None,
    };
    let (pressure, stiffness) = interface_histories(s, &out, &mut summary);
    let shear = shear::analyse(s, &out, &mut summary);
    let mut accel = vec![0.0; n];
    for k in 1..n.saturating_sub(1) {
        accel[k] = (u0[k + 1] - 2.0 * u0[k] + u0[k - 1]) / (dt * dt);
    }
    Ok(BarStackResult {
        file: s.file.clone(),
        dt: s.dt,
        static_pressure: s.static_pressure.clone(),
        t: out.t.clone(),
        force: vec![0.0; n],
        displacement: u0.clone(),
        acceleration: accel,
        gap: out.gap.clone(),
        pressure,
        beta: out.beta.clone(),
        stiffness,
        probes,
        frf: Frf::default(),
        waves,
        shear,
        summary,
    })
}

impl BarStackScenario {
    /// Peak of the force signal, N (sampled on the time grid).
    pub fn force_peak(&self) -> f64 {
        let d = self.pulse_duration;
        (0..=1000)
            .map(|i| self.force.value(d * i as f64 / 1000.0).abs())
            .fold(0.0, f64::max)
    }
}

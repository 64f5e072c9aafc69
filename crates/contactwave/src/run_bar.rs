//! One bar-stack simulation (model.md section 5, thesis chapter 4): the hammer test, the
//! frequency response functions (H1 estimate of receptance and accelerance, thesis
//! section 2.2), the first mode and its second harmonic from the free response after the
//! pulse, the next (guide) mode from a small linear impulse, the mean contact stiffness
//! over the response (eq. 4.2) and the contact pressures.

use crate::analysis::Summary;
use crate::error::Result;
use crate::scenario::bar_stack::{BarStackScenario, HalfSine, DEFAULT_PULSE_DURATION};
use crate::solver::barstack::{FdRun, ForceSource, StepProgress};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use std::sync::Arc;

/// Frequency response of the first node (where the force acts).
#[derive(Debug, Clone, Default)]
pub struct Frf {
    /// Frequencies, Hz.
    pub frequency: Vec<f64>,
    /// |receptance| = |displacement / force|, m/N.
    pub receptance: Vec<f64>,
    /// Phase of the receptance, rad.
    pub phase: Vec<f64>,
    /// |accelerance| = |acceleration / force|, (m/s^2)/N.
    pub accelerance: Vec<f64>,
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
}

/// Everything a bar-stack run produces.
#[derive(Debug, Clone)]
pub struct BarStackResult {
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
    /// FRF.
    pub frf: Frf,
    /// Summary scalars (per-interface values as `key_0`, `key_1`, ...).
    pub summary: Summary,
}

fn spectrum(x: &[f64], window: bool) -> Vec<Complex<f64>> {
    let n = x.len().next_power_of_two() * 2;
    let mut planner = RealFftPlanner::<f64>::new();
    let plan = planner.plan_fft_forward(n);
    let mut input = vec![0.0; n];
    let m = x.len();
    for (i, v) in x.iter().enumerate() {
        let w = if window {
            0.5 * (1.0 - (2.0 * std::f64::consts::PI * i as f64 / (m as f64 - 1.0)).cos())
        } else {
            1.0
        };
        input[i] = v * w;
    }
    let mut out = plan.make_output_vec();
    let _ = plan.process(&mut input, &mut out);
    out
}

/// Peak of |spec| between f_lo and f_hi with parabolic interpolation: (frequency, magnitude).
fn peak(spec: &[f64], df: f64, f_lo: f64, f_hi: f64) -> (f64, f64) {
    let lo = ((f_lo / df).ceil() as usize).max(1);
    let hi = ((f_hi / df).floor() as usize).min(spec.len().saturating_sub(2));
    if hi <= lo {
        return (f64::NAN, 0.0);
    }
    let k = (lo..=hi)
        .max_by(|&a, &b| spec[a].total_cmp(&spec[b]))
        .unwrap_or(lo);
    let (a, b, c) = (spec[k - 1], spec[k], spec[k + 1]);
    let den = a - 2.0 * b + c;
    let delta = if den != 0.0 { 0.5 * (a - c) / den } else { 0.0 };
    ((k as f64 + delta.clamp(-0.5, 0.5)) * df, b)
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
    let dt = s.dt;
    let steps = (s.spec.model.duration / dt).ceil() as usize;
    let run = FdRun {
        dt,
        t0: 0.0,
        steps,
        record_every: 1,
        probes: std::iter::once(0)
            .chain(s.probes.iter().flat_map(|p| [p.node, p.other]))
            .chain(std::iter::once(1))
            .collect(),
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
    };
    let out = s.stack.run(&run)?;
    let probes: Vec<ProbeHistory> = s
        .probes
        .iter()
        .enumerate()
        .map(|(k, p)| {
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
            }
        })
        .collect();
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
    // vanishes (zeros of the half-sine at (2k+1)/(2 tau), k >= 1), where no FRF estimate holds
    let fx = spectrum(u, false);
    let ff = spectrum(&force, false);
    let nfft = (u.len().next_power_of_two() * 2) as f64;
    let df = 1.0 / (nfft * dt);
    let fmax_out = 20_000.0f64.min(0.5 / dt);
    let kmax = ((fmax_out / df) as usize).min(ff.len());
    let fpow_max = ff.iter().fold(0.0f64, |m, c| m.max(c.norm_sqr()));
    let mut frf = Frf::default();
    for k in 1..kmax {
        let h = fx[k] * ff[k].conj() / (ff[k].norm_sqr() + 1e-8 * fpow_max);
        let f = k as f64 * df;
        frf.frequency.push(f);
        frf.receptance.push(h.norm());
        frf.phase.push(h.arg());
        frf.accelerance
            .push(h.norm() * (2.0 * std::f64::consts::PI * f).powi(2));
    }
    // free response after the pulse: first mode and its second harmonic
    let pulse_end = s.spec.excitation.duration.unwrap_or(DEFAULT_PULSE_DURATION);
    let k0 = ((2.0 * pulse_end / dt) as usize).min(n.saturating_sub(16));
    // with an imposed displacement the driven end is held after the pulse: the free
    // response is in its reaction force
    let response = if s.imposed_displacement { &force } else { &acc };
    let free = spectrum(&response[k0..n.saturating_sub(1)], true);
    let nf = ((n - 1 - k0).next_power_of_two() * 2) as f64;
    let dff = 1.0 / (nf * dt);
    let mag: Vec<f64> = free.iter().map(|c| c.norm()).collect();
    let an = &s.spec.analysis;
    let (f1, a1) = peak(&mag, dff, an.first_mode_min, an.first_mode_max);
    let (f2, a2) = peak(&mag, dff, 1.8 * f1, 2.2 * f1);
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
        ..run.clone()
    };
    let lin = s.stack.run(&probe_run)?;
    let ul = &lin.displacement[0];
    // displacement spectrum (the acceleration one over-weights the high modes)
    let sl = spectrum(ul, true);
    let magl: Vec<f64> = sl.iter().map(|c| c.norm()).collect();
    let dfl = 1.0 / (((ul.len()).next_power_of_two() * 2) as f64 * dt);
    let (fg, _) = peak(&magl, dfl, (3.0 * f1).max(2000.0), 0.45 / dt);
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
    let mut min_p = f64::INFINITY;
    let laws: Vec<_> = s
        .stack
        .interfaces
        .iter()
        .cloned()
        .chain(match &s.stack.right {
            crate::solver::barstack::End::Obstacle(l) => Some(l.clone()),
            _ => None,
        })
        .collect();
    let mut pressure = Vec::new();
    let mut stiffness = Vec::new();
    for (i, law) in laws.iter().enumerate() {
        let uc = law.critical_gap();
        stiffness.push(
            out.gap[i]
                .iter()
                .zip(&out.beta[i])
                .map(|(&g, &b)| {
                    if g <= uc {
                        if law.compression.is_rigid() {
                            f64::INFINITY
                        } else {
                            law.compression.tangent(g)
                        }
                    } else {
                        law.traction.tangent(g - uc, b)
                    }
                })
                .collect(),
        );
        let p: Vec<f64> = out.stress[i].iter().map(|x| -x).collect();
        let pmin = p.iter().cloned().fold(f64::INFINITY, f64::min);
        min_p = min_p.min(pmin);
        // eq. 4.2: mean of the tangent stiffness over the response (closed instants)
        let (mut sum, mut cnt) = (0.0, 0usize);
        for &g in &out.gap[i] {
            if g <= law.critical_gap() && !law.compression.is_rigid() {
                sum += law.compression.tangent(g);
                cnt += 1;
            }
        }
        summary.set(
            &format!("static_interface_pressure_{i}"),
            s.static_pressure.get(i).copied().unwrap_or(f64::NAN),
        );
        summary.set(
            &format!("mean_contact_stiffness_{i}"),
            if cnt > 0 { sum / cnt as f64 } else { f64::NAN },
        );
        summary.set(&format!("min_contact_pressure_{i}"), pmin);
        pressure.push(p);
    }
    summary.set("min_contact_pressure", min_p);
    Ok(BarStackResult {
        t: out.t.clone(),
        force,
        displacement: u.clone(),
        acceleration: acc,
        gap: out.gap.clone(),
        pressure,
        beta: out.beta.clone(),
        stiffness,
        probes,
        frf,
        summary,
    })
}

impl BarStackScenario {
    /// Peak of the force signal, N (sampled on the time grid).
    pub fn force_peak(&self) -> f64 {
        let d = self
            .spec
            .excitation
            .duration
            .unwrap_or(DEFAULT_PULSE_DURATION);
        (0..=1000)
            .map(|i| self.force.value(d * i as f64 / 1000.0).abs())
            .fold(0.0, f64::max)
    }
}

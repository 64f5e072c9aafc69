//! The waves of a bar-stack run with an incident wave (longitudinal or shear) at the ends
//! of the stack: the incident displacement at `x = 0`, the reflected and transmitted
//! ones, their velocity bands and energies (model.md sections 9.3 and 9.7).

use crate::excitation::Excitation;
use crate::numeric::gauss4;
use crate::scenario::bar_stack::BarStackScenario;
use crate::solver::bar_stack::End;
use std::sync::Arc;

/// The waves of an `[incident]` run, displacements in m at the ends of the stack.
#[derive(Debug, Clone, Default)]
pub struct WaveHistories {
    /// Incident wave at x = 0: `F(t) = -(1/Z_0) int_0^t s_inc` (Z_0 the first segment's
    /// impedance).
    pub incident: Vec<f64>,
    /// Reflected (outgoing) wave at x = 0: the displacement there minus the incident one.
    pub reflected: Vec<f64>,
    /// Transmitted wave at the far end when it is transparent (the displacement there).
    pub transmitted: Option<Vec<f64>>,
}

/// The waves of one type at the ends of the stack and their analysis.
pub(super) struct WaveAnalysis {
    /// Incident, reflected and transmitted displacements, m.
    pub histories: WaveHistories,
    /// Incident velocity amplitude `peak / Z_0`, m/s.
    pub a_inc: f64,
    /// Velocity bands of the reflected wave.
    pub reflected_bands: crate::analysis::BandAmplitudes,
    /// Velocity bands of the transmitted wave (transparent far end).
    pub transmitted_bands: Option<crate::analysis::BandAmplitudes>,
    /// Incident, reflected and transmitted energies over the cross-section, J.
    pub energy: [f64; 3],
}

/// Analyse the waves of incident wave `inc` (stress at x = 0, Pa) on the first end's
/// displacement `u0` and the far end's `far` (m, at times `t`), with impedances `(Z_0,
/// Z_n)` of the first and last segments for this wave type (Pa s/m): the incident
/// displacement `F(t) = -(1/Z_0) int_0^t s_inc` (Gauss-Legendre per step), the reflected
/// `u0 - F`, the transmitted `far` when the last end is transparent; energies `S/Z_0 int
/// s_inc^2`, `S Z_0 int v^2`, `S Z_n int v^2` (v by differences of the displacements).
pub(super) fn wave_analysis(
    s: &BarStackScenario,
    inc: &Arc<dyn Excitation>,
    (z0, zn): (f64, f64),
    u0: &[f64],
    far: &[f64],
    t: &[f64],
) -> WaveAnalysis {
    let dt = s.dt;
    let mut incident = Vec::with_capacity(t.len());
    let mut acc = 0.0;
    for (k, &tk) in t.iter().enumerate() {
        if k > 0 {
            acc += gauss4(t[k - 1], tk, |x| inc.stress(x));
        }
        incident.push(-acc / z0);
    }
    let reflected: Vec<f64> = u0.iter().zip(&incident).map(|(u, f)| u - f).collect();
    let transmitted = matches!(s.stack.right, End::Transparent).then(|| far.to_vec());
    let (f0, f2) = (inc.fundamental(), inc.second_frequency());
    let area = s.stack.area;
    let e_inc = area / z0 * gauss_energy(inc, t.last().copied().unwrap_or(0.0));
    let e_ref = area * z0 * velocity_energy(&reflected, dt);
    let e_tr = transmitted
        .as_ref()
        .map_or(0.0, |tr| area * zn * velocity_energy(tr, dt));
    WaveAnalysis {
        a_inc: inc.peak() / z0,
        reflected_bands: crate::analysis::velocity_bands(&reflected, dt, f0, f2),
        transmitted_bands: transmitted
            .as_ref()
            .map(|tr| crate::analysis::velocity_bands(tr, dt, f0, f2)),
        energy: [e_inc, e_ref, e_tr],
        histories: WaveHistories {
            incident,
            reflected,
            transmitted,
        },
    }
}

/// `int_0^t_end s_inc^2 dt` (Pa^2 s), Gauss-Legendre between the waveform's breakpoints
/// and over sub-intervals of a twentieth of a period.
fn gauss_energy(inc: &Arc<dyn Excitation>, t_end: f64) -> f64 {
    let end = inc.duration().min(t_end);
    let h = 0.05 / inc.highest_frequency();
    let m = (end / h).ceil().max(1.0) as usize;
    let h = end / m as f64;
    (0..m)
        .map(|k| gauss4(k as f64 * h, (k + 1) as f64 * h, |x| inc.stress(x).powi(2)))
        .sum()
}

/// `int v^2 dt` of the velocity by differences of a displacement record, m^2/s.
fn velocity_energy(u: &[f64], dt: f64) -> f64 {
    u.windows(2).map(|w| (w[1] - w[0]).powi(2) / dt).sum()
}

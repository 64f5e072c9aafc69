//! The transverse field of a bar-stack run (model.md sections 9.7 and 13): the shear waves
//! at the ends of the stack and their harmonics, the tangential histories of every
//! interface (gap, shear stress, slip, slider state), the frictional and damage
//! dissipation and the energy balance of both wave types, and the transverse histories
//! at the probes.

use super::waves::{wave_analysis, WaveHistories};
use crate::analysis::{set_shear_harmonics, Summary};
use crate::scenario::bar_stack::BarStackScenario;
use crate::solver::bar_stack::{End, FdOutput, Mesh};

/// The transverse field of a bar-stack run.
#[derive(Debug, Clone, Default)]
pub struct BarShear {
    /// Incident, reflected and transmitted shear waves (transverse displacements at the
    /// ends, m) of a `[shear_incident]` run.
    pub waves: Option<WaveHistories>,
    /// Tangential gap `[u]_T` of each interface (obstacle last), m.
    pub gap: Vec<Vec<f64>>,
    /// Contact shear stress tau of each interface, Pa.
    pub stress: Vec<Vec<f64>>,
    /// Accumulated slip of each interface, m.
    pub slip: Vec<Vec<f64>>,
    /// Slider state of each interface: 0 stick, +1 / -1 slipping, NaN free.
    pub state: Vec<Vec<f64>>,
    /// Frictional dissipation of each interface over the run, J (over the cross-section).
    pub friction_dissipation: Vec<f64>,
    /// Energy released by damage at each interface over the run, J.
    pub damage_dissipation: Vec<f64>,
}

/// Transverse histories at one `[[probe]]`.
#[derive(Debug, Clone)]
pub struct ShearProbeHistory {
    /// Transverse displacement, m.
    pub displacement: Vec<f64>,
    /// Transverse velocity (centred differences), m/s.
    pub velocity: Vec<f64>,
    /// Dynamic shear stress G du/dx over the adjacent cell, Pa.
    pub stress: Vec<f64>,
}

/// The transverse-field nodes a run records: the first node, each probe's node and its
/// neighbour, and the last node.
pub(super) fn recorded_nodes(s: &BarStackScenario, mesh: &Mesh) -> Vec<usize> {
    std::iter::once(0)
        .chain(
            s.probes
                .iter()
                .filter_map(|p| p.shear.map(|q| [q.node, q.other]))
                .flatten(),
        )
        .chain(std::iter::once(mesh.nodes - 1))
        .collect()
}

/// Transverse histories at the probes (`None` for each without a shear field).
pub(super) fn probe_histories(
    s: &BarStackScenario,
    out: &FdOutput,
) -> Vec<Option<ShearProbeHistory>> {
    let dt = s.dt;
    let Some(sh) = &out.shear else {
        return vec![None; s.probes.len()];
    };
    s.probes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let q = p.shear?;
            let (u, w) = (&sh.displacement[1 + 2 * k], &sh.displacement[2 + 2 * k]);
            let n = u.len();
            let mut velocity = vec![0.0; n];
            for i in 1..n.saturating_sub(1) {
                velocity[i] = (u[i + 1] - u[i - 1]) / (2.0 * dt);
            }
            Some(ShearProbeHistory {
                displacement: u.clone(),
                velocity,
                stress: u
                    .iter()
                    .zip(w)
                    .map(|(a, b)| q.shear_modulus * (b - a) / q.distance)
                    .collect(),
            })
        })
        .collect()
}

/// The transverse field's results and summary keys (docs/scenario.md, bar-stack outputs):
/// with a `[shear_incident]` the shear harmonics (`shear_A*`, `shear_tr_A*`), the shear
/// energies and the energy closure of both wave types; per interface `friction_dissipation_i`,
/// `damage_dissipation_i` (J), `max_slip_i` (m), `max_shear_stress_i` (Pa); the friction
/// ratio `mu p0 / tau_inc` of the first interface with friction. `None` without a shear
/// field.
pub(super) fn analyse(
    s: &BarStackScenario,
    out: &FdOutput,
    summary: &mut Summary,
) -> Option<BarShear> {
    let sh = out.shear.as_ref()?;
    let stack = &s.stack;
    let sh_stack = stack.shear.as_ref()?;
    let area = stack.area;
    let mut r = BarShear {
        waves: None,
        gap: sh.gap.clone(),
        stress: sh.stress.clone(),
        slip: sh.slip.clone(),
        state: sh.state.clone(),
        friction_dissipation: sh.friction_dissipation.iter().map(|e| e * area).collect(),
        damage_dissipation: sh.damage_dissipation.iter().map(|e| e * area).collect(),
    };
    for i in 0..r.gap.len() {
        summary.set(
            &format!("friction_dissipation_{i}"),
            r.friction_dissipation[i],
        );
        summary.set(&format!("damage_dissipation_{i}"), r.damage_dissipation[i]);
        let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        summary.set(&format!("max_slip_{i}"), max_abs(&r.slip[i]));
        summary.set(&format!("max_shear_stress_{i}"), max_abs(&r.stress[i]));
    }
    let friction: f64 = r.friction_dissipation.iter().sum();
    let damage: f64 = r.damage_dissipation.iter().sum();
    summary.set("friction_dissipation", friction);
    let Some(inc) = &s.shear_incident else {
        return Some(r);
    };
    let seg = &stack.segments;
    let zt = |i: usize| seg[i].material.shear_impedance().unwrap_or(f64::NAN);
    let (u0, far) = (
        &sh.displacement[0],
        &sh.displacement[sh.displacement.len() - 1],
    );
    let w = wave_analysis(s, inc, (zt(0), zt(seg.len() - 1)), u0, far, &out.t);
    let amp = inc.peak();
    summary.set("shear_amplitude", amp);
    summary.set("shear_frequency", inc.fundamental());
    summary.set("shear_A_inc", w.a_inc);
    // the first interface with friction (stack order, the obstacle last)
    let frictional = sh_stack
        .interfaces
        .iter()
        .chain(&sh_stack.obstacle)
        .enumerate()
        .find(|(_, tl)| tl.branch.friction() > 0.0);
    let (mu, q0, p0) = frictional.map_or((0.0, 0.0, 0.0), |(i, tl)| {
        let p0 = s.static_pressure.get(i).copied().unwrap_or(0.0);
        (tl.branch.friction(), tl.static_shear, p0)
    });
    summary.set("friction_coefficient", mu);
    summary.set("static_shear", q0);
    summary.set(
        "friction_ratio",
        if amp > 0.0 { mu * p0 / amp } else { 0.0 },
    );
    set_shear_harmonics(summary, "shear_", &w.reflected_bands, w.a_inc);
    if let Some(bt) = &w.transmitted_bands {
        set_shear_harmonics(summary, "shear_tr_", bt, w.a_inc);
    }
    let [e_inc, e_ref, e_tr] = w.energy;
    summary.set("shear_energy_incident", e_inc);
    summary.set("shear_energy_reflected_fraction", e_ref / e_inc);
    if matches!(stack.right, End::Transparent) {
        summary.set("shear_energy_transmitted_fraction", e_tr / e_inc);
    }
    // both wave types: what came in left as waves or was dissipated at the interfaces
    let get = |k: &str| summary.get(k).unwrap_or(0.0);
    let n_inc = get("energy_incident");
    let n_out = n_inc * (get("energy_reflected_fraction") + get("energy_transmitted_fraction"));
    let total = e_inc + n_inc;
    summary.set("friction_dissipation_fraction", friction / total);
    summary.set(
        "energy_closure_error",
        (total - n_out - e_ref - e_tr - friction - damage).abs() / total,
    );
    r.waves = Some(w.histories);
    Some(r)
}

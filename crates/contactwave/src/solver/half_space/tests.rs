//! The grid fast paths and the affine blocks of the time loop against the general,
//! event-locating path.

use super::*;
use crate::excitation::{Delayed, ToneBurst, Window};
use crate::law::registry::build_law;
use crate::law::spec::{CompressionSpec, TractionSpec};

/// Every recorded series and scalar of `out`, as bits.
fn fingerprint(out: &HalfSpaceOutput) -> Vec<u64> {
    let mut v: Vec<u64> = [
        &out.t,
        &out.beta,
        &out.gap,
        &out.contact_stress,
        &out.incident_stress,
        &out.reflected_stress,
        &out.transmitted_stress,
        &out.reflected_displacement,
        &out.incident_displacement,
        &out.transmitted_displacement,
    ]
    .iter()
    .flat_map(|s| s.iter().map(|x| x.to_bits()))
    .collect();
    let e = &out.energy;
    v.extend(
        [
            e.incident,
            e.reflected,
            e.transmitted,
            e.stored,
            e.damage,
            out.max_gap,
            out.open_time_in_burst,
        ]
        .map(f64::to_bits),
    );
    v.push(out.events as u64);
    v
}

/// Solve with the paths of `paths` (0 all, 1 no affine blocks, 2 general only).
fn solve(hs: &HalfSpace, samples_per_period: usize, paths: u8) -> HalfSpaceOutput {
    let settings = HalfSpaceSettings {
        samples_per_period,
        ..Default::default()
    };
    let paths = match paths {
        0 => Paths::All,
        1 => Paths::NoAffineBlocks,
        _ => Paths::General,
    };
    hs.solve_taking(&settings, &mut Workspace::new(), paths)
        .unwrap()
}

/// Every recorded series of `out`, and its scalars.
fn series(out: &HalfSpaceOutput) -> Vec<(&'static str, Vec<f64>)> {
    let e = &out.energy;
    vec![
        ("t", out.t.clone()),
        ("beta", out.beta.clone()),
        ("gap", out.gap.clone()),
        ("contact_stress", out.contact_stress.clone()),
        ("incident_stress", out.incident_stress.clone()),
        ("reflected_stress", out.reflected_stress.clone()),
        ("transmitted_stress", out.transmitted_stress.clone()),
        ("reflected_displacement", out.reflected_displacement.clone()),
        ("incident_displacement", out.incident_displacement.clone()),
        (
            "transmitted_displacement",
            out.transmitted_displacement.clone(),
        ),
        (
            "energy",
            vec![e.incident, e.reflected, e.transmitted, e.damage],
        ),
        ("max_gap", vec![out.max_gap]),
        ("open_time_in_burst", vec![out.open_time_in_burst]),
    ]
}

/// The scenarios of the comparisons: laws with stuck, affine and nonlinear phases, damage
/// with and without viscosity, clapping and no contact loss, two windows and a delayed
/// burst, a rigid wall and a second medium, four samplings.
fn cases() -> Vec<(String, HalfSpace, usize)> {
    let p0 = 0.1e6;
    let c_n = 2e13;
    let compressions = [
        CompressionSpec::Rigid(Default::default()),
        CompressionSpec::Linear(crate::law::compression::linear::Spec { stiffness: 3e12 }),
        CompressionSpec::Quadratic(crate::law::compression::quadratic::Spec { k0: 3e12, k1: 1e19 }),
    ];
    let tractions = [
        TractionSpec::Free(Default::default()),
        TractionSpec::Linear(crate::law::traction::linear::Spec { stiffness: 1e12 }),
        TractionSpec::Rccm(crate::law::traction::rccm::Spec {
            stiffness: c_n,
            energy: 0.1,
            viscosity: 1e-8,
        }),
        TractionSpec::Rccm(crate::law::traction::rccm::Spec {
            stiffness: c_n,
            energy: 0.02,
            viscosity: 0.0,
        }),
        TractionSpec::Bonded(Default::default()),
    ];
    let (pmma, steel) = (Material::PMMA, Material::STEEL);
    let mut cases = Vec::new();
    for compression in &compressions {
        for traction in &tractions {
            let law = match build_law(p0, compression, traction, "test.toml", "interface") {
                Ok(l) => Arc::new(l),
                Err(_) => continue,
            };
            for (i, xi) in [0.3, 0.6, 0.95, 1.2, 1.6, 2.2, 3.0, 4.5, 6.0, 9.0]
                .into_iter()
                .enumerate()
            {
                let window = if i % 2 == 1 {
                    Window::Hann
                } else {
                    Window::HannRamps { ramp_fraction: 0.2 }
                };
                let cycles = [6.0, 6.5, 5.25][i % 3];
                let burst: Arc<dyn Excitation> =
                    Arc::new(ToneBurst::new(xi * p0, 1e6, cycles, window));
                let incident: Arc<dyn Excitation> = if i % 4 == 2 {
                    Arc::new(Delayed::new(burst, 0.37e-6))
                } else {
                    burst
                };
                let counterpart = (i % 3 == 1).then_some(steel);
                let spp = [200, 48, 100, 64][i % 4];
                let name = format!("{compression:?} x {traction:?} at xi = {xi}");
                cases.push((
                    name,
                    HalfSpace::new(pmma, counterpart, law.clone(), incident),
                    spp,
                ));
            }
        }
    }
    cases
}

/// The grid fast paths (stuck steps from the table or after the burst, ODE steps without
/// an event) give the general path's outputs bit for bit.
#[test]
fn fast_paths_are_the_general_path_bit_for_bit() {
    let mut compared = 0;
    for (name, hs, spp) in cases() {
        let (fast, general) = (solve(&hs, spp, 1), solve(&hs, spp, 2));
        let (a, b) = (fingerprint(&fast), fingerprint(&general));
        let first = (0..a.len().max(b.len())).find(|&i| a.get(i) != b.get(i));
        assert!(
            first.is_none(),
            "{name}: entry {first:?} of {} differs",
            a.len()
        );
        compared += 1;
    }
    assert!(compared >= 120, "{compared} runs compared");
}

/// The runs of affine steps ([`GapRun::affine_block`]: the same collocation solution, its
/// stage stresses from the phase's stiffness instead of the law) give the step-by-step
/// outputs to round-off: the same events and record length, every series within 1e-12 of
/// its largest magnitude, every scalar within 1e-12 relative.
#[test]
fn affine_blocks_are_the_step_by_step_solution() {
    let mut compared = 0;
    for (name, hs, spp) in cases() {
        let (block, steps) = (solve(&hs, spp, 0), solve(&hs, spp, 1));
        assert_eq!(block.events, steps.events, "{name}: events");
        for ((key, a), (_, b)) in series(&block).into_iter().zip(series(&steps)) {
            assert_eq!(a.len(), b.len(), "{name}: length of {key}");
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                let tol = 1e-12 * if b.len() > 4 { scale } else { y.abs() };
                assert!(
                    (x - y).abs() <= tol,
                    "{name}: {key}[{i}] = {x:e} with blocks, {y:e} step by step"
                );
            }
        }
        compared += 1;
    }
    assert!(compared >= 120, "{compared} runs compared");
}

/// The incident table a workspace keeps from its last run ([`Workspace`]) gives the
/// outputs of a table made anew, bit for bit: used again by the same wave on the same
/// grid, replaced after another (other amplitudes, windows, delays and samplings).
#[test]
fn a_kept_incident_table_is_the_table_made_anew() {
    let mut ws = Workspace::new();
    let on = |hs: &HalfSpace, spp: usize, ws: &mut Workspace| {
        let settings = HalfSpaceSettings {
            samples_per_period: spp,
            ..Default::default()
        };
        fingerprint(&hs.solve_in(&settings, ws).unwrap())
    };
    let mut reused = 0;
    for (name, hs, spp) in cases() {
        // the table of the case before is there: replaced
        let after_other = on(&hs, spp, &mut ws);
        ws.clear();
        let fresh = on(&hs, spp, &mut ws);
        // the table of this very run is there: used again
        let kept = on(&hs, spp, &mut ws);
        assert!(after_other == fresh, "{name}: after another run");
        assert!(kept == fresh, "{name}: with its own table kept");
        reused += 1;
    }
    assert!(reused >= 120, "{reused} runs compared");
    // one shape, amplitudes one after the other: each its own table
    let p0 = 0.1e6;
    let law = Arc::new(
        build_law(
            p0,
            &CompressionSpec::Rigid(Default::default()),
            &TractionSpec::Free(Default::default()),
            "test.toml",
            "interface",
        )
        .unwrap(),
    );
    let window = Window::HannRamps { ramp_fraction: 0.2 };
    for xi in [0.5, 1.5, 3.0, 1.5] {
        let burst = Arc::new(ToneBurst::new(xi * p0, 1e6, 6.0, window));
        let hs = HalfSpace::new(Material::PMMA, None, law.clone(), burst);
        let after_other = on(&hs, 100, &mut ws);
        ws.clear();
        assert!(after_other == on(&hs, 100, &mut ws), "xi = {xi}");
    }
}

//! The GPU backend against the CPU (feature `gpu`; these tests need an NVIDIA GPU and
//! fail without one): the same receivers' traces, crack fields and energy audit (the flux
//! into absorbing layers too) to round-off, the audit closed at round-off on the GPU as
//! well in closed domains, and the same bits on every GPU run.

use super::tests::{clapping_plate, frictional};
use super::*;

/// Largest difference between `a` and `b` over the largest magnitude of `b`.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale.max(f64::MIN_POSITIVE)
}

/// Run `problem` with stress receivers at `stress_at` (m) on both backends and compare.
fn compare<L: NormalPart + TangentialPart + Clone>(
    name: &str,
    problem: &Solid2d<L>,
    stress_at: &[[f64; 2]],
) {
    let mut plan = problem.plan("<test>").unwrap();
    plan.add_stress_receivers(stress_at, &problem.layers, "<test>")
        .unwrap();
    plan.capture_at(vec![plan.steps / 2, plan.steps - 1]);
    let cpu = plan.clone().run_on(Backend::Cpu, "<test>", None).unwrap();
    let gpu = plan.clone().run_on(Backend::Gpu, "<test>", None).unwrap();
    let again = plan.clone().run_on(Backend::Gpu, "<test>", None).unwrap();
    let rec = relative(&gpu.receivers, &cpu.receivers);
    let stress = relative(&gpu.stresses, &cpu.stresses);
    assert_eq!(cpu.stresses.is_empty(), stress_at.is_empty());
    let snap = relative(&gpu.snapshots.frames, &cpu.snapshots.frames);
    let (gc, cc) = (&gpu.cracks[0], &cpu.cracks[0]);
    let gap = relative(&gc.normal_gap, &cc.normal_gap);
    let slip = relative(&gc.tangential_gap, &cc.tangential_gap);
    let (eg, ec) = (gpu.energy, cpu.energy);
    eprintln!(
        "{name}: receivers {rec:.2e}, stresses {stress:.2e}, snapshots {snap:.2e}, gap {gap:.2e}, slip {slip:.2e}; \
         energy input {:.2e}, solid {:.2e}, absorbed {:.2e}; GPU closure {:.2e} (CPU {:.2e})",
        (eg.input - ec.input).abs() / ec.input,
        (eg.solid - ec.solid).abs() / ec.solid,
        (eg.absorbed - ec.absorbed).abs() / ec.input,
        eg.closure_error(),
        ec.closure_error()
    );
    assert!(
        rec < 1e-9 && snap < 1e-9 && stress < 1e-9,
        "{name}: {rec:e} {snap:e} {stress:e}"
    );
    assert!(gap < 1e-9 && slip < 1e-9, "{name}: {gap:e} {slip:e}");
    assert!((eg.input - ec.input).abs() < 1e-9 * ec.input, "{name}");
    assert!(
        (eg.absorbed - ec.absorbed).abs() <= 1e-9 * ec.input,
        "{name}: {eg:?} {ec:?}"
    );
    if ec.absorbed == 0.0 {
        assert!(eg.closure_error() < 1e-9, "{name}: {eg:?}");
    } else {
        // absorbing layers: the flux into them measured alike on both
        assert!(eg.absorbed > 0.0, "{name}: {eg:?}");
        assert!(
            (eg.closure_error() - ec.closure_error()).abs() < 1e-9,
            "{name}"
        );
    }
    assert_eq!(gpu.time, cpu.time);
    assert_eq!(gc.time, cc.time);
    // the same bits on every GPU run
    let bits = |o: &Solid2dOutput| {
        let mut v: Vec<u64> = o.receivers.iter().map(|x| x.to_bits()).collect();
        v.extend(o.stresses.iter().map(|x| x.to_bits()));
        v.extend(o.cracks[0].normal_gap.iter().map(|x| x.to_bits()));
        v.push(o.energy.solid.to_bits());
        v
    };
    assert_eq!(bits(&gpu), bits(&again), "{name}");
}

/// A clapping Signorini crack in plane strain, free, rigid and periodic sides (the last
/// with an odd element count: the periodic seam needs extra colours), orders 4 and 6, and
/// absorbing sides and bottom.
#[test]
fn gpu_matches_the_cpu_on_a_clapping_crack() {
    for (sides, width, order) in [
        (Side::Free, 8e-3, 6),
        (Side::Rigid, 8e-3, 4),
        (Side::Periodic, 8.5e-3, 6),
    ] {
        let p = Solid2d {
            width,
            order,
            ..clapping_plate(sides)
        };
        compare(&format!("P-SV {sides:?} order {order}"), &p, &[]);
    }
    // absorbing x sides and bottom (perfectly matched layers, their corners included)
    let p = Solid2d {
        bottom: Side::Absorbing,
        order: 6,
        receivers: vec![[4e-3, 0.0], [4e-3, 3e-3]],
        ..clapping_plate(Side::Absorbing)
    };
    compare("P-SV absorbing order 6", &p, &[]);
}

/// An SH wave on a frictional crack (Coulomb, mu = 0.3), antiplane elements, periodic then
/// absorbing sides.
#[test]
fn gpu_matches_the_cpu_on_a_frictional_sh_crack() {
    let p0 = 1e6;
    let law = frictional(p0, 0.3);
    let base = clapping_plate(Side::Periodic);
    let mut sources = base.sources.clone();
    if let SourceKind::Traction { normal, .. } = &mut sources[0].kind {
        *normal = false;
    }
    let p = Solid2d {
        width: base.width,
        layers: base.layers.clone(),
        wave: WaveType::Sh,
        top: base.top,
        bottom: base.bottom,
        sides: base.sides,
        element_size: base.element_size,
        order: 6,
        courant: base.courant,
        max_time_step: base.max_time_step,
        cracks: vec![Crack {
            start: base.cracks[0].start,
            end: base.cracks[0].end,
            full_width: false,
            law,
            profile: None,
        }],
        sources,
        receivers: base.receivers.clone(),
        duration: base.duration,
        crack_every: base.crack_every,
        pml: base.pml,
    };
    compare("SH Coulomb", &p, &[[4e-3, 1e-3], [4e-3, 2e-3]]);
    let p = Solid2d {
        sides: Side::Absorbing,
        ..p
    };
    compare("SH Coulomb absorbing", &p, &[]);
    // a plane SH wave from a line above the crack instead of the transducer
    let p = Solid2d {
        sources: vec![plane_wave(Incidence::Sh, 15.0, 1e-3)],
        ..p
    };
    compare(
        "SH plane wave at 15 degrees",
        &p,
        &[[4e-3, 1.5e-3], [3e-3, 3e-3]],
    );
}

/// A plane-wave source at `degrees` from the z axis across the line `z` (m): 10 MPa, 2 MHz.
fn plane_wave(incidence: Incidence, degrees: f64, z: f64) -> Source {
    Source {
        kind: SourceKind::PlaneWave {
            incidence,
            angle: degrees.to_radians(),
            z,
        },
        signal: super::tests::burst(10e6, 2e6, 3.0),
    }
}

/// Plane P and SV waves at an angle (total-field/scattered-field injection) on the
/// clapping crack, absorbing sides and bottom, with stress receivers above, beside and
/// below the crack and on the surface; and a normal P wave with periodic sides.
#[test]
fn gpu_matches_the_cpu_with_plane_waves_and_stress_receivers() {
    let at = [[4e-3, 0.0], [4e-3, 1.5e-3], [1e-3, 2e-3], [4.5e-3, 3e-3]];
    let p = Solid2d {
        bottom: Side::Absorbing,
        order: 6,
        sources: vec![
            plane_wave(Incidence::P, 20.0, 1e-3),
            plane_wave(Incidence::Sv, -10.0, 1e-3),
        ],
        ..clapping_plate(Side::Absorbing)
    };
    compare("P and SV plane waves, absorbing", &p, &at);
    let p = Solid2d {
        sides: Side::Periodic,
        sources: vec![plane_wave(Incidence::P, 0.0, 1e-3)],
        ..p
    };
    compare("P plane wave, periodic sides", &p, &at);
}

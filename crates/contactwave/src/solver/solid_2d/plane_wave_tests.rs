//! Plane waves by total-field/scattered-field injection: the leakage into the scattered
//! region and the determinism of plane-wave runs (docs/model.md section 15.8; the 1D
//! reduction of a full-width interface for every law is `study/validation/
//! solid_2d_reduction.rs`, the oblique waves `study/validation/solid_2d_plane.rs`).

use super::tests::{burst, Signorini, ALUMINIUM};
use super::*;

/// No crack: below the line the velocity is the incident wave's `-s(t - tau)/(rho c)`,
/// above it (the scattered region) the field stays below -40 dB of the incident peak and
/// falls with the resolution; P-SV (P and SV) and SH. Returns, per element size (of
/// `order`, in wavelengths), the leakage and the total-field error, both over the incident
/// peak.
fn leakage(wave: WaveType, incidence: Incidence, order: usize, sizes: &[f64]) -> Vec<(f64, f64)> {
    let f0 = 1e6;
    let c = if incidence == Incidence::P {
        ALUMINIUM.p_speed
    } else {
        ALUMINIUM.s_speed
    };
    let lambda = c / f0;
    let amp = 1e6;
    let sig = burst(amp, f0, 2.0);
    let peak = amp / (ALUMINIUM.density * c);
    let comp = match (wave, incidence) {
        (WaveType::Sh, _) => 0,
        (_, Incidence::P) => 1,
        _ => 0,
    };
    let mut out = Vec::new();
    for &size in sizes {
        let h = size * lambda;
        let (z_line, depth) = (2.0 * lambda, 6.0 * lambda);
        let (z_s, z_t) = (1.0 * lambda, 4.0 * lambda);
        let problem: Solid2d<Signorini> = Solid2d {
            receivers: vec![[0.0, z_s], [0.0, z_t]],
            order,
            ..Solid2d::plane_wave_strip(
                ALUMINIUM,
                wave,
                incidence,
                h,
                depth,
                z_line,
                sig.clone(),
                z_t / c + 3.0 / f0,
            )
        };
        let plan = problem.plan("<test>").unwrap();
        let plan = plan;
        let tau = plan.plane_waves[0].delay_at([0.0, z_t]);
        let o = plan.run().unwrap();
        let scattered = o.trace(0, comp).iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let mut err = 0.0f64;
        for (k, &t) in o.time.iter().enumerate() {
            let exact = -sig.stress(t - tau) / (ALUMINIUM.density * c);
            err = err.max((o.trace(1, comp)[k] - exact).abs());
        }
        assert!(o.energy.closure_error() < 1e-9, "{:?}", o.energy);
        out.push((scattered / peak, err / peak));
    }
    out
}

/// The leakage of the injection into the scattered region is below -40 dB of the incident
/// peak at 4 elements (order 4) per wavelength and falls with the resolution; the total
/// field below the line is the incident wave (P, SV in P-SV runs, SH).
#[test]
fn plane_wave_injection_leaks_less_than_40_db() {
    for (wave, inc) in [
        (WaveType::PSv, Incidence::P),
        (WaveType::PSv, Incidence::Sv),
        (WaveType::Sh, Incidence::Sh),
    ] {
        let r = leakage(wave, inc, 4, &[0.5, 0.25, 0.125]);
        let db: Vec<f64> = r.iter().map(|x| 20.0 * x.0.log10()).collect();
        eprintln!("{inc:?}: leakage dB {db:.1?}, total-field error / peak {r:?}");
        assert!(db[1] < -40.0, "{inc:?}: {db:?}");
        assert!(db[2] < db[1] - 6.0, "{inc:?}: {db:?}");
        assert!(r[2].1 < 5e-3 && r[2].1 < r[1].1, "{inc:?}: {r:?}");
    }
}

/// The same at the default order 6 and its default element size for 3 f0 (0.85 elements
/// per S wavelength at 3 f0: 2.55 per S wavelength, 5.2 per P wavelength at f0), and at half
/// of it: below -40 dB there, and falling.
#[test]
fn plane_wave_injection_at_the_default_order() {
    let s_per_p = ALUMINIUM.s_speed / ALUMINIUM.p_speed;
    for (wave, inc, scale) in [
        (WaveType::PSv, Incidence::P, s_per_p),
        (WaveType::PSv, Incidence::Sv, 1.0),
        (WaveType::Sh, Incidence::Sh, 1.0),
    ] {
        // element sizes in this wave's wavelengths at f0
        let h = scale / 3.5;
        let r = leakage(wave, inc, 6, &[h, h / 2.0]);
        let db: Vec<f64> = r.iter().map(|x| 20.0 * x.0.log10()).collect();
        eprintln!("order 6, {inc:?}: leakage dB {db:.1?}, total-field error / peak {r:?}");
        assert!(db[0] < -40.0 && db[1] < db[0], "{inc:?}: {db:?}");
        assert!(r[1].1 < r[0].1, "{inc:?}: {r:?}");
    }
}

/// A plane wave on a clapping full-width interface, wider than one element (8 elements
/// across): the same bits on 1 and 2 threads, and every node of the interface moves alike.
#[test]
fn plane_wave_runs_are_bit_identical_for_any_thread_count() {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let h = 0.25 * lambda;
    let problem = Solid2d {
        width: 8.0 * h,
        cracks: vec![Crack::across(
            8.0 * h,
            2.5 * lambda,
            super::tests::signorini(0.3e6),
        )],
        receivers: vec![[0.0, 0.5 * lambda], [3.0 * h, 4.5 * lambda]],
        ..Solid2d::plane_wave_strip(
            ALUMINIUM,
            WaveType::PSv,
            Incidence::P,
            h,
            5.0 * lambda,
            lambda,
            burst(1e6, f0, 2.0),
            4.0 / f0,
        )
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| problem.plan("<test>").unwrap().run().unwrap())
    };
    let (a, b) = (run(1), run(2));
    let bits = |o: &Solid2dOutput| {
        let mut v: Vec<u64> = o.receivers.iter().map(|x| x.to_bits()).collect();
        v.extend(o.cracks[0].normal_gap.iter().map(|x| x.to_bits()));
        v.push(o.energy.input.to_bits());
        v
    };
    assert_eq!(bits(&a), bits(&b));
    let rec = &a.cracks[0];
    let n = rec.position.len();
    let gmax = rec.normal_gap.iter().fold(0.0f64, |m, &g| m.max(g));
    assert!(gmax > 0.0);
    for g in rec.normal_gap.chunks(n) {
        let spread = g.iter().fold(0.0f64, |m, &x| m.max((x - g[0]).abs()));
        assert!(spread <= 1e-9 * gmax, "spread {spread:e} of {gmax:e}");
    }
}

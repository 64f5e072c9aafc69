//! Plane waves by total-field/scattered-field injection: the leakage into the scattered
//! region, the 1D reduction of a full-width interface under a plane wave against the exact
//! half-space and coupled solvers for every law, and oblique P and SV waves on a linear
//! spring interface against the closed form (docs/model.md section 15.8).

use super::tests::{burst, strip, Signorini, ALUMINIUM};
use super::*;

/// A periodic strip `h` wide, `depth` deep, absorbing top and bottom, with a plane wave of
/// `incidence` injected at normal incidence across `z_line`.
fn plane_strip<L>(
    wave: WaveType,
    incidence: Incidence,
    h: f64,
    depth: f64,
    z_line: f64,
    signal: Arc<dyn Excitation>,
    duration: f64,
) -> Solid2d<L> {
    Solid2d {
        top: Side::Absorbing,
        bottom: Side::Absorbing,
        sources: vec![Source {
            kind: SourceKind::PlaneWave {
                incidence,
                angle: 0.0,
                z: z_line,
            },
            signal: signal.clone(),
        }],
        ..strip(wave, h, depth, true, signal, duration)
    }
}

/// No crack: below the line the velocity is the incident wave's `-s(t - tau)/(rho c)`,
/// above it (the scattered region) the field stays below -40 dB of the incident peak and
/// falls with the resolution; P-SV (P and SV) and SH. Returns, per element size, the
/// leakage and the total-field error, both over the incident peak.
fn leakage(wave: WaveType, incidence: Incidence, sizes: &[f64]) -> Vec<(f64, f64)> {
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
            ..plane_strip(
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
        let mut plan = plan;
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
        let r = leakage(wave, inc, &[0.5, 0.25, 0.125]);
        let db: Vec<f64> = r.iter().map(|x| 20.0 * x.0.log10()).collect();
        eprintln!("{inc:?}: leakage dB {db:.1?}, total-field error / peak {r:?}");
        assert!(db[1] < -40.0, "{inc:?}: {db:?}");
        assert!(db[2] < db[1] - 6.0, "{inc:?}: {db:?}");
        assert!(r[2].1 < 5e-3 && r[2].1 < r[1].1, "{inc:?}: {r:?}");
    }
}

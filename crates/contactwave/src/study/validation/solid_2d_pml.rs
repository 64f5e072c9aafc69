//! The absorbing layers (docs/model.md section 15.7) as `contactwave validate` rows: their
//! reflection at normal incidence at the default thickness and resolution (P, SV and SH
//! waves from a point force one P wavelength above the bottom layer), at most -40 dB; and,
//! as tests, the reflection against angle, the energy that flows into them (the audit
//! closes at round-off), their long-time stability and, undamped, the interior's scheme
//! continued.

use super::{ValidationCase, ALUMINIUM};
use crate::error::Result;
use crate::excitation::{ToneBurst, Window};
use crate::law::compression::Rigid;
use crate::law::point::PointLaw;
use crate::law::tangential::Free as FreeSliding;
use crate::law::traction::Free;
use crate::scenario::solid_2d::DEFAULT_ORDER;
use crate::solver::solid_2d::{
    pml, Layer, Pml, Side, Solid2d, Solid2dOutput, Source, SourceKind, WaveType,
};
use std::sync::Arc;

type Law = PointLaw<Rigid, Free, FreeSliding>;

/// The scenarios' default element size for a burst of `f0` (resolved for 3 f0), m.
fn default_h(f0: f64) -> f64 {
    super::solid_2d_dispersion::default_element_size_at(&ALUMINIUM, 3.0 * f0)
        .unwrap_or(ALUMINIUM.s_speed / (3.0 * f0) / 2.0)
}

/// A rectangle `width` x `depth` of aluminium, every side absorbing (default layers), a
/// 3-cycle Hann burst of a point force at `at` along `direction` (y in SH runs), the default order at
/// element size `h`, the default time step for 3 f0.
#[allow(clippy::too_many_arguments)]
fn box_run(
    wave: WaveType,
    f0: f64,
    h: f64,
    (width, depth): (f64, f64),
    at: [f64; 2],
    direction: [f64; 2],
    receivers: Vec<[f64; 2]>,
    duration: f64,
) -> Solid2d<Law> {
    Solid2d {
        width,
        layers: vec![Layer {
            bottom: depth,
            material: ALUMINIUM,
        }],
        wave,
        top: Side::Absorbing,
        bottom: Side::Absorbing,
        sides: Side::Absorbing,
        element_size: h,
        order: DEFAULT_ORDER,
        courant: 0.9,
        max_time_step: 0.12 / (2.0 * std::f64::consts::PI * 3.0 * f0),
        cracks: vec![],
        sources: vec![Source {
            kind: SourceKind::Force { at, direction },
            signal: Arc::new(ToneBurst::new(1e3, f0, 3.0, Window::Hann)),
        }],
        receivers,
        duration,
        crack_every: 1000,
        pml: Pml::elements(pml::DEFAULT_ELEMENTS, h),
    }
}

/// Peak speed of receiver `r` over the samples before `t_end` (all components), m/s.
fn peak(out: &Solid2dOutput, r: usize, other: Option<(&Solid2dOutput, usize)>, t_end: f64) -> f64 {
    let mut best = 0.0f64;
    for (k, &t) in out.time.iter().enumerate() {
        if t > t_end {
            break;
        }
        let mut s2 = 0.0;
        for c in 0..out.components {
            let mut v = out.trace(r, c)[k];
            if let Some((o, ro)) = other {
                v -= o.trace(ro, c)[k];
            }
            s2 += v * v;
        }
        best = best.max(s2.sqrt());
    }
    best
}

/// The reflection of the bottom layer against angle, in dB: a point force `H = lambda_P`
/// above it; receivers at its depth, `2 H tan(theta)` aside, see the wave the layer sends
/// back at incidence theta (specular path `2 H / cos(theta)`). The same run on a rectangle
/// deeper by `5 lambda_P` (the same mesh above, so the same bits until the wave reaches the
/// first bottom) gives the field without that reflection; their difference is the reflected
/// wave, compared with the incident one in the deeper run at the same distance from the
/// force along the mirrored ray (same radiation pattern), all before any wave from the
/// deeper run's bottom arrives.
pub fn reflection_db(wave: WaveType, direction: [f64; 2], angles: &[f64]) -> Result<Vec<f64>> {
    let f0 = 1e6;
    let h = default_h(f0);
    let lp = ALUMINIUM.p_speed / f0;
    let (xs, zs, hh) = (1.0 * lp, 2.5 * lp, 1.0 * lp);
    let width = xs + 2.0 * hh * 60f64.to_radians().tan() + 1.0 * lp;
    // (the receivers on the force's depth, then the mirrored ones 2 H above it)
    let mut receivers = Vec::new();
    for &a in angles {
        receivers.push([xs + 2.0 * hh * a.to_radians().tan(), zs]);
    }
    for &a in angles {
        receivers.push([xs + 2.0 * hh * a.to_radians().tan(), zs - 2.0 * hh]);
    }
    // the window: the reflected S at 60 degrees and the burst's length
    let t_end = 4.0 * hh / ALUMINIUM.s_speed + 3.2 / f0;
    let extra = 5.5 * lp;
    debug_assert!(2.0 * (hh + extra) / ALUMINIUM.p_speed > t_end);
    let run = |depth: f64| {
        box_run(
            wave,
            f0,
            h,
            (width, depth),
            [xs, zs],
            direction,
            receivers.clone(),
            t_end,
        )
        .plan("<validation>")?
        .run()
    };
    // (edges at whole elements: the deeper mesh repeats the shallower one above)
    let depth = ((zs + hh) / h).round() * h;
    let test = run(depth)?;
    let reference = run(depth + (extra / h).round() * h)?;
    let n = angles.len();
    Ok((0..n)
        .map(|i| {
            let reflected = peak(&test, i, Some((&reference, i)), t_end);
            let incident = peak(&reference, n + i, None, t_end);
            20.0 * (reflected / incident).log10()
        })
        .collect())
}

/// The rows: the reflection of the default layers at normal incidence for a P, an SV and
/// an SH wave, as the amplitude ratio of the reflected to the incident wave (reference 0,
/// tolerance 0.01 = -40 dB), and at 45 degrees (tolerance the continuum's `R0^cos(45)` for
/// P plus 10 dB, 0.024).
pub fn run_all() -> Result<Vec<ValidationCase>> {
    let mut v = Vec::new();
    for (name, wave, direction) in [
        ("P", WaveType::PSv, [0.0, 1.0]),
        ("SV", WaveType::PSv, [1.0, 0.0]),
        ("SH", WaveType::Sh, [0.0, 1.0]),
    ] {
        let db = reflection_db(wave, direction, &[0.0, 45.0])?;
        let ratio = |d: f64| 10f64.powf(d / 20.0);
        v.push(ValidationCase::new(
            format!("2D PML reflection, {name} at 0 deg (amplitude; 0.01 = -40 dB)"),
            0.0,
            ratio(db[0]),
            0.01,
        ));
        // at 45 degrees: the continuum's R0^cos(45) for P plus 10 dB (as the tests)
        let bound = ratio(20.0 * pml::DEFAULT_REFLECTION.log10() * 45f64.to_radians().cos() + 10.0);
        v.push(ValidationCase::new(
            format!("2D PML reflection, {name} wave source at 45 deg (amplitude; R0^cos + 10 dB)"),
            0.0,
            ratio(db[1]),
            bound,
        ));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default layers reflect at most -40 dB at normal incidence, and at oblique incidence
    /// no more than the continuum's `R0^cos(theta)` for P (the damping is scaled for c_P; S
    /// waves, slower, are damped more) plus 10 dB.
    fn check_reflection(name: &str, wave: WaveType, direction: [f64; 2]) {
        let angles = [0.0, 30.0, 45.0, 60.0];
        let db = reflection_db(wave, direction, &angles).unwrap();
        eprintln!("{name}: reflection at {angles:?} degrees: {db:.1?} dB");
        assert!(db[0] <= -40.0, "{name}: {db:?}");
        for (a, d) in angles.iter().zip(&db) {
            let continuum = 20.0 * pml::DEFAULT_REFLECTION.log10() * a.to_radians().cos();
            assert!(*d <= continuum + 10.0, "{name} at {a} degrees: {d} dB");
        }
    }

    #[test]
    fn default_layers_reflect_p_less_than_40_db_at_normal_incidence() {
        check_reflection(
            "P-SV, vertical force (P at normal incidence)",
            WaveType::PSv,
            [0.0, 1.0],
        );
    }

    #[test]
    fn default_layers_reflect_sv_less_than_40_db_at_normal_incidence() {
        check_reflection(
            "P-SV, horizontal force (SV at normal incidence)",
            WaveType::PSv,
            [1.0, 0.0],
        );
    }

    #[test]
    fn default_layers_reflect_sh_less_than_40_db_at_normal_incidence() {
        check_reflection("SH, force along y", WaveType::Sh, [0.0, 1.0]);
    }

    /// A point force in a box with absorbing layers on every side: once the waves have left,
    /// what flowed into the layers is the sources' work less the little the layers sent back,
    /// and the audit (input = solid + absorbed) closes at round-off at two resolutions.
    #[test]
    fn energy_flows_into_the_layers_and_the_audit_closes() {
        let f0 = 1e6;
        let lp = ALUMINIUM.p_speed / f0;
        for (wave, dir) in [(WaveType::PSv, [0.3, 0.8]), (WaveType::Sh, [0.0, 1.0])] {
            for refine in [1.0, 2.0] {
                let h = default_h(f0) / refine;
                let duration = 3.0 / f0 + 4.0 * lp / ALUMINIUM.s_speed;
                let out = box_run(
                    wave,
                    f0,
                    h,
                    (2.0 * lp, 1.5 * lp),
                    [0.8 * lp, 0.7 * lp],
                    dir,
                    vec![],
                    duration,
                )
                .plan("<test>")
                .unwrap()
                .run()
                .unwrap();
                let e = out.energy;
                eprintln!(
                    "{wave:?}, h = {h:.3e} m: input {:.4e} J/m, left in the solid {:.2e} of it, absorbed {:.6} of it, closure error {:.1e}",
                    e.input,
                    e.solid / e.input,
                    e.absorbed / e.input,
                    e.closure_error()
                );
                assert!(e.closure_error() < 1e-9, "{e:?}");
                assert!(e.solid < 1e-3 * e.input, "{e:?}");
                assert!(e.absorbed > 0.999 * e.input, "{e:?}");
            }
        }
    }

    /// The layers are stable at the interior's stability limit (courant 0.99, no cap on the
    /// time step): a small box driven once, then run for 300 crossing times (S), with layers
    /// on every side, above and below only (periodic sides), and on the x sides only (rigid top
    /// and bottom): the energy left in the interior only decays (below 1e-6 of the input at the
    /// end) and the audit closes. (The classical split PML, without the multiaxial damping,
    /// fails it at order 4: 2.4e-3 with layers on every side, 3e23 above and below.)
    #[test]
    #[ignore = "slow: full tier"]
    fn layers_are_stable_over_long_runs() {
        let f0 = 1e6;
        let lp = ALUMINIUM.p_speed / f0;
        for wave in [WaveType::PSv, WaveType::Sh] {
            for (top, sides) in [
                (Side::Absorbing, Side::Absorbing),
                (Side::Absorbing, Side::Periodic),
                (Side::Rigid, Side::Absorbing),
            ] {
                let h = default_h(f0) * 2.0;
                let problem = Solid2d {
                    top,
                    bottom: top,
                    sides,
                    courant: 0.99,
                    max_time_step: f64::INFINITY,
                    ..box_run(
                        wave,
                        f0,
                        h,
                        (lp, lp),
                        [0.5 * lp, 0.5 * lp],
                        [0.6, 0.8],
                        vec![],
                        300.0 * lp / ALUMINIUM.s_speed,
                    )
                };
                let plan = problem.plan("<test>").unwrap();
                let steps = plan.steps;
                let out = plan.run().unwrap();
                let e = out.energy;
                eprintln!(
                    "{wave:?}, top/bottom {top:?}, sides {sides:?}: {steps} steps at courant 0.99: left {:.1e} of the input, closure {:.1e}",
                    e.solid / e.input,
                    e.closure_error()
                );
                assert!(e.solid < 1e-6 * e.input, "{e:?}");
                assert!(e.closure_error() < 1e-9, "{e:?}");
            }
        }
    }

    /// Undamped (R0 -> 1), a layer is the interior's scheme continued: a box with absorbing
    /// sides gives, to round-off, the traces of the box widened by the layers' thickness with
    /// the layers' outer edge (rigid) as its sides (the same mesh, advanced by the
    /// displacement leapfrog there).
    #[test]
    fn undamped_layers_continue_the_interior_scheme() {
        let f0 = 1e6;
        let h = default_h(f0);
        let lp = ALUMINIUM.p_speed / f0;
        for wave in [WaveType::PSv, WaveType::Sh] {
            let l = 3.0 * h;
            let base = box_run(
                wave,
                f0,
                h,
                (8.0 * h, 6.0 * h),
                [4.0 * h, 3.0 * h],
                [0.6, 0.8],
                vec![[1.0 * h, 0.0], [8.0 * h, 5.0 * h], [0.0, 6.0 * h]],
                2.0 * lp / ALUMINIUM.s_speed,
            );
            let pml = Solid2d {
                top: Side::Free,
                bottom: Side::Free,
                pml: Pml {
                    thickness: l,
                    reflection: 1.0 - 1e-15,
                },
                ..base.clone()
            };
            let wide = Solid2d {
                width: 8.0 * h + 2.0 * l,
                top: Side::Free,
                bottom: Side::Free,
                sides: if pml::RIGID_EDGE {
                    Side::Rigid
                } else {
                    Side::Free
                },
                sources: vec![Source {
                    kind: SourceKind::Force {
                        at: [4.0 * h + l, 3.0 * h],
                        direction: [0.6, 0.8],
                    },
                    signal: base.sources[0].signal.clone(),
                }],
                receivers: base.receivers.iter().map(|r| [r[0] + l, r[1]]).collect(),
                ..base.clone()
            };
            let (a, b) = (
                pml.plan("<test>").unwrap().run().unwrap(),
                wide.plan("<test>").unwrap().run().unwrap(),
            );
            assert_eq!(a.time.len(), b.time.len());
            let scale = a.receivers.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let diff = a
                .receivers
                .iter()
                .zip(&b.receivers)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            eprintln!(
                "{wave:?}: undamped layer against the widened box: {:.1e}",
                diff / scale
            );
            assert!(scale > 0.0 && diff <= 1e-9 * scale, "{diff:e} of {scale:e}");
        }
    }

    /// Receivers and point forces in a layer are refused, naming the key.
    #[test]
    fn receivers_and_forces_in_a_layer_are_refused() {
        let f0 = 1e6;
        let h = default_h(f0);
        let base = box_run(
            WaveType::PSv,
            f0,
            h,
            (8.0 * h, 6.0 * h),
            [4.0 * h, 3.0 * h],
            [0.0, 1.0],
            vec![],
            1e-6,
        );
        let rec = Solid2d {
            receivers: vec![[-h, 3.0 * h]],
            ..base.clone()
        };
        let err = rec.plan("f.toml").unwrap_err().to_string();
        assert!(err.contains("receiver.0.at"), "{err}");
        let force = Solid2d {
            sources: vec![Source {
                kind: SourceKind::Force {
                    at: [4.0 * h, 7.0 * h],
                    direction: [0.0, 1.0],
                },
                signal: base.sources[0].signal.clone(),
            }],
            ..base.clone()
        };
        let err = force.plan("f.toml").unwrap_err().to_string();
        assert!(err.contains("source.0.at"), "{err}");
        let thin = Solid2d {
            pml: Pml {
                thickness: 0.0,
                reflection: 1e-3,
            },
            ..base
        };
        let err = thin.plan("f.toml").unwrap_err().to_string();
        assert!(err.contains("model.pml_thickness"), "{err}");
    }

    /// With layers on every side (more band elements than one parallel task), a run on 1 and
    /// on 3 threads gives identical bits (receivers and energy).
    #[test]
    fn layers_are_bit_identical_for_any_thread_count() {
        let f0 = 1e6;
        let h = default_h(f0);
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                box_run(
                    WaveType::PSv,
                    f0,
                    h,
                    (10.0 * h, 8.0 * h),
                    [3.0 * h, 5.0 * h],
                    [0.6, 0.8],
                    vec![[0.0, 0.0], [10.0 * h, 8.0 * h], [5.0 * h, 7.0 * h]],
                    2e-6,
                )
                .plan("<test>")
                .unwrap()
                .run()
                .unwrap()
            })
        };
        let (a, b) = (run(1), run(3));
        let bits = |o: &Solid2dOutput| o.receivers.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert!(a.energy.absorbed > 0.0);
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a.energy.absorbed.to_bits(), b.energy.absorbed.to_bits());
    }
}

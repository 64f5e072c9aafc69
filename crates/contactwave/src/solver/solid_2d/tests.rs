//! Physics tests of the 2D solver: energy closure at round-off in a closed domain with a
//! clapping crack, Signorini at every crack node, bit-identical results for any thread
//! count, and the reduction to the 1D exact solver of a full-width interface.

use super::*;
use crate::excitation::{ToneBurst, Window};
use crate::law::compression::Rigid;
use crate::law::point::PointLaw;
use crate::law::tangential::{Coulomb, Free as FreeSliding};
use crate::law::traction::Free;
use crate::material::Material;
use crate::solver::half_space::{HalfSpace, HalfSpaceSettings};

pub(super) type Signorini = PointLaw<Rigid, Free, FreeSliding>;

pub(super) const ALUMINIUM: Elastic = Elastic {
    density: 2700.0,
    p_speed: 6320.0,
    s_speed: 3130.0,
};

pub(super) fn signorini(p0: f64) -> Signorini {
    PointLaw::normal(
        p0,
        Rigid {
            static_pressure: p0,
        },
        Free,
        FreeSliding,
    )
}

/// Signorini with Coulomb friction (rigid stick).
pub(super) type Frictional = PointLaw<Rigid, Free, Coulomb>;

pub(super) fn frictional(p0: f64, friction: f64) -> Frictional {
    PointLaw::normal(
        p0,
        Rigid {
            static_pressure: p0,
        },
        Free,
        Coulomb {
            friction,
            stick_stiffness: f64::INFINITY,
        },
    )
}

pub(super) fn burst(amplitude: f64, f0: f64, cycles: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(amplitude, f0, cycles, Window::Hann))
}

/// A plate 8 x 4 mm with a 3 mm horizontal crack at 2 mm depth under 1 MPa closure, a
/// 10 MPa, 2 MHz burst from a 2 mm transducer above it: the crack claps.
pub(super) fn clapping_plate(sides: Side) -> Solid2d<Signorini> {
    Solid2d {
        width: 8e-3,
        layers: vec![Layer {
            bottom: 4e-3,
            material: ALUMINIUM,
        }],
        wave: WaveType::PSv,
        top: Side::Free,
        bottom: Side::Free,
        sides,
        element_size: 0.5e-3,
        order: 4,
        courant: 0.8,
        max_time_step: f64::INFINITY,
        cracks: vec![Crack {
            start: [2.5e-3, 2e-3],
            end: [5.5e-3, 2e-3],
            full_width: false,
            law: signorini(1e6),
            profile: None,
        }],
        sources: vec![Source {
            kind: SourceKind::Traction {
                top: true,
                x0: 3e-3,
                x1: 5e-3,
                normal: true,
                delay_per_m: 0.0,
            },
            signal: burst(10e6, 2e6, 3.0),
        }],
        receivers: vec![[4e-3, 0.0], [4e-3, 4e-3]],
        duration: 4e-6,
        crack_every: 1,
        pml: Pml::elements(pml::DEFAULT_ELEMENTS, 0.5e-3),
    }
}

/// In a closed domain (free top and bottom; rigid, then periodic x sides) the discrete
/// energy of the solid plus what the crack took equals the sources' work at round-off,
/// while the crack opens and closes again; Signorini holds at every node and step (no
/// penetration, no tension).
#[test]
fn clapping_crack_closes_the_energy_at_round_off_and_keeps_signorini() {
    for sides in [Side::Rigid, Side::Periodic, Side::Free] {
        let plan = clapping_plate(sides).plan("<test>").unwrap();
        let out = plan.run().unwrap();
        let e = out.energy;
        assert!(e.input > 0.0);
        assert!(
            e.closure_error() < 1e-9,
            "{sides:?}: {e:?} closure {:e}",
            e.closure_error()
        );
        let rec = &out.cracks[0];
        let gmax = rec.normal_gap.iter().fold(0.0f64, |a, &b| a.max(b));
        // opened by far more than round-off, and closed again (contact at some later record)
        assert!(gmax > 1e-10, "{sides:?}: max gap {gmax:e}");
        let n = rec.position.len();
        let closed_after_open = rec
            .normal_gap
            .chunks(n)
            .skip_while(|g| g.iter().all(|&x| x <= 0.0))
            .any(|g| g.contains(&0.0));
        assert!(closed_after_open, "{sides:?}");
        for (&g, &s) in rec.normal_gap.iter().zip(&rec.normal_stress) {
            assert!(g >= 0.0, "penetration {g:e}");
            assert!(s <= 1e-9 * 1e6, "tension {s:e} Pa");
            // complementarity: open faces carry no stress
            assert!(
                g == 0.0 || s.abs() <= 1e-9 * 1e6,
                "gap {g:e} with stress {s:e}"
            );
        }
        assert!(e.cracks.abs() < 0.5 * e.input, "{e:?}");
    }
}

/// A vertical crack across the boundary of two layers (aluminium over steel, the crack
/// from 1 to 3 mm, the boundary at 2 mm; no closure): its face nodes on the boundary take
/// the lumped masses of both layers' elements on their side, and the run keeps what the
/// one-layer crack keeps: the energy closes at round-off, the faces open on both sides
/// of the boundary, never interpenetrate and carry no tension (docs/scenario.md: a crack
/// may cross a layer boundary).
#[test]
fn a_crack_across_a_layer_boundary_keeps_signorini_and_the_energy() {
    let steel = Elastic {
        density: 7850.0,
        p_speed: 5900.0,
        s_speed: 3230.0,
    };
    let mut problem = clapping_plate(Side::Free);
    problem.layers = vec![
        Layer {
            bottom: 2e-3,
            material: ALUMINIUM,
        },
        Layer {
            bottom: 4e-3,
            material: steel,
        },
    ];
    problem.cracks[0].start = [4e-3, 1e-3];
    problem.cracks[0].end = [4e-3, 3e-3];
    problem.cracks[0].law = signorini(0.0);
    problem.duration = 3e-6;
    let out = problem.plan("<test>").unwrap().run().unwrap();
    let e = out.energy;
    assert!(e.closure_error() < 1e-9, "{e:?}");
    let rec = &out.cracks[0];
    let n = rec.position.len();
    let mut opened = [false; 2];
    for (k, (&g, &s)) in rec.normal_gap.iter().zip(&rec.normal_stress).enumerate() {
        assert!(g >= 0.0, "penetration {g:e}");
        assert!(s <= 1e-9 * 1e6, "tension {s:e} Pa");
        if g > 1e-12 {
            // position along the crack from z = 1 mm: the boundary at 1 mm
            opened[usize::from(rec.position[k % n] > 1e-3)] = true;
        }
    }
    assert!(
        opened[0] && opened[1],
        "opened above / below the boundary: {opened:?}"
    );
}

/// The same run on 1 and on 2 threads gives identical bits.
#[test]
fn results_are_bit_identical_for_any_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            clapping_plate(Side::Free)
                .plan("<test>")
                .unwrap()
                .run()
                .unwrap()
        })
    };
    let (a, b) = (run(1), run(2));
    let bits = |o: &Solid2dOutput| {
        let mut v: Vec<u64> = o.receivers.iter().map(|x| x.to_bits()).collect();
        v.extend(o.cracks[0].normal_gap.iter().map(|x| x.to_bits()));
        v.push(o.energy.solid.to_bits());
        v
    };
    assert_eq!(bits(&a), bits(&b));
}

/// The kernel gives the same bits on every CPU path (AVX-512 with its row gather and
/// scatter, AVX2, portable) and with its regular blocks read through the element-to-node
/// map, with split nodes, periodic sides and antiplane elements, for
/// orders 2 to 8, and the fused step advances every node exactly as the separate update
/// does.
#[test]
fn every_cpu_path_gives_the_same_bits() {
    let cases = [
        (Side::Free, WaveType::PSv),
        (Side::Periodic, WaveType::PSv),
        (Side::Absorbing, WaveType::PSv),
        (Side::Free, WaveType::Sh),
    ];
    let orders = [2, 3, 5, 6, 7, 8].map(|o| (o, Side::Free, WaveType::PSv));
    for (order, sides, wave) in cases.map(|(s, w)| (4, s, w)).into_iter().chain(orders) {
        let mut plate = clapping_plate(sides);
        plate.wave = wave;
        plate.order = order;
        let plan = plate.plan("<test>").unwrap();
        let k = &plan.stiffness;
        let len = plan.components * plan.mesh.n_nodes;
        let u: Vec<f64> = (0..len).map(|i| (i as f64 * 0.731).sin() * 1e-9).collect();
        let (mut fast, mut portable) = (vec![0.0; len], vec![0.0; len]);
        k.apply(&u, &mut fast);
        k.apply_portable(&u, &mut portable);
        assert!(fast.iter().any(|&f| f != 0.0));
        assert!(
            fast.iter()
                .zip(&portable)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{order} {sides:?} {wave:?}"
        );
        if sides == Side::Free {
            // some blocks of eight elements are regular, others (at the crack) are not
            assert!(k.regular.iter().any(|r| r.is_some()) && k.regular.iter().any(|r| r.is_none()));
        }
        // the regular blocks' nodes addressed by rows, not read from the map: the same bits
        let mut by_map = k.clone();
        by_map.regular.clear();
        let mut mapped = vec![0.0; len];
        by_map.apply(&u, &mut mapped);
        assert!(
            fast.iter()
                .zip(&mapped)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "map: {order} {sides:?} {wave:?}"
        );
        // the fused step: the forces of the kernel, then v += dt f / m, u += dt v, f = 0
        let (dt, c) = (plan.dt, plan.components);
        let v: Vec<f64> = (0..len).map(|i| (i as f64 * 0.377).cos()).collect();
        let (mut u1, mut v1, mut f1) = (u.clone(), v.clone(), vec![0.0; len]);
        k.step(&mut u1, &mut v1, &mut f1, &plan.inv_mass, dt, plan.rows.0);
        for &g in &plan.rows.1 {
            let g = g as usize;
            for j in c * g..c * (g + 1) {
                v1[j] += dt * plan.inv_mass[g] * f1[j];
                u1[j] += dt * v1[j];
                f1[j] = 0.0;
            }
        }
        let (mut u2, mut v2) = (u.clone(), v.clone());
        for j in 0..len {
            v2[j] += dt * plan.inv_mass[j / c] * fast[j];
            u2[j] += dt * v2[j];
        }
        assert!(f1.iter().all(|&f| f == 0.0));
        assert!(
            u1.iter().zip(&u2).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{sides:?}"
        );
        assert!(
            v1.iter().zip(&v2).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{sides:?}"
        );
    }
}

/// A periodic strip of aluminium `h` wide and `depth` deep ([`Solid2d::periodic_strip`]).
pub(super) fn strip<L>(
    wave: WaveType,
    h: f64,
    depth: f64,
    normal: bool,
    signal: Arc<dyn Excitation>,
    duration: f64,
) -> Solid2d<L> {
    Solid2d::periodic_strip(ALUMINIUM, wave, h, depth, (normal, signal), duration)
}

/// The exact half-space solver's normal gap (m) at time `t` (s, from the wave's arrival)
/// for identical half-spaces of aluminium's P-wave modulus under a 2-cycle burst of `amp`
/// (Pa) at `f0` (Hz) with the 1D law `law_1d`, and its largest magnitude: the reference of
/// the full-width interfaces' reductions (here and on meshes).
pub(super) fn exact_gap(
    law_1d: crate::law::ContactLaw,
    amp: f64,
    f0: f64,
) -> (impl Fn(f64) -> f64, f64) {
    let medium = Material {
        youngs_modulus: ALUMINIUM.density * ALUMINIUM.p_speed * ALUMINIUM.p_speed,
        density: ALUMINIUM.density,
        shear_modulus: Some(ALUMINIUM.mu()),
    };
    let exact = HalfSpace::new(medium, Some(medium), Arc::new(law_1d), burst(amp, f0, 2.0))
        .solve(&HalfSpaceSettings {
            samples_per_period: 4000,
            tail_periods: Some(1.0),
            summary_only: false,
        })
        .unwrap();
    let gmax = exact.gap.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    assert!(gmax > 0.0);
    let at = move |t: f64| -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let k = exact
            .t
            .partition_point(|&x| x < t)
            .clamp(1, exact.t.len() - 1);
        let (t0, t1) = (exact.t[k - 1], exact.t[k]);
        let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        exact.gap[k - 1] + s * (exact.gap[k] - exact.gap[k - 1])
    };
    (at, gmax)
}

/// The 1D Signorini interface (rigid in compression, free in traction) closed by `p0`
/// (Pa): the exact solver's law of the reductions of a full-width Signorini interface.
pub(super) fn signorini_1d(p0: f64) -> crate::law::ContactLaw {
    crate::law::ContactLaw {
        static_pressure: p0,
        compression: Box::new(Rigid {
            static_pressure: p0,
        }),
        traction: Box::new(Free),
    }
}

/// A linear spring interface of stiffness `k` (Pa/m) closed by `p0` (Pa), frictionless:
/// the 2D point law and the exact solver's 1D law of the reductions.
pub(super) fn linear_spring(
    p0: f64,
    k: f64,
) -> (
    impl NormalPart + TangentialPart + Clone,
    crate::law::ContactLaw,
) {
    use crate::law::compression::Linear;
    use crate::law::traction::Linear as LinearTraction;
    let law_2d = PointLaw::normal(
        p0,
        Linear {
            static_pressure: p0,
            stiffness: k,
        },
        LinearTraction { stiffness: k },
        FreeSliding,
    );
    let law = crate::law::ContactLaw {
        static_pressure: p0,
        compression: Box::new(Linear {
            static_pressure: p0,
            stiffness: k,
        }),
        traction: Box::new(LinearTraction { stiffness: k }),
    };
    (law_2d, law)
}

/// The largest gap error (over the max gap) of a full-width interface (periodic sides)
/// under a plane P wave at normal incidence, against the exact half-space solver (delayed
/// by the travel time from the surface), at each element size of `sizes` (wavelengths).
fn reduction_errors<L: NormalPart + TangentialPart + Clone>(
    law_2d: L,
    law_1d: crate::law::ContactLaw,
    sizes: &[f64],
) -> Vec<f64> {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let (zc, depth) = (2.5 * lambda, 5.0 * lambda);
    let amp = 1e6;
    let (at, gmax) = exact_gap(law_1d, amp, f0);
    let mut errors = Vec::new();
    for &size in sizes {
        let h = size * lambda;
        let problem = Solid2d {
            cracks: vec![Crack::across(h, zc, law_2d.clone())],
            ..strip(
                WaveType::PSv,
                h,
                depth,
                true,
                burst(amp, f0, 2.0),
                zc / ALUMINIUM.p_speed + 3.0 / f0,
            )
        };
        let out = problem.plan("<test>").unwrap().run().unwrap();
        let rec = &out.cracks[0];
        let n = rec.position.len();
        let delay = zc / ALUMINIUM.p_speed;
        let mut err = 0.0f64;
        for (k, &t) in rec.time.iter().enumerate() {
            // every node of the line moves alike (a plane wave)
            let g = &rec.normal_gap[k * n..(k + 1) * n];
            let spread = g.iter().fold(0.0f64, |a, &b| a.max((b - g[0]).abs()));
            assert!(spread <= 1e-9 * gmax, "spread {spread:e}");
            err = err.max((g[0] - at(t - delay)).abs());
        }
        errors.push(err / gmax);
        assert!(out.energy.closure_error() < 1e-9);
    }
    errors
}

/// A full-width Signorini interface reduces to the exact 1D solver: the gap error falls
/// with the element size, at about first order (the faces' impact at each closing sends
/// stress jumps into both solids, which the elements resolve to O(h); measured 0.21, 0.070,
/// 0.022, 0.0105 of the max gap at 2, 4, 8 and 16 elements per wavelength).
#[test]
fn full_width_signorini_interface_reduces_to_the_exact_1d_solver() {
    let p0 = 0.3e6;
    let errors = reduction_errors(signorini(p0), signorini_1d(p0), &[0.5, 0.25, 0.125, 0.0625]);
    eprintln!("1D reduction (Signorini), max gap error / max gap: {errors:?}");
    assert!(errors[3] < 0.02, "{errors:?}");
    assert!(
        errors[3] < 0.6 * errors[2] && errors[2] < 0.6 * errors[1],
        "{errors:?}"
    );
}

/// A full-width linear spring interface (smooth: no kinks) reduces to the exact 1D solver
/// at a high order.
#[test]
fn full_width_linear_interface_reduces_to_the_exact_1d_solver() {
    let (law_2d, law) = linear_spring(1e6, 1e14);
    let errors = reduction_errors(law_2d, law, &[0.5, 0.25, 0.125, 0.0625]);
    eprintln!("1D reduction (linear spring), max gap error / max gap: {errors:?}");
    // second order (the central differences in time; the elements are of order 4):
    // measured 0.030, 0.0065, 0.0016, 0.00040
    assert!(errors[3] < 1e-3, "{errors:?}");
    for w in errors.windows(2) {
        assert!(w[1] < w[0] / 3.5, "observed order below 1.8: {errors:?}");
    }
}

/// An antiplane (SH) burst on a frictional full-width interface that slips: the energy
/// still closes at round-off, the friction takes energy, and the shear stress never
/// exceeds mu p0.
#[test]
fn sh_wave_on_a_frictional_interface_slips_within_coulomb() {
    let f0 = 1e6;
    let lambda = ALUMINIUM.s_speed / f0;
    let p0 = 1e6;
    let mu = 0.3;
    let law = frictional(p0, mu);
    let h = lambda / 4.0;
    let problem = Solid2d {
        cracks: vec![Crack::across(h, 2.0 * lambda, law)],
        receivers: vec![[0.0, 4.0 * lambda]],
        ..strip(
            WaveType::Sh,
            h,
            4.0 * lambda,
            false,
            burst(1e6, f0, 2.0),
            2.0 * lambda / ALUMINIUM.s_speed + 3.0 / f0,
        )
    };
    let out = problem.plan("<test>").unwrap().run().unwrap();
    let e = out.energy;
    assert!(e.closure_error() < 1e-9, "{e:?}");
    let rec = &out.cracks[0];
    let smax = rec.shear_stress.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    assert!(smax <= mu * p0 * (1.0 + 1e-12), "{smax:e}");
    assert!(
        smax >= mu * p0 * (1.0 - 1e-9),
        "never reached the limit: {smax:e}"
    );
    let slip = rec
        .tangential_gap
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()));
    assert!(slip > 0.0);
    // friction dissipates: the crack took a positive share of the input
    assert!(e.cracks > 1e-3 * e.input, "{e:?}");
    assert!(rec.normal_gap.iter().all(|&g| g == 0.0));
    // no normal motion: the crack's work is all tangential; rigid stick stores nothing
    // and nothing is damaged: it is friction, to within the per-point tally's own
    // discretisation of the work (measured 5.6e-4)
    eprintln!(
        "crack {:e} (tangential {:e}), friction {:e}, damage {:e}",
        e.cracks, e.cracks_tangential, e.friction, e.damage
    );
    assert!(
        (e.cracks - e.cracks_tangential).abs() <= 1e-12 * e.cracks,
        "{e:?}"
    );
    assert_eq!(e.damage, 0.0);
    assert!(
        (e.friction / e.cracks_tangential - 1.0).abs() < 2e-3,
        "{e:?}"
    );
}

/// A plane P wave from a surface traction over the whole width of a periodic strip: the
/// velocity at depth is `-s(t - z / c_P) / Z` (Z = rho c_P) until the bottom's echo.
#[test]
fn plane_wave_from_a_surface_traction() {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let z = 2.5 * lambda;
    let sig = burst(1e6, f0, 2.0);
    let zimp = ALUMINIUM.density * ALUMINIUM.p_speed;
    let mut errors = Vec::new();
    for size in [0.5, 0.25, 0.125] {
        let h = size * lambda;
        let problem: Solid2d<Signorini> = Solid2d {
            receivers: vec![[0.0, z]],
            ..strip(
                WaveType::PSv,
                h,
                5.0 * lambda,
                true,
                sig.clone(),
                z / ALUMINIUM.p_speed + 3.0 / f0,
            )
        };
        let out = problem.plan("<test>").unwrap().run().unwrap();
        let tr = out.trace(0, 1);
        let mut err = 0.0f64;
        for (k, &t) in out.time.iter().enumerate() {
            let exact = -sig.stress(t - z / ALUMINIUM.p_speed) / zimp;
            err = err.max((tr[k] - exact).abs());
        }
        errors.push(err * zimp / 1e6);
    }
    eprintln!("plane wave, max velocity error / peak: {errors:?}");
    // second order in time and space together (dt scales with h): measured 0.036, 0.0076,
    // 0.0021
    assert!(errors[2] < 5e-3, "{errors:?}");
    assert!(
        errors[1] < errors[0] / 3.5 && errors[2] < errors[1] / 3.5,
        "{errors:?}"
    );
}

// The phase velocity at the default resolution, in the time domain and by the Bloch
// analysis of the scheme: `study::validation::solid_2d_dispersion` and `dispersion.rs`.

/// The absorbing bottom at normal incidence: a plane P (and SH) burst from the top of a
/// periodic strip comes back from an absorbing bottom at most -40 dB of its amplitude, and
/// the energy audit (with the flux into the layer) still closes at round-off.
#[test]
fn absorbing_side_reflects_less_than_40_db_at_normal_incidence() {
    let f0 = 1e6;
    for (wave, normal, c) in [
        (WaveType::PSv, true, ALUMINIUM.p_speed),
        (WaveType::Sh, false, ALUMINIUM.s_speed),
    ] {
        let lambda = c / f0;
        let h = ALUMINIUM.s_speed / (3.0 * f0) / 2.0;
        let (z_rec, depth) = (3.0 * lambda, 6.0 * lambda);
        let problem: Solid2d<Signorini> = Solid2d {
            bottom: Side::Absorbing,
            courant: 0.9,
            max_time_step: 0.12 / (2.0 * std::f64::consts::PI * 3.0 * f0),
            receivers: vec![[0.0, z_rec]],
            crack_every: 1000,
            ..strip(
                wave,
                h,
                depth,
                normal,
                burst(1e6, f0, 3.0),
                (2.0 * depth + z_rec) / c,
            )
        };
        let out = problem.plan("<test>").unwrap().run().unwrap();
        let comp = if wave == WaveType::PSv { 1 } else { 0 };
        let tr = out.trace(0, comp);
        let split = (z_rec + 3.0 * lambda + 0.5 * lambda) / c;
        let (mut inc, mut refl) = (0.0f64, 0.0f64);
        for (k, &t) in out.time.iter().enumerate() {
            if t < split {
                inc = inc.max(tr[k].abs());
            } else {
                refl = refl.max(tr[k].abs());
            }
        }
        let db = 20.0 * (refl / inc).log10();
        eprintln!("{wave:?}: reflection at normal incidence {db:.1} dB");
        assert!(db < -40.0, "{wave:?}: {db} dB");
        let e = out.energy;
        assert!(e.absorbed > 0.9 * e.input, "{e:?}");
        assert!(e.closure_error() < 1e-9, "{e:?}");
    }
}

/// A plan runs from rest every time: the second run of the same plan (its crack clapped
/// in the first) is the first, bit for bit, and two runs of the one plan at once on two
/// threads (the plan shared, immutable) give those bits too.
#[test]
fn a_plan_runs_from_rest_every_time() {
    let plan = clapping_plate(Side::Free).plan("<test>").unwrap();
    let a = plan.run().unwrap();
    assert!(a.cracks[0].peak_normal_gap > 0.0);
    let b = plan.run().unwrap();
    assert_eq!(a.receivers, b.receivers);
    assert_eq!(a.cracks[0].normal_gap, b.cracks[0].normal_gap);
    assert_eq!(a.cracks[0].peak_normal_gap, b.cracks[0].peak_normal_gap);
    assert_eq!(a.energy.cracks, b.energy.cracks);
    let (c, d) = std::thread::scope(|s| {
        let c = s.spawn(|| plan.run().unwrap());
        let d = s.spawn(|| plan.run().unwrap());
        (c.join().unwrap(), d.join().unwrap())
    });
    for o in [&c, &d] {
        assert_eq!(a.receivers, o.receivers);
        assert_eq!(a.cracks[0].normal_gap, o.cracks[0].normal_gap);
    }
}

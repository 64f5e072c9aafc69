//! Periodic sides on a mesh: the rectangle's periodic strip with a full-width interface on
//! a mesh of its own grid is the rectangle's run; the same strip on a skewed, curved
//! second-order mesh reduces to the exact 1D solver as the rectangle's strip does; curves
//! that are not translates, and a crack that ends on one periodic side only, are refused.

use super::input::QuadInput;
use super::*;
use crate::solver::solid_2d::tests::{
    burst, exact_gap, linear_spring, signorini, signorini_1d, strip, ALUMINIUM,
};
use crate::solver::solid_2d::{Crack, Solid2d};

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
}

/// On the strip's own grid, with the rectangle's time step, the mesh path's periodic strip
/// is the rectangle's: the interface's gaps along it within 1e-9 of their peak, the same
/// energies, the audit closed.
#[test]
fn a_periodic_strip_on_its_own_grid_is_the_rectangle_strip() {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let zc = 1.5 * lambda;
    let mut rect: Solid2d<_> = Solid2d {
        cracks: vec![Crack::across(0.25 * lambda, zc, signorini(0.3e6))],
        ..strip(
            WaveType::PSv,
            0.25 * lambda,
            3.0 * lambda,
            true,
            burst(1e6, f0, 2.0),
            zc / ALUMINIUM.p_speed + 3.0 / f0,
        )
    };
    rect.element_size = 0.125 * lambda;
    let plan = rect.plan("<test>").unwrap();
    let dt = 0.95 * plan.dt;
    drop(plan);
    rect.max_time_step = dt;
    let a = rect.plan("<test>").unwrap().run().unwrap();
    let quad = QuadSolid::of_rectangle(&rect, &|p| p, "<test>")
        .unwrap()
        .expect("a periodic strip carries over");
    let plan = quad.plan("<test>").unwrap();
    assert!(!plan.mirrors.is_empty());
    assert_eq!(plan.dt, dt);
    let b = plan.run().unwrap();
    let (ca, cb) = (&a.cracks[0], &b.cracks[0]);
    assert_eq!(ca.position.len(), cb.position.len(), "one point a node");
    assert_eq!(ca.time.len(), cb.time.len());
    let scale = max_abs(&ca.normal_gap);
    assert!(scale > 1e-12, "the interface opens: {scale:e}");
    let err = ca
        .normal_gap
        .iter()
        .zip(&cb.normal_gap)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(err < 1e-9 * scale, "gaps differ by {err:e} of {scale:e}");
    let (ea, eb) = (&a.energy, &b.energy);
    assert!((ea.input - eb.input).abs() < 1e-9 * ea.input);
    assert!(eb.closure_error() < 1e-10, "{eb:?}");
}

/// The map of the skewed strip: a shear along x (the sides stay translates) and a wobble
/// that vanishes on the sides, the surface, the interface and the bottom.
fn skew(width: f64, zc: f64, h: f64) -> impl Fn([f64; 2]) -> [f64; 2] {
    use std::f64::consts::PI;
    move |[x, z]: [f64; 2]| {
        let w = (2.0 * PI * x / width).sin() * (PI * z / zc).sin();
        [x + 0.3 * z + 0.15 * h * w, z + 0.1 * h * w]
    }
}

/// An aluminium strip on the mesh `input` at order 4, its sides `left` and `right`
/// periodic (`periodic`) or free, the curves of `cracks` cracks of `law`, a normal
/// traction `signal` on `top`, for `duration` (s).
fn strip_on<L>(
    input: QuadInput,
    periodic: (&str, &str),
    cracks: &[&str],
    law: L,
    signal: Arc<dyn crate::excitation::Excitation>,
    duration: f64,
) -> QuadSolid<L>
where
    L: Clone,
{
    QuadSolid {
        input: Arc::new(input),
        order: 4,
        materials: vec![ALUMINIUM],
        wave: WaveType::PSv,
        courant: 0.5,
        max_time_step: f64::INFINITY,
        boundaries: Vec::new(),
        periodic: vec![(periodic.0.into(), periodic.1.into())],
        cracks: cracks
            .iter()
            .map(|&c| QuadCrack {
                curve: c.into(),
                law: law.clone(),
                profile: None,
            })
            .collect(),
        sources: vec![QuadSource {
            kind: QuadSourceKind::Traction {
                curve: "top".into(),
                normal: true,
                delay_per_m: 0.0,
            },
            signal,
        }],
        receivers: Vec::new(),
        stress_receivers: Vec::new(),
        duration,
        crack_every: 1,
        pml: None,
    }
}

/// A full-width interface in a strip three elements wide on the skewed, curved mesh of
/// elements `size` wavelengths, periodic sides, under a normal traction on the surface:
/// the largest gap error over the max gap against the exact 1D solver, and the largest
/// spread of the gap along the interface (over the max gap).
fn skewed_reduction<L: NormalPart + TangentialPart + Clone>(
    law_2d: L,
    law_1d: crate::law::ContactLaw,
    size: f64,
) -> (f64, f64) {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let (zc, depth) = (2.5 * lambda, 5.0 * lambda);
    let amp = 1e6;
    let (at, gmax) = exact_gap(law_1d, amp, f0);
    let h = size * lambda;
    let width = 3.0 * h;
    let nz = (depth / h).round() as usize;
    let xs: Vec<f64> = (0..=3).map(|i| i as f64 * h).collect();
    let zs: Vec<f64> = (0..=nz).map(|j| j as f64 * h).collect();
    let input = QuadInput::grid(
        &xs,
        &zs,
        &skew(width, zc, h),
        vec!["aluminium".into()],
        &|_| 0,
        &[("interface", [0.0, zc], [width, zc])],
        true,
    );
    let quad = strip_on(
        input,
        ("left", "right"),
        &["interface"],
        law_2d,
        burst(amp, f0, 2.0),
        zc / ALUMINIUM.p_speed + 3.0 / f0,
    );
    let plan = quad.plan("<test>").unwrap();
    assert!(
        plan.mesh.rectangle.iter().all(|&r| !r),
        "every element general"
    );
    let out = plan.run().unwrap();
    assert!(
        out.energy.closure_error() < 1e-9,
        "energy closure {:e}",
        out.energy.closure_error()
    );
    let rec = &out.cracks[0];
    let n = rec.position.len();
    assert_eq!(n, 3 * 4, "the points of three edges, the mouths joined");
    let delay = zc / ALUMINIUM.p_speed;
    let (mut err, mut spread) = (0.0f64, 0.0f64);
    for (k, &t) in rec.time.iter().enumerate() {
        let g = &rec.normal_gap[k * n..(k + 1) * n];
        let mean = g.iter().sum::<f64>() / n as f64;
        spread = spread.max(g.iter().fold(0.0f64, |a, &b| a.max((b - mean).abs())));
        err = err.max((mean - at(t - delay)).abs());
    }
    (err / gmax, spread / gmax)
}

/// The 1D reduction on a skewed, curved periodic mesh: a full-width Signorini interface's
/// gap against the exact solver falls with the element size as on the rectangle's strip
/// (there 0.070 and 0.022 of the max gap at 4 and 8 elements a wavelength; here measured
/// 0.067 and 0.019), the interface moving as one line (the plane wave stays plane through
/// general elements: its gap's spread along the line 0.036 and 0.011 of the max gap).
#[test]
fn the_1d_reduction_holds_on_a_skewed_periodic_mesh() {
    let p0 = 0.3e6;
    let coarse = skewed_reduction(signorini(p0), signorini_1d(p0), 0.25);
    let fine = skewed_reduction(signorini(p0), signorini_1d(p0), 0.125);
    eprintln!("skewed mesh 1D reduction (Signorini), (error, spread) / max gap: {coarse:?} at 4 per wavelength, {fine:?} at 8");
    assert!(fine.0 < 0.04, "{fine:?}");
    assert!(fine.0 < 0.6 * coarse.0, "{coarse:?} {fine:?}");
    assert!(fine.1 < 0.05, "{fine:?}");
}

/// A full-width linear spring interface (smooth) on the skewed mesh: the error falls at
/// second order (measured 4.7e-3 and 1.16e-3 of the max gap at 4 and 8 elements a
/// wavelength; the rectangle's strip 6.5e-3 and 1.6e-3).
#[test]
fn a_linear_interface_reduces_at_second_order_on_a_skewed_periodic_mesh() {
    let (law_2d, law) = linear_spring(1e6, 1e14);
    let (_, law_fine) = linear_spring(1e6, 1e14);
    let coarse = skewed_reduction(law_2d.clone(), law, 0.25);
    let fine = skewed_reduction(law_2d, law_fine, 0.125);
    eprintln!("skewed mesh 1D reduction (linear spring), (error, spread) / max gap: {coarse:?} at 4 per wavelength, {fine:?} at 8");
    assert!(fine.0 < 2e-3, "{fine:?}");
    assert!(
        fine.0 < coarse.0 / 3.5,
        "observed order below 1.8: {coarse:?} {fine:?}"
    );
}

/// Curves that are not translates of each other, and a crack that ends on one periodic
/// side but not on its partner, are refused in one line naming the key.
#[test]
fn periodic_curves_that_do_not_match_are_refused() {
    let f0 = 1e6;
    let lambda = ALUMINIUM.p_speed / f0;
    let h = 0.25 * lambda;
    let xs: Vec<f64> = (0..=3).map(|i| i as f64 * h).collect();
    let zs: Vec<f64> = (0..=8).map(|j| j as f64 * h).collect();
    let base = |lines: &[(&str, [f64; 2], [f64; 2])], periodic: (&str, &str)| {
        let input = QuadInput::grid(
            &xs,
            &zs,
            &|p| p,
            vec!["aluminium".into()],
            &|_| 0,
            lines,
            false,
        );
        let cracks: Vec<&str> = lines
            .iter()
            .map(|l| l.0)
            .filter(|&n| n == "crack")
            .collect();
        strip_on(
            input,
            periodic,
            &cracks,
            signorini(1e6),
            burst(1e6, f0, 2.0),
            1e-6,
        )
    };
    let msg = |q: QuadSolid<_>| q.check("strip.toml").unwrap_err().to_string();
    // the top is 3 edges, the left 8
    let e = msg(base(&[], ("left", "top")));
    assert!(e.contains("strip.toml") && e.contains("periodic"), "{e}");
    assert!(!e.contains('\n'), "{e}");
    // a crack from the left side to the middle: its mouth on `left` has no partner
    let e = msg(base(
        &[("crack", [0.0, 4.0 * h], [2.0 * h, 4.0 * h])],
        ("left", "right"),
    ));
    assert!(e.contains("crack.0") && e.contains("periodic side"), "{e}");
    // across: accepted
    base(
        &[("crack", [0.0, 4.0 * h], [3.0 * h, 4.0 * h])],
        ("left", "right"),
    )
    .check("strip.toml")
    .unwrap();
}

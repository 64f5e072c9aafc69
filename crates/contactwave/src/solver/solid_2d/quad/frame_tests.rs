//! The PML frame of a mesh ([`super::frame`]): on the rectangle's own grid it is the
//! rectangle's absorbing layers (the same run to round-off); on a mesh whose elements are
//! general it closes the energy audit and absorbs what dashpots reflect; sides it cannot
//! frame are refused by name.

use super::input::QuadInput;
use super::*;
use crate::solver::solid_2d::tests::{burst, clapping_plate, ALUMINIUM};
use crate::solver::solid_2d::{Energy2d, Side};

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The clapping plate with absorbing sides and bottom (and top: the transducer on the
/// frame's inner edge, the corners filled): the rectangle's run against the same plate on
/// a mesh of its own grid with a PML frame of the same layers, at one time step:
/// receivers and crack gaps within 1e-9 of their peaks (measured: 2e-16), the same
/// absorbed energy, both audits closed.
#[test]
fn a_framed_mesh_of_the_rectangle_grid_is_the_rectangle_run() {
    for top in [Side::Free, Side::Absorbing] {
        let mut rect = clapping_plate(Side::Absorbing);
        rect.bottom = Side::Absorbing;
        rect.top = top;
        rect.duration = 5e-6;
        let dt = 0.9 * rect.plan("<test>").unwrap().dt;
        rect.max_time_step = dt;
        let a = rect.plan("<test>").unwrap().run().unwrap();
        let quad = QuadSolid::of_rectangle(&rect, &|p| p, "<test>")
            .unwrap()
            .expect("absorbing sides carry over as a frame");
        let plan = quad.plan("<test>").unwrap();
        assert_eq!(plan.dt, dt);
        assert_eq!(plan.frame_layers, 4);
        assert!(plan.nodes > plan.mesh.n_nodes());
        let b = plan.run().unwrap();
        assert_eq!(a.receivers.len(), b.receivers.len());
        let scale = max_abs(&a.receivers);
        let err = max_diff(&a.receivers, &b.receivers);
        assert!(scale > 0.0);
        assert!(
            err < 1e-9 * scale,
            "{top:?}: receivers differ by {err:e} of {scale:e}"
        );
        let (ca, cb) = (&a.cracks[0], &b.cracks[0]);
        let gap = max_abs(&ca.normal_gap);
        assert!(gap > 1e-12, "the crack claps: {gap:e}");
        let err = max_diff(&ca.normal_gap, &cb.normal_gap);
        assert!(
            err < 1e-9 * gap,
            "{top:?}: gaps differ by {err:e} of {gap:e}"
        );
        let (ea, eb) = (&a.energy, &b.energy);
        assert!(ea.absorbed > 0.5 * ea.input, "{ea:?}");
        assert!(
            (ea.absorbed - eb.absorbed).abs() < 1e-9 * ea.input,
            "{ea:?} {eb:?}"
        );
        assert!(eb.closure_error() < 1e-9, "{eb:?}");
    }
}

/// A 10 x 10 mm aluminium plate on a mesh of 0.5 mm elements whose inner nodes are moved
/// (the inner elements general; the sides stay straight), a 1 MHz point force at its
/// centre at order 4 (6 elements an S wavelength), every side absorbing: by a PML frame,
/// then by dashpots. Returns the energy audit after the waves have left, and the energy
/// left in the plate over the input.
fn radiating(kind: Boundary) -> (Energy2d, f64) {
    use std::f64::consts::PI;
    let (w, h) = (10e-3, 0.5e-3);
    let edges: Vec<f64> = (0..=20).map(|i| i as f64 * h).collect();
    let wobble = move |[x, z]: [f64; 2]| {
        let s = (PI * x / w).sin() * (PI * z / w).sin();
        [
            x + 0.2 * h * s * (3.0 * PI * z / w).sin(),
            z + 0.2 * h * s * (2.0 * PI * x / w).cos(),
        ]
    };
    let input = QuadInput::grid(
        &edges,
        &edges,
        &wobble,
        vec!["al".into()],
        &|_| 0,
        &[],
        false,
    );
    let q = QuadSolid {
        input: Arc::new(input),
        order: 4,
        materials: vec![ALUMINIUM],
        wave: WaveType::PSv,
        courant: 0.5,
        max_time_step: f64::INFINITY,
        boundaries: ["top", "bottom", "left", "right"]
            .iter()
            .map(|s| (s.to_string(), kind))
            .collect(),
        periodic: Vec::new(),
        cracks: Vec::<QuadCrack<crate::law::point::SharedLaw>>::new(),
        sources: vec![QuadSource {
            kind: QuadSourceKind::Force {
                at: [0.5 * w, 0.5 * w],
                direction: [0.6, 0.8],
            },
            signal: burst(1e3, 1e6, 2.0),
        }],
        receivers: vec![[0.2 * w, 0.3 * w]],
        stress_receivers: Vec::new(),
        // the S wave's tail leaves the plate's far corner after about 3.7 us
        duration: 6e-6,
        crack_every: usize::MAX,
        pml: None,
    };
    let plan = q.plan("<test>").unwrap();
    assert!(plan.mesh.rectangle.iter().any(|r| !r), "general elements");
    let out = plan.run().unwrap();
    let e = out.energy;
    (e, e.solid / e.input)
}

/// On the general mesh the frame's run closes its audit at round-off (the flux into the
/// frame counted as absorbed) and leaves in the plate under 1e-5 of the input, a
/// hundredth of what dashpots leave (measured: 1.2e-6 against 5.3e-4).
#[test]
fn a_frame_on_general_elements_absorbs_what_dashpots_reflect() {
    let (pml, left_pml) = radiating(Boundary::Pml);
    let (dash, left_dash) = radiating(Boundary::Absorbing);
    assert!(pml.closure_error() < 1e-9, "{pml:?}");
    assert!(dash.closure_error() < 1e-9, "{dash:?}");
    assert!(
        left_pml < 1e-5,
        "left in the plate with a frame: {left_pml:e}"
    );
    assert!(
        left_pml < 1e-2 * left_dash,
        "frame {left_pml:e}, dashpots {left_dash:e}"
    );
}

/// Sides a frame cannot go around are refused, each naming its curve: one off the
/// bounding box (a rotated plate), one meeting a periodic side, one that a crack's mouth
/// reaches.
#[test]
fn sides_a_frame_cannot_take_are_refused_by_name() {
    let mut rect = clapping_plate(Side::Absorbing);
    rect.bottom = Side::Absorbing;
    let (s, c) = 30f64.to_radians().sin_cos();
    let rotate = move |p: [f64; 2]| [c * p[0] - s * p[1], s * p[0] + c * p[1]];
    let q = QuadSolid::of_rectangle(&rect, &rotate, "<test>")
        .unwrap()
        .unwrap();
    let e = q.plan("<test>").unwrap_err().to_string();
    assert!(
        e.contains("boundary `bottom`") && e.contains("bounding box"),
        "{e}"
    );
    // a periodic strip with a framed bottom
    rect.sides = Side::Periodic;
    rect.cracks.clear();
    let q = QuadSolid::of_rectangle(&rect, &|p| p, "<test>")
        .unwrap()
        .unwrap();
    let e = q.plan("<test>").unwrap_err().to_string();
    assert!(e.contains("periodic"), "{e}");
    // a crack from the free top into the plate, its mouth on a framed top
    let mut rect = clapping_plate(Side::Free);
    rect.cracks[0].start = [6e-3, 0.0];
    rect.cracks[0].end = [6e-3, 2e-3];
    let mut q = QuadSolid::of_rectangle(&rect, &|p| p, "<test>")
        .unwrap()
        .unwrap();
    q.boundaries = vec![("top".into(), Boundary::Pml)];
    let e = q.plan("<test>").unwrap_err().to_string();
    assert!(e.contains("boundary `top`") && e.contains("crack"), "{e}");
}

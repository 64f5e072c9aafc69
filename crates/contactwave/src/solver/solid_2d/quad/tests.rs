//! Tests of the quadrilateral-mesh path: on the rectangle's own grid it is the rectangle's
//! run (the same traces and crack fields to round-off); the same specimen rotated gives the
//! rotated run; on a skewed, curved second-order mesh with an inclined curved crack the
//! energy closes at round-off, no point penetrates, a crack closed beyond the wave's
//! stress never opens and reciprocity holds; a crack made as an interface between two
//! parts is the crack made by splitting one mesh; the Gmsh reader reads a file and refuses
//! what the solver cannot use.

use super::input::QuadInput;
use super::*;
use crate::solver::solid_2d::tests::{burst, clapping_plate, signorini, Signorini, ALUMINIUM};
use crate::solver::solid_2d::{Side, Solid2d, Solid2dOutput};

/// The grid lines of the structured problem's mesh (no absorbing layers).
fn grid_of(p: &Solid2d<Signorini>) -> (Vec<f64>, Vec<f64>) {
    let plan = p.plan("<test>").unwrap();
    (plan.mesh.x_edges.clone(), plan.mesh.z_edges.clone())
}

/// The clapping plate of the rectangle's tests on a quadrilateral mesh of its own grid,
/// mapped by `map` (the sources, crack and receivers mapped with it).
fn clapping_quad(
    map: &dyn Fn([f64; 2]) -> [f64; 2],
    second_order: bool,
    dt: f64,
) -> QuadSolid<Signorini> {
    let p = clapping_plate(Side::Free);
    let (xs, zs) = grid_of(&p);
    let c = &p.cracks[0];
    let input = QuadInput::grid(
        &xs,
        &zs,
        map,
        vec!["aluminium".into()],
        &|_| 0,
        &[
            ("crack", c.start, c.end),
            ("wedge", [3e-3, 0.0], [5e-3, 0.0]),
        ],
        second_order,
    );
    QuadSolid {
        input: Arc::new(input),
        order: p.order,
        materials: vec![ALUMINIUM],
        wave: WaveType::PSv,
        courant: p.courant,
        max_time_step: dt,
        boundaries: Vec::new(),
        periodic: Vec::new(),
        cracks: vec![QuadCrack {
            curve: "crack".into(),
            law: signorini(1e6),
            profile: None,
        }],
        sources: vec![QuadSource {
            kind: QuadSourceKind::Traction {
                curve: "wedge".into(),
                normal: true,
                delay_per_m: 0.0,
            },
            signal: burst(10e6, 2e6, 3.0),
        }],
        receivers: p.receivers.iter().map(|&r| map(r)).collect(),
        stress_receivers: Vec::new(),
        duration: p.duration,
        crack_every: 1,
        pml: None,
    }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
}

/// The rectangle's time step, a little under its own (both paths then take it).
fn common_dt() -> f64 {
    0.95 * clapping_plate(Side::Free).plan("<test>").unwrap().dt
}

/// On the rectangle's own grid (every element on the fast path), with the same time step,
/// the quadrilateral path's run is the rectangle's: receiver traces and the crack's gaps
/// within 1e-9 of their peaks (the sums run in another order), the same energies; a
/// stress receiver at an element's interior GLL node reads the rectangle's stress there.
#[test]
fn the_rectangle_grid_gives_the_rectangle_run() {
    let dt = common_dt();
    let mut rect = clapping_plate(Side::Free);
    rect.max_time_step = dt;
    // the centre node of the element [4, 4.5] x [1, 1.5] mm (order 4)
    let at = [4.25e-3, 1.25e-3];
    let mut plan = rect.plan("<test>").unwrap();
    plan.add_stress_receivers(&[at], &rect.layers, "<test>")
        .unwrap();
    let a = plan.run().unwrap();
    let mut q = clapping_quad(&|p| p, false, dt);
    q.stress_receivers = vec![at];
    let quad = q.plan("<test>").unwrap();
    assert!(quad.mesh.rectangle.iter().all(|&r| r));
    assert_eq!(quad.dt, dt);
    let b = quad.run().unwrap();
    assert_eq!(a.time.len(), b.time.len());
    let scale = max_abs(&a.receivers);
    let err = a
        .receivers
        .iter()
        .zip(&b.receivers)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        scale > 0.0 && err < 1e-9 * scale,
        "receivers differ by {err:e} of {scale:e}"
    );
    let (ca, cb) = (&a.cracks[0], &b.cracks[0]);
    assert_eq!(ca.position.len(), cb.position.len());
    assert!(ca.peak_normal_gap > 1e-10);
    let g = (ca.peak_normal_gap - cb.peak_normal_gap).abs();
    assert!(
        g < 1e-8 * ca.peak_normal_gap,
        "peak gap {:e} vs {:e}",
        ca.peak_normal_gap,
        cb.peak_normal_gap
    );
    let gap_err = ca
        .normal_gap
        .iter()
        .zip(&cb.normal_gap)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        gap_err < 1e-8 * ca.peak_normal_gap,
        "gaps differ by {gap_err:e}"
    );
    assert!((a.energy.input - b.energy.input).abs() < 1e-9 * a.energy.input);
    assert!(b.energy.closure_error() < 1e-9, "{:?}", b.energy);
    let scale = max_abs(&a.stresses);
    let err = a
        .stresses
        .iter()
        .zip(&b.stresses)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        scale > 1e5 && a.stresses.len() == b.stresses.len() && err < 1e-9 * scale,
        "stresses differ by {err:e} of {scale:e} Pa"
    );
}

/// The same specimen, crack and source rotated by 30 and by 45 degrees: every element on
/// the general path, and the receivers' velocities are the aligned run's rotated, within
/// 1e-9 of their peak (the discrete problem is the same one rotated), and stress
/// receivers inside elements read the aligned stress tensor rotated, `R sigma R^T`.
#[test]
fn a_rotated_specimen_gives_the_rotated_run() {
    let dt = common_dt();
    let stress_at = [[4.13e-3, 1.17e-3], [1.31e-3, 3.2e-3]];
    let mut q = clapping_quad(&|p| p, false, dt);
    q.stress_receivers = stress_at.to_vec();
    let aligned = q.plan("<test>").unwrap().run().unwrap();
    let sigma_scale = max_abs(&aligned.stresses);
    let scale = max_abs(&aligned.receivers);
    for deg in [30.0f64, 45.0] {
        let (s, c) = deg.to_radians().sin_cos();
        let rot = move |p: [f64; 2]| [c * p[0] - s * p[1], s * p[0] + c * p[1]];
        let mut q = clapping_quad(&rot, false, dt);
        q.stress_receivers = stress_at.iter().map(|&p| rot(p)).collect();
        let plan = q.plan("<test>").unwrap();
        assert!(plan.mesh.rectangle.iter().all(|&r| !r));
        let out = plan.run().unwrap();
        let n = out.time.len();
        let mut err = 0.0f64;
        for r in 0..2 {
            for k in 0..n {
                let (vx, vz) = (aligned.trace(r, 0)[k], aligned.trace(r, 1)[k]);
                let want = rot([vx, vz]);
                err = err.max((out.trace(r, 0)[k] - want[0]).abs());
                err = err.max((out.trace(r, 1)[k] - want[1]).abs());
            }
        }
        assert!(err < 1e-9 * scale, "{deg} degrees: {err:e} of {scale:e}");
        let mut err = 0.0f64;
        for r in 0..2 {
            for k in 0..n {
                let t = |o: &Solid2dOutput, cc| o.stress_trace(r, cc)[k];
                let (xx, zz, xz) = (t(&aligned, 0), t(&aligned, 1), t(&aligned, 2));
                let want = [
                    c * c * xx - 2.0 * c * s * xz + s * s * zz,
                    s * s * xx + 2.0 * c * s * xz + c * c * zz,
                    c * s * (xx - zz) + (c * c - s * s) * xz,
                ];
                for (cc, w) in want.iter().enumerate() {
                    err = err.max((t(&out, cc) - w).abs());
                }
            }
        }
        assert!(
            sigma_scale > 1e5 && err < 1e-9 * sigma_scale,
            "{deg} degrees: stresses {err:e} of {sigma_scale:e} Pa"
        );
        let g = (out.cracks[0].peak_normal_gap - aligned.cracks[0].peak_normal_gap).abs();
        assert!(g < 1e-8 * aligned.cracks[0].peak_normal_gap);
    }
}

/// A skewed and bent map: straight grid lines become inclined curves.
fn bend(p: [f64; 2]) -> [f64; 2] {
    [
        p[0] + 0.35 * p[1],
        p[1] + 0.25e-3 * (2.0 * std::f64::consts::PI * p[0] / 8e-3).sin(),
    ]
}

/// On a skewed, curved second-order mesh with an inclined, curved clapping crack (free
/// sides: a closed domain): the energy audit closes at round-off, no point penetrates
/// (`U_N >= 0` at every point and record) and the crack opens and closes again.
#[test]
fn a_curved_mesh_with_an_inclined_crack_closes_the_energy() {
    let plan = clapping_quad(&bend, true, f64::INFINITY)
        .plan("<test>")
        .unwrap();
    assert!(plan.mesh.rectangle.iter().all(|&r| !r));
    let out = plan.run().unwrap();
    let e = out.energy;
    assert!(e.input > 0.0);
    assert!(
        e.closure_error() < 1e-9,
        "{e:?}: closure {:e}",
        e.closure_error()
    );
    let rec = &out.cracks[0];
    assert!(
        rec.peak_normal_gap > 1e-10,
        "never opened: {:e}",
        rec.peak_normal_gap
    );
    let least = rec.normal_gap.iter().fold(f64::INFINITY, |a, &b| a.min(b));
    assert!(
        least >= -1e-12 * rec.peak_normal_gap,
        "penetration {least:e}"
    );
    // the normals vary along the curved crack: not one value
    let n0 = plan.cracks[0].normal[0];
    assert!(plan.cracks[0]
        .normal
        .iter()
        .any(|n| (n[0] - n0[0]).abs() > 1e-3));
}

/// The same curved mesh with the crack pressed far beyond the wave's stress (1 GPa under a
/// 10 kPa burst): it never opens, the run is linear, and a point force at A read at B
/// equals the force at B read at A (reciprocity, to 1e-6 of the peak).
#[test]
fn a_closed_crack_never_opens_and_the_run_is_reciprocal() {
    let a = [2.0e-3, 1.0e-3];
    let b = [6.0e-3, 3.2e-3];
    let (da, db) = ([0.6, 0.8], [1.0, 0.0]);
    let run = |at: [f64; 2], dir: [f64; 2], at_r: [f64; 2]| {
        let mut p = clapping_quad(&bend, true, f64::INFINITY);
        p.cracks[0].law = signorini(1e9);
        p.sources = vec![QuadSource {
            kind: QuadSourceKind::Force {
                at: bend(at),
                direction: dir,
            },
            signal: burst(1e4, 2e6, 3.0),
        }];
        p.receivers = vec![bend(at_r)];
        p.plan("<test>").unwrap().run().unwrap()
    };
    let ab = run(a, da, b);
    let ba = run(b, db, a);
    assert_eq!(ab.cracks[0].peak_normal_gap, 0.0);
    assert_eq!(ba.cracks[0].peak_normal_gap, 0.0);
    // v_B . db from the force at A along da, and v_A . da from the force at B along db
    let n = ab.time.len();
    let g_ab: Vec<f64> = (0..n)
        .map(|k| ab.trace(0, 0)[k] * db[0] + ab.trace(0, 1)[k] * db[1])
        .collect();
    let g_ba: Vec<f64> = (0..n)
        .map(|k| ba.trace(0, 0)[k] * da[0] + ba.trace(0, 1)[k] * da[1])
        .collect();
    let scale = max_abs(&g_ab);
    let err = g_ab
        .iter()
        .zip(&g_ba)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        scale > 0.0 && err < 1e-6 * scale,
        "reciprocity: {err:e} of {scale:e}"
    );
}

/// A plan runs twice to the same bits (each run from rest), and on one thread as on many.
#[test]
fn runs_repeat_bit_for_bit_for_any_thread_count() {
    let plan = clapping_quad(&bend, true, f64::INFINITY)
        .plan("<test>")
        .unwrap();
    let a = plan.run().unwrap();
    let b = plan.run().unwrap();
    assert_eq!(a.receivers, b.receivers);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let c = one.install(|| plan.run().unwrap());
    assert_eq!(a.receivers, c.receivers);
    assert_eq!(a.cracks[0].normal_gap, c.cracks[0].normal_gap);
}

/// A minimal MSH 4.1 file: two unit squares side by side (nodes 1-6), the curve "top"
/// (y = 0) and the surface "steel"; `tri` makes the second element a triangle.
fn tiny_msh(tri: bool) -> String {
    let el = if tri {
        "2 1 2 1\n2 2 3 6\n"
    } else {
        "2 1 3 1\n2 2 3 6 5\n"
    };
    format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"top\"\n2 2 \"steel\"\n\
         $EndPhysicalNames\n$Entities\n0 1 1 0\n1 0 0 0 2 0 0 1 1 0\n1 0 0 0 2 1 0 1 2 1 1\n\
         $EndEntities\n$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n\
         1 1 0\n2 1 0\n$EndNodes\n$Elements\n3 4 1 4\n1 1 1 2\n3 1 2\n4 2 3\n2 1 3 1\n1 1 2 5 4\n\
         {el}$EndElements\n"
    )
}

#[test]
fn the_gmsh_reader_reads_groups_and_refuses_triangles() {
    let input = gmsh::read(tiny_msh(false).as_bytes(), "tiny.msh").unwrap();
    assert_eq!(input.quads.len(), 2);
    assert_eq!(input.materials, vec!["steel".to_string()]);
    assert_eq!(input.curve("top").map(|s| s.len()), Some(2));
    let mesh = geometry::Mesh::build(&input, 4).unwrap();
    // two elements of order 4 sharing an edge: 9 x 5 nodes
    assert_eq!(mesh.n_nodes(), 45);
    let e = gmsh::read(tiny_msh(true).as_bytes(), "tiny.msh")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("tiny.msh: field `element 2`") && e.contains("recombine"),
        "{e}"
    );
    let e = gmsh::read(b"hello", "x.msh").unwrap_err().to_string();
    assert!(e.contains("MSH 4.1"), "{e}");
}

/// Errors name the entity: a crack group that is not in the mesh, a crack on the
/// boundary, a receiver outside the mesh, a degenerate element.
#[test]
fn unusable_meshes_and_keys_are_refused_in_one_line() {
    let dt = f64::INFINITY;
    let mut p = clapping_quad(&|p| p, false, dt);
    p.cracks[0].curve = "krack".into();
    let e = p.plan("s.toml").unwrap_err().to_string();
    assert!(e.contains("`krack`") && e.contains("crack, wedge"), "{e}");
    let mut p = clapping_quad(&|p| p, false, dt);
    p.cracks[0].curve = "top".into();
    let e = p.plan("s.toml").unwrap_err().to_string();
    assert!(e.contains("inside the mesh"), "{e}");
    let mut p = clapping_quad(&|p| p, false, dt);
    p.receivers[0] = [9e-3, 1e-3];
    let e = p.plan("s.toml").unwrap_err().to_string();
    assert!(e.contains("receiver.0.at"), "{e}");
    let mut p = clapping_quad(&|p| p, false, dt);
    let mut input = (*p.input).clone();
    input.nodes[input.quads[3][2] as usize] = input.nodes[input.quads[3][0] as usize];
    p.input = Arc::new(input);
    let e = p.plan("s.toml").unwrap_err().to_string();
    assert!(e.contains("element 4") && e.contains("degenerate"), "{e}");
}

/// Two parts meshed apart (the plate's upper and lower halves, their nodes coincident
/// along z = 2 mm) joined by a contact interface along part of their common boundary (the
/// rest welded by the coincident nodes): the run of the crack made by splitting one mesh,
/// to round-off.
#[test]
fn an_interface_between_two_parts_is_the_split_crack() {
    let one = clapping_quad(&|p| p, false, f64::INFINITY);
    let (xs, zs) = grid_of(&clapping_plate(Side::Free));
    let cut = zs.iter().position(|&z| (z - 2e-3).abs() < 1e-12).unwrap();
    let crack = ("crack", [2.5e-3, 2e-3], [5.5e-3, 2e-3]);
    let wedge = ("wedge", [3e-3, 0.0], [5e-3, 0.0]);
    let id = |p: [f64; 2]| p;
    let upper = QuadInput::grid(
        &xs,
        &zs[..=cut],
        &id,
        vec!["aluminium".into()],
        &|_| 0,
        &[crack, wedge],
        false,
    );
    let lower = QuadInput::grid(
        &xs,
        &zs[cut..],
        &id,
        vec!["aluminium".into()],
        &|_| 0,
        &[crack],
        false,
    );
    // the lower part after the upper one, its nodes renumbered
    let mut both = upper.clone();
    let shift = both.nodes.len() as u32;
    both.nodes.extend(&lower.nodes);
    both.quads
        .extend(lower.quads.iter().map(|q| q.map(|k| k + shift)));
    both.material.extend(&lower.material);
    for (name, segs) in &lower.curves {
        let segs = segs.iter().map(|s| s.map(|k| k + shift));
        match both.curves.iter_mut().find(|c| &c.0 == name) {
            Some(c) if name == "crack" => c.1.extend(segs),
            Some(_) => {}
            None => both.curves.push((name.clone(), segs.collect())),
        }
    }
    let mut two = one.clone();
    two.input = Arc::new(both);
    let (a, b) = (one.plan("<test>").unwrap(), two.plan("<test>").unwrap());
    assert_eq!(a.mesh.n_nodes(), b.mesh.n_nodes());
    assert_eq!(a.dt, b.dt);
    let (a, b) = (a.run().unwrap(), b.run().unwrap());
    assert_eq!(a.receivers, b.receivers);
    assert_eq!(a.cracks[0].normal_gap, b.cracks[0].normal_gap);
}

/// Every example mesh reads, splits its cracks (a mouth on the bottom surface, a crack
/// from a hole, an interface between two plates, a curved delamination) and runs a
/// microsecond with the energy closed at round-off (free sides).
#[test]
fn the_example_meshes_build_and_close_their_energy() {
    let root =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/solid_2d/mesh");
    for (file, crack, wedge, order) in [
        ("inclined_crack/plate.msh", "crack", "wedge", 3),
        ("rivet_hole/plate.msh", "crack", "wedge", 2),
        ("lap_joint/joint.msh", "joint", "wedge", 3),
        ("curved_delamination/shell.msh", "delamination", "wedge", 3),
        ("rotated/plate_30.msh", "crack", "wedge", 3),
    ] {
        let bytes = std::fs::read(root.join(file)).unwrap();
        let input = gmsh::read(&bytes, file).unwrap();
        let at = input.nodes[input.quads[0][0] as usize];
        let p = QuadSolid {
            materials: vec![ALUMINIUM; input.materials.len()],
            input: Arc::new(input),
            order,
            wave: WaveType::PSv,
            courant: 0.8,
            max_time_step: f64::INFINITY,
            boundaries: Vec::new(),
            periodic: Vec::new(),
            cracks: vec![QuadCrack {
                curve: crack.into(),
                law: signorini(1e5),
                profile: None,
            }],
            sources: vec![QuadSource {
                kind: QuadSourceKind::Traction {
                    curve: wedge.into(),
                    normal: true,
                    delay_per_m: 0.0,
                },
                signal: burst(10e6, 2e6, 2.0),
            }],
            receivers: vec![at],
            stress_receivers: Vec::new(),
            duration: 1e-6,
            crack_every: 10,
            pml: None,
        };
        let plan = p.plan(file).unwrap_or_else(|e| panic!("{file}: {e}"));
        let out = plan.run().unwrap();
        let e = out.energy;
        assert!(e.input > 0.0 && e.closure_error() < 1e-9, "{file}: {e:?}");
        assert!(!out.cracks[0].position.is_empty());
    }
}

/// The batched kernel (eight elements a batch, the production path) gives the scalar
/// element loop's forces to round-off (the even-odd derivative, and the sums in another
/// order), on rectangles and on curved general elements, in plane strain and antiplane, on
/// every instruction set the CPU runs (its own and the lesser ones).
#[test]
fn the_batched_kernel_is_the_scalar_loop_to_round_off() {
    for (map, second) in [
        (&(|p: [f64; 2]| p) as &dyn Fn([f64; 2]) -> [f64; 2], false),
        (&bend, true),
    ] {
        for antiplane in [false, true] {
            let plan = clapping_quad(map, second, f64::INFINITY)
                .plan("<test>")
                .unwrap();
            let lame = vec![[ALUMINIUM.lambda(), ALUMINIUM.mu()]; plan.mesh.n_elements()];
            let reference = kernel::Operator::new(&plan.mesh, lame.clone(), antiplane);
            let c = if antiplane { 1 } else { 2 };
            let len = c * plan.mesh.n_nodes();
            let u: Vec<f64> = (0..len)
                .map(|i| ((i * 7919) % 101) as f64 * 1e-9 - 5e-8)
                .collect();
            let mut b = vec![0.0; len];
            reference.add_forces_serial(&plan.mesh, &u, &mut b);
            let scale = max_abs(&b);
            // the CPU's own instruction set, and the lesser ones it also runs
            use super::lanes::Isa;
            for isa in [Isa::Avx512, Isa::Avx2, Isa::Portable] {
                let runs = match reference.isa() {
                    Isa::Avx512 => true,
                    Isa::Avx2 => isa != Isa::Avx512,
                    Isa::Portable => isa == Isa::Portable,
                };
                if !runs {
                    continue;
                }
                let op = kernel::Operator::on(isa, &plan.mesh, lame.clone(), antiplane);
                let mut a = vec![0.0; len];
                op.add_forces(&u, &mut a);
                let err = a
                    .iter()
                    .zip(&b)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max);
                assert!(
                    scale > 0.0 && err <= 1e-13 * scale,
                    "{isa:?}, antiplane {antiplane}, second order {second}: {err:e} of {scale:e}"
                );
            }
        }
    }
}

/// Pictures on a mesh: on a grid rotated by 30 degrees (affine elements), a velocity field
/// that is a polynomial of degree `order` in x and z is resampled by the elements' Lagrange
/// interpolants to round-off at every pixel inside the rotated plate, pixels outside it are
/// NaN, the outline is the plate's rim (its length the perimeter) and the sub-cells tile the
/// plate (their areas sum to the plate's).
#[test]
fn pictures_on_a_mesh_interpolate_inside_and_leave_the_outside_blank() {
    use crate::solver::solid_2d::snapshot::{Capture, Field};
    let (s, c) = 30f64.to_radians().sin_cos();
    let rot = move |p: [f64; 2]| [c * p[0] - s * p[1], s * p[0] + c * p[1]];
    let xs: Vec<f64> = (0..=6).map(|i| i as f64 * 1e-3).collect();
    let zs: Vec<f64> = (0..=3).map(|i| i as f64 * 1e-3).collect();
    let input = QuadInput::grid(&xs, &zs, &rot, vec!["al".into()], &|_| 0, &[], false);
    let order = 4;
    let mesh = geometry::Mesh::build(&input, order).unwrap();
    // vx = (x/L)^4 - 2 (x/L)(z/L)^3 + 1, vz = (z/L)^2 (x/L): degree <= 4
    let l = 1e-3;
    let f = |p: [f64; 2]| {
        let (x, z) = (p[0] / l, p[1] / l);
        [x.powi(4) - 2.0 * x * z.powi(3) + 1.0, z * z * x]
    };
    let mut cap = Capture::new(vec![0], 2 * mesh.n_nodes());
    let v: Vec<f64> = mesh.position.iter().flat_map(|&p| f(p)).collect();
    cap.take(0, 0.5, &v);
    let (lo, hi) = raster::bounds(&mesh);
    let r = raster::raster(&mesh, 2, &cap, Field::Component(0), 80, lo, hi);
    let rz = raster::raster(&mesh, 2, &cap, Field::Component(1), 80, lo, hi);
    let m = raster::raster(&mesh, 2, &cap, Field::Magnitude, 80, lo, hi);
    assert_eq!(r.frames(), 1);
    // inside: the pixel rotated back lies in the aligned plate
    let back = |p: [f64; 2]| [c * p[0] + s * p[1], -s * p[0] + c * p[1]];
    let (mut inside, mut outside, mut err) = (0, 0, 0.0f64);
    let scale = 6f64.powi(4);
    for (iz, &z) in r.z.iter().enumerate() {
        for (ix, &x) in r.x.iter().enumerate() {
            let k = iz * r.x.len() + ix;
            let q = back([x, z]);
            let margin = 1e-9;
            let within =
                q[0] > margin && q[0] < 6e-3 - margin && q[1] > margin && q[1] < 3e-3 - margin;
            let beyond =
                q[0] < -margin || q[0] > 6e-3 + margin || q[1] < -margin || q[1] > 3e-3 + margin;
            let want = f([x, z]);
            if within {
                inside += 1;
                err = err.max((r.values[k] - want[0]).abs() / scale);
                err = err.max((rz.values[k] - want[1]).abs() / scale);
                let mag = (want[0] * want[0] + want[1] * want[1]).sqrt();
                err = err.max((m.values[k] - mag).abs() / scale);
            } else if beyond {
                outside += 1;
                assert!(
                    r.values[k].is_nan() && m.values[k].is_nan(),
                    "pixel {ix},{iz}"
                );
            }
        }
    }
    assert!(
        inside > 1000 && outside > 1000,
        "{inside} inside, {outside} outside"
    );
    assert!(
        err < 1e-12,
        "interpolation error {err:e} of the field's scale"
    );
    let rim: f64 = raster::outline(&mesh)
        .iter()
        .map(|g| ((g[2] - g[0]).powi(2) + (g[3] - g[1]).powi(2)).sqrt())
        .sum();
    assert!((rim - 18e-3).abs() < 1e-12, "outline length {rim:e}");
    let area: f64 = raster::sub_cells(&mesh)
        .iter()
        .map(|q| {
            let p: Vec<[f64; 2]> = q.iter().map(|&i| mesh.position[i as usize]).collect();
            0.5 * (0..4)
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % 4]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum::<f64>()
        })
        .sum();
    assert!((area.abs() - 18e-6).abs() < 1e-15, "sub-cell area {area:e}");
}

//! The finite-difference bar-stack solver (issue 3): Courant-1 exactness and
//! cross-validation against the exact half-space solver.

use crate::common::*;
use contactwave::excitation::{ToneBurst, Window};
use contactwave::material::Material;
use contactwave::solver::bar_stack::{BarStack, End, FdRun, Segment};
use std::sync::Arc;

/// At Courant number 1 a pulse crosses a uniform bar unchanged (to 1e-12).
#[test]
fn courant_one_pulse_crosses_unchanged() {
    let f = 1e6;
    let spp = 50.0;
    let dt = 1.0 / (f * spp);
    let m = Material::ALUMINIUM;
    let dx = m.wave_speed() * dt;
    let len = 400.0 * dx;
    let burst = Arc::new(ToneBurst::new(1e6, f, 3.0, Window::Hann));
    let stack = BarStack {
        area: 1.0,
        segments: vec![Segment {
            name: "bar".into(),
            length: len,
            material: m,
            damping: 0.0,
        }],
        interfaces: vec![],
        left: End::Transparent,
        right: End::Transparent,
        incident: Some(burst),
        shear: None,
    };
    let mesh = stack.mesh(dt);
    assert_eq!(mesh.cells[0], 400);
    assert!((mesh.courant[0] - 1.0).abs() < 1e-12);
    let (p1, p2) = (100usize, 300usize);
    let run = FdRun {
        dt,
        t0: -len / m.wave_speed(),
        steps: 1000,
        record_every: 1,
        probes: vec![p1, p2],
        ..FdRun::default()
    };
    let out = stack.run(&run).unwrap();
    let lag = p2 - p1; // steps for 200 cells at Courant 1
    let a = &out.displacement[0];
    let b = &out.displacement[1];
    let peak = max_abs(a);
    assert!(peak > 0.0);
    let mut err = 0.0f64;
    for k in 0..a.len() - lag {
        err = err.max((b[k + lag] - a[k]).abs());
    }
    assert!(err < 1e-12 * peak, "relative error {:e}", err / peak);
    // and nothing is reflected by the transparent ends: the bar is at rest at the end
    assert!(max_abs(&a[a.len() - 50..]) < 1e-12 * peak);
}

fn compare(law: &str, xi: f64, spp: Option<usize>) -> (f64, f64) {
    let base = pmma(
        &format!("static_pressure = 0.14e6\n{law}"),
        &format!("cycles = 15\nxi = {xi}"),
    );
    let exact = run(&format!("{base}[solver]\ntail_periods = 100\n"));
    let spp = spp
        .map(|s| format!("samples_per_period = {s}\n"))
        .unwrap_or_default();
    let fd = run(&format!(
        "{base}[solver]\nmethod = \"fd\"\ntail_periods = 100\n{spp}"
    ));
    let rel = |k: &str| (get(&fd, k) - get(&exact, k)).abs() / get(&exact, k);
    (rel("A1_over_Ainc"), rel("A2_over_Ainc"))
}

const LAWS: [&str; 4] = [
    "",
    "traction = { law = \"rccm\", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }",
    "compression = { law = \"linear\", stiffness = 3e11 }\ntraction = { law = \"linear\", stiffness = 1e10 }",
    "compression = { law = \"power\", c = 1.81e10, m = 0.35 }\ntraction = { law = \"rccm\", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }",
];

/// FD and exact solvers agree within 1% on A1/A_inc and A2/A_inc at the default FD
/// resolution for unilateral, RCCM, bilinear and power x RCCM laws.
#[test]
fn fd_agrees_with_exact_solver() {
    for law in LAWS {
        for xi in [0.2, 0.5] {
            let (e1, e2) = compare(law, xi, None);
            assert!(e1 < 0.01 && e2 < 0.01, "{law} xi {xi}: A1 {e1:e} A2 {e2:e}");
        }
    }
}

/// ... and the FD result converges to the exact one when refined.
#[test]
fn fd_converges_to_exact_solver() {
    for law in LAWS {
        let (_, coarse) = compare(law, 0.5, Some(200));
        let (_, fine) = compare(law, 0.5, Some(800));
        assert!(
            fine < 0.6 * coarse || fine < 1e-3,
            "{law}: {coarse:e} -> {fine:e}"
        );
    }
}

//! Criterion benchmarks of the exact half-space solver (docs/performance.md).
//!
//! - `simulate_summary/rccm_0.82MPa`: one run of the thesis' chapter-3 RCCM scenario
//!   (PMMA, p0 = 0.082 MPa, C_N = 2e13 Pa/m, w = 0.1 J/m^2, b = 1e-8, 1 MHz, 15 cycles,
//!   amplitude 0.82 MPa), solver plus harmonic analysis, one thread;
//! - `simulate_summary/unilateral_xi0.35`: unilateral contact (rigid x free) at xi = 0.35;
//!   (both repeat one scenario on one workspace: from the second run on, the analysis
//!   floor of the locked interface comes from the workspace, as in every sweep point
//!   after the first, docs/model.md section 6.1, and the incident wave's table on the
//!   solver's grid is the one the workspace kept from its last run, as in every run of an
//!   identification or of a sweep over the interface, docs/model.md section 4)
//! - `simulate_summary_cold/*`: the same runs with the workspace emptied before each, so
//!   that each run also solves and analyses the locked interface and tabulates its burst
//!   (a first run);
//! - `xi_sweep/rccm_100_points`: 100 load ratios xi in [0.05, 1.2] of the RCCM scenario,
//!   scenarios built beforehand, run with rayon `par_iter` on all cores (a workspace per
//!   rayon job, `map_init`);
//! - `shear_sweep/friction_ratio_100_points`: the coupled normal/tangential solver on 100
//!   static pressures (mu p0 / tau_inc from 0.03 to 1.2) of a rigid-stick Coulomb interface
//!   between aluminium half-spaces hit by a 15-cycle, 5 MPa, 1 MHz shear burst
//!   (examples/shear/clipping.toml at 200 samples per period), on all cores.
//!
//! Sample sizes are small so that `cargo bench -p contactwave` finishes in a few minutes on
//! two cores.

use contactwave::model::Workspace;
use contactwave::scenario::Scenario;
use contactwave::simulate_summary_in;
use criterion::{criterion_group, criterion_main, Criterion};
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

/// The chapter-3 RCCM scenario (thesis chapter 3; `contactwave bench` runs the same one).
const RCCM: &str = r#"
[medium]
material = "pmma"
youngs_modulus = 5e9             # the thesis' E (its 1D convention)
[interface]
static_pressure = 0.082e6
traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 15
amplitude = 0.82e6
"#;

/// Unilateral contact (rigid compression, free traction) at load ratio xi = 0.35.
const UNILATERAL: &str = r#"
[medium]
material = "pmma"
youngs_modulus = 5e9             # the thesis' E (its 1D convention)
[interface]
static_pressure = 0.1e6
[incident]
frequency = 1e6
cycles = 15
xi = 0.35
"#;

/// Number of points of the xi sweep.
const SWEEP_POINTS: usize = 100;

fn scenario(text: &str, name: &str) -> Scenario {
    Scenario::from_toml_str(text, name).expect("benchmark scenario is valid")
}

/// The RCCM scenario with its amplitude replaced by load ratio `xi`.
fn rccm_at_xi(xi: f64) -> Scenario {
    let text = RCCM.replace("amplitude = 0.82e6", &format!("xi = {xi:?}"));
    scenario(&text, "rccm_xi.toml")
}

fn single_runs(c: &mut Criterion) {
    let rccm = scenario(RCCM, "rccm_0.82MPa.toml");
    let unilateral = scenario(UNILATERAL, "unilateral.toml");
    let mut g = c.benchmark_group("simulate_summary");
    g.sample_size(20).measurement_time(Duration::from_secs(5));
    let mut ws = Workspace::new();
    g.bench_function("rccm_0.82MPa", |b| {
        b.iter(|| simulate_summary_in(black_box(&rccm), &mut ws).expect("run succeeds"))
    });
    g.bench_function("unilateral_xi0.35", |b| {
        b.iter(|| simulate_summary_in(black_box(&unilateral), &mut ws).expect("run succeeds"))
    });
    g.finish();
    let mut g = c.benchmark_group("simulate_summary_cold");
    g.sample_size(20).measurement_time(Duration::from_secs(5));
    for (name, s) in [("rccm_0.82MPa", &rccm), ("unilateral_xi0.35", &unilateral)] {
        g.bench_function(name, |b| {
            b.iter(|| {
                ws.clear();
                simulate_summary_in(black_box(s), &mut ws).expect("run succeeds")
            })
        });
    }
    g.finish();
}

fn xi_sweep(c: &mut Criterion) {
    let n = SWEEP_POINTS;
    let scenarios: Vec<Scenario> = (0..n)
        .map(|i| rccm_at_xi(0.05 + (1.2 - 0.05) * i as f64 / (n - 1) as f64))
        .collect();
    let mut g = c.benchmark_group("xi_sweep");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("rccm_100_points", |b| {
        b.iter(|| {
            scenarios
                .par_iter()
                .map_init(Workspace::new, |ws, s| {
                    simulate_summary_in(s, ws).expect("run succeeds")
                })
                .collect::<Vec<_>>()
        })
    });
    g.finish();
}

/// A shear burst at a rigid-stick Coulomb interface (aluminium half-spaces, mu = 0.3).
const SHEAR: &str = r#"
[medium]
material = "aluminium"
[counterpart]
kind = "medium"
material = "aluminium"
[interface]
static_pressure = 10e6
tangential = { law = "coulomb", friction = 0.3 }
[shear_incident]
frequency = 1e6
cycles = 15
amplitude = 5e6
"#;

fn shear_sweep(c: &mut Criterion) {
    let n = SWEEP_POINTS;
    let scenarios: Vec<Scenario> = (0..n)
        .map(|i| {
            let p0 = 0.5e6 + (20e6 - 0.5e6) * i as f64 / (n - 1) as f64;
            let text = SHEAR.replace(
                "static_pressure = 10e6",
                &format!("static_pressure = {p0:?}"),
            );
            scenario(&text, "shear.toml")
        })
        .collect();
    let mut g = c.benchmark_group("shear_sweep");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    g.bench_function("friction_ratio_100_points", |b| {
        b.iter(|| {
            scenarios
                .par_iter()
                .map_init(Workspace::new, |ws, s| {
                    simulate_summary_in(s, ws).expect("run succeeds")
                })
                .collect::<Vec<_>>()
        })
    });
    g.finish();
}

criterion_group!(benches, single_runs, xi_sweep, shear_sweep);
criterion_main!(benches);

//! Throughput of the finite-difference bar-stack solver (issue 3, item 9): node updates
//! per second on the half-space case at the thesis resolution (dx = 2e-5 m, about 3000
//! nodes, unilateral contact with a rigid wall) and on the Tribobrake model; and the whole
//! Tribobrake hammer test as `contactwave run` does it (issue 13, item 4).

use contactwave::excitation::{ToneBurst, Window};
use contactwave::law::{compression::Rigid, traction::Free, ContactLaw};
use contactwave::material::Material;
use contactwave::model::bar_stack::simulate_bar_stack;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::solver::bar_stack::{BarStack, End, FdRun, InterfaceScheme, Segment};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::path::Path;
use std::sync::Arc;

fn half_space(c: &mut Criterion) {
    let m = Material::PMMA;
    let dx = 2e-5;
    let dt = dx / m.wave_speed();
    let cells = 3000usize;
    let law = ContactLaw {
        static_pressure: 0.082e6,
        compression: Box::new(Rigid {
            static_pressure: 0.082e6,
        }),
        traction: Box::new(Free),
    };
    let stack = BarStack {
        area: 1.0,
        segments: vec![Segment {
            name: "pmma".into(),
            length: cells as f64 * dx,
            material: m,
            damping: 0.0,
        }],
        interfaces: vec![],
        left: End::Transparent,
        right: End::Obstacle(Arc::new(law)),
        incident: Some(Arc::new(ToneBurst::new(
            0.3e6,
            1e6,
            15.0,
            Window::HannRamps {
                ramp_fraction: 0.25,
            },
        ))),
        shear: None,
    };
    let steps = 5000;
    let run = FdRun {
        dt,
        t0: -(cells as f64) * dt,
        steps,
        record_every: 1,
        probes: vec![1500],
        ..FdRun::default()
    };
    let mut g = c.benchmark_group("fd_half_space_3000_nodes");
    g.throughput(Throughput::Elements(((cells + 1) * steps) as u64));
    g.sample_size(20);
    g.bench_function("unilateral", |b| b.iter(|| stack.run(&run).unwrap()));
    let backward = FdRun {
        interface_scheme: InterfaceScheme::Backward,
        ..run.clone()
    };
    g.bench_function("unilateral_backward", |b| {
        b.iter(|| stack.run(&backward).unwrap())
    });
    g.finish();
}

fn tribobrake(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tribobrake.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("duration = 0.2 ", "duration = 0.02 ");
    let s = BarStackScenario::from_table(text.parse().unwrap(), &path).unwrap();
    let steps = (0.02 / s.dt) as usize;
    let nodes = s.stack.mesh(s.dt).nodes;
    let run = FdRun {
        dt: s.dt,
        t0: 0.0,
        steps,
        record_every: 1,
        probes: vec![0],
        ..FdRun::default()
    };
    let mut g = c.benchmark_group("fd_tribobrake_0.02s");
    g.throughput(Throughput::Elements((nodes * steps) as u64));
    g.sample_size(10);
    g.bench_function("modified_power", |b| b.iter(|| s.stack.run(&run).unwrap()));
    let backward = FdRun {
        interface_scheme: InterfaceScheme::Backward,
        ..run.clone()
    };
    g.bench_function("modified_power_backward", |b| {
        b.iter(|| s.stack.run(&backward).unwrap())
    });
    g.finish();
}

/// The whole hammer test of examples/tribobrake.toml (0.2 s simulated, FRF, modes,
/// guide-mode probe run, interface histories): the work inside `contactwave run`, without
/// the files.
fn tribobrake_run(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tribobrake.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let s = BarStackScenario::from_table(text.parse().unwrap(), &path).unwrap();
    let mut g = c.benchmark_group("tribobrake_run");
    g.sample_size(10);
    g.bench_function("simulate_0.2s", |b| {
        b.iter(|| simulate_bar_stack(&s).unwrap())
    });
    g.finish();
}

criterion_group!(benches, half_space, tribobrake, tribobrake_run);
criterion_main!(benches);

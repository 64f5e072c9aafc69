//! Throughput of the 2D spectral-element solver (issue 26, item 6): node-updates per second
//! (one node advanced one step in all its fields) of the plate-crack case, aluminium 40 x
//! 10 mm with a 2 mm Signorini + Coulomb crack at mid-depth under 1 MPa closure and a
//! 5 MHz burst from a 4 mm transducer, here over 0.5 us (the throughput does not depend on
//! the duration), and the crack-free plate for the crack's share of the step; order-6
//! elements of 0.25 mm, about the scenarios' default for it (model.md section 15.4).

use contactwave::excitation::{ToneBurst, Window};
use contactwave::law::compression::Rigid;
use contactwave::law::point::PointLaw;
use contactwave::law::tangential::Coulomb;
use contactwave::law::traction::Free;
use contactwave::solver::solid_2d::{
    Crack, Elastic, Layer, Side, Solid2d, Source, SourceKind, WaveType,
};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::sync::Arc;

type Law = PointLaw<Rigid, Free, Coulomb>;

fn plate(cracked: bool, duration: f64) -> Solid2d<Law> {
    let p0 = 1e6;
    let law = PointLaw::normal(
        p0,
        Rigid {
            static_pressure: p0,
        },
        Free,
        Coulomb {
            friction: 0.3,
            stick_stiffness: f64::INFINITY,
        },
    );
    Solid2d {
        width: 40e-3,
        layers: vec![Layer {
            bottom: 10e-3,
            material: Elastic {
                density: 2700.0,
                p_speed: 6320.0,
                s_speed: 3130.0,
            },
        }],
        wave: WaveType::PSv,
        top: Side::Free,
        bottom: Side::Free,
        sides: Side::Free,
        element_size: 0.25e-3,
        order: 6,
        courant: 0.8,
        max_time_step: f64::INFINITY,
        cracks: if cracked {
            vec![Crack {
                start: [19e-3, 5e-3],
                end: [21e-3, 5e-3],
                full_width: false,
                law,
                profile: None,
            }]
        } else {
            vec![]
        },
        sources: vec![Source {
            kind: SourceKind::Traction {
                top: true,
                x0: 8e-3,
                x1: 12e-3,
                normal: true,
                delay_per_m: 0.0,
            },
            signal: Arc::new(ToneBurst::new(10e6, 5e6, 5.0, Window::Hann)),
        }],
        receivers: vec![[30e-3, 0.0]],
        duration,
        crack_every: 10,
        pml: contactwave::solver::solid_2d::Pml::elements(4.0, 0.25e-3),
    }
}

fn solid_2d(c: &mut Criterion) {
    let mut g = c.benchmark_group("solid_2d");
    g.sample_size(10);
    for cracked in [true, false] {
        let p = plate(cracked, 0.5e-6);
        let plan = p.plan("<bench>").unwrap();
        eprintln!(
            "{} nodes, dt {:e} s, {} steps",
            plan.mesh.n_nodes, plan.dt, plan.steps
        );
        let updates = (plan.mesh.n_nodes * plan.steps) as u64;
        g.throughput(Throughput::Elements(updates));
        let name = if cracked {
            "plate_crack_0.5us"
        } else {
            "plate_0.5us"
        };
        g.bench_function(name, |b| b.iter(|| plan.clone().run().unwrap()));
    }
    g.finish();
}

criterion_group!(benches, solid_2d);
criterion_main!(benches);

//! Criterion benchmark of the identification (docs/performance.md section 2).
//!
//! - `identify/rccm_damaged`: `examples/identify/rccm_damaged.toml` as
//!   `contactwave identify` runs it, files excluded: three parameters of a damaged RCCM
//!   interface (`C_N`, `w`, `b`) from A2/A1 and A1/Ainc at 30 points (15 load ratios at
//!   1 and 2 MHz), particle swarm + Levenberg-Marquardt from three starts, profile
//!   likelihood and 8 bootstrap refits; the forward runs in parallel on all cores.
//!
//! One identification takes seconds: the bench takes the minimum of 10 samples criterion
//! allows, so it runs for a few minutes (`cargo bench -p contactwave --bench identify`).

use contactwave::inverse::{identify, IdentifySpec};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

fn identify_bench(c: &mut Criterion) {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify/rccm_damaged.toml");
    let spec = IdentifySpec::load(&path).expect("the example identification is valid");
    let mut g = c.benchmark_group("identify");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(1));
    g.measurement_time(Duration::from_secs(60));
    g.bench_function("rccm_damaged", |b| {
        b.iter(|| {
            let r = identify(black_box(&spec), &|_| {}).expect("identification runs");
            black_box(r.estimate.cost)
        })
    });
    g.finish();
}

criterion_group!(benches, identify_bench);
criterion_main!(benches);

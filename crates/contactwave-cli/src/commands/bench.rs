//! `contactwave bench`: time one simulation of the thesis' chapter-3 RCCM scenario (median
//! of `--runs` runs on one thread) and an in-memory sweep of `--points` load ratios on all
//! cores, and print the timings. Writes no files.

use super::EXIT_OK;
use contactwave::model;
use contactwave::run::Executor;
use contactwave::scenario::parse_toml;
use contactwave::study;
use std::path::Path;
use std::time::Instant;

/// Time one simulation of the thesis' chapter-3 RCCM scenario (PMMA, p0 = 0.082 MPa,
/// 1 MHz, 15 cycles, amplitude 0.82 MPa; median of --runs runs, one thread) and a sweep
/// of --points load ratios xi in [0.05, 1.2] on all cores (in memory, no files).
#[derive(clap::Args)]
pub struct Args {
    /// Points of the xi sweep.
    #[arg(long, default_value_t = 100,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
    points: usize,
    /// Repetitions of the single simulation (the median is reported).
    #[arg(long, default_value_t = 50,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
    runs: usize,
}

/// The chapter-3 RCCM scenario of `bench`.
const BENCH_SCENARIO: &str = r#"
[medium]
material = "pmma"
[interface]
static_pressure = 0.082e6
traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 15
amplitude = 0.82e6
[probe]
x = -0.03
"#;

pub fn run(args: Args) -> contactwave::Result<u8> {
    let Args { points, runs } = args;
    let file = "<bench: chapter-3 RCCM scenario>";
    let table = parse_toml(BENCH_SCENARIO, file)?;
    let template = model::plan_valid(table, Path::new(file))?;
    let scenario = template.base()?;
    // (a) one simulation, single thread, median of `runs`
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t0 = Instant::now();
        let s = scenario.summary()?;
        times.push(t0.elapsed().as_secs_f64());
        std::hint::black_box(s);
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    // (b) xi sweep on all cores, in memory: the models are built from the template first
    let xis = study::linspace(0.05, 1.2, points);
    let xi = template.param("incident.xi")?;
    let models = xis
        .iter()
        .map(|&v| template.build(&[(&xi, v)]))
        .collect::<contactwave::Result<Vec<_>>>()?;
    let t0 = Instant::now();
    let results = Executor::new().try_map(&models, |m| m.summary())?;
    let sweep_s = t0.elapsed().as_secs_f64();
    std::hint::black_box(results);
    println!("single simulation (chapter-3 RCCM, 0.82 MPa, 1 thread):");
    println!(
        "  median {:.3} ms per simulation over {} runs (min {:.3} ms, max {:.3} ms)",
        median * 1e3,
        runs,
        times[0] * 1e3,
        times[times.len() - 1] * 1e3
    );
    println!(
        "xi sweep ({} points in [0.05, 1.2], {} threads):",
        points,
        Executor::new().thread_count()
    );
    println!(
        "  total {:.1} ms ({:.3} ms per point)",
        sweep_s * 1e3,
        sweep_s * 1e3 / points as f64
    );
    Ok(EXIT_OK)
}

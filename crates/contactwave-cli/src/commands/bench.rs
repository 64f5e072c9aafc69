//! `contactwave bench`: time one simulation of the thesis' chapter-3 RCCM scenario (median
//! of `--runs` runs on one thread; warm, on one workspace whose analysis floor of the
//! locked interface is kept after the first run as in a sweep and the burst's table kept
//! from the last run, and cold), an in-memory sweep of `--points` load ratios on all
//! cores, the Tribobrake hammer test of `examples/tribobrake.toml`, and with `--identify`
//! an identification, and print the timings (docs/performance.md). Writes no files.

use super::EXIT_OK;
use contactwave::inverse::{identify, IdentifySpec};
use contactwave::model::{self, Workspace};
use contactwave::run::{Executor, Workspaces};
use contactwave::scenario::parse_toml;
use contactwave::solver::solid_2d::Backend;
use contactwave::study;
use std::path::Path;
use std::time::Instant;

/// Time one simulation of the thesis' chapter-3 RCCM scenario (PMMA, p0 = 0.082 MPa,
/// 1 MHz, 15 cycles, amplitude 0.82 MPa; median of --runs runs, one thread), a sweep of
/// --points load ratios xi in [0.05, 1.2] on all cores, the Tribobrake hammer test of
/// examples/tribobrake.toml (median of --tribobrake-runs) and, with --identify FILE, one
/// identification (in memory, no files).
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
    /// Repetitions of the Tribobrake hammer test (the median is reported; 0: skip it).
    #[arg(long, default_value_t = 3)]
    tribobrake_runs: usize,
    /// Simulated microseconds of the 2D reference case
    /// (examples/solid_2d/plate_crack.toml, its mesh and time step; 0: skip it): prints
    /// its throughput in node-updates per second.
    #[arg(long, default_value_t = 1.0)]
    solid_2d_us: f64,
    /// Where the 2D case runs: `cpu`, or `gpu` (a build with `--features gpu` and an
    /// NVIDIA GPU; timed on a second run, after the kernels' compilation).
    #[arg(long, default_value = "cpu", value_parser = ["cpu", "gpu"])]
    backend: String,
    /// Element size of the 2D case, m (default: the scenario's, 0.25 mm at order 6): a
    /// smaller one gives a larger mesh of the same plate.
    #[arg(long, value_name = "M")]
    solid_2d_element_size: Option<f64>,
    /// Also time one identification of this file (e.g.
    /// examples/identify/rccm_damaged.toml: a few seconds), files not written.
    #[arg(long, value_name = "FILE")]
    identify: Option<std::path::PathBuf>,
}

/// The Tribobrake hammer test of the thesis' chapter 4 (examples/tribobrake.toml).
const TRIBOBRAKE: &str = include_str!("../../../../examples/tribobrake.toml");

/// Print `title` and the median, minimum and maximum `t` (s) of `runs` runs in ms with
/// `digits` decimals.
fn print_timing(title: &str, what: &str, runs: usize, t: (f64, f64, f64), digits: usize) {
    let ms = |x: f64| format!("{:.*}", digits, x * 1e3);
    println!("{title}");
    println!(
        "  median {} ms per {what} over {runs} runs (min {} ms, max {} ms)",
        ms(t.0),
        ms(t.1),
        ms(t.2)
    );
}

/// Median (s) of `runs` timings of `f`, with the minimum and maximum.
fn timed(
    runs: usize,
    mut f: impl FnMut() -> contactwave::Result<()>,
) -> contactwave::Result<(f64, f64, f64)> {
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        contactwave::interrupt::check()?;
        let t0 = Instant::now();
        f()?;
        times.push(t0.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok((times[times.len() / 2], times[0], times[times.len() - 1]))
}

/// The 2D reference case (examples/solid_2d/plate_crack.toml).
const PLATE_CRACK: &str = include_str!("../../../../examples/solid_2d/plate_crack.toml");

/// The chapter-3 RCCM scenario of `bench` (examples/rccm_0.82MPa.toml).
const BENCH_SCENARIO: &str = include_str!("../../../../examples/rccm_0.82MPa.toml");

pub fn run(args: Args) -> contactwave::Result<u8> {
    let Args {
        points,
        runs,
        tribobrake_runs,
        solid_2d_us,
        backend,
        solid_2d_element_size,
        identify: identify_file,
    } = args;
    let file = "<bench: examples/rccm_0.82MPa.toml>";
    let table = parse_toml(BENCH_SCENARIO, file)?;
    let template = model::plan_valid(table, Path::new(file))?;
    let scenario = template.base()?;
    // (a) one simulation, single thread, median of `runs`
    let mut ws = Workspace::new();
    let (median, min, max) = timed(runs, || {
        std::hint::black_box(scenario.summary_in(&mut ws)?);
        Ok(())
    })?;
    print_timing(
        "single simulation (chapter-3 RCCM, 0.82 MPa, 1 thread):",
        "simulation",
        runs,
        (median, min, max),
        3,
    );
    // (a') the same as a first run: the locked interface's floor solved and the burst
    // tabulated every time
    let cold = timed(runs, || {
        ws.clear();
        std::hint::black_box(scenario.summary_in(&mut ws)?);
        Ok(())
    })?;
    print_timing(
        "single simulation, cold (the floor's locked solve and the burst's table in each run):",
        "simulation",
        runs,
        cold,
        3,
    );
    // (b) xi sweep on all cores, in memory: the models are built from the template first
    let xis = study::linspace(0.05, 1.2, points);
    let xi = template.param("incident.xi")?;
    let models = xis
        .iter()
        .map(|&v| template.build(&[(&xi, v)]))
        .collect::<contactwave::Result<Vec<_>>>()?;
    let t0 = Instant::now();
    let workspaces = Workspaces::new();
    let results = Executor::new().try_map(&models, |m| workspaces.with(|ws| m.summary_in(ws)))?;
    let sweep_s = t0.elapsed().as_secs_f64();
    std::hint::black_box(results);
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
    // (c) the Tribobrake hammer test (0.2 s simulated, FRF, guide-mode probe run)
    if tribobrake_runs > 0 {
        let file = "<bench: examples/tribobrake.toml>";
        let tb = model::plan_valid(parse_toml(TRIBOBRAKE, file)?, Path::new(file))?.base()?;
        let (median, min, max) = timed(tribobrake_runs, || {
            std::hint::black_box(tb.summary()?);
            Ok(())
        })?;
        print_timing(
            "Tribobrake hammer test (examples/tribobrake.toml, summary, 1 thread):",
            "run",
            tribobrake_runs,
            (median, min, max),
            1,
        );
    }
    // (d) the 2D reference case over `solid_2d_us` microseconds
    if solid_2d_us > 0.0 {
        let file = "<bench: examples/solid_2d/plate_crack.toml>";
        // the kernel's throughput: no wavefield pictures (their interval, 1 us, would also
        // refuse a case shorter than two of them)
        let mut table = parse_toml(PLATE_CRACK, file)?;
        table.remove("snapshots");
        let t = model::plan_valid(table, Path::new(file))?;
        let duration = t.param("model.duration")?;
        let size = t.param("model.element_size")?;
        let mut values = vec![(&duration, solid_2d_us * 1e-6)];
        if let Some(h) = solid_2d_element_size {
            values.push((&size, h));
        }
        let m = t.build(&values)?;
        let scenario = m
            .as_any()
            .downcast_ref::<contactwave::scenario::solid_2d::Solid2dScenario>()
            .expect("a solid_2d scenario");
        let plan = scenario.problem.plan(file)?;
        let updates = (plan.mesh.n_nodes * plan.steps) as f64;
        let on = Backend::parse(&backend).unwrap_or_default();
        if on == Backend::Gpu {
            // the context and the kernels' compilation, outside the timing
            plan.clone().run_on(on, file, None)?;
        }
        let run = plan.clone();
        let t0 = Instant::now();
        std::hint::black_box(run.run_on(on, file, None)?);
        let s = t0.elapsed().as_secs_f64();
        let threads = match on {
            Backend::Cpu => format!("{} threads", Executor::new().thread_count()),
            Backend::Gpu => "GPU".to_string(),
        };
        println!(
            "2D solid, plate crack (examples/solid_2d/plate_crack.toml, {} nodes, {} steps, {threads}): {:.3e} node-updates/s",
            plan.mesh.n_nodes,
            plan.steps,
            updates / s
        );
        if on == Backend::Cpu {
            mesh_lines(&scenario.problem, file, updates / s)?;
        }
    }
    // (e) one identification, forward runs on all cores
    if let Some(path) = identify_file {
        let spec = IdentifySpec::load(&path)?;
        let t0 = Instant::now();
        let r = identify(&spec, &|_| {})?;
        println!("identification ({}):", path.display());
        println!(
            "  {:.2} s wall, {} forward runs ({:.0} runs/s)",
            t0.elapsed().as_secs_f64(),
            r.forward_runs,
            r.forward_runs as f64 / t0.elapsed().as_secs_f64()
        );
    }
    Ok(EXIT_OK)
}

/// The same plate through the quadrilateral-mesh path (docs/model.md section 15.13): on
/// its own grid (every element on the rectangle fast path) and rotated by 30 degrees
/// (every element general), each beside the rectangle path's `rect` node-updates/s; the
/// kernels' bytes and flops per node-update and a STREAM-like triad's bandwidth.
fn mesh_lines(
    problem: &contactwave::solver::solid_2d::Solid2d<contactwave::law::point::SharedLaw>,
    file: &str,
    rect: f64,
) -> contactwave::Result<()> {
    use contactwave::solver::solid_2d::quad::QuadSolid;
    let (s, c) = 30f64.to_radians().sin_cos();
    let rotate = move |p: [f64; 2]| [c * p[0] - s * p[1], s * p[0] + c * p[1]];
    let identity = |p: [f64; 2]| p;
    type Map<'a> = &'a dyn Fn([f64; 2]) -> [f64; 2];
    let maps: [(&str, Map); 2] = [
        ("its own grid, rectangle elements", &identity),
        ("rotated 30 degrees, general elements", &rotate),
    ];
    let n = problem.order;
    let mut general = 0.0;
    for (what, map) in maps {
        let Some(q) = QuadSolid::of_rectangle(problem, map, file)? else {
            return Ok(());
        };
        let plan = q.plan(file)?;
        let updates = (plan.mesh.n_nodes() * plan.steps) as f64;
        let t0 = Instant::now();
        std::hint::black_box(plan.run()?);
        let rate = updates / t0.elapsed().as_secs_f64();
        general = rate;
        println!(
            "2D solid on a mesh ({what}, {} nodes, {} steps): {rate:.3e} node-updates/s ({:.2} of the rectangle path)",
            plan.mesh.n_nodes(),
            plan.steps,
            rate / rect
        );
    }
    // per node-update, P-SV, order n: the element pass over (n+1)^2/n^2 points a node
    // (conn 4 B, metric 40 B of a general element, u gathered 16 B, f scattered 32 B) and
    // the node pass (u, v, f read and written, the inverse mass: 56 B)
    let per = ((n + 1) * (n + 1)) as f64 / (n * n) as f64;
    let m = (n + 1) as f64;
    let bytes = (
        per * (4.0 + 40.0 + 16.0 + 32.0),
        per * (4.0 + 16.0 + 32.0) + 56.0,
    );
    let flops = (per * (16.0 * m + 50.0), per * (16.0 * m + 24.0));
    let triad = triad_bandwidth();
    println!(
        "  kernel per node-update at order {n}: general {:.0} B, {:.0} flops; rectangle {:.0} B, {:.0} flops; triad bandwidth {:.2e} B/s (the general path at its rate above moves {:.0} % of it)",
        bytes.0 + 56.0,
        flops.0,
        bytes.1,
        flops.1,
        triad,
        100.0 * general * (bytes.0 + 56.0) / triad
    );
    Ok(())
}

/// A STREAM-like triad `a = b + s c` over three 32-Mi-value arrays (768 MiB, past every
/// cache), on all threads: the best of 5, bytes moved per second (24 B a value).
fn triad_bandwidth() -> f64 {
    use rayon::prelude::*;
    let n = 1 << 25;
    let b = vec![1.0f64; n];
    let c = vec![2.0f64; n];
    let mut a = vec![0.0f64; n];
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t0 = Instant::now();
        a.par_chunks_mut(1 << 16)
            .zip(b.par_chunks(1 << 16).zip(c.par_chunks(1 << 16)))
            .for_each(|(a, (b, c))| {
                for i in 0..a.len() {
                    a[i] = b[i] + 3.0 * c[i];
                }
            });
        best = best.min(t0.elapsed().as_secs_f64());
        std::hint::black_box(&a);
    }
    24.0 * n as f64 / best
}

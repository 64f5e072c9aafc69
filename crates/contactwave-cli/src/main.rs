//! `contactwave`: command-line interface of the contactwave library.
//!
//! Exit codes: 0 success; 1 `validate` found a case outside its tolerance; 2 invalid input
//! (scenario or sweep file, missing file, output path, I/O); 3 numerical failure of a
//! simulation; 130 interrupted (Ctrl-C). Every error is one line on stderr starting with
//! `error: `, and no output folder is created or modified when an input is invalid or the
//! simulation fails.

use clap::{Parser, Subcommand};
use contactwave::output;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::{parse_toml, set_dotted, Scenario};
use contactwave::study::{self, Sweep, SweepOptions};
use contactwave::Error;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

/// Set by Ctrl-C; sweeps check it before each point.
static CANCEL: AtomicBool = AtomicBool::new(false);

const AFTER_HELP: &str = "\
Units are SI throughout: Pa (stress, p0, amplitude), m (gap, probe position), s, Hz,
kg/m^3, Pa/m (interface stiffness), J/m^2 (decohesion energy). Stress is tension-positive;
p0 is a compression.

Exit codes: 0 success, 1 validation case outside tolerance, 2 invalid input or I/O error,
3 numerical failure, 130 interrupted.";

#[derive(Parser)]
#[command(
    name = "contactwave",
    version,
    about = "Simulate elastic waves interacting with nonlinear contact interfaces",
    after_help = AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// What `fit` fits.
#[derive(Clone, Copy, clap::ValueEnum)]
enum FitKind {
    /// Contact stiffness vs pressure, K = C p^m (thesis eq. 4.4).
    PowerLaw,
}

/// Solver refined by `convergence`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum ConvMethod {
    /// The finite-difference scheme (Courant 1: dx = c dt).
    Fd,
    /// The exact solver (its output sampling).
    Exact,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the studies of thesis chapters 3, 4 and 5 from embedded scenarios (no
    /// input file): DIR/report.html (self-contained, inline SVG), DIR/findings.json and
    /// DIR/figures/<id>.svg + <id>.csv.
    Reproduce {
        /// Which studies.
        #[arg(default_value = "all",
              value_parser = ["chapter3", "chapter4", "chapter5", "all"])]
        which: String,
        /// Output folder (created if needed; files in it are replaced).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Fit a stiffness-pressure law to measured data: `fit power-law data.csv` (pressure in
    /// Pa, stiffness in Pa/m; least squares in log-log) prints C, m and R^2.
    Fit {
        /// What to fit.
        #[arg(value_enum)]
        what: FitKind,
        /// CSV file with a header line.
        data: PathBuf,
        /// Pressure and stiffness columns by header name, e.g. `--columns P,K` (default:
        /// the first two columns).
        #[arg(long, value_name = "P,K")]
        columns: Option<String>,
        /// Print a JSON object with keys c, m, r2.
        #[arg(long)]
        json: bool,
    },
    /// Simulate one scenario and write summary.json, timeseries.csv, probe.csv,
    /// spectrum.csv and SVG plots into DIR (SI units: s, m, Pa, m/s, Hz).
    Run {
        /// Scenario file (TOML; see docs/scenario.md).
        scenario: PathBuf,
        /// Output folder (created if needed; files in it are replaced).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write the contact law of a scenario as law_curve.csv (gap m, stress Pa) and
    /// law_curve.svg into DIR.
    Law {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Run a parameter sweep and write DIR/sweep.csv (one row per point: point index,
    /// swept parameters in their SI units, summary values), DIR/sweep.csv.hash and
    /// DIR/sweep.svg. Points whose simulation fails are listed in DIR/sweep_errors.csv.
    Sweep {
        /// Sweep file (TOML: `base = "scenario.toml"` and `[[axis]]` tables).
        sweep: PathBuf,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Keep the rows of an existing sweep.csv of the same sweep and compute only the
        /// missing points (refused if the sweep, its base scenario or the version changed).
        #[arg(long)]
        resume: bool,
        /// Worker threads (default: one per core).
        #[arg(long, value_name = "N",
              value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
        threads: Option<usize>,
        /// Run only shard K of N: the points whose index i has i % N == K - 1 (1 <= K <= N).
        /// Header and hash file are those of the whole sweep; combine shards with `merge`.
        #[arg(long, value_name = "K/N", value_parser = study::Shard::parse)]
        shard: Option<study::Shard>,
    },
    /// Merge the sweep.csv files of the shards of one sweep (`sweep --shard K/N`) into OUT
    /// (rows sorted by point) and OUT.hash, after checking that the shards have the same
    /// hash file and that no point is missing or duplicated.
    Merge {
        /// Merged CSV to write (its folder is created if needed).
        out: PathBuf,
        /// The shards' CSV files.
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// The sweep file: check the shards against its hash and its whole grid (without
        /// it, the points must be 0 to the largest point found).
        #[arg(long, value_name = "FILE")]
        sweep: Option<PathBuf>,
    },
    /// Convergence study of a half-space scenario (thesis eqs. 2.42-2.43, Figure 22):
    /// A2/A_inc over a grid of xi for a series of resolutions; prints the error of each
    /// against the finest one and against the exact solver, and the observed order.
    Convergence {
        /// Half-space scenario file (TOML); its xi and resolution are overridden.
        scenario: PathBuf,
        /// Resolutions in samples per period of the highest input frequency (with the FD
        /// solver dx = c dt). Default 125,250,500,1000,2000,4000.
        #[arg(long, value_name = "N,N,...", value_delimiter = ',')]
        spp: Option<Vec<usize>>,
        /// Load ratios. Default 0.1,0.2,...,1.0 (the thesis' xi in ]0, 1]).
        #[arg(long, value_name = "XI,XI,...", value_delimiter = ',')]
        xi: Option<Vec<f64>>,
        /// Solver to refine.
        #[arg(long, value_enum, default_value = "fd")]
        method: ConvMethod,
        /// Harmonic whose efficiency A_n/A_inc is studied (1 to 5).
        #[arg(long, default_value_t = 2)]
        harmonic: usize,
        /// Also write convergence.csv, efficiency.csv and convergence.svg into DIR.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Run the validation cases and print `case | reference | computed | rel. error`
    /// (exit code 1 if a case exceeds its tolerance).
    Validate,
    /// Time one simulation of the thesis' chapter-3 RCCM scenario (PMMA, p0 = 0.082 MPa,
    /// 1 MHz, 15 cycles, amplitude 0.82 MPa; median of --runs runs, one thread) and a sweep
    /// of --points load ratios xi in [0.05, 1.2] on all cores (in memory, no files).
    Bench {
        /// Points of the xi sweep.
        #[arg(long, default_value_t = 100,
              value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
        points: usize,
        /// Repetitions of the single simulation (the median is reported).
        #[arg(long, default_value_t = 50,
              value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
        runs: usize,
    },
    /// Identify interface parameters from a measured curve (identification file: base
    /// scenario, measured CSV, unknown parameters with bounds and scale; docs/identify.md).
    /// Writes DIR/identification.json, fit.csv, fit.svg, sensitivity.svg and
    /// identification.html. With --design, ranks the [design] candidates instead and
    /// prints a table (and writes DIR/design.json and design.csv if --out is given).
    Identify {
        /// Identification file (TOML).
        spec: PathBuf,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR", required_unless_present_any = ["design", "synthesize"])]
        out: Option<PathBuf>,
        /// Rank the candidate experiments of the file's [design] table.
        #[arg(long)]
        design: bool,
        /// Print synthetic data instead (CSV on stdout): the file's data rows simulated
        /// with KEY=VALUE for the unknowns (repeat the option), times 1 + noise * N(0, 1).
        #[arg(long, value_name = "KEY=VALUE")]
        synthesize: Vec<String>,
        /// Relative noise of --synthesize.
        #[arg(long, default_value_t = 0.01)]
        noise: f64,
        /// Seed of the --synthesize noise.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    match dispatch(cli.command) {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            let code = match e {
                Error::Numerical { .. } => 3,
                Error::Interrupted => 130,
                _ => 2,
            };
            let msg = e.to_string().replace(['\n', '\r'], " ");
            eprintln!("error: {msg}");
            ExitCode::from(code)
        }
    }
}

fn dispatch(cmd: Command) -> contactwave::Result<u8> {
    match cmd {
        Command::Run { scenario, out } => run(&scenario, &out),
        Command::Law { scenario, out } => law(&scenario, &out),
        Command::Sweep {
            sweep,
            out,
            resume,
            threads,
            shard,
        } => sweep_cmd(&sweep, &out, resume, threads, shard),
        Command::Merge { out, shards, sweep } => merge_cmd(&out, &shards, sweep.as_deref()),
        Command::Validate => validate(),
        Command::Reproduce { which, out } => reproduce(&which, &out),
        Command::Convergence {
            scenario,
            spp,
            xi,
            method,
            harmonic,
            out,
        } => convergence(&scenario, spp, xi, method, harmonic, out.as_deref()),
        Command::Fit {
            what,
            data,
            columns,
            json,
        } => match what {
            FitKind::PowerLaw => fit_cmd(&data, columns.as_deref(), json),
        },
        Command::Bench { points, runs } => bench(points, runs),
        Command::Identify {
            spec,
            out,
            design,
            synthesize,
            noise,
            seed,
        } => {
            if synthesize.is_empty() {
                identify_cmd(&spec, out.as_deref(), design)
            } else {
                synthesize_cmd(&spec, &synthesize, noise, seed)
            }
        }
    }
}

/// Refuse an output path that exists and is not a folder (before any work is done).
fn check_out_dir(out: &Path) -> contactwave::Result<()> {
    if out.exists() && !out.is_dir() {
        return Err(Error::io(
            out,
            std::io::Error::other("exists and is not a directory"),
        ));
    }
    Ok(())
}

fn run(path: &Path, out: &Path) -> contactwave::Result<u8> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let table = parse_toml(&text, &path.display().to_string())?;
    if BarStackScenario::is_bar_stack(&table) {
        return run_bar_stack(table, path, out);
    }
    let scenario = Scenario::from_table(table, path)?;
    check_out_dir(out)?;
    let t0 = Instant::now();
    let result = contactwave::simulate(&scenario)?;
    let wall = t0.elapsed();
    let files = output::run_files(&result, &scenario)?;
    output::write_files(out, &files)?;
    let s = &result.summary;
    let get = |k: &str| s.get(k).unwrap_or(f64::NAN);
    println!("scenario               {}", path.display());
    println!("xi                     {:.6}", get("xi"));
    println!("A1/Ainc                {:.6e}", get("A1_over_Ainc"));
    println!("A2/Ainc                {:.6e}", get("A2_over_Ainc"));
    println!("A2/A1                  {:.6e}", get("A2_over_A1"));
    println!("beta_end               {:.6}", get("beta_end"));
    println!("contact loss fraction  {:.6}", get("contact_loss_fraction"));
    println!("energy closure error   {:.3e}", get("energy_closure_error"));
    println!("wall time              {:.1} ms", wall.as_secs_f64() * 1e3);
    println!("wrote {} files to {}", files.len(), out.display());
    Ok(0)
}

/// `run` on a bar-stack scenario: the hammer test, FRF and modes (thesis chapter 4).
fn run_bar_stack(table: toml::Table, path: &Path, out: &Path) -> contactwave::Result<u8> {
    let scenario = BarStackScenario::from_table(table, path)?;
    check_out_dir(out)?;
    let t0 = Instant::now();
    // long runs report progress on a terminal
    let bar = progress_bar();
    let b = bar.clone();
    let progress = contactwave::solver::barstack::StepProgress(std::sync::Arc::new(
        move |done: usize, total: usize| {
            b.set_length(total as u64);
            b.set_position(done as u64);
        },
    ));
    let result = contactwave::simulate_bar_stack_with_progress(&scenario, Some(progress));
    bar.finish_and_clear();
    let result = result?;
    let wall = t0.elapsed();
    let files = output::bar_stack_files(&result, &path.display().to_string())?;
    output::write_files(out, &files)?;
    let get = |k: &str| result.summary.get(k).unwrap_or(f64::NAN);
    println!("scenario               {}", path.display());
    for (i, p) in scenario.static_pressure.iter().enumerate() {
        let closure = get(&format!("static_interface_closure_{i}"));
        println!("static pressure [{i}]    {p:.6e} Pa (closure {closure:.4e} m)");
    }
    if scenario.incident.is_some() {
        println!("xi (first interface)   {:.6}", get("xi"));
        println!("A1/Ainc (reflected)    {:.6e}", get("A1_over_Ainc"));
        println!("A2/Ainc (reflected)    {:.6e}", get("A2_over_Ainc"));
        if result.summary.get("transmitted_A1_over_Ainc").is_some() {
            println!(
                "A1/Ainc (transmitted)  {:.6e}",
                get("transmitted_A1_over_Ainc")
            );
            println!(
                "A2/Ainc (transmitted)  {:.6e}",
                get("transmitted_A2_over_Ainc")
            );
        }
        println!(
            "energy R / T           {:.6} / {:.6}",
            get("energy_reflected_fraction"),
            result
                .summary
                .get("energy_transmitted_fraction")
                .unwrap_or(0.0)
        );
    } else {
        println!("first mode             {:.2} Hz", get("first_mode_hz"));
        println!("second harmonic        {:.2} Hz", get("second_harmonic_hz"));
        println!("A2/A1                  {:.4e}", get("A2_over_A1"));
        println!("guide mode             {:.1} Hz", get("guide_mode_hz"));
    }
    println!(
        "min contact pressure   {:.4e} Pa",
        get("min_contact_pressure")
    );
    println!("wall time              {:.1} ms", wall.as_secs_f64() * 1e3);
    println!("wrote {} files to {}", files.len(), out.display());
    Ok(0)
}

/// `fit power-law`: least squares of K = C p^m in log-log on two columns of a CSV file.
fn fit_cmd(path: &Path, columns: Option<&str>, json: bool) -> contactwave::Result<u8> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let mut rdr = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| Error::invalid(&file, "header", "?", format!("CSV error: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    let (ip, ik) = match columns {
        None => (0, 1),
        Some(c) => {
            let parts: Vec<&str> = c.split(',').map(str::trim).collect();
            let find = |name: &str| header.iter().position(|h| h == name);
            match parts.as_slice() {
                [p, k] => match (find(p), find(k)) {
                    (Some(a), Some(b)) => (a, b),
                    _ => {
                        return Err(Error::invalid(
                            &file,
                            "--columns",
                            c,
                            format!("column names from the header: {}", header.join(", ")),
                        ))
                    }
                },
                _ => {
                    return Err(Error::invalid(
                        &file,
                        "--columns",
                        c,
                        "two column names: PRESSURE,STIFFNESS",
                    ))
                }
            }
        }
    };
    let (mut p, mut k) = (Vec::new(), Vec::new());
    for (row, rec) in rdr.records().enumerate() {
        let rec = rec.map_err(|e| {
            Error::invalid(
                &file,
                format!("row {}", row + 1),
                "?",
                format!("CSV error: {e}"),
            )
        })?;
        let val = |i: usize, name: &str| -> contactwave::Result<f64> {
            rec.get(i)
                .and_then(|v| v.parse::<f64>().ok())
                .ok_or_else(|| {
                    Error::invalid(
                        &file,
                        format!("row {} {name}", row + 1),
                        rec.get(i).unwrap_or(""),
                        "a number",
                    )
                })
        };
        p.push(val(ip, "pressure")?);
        k.push(val(ik, "stiffness")?);
    }
    let fit = contactwave::analysis::fit::fit_power_law(&p, &k).map_err(|e| e.in_file(&file))?;
    if json {
        println!(
            "{}",
            serde_json::json!({"c": fit.c, "m": fit.m, "r2": fit.r2})
        );
    } else {
        println!("K = C p^m fitted on {} points of {file}", p.len());
        println!("C  = {:.6e} Pa^(1-m)/m", fit.c);
        println!("m  = {:.6}", fit.m);
        println!("R2 = {:.6}", fit.r2);
    }
    Ok(0)
}

fn law(path: &Path, out: &Path) -> contactwave::Result<u8> {
    let scenario = Scenario::load(path)?;
    check_out_dir(out)?;
    let files = output::law_files(&scenario.law)?;
    let written = output::write_files(out, &files)?;
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(0)
}

fn sweep_cmd(
    path: &Path,
    out: &Path,
    resume: bool,
    threads: Option<usize>,
    shard: Option<study::Shard>,
) -> contactwave::Result<u8> {
    let sweep = Sweep::load(path)?;
    // validate every point before creating anything
    sweep.runnable()?;
    check_out_dir(out)?;
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let _ = ctrlc::set_handler(|| {
        if CANCEL.swap(true, Ordering::SeqCst) {
            // second Ctrl-C: give up at once (finished rows are on disk already)
            std::process::exit(130);
        }
    });
    let shard = shard.unwrap_or(study::Shard::ALL);
    let total = (0..sweep.points.len())
        .filter(|&i| shard.contains(i))
        .count();
    let bar = if std::io::stderr().is_terminal() {
        let b = ProgressBar::new(total as u64);
        if let Ok(style) = ProgressStyle::with_template(
            "{bar:40} {pos}/{len} points  {elapsed_precise} elapsed, eta {eta}",
        ) {
            b.set_style(style);
        }
        b
    } else {
        ProgressBar::hidden()
    };
    let done = AtomicUsize::new(0);
    let progress = |d: usize, _total: usize| {
        done.store(d, Ordering::SeqCst);
        bar.set_position(d as u64);
    };
    let csv = out.join("sweep.csv");
    let opts = SweepOptions { threads, resume };
    match study::run_sweep_shard(&sweep, shard, &csv, &opts, &progress, &CANCEL) {
        Ok(report) => {
            bar.finish_and_clear();
            let mut plotted = false;
            if let Some(svg) = output::sweep_svg(&sweep, &csv)? {
                output::write_files(
                    out,
                    &[output::OutputFile {
                        name: "sweep.svg".into(),
                        contents: svg,
                    }],
                )?;
                plotted = true;
            }
            println!(
                "{} points: {} computed, {} already done, {} failed",
                report.total, report.computed, report.skipped, report.failed
            );
            println!("wrote {}", csv.display());
            if plotted {
                println!("wrote {}", out.join("sweep.svg").display());
            }
            if let Some(e) = report.errors_csv {
                eprintln!(
                    "warning: {} points failed; messages in {}",
                    report.failed,
                    e.display()
                );
            }
            Ok(0)
        }
        Err(Error::Interrupted) => {
            bar.abandon();
            eprintln!(
                "interrupted: {} of {} points done; rerun with --resume",
                done.load(Ordering::SeqCst),
                total
            );
            Ok(130)
        }
        Err(e) => {
            bar.abandon();
            Err(e)
        }
    }
}

/// `merge`: shard CSVs -> one CSV sorted by point, plus its hash file.
fn merge_cmd(out: &Path, shards: &[PathBuf], sweep: Option<&Path>) -> contactwave::Result<u8> {
    let sweep = sweep.map(Sweep::load).transpose()?;
    if out.is_dir() {
        return Err(Error::io(
            out,
            std::io::Error::other("is a directory; give the merged CSV's file name"),
        ));
    }
    let report = study::merge_sweep_csvs(out, shards, sweep.as_ref())?;
    println!(
        "merged {} points from {} shards",
        report.points, report.shards
    );
    println!("wrote {}", report.csv.display());
    println!("wrote {}", report.hash_file.display());
    Ok(0)
}

fn convergence(
    path: &Path,
    spp: Option<Vec<usize>>,
    xi: Option<Vec<f64>>,
    method: ConvMethod,
    harmonic: usize,
    out: Option<&Path>,
) -> contactwave::Result<u8> {
    use contactwave::study::convergence::{run_convergence, ConvergenceMethod, ConvergenceSpec};
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let table = parse_toml(&text, &path.display().to_string())?;
    if BarStackScenario::is_bar_stack(&table) {
        return Err(Error::invalid(
            path.display().to_string(),
            "model.kind",
            "\"bar_stack\"",
            "a half-space scenario (the study compares with the exact solver)",
        ));
    }
    let mut spec = ConvergenceSpec {
        method: match method {
            ConvMethod::Fd => ConvergenceMethod::Fd,
            ConvMethod::Exact => ConvergenceMethod::Exact,
        },
        harmonic,
        ..ConvergenceSpec::default()
    };
    if let Some(v) = spp {
        spec.samples_per_period = v;
    }
    if let Some(v) = xi {
        spec.xi = v;
    }
    if let Some(o) = out {
        check_out_dir(o)?;
    }
    let bar = progress_bar();
    let t0 = Instant::now();
    let r = run_convergence(&table, path, &spec, &|d, n| {
        bar.set_length(n as u64);
        bar.set_position(d as u64);
    })?;
    bar.finish_and_clear();
    println!(
        "convergence of A{h}/A_inc over {} load ratios (xi {} to {}), {} solver; thesis eqs. 2.42-2.43",
        r.xi.len(),
        r.xi.iter().cloned().fold(f64::INFINITY, f64::min),
        r.xi.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        match spec.method {
            ConvergenceMethod::Fd => "FD (Courant 1)",
            ConvergenceMethod::Exact => "exact",
        },
        h = r.harmonic
    );
    println!(
        "{:>8} | {:>11} | {:>11} | {:>16} | {:>15}",
        "spp", "dt (s)", "dx (m)", "error vs finest %", "error vs exact %"
    );
    for l in &r.levels {
        println!(
            "{:>8} | {:>11.4e} | {:>11.4e} | {:>16.4e} | {:>15.4e}",
            l.samples_per_period,
            l.dt,
            l.dx,
            100.0 * l.error_finest,
            100.0 * l.error_exact
        );
    }
    println!(
        "observed order: {:.3} against the exact solver, {:.3} against the finest resolution",
        r.order_exact, r.order_finest
    );
    if let Some(o) = out {
        let svg = output::plot::convergence(&r)?;
        let files = [
            ("convergence.csv", r.levels_csv()),
            ("efficiency.csv", r.curves_csv()),
            ("convergence.svg", svg),
        ]
        .map(|(n, c)| output::OutputFile {
            name: n.into(),
            contents: c,
        });
        output::write_files(o, &files)?;
        println!("wrote 3 files to {}", o.display());
    }
    println!("wall time {:.2} s", t0.elapsed().as_secs_f64());
    Ok(0)
}

fn reproduce(which: &str, out: &Path) -> contactwave::Result<u8> {
    use contactwave::reproduce::{run_chapter, write_report, Chapter};
    let chapters = Chapter::parse_list(which)?;
    check_out_dir(out)?;
    let t0 = Instant::now();
    let bar = if std::io::stderr().is_terminal() {
        let b = ProgressBar::new(0);
        if let Ok(style) =
            ProgressStyle::with_template("{msg:<28} {bar:30} {pos}/{len} runs  {elapsed_precise}")
        {
            b.set_style(style);
        }
        b
    } else {
        ProgressBar::hidden()
    };
    let current = std::sync::Mutex::new(String::new());
    let progress = |study: &str, done: usize, total: usize| {
        let mut c = current.lock().unwrap_or_else(|p| p.into_inner());
        if *c != study {
            if !c.is_empty() && !bar.is_hidden() {
                bar.println(format!("  done: {c}"));
            }
            *c = study.to_string();
            bar.set_message(study.to_string());
            bar.set_length(total as u64);
            bar.reset_elapsed();
        }
        bar.set_position(done as u64);
    };
    let mut results = Vec::new();
    for ch in chapters {
        let r = run_chapter(ch, &progress)?;
        bar.println(format!(
            "{}: {} figures, {} simulations, {:.1} s",
            ch.name(),
            r.figures.len(),
            r.runs,
            r.seconds
        ));
        results.push(r);
    }
    bar.finish_and_clear();
    let total = t0.elapsed().as_secs_f64();
    let written = write_report(out, &results, total)?;
    for r in &results {
        println!(
            "{}: {} figures, {} simulations, {:.1} s",
            r.chapter.name(),
            r.figures.len(),
            r.runs,
            r.seconds
        );
        for f in &r.findings {
            println!("  {}: {}", f.key, f.line());
        }
    }
    println!(
        "wrote {} files to {} (open {}) in {:.1} s",
        written.len(),
        out.display(),
        out.join("report.html").display(),
        total
    );
    Ok(0)
}

/// A progress bar on stderr when it is a terminal (hidden otherwise).
fn progress_bar() -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(0);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len}  {elapsed_precise} elapsed, eta {eta}")
    {
        b.set_style(style);
    }
    b
}

fn validate() -> contactwave::Result<u8> {
    let cases = study::validation::run_all()?;
    let w = cases.iter().map(|c| c.name.len()).max().unwrap_or(4).max(4);
    println!(
        "{:<w$} | {:>12} | {:>12} | {:>10} | {:>9} | ok",
        "case", "reference", "computed", "rel. error", "tolerance"
    );
    println!("{}", "-".repeat(w + 62));
    let mut failed = 0;
    for c in &cases {
        let ok = c.passed();
        if !ok {
            failed += 1;
        }
        println!(
            "{:<w$} | {:>12.6e} | {:>12.6e} | {:>10.3e} | {:>9.1e} | {}",
            c.name,
            c.reference,
            c.computed,
            c.rel_error,
            c.tolerance,
            if ok { "yes" } else { "NO" }
        );
    }
    println!(
        "{} of {} cases within tolerance",
        cases.len() - failed,
        cases.len()
    );
    Ok(if failed > 0 { 1 } else { 0 })
}

fn bench(points: usize, runs: usize) -> contactwave::Result<u8> {
    let file = "<bench: chapter-3 RCCM scenario>";
    let table = parse_toml(BENCH_SCENARIO, file)?;
    let scenario = Scenario::from_table(table.clone(), Path::new(file))?;
    // (a) one simulation, single thread, median of `runs`
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t0 = Instant::now();
        let s = contactwave::simulate_summary(&scenario)?;
        times.push(t0.elapsed().as_secs_f64());
        std::hint::black_box(s);
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    // (b) xi sweep on all cores, in memory
    let xis = study::linspace(0.05, 1.2, points);
    let scenarios = xis
        .iter()
        .map(|&xi| {
            let mut t = table.clone();
            set_dotted(&mut t, "incident.xi", toml::Value::Float(xi))?;
            Scenario::from_table(t, Path::new(file))
        })
        .collect::<contactwave::Result<Vec<_>>>()?;
    let t0 = Instant::now();
    let results = scenarios
        .par_iter()
        .map(contactwave::simulate_summary)
        .collect::<contactwave::Result<Vec<_>>>()?;
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
        rayon::current_num_threads()
    );
    println!(
        "  total {:.1} ms ({:.3} ms per point)",
        sweep_s * 1e3,
        sweep_s * 1e3 / points as f64
    );
    Ok(0)
}

/// `identify`: estimate the unknowns of an identification file, or rank its design
/// candidates (`--design`). Everything is validated before the output folder is touched.
fn identify_cmd(path: &Path, out: Option<&Path>, design: bool) -> contactwave::Result<u8> {
    use contactwave::inverse::{self, IdentifySpec, Model};
    let spec = IdentifySpec::load(path)?;
    if let Some(out) = out {
        check_out_dir(out)?;
    }
    let quiet = !std::io::stderr().is_terminal();
    let progress = |m: &str| {
        if !quiet {
            eprintln!("{m}");
        }
    };
    if design {
        let model = Model::new(&spec);
        let report = inverse::design(&model)?;
        println!(
            "candidate experiments ranked by log10 det(S^T S) ({} over {} = {} values; {} forward runs in {:.2} s):",
            report.key,
            report.control,
            report.control_values.len(),
            report.forward_runs,
            report.wall_seconds
        );
        print!("{}", report.table());
        if let Some(out) = out {
            let json = serde_json::to_string_pretty(&report.to_json())
                .map_err(|e| Error::io(out, std::io::Error::other(e)))?;
            let files = [
                output::OutputFile {
                    name: "design.json".into(),
                    contents: json + "\n",
                },
                output::OutputFile {
                    name: "design.csv".into(),
                    contents: report.to_csv(),
                },
            ];
            for p in output::write_files(out, &files)? {
                println!("wrote {}", p.display());
            }
        }
        return Ok(0);
    }
    let result = inverse::identify(&spec, &progress)?;
    let files = result.files()?;
    for line in result.verdict_lines() {
        println!("{line}");
    }
    let id = &result.identifiability;
    for (p, v) in result.parameters.iter().zip(&result.estimate.values) {
        println!("estimate {} = {v:.6e}", p.key);
    }
    println!(
        "residual norm {:.4e} ({} residuals), singular values [{}], condition number {:.3e}",
        result.residual_norm(),
        result.measured.residual_count(),
        id.singular_values
            .iter()
            .map(|s| format!("{s:.3e}"))
            .collect::<Vec<_>>()
            .join(", "),
        id.condition_number
    );
    println!(
        "{} forward runs in {:.2} s ({:.0} runs/s)",
        result.forward_runs,
        result.wall_seconds,
        result.forward_runs as f64 / result.wall_seconds.max(1e-9)
    );
    if let Some(out) = out {
        for p in output::write_files(out, &files)? {
            println!("wrote {}", p.display());
        }
    }
    Ok(0)
}

/// `identify --synthesize KEY=VALUE ...`: synthetic data of an identification file on stdout.
fn synthesize_cmd(path: &Path, pairs: &[String], noise: f64, seed: u64) -> contactwave::Result<u8> {
    use contactwave::inverse::{synthesize, IdentifySpec};
    let spec = IdentifySpec::load(path)?;
    let truth = pairs
        .iter()
        .map(|p| {
            let (k, v) = p.split_once('=').unwrap_or((p, ""));
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .map(|x| (k.trim().to_string(), x))
                .ok_or_else(|| {
                    Error::invalid("--synthesize", k, v, "KEY=VALUE with a finite number")
                })
        })
        .collect::<contactwave::Result<Vec<_>>>()?;
    let data = synthesize(&spec, &truth, noise, seed)?;
    let comment = format!(
        "synthetic data: contactwave identify {} --synthesize {} --noise {noise} --seed {seed}",
        path.display(),
        pairs.join(" --synthesize ")
    );
    print!("{}", data.measured.to_csv(&comment));
    Ok(0)
}

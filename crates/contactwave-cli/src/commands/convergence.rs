//! `contactwave convergence SCENARIO`: convergence study of a half-space scenario (thesis
//! eqs. 2.42-2.43, Figure 22). Computes A_n/A_inc over a grid of load ratios xi for a
//! series of resolutions and prints, per resolution, the error against the finest one and
//! against the exact solver, then the observed order. With `--out DIR` it also writes
//! DIR/convergence.csv, DIR/efficiency.csv and DIR/convergence.svg.

use super::{
    check_out, output_file, progress_bar, read_table, step_reporter, EXIT_OK, STEPS_TEMPLATE,
};
use contactwave::output;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::solid_2d::Solid2dScenario;
use contactwave::study::convergence::{run_convergence, ConvergenceMethod, ConvergenceSpec};
use contactwave::Error;
use std::path::PathBuf;
use std::time::Instant;

/// Solver refined by `convergence`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ConvMethod {
    /// The finite-difference scheme (Courant 1: dx = c dt).
    Fd,
    /// The exact solver (its output sampling).
    Exact,
}

/// Convergence study of a half-space scenario (thesis eqs. 2.42-2.43, Figure 22):
/// A2/A_inc over a grid of xi for a series of resolutions; prints the error of each
/// against the finest one and against the exact solver, and the observed order.
#[derive(clap::Args)]
pub struct Args {
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
    #[command(flatten)]
    overwrite: super::Overwrite,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let (path, out) = (args.scenario.as_path(), args.out.as_deref());
    let table = read_table(path)?;
    let other = if BarStackScenario::is_bar_stack(&table) {
        Some("\"bar_stack\"")
    } else if Solid2dScenario::is_solid_2d(&table) {
        Some("\"solid_2d\" (its convergence: docs/model.md section 15.4 and `validate`)")
    } else {
        None
    };
    if let Some(kind) = other {
        return Err(Error::invalid(
            path.display().to_string(),
            "model.kind",
            kind,
            "a half-space scenario (the study compares with the exact solver)",
        ));
    }
    let mut spec = ConvergenceSpec {
        method: match args.method {
            ConvMethod::Fd => ConvergenceMethod::Fd,
            ConvMethod::Exact => ConvergenceMethod::Exact,
        },
        harmonic: args.harmonic,
        ..ConvergenceSpec::default()
    };
    if let Some(v) = args.spp {
        spec.samples_per_period = v;
    }
    if let Some(v) = args.xi {
        spec.xi = v;
    }
    let source = super::source("convergence", &[path]);
    if let Some(o) = out {
        check_out(o, &source, args.overwrite)?;
    }
    let bar = progress_bar(STEPS_TEMPLATE, 0);
    let t0 = Instant::now();
    let r = run_convergence(&table, path, &spec, &step_reporter(&bar))?;
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
            output_file("convergence.csv", r.levels_csv()),
            output_file("efficiency.csv", r.curves_csv()),
            output_file("convergence.svg", svg),
        ];
        super::check_names(o, files.iter().map(|f| f.name.as_str()), args.overwrite)?;
        output::write_files(o, &files)?;
        super::claim_files(o, "convergence", &source, &files)?;
        println!("wrote 3 files to {}", o.display());
    }
    println!("wall time {:.2} s", t0.elapsed().as_secs_f64());
    Ok(EXIT_OK)
}

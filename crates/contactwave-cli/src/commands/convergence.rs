//! `contactwave convergence SCENARIO`: convergence study of a half-space scenario (thesis
//! eqs. 2.42-2.43, Figure 22) or of a 2D one (docs/model.md section 15.4). Half-space:
//! A_n/A_inc over a grid of load ratios xi for a series of resolutions; prints, per
//! resolution, the error against the finest one and against the exact solver, then the
//! observed order; with `--out DIR` it also writes DIR/convergence.csv, DIR/efficiency.csv
//! and DIR/convergence.svg. 2D: the scenario at a sequence of element sizes; prints, per
//! level, the mesh, the cracks' split nodes and each receiver's A_n/A1 with its change
//! against the finest level, then each one's observed order and the estimated error of the
//! scenario's own level; with `--out DIR` it writes DIR/convergence.csv,
//! DIR/convergence_order.csv and DIR/convergence.svg.

use super::{
    check_out, output_file, progress_bar, read_table, step_reporter, EXIT_OK, STEPS_TEMPLATE,
};
use contactwave::output;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::solid_2d::Solid2dScenario;
use contactwave::study::convergence::{run_convergence, ConvergenceMethod, ConvergenceSpec};
use contactwave::study::convergence_2d::{
    plan_convergence_2d, Convergence2dResult, Convergence2dSpec, MIN_ORDER,
};
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
/// against the finest one and against the exact solver, and the observed order. Of a 2D
/// scenario (`kind = "solid_2d"`, docs/model.md section 15.4): the scenario at a sequence of
/// element sizes (its own, then each `--ratio` times smaller); prints each receiver's
/// A2/A1 and A3/A1 per level with its change against the finest, the observed order
/// (Richardson, last three levels) and the estimated error of the scenario's own level.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (TOML): half-space (its xi and resolution are overridden) or 2D (its
    /// element size is).
    scenario: PathBuf,
    /// Half-space: resolutions in samples per period of the highest input frequency (with
    /// the FD solver dx = c dt). Default 125,250,500,1000,2000,4000.
    #[arg(long, value_name = "N,N,...", value_delimiter = ',')]
    spp: Option<Vec<usize>>,
    /// Half-space: load ratios. Default 0.1,0.2,...,1.0 (the thesis' xi in ]0, 1]).
    #[arg(long, value_name = "XI,XI,...", value_delimiter = ',')]
    xi: Option<Vec<f64>>,
    /// Half-space: solver to refine (default fd).
    #[arg(long, value_enum)]
    method: Option<ConvMethod>,
    /// Harmonic studied: half-space A_n/A_inc (1 to 5, default 2); 2D A_n/A1 at every
    /// receiver (2 to 5; default 2 and 3).
    #[arg(long)]
    harmonic: Option<usize>,
    /// 2D: number of element sizes, 3 to 8 (default 6: 15 to 25 s on 2 cores for
    /// examples/solid_2d/plate_crack_quick.toml; each more level about 3.5 times as long;
    /// on a mesh, default 3, each level `mesh.refine` times the ratio, at most 8).
    #[arg(long, value_name = "N")]
    levels: Option<usize>,
    /// 2D: ratio of one element size to the next, 1.1 to 4 (default 1.5; on a mesh an
    /// integer, default 2: each element split into ratio x ratio).
    #[arg(long, value_name = "R")]
    ratio: Option<f64>,
    /// Also write the study's files into DIR (half-space: convergence.csv, efficiency.csv
    /// and convergence.svg; 2D: convergence.csv, convergence_order.csv and
    /// convergence.svg).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

/// An option given for the other kind of scenario: an error naming it.
fn refuse(path: &std::path::Path, option: &str, value: String, kind: &str) -> Error {
    Error::invalid(
        path.display().to_string(),
        option,
        value,
        format!("only for {kind} scenarios"),
    )
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let (path, out) = (args.scenario.as_path(), args.out.as_deref());
    let table = read_table(path)?;
    if Solid2dScenario::is_solid_2d(&table) {
        return run_2d(&args, table);
    }
    if BarStackScenario::is_bar_stack(&table) {
        return Err(Error::invalid(
            path.display().to_string(),
            "model.kind",
            "\"bar_stack\"",
            "a half-space scenario (the study compares with the exact solver) or a 2D one",
        ));
    }
    if let Some(n) = args.levels {
        return Err(refuse(path, "--levels", n.to_string(), "2D"));
    }
    if let Some(r) = args.ratio {
        return Err(refuse(path, "--ratio", r.to_string(), "2D"));
    }
    let mut spec = ConvergenceSpec {
        method: match args.method.unwrap_or(ConvMethod::Fd) {
            ConvMethod::Fd => ConvergenceMethod::Fd,
            ConvMethod::Exact => ConvergenceMethod::Exact,
        },
        harmonic: args.harmonic.unwrap_or(2),
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

/// Quantities printed per table block (each a value and its change).
const COLUMNS: usize = 4;
/// Most quantities printed (a receiver line's points are many: convergence.csv has all).
const PRINTED: usize = 16;

/// The 2D study: options checked, levels run, tables printed, files written.
fn run_2d(args: &Args, table: toml::Table) -> contactwave::Result<u8> {
    let (path, out) = (args.scenario.as_path(), args.out.as_deref());
    if let Some(v) = &args.spp {
        return Err(refuse(path, "--spp", format!("{v:?}"), "half-space"));
    }
    if let Some(v) = &args.xi {
        return Err(refuse(path, "--xi", format!("{v:?}"), "half-space"));
    }
    if args.method.is_some() {
        return Err(refuse(path, "--method", "given".into(), "half-space"));
    }
    let mut spec = Convergence2dSpec {
        levels: args.levels,
        ratio: args.ratio,
        ..Convergence2dSpec::default()
    };
    if let Some(n) = args.harmonic {
        spec.harmonics = vec![n];
    }
    let template = contactwave::model::plan_valid(table, path)?;
    let base = template.base()?;
    base.check_budget()?;
    // the scenario's own warnings (a crack too short for its elements among them): the
    // study measures what they warn of
    for w in base.warnings() {
        eprintln!("warning: {w}");
    }
    let source = super::source("convergence", &[path]);
    if let Some(o) = out {
        check_out(o, &source, args.overwrite)?;
    }
    let t0 = Instant::now();
    let plan = plan_convergence_2d(template.as_ref(), &spec)?;
    let total: f64 = plan.node_updates.iter().sum();
    let last = plan.element_sizes.len() - 1;
    eprintln!(
        "{} element sizes, {:.3e} to {:.3e} m: about {total:.1e} node-updates in all ({:.0} % \
         in the finest)",
        plan.element_sizes.len(),
        plan.element_sizes[0],
        plan.element_sizes[last],
        100.0 * plan.node_updates[last] / total
    );
    let bar = progress_bar(STEPS_TEMPLATE, 0);
    let reporter = super::progress::Reporter::new(&bar, "levels");
    let r = plan.run(&move |d, n| reporter.report(d, n));
    bar.finish_and_clear();
    let r = r?;
    for line in report_2d(&r) {
        println!("{line}");
    }
    if let Some(o) = out {
        let files = [
            output_file("convergence.csv", r.levels_csv()),
            output_file("convergence_order.csv", r.order_csv()),
            output_file("convergence.svg", output::plot::convergence_2d(&r)?),
        ];
        super::check_names(o, files.iter().map(|f| f.name.as_str()), args.overwrite)?;
        output::write_files(o, &files)?;
        super::claim_files(o, "convergence", &source, &files)?;
        println!("wrote 3 files to {}", o.display());
    }
    println!("wall time {:.2} s", t0.elapsed().as_secs_f64());
    Ok(EXIT_OK)
}

/// A relative change as a signed percentage (`n/a` where not finite).
fn percent(v: f64) -> String {
    if v.is_finite() {
        format!("{:+.2} %", 100.0 * v)
    } else {
        "n/a".into()
    }
}

/// The lines `convergence` prints for a 2D study.
fn report_2d(r: &Convergence2dResult) -> Vec<String> {
    let mut out = Vec::new();
    let first = &r.levels[0];
    let cracks: Vec<String> = r
        .cracks
        .iter()
        .enumerate()
        .map(|(i, l)| format!("crack {i} {l:.3e} m"))
        .collect();
    out.push(format!(
        "2D convergence of {} in space: {} element sizes from {:.4e} m (the scenario's own) \
         down by {}{}",
        r.file,
        r.levels.len(),
        first.element_size,
        r.ratio,
        if cracks.is_empty() {
            String::new()
        } else {
            format!("; {}", cracks.join(", "))
        }
    ));
    out.push(format!(
        "{:>5} | {:>11} | {:>9} | {:>6} | {:>11} | split nodes",
        "level", "element (m)", "nodes", "steps", "dt (s)"
    ));
    for (k, l) in r.levels.iter().enumerate() {
        let split: Vec<String> = l.split_nodes.iter().map(|n| n.to_string()).collect();
        out.push(format!(
            "{k:>5} | {:>11.4e} | {:>9} | {:>6} | {:>11.4e} | {}",
            l.element_size,
            l.nodes,
            l.steps,
            l.dt,
            if split.is_empty() {
                "-".into()
            } else {
                split.join(", ")
            }
        ));
    }
    let shown = r.quantities.len().min(PRINTED);
    let name = |i: usize| {
        let q = &r.quantities[i];
        format!("{} A{}/A1", r.receivers[q.receiver], q.harmonic)
    };
    for block in (0..shown).collect::<Vec<_>>().chunks(COLUMNS) {
        let mut head = format!("{:>5}", "level");
        for &i in block {
            head.push_str(&format!(" | {:>24}", name(i)));
        }
        out.push(head);
        for (k, l) in r.levels.iter().enumerate() {
            let mut row = format!("{k:>5}");
            for &i in block {
                row.push_str(&format!(
                    " | {:>11.4e} ({:>9})",
                    l.values[i],
                    percent(l.change[i])
                ));
            }
            out.push(row);
        }
    }
    out.push(format!(
        "(in parentheses: the change against the finest level) observed order (Richardson, \
         levels {}-{}) and estimated error of the scenario's own level:",
        r.levels.len() - 3,
        r.levels.len() - 1
    ));
    for i in 0..shown {
        let (p, ext) = (r.order[i], r.extrapolated[i]);
        let order = if !p.is_finite() {
            "n/a (the last three levels oscillate)".into()
        } else if p < MIN_ORDER {
            format!("{p:.2} (below {MIN_ORDER}: not converging over the last three levels)")
        } else {
            format!("{p:.2}")
        };
        let against = if ext.is_finite() {
            format!("against the extrapolated {ext:.4e}")
        } else {
            "against the finest level: a lower bound".into()
        };
        out.push(format!(
            "  {:<24} order {order}, error {} ({against})",
            name(i),
            percent(r.default_error[i])
        ));
    }
    if shown < r.quantities.len() {
        out.push(format!(
            "  ... {} quantities in all (convergence.csv, convergence_order.csv)",
            r.quantities.len()
        ));
    }
    for (name, m) in r.receivers.iter().zip(&r.moved) {
        if *m > 0.0 {
            out.push(format!(
                "note: {name} records at the node nearest its position, which moves with the \
                 mesh (up to {m:.3e} m over the levels): its changes include the move (a \
                 receiver on a mesh line, a crack's middle or a corner stays put)"
            ));
        }
    }
    out
}

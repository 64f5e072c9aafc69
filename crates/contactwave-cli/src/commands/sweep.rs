//! `contactwave sweep SWEEP --out DIR`: run the points of a parameter sweep on a thread pool
//! and write DIR/sweep.csv (one row per point, appended as points finish, sorted by point
//! once finished), its hash file DIR/sweep.csv.hash, DIR/sweep.svg, the provenance
//! DIR/provenance.json (docs/outputs.md), with --hdf5 DIR/sweep.h5, and, if points fail,
//! DIR/sweep_errors.csv (exit code 1 unless --tolerate-failures).
//!
//! `--resume` computes only the points missing from an existing sweep.csv, `--shard K/N`
//! one shard of the points (combined by `merge`). Ctrl-C or SIGTERM stops the running
//! points at their next check (exit code 130, rerun with --resume); a second one exits at
//! once.

use super::{
    cancel_on_ctrl_c, check_names, check_out, claim_out, output_file, progress_bar, EXIT_FAILED,
    EXIT_INTERRUPTED, EXIT_OK,
};
use contactwave::output;
use contactwave::output::provenance::{self, process_command_line, Provenance};
use contactwave::study::{self, Sweep, SweepOptions};
use contactwave::Error;
use std::path::PathBuf;

/// Run a parameter sweep and write DIR/sweep.csv (one row per point: point index,
/// swept parameters in their SI units, summary values), DIR/sweep.csv.hash and
/// DIR/sweep.svg. Points whose simulation fails are listed in DIR/sweep_errors.csv.
#[derive(clap::Args)]
pub struct Args {
    /// Sweep file (TOML: `base = "scenario.toml"` and `[[axis]]` tables).
    sweep: PathBuf,
    /// Output folder (created if needed; another run's results in it are kept unless
    /// --overwrite).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
    /// Keep the rows of an existing sweep.csv of the same sweep and compute only the
    /// missing points (refused if the sweep, its base scenario or the version changed).
    #[arg(long)]
    resume: bool,
    /// Worker threads, 1 to 1024 (default: one per core).
    #[arg(long, value_name = "N",
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new()
              .range(1..=contactwave::run::MAX_THREADS as u64))]
    threads: Option<usize>,
    /// Run only shard K of N: the points whose index i has i % N == K - 1 (1 <= K <= N).
    /// Header and hash file are those of the whole sweep; combine shards with `merge`.
    #[arg(long, value_name = "K/N", value_parser = study::Shard::parse)]
    shard: Option<study::Shard>,
    /// Exit 0 even when points fail (their messages are in DIR/sweep_errors.csv); without
    /// it a sweep with failed points exits 1 after writing every row it could.
    #[arg(long)]
    tolerate_failures: bool,
    /// Also write DIR/sweep.h5: every column of sweep.csv as a dataset of the group
    /// /sweep with `units` and `description` attributes, the provenance as attributes of
    /// the root group (docs/outputs.md).
    #[arg(long)]
    hdf5: bool,
    /// Run the sweep even where its base scenario holds a slip that cannot be meant (a 2D
    /// source whose wave does not fit the rectangle, a side over 10 m: docs/scenario.md
    /// section 1.2), which is refused without it.
    #[arg(long)]
    yes: bool,
}

/// The files a sweep writes into its folder (those that exist are its manifest).
const SWEEP_FILES: [&str; 7] = [
    "sweep.csv",
    "sweep.csv.hash",
    "sweep.csv.shard",
    "sweep.svg",
    "sweep_errors.csv",
    provenance::SIDECAR,
    output::hdf5::SWEEP_FILE,
];

pub fn run(args: Args) -> contactwave::Result<u8> {
    let out = args.out.as_path();
    let sweep = Sweep::load(&args.sweep)?;
    let source = super::source("sweep", &[&args.sweep]);
    check_out(out, &source, args.overwrite)?;
    // a sweep.csv (or another of the sweep's files) contactwave did not write is not
    // replaced (--resume reads it, and refuses one of another sweep)
    if !args.resume {
        check_names(out, SWEEP_FILES, args.overwrite)?;
    }
    // every point validated before the folder or any file is created (progress on a
    // terminal: a large grid takes seconds)
    let setup = progress_bar(
        "validating {bar:40} {pos}/{len} points  {elapsed_precise} elapsed, eta {eta}",
        sweep.points.len() as u64,
    );
    let checked = |d: usize, _total: usize| {
        if d.is_multiple_of(1024) || d == sweep.points.len() {
            setup.set_position(d as u64);
        }
    };
    let validated = sweep.validate_with(&checked);
    setup.finish_and_clear();
    validated?;
    // the base scenario's likely unit slips (one line each; the sweep goes on, unless
    // one cannot be meant and --yes is not given)
    if let Ok(base) = contactwave::model::plan(sweep.base_table.clone(), &sweep.base).base() {
        let slips = base.warnings();
        super::run::refuse_slips(&slips, args.yes)?;
        for w in slips {
            eprintln!("warning: {w}");
        }
    }
    // the input files hashed as read; the sidecar provenance.json beside sweep.csv
    // (a plain table for pandas and `merge`) is written once the rows are
    let prov = Provenance::of_sweep(&sweep, process_command_line())?;
    let cancel = cancel_on_ctrl_c();
    let shard = args.shard.unwrap_or(study::Shard::ALL);
    let total = (0..sweep.points.len())
        .filter(|&i| shard.contains(i))
        .count();
    let bar = progress_bar(
        "{bar:40} {pos}/{len} points  {elapsed_precise} elapsed, eta {eta}",
        total as u64,
    );
    // (lines with the time left in a log, the time estimate once measured)
    let reporter = super::progress::Reporter::new(&bar, "points");
    let progress = |d: usize, t: usize| reporter.report(d, t);
    let csv = out.join("sweep.csv");
    let opts = SweepOptions {
        threads: args.threads,
        resume: args.resume,
        validated: true,
    };
    // the folder's manifest: the sweep's files (which --resume keeps); an earlier
    // command's other files are removed
    let claim = || {
        // written also after Ctrl-C (the rows on disk are complete): plain writes, not
        // output::write_files, which stops at an interruption
        if csv.is_file() {
            let put = |name: &str, bytes: &[u8]| {
                let path = out.join(name);
                std::fs::write(&path, bytes).map_err(|e| Error::io(&path, e))
            };
            put(provenance::SIDECAR, prov.sidecar().contents.as_bytes())?;
            if args.hdf5 {
                let table = study::read_sweep_csv(&csv)?;
                let h5 = output::hdf5::sweep_file(&table, &prov)?;
                put(&h5.name, &h5.bytes)?;
            }
        }
        let names: Vec<String> = SWEEP_FILES
            .iter()
            // a sweep.h5 of an earlier `--hdf5` run is removed by a run without it
            .filter(|n| out.join(n).is_file() && (args.hdf5 || **n != output::hdf5::SWEEP_FILE))
            .map(|n| n.to_string())
            .collect();
        claim_out(out, "sweep", &source, &names)
    };
    match study::run_sweep_shard(&sweep, shard, &csv, &opts, &progress, cancel) {
        Ok(report) => {
            bar.finish_and_clear();
            let mut plotted = false;
            if let Some(svg) = output::sweep_svg(&sweep, &csv)? {
                output::write_files(out, &[output_file("sweep.svg", svg)])?;
                plotted = true;
            }
            claim()?;
            println!(
                "{} points: {} computed, {} already done, {} failed",
                report.total, report.computed, report.skipped, report.failed
            );
            println!("wrote {}", csv.display());
            if plotted {
                println!("wrote {}", out.join("sweep.svg").display());
            }
            if let Ok(t) = study::read_sweep_csv(&csv) {
                if let Some(c) = t.column("harmonic_floor_warning") {
                    let n = t.rows.iter().filter(|r| r.get(c) == Some(&1.0)).count();
                    if n > 0 {
                        eprintln!(
                            "warning: {n} of {} points have a harmonic within a factor 10 of its analysis floor (harmonic_floor_warning = 1, A*_floor_over_Ainc); see [analysis] method in docs/scenario.md",
                            t.rows.len()
                        );
                    }
                }
            }
            if let Some(e) = report.errors_csv {
                let first = first_error(&e);
                let what = if args.tolerate_failures {
                    "warning"
                } else {
                    "error"
                };
                eprintln!(
                    "{what}: {} of {} points failed (messages in {}); first: {first}",
                    report.failed,
                    report.total,
                    e.display()
                );
                if !args.tolerate_failures {
                    return Ok(EXIT_FAILED);
                }
            }
            Ok(EXIT_OK)
        }
        Err(Error::Interrupted) => {
            bar.abandon();
            claim()?;
            // what is on disk: the rows of the CSV (points stopped mid-run have none)
            let saved = study::read_sweep_csv(&csv).map_or(0, |t| t.rows.len());
            eprintln!(
                "interrupted: {saved} of {total} points saved in {}; rerun with --resume",
                csv.display()
            );
            Ok(EXIT_INTERRUPTED)
        }
        Err(e) => {
            bar.abandon();
            Err(e)
        }
    }
}

/// The first message of an errors file (`point,message` rows): `point N: MESSAGE`.
fn first_error(path: &std::path::Path) -> String {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| {
            t.lines().nth(1).map(|l| {
                let (p, m) = l.split_once(',').unwrap_or(("?", l));
                format!("point {p}: {}", m.trim_matches('"').replace("\"\"", "\""))
            })
        })
        .unwrap_or_else(|| "(unreadable)".to_string())
}

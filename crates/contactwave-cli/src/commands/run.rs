//! `contactwave run SCENARIO --out DIR`: simulate one scenario and print its summary.
//!
//! A half-space scenario writes summary.json, timeseries.csv, probe.csv, spectrum.csv and
//! SVG plots into DIR; a bar-stack scenario (thesis chapter 4) writes the files of the
//! hammer test (FRF and modes) or of its incident wave; a 2D scenario its receivers,
//! crack fields, plots and snapshots; long runs with a progress bar on a terminal (plain
//! progress lines without one).

use super::{check_out, progress_bar, read_table, step_reporter, EXIT_OK, STEPS_TEMPLATE};
use contactwave::human;
use contactwave::model::{self, RunControl};
use contactwave::output;
use contactwave::output::provenance::{process_command_line, Provenance};
use contactwave::output::recording::{self, Recording, Series};
use contactwave::solver::bar_stack::StepProgress;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// Simulate one scenario and write its files into DIR (SI units: s, m, Pa, m/s, Hz): for a
/// half-space scenario summary.json, timeseries.csv, probe.csv, spectrum.csv and SVG plots;
/// for a bar stack summary.json, timeseries.csv, then frf.csv and frf.svg (hammer) or
/// waves.csv (incident wave), and probes.csv with [[probe]] tables; for a 2D scenario
/// summary.json, receivers.csv, crack.csv, receivers.svg, spectra.svg, crack_state.svg,
/// crack_map.png, crack_state.png and, with [snapshots], snapshots/frame_NNNN.png, a GIF and VTK files
/// (docs/scenario.md section 4). Ctrl-C stops it (exit 130, nothing written).
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (TOML; see docs/scenario.md).
    scenario: PathBuf,
    /// Output folder (created if needed; this run's earlier files in it are replaced,
    /// another run's results are kept unless --overwrite).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
    /// Recorded series written (timeseries.csv, probe.csv, probes.csv, waves.csv,
    /// receivers.csv):
    /// `decimated` keeps at most 20000 rows per file (every k-th time sample), `full`
    /// every time sample, `none` no such file. Summaries, spectra and FRFs use the full
    /// series whatever the choice.
    #[arg(long, value_enum, default_value_t = Record::Decimated)]
    record: Record,
    /// Sampling step of the written series, s (rounded to whole time steps; implies
    /// `--record decimated`).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    record_step: Option<f64>,
    /// Also write DIR/result.h5: every table of the run (the recorded series, receivers,
    /// crack fields, spectra) as datasets with `units` and `description` attributes, the
    /// summary and the provenance as attributes (docs/outputs.md; MATLAB h5read, h5py).
    #[arg(long)]
    hdf5: bool,
    /// Run a scenario even where it holds a slip that cannot be meant (a 2D source whose
    /// wave does not fit the rectangle, a side over 10 m: docs/scenario.md section 1.2),
    /// which is refused without it.
    #[arg(long)]
    yes: bool,
}

/// Refuse the first of `warnings` that is a slip that cannot be meant
/// ([`contactwave::scenario::Warning::blocking`]) unless `yes` (`--yes`): an error naming
/// its file, key and value (exit 2, nothing run or written).
pub fn refuse_slips(
    warnings: &[contactwave::scenario::Warning],
    yes: bool,
) -> contactwave::Result<()> {
    match warnings.iter().find(|w| w.blocking) {
        Some(w) if !yes => Err(contactwave::Error::invalid(
            &w.file,
            &w.field,
            &w.value,
            format!("{}; nothing was run (--yes runs it as it is)", w.reason),
        )),
        _ => Ok(()),
    }
}

/// `--record`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Record {
    None,
    Decimated,
    Full,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let t0 = Instant::now();
    let (path, out) = (args.scenario.as_path(), args.out.as_path());
    let recording = Recording {
        series: match args.record {
            Record::None => Series::None,
            Record::Decimated => Series::Decimated,
            Record::Full => Series::Full,
        },
        step: args.record_step,
    };
    recording.validate()?;
    let template = model::plan_valid(read_table(path)?, path)?;
    // a run beyond the memory budget is refused before any warning: its error is the one line
    let base = template.base()?;
    base.check_budget()?;
    // values that are legal but almost surely a unit slip: one line each, the run goes on
    // (a slip that cannot be meant stops it, unless --yes)
    let slips = base.warnings();
    refuse_slips(&slips, args.yes)?;
    for w in &slips {
        eprintln!("warning: {w}");
    }
    let source = super::source("run", &[path]);
    check_out(out, &source, args.overwrite)?;
    // the input files hashed as read (a file edited during the run does not change them)
    let provenance = Provenance::of_scenario(path, process_command_line())?;
    // long runs report progress: a bar on a terminal, lines in a log
    let bar = progress_bar(STEPS_TEMPLATE, 0);
    let control = RunControl {
        progress: Some(StepProgress(Arc::new(step_reporter(&bar)))),
    };
    let outcome = base.run(&control);
    bar.finish_and_clear();
    let outcome = outcome?;
    let simulated = t0.elapsed();
    let mut files = recording::files(&*outcome, &recording)?;
    // every warning of the run in summary.json: the scenario's, then the results'
    let mut warnings: Vec<String> = slips.iter().map(|w| w.to_string()).collect();
    warnings.extend(outcome.warnings());
    contactwave::render::stamp_warnings(&mut files, &warnings);
    provenance.stamp(&mut files);
    // every file is rendered before the first is written: an error writes nothing
    let mut binary = outcome.binary_files()?;
    if args.hdf5 {
        binary.push(output::hdf5::run_file(&files, &provenance)?);
    }
    let names = files.iter().map(|f| f.name.as_str());
    let names = names.chain(binary.iter().map(|f| f.name.as_str()));
    provenance.check_inputs_kept(out, names.clone())?;
    super::check_names(out, names, args.overwrite)?;
    // all or none: an interruption while writing leaves the folder as it was
    output::write_all(out, &files, &binary)?;
    let mut names: Vec<String> = files.iter().map(|f| f.name.clone()).collect();
    names.extend(binary.iter().map(|f| f.name.clone()));
    super::claim_out(out, "run", &source, &names)?;
    println!("scenario               {}", path.display());
    for line in outcome.report() {
        println!("{line}");
    }
    // the whole command: the scenario read, the run and its files rendered and written
    let wall = t0.elapsed();
    println!(
        "wall time              {} (simulation {}, files {})",
        human::duration(wall.as_secs_f64()),
        human::duration(simulated.as_secs_f64()),
        human::duration((wall - simulated).as_secs_f64())
    );
    println!("wrote {} files to {}", names.len(), out.display());
    Ok(EXIT_OK)
}

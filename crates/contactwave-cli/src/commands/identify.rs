//! `contactwave identify SPEC`: inverse problem on an identification file (base scenario,
//! measured CSV, unknown parameters with bounds and scale; docs/identify.md).
//!
//! - default: estimate the unknowns, print the verdict, estimates, residual and
//!   identifiability figures, and write DIR/identification.json, fit.csv, fit.svg,
//!   sensitivity.svg and identification.html;
//! - `--design`: rank the candidate experiments of the file's `[design]` table, print the
//!   table and, with `--out`, write DIR/design.json and design.csv;
//! - `--synthesize KEY=VALUE ...`: print synthetic data (CSV on stdout), no files.
//!
//! Everything is validated before the output folder is touched.

use super::{check_out, output_file, write_out, Overwrite, EXIT_FAILED, EXIT_OK};
use contactwave::inverse::{self, synthesize, IdentifySpec, Model};
use contactwave::Error;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// Identify interface parameters from a measured curve (identification file: base
/// scenario, measured CSV, unknown parameters with bounds and scale; docs/identify.md).
/// Writes DIR/identification.json, fit.csv, fit.svg, sensitivity.svg and
/// identification.html. With --design, ranks the [design] candidates instead and
/// prints a table (and writes DIR/design.json and design.csv if --out is given).
#[derive(clap::Args)]
pub struct Args {
    /// Identification file (TOML).
    spec: PathBuf,
    /// Output folder (created if needed; another run's results in it are kept unless
    /// --overwrite).
    #[arg(long, value_name = "DIR", required_unless_present_any = ["design", "synthesize"])]
    out: Option<PathBuf>,
    #[command(flatten)]
    overwrite: super::Overwrite,
    /// Rank the candidate experiments of the file's [design] table.
    #[arg(long)]
    design: bool,
    /// Print synthetic data instead (CSV on stdout): the file's data rows simulated
    /// with KEY=VALUE for the unknowns (repeat the option), times 1 + noise * N(0, 1);
    /// with [records], the raw records (t, record_1, ...) through the file's transducer
    /// plus white noise of noise times each record's peak.
    #[arg(long, value_name = "KEY=VALUE")]
    synthesize: Vec<String>,
    /// Relative noise of --synthesize, 0 to 1 [default: 0.01].
    #[arg(long)]
    noise: Option<f64>,
    /// Seed of the --synthesize noise [default: 1].
    #[arg(long)]
    seed: Option<u64>,
    /// Exit 0 even when forward runs fail (the fit gives their parameter points a
    /// prohibitive cost and goes on); without it an identification with failed forward
    /// runs exits 1 after writing its files.
    #[arg(long)]
    tolerate_failures: bool,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    // options of one mode given to the other would be ignored without a word
    let misplaced = if args.synthesize.is_empty() {
        (args.noise.map(|v| ("--noise", v.to_string())))
            .or(args.seed.map(|v| ("--seed", v.to_string())))
            .map(|(k, v)| (k, v, "only with --synthesize, whose data it makes"))
    } else {
        (args
            .out
            .as_ref()
            .map(|o| ("--out", o.display().to_string())))
        .map(|(k, v)| {
            (
                k,
                v,
                "not with --synthesize, which prints its data on stdout (redirect them to a file)",
            )
        })
    };
    if let Some((key, value, allowed)) = misplaced {
        return Err(Error::invalid("<command line>", key, value, allowed));
    }
    let noise = args.noise.unwrap_or(0.01);
    if !(0.0..=1.0).contains(&noise) {
        return Err(Error::invalid(
            "<command line>",
            "--noise",
            noise,
            "a relative noise from 0 to 1",
        ));
    }
    let seed = args.seed.unwrap_or(1);
    if args.synthesize.is_empty() {
        identify(
            &args.spec,
            args.out.as_deref(),
            args.design,
            args.tolerate_failures,
            args.overwrite,
        )
    } else {
        synthesize_data(&args.spec, &args.synthesize, noise, seed)
    }
}

/// Estimate the unknowns of an identification file, or rank its design candidates
/// (`design`). Forward runs that failed: exit 1 (count and first message on stderr)
/// unless `tolerate`.
fn identify(
    path: &Path,
    out: Option<&Path>,
    design: bool,
    tolerate: bool,
    overwrite: Overwrite,
) -> contactwave::Result<u8> {
    let spec = IdentifySpec::load(path)?;
    let source = super::source("identify", &[path]);
    if let Some(out) = out {
        check_out(out, &source, overwrite)?;
    }
    let provenance = identification_provenance(path, &spec)?;
    // on a terminal: a spinner with the elapsed time and the current stage, each finished
    // stage printed above it; nothing otherwise
    let spinner = if std::io::stderr().is_terminal() {
        let b = indicatif::ProgressBar::new_spinner();
        if let Ok(style) =
            indicatif::ProgressStyle::with_template("{spinner} {elapsed_precise} {msg}")
        {
            b.set_style(style);
        }
        b.set_message("identifying (forward runs on all cores)");
        b.enable_steady_tick(std::time::Duration::from_millis(200));
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    let progress = |m: &str| {
        spinner.println(m);
        spinner.set_message(format!("after: {m}"));
    };
    if design {
        let model = Model::new(&spec);
        spinner.set_message("ranking the design candidates");
        let report = inverse::design(&model);
        spinner.finish_and_clear();
        let report = report?;
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
            let mut files = [
                output_file("design.json", json + "\n"),
                output_file("design.csv", report.to_csv()),
            ];
            provenance.stamp(&mut files);
            provenance.check_inputs_kept(out, files.iter().map(|f| f.name.as_str()))?;
            write_out(out, "identify", &source, overwrite, &files)?;
        }
        return Ok(EXIT_OK);
    }
    let result = inverse::identify(&spec, &progress);
    spinner.finish_and_clear();
    let result = result?;
    let mut files = contactwave::output::identify::identification_files(&result)?;
    provenance.stamp(&mut files);
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
        provenance.check_inputs_kept(out, files.iter().map(|f| f.name.as_str()))?;
        write_out(out, "identify", &source, overwrite, &files)?;
    }
    if result.failed_runs > 0 {
        let what = if tolerate { "warning" } else { "error" };
        eprintln!(
            "{what}: {} of {} forward runs failed (the fit gave them a prohibitive cost; --tolerate-failures to accept); first: {}",
            result.failed_runs,
            result.forward_runs,
            result.first_failure.as_deref().unwrap_or("(no message)")
        );
        if !tolerate {
            return Ok(EXIT_FAILED);
        }
    }
    Ok(EXIT_OK)
}

/// The provenance of an identification: the identification file as the input, its base
/// scenario, the base's waveform files and its data CSV as data files.
fn identification_provenance(
    path: &Path,
    spec: &IdentifySpec,
) -> contactwave::Result<contactwave::output::provenance::Provenance> {
    use contactwave::output::provenance::{process_command_line, Provenance};
    Provenance::of_identification(path, spec, process_command_line())
}

/// `--synthesize KEY=VALUE ...`: synthetic data of an identification file on stdout.
fn synthesize_data(
    path: &Path,
    pairs: &[String],
    noise: f64,
    seed: u64,
) -> contactwave::Result<u8> {
    // with [records] the record files are what is made: they need not exist yet
    let spec = IdentifySpec::load_unmeasured(path)?;
    let truth = pairs
        .iter()
        .map(|p| {
            let (k, v) = p.split_once('=').unwrap_or((p, ""));
            // a number (SI) or a unit string of the key ("2 MHz")
            let unit = contactwave::scenario::units::dimension_of_key(k.trim());
            v.trim()
                .parse::<f64>()
                .ok()
                .or_else(|| unit.and_then(|d| contactwave::scenario::units::parse(v, d).ok()))
                .filter(|x| x.is_finite())
                .map(|x| (k.trim().to_string(), x))
                .ok_or_else(|| {
                    Error::invalid(
                        "--synthesize",
                        k,
                        v,
                        "KEY=VALUE with a finite number (SI) or a unit string such as 2MHz",
                    )
                })
        })
        .collect::<contactwave::Result<Vec<_>>>()?;
    let comment = format!(
        "synthetic data: contactwave identify {} --synthesize {} --noise {noise} --seed {seed}",
        path.display(),
        pairs.join(" --synthesize ")
    );
    if spec.records.is_some() {
        let text = inverse::synthesize_records(&spec, &truth, noise, seed, &comment)?;
        print!("{text}");
        return Ok(EXIT_OK);
    }
    let data = synthesize(&spec, &truth, noise, seed)?;
    print!("{}", data.measured.to_csv(&comment));
    Ok(EXIT_OK)
}

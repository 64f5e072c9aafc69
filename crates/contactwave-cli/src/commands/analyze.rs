//! `contactwave analyze RECORDS... --out DIR`: measured waveforms through the simulator's
//! own harmonic analysis (docs/scenario.md section 9, model.md section 16).

use super::{check_out, write_out, EXIT_OK};
use contactwave::analysis::{AnalysisMethod, Gate};
use contactwave::measured::{self, Amplitudes, Layout, Settings, Sources};
use contactwave::output::analyze as files;
use contactwave::output::provenance::{process_command_line, Provenance};
use contactwave::Error;
use std::path::PathBuf;

/// Analyse measured records (CSV, .npy, .npz, .mat v5/v7.3, HDF5) with the simulator's
/// methods: A1...A5, A2/A1, beta* = A2/A1^2 per record, each harmonic's floor, and over a
/// series of drive amplitudes the fit of A2 against A1^2. Writes summary.json,
/// records.csv, spectrum.csv, record.svg, spectrum.svg and fit.svg (a series) into DIR.
#[derive(clap::Args)]
pub struct Args {
    /// Record files: every record of each, in order (several files: one per drive
    /// amplitude).
    #[arg(required = true, value_name = "RECORDS")]
    records: Vec<PathBuf>,
    /// Output folder (created if needed; this command's earlier files in it are replaced,
    /// another run's results are kept unless --overwrite).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
    /// Fundamental, Hz (default: detected, the largest record's spectral peak).
    #[arg(long, value_name = "HZ")]
    f0: Option<f64>,
    /// Time gate around the echo, s: START,END or START,END,TAPER (half-cosine ramps
    /// TAPER long inside the gate; default a tenth of the gate).
    #[arg(long, value_name = "T0,T1[,TAPER]", allow_hyphen_values = true)]
    gate: Option<String>,
    /// Analysis method.
    #[arg(long, value_enum, default_value_t = Method::BandPeak)]
    method: Method,
    /// Sampling rate, Hz, for records without a time column or array.
    #[arg(long, value_name = "HZ")]
    sample_rate: Option<f64>,
    /// The time column / array / dataset (default: one named t, time or time_s).
    #[arg(long, value_name = "NAME")]
    time: Option<String>,
    /// The columns / arrays / dataset paths holding records, comma-separated (default:
    /// every one but the time; needed for HDF5 files with other datasets).
    #[arg(long, alias = "columns", value_name = "NAMES", value_delimiter = ',')]
    datasets: Vec<String>,
    /// Opposite-polarity records (pulse inversion), one per record in the same order.
    #[arg(long, value_name = "FILE", num_args = 1..)]
    inverse: Vec<PathBuf>,
    /// Low-amplitude record of the same echo (linear reference): one for all, or one
    /// per record.
    #[arg(long, value_name = "FILE")]
    linear: Option<PathBuf>,
    /// Drive amplitudes, one per record: a comma-separated list, or the name of an array
    /// of the first file.
    #[arg(long, value_name = "LIST|NAME")]
    amplitudes: Option<String>,
    /// Keep the records' mean (default: removed as a DC offset).
    #[arg(long)]
    keep_dc: bool,
    /// The digitiser's full scale, in the records' unit: samples at +-V are clipped
    /// (default: clipping detected as flat runs at a record's extremes).
    #[arg(long, value_name = "V")]
    full_scale: Option<f64>,
}

/// `--method`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Method {
    BandPeak,
    PulseInversion,
    LinearReference,
    PlateauFit,
}

fn parse_gate(text: &str) -> contactwave::Result<Gate> {
    let bad = || {
        Error::invalid(
            "<command line>",
            "--gate",
            text,
            "START,END or START,END,TAPER in s, START < END, TAPER at most half the gate",
        )
    };
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    Gate::from_values(&v).ok_or_else(bad)
}

fn parse_amplitudes(text: &str) -> Amplitudes {
    let values: Result<Vec<f64>, _> = text.split(',').map(|s| s.trim().parse::<f64>()).collect();
    match values {
        Ok(v) if !v.is_empty() => Amplitudes::Values(v),
        _ => Amplitudes::Array(text.to_string()),
    }
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let method = match args.method {
        Method::BandPeak => AnalysisMethod::BandPeak,
        Method::PulseInversion => AnalysisMethod::PulseInversion,
        Method::LinearReference => AnalysisMethod::LinearReference,
        Method::PlateauFit => AnalysisMethod::PlateauFit,
    };
    let gate = args.gate.as_deref().map(parse_gate).transpose()?;
    if let Some(f) = args.f0 {
        if f.is_nan() || f <= 0.0 || !f.is_finite() {
            return Err(Error::invalid(
                "<command line>",
                "--f0",
                f,
                "must be > 0 Hz",
            ));
        }
    }
    let sources = Sources {
        records: args.records.clone(),
        layout: Layout {
            sample_rate: args.sample_rate,
            time: args.time.clone(),
            records: args.datasets.clone(),
        },
        inverse: args.inverse.clone(),
        linear: args.linear.clone(),
        amplitudes: args.amplitudes.as_deref().map(parse_amplitudes),
    };
    let series = measured::load(&sources)?;
    let settings = Settings {
        f0: args.f0,
        gate,
        method,
        keep_dc: args.keep_dc,
        full_scale: args.full_scale,
    };
    let first = args.records[0].display().to_string();
    let analysis = measured::analyze(&series, &settings, &first)?;
    let mut inputs: Vec<String> = args
        .records
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    inputs.extend(args.inverse.iter().map(|p| p.display().to_string()));
    inputs.extend(args.linear.iter().map(|p| p.display().to_string()));
    let mut out_files = files::files(&analysis, &series, &inputs)?;
    // provenance: every record file read, hashed
    let mut provenance = Provenance::new(process_command_line());
    for p in args.records.iter().chain(&args.inverse).chain(&args.linear) {
        provenance.add_data_file(p)?;
    }
    provenance.stamp(&mut out_files);
    let inputs: Vec<&std::path::Path> = args.records.iter().map(|p| p.as_path()).collect();
    let source = super::source("analyze", &inputs);
    check_out(&args.out, &source, args.overwrite)?;
    provenance.check_inputs_kept(&args.out, out_files.iter().map(|f| f.name.as_str()))?;
    write_out(&args.out, "analyze", &source, args.overwrite, &out_files)?;
    println!(
        "f0 = {:.6e} Hz{}; method {}; {} record(s)",
        analysis.f0,
        if analysis.f0_detected {
            " (detected)"
        } else {
            ""
        },
        method.name(),
        analysis.records.len()
    );
    for r in &analysis.records {
        println!(
            "{:<16} A1 = {:.4e}  {}  {}  beta* = {:.4e}{}",
            r.name,
            r.harmonics[1],
            files::ratio_with_floor(r, 2),
            files::ratio_with_floor(r, 3),
            r.beta_star(),
            if r.clipped.is_some() {
                "  CLIPPED: harmonics unreliable"
            } else {
                ""
            }
        );
    }
    if let Some(f) = analysis.fit {
        if f.count < 3 {
            // two records fix a line exactly: no R^2, no interval
            println!(
                "A2 = slope A1^2 + intercept through {} records: slope = {:.4e} (a line through \
                 two points: no fit statistics; 3 records or more for R^2 and a 95% interval)",
                f.count, f.slope
            );
        } else {
            println!(
                "A2 = slope A1^2 + intercept over {} records: slope = {:.4e} (95%: {:.4e} .. \
                 {:.4e}), R^2 = {:.5}",
                f.count, f.slope, f.slope_interval.0, f.slope_interval.1, f.r_squared
            );
        }
    }
    for w in files::warnings(&analysis) {
        eprintln!("warning: {w}");
    }
    Ok(EXIT_OK)
}

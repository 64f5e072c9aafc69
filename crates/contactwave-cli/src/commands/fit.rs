//! `contactwave fit power-law DATA.csv`: fit the contact stiffness-pressure law
//! K = C p^m (thesis eq. 4.4) by least squares in log-log on two columns of a CSV file, and
//! print C, m and R^2 (as text, or as a JSON object with `--json`). Writes no files.

use super::EXIT_OK;
use contactwave::numeric::table::{CsvReader, Header};
use contactwave::Error;
use std::path::{Path, PathBuf};

/// What `fit` fits.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum FitKind {
    /// Contact stiffness vs pressure, K = C p^m (thesis eq. 4.4).
    PowerLaw,
}

/// Fit a stiffness-pressure law to measured data: `fit power-law data.csv` (pressure in
/// Pa, stiffness in Pa/m; least squares in log-log) prints C, m and R^2.
#[derive(clap::Args)]
pub struct Args {
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
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    match args.what {
        FitKind::PowerLaw => power_law(&args.data, args.columns.as_deref(), args.json),
    }
}

/// `fit power-law`: least squares of K = C p^m in log-log on two columns of a CSV file.
fn power_law(path: &Path, columns: Option<&str>, json: bool) -> contactwave::Result<u8> {
    let file = path.display().to_string();
    let mut rdr = CsvReader::open(path, Header::Required)?;
    let header = rdr.header().to_vec();
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
    let mut row = Vec::with_capacity(2);
    while rdr.next_row(&[ip, ik], &mut row)?.is_some() {
        p.push(row[0]);
        k.push(row[1]);
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
    Ok(EXIT_OK)
}

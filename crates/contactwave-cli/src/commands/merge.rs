//! `contactwave merge OUT SHARD.csv... [--sweep FILE]`: combine the sweep.csv files of the
//! shards of one sweep (`sweep --shard K/N`) into OUT, rows sorted by point, and OUT.hash,
//! after checking that the shards agree (same hash file, no point missing or duplicated).

use super::EXIT_OK;
use contactwave::study::{self, Sweep};
use contactwave::Error;
use std::path::PathBuf;

/// Merge the sweep.csv files of the shards of one sweep (`sweep --shard K/N`) into OUT
/// (rows sorted by point) and OUT.hash, after checking that the shards have the same
/// hash file and that no point is missing or duplicated.
#[derive(clap::Args)]
pub struct Args {
    /// Merged CSV to write (its folder is created if needed).
    out: PathBuf,
    /// The shards' CSV files.
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// The sweep file: check the shards against its hash and its whole grid (without
    /// it, the points must be 0 to the largest point found).
    #[arg(long, value_name = "FILE")]
    sweep: Option<PathBuf>,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let out = args.out.as_path();
    let sweep = args.sweep.as_deref().map(Sweep::load).transpose()?;
    if out.is_dir() {
        return Err(Error::io(
            out,
            std::io::Error::other("is a directory; give the merged CSV's file name"),
        ));
    }
    let report = study::merge_sweep_csvs(out, &args.shards, sweep.as_ref())?;
    println!(
        "merged {} points from {} shards",
        report.points, report.shards
    );
    println!("wrote {}", report.csv.display());
    println!("wrote {}", report.hash_file.display());
    Ok(EXIT_OK)
}

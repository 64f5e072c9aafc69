//! `contactwave merge OUT SHARD.csv... [--sweep FILE]`: combine the sweep.csv files of the
//! shards of one sweep (`sweep --shard K/N`) into OUT, rows sorted by point, OUT.hash and
//! OUT.shard, after checking that the shards agree (same hash file and grid size, no point
//! missing from any shard, none duplicated),
//! and the merged sweep's plot OUT.svg (`sweep.svg` beside `sweep.csv`).

use super::EXIT_OK;
use contactwave::output;
use contactwave::study::{self, Sweep};
use contactwave::Error;
use std::path::PathBuf;

/// Merge the sweep.csv files of the shards of one sweep (`sweep --shard K/N`) into OUT
/// (rows sorted by point), OUT.hash, OUT.shard and the plot OUT.svg (OUT with the extension
/// .svg), after checking that the shards have the same hash file and grid size (side files
/// .hash and .shard) and that no point is missing from any shard or duplicated.
#[derive(clap::Args)]
pub struct Args {
    /// Merged CSV to write (its folder is created if needed).
    out: PathBuf,
    /// The shards' CSV files.
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// The sweep file: check the shards against its hash and its whole grid (without
    /// it, against the grid size and shard in each shard's side file SHARD.csv.shard).
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
    println!("wrote {}", report.shard_file.display());
    // the merged sweep's plot beside it (OUT with the extension .svg)
    if let Some(svg) = output::merged_sweep_svg(sweep.as_ref(), &report.csv)? {
        let svg_path = report.csv.with_extension("svg");
        let dir = svg_path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        let name = svg_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "sweep.svg".into());
        super::write_and_list(dir, &[super::output_file(&name, svg)])?;
    }
    Ok(EXIT_OK)
}

//! `contactwave law SCENARIO --out DIR`: the contact law of a scenario, written as
//! DIR/law_curve.csv (gap m, stress Pa) and DIR/law_curve.svg, and for a scenario with a
//! tangential part DIR/law_tangential.csv (tangential gap m, shear stress Pa) and
//! DIR/law_tangential.svg; prints `wrote PATH` per file.

use super::{check_out_dir, write_and_list, EXIT_OK};
use contactwave::output;
use contactwave::scenario::Scenario;
use std::path::PathBuf;

/// Write the contact law of a scenario as law_curve.csv (gap m, stress Pa) and
/// law_curve.svg into DIR.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (TOML).
    scenario: PathBuf,
    /// Output folder (created if needed).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let scenario = Scenario::load(&args.scenario)?;
    check_out_dir(&args.out)?;
    let tangential = scenario.shear.as_ref().map(|s| &*s.tangential);
    let files = output::law_files_with(&scenario.law, tangential)?;
    write_and_list(&args.out, &files)?;
    Ok(EXIT_OK)
}

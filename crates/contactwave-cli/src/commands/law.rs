//! `contactwave law SCENARIO --out DIR`: the contact law of a scenario, written as
//! DIR/law_curve.csv (gap m, stress Pa) and DIR/law_curve.svg, and for a scenario with a
//! tangential part DIR/law_tangential.csv (tangential gap m, shear stress Pa) and
//! DIR/law_tangential.svg; prints `wrote PATH` per file. For a bar stack, the same files
//! per interface with its number before the extension (`law_curve_0.csv`, ...; the
//! obstacle contact last), each law at its interface's static pressure; for a 2D scenario
//! (`[model] kind = "solid_2d"`), per crack (`law_curve_0.csv`, `law_tangential_0.csv`,
//! ...), each law at the crack's static pressure (its closure table's values aside).

use super::{check_out, EXIT_OK};
use contactwave::output;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::read_table;
use contactwave::scenario::solid_2d::{Solid2dScenario, Solid2dSpec};
use contactwave::scenario::{BuildCache, Scenario};
use contactwave::solver::bar_stack::End;
use contactwave::Error;
use std::path::{Path, PathBuf};

/// Write the contact law of a scenario as law_curve.csv (gap m, stress Pa) and
/// law_curve.svg into DIR.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (TOML).
    scenario: PathBuf,
    /// Output folder (created if needed; another run's results in it are kept unless
    /// --overwrite).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let table = read_table(&args.scenario)?;
    let source = super::source("law", &[&args.scenario]);
    let check_out_dir = |out: &Path| check_out(out, &source, args.overwrite);
    let files = if BarStackScenario::is_bar_stack(&table) {
        let s = BarStackScenario::from_table(table, &args.scenario)?;
        check_out_dir(&args.out)?;
        let stack = &s.stack;
        let laws = stack.interfaces.iter().chain(match &stack.right {
            End::Obstacle(l) => Some(l),
            _ => None,
        });
        let tangential: Vec<_> = match &stack.shear {
            Some(sh) => sh.interfaces.iter().chain(&sh.obstacle).map(Some).collect(),
            None => Vec::new(),
        };
        let mut files = Vec::new();
        for (i, law) in laws.enumerate() {
            let tl = tangential.get(i).copied().flatten().map(|t| &**t);
            files.extend(numbered(output::law_files_with(law, tl)?, i));
        }
        files
    } else if Solid2dScenario::is_solid_2d(&table) {
        let file = args.scenario.display().to_string();
        let spec = Solid2dSpec::from_table(table, &file)?;
        let dir = args.scenario.parent().unwrap_or(Path::new("."));
        let s = Solid2dScenario::from_spec(spec, &file, dir, &BuildCache::new())?;
        if s.problem.cracks.is_empty() {
            return Err(Error::invalid(
                file,
                "crack",
                "none",
                "at least one `[[crack]]` (a 2D scenario's contact laws are its cracks')",
            ));
        }
        check_out_dir(&args.out)?;
        let mut files = Vec::new();
        for (i, c) in s.problem.cracks.iter().enumerate() {
            let law = &c.law;
            files.extend(numbered(
                output::law_files_with(&law.normal, Some(&law.tangential))?,
                i,
            ));
        }
        files
    } else {
        let scenario = Scenario::from_table(table, &args.scenario)?;
        check_out_dir(&args.out)?;
        let tangential = scenario.shear.as_ref().map(|s| &*s.tangential);
        output::law_files_with(&scenario.law, tangential)?
    };
    super::write_out(&args.out, "law", &source, args.overwrite, &files)?;
    Ok(EXIT_OK)
}

/// `files` with the number `i` before each name's extension (`law_curve_0.csv`).
fn numbered(files: Vec<output::OutputFile>, i: usize) -> Vec<output::OutputFile> {
    files
        .into_iter()
        .map(|mut f| {
            f.name = match f.name.rsplit_once('.') {
                Some((stem, ext)) => format!("{stem}_{i}.{ext}"),
                None => format!("{}_{i}", f.name),
            };
            f
        })
        .collect()
}

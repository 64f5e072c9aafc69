//! `contactwave reproduce [WHICH] --out DIR [--quick]`: run the studies of thesis chapters
//! 3, 4 and 5 and the chapters beyond the thesis (shear waves, finite cracks in 2D) from scenarios embedded in the library (no
//! input file), with a progress bar per study
//! on a terminal, and write DIR/report.html (self-contained, inline SVG),
//! DIR/findings.json and DIR/figures/<id>.svg + <id>.csv. Prints each chapter's figure
//! and simulation counts and its findings.

use super::{check_out, progress_bar, EXIT_OK};
use contactwave::output::provenance::{process_command_line, Provenance};
use contactwave::reproduce::{run_chapter_at, write_report_with, Chapter};
use std::path::PathBuf;
use std::time::Instant;

/// Reproduce the studies of thesis chapters 3, 4 and 5 and, beyond the thesis, of shear
/// waves (`shear`) and finite cracks in 2D (`finite_crack`) from embedded scenarios (no
/// input file): DIR/report.html (self-contained, inline SVG), DIR/findings.json and
/// DIR/figures/<id>.svg + <id>.csv.
#[derive(clap::Args)]
pub struct Args {
    /// Which studies: `chapter3`, `chapter4`, `chapter5` (the thesis' chapters), `shear`
    /// (shear waves and tangential contact), `finite_crack` (finite cracks in 2D: the
    /// longest; `--quick` for its coarser resolution) or `all`.
    #[arg(default_value = "all",
          value_parser = ["chapter3", "chapter4", "chapter5", "shear", "finite_crack", "all"])]
    which: String,
    /// The coarser resolution and fewer points of the chapters that have one
    /// (`finite_crack`; the one CI runs); the others run alike.
    #[arg(long)]
    quick: bool,
    /// Output folder (created if needed; this command's earlier files in it are replaced,
    /// another run's results are kept unless --overwrite).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let out = args.out.as_path();
    let chapters = Chapter::parse_list(&args.which)?;
    // the studies chosen name the run (--quick or not: the same studies, replaced)
    let source = format!("reproduce {}", args.which);
    check_out(out, &source, args.overwrite)?;
    let t0 = Instant::now();
    // a bar per study on a terminal; in a log, progress lines per study with the time left
    let bar = progress_bar("{msg:<28} {bar:30} {pos}/{len} runs  {elapsed_precise}", 0);
    let reporter = super::progress::Reporter::new(&bar, "runs");
    let current = std::sync::Mutex::new(String::new());
    let progress = |study: &str, done: usize, total: usize| {
        let mut c = current.lock().unwrap_or_else(|p| p.into_inner());
        if *c != study {
            if !c.is_empty() {
                reporter.say(&format!("  done: {c}"));
            }
            *c = study.to_string();
            reporter.stage(study);
        }
        reporter.report(done, total);
    };
    let mut results = Vec::new();
    for ch in chapters {
        let r = run_chapter_at(ch, args.quick, &progress)?;
        reporter.say(&format!(
            "{}: {} figures, {} simulations, {:.1} s",
            ch.name(),
            r.figures.len(),
            r.runs,
            r.seconds
        ));
        results.push(r);
    }
    bar.finish_and_clear();
    let total = t0.elapsed().as_secs_f64();
    let provenance = Provenance::new(process_command_line());
    let written = write_report_with(out, &results, total, Some(&provenance))?;
    let names: Vec<String> = written
        .iter()
        .map(|p| {
            let rel = p.strip_prefix(out).unwrap_or(p);
            rel.to_string_lossy().replace('\\', "/")
        })
        .collect();
    super::claim_out(out, "reproduce", &source, &names)?;
    for r in &results {
        println!(
            "{}: {} figures, {} simulations, {:.1} s",
            r.chapter.name(),
            r.figures.len(),
            r.runs,
            r.seconds
        );
        for f in &r.findings {
            println!("  {}: {}", f.key, f.line());
        }
    }
    println!(
        "wrote {} files to {} (open {}) in {:.1} s",
        written.len(),
        out.display(),
        out.join("report.html").display(),
        total
    );
    Ok(EXIT_OK)
}

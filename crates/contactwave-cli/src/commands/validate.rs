//! `contactwave validate`: run the library's validation cases (each compares one computed
//! number with an analytical solution, an exact identity or a published finding) and print
//! the table `case | reference | computed | rel. error | tolerance | ok` of the checks, then
//! the informational rows (no criterion) apart, and the count of checks passed (the
//! informational rows are never counted). Writes no files; exit code 1 if a check is
//! outside its tolerance.

use super::{EXIT_OK, EXIT_VALIDATION_FAILED};
use contactwave::study;

/// Run the validation cases and print `case | reference | computed | rel. error`
/// (exit code 1 if a check exceeds its tolerance).
#[derive(clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> contactwave::Result<u8> {
    let cases = study::validation::run_all()?;
    let (checks, info): (Vec<_>, Vec<_>) = cases.iter().partition(|c| c.is_check());
    let w = cases.iter().map(|c| c.name.len()).max().unwrap_or(4).max(4);
    println!(
        "{:<w$} | {:>12} | {:>12} | {:>10} | {:>9} | ok",
        "check", "reference", "computed", "rel. error", "tolerance"
    );
    println!("{}", "-".repeat(w + 62));
    for c in &checks {
        println!(
            "{:<w$} | {:>12.6e} | {:>12.6e} | {:>10.3e} | {:>9.1e} | {}",
            c.name,
            c.reference,
            c.computed,
            c.rel_error,
            c.tolerance.unwrap_or(f64::NAN),
            if c.passed() { "yes" } else { "NO" }
        );
    }
    if !info.is_empty() {
        println!();
        println!("informational (no criterion, not counted):");
        println!(
            "{:<w$} | {:>12} | {:>12} | {:>10}",
            "row", "reference", "computed", "rel. error"
        );
        println!("{}", "-".repeat(w + 45));
        for c in &info {
            println!(
                "{:<w$} | {:>12.6e} | {:>12.6e} | {:>10.3e}",
                c.name, c.reference, c.computed, c.rel_error
            );
        }
    }
    let failed = checks.iter().filter(|c| c.failed()).count();
    println!(
        "{} of {} checks passed; {} informational rows",
        checks.len() - failed,
        checks.len(),
        info.len()
    );
    Ok(if failed > 0 {
        EXIT_VALIDATION_FAILED
    } else {
        EXIT_OK
    })
}

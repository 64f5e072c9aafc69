//! `contactwave validate`: run the library's validation cases (each compares one computed
//! number with an analytical solution, an exact identity or a published finding) and print
//! the table `case | reference | computed | rel. error | tolerance | ok` and a count.
//! Writes no files; exit code 1 if a case is outside its tolerance.

use super::{EXIT_OK, EXIT_VALIDATION_FAILED};
use contactwave::study;

/// Run the validation cases and print `case | reference | computed | rel. error`
/// (exit code 1 if a case exceeds its tolerance).
#[derive(clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> contactwave::Result<u8> {
    let cases = study::validation::run_all()?;
    let w = cases.iter().map(|c| c.name.len()).max().unwrap_or(4).max(4);
    println!(
        "{:<w$} | {:>12} | {:>12} | {:>10} | {:>9} | ok",
        "case", "reference", "computed", "rel. error", "tolerance"
    );
    println!("{}", "-".repeat(w + 62));
    let mut failed = 0;
    for c in &cases {
        let ok = c.passed();
        if !ok {
            failed += 1;
        }
        println!(
            "{:<w$} | {:>12.6e} | {:>12.6e} | {:>10.3e} | {:>9.1e} | {}",
            c.name,
            c.reference,
            c.computed,
            c.rel_error,
            c.tolerance,
            if ok { "yes" } else { "NO" }
        );
    }
    println!(
        "{} of {} cases within tolerance",
        cases.len() - failed,
        cases.len()
    );
    Ok(if failed > 0 {
        EXIT_VALIDATION_FAILED
    } else {
        EXIT_OK
    })
}

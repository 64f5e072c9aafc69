//! `contactwave validate`: run the library's validation cases (each compares one computed
//! number with an analytical solution, an exact identity or a published finding) and print
//! the table `case | reference | computed | rel. error | tolerance | ok` of the checks, then
//! the informational rows (no criterion) apart, and the count of checks passed (the
//! informational rows are never counted). Writes no files; exit code 1 if a check is
//! outside its tolerance.

use super::{EXIT_OK, EXIT_VALIDATION_FAILED};
use contactwave::study;
use contactwave::study::validation::ValidationCase;

/// Run the validation cases and print `case | reference | computed | rel. error`
/// (exit code 1 if a check exceeds its tolerance).
#[derive(clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> contactwave::Result<u8> {
    let cases = study::validation::run_all()?;
    let (text, failed) = table(&cases);
    print!("{text}");
    Ok(if failed > 0 {
        EXIT_VALIDATION_FAILED
    } else {
        EXIT_OK
    })
}

/// The text `validate` prints for `cases` (the checks' table, the informational rows
/// apart, the closing count of checks passed) and the number of failed checks.
fn table(cases: &[ValidationCase]) -> (String, usize) {
    use std::fmt::Write;
    let mut s = String::new();
    let (checks, info): (Vec<_>, Vec<_>) = cases.iter().partition(|c| c.is_check());
    let w = cases.iter().map(|c| c.name.len()).max().unwrap_or(4).max(4);
    // writing into a String cannot fail
    let _ = writeln!(
        s,
        "{:<w$} | {:>12} | {:>12} | {:>10} | {:>9} | ok",
        "check", "reference", "computed", "rel. error", "tolerance"
    );
    let _ = writeln!(s, "{}", "-".repeat(w + 62));
    for c in &checks {
        let _ = writeln!(
            s,
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
        let _ = writeln!(s);
        let _ = writeln!(s, "informational (no criterion, not counted):");
        let _ = writeln!(
            s,
            "{:<w$} | {:>12} | {:>12} | {:>10}",
            "row", "reference", "computed", "rel. error"
        );
        let _ = writeln!(s, "{}", "-".repeat(w + 45));
        for c in &info {
            let _ = writeln!(
                s,
                "{:<w$} | {:>12.6e} | {:>12.6e} | {:>10.3e}",
                c.name, c.reference, c.computed, c.rel_error
            );
        }
    }
    let failed = checks.iter().filter(|c| c.failed()).count();
    let _ = writeln!(
        s,
        "{} of {} checks passed; {} informational rows",
        checks.len() - failed,
        checks.len(),
        info.len()
    );
    (s, failed)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Only checks are counted: an informational row is printed apart and never counted,
    /// a failed check reads NO and is counted as failed. The real table (every check
    /// "yes", the three band-peak rows and nothing else informational, exit code 0) is
    /// the reference output stdout/validate.txt of tests/reference/, line by line.
    #[test]
    fn only_checks_are_counted_and_informational_rows_stand_apart() {
        let cases = [
            ValidationCase::new("a", 1.0, 1.0 + 1e-9, 1e-6),
            ValidationCase::informational("band_peak x", 1.0, 1.1),
            ValidationCase::new("b", 2.0, 2.5, 1e-3),
        ];
        let (text, failed) = table(&cases);
        assert_eq!(failed, 1);
        let (checks, info) = text
            .split_once("informational (no criterion, not counted):")
            .expect("an informational section");
        assert!(
            checks.contains("| yes") && checks.contains("| NO"),
            "{text}"
        );
        assert!(
            !checks.contains("band_peak") && info.contains("band_peak x"),
            "{text}"
        );
        assert_eq!(
            text.lines().last().unwrap(),
            "1 of 2 checks passed; 1 informational rows"
        );
        let (all_ok, none_failed) = table(&cases[..2]);
        assert_eq!(none_failed, 0);
        assert!(all_ok.ends_with("1 of 1 checks passed; 1 informational rows\n"));
    }
}

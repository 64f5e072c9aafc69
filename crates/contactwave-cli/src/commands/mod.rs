//! The subcommands of `contactwave`, one module each (its clap `Args`, whose doc comment is
//! the command's help text, and its `run`), and what they share: exit codes, the output
//! folder check and file writing, progress bars and Ctrl-C handling.

pub mod analyze;
pub mod bench;
pub mod convergence;
pub mod fit;
pub mod identify;
pub mod law;
pub mod merge;
pub mod progress;
pub mod reproduce;
pub mod run;
pub mod sweep;
pub mod validate;

use contactwave::output::{self, OutputFile};
use contactwave::Error;
pub use progress::{progress_bar, step_reporter, STEPS_TEMPLATE};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit code: success.
pub const EXIT_OK: u8 = 0;
/// Exit code: `validate` found a case outside its tolerance.
pub const EXIT_VALIDATION_FAILED: u8 = 1;
/// Exit code: a failed computation: the work finished but some of its points failed (a
/// sweep without `--tolerate-failures`), or a simulation failed numerically (or on a bug);
/// the same code as [`EXIT_VALIDATION_FAILED`]. No command exits with a code other than
/// 0, 1, 2, 130 or 141.
pub const EXIT_FAILED: u8 = 1;
/// Exit code: invalid input (scenario or sweep file, missing file, output path, I/O).
pub const EXIT_INVALID_INPUT: u8 = 2;
/// Exit code: interrupted (Ctrl-C).
pub const EXIT_INTERRUPTED: u8 = 130;
/// Exit code: standard output or error closed by its reader (`contactwave ... | head`):
/// the command stops silently, as `cat` does (128 + SIGPIPE).
pub const EXIT_OUTPUT_CLOSED: u8 = 141;

/// `--overwrite`, shared by the commands that write an output folder.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct Overwrite {
    /// Replace another run's results in the output folder (without it a folder holding the
    /// results of another command or input, or files contactwave did not write under the
    /// names this run writes, is refused before any work; the same run re-run into its own
    /// folder replaces its files)
    #[arg(long)]
    pub overwrite: bool,
}

/// The run a command's output folder belongs to, as its manifest records it: the command
/// and its input (`run /abs/plate.toml`; the input canonicalized where it exists).
pub fn source(command: &str, inputs: &[&Path]) -> String {
    let mut s = command.to_string();
    for p in inputs {
        let p = std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
        s.push(' ');
        s.push_str(&p.display().to_string());
    }
    s
}

/// Refuse, before any work, an output path that exists and is not a folder, or a folder
/// holding another run's results (unless `overwrite`: [`output::manifest::check_owner`]).
pub fn check_out(out: &Path, source: &str, overwrite: Overwrite) -> contactwave::Result<()> {
    if out.exists() && !out.is_dir() {
        return Err(Error::io(
            out,
            std::io::Error::other("exists and is not a directory"),
        ));
    }
    output::manifest::check_owner(out, source, overwrite.overwrite)
}

/// Refuse, before writing, to replace a file of `out` no contactwave command wrote
/// ([`output::manifest::check_collisions`]).
pub fn check_names<'a>(
    out: &Path,
    names: impl IntoIterator<Item = &'a str>,
    overwrite: Overwrite,
) -> contactwave::Result<()> {
    let names: Vec<String> = names.into_iter().map(str::to_string).collect();
    output::manifest::check_collisions(out, &names, overwrite.overwrite)
}

/// Read and parse a scenario file into its TOML table (not yet checked as a scenario).
pub fn read_table(path: &Path) -> contactwave::Result<toml::Table> {
    contactwave::scenario::read_table(path)
}

/// An output file named `name` (no folder).
pub fn output_file(name: &str, contents: String) -> OutputFile {
    OutputFile {
        name: name.into(),
        contents,
    }
}

/// Write `files` into the folder `out` (created if needed) and print `wrote PATH` for each.
pub fn write_and_list(out: &Path, files: &[OutputFile]) -> contactwave::Result<()> {
    for p in output::write_files(out, files)? {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// Write `files` into the output folder `out` of `command` run on `source` ([`source`])
/// ([`write_and_list`], refused where it would replace a file no contactwave command
/// wrote: [`check_names`]) and record them in the folder's manifest ([`claim_out`]).
pub fn write_out(
    out: &Path,
    command: &str,
    source: &str,
    overwrite: Overwrite,
    files: &[OutputFile],
) -> contactwave::Result<()> {
    check_names(out, files.iter().map(|f| f.name.as_str()), overwrite)?;
    write_and_list(out, files)?;
    claim_files(out, command, source, files)
}

/// [`claim_out`] for the `files` of `command` written into `out`.
pub fn claim_files(
    out: &Path,
    command: &str,
    source: &str,
    files: &[OutputFile],
) -> contactwave::Result<()> {
    let names: Vec<String> = files.iter().map(|f| f.name.clone()).collect();
    claim_out(out, command, source, &names)
}

/// Record that `command` wrote `files` (relative to `out`) into its output folder `out`
/// (the manifest `.contactwave-manifest.json`): the files an earlier contactwave command
/// wrote there and this one did not are removed (a note on stderr names them), files no
/// contactwave command wrote are left untouched and named in a warning.
pub fn claim_out(
    out: &Path,
    command: &str,
    source: &str,
    files: &[String],
) -> contactwave::Result<()> {
    let c = output::manifest::claim(out, command, source, files)?;
    let list = |paths: &[std::path::PathBuf]| {
        let mut s = paths
            .iter()
            .take(5)
            .map(|p| p.strip_prefix(out).unwrap_or(p).display().to_string())
            .collect::<Vec<_>>()
            .join(", ");
        if paths.len() > 5 {
            s.push_str(&format!(", ... ({} in all)", paths.len()));
        }
        s
    };
    if !c.removed.is_empty() {
        eprintln!(
            "note: removed {} file(s) an earlier contactwave command wrote to {}: {}",
            c.removed.len(),
            out.display(),
            list(&c.removed)
        );
    }
    if !c.foreign.is_empty() {
        eprintln!(
            "warning: {} also holds files contactwave did not write (left untouched): {}",
            out.display(),
            list(&c.foreign)
        );
    }
    Ok(())
}

/// Set by Ctrl-C or SIGTERM once [`install_interrupt_handler`] has installed its handler.
static CANCEL: AtomicBool = AtomicBool::new(false);

/// How long the work may take to stop by itself after Ctrl-C or SIGTERM before the
/// process ends (a sweep finishes writing its rows and prints what it did).
const GRACE: std::time::Duration = std::time::Duration::from_millis(800);

/// Install, for every command, the handler of Ctrl-C (SIGINT) and SIGTERM: the first
/// signal asks the work to stop ([`contactwave::interrupt`]: solvers, executors and file
/// writing stop at their next check, and the command exits 130); if it has not ended
/// within [`GRACE`], the process exits 130 as soon as no file is being written (what was
/// written is complete; nothing is half-written). A second signal exits at once.
pub fn install_interrupt_handler() {
    let _ = ctrlc::set_handler(|| {
        if CANCEL.swap(true, Ordering::SeqCst) {
            // second signal: give up at once (finished work is on disk already)
            std::process::exit(EXIT_INTERRUPTED.into());
        }
        contactwave::interrupt::request();
        std::thread::spawn(|| {
            std::thread::sleep(GRACE);
            while contactwave::interrupt::writing() > 0 {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            eprintln!("error: interrupted");
            std::process::exit(EXIT_INTERRUPTED.into());
        });
    });
}

/// The flag Ctrl-C sets (the handler is installed by `main`): work checks it to stop.
pub fn cancel_on_ctrl_c() -> &'static AtomicBool {
    &CANCEL
}

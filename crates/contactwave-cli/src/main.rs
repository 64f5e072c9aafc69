//! `contactwave`: command-line interface of the contactwave library.
//!
//! Exit codes: 0 success; 1 a failed computation (`validate` found a case outside its
//! tolerance, a sweep finished with failed points, or a simulation failed numerically); 2
//! invalid input (scenario or sweep file, missing file, output path, I/O, beyond the memory
//! budget); 130 interrupted (Ctrl-C or SIGTERM). Every error is one line on stderr starting with
//! `error: `, and no output folder is created or modified when an input is invalid or the
//! simulation fails.
//!
//! This file holds the top-level clap definition, the dispatch and the mapping of errors to
//! exit codes; each subcommand (its arguments, help text and work) is a module of
//! [`commands`].

mod commands;

use clap::{Parser, Subcommand};
use commands::{
    analyze, bench, convergence, fit, identify, law, merge, reproduce, run, sweep, validate,
    EXIT_FAILED, EXIT_INTERRUPTED, EXIT_INVALID_INPUT, EXIT_OUTPUT_CLOSED,
};
use contactwave::Error;
use std::io::Write;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set when a print found standard output or error closed by its reader (a broken pipe).
static OUTPUT_CLOSED: AtomicBool = AtomicBool::new(false);

const AFTER_HELP: &str = "\
Units are SI throughout: Pa (stress, p0, amplitude), m (gap, probe position), s, Hz,
kg/m^3, Pa/m (interface stiffness), J/m^2 (decohesion energy). Stress is tension-positive;
p0 is a compression.

Memory: every command refuses work beyond the memory budget, or beyond the machine's
memory whatever the budget, before allocating it (CONTACTWAVE_MEMORY_BUDGET, bytes with an
optional k/M/G/T suffix; default half the available memory).

Progress: a bar on a terminal; in a log, a line at each tenth with the time left once a
command has run 10 s (CONTACTWAVE_PROGRESS_AFTER, seconds).

Exit codes: 0 success, 1 failed computation (validation case outside tolerance, failed
sweep points or numerical failure of a simulation), 2 invalid input, I/O error or beyond
the memory budget, 130 interrupted (Ctrl-C or SIGTERM). No other code is used.";

#[derive(Parser)]
#[command(
    name = "contactwave",
    version,
    about = "Simulate elastic waves interacting with nonlinear contact interfaces",
    after_help = AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The subcommands, in the order of `--help`; each one's help text is the doc comment of
/// its `Args`.
#[derive(Subcommand)]
enum Command {
    Reproduce(reproduce::Args),
    Fit(fit::Args),
    Analyze(analyze::Args),
    Run(run::Args),
    Law(law::Args),
    Sweep(sweep::Args),
    Merge(merge::Args),
    Convergence(convergence::Args),
    Validate(validate::Args),
    Bench(bench::Args),
    Identify(identify::Args),
}

/// The command line parsed; a mistake in it is one line on stderr, exit 2 (clap's own
/// report spans several lines: its lines before the usage are joined). Every option that
/// takes a value takes a negative number too (`--f0 -1e6`), so that the command's range
/// check names the option and what is allowed, instead of clap calling `-1e6` a flag.
fn parse() -> Result<Cli, ExitCode> {
    use clap::error::ErrorKind;
    use clap::{CommandFactory, FromArgMatches};
    let negative = |a: clap::Arg| {
        if a.get_action().takes_values() {
            a.allow_negative_numbers(true)
        } else {
            a
        }
    };
    let command = Cli::command().mut_subcommands(|s| s.mut_args(negative));
    match command
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => Ok(cli),
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
            _ => {
                let text = e.render().to_string();
                let line = text
                    .lines()
                    .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more"))
                    .map(str::trim)
                    .filter(|l| !l.is_empty())
                    .map(|l| match l.strip_prefix("tip: ") {
                        Some(tip) => format!("({tip})"),
                        None => l.to_string(),
                    })
                    .collect::<Vec<_>>()
                    .join(" ");
                let line = line.strip_prefix("error: ").unwrap_or(&line);
                let _ = writeln!(std::io::stderr(), "error: <command line>: {line}");
                Err(ExitCode::from(EXIT_INVALID_INPUT))
            }
        },
    }
}

fn main() -> ExitCode {
    let cli = match parse() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    commands::install_interrupt_handler();
    // a panic is a bug: one line on stderr (not the default multi-line report), and the
    // command ends with exit code 1 like any failed computation (never 101)
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        // `println!` into a pipe whose reader has gone (`| head`): not a bug, stop silently
        if msg.starts_with("failed printing to std") && msg.contains("Broken pipe") {
            OUTPUT_CLOSED.store(true, Ordering::SeqCst);
            return;
        }
        let msg = msg.replace(['\n', '\r'], " ");
        // (never a panic in the hook: a closed stderr is ignored)
        let _ = writeln!(
            std::io::stderr(),
            "error: internal error (panic{at}): {msg}"
        );
    }));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| dispatch(cli.command)))
        .unwrap_or_else(|_| {
            Err(Error::Internal {
                message: "the command stopped on a bug (see the line above)".into(),
            })
        });
    if OUTPUT_CLOSED.load(Ordering::SeqCst) {
        return ExitCode::from(EXIT_OUTPUT_CLOSED);
    }
    match result {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            let code = match e {
                Error::Numerical { .. } | Error::Internal { .. } | Error::Device { .. } => {
                    EXIT_FAILED
                }
                Error::Interrupted => EXIT_INTERRUPTED,
                _ => EXIT_INVALID_INPUT,
            };
            let msg = e.to_string().replace(['\n', '\r'], " ");
            let _ = writeln!(std::io::stderr(), "error: {msg}");
            ExitCode::from(code)
        }
    }
}

/// Run a subcommand; `Ok` holds its exit code.
fn dispatch(cmd: Command) -> contactwave::Result<u8> {
    match cmd {
        Command::Reproduce(args) => reproduce::run(args),
        Command::Fit(args) => fit::run(args),
        Command::Analyze(args) => analyze::run(args),
        Command::Run(args) => run::run(args),
        Command::Law(args) => law::run(args),
        Command::Sweep(args) => sweep::run(args),
        Command::Merge(args) => merge::run(args),
        Command::Convergence(args) => convergence::run(args),
        Command::Validate(args) => validate::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Identify(args) => identify::run(args),
    }
}

//! `contactwave`: command-line interface of the contactwave library.
//!
//! Exit codes: 0 success; 1 `validate` found a case outside its tolerance, or a sweep
//! finished with failed points; 2 invalid input (scenario or sweep file, missing file,
//! output path, I/O, beyond the memory budget); 3 numerical failure of a simulation; 130
//! interrupted (Ctrl-C or SIGTERM). Every error is one line on stderr starting with
//! `error: `, and no output folder is created or modified when an input is invalid or the
//! simulation fails.
//!
//! This file holds the top-level clap definition, the dispatch and the mapping of errors to
//! exit codes; each subcommand (its arguments, help text and work) is a module of
//! [`commands`].

mod commands;

use clap::{Parser, Subcommand};
use commands::{
    bench, convergence, fit, identify, law, merge, reproduce, run, sweep, validate,
    EXIT_INTERRUPTED, EXIT_INVALID_INPUT, EXIT_NUMERICAL,
};
use contactwave::Error;
use std::process::ExitCode;

const AFTER_HELP: &str = "\
Units are SI throughout: Pa (stress, p0, amplitude), m (gap, probe position), s, Hz,
kg/m^3, Pa/m (interface stiffness), J/m^2 (decohesion energy). Stress is tension-positive;
p0 is a compression.

Memory: every command refuses work beyond the memory budget before allocating it
(CONTACTWAVE_MEMORY_BUDGET, bytes with an optional k/M/G/T suffix; default half the
available memory).

Exit codes: 0 success, 1 validation case outside tolerance or failed sweep points, 2
invalid input, I/O error or beyond the memory budget, 3 numerical failure, 130 interrupted
(Ctrl-C or SIGTERM).";

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
    Run(run::Args),
    Law(law::Args),
    Sweep(sweep::Args),
    Merge(merge::Args),
    Convergence(convergence::Args),
    Validate(validate::Args),
    Bench(bench::Args),
    Identify(identify::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    commands::install_interrupt_handler();
    match dispatch(cli.command) {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            let code = match e {
                Error::Numerical { .. } => EXIT_NUMERICAL,
                Error::Interrupted => EXIT_INTERRUPTED,
                _ => EXIT_INVALID_INPUT,
            };
            let msg = e.to_string().replace(['\n', '\r'], " ");
            eprintln!("error: {msg}");
            ExitCode::from(code)
        }
    }
}

/// Run a subcommand; `Ok` holds its exit code.
fn dispatch(cmd: Command) -> contactwave::Result<u8> {
    match cmd {
        Command::Reproduce(args) => reproduce::run(args),
        Command::Fit(args) => fit::run(args),
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

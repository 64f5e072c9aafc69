//! Every integration test of `contactwave-cli` in one binary (one link instead of one per file):
//! a module a file. Run one file's tests with `cargo nextest run -p contactwave-cli -E 'test(/^cli::/)'`
//! or `cargo test --release -p contactwave-cli --test all -- cli::`.

mod analyze;
mod cli;
mod cli_identify;
mod common;
mod convergence_2d;
mod determinism;
mod hostile;
mod mesh;
mod provenance;
mod trust;

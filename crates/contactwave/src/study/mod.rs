//! Parameter studies: sweeps over dotted scenario keys ([`Sweep`], [`run_sweep`]) and the
//! validation cases of `contactwave validate` ([`validation`]).
//!
//! This module owns the sweep file format (TOML), the grid it resolves to, the resumable
//! `sweep.csv` it writes and the hash that ties a CSV to the sweep that produced it. It
//! never touches the physics: every grid point is a [`crate::scenario::Scenario`] built
//! from the base scenario with [`crate::scenario::set_dotted`] and run through
//! [`crate::simulate_summary`].

pub mod convergence;
mod sweep;
pub mod validation;

pub use sweep::{
    errors_path, grid, hash_path, linspace, logspace, merge_sweep_csvs, point_table,
    read_sweep_csv, run_sweep, run_sweep_shard, shard_path, Axis, AxisSpec, MergeReport, Shard,
    ShardFile, Sweep, SweepOptions, SweepReport, SweepTable,
};

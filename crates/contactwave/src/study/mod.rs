//! Parameter studies: sweeps over dotted scenario keys ([`Sweep`], [`run_sweep`]) and the
//! validation cases of `contactwave validate` ([`validation`]).
//!
//! This module owns the sweep file format (TOML), the grid it resolves to, the resumable
//! `sweep.csv` it writes and the hash that ties a CSV to the sweep that produced it. It
//! never touches the physics: the base scenario is planned once into a
//! [`crate::model::Template`] (its table parsed, its laws and files built once) with one
//! typed [`crate::model::Param`] per axis; every grid point is the template built with
//! the point's values ([`crate::model::Template::build`], validated before anything
//! runs), and the points run on the [`crate::run::Executor`], whose observer writes each
//! row as it finishes.

pub mod convergence;
pub mod convergence_2d;
mod sweep;
pub mod validation;

pub use sweep::{
    errors_path, grid, hash_path, linspace, logspace, merge_sweep_csvs, point_table,
    read_sweep_csv, run_sweep, run_sweep_shard, shard_path, Axis, AxisSpec, MergeReport, Shard,
    ShardFile, Sweep, SweepOptions, SweepReport, SweepTable,
};

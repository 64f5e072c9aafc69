//! Sweep files, their grid, and the resumable `sweep.csv`.
//!
//! # Sweep file (TOML)
//!
//! ```toml
//! base = "unilateral.toml"          # base scenario, relative to this file
//!
//! [[axis]]                          # first axis: varies slowest
//! parameter = "incident.xi"         # any dotted scenario key holding a number
//! linspace = [0.05, 1.2, 47]        # start, end, number of points (>= 1)
//!
//! [[axis]]
//! parameter = "interface.traction.stiffness"
//! logspace = [9, 16, 8]             # exponents of 10: 1e9 ... 1e16, 8 points
//! # or: values = [1e9, 1e12, 1e15]
//! ```
//!
//! Several axes form a grid (cartesian product, first axis slowest, last fastest). Axis
//! indices in error messages are 0-based (`axis.0` is the first `[[axis]]` table). Values
//! are written into the base scenario with [`crate::scenario::set_dotted`] (so sweeping
//! `incident.xi` removes the base's `incident.amplitude` and vice versa), and every point is
//! validated as a [`Scenario`] before anything runs. Units are those of the swept key
//! (SI: Pa, Pa/m, Hz, J/m^2, ...).
//!
//! # Output
//!
//! `sweep.csv`: a header line, then one row per finished point, appended in order of
//! completion and sorted by `point` (the 0-based grid index) once the sweep has finished
//! (an interrupted one stays in completion order until `--resume` finishes it), one column per axis named by
//! its dotted key, then the keys of [`crate::analysis::Summary`] in their order. Numbers are
//! written so that they parse back to the same `f64` (`NaN`, `inf` for non-finite values).
//! Each row is written with one `write` call as soon as its point finishes, so an
//! interrupted sweep loses no finished row.
//!
//! `sweep.csv.hash` (side file, one line): the SHA-256, in hex, of a canonical
//! serialisation of the contactwave version, the base scenario table, the axes and the
//! grid ([`Sweep::hash`]). A resumed sweep appends to a CSV only when its hash matches.
//! The hash lives in a side file rather than a comment line so that `sweep.csv` stays a
//! plain CSV for every reader.
//!
//! `sweep.csv.shard` (side file, TOML): `shard = "K/N"` (`"1/1"` for a whole sweep) and
//! `points = TOTAL`, the size of the whole grid ([`ShardFile`]), so that `merge` knows
//! which points each shard must hold, with or without the sweep file.
//!
//! `sweep_errors.csv` (`<stem>_errors.csv` beside the CSV; only when a point failed):
//! `point,message` for each point whose simulation failed (numerical failure). Failed
//! points have no row in `sweep.csv`, so `--resume` retries them; the errors file is
//! rewritten by every run.
//!
//! # Modules
//!
//! From the bottom up; each uses only those above it in this list, none imports the driver:
//!
//! - `grid`: [`linspace`], [`logspace`], [`grid()`] (numbers only);
//! - `csv_io`: the rows of `sweep.csv` written and read back ([`read_sweep_csv`],
//!   [`SweepTable`]), the hash side file and the canonical form behind [`Sweep::hash`], the
//!   errors file;
//! - `format`: the sweep file ([`Sweep`], [`Axis`], [`AxisSpec`], `[set]`) and the scenario
//!   table of each point ([`point_table`]);
//! - `shard`: slices of the grid ([`Shard`]) and the merge of shard CSVs
//!   ([`merge_sweep_csvs`]);
//! - `driver`: [`run_sweep`], [`run_sweep_shard`] (the rayon loop).

mod csv_io;
mod driver;
mod format;
mod grid;
mod shard;
#[cfg(test)]
mod test_support;

pub use csv_io::{errors_path, hash_path, read_sweep_csv, SweepTable};
pub use driver::{run_sweep, run_sweep_shard, SweepOptions, SweepReport};
pub use format::{point_table, Axis, AxisSpec, Sweep};
pub use grid::{grid, linspace, logspace};
pub use shard::{merge_sweep_csvs, shard_path, MergeReport, Shard, ShardFile};

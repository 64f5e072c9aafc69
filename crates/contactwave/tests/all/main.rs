//! Every integration test of `contactwave` in one binary (one link instead of one per file):
//! a module a file. Run one file's tests with `cargo nextest run -p contactwave -E 'test(/^barstack::/)'`
//! or `cargo test --release -p contactwave --test all -- barstack::`.

mod barstack;
mod barstack_incident;
mod barstack_shear;
mod common;
mod fd;
mod identify;
mod identify_2d;
mod identify_records;
mod layers;
mod measured;
mod oblique;
mod properties;
mod reproduce;
mod shear;
mod shear_fd;
mod slip_weakening;
mod solid_2d;
mod solid_2d_examples;
mod solid_2d_mesh;
mod solid_2d_plane;
mod sweep_2d;
mod units;
mod validation;
mod weak_nonlinearity;

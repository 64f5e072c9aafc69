//! Measured waveforms (model.md section 16): oscilloscope records read from CSV, NumPy,
//! MATLAB or HDF5 files ([`arrays`]), put on one uniform time base ([`Records`]), and
//! analysed by the simulator's own analysis ([`analyze`]: the same gate, the same band
//! peak, pulse inversion, linear reference and plateau fit as the summaries of a run),
//! giving A1...A5, A2/A1, beta* = A2/A1^2, each harmonic's floor, and over a series of
//! drive amplitudes the fit of A2 against A1^2.
//!
//! ```
//! use contactwave::measured::{analyze, Measured, Series, Settings};
//! use std::f64::consts::PI;
//! // a 5 MHz-sampled record: 20 cycles of 100 kHz with 1% second harmonic
//! let (f0, dt) = (1e5, 2e-7);
//! let x: Vec<f64> = (0..4000)
//!     .map(|k| {
//!         let t = k as f64 * dt;
//!         let w = if t < 2e-4 { (PI * t / 2e-4).sin().powi(2) } else { 0.0 };
//!         w * ((2.0 * PI * f0 * t).sin() + 0.01 * (4.0 * PI * f0 * t).sin())
//!     })
//!     .collect();
//! let series = Series { dt, t0: 0.0, records: vec![Measured::new("echo", x)] };
//! let a = analyze(&series, &Settings::default(), "echo.csv").unwrap();
//! assert!((a.f0 - f0).abs() < 50.0); // detected
//! assert!((a.records[0].harmonics[2] / a.records[0].harmonics[1] - 0.01).abs() < 2e-4);
//! ```

pub mod analyze;
pub mod arrays;
mod load;
mod series;
mod transducer;

pub use analyze::{
    analyze, clip_levels, Analysis, Clipping, RecordAnalysis, SeriesFit, Settings, HARMONIC_KEYS,
};
pub use arrays::{read_arrays, Format, NamedArray};
pub use load::{load, Amplitudes, Sources};
pub use series::{read_records, Layout, Measured, Records, Series, Trace};
pub use transducer::BandPass;

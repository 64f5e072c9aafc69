//! Signal analysis of the thesis (model.md section 6): spectra, band-filtered harmonic
//! amplitudes `A_n`, sub-harmonic, two-tone sum and difference components, and the summary
//! of a run.
//!
//! `A_n` is the peak of the band-filtered reflected particle velocity in the band
//! `[n f0 - f0/2, n f0 + f0/2)`, computed as the peak of the envelope (modulus of the
//! analytic band signal), which equals the peak of the band-filtered signal up to its
//! sampling. Velocities enter as cell averages (differences of the exact displacement at
//! the grid points divided by dt), whose spectrum is corrected by the known
//! `sinc(pi f dt)` response: jumps of the reflected wave at closures then alias by
//! O(1/samples_per_period^2) only.

mod envelope;
pub mod fit;
pub mod gate;
mod low_bins;
pub mod methods;
pub mod projection;
mod spectrum;
mod summary;

pub use gate::Gate;
pub use methods::{floor_reading, AnalysisMethod, Quantity};
pub use spectrum::{
    cell_velocity, spectral_peak, velocity_bands, with_analyzer, Analyzer, BandAmplitudes, Spectrum,
};
pub use summary::{
    harmonics_near_floor, json_number, push_csv_number, set_analysis_keys, set_record_harmonics,
    set_reflected_harmonics, set_shear_harmonics, Summary, HARMONIC_KEYS,
};

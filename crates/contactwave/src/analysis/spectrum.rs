//! Spectra and band amplitudes with plans made once and reused (RustFFT's planner design):
//! an [`Analyzer`] owns its planners and scratch buffers; a sweep keeps one per thread.

use super::envelope::EnvelopePeak;
use super::low_bins::LowBins;
use crate::error::{Error, Result};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use std::cell::RefCell;

thread_local! {
    /// One analyser per thread: its plans serve every run of a sweep on that thread. A
    /// plan cache (RustFFT's planners and their scratch buffers, keyed by length): what a
    /// run gets from it does not depend on the runs before, so it stays per thread rather
    /// than in the caller's `model::Workspace` (which holds the solver's kept state).
    static ANALYZER: RefCell<Analyzer> = RefCell::new(Analyzer::new());
}

/// Run `f` with this thread's analyser.
pub fn with_analyzer<T>(f: impl FnOnce(&mut Analyzer) -> T) -> T {
    ANALYZER.with(|a| f(&mut a.borrow_mut()))
}

/// Cell-averaged velocities (m/s) from displacements at the grid points (m, step `dt` s).
pub fn cell_velocity(disp: &[f64], dt: f64) -> Vec<f64> {
    disp.windows(2).map(|w| (w[1] - w[0]) / dt).collect()
}

/// Band amplitudes (m/s) of the cell-averaged velocity of a displacement record (m, step
/// `dt` s), for fundamental `f0` and optional second frequency `f2` (Hz).
pub fn velocity_bands(displacement: &[f64], dt: f64, f0: f64, f2: Option<f64>) -> BandAmplitudes {
    with_analyzer(|a| a.displacement_bands(displacement, dt, f0, f2))
}

/// Peak of the magnitudes `spec` (bin width `df` Hz) between `f_lo` and `f_hi` with
/// parabolic interpolation: (frequency Hz, magnitude); `(NaN, 0)` for an empty range.
pub fn spectral_peak(spec: &[f64], df: f64, f_lo: f64, f_hi: f64) -> (f64, f64) {
    let lo = ((f_lo / df).ceil() as usize).max(1);
    let hi = ((f_hi / df).floor() as usize).min(spec.len().saturating_sub(2));
    if hi <= lo {
        return (f64::NAN, 0.0);
    }
    let k = (lo..=hi)
        .max_by(|&a, &b| spec[a].total_cmp(&spec[b]))
        .unwrap_or(lo);
    let (a, b, c) = (spec[k - 1], spec[k], spec[k + 1]);
    let den = a - 2.0 * b + c;
    let delta = if den != 0.0 { 0.5 * (a - c) / den } else { 0.0 };
    ((k as f64 + delta.clamp(-0.5, 0.5)) * df, b)
}

/// Band amplitudes of one signal, in the signal's units (m/s for velocities).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BandAmplitudes {
    /// `A_n`, n = 1..5 (index 0 unused).
    pub harmonic: [f64; 6],
    /// Sub-harmonic f0/2 (band `[f0/4, 3 f0/4)`).
    pub subharmonic: f64,
    /// Two-tone: component at f2.
    pub f2: f64,
    /// Two-tone: sum component f1 + f2.
    pub sum: f64,
    /// Two-tone: difference component |f2 - f1|.
    pub difference: f64,
}

/// One-sided amplitude spectrum of a signal: `|X(f)| dt` (Fourier transform magnitude).
#[derive(Debug, Clone, Default)]
pub struct Spectrum {
    /// Frequencies, Hz.
    pub frequency: Vec<f64>,
    /// Magnitude, signal units x s.
    pub magnitude: Vec<f64>,
}

/// Planner-owning analyser.
pub struct Analyzer {
    real: RealFftPlanner<f64>,
    cplx: FftPlanner<f64>,
    input: Vec<f64>,
    spec: Vec<Complex<f64>>,
    band: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
    /// Plans of the band analysis' low bins ([`LowBins`]), newest last.
    low: Vec<LowBins>,
    /// Plans of the band envelopes' peaks ([`EnvelopePeak`]), newest last.
    envelopes: Vec<EnvelopePeak>,
    /// `(n_fft, dt bits)` of `sinc`.
    sinc_key: (usize, u64),
    /// The cell-average response `max(sin(a)/a, 1e-3)`, `a = pi k df dt`, of bins `k`.
    sinc: Vec<f64>,
    /// The input holds point samples (no cell-average response to divide out).
    point: bool,
}

/// Most [`LowBins`] (and [`EnvelopePeak`]) plans an analyser keeps.
const MAX_LOW_PLANS: usize = 4;

impl Default for Analyzer {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for Analyzer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Analyzer")
    }
}

impl Analyzer {
    /// A new analyser (plans are created lazily per size and cached).
    pub fn new() -> Self {
        Analyzer {
            real: RealFftPlanner::new(),
            cplx: FftPlanner::new(),
            input: Vec::new(),
            spec: Vec::new(),
            band: Vec::new(),
            scratch: Vec::new(),
            low: Vec::new(),
            point: false,
            envelopes: Vec::new(),
            sinc_key: (0, 0),
            sinc: Vec::new(),
        }
    }

    /// [`Self::transform_input`] for bins `0..k` only (the bins a band analysis reads):
    /// from a [`LowBins`] plan where that is cheaper than the whole transform. Leaves at
    /// least bins `0..k` (at most `n_fft / 2 + 1`) in `self.spec`; returns (n_fft, df).
    fn transform_low(&mut self, dt: f64, min_len: usize, f_max: f64) -> (usize, f64) {
        let len = self.input.len();
        let n_fft = padded_len(len, min_len);
        let df = 1.0 / (n_fft as f64 * dt);
        let k = (f_max / df).ceil();
        let k = if k.is_finite() && k >= 0.0 {
            (k as usize).min(n_fft / 2 + 1)
        } else {
            n_fft / 2 + 1
        };
        let i = match self
            .low
            .iter()
            .position(|p| p.size() == n_fft && p.bins() == k)
        {
            Some(i) => Some(i),
            None => LowBins::plan(&mut self.cplx, n_fft, k).map(|p| {
                if self.low.len() >= MAX_LOW_PLANS {
                    self.low.remove(0);
                }
                self.low.push(p);
                self.low.len() - 1
            }),
        };
        match i {
            Some(i) => {
                self.low[i].process(&self.input, &mut self.spec);
                (n_fft, df)
            }
            None => self.transform_input(dt, min_len),
        }
    }

    /// Tabulate in `self.sinc` the cell-average responses of bins `0..k` for transform
    /// length `n_fft` and step `dt`: `max(sin(a)/a, 1e-3)`, `a = pi k df dt` (once per
    /// `(n_fft, dt)`; a longer `k` extends the table).
    fn tabulate_sinc(&mut self, n_fft: usize, df: f64, dt: f64, k: usize) {
        let key = (n_fft, dt.to_bits());
        if self.sinc_key != key {
            self.sinc_key = key;
            self.sinc.clear();
        }
        while self.sinc.len() < k {
            let a = std::f64::consts::PI * self.sinc.len() as f64 * df * dt;
            self.sinc.push((a.sin() / a).max(1e-3));
        }
    }

    /// Forward transform of cell-averaged samples `x` (step `dt`), zero-padded to a power
    /// of two at least `2 len`, with the cell-average response divided out. Leaves the
    /// spectrum in `self.spec`; returns (n_fft, df).
    fn transform(&mut self, x: &[f64], dt: f64, min_len: usize) -> (usize, f64) {
        self.input.clear();
        self.input.extend_from_slice(x);
        self.transform_input(dt, min_len)
    }

    /// [`Self::transform`] of the samples already in `self.input`.
    fn transform_input(&mut self, dt: f64, min_len: usize) -> (usize, f64) {
        let len = self.input.len();
        let n_fft = padded_len(len, min_len);
        let plan = self.real.plan_fft_forward(n_fft);
        self.input.resize(n_fft, 0.0);
        self.spec.resize(n_fft / 2 + 1, Complex::new(0.0, 0.0));
        self.scratch
            .resize(plan.get_scratch_len(), Complex::new(0.0, 0.0));
        // lengths are consistent by construction
        let _ = plan.process_with_scratch(&mut self.input, &mut self.spec, &mut self.scratch);
        (n_fft, 1.0 / (n_fft as f64 * dt))
    }

    /// Peak of the envelope of the signal band-limited to `[f_lo, f_hi)`.
    fn band_peak(&mut self, n_fft: usize, df: f64, dt: f64, f_lo: f64, f_hi: f64) -> f64 {
        let k_lo = (f_lo / df).ceil().max(1.0) as usize;
        let k_hi = ((f_hi / df).ceil() as usize).min(self.spec.len());
        if k_hi <= k_lo {
            return 0.0;
        }
        let nb = k_hi - k_lo;
        let m = (16 * nb).next_power_of_two().max(64);
        // divide out the cell-average response sinc(pi f dt)
        self.tabulate_sinc(n_fft, df, dt, k_hi);
        self.band.clear();
        let point = self.point;
        self.band.extend(
            self.spec[k_lo..k_hi]
                .iter()
                .zip(&self.sinc[k_lo..k_hi])
                .map(|(c, s)| if point { *c } else { c / s }),
        );
        let i = match self.envelopes.iter().position(|p| p.size() == m) {
            Some(i) => i,
            None => {
                // (m is a power of two of at least 64: a multiple of 16)
                let Some(p) = EnvelopePeak::plan(&mut self.cplx, m) else {
                    return f64::NAN;
                };
                if self.envelopes.len() >= MAX_LOW_PLANS {
                    self.envelopes.remove(0);
                }
                self.envelopes.push(p);
                self.envelopes.len() - 1
            }
        };
        let peak2 = self.envelopes[i].peak_norm_sqr(&self.band);
        2.0 * peak2.sqrt() / n_fft as f64
    }

    /// Band amplitudes of the cell-averaged signal `x` (step `dt`) for fundamental `f0`
    /// and optional second frequency `f2` (two-tone).
    pub fn bands(&mut self, x: &[f64], dt: f64, f0: f64, f2: Option<f64>) -> BandAmplitudes {
        self.input.clear();
        self.input.extend_from_slice(x);
        self.input_bands(dt, f0, f2)
    }

    /// [`Self::bands`] of point samples `x` (a signal sampled at `t0 + k dt`, as a 2D
    /// receiver or an oscilloscope records it): no cell-average response is divided out.
    pub fn point_bands(&mut self, x: &[f64], dt: f64, f0: f64, f2: Option<f64>) -> BandAmplitudes {
        self.point = true;
        let b = self.bands(x, dt, f0, f2);
        self.point = false;
        b
    }

    /// [`Self::bands`] of the cell-averaged velocity (m/s) of a displacement record (m,
    /// step `dt` s): the velocities are written straight into the transform's input (the
    /// same values as [`cell_velocity`], without a vector of their own).
    pub fn displacement_bands(
        &mut self,
        displacement: &[f64],
        dt: f64,
        f0: f64,
        f2: Option<f64>,
    ) -> BandAmplitudes {
        self.input.clear();
        self.input
            .extend(displacement.windows(2).map(|w| (w[1] - w[0]) / dt));
        self.input_bands(dt, f0, f2)
    }

    /// [`Self::bands`] of the samples already in `self.input`.
    fn input_bands(&mut self, dt: f64, f0: f64, f2: Option<f64>) -> BandAmplitudes {
        let len = self.input.len();
        // zero-pad by BAND_PAD_PERIODS periods of f0 at least: the band filter's kernel
        // rings over tens of periods, and without the padding its circular wrap-around
        // makes the amplitudes depend on how long the record is (0.2% seen)
        let pad = (BAND_PAD_PERIODS / (f0 * dt)).ceil();
        let min_len = if pad.is_finite() && pad < 1e8 {
            len + pad as usize
        } else {
            0
        };
        // the bands: harmonics 1..=5, the sub-harmonic, and a two-tone's f2, sum and
        // difference components
        let mut bands = [(0.0, 0.0); 9];
        for (n, b) in bands.iter_mut().enumerate().take(6).skip(1) {
            let c = n as f64 * f0;
            *b = (c - 0.5 * f0, c + 0.5 * f0);
        }
        bands[0] = (0.25 * f0, 0.75 * f0);
        let used = match f2 {
            Some(f2) => {
                let diff = (f2 - f0).abs();
                let hw = 0.25 * f0.min(f2).min(diff);
                bands[6] = (f2 - hw, f2 + hw);
                bands[7] = (f0 + f2 - hw, f0 + f2 + hw);
                bands[8] = (diff - hw, diff + hw);
                9
            }
            None => 6,
        };
        let f_max = bands[..used].iter().fold(0.0f64, |m, b| m.max(b.1));
        let (n_fft, df) = self.transform_low(dt, min_len, f_max);
        let mut peak = [0.0; 9];
        for (p, &(lo, hi)) in peak.iter_mut().zip(&bands[..used]) {
            *p = self.band_peak(n_fft, df, dt, lo, hi);
        }
        let mut out = BandAmplitudes::default();
        out.harmonic[1..6].copy_from_slice(&peak[1..6]);
        out.subharmonic = peak[0];
        if f2.is_some() {
            (out.f2, out.sum, out.difference) = (peak[6], peak[7], peak[8]);
        }
        out
    }

    /// Discrete Fourier transform (bins 0..=n/2) of the samples `x`, optionally under a
    /// Hann window over their length, zero-padded to `n = 2 next_power_of_two(len)`.
    pub fn dft_padded(&mut self, x: &[f64], hann: bool) -> Result<Vec<Complex<f64>>> {
        let n = x.len().next_power_of_two() * 2;
        let plan = self.real.plan_fft_forward(n);
        let m = x.len();
        self.input.clear();
        self.input.extend(x.iter().enumerate().map(|(i, v)| {
            let w = if hann {
                0.5 * (1.0 - (2.0 * std::f64::consts::PI * i as f64 / (m as f64 - 1.0)).cos())
            } else {
                1.0
            };
            v * w
        }));
        self.input.resize(n, 0.0);
        let mut out = plan.make_output_vec();
        self.scratch
            .resize(plan.get_scratch_len(), Complex::new(0.0, 0.0));
        plan.process_with_scratch(&mut self.input, &mut out, &mut self.scratch)
            .map_err(|e| Error::numerical(0.0, format!("FFT of {m} samples: {e}"), ""))?;
        Ok(out)
    }

    /// One-sided amplitude spectrum `|X(f)| dt` of the cell-averaged signal `x`, up to
    /// `f_max` (Hz).
    pub fn spectrum(&mut self, x: &[f64], dt: f64, f_max: f64) -> Spectrum {
        let (_n, df) = self.transform(x, dt, 0);
        let kmax = ((f_max / df).ceil() as usize).min(self.spec.len());
        let sinc = |k: usize| {
            let a = std::f64::consts::PI * k as f64 * df * dt;
            if k == 0 {
                1.0
            } else {
                (a.sin() / a).max(1e-3)
            }
        };
        Spectrum {
            frequency: (0..kmax).map(|k| k as f64 * df).collect(),
            magnitude: self.spec[..kmax]
                .iter()
                .enumerate()
                .map(|(k, c)| c.norm() * dt / sinc(k))
                .collect(),
        }
    }
}

/// Zero padding of the band analysis, in periods of the fundamental.
const BAND_PAD_PERIODS: f64 = 64.0;

/// Transform length of a record of `len` samples: at least `1.125 len + 16` and
/// `min_len`, of the form 2^a 3^b 5^c.
fn padded_len(len: usize, min_len: usize) -> usize {
    fast_len((len + len / 8 + 16).max(min_len))
}

/// Smallest length >= n of the form 2^a 3^b 5^c (fast for RustFFT).
fn fast_len(n: usize) -> usize {
    let mut best = n.next_power_of_two();
    let mut p5 = 1;
    while p5 < best {
        let mut p35 = p5;
        while p35 < best {
            let mut v = p35;
            while v < n {
                v *= 2;
            }
            best = best.min(v);
            p35 *= 3;
        }
        p5 *= 5;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn band_amplitudes_of_known_signal() {
        // Hann-windowed 1.0 sin(w t) + 0.1 sin(2 w t) over 40 periods, as cell averages;
        // a smooth window keeps the brick-wall band filter free of Gibbs overshoot
        let f = 1e6;
        let dt = 1.0 / (f * 64.0);
        let n = 64 * 40;
        let dur = n as f64 * dt;
        let v = |t: f64| {
            let w = 2.0 * std::f64::consts::PI * f;
            let win = 0.5 * (1.0 - (2.0 * std::f64::consts::PI * t / dur).cos());
            win * ((w * t).sin() + 0.1 * (2.0 * w * t).sin())
        };
        let x: Vec<f64> = (0..n)
            .map(|k| crate::numeric::gauss4(k as f64 * dt, (k + 1) as f64 * dt, v) / dt)
            .collect();
        let mut a = Analyzer::new();
        let b = a.bands(&x, dt, f, None);
        assert!((b.harmonic[1] - 1.0).abs() < 2e-3, "{}", b.harmonic[1]);
        assert!((b.harmonic[2] - 0.1).abs() < 2e-4, "{}", b.harmonic[2]);
        assert!(b.harmonic[3] < 1e-2);
    }
}

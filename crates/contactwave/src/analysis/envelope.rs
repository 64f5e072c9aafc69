//! The peak of a band's envelope without the whole zero-padded inverse transform.
//!
//! The band analysis reads a band of `nb` bins, zero-pads it to `m >= 16 nb` and takes the
//! largest modulus of its inverse transform `y[n] = sum_{k < nb} c_k W^(-n k)`,
//! `W = exp(-2 pi i / m)`. With `n = r + 16 q` (`r < 16`, `q < m / 16`),
//!
//! ```text
//! y[r + 16 q] = sum_{k < m/16} (c_k W^(-r k)) W_{m/16}^(-q k),
//! ```
//!
//! so the `m` samples are 16 inverse transforms of length `m / 16` of the twiddled band
//! (the band fits in one: `nb <= m / 16`). Only the largest modulus is wanted, so the
//! samples are not put back in order. The samples are the `m`-point transform's, to
//! round-off.

use multiversion::multiversion;
use realfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Rows of the decomposition (the oversampling a band analysis asks for at least).
const ROWS: usize = 16;

/// A plan for the envelope peak of bands zero-padded to `m` samples.
pub struct EnvelopePeak {
    m: usize,
    fft: Arc<dyn Fft<f64>>,
    /// `twiddle[r * (m / 16) + k] = exp(2 pi i r k / m)`.
    twiddle: Vec<Complex<f64>>,
    buf: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl std::fmt::Debug for EnvelopePeak {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "EnvelopePeak(m = {})", self.m)
    }
}

impl EnvelopePeak {
    /// A plan for `m` samples (`None` unless `m` is a multiple of 16).
    pub fn plan(planner: &mut FftPlanner<f64>, m: usize) -> Option<EnvelopePeak> {
        if m == 0 || !m.is_multiple_of(ROWS) {
            return None;
        }
        let q = m / ROWS;
        let twiddle = super::low_bins::unit_roots(ROWS, q, m, 1.0);
        let fft = planner.plan_fft_inverse(q);
        let scratch = vec![Complex::new(0.0, 0.0); fft.get_inplace_scratch_len()];
        Some(EnvelopePeak {
            m,
            fft,
            twiddle,
            buf: vec![Complex::new(0.0, 0.0); m],
            scratch,
        })
    }

    /// Samples `m`.
    pub fn size(&self) -> usize {
        self.m
    }

    /// The largest `|y[n]|^2` of the inverse transform of `band` zero-padded to `m`
    /// (`band.len() <= m / 16`; a longer band is cut there). NaN samples are passed over.
    pub fn peak_norm_sqr(&mut self, band: &[Complex<f64>]) -> f64 {
        let q = self.m / ROWS;
        let nb = band.len().min(q);
        twiddle_rows(&mut self.buf, &self.twiddle, &band[..nb], q);
        self.fft
            .process_with_scratch(&mut self.buf, &mut self.scratch);
        max_norm_sqr(&self.buf)
    }
}

/// Rows of `q` entries of `buf`: `band` times the row's twiddles, then zeros.
#[multiversion(targets("x86_64+avx+avx2"))]
fn twiddle_rows(
    buf: &mut [Complex<f64>],
    twiddle: &[Complex<f64>],
    band: &[Complex<f64>],
    q: usize,
) {
    let nb = band.len();
    for (row, tw) in buf.chunks_exact_mut(q).zip(twiddle.chunks_exact(q)) {
        for ((y, c), w) in row.iter_mut().zip(band).zip(tw) {
            *y = c * w;
        }
        row[nb..].fill(Complex::new(0.0, 0.0));
    }
}

/// The largest `|c|^2` of `v` (0 for an empty slice; NaN entries are passed over), in
/// four lanes so that the loop vectorises.
#[multiversion(targets("x86_64+avx+avx2"))]
pub fn max_norm_sqr(v: &[Complex<f64>]) -> f64 {
    let mut lanes = [0.0f64; 4];
    let chunks = v.chunks_exact(4);
    let rest = chunks.remainder();
    for ch in chunks {
        for (m, c) in lanes.iter_mut().zip(ch) {
            let x = c.norm_sqr();
            *m = if x > *m { x } else { *m };
        }
    }
    for c in rest {
        let x = c.norm_sqr();
        lanes[0] = if x > lanes[0] { x } else { lanes[0] };
    }
    lanes.iter().fold(0.0, |a, &b| a.max(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The peak equals the largest modulus of the whole zero-padded inverse transform to
    /// round-off, for bands filling the row length or not, and several sizes.
    #[test]
    fn peak_is_the_zero_padded_transform_peak() {
        let mut planner = FftPlanner::new();
        for (m, nb) in [(64, 4), (1024, 42), (2048, 84), (2048, 128), (4096, 200)] {
            let band: Vec<Complex<f64>> = (0..nb)
                .map(|k| {
                    let x = k as f64 / nb as f64;
                    Complex::new((7.0 * x).sin() + 0.3, (3.0 * x).cos() * (1.0 - x))
                })
                .collect();
            let mut plan = EnvelopePeak::plan(&mut planner, m).expect("a multiple of 16");
            assert_eq!(plan.size(), m);
            let peak = plan.peak_norm_sqr(&band);
            // the same band twice: nothing carried between calls
            assert_eq!(plan.peak_norm_sqr(&band), peak);
            let mut full = band.clone();
            full.resize(m, Complex::new(0.0, 0.0));
            planner.plan_fft_inverse(m).process(&mut full);
            let direct = full.iter().fold(0.0f64, |p, c| p.max(c.norm_sqr()));
            assert!(
                (peak - direct).abs() <= 1e-13 * direct,
                "m {m} nb {nb}: {peak:e} vs {direct:e}"
            );
        }
        assert!(EnvelopePeak::plan(&mut planner, 100).is_none());
    }

    #[test]
    fn max_norm_sqr_of_every_length() {
        for n in 0..11 {
            let v: Vec<Complex<f64>> = (0..n)
                .map(|i| Complex::new(i as f64 - 4.0, 0.5 * i as f64))
                .collect();
            let direct = v.iter().fold(0.0f64, |p, c| p.max(c.norm_sqr()));
            assert_eq!(max_norm_sqr(&v), direct, "n = {n}");
        }
    }
}

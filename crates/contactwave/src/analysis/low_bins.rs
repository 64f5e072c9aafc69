//! The low bins of a long, zero-padded real DFT without the whole transform.
//!
//! The band analysis pads a record of `L` samples to `N` (tens of periods of zeros, so that
//! the band filter does not wrap around) and reads only the bins of the bands it analyses,
//! `k < K`, a few percent of the `N / 2` a real FFT returns. With `N = N1 N2`, `N2 >= K`,
//! and the input index `n = n1 + N1 n2` (Cooley-Tukey, decimation in time),
//!
//! ```text
//! X[k] = sum_{n1 < N1} W_N^(n1 k) Y_n1[k],   Y_n1 = DFT_N2( x[n1 + N1 n2] ),   k < K <= N2,
//! ```
//!
//! so the bins `k < K` take `N1` transforms of length `N2` (two real sequences per complex
//! transform) and `N1 K` twiddled sums, instead of the whole length-`N` transform (which a
//! real FFT of odd `N` computes as a complex one). The bins are the DFT's, to round-off.

use multiversion::multiversion;
use realfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// A plan for bins `0..k` of the `n`-point DFT of a real signal (zero-padded to `n`).
pub struct LowBins {
    n: usize,
    k: usize,
    n1: usize,
    n2: usize,
    fft: Arc<dyn Fft<f64>>,
    /// `twiddle[n1 * k + kk] = exp(-2 pi i n1 kk / n)`.
    twiddle: Vec<Complex<f64>>,
    buf: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl std::fmt::Debug for LowBins {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "LowBins(n = {}, k = {}, {} x {})",
            self.n, self.k, self.n1, self.n2
        )
    }
}

/// Rough cost of a complex FFT of length `m` (butterfly operations).
fn fft_cost(m: usize) -> f64 {
    let m = m as f64;
    m * m.log2().max(1.0)
}

impl LowBins {
    /// A plan for bins `0..k` of the `n`-point real DFT, or `None` where it would not be
    /// clearly cheaper than the whole real FFT (`n` even: realfft's half-length transform;
    /// no divisor of `n` at least `k` with a cofactor >= 2).
    pub fn plan(planner: &mut FftPlanner<f64>, n: usize, k: usize) -> Option<LowBins> {
        if k == 0 || n < 64 || k > n / 2 {
            return None;
        }
        // the whole transform: realfft's odd lengths are complex FFTs of the full length
        let full = if n.is_multiple_of(2) {
            fft_cost(n / 2) + 2.0 * n as f64
        } else {
            fft_cost(n)
        };
        let mut best: Option<(f64, usize)> = None;
        let divisors = (1..)
            .take_while(|d| d * d <= n)
            .filter(|d| n.is_multiple_of(*d))
            .flat_map(|d| [d, n / d]);
        for n2 in divisors.filter(|&d| d >= k && d <= n / 2) {
            let n1 = n / n2;
            let cost = n1.div_ceil(2) as f64 * fft_cost(n2) + 16.0 * (n1 * k) as f64;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, n2));
            }
        }
        let (cost, n2) = best?;
        if cost > 0.7 * full {
            return None;
        }
        let n1 = n / n2;
        let twiddle = unit_roots(n1, k, n, -1.0);
        let fft = planner.plan_fft_forward(n2);
        let scratch = vec![Complex::new(0.0, 0.0); fft.get_inplace_scratch_len()];
        Some(LowBins {
            n,
            k,
            n1,
            n2,
            fft,
            twiddle,
            buf: Vec::new(),
            scratch,
        })
    }

    /// Transform length `n`.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Number of bins `k`.
    pub fn bins(&self) -> usize {
        self.k
    }

    /// Bins `0..k` of the DFT of `x` zero-padded to `n` (`x.len() <= n`), into `out`
    /// (resized to `k`).
    pub fn process(&mut self, x: &[f64], out: &mut Vec<Complex<f64>>) {
        let (n1, n2, k) = (self.n1, self.n2, self.k);
        let len = x.len().min(self.n);
        let pairs = n1.div_ceil(2);
        self.buf.resize(pairs * n2, Complex::new(0.0, 0.0));
        // two decimated sequences per complex transform: x[a + n1 j] + i x[a + 1 + n1 j]
        // (zero where the record has ended; every entry is written: no clearing first)
        for (p, chunk) in self.buf.chunks_exact_mut(n2).enumerate() {
            let a = 2 * p;
            // entries with both parts in the record, then the last partial one
            let both = if a + 1 < n1 && a + 1 < len {
                (len - a - 1).div_ceil(n1).min(n2)
            } else {
                0
            };
            let real = if a < len {
                (len - a).div_ceil(n1).min(n2)
            } else {
                0
            };
            for (j, c) in chunk[..both].iter_mut().enumerate() {
                let i = a + n1 * j;
                *c = Complex::new(x[i], x[i + 1]);
            }
            for (j, c) in chunk[both..real].iter_mut().enumerate() {
                *c = Complex::new(x[a + n1 * (both + j)], 0.0);
            }
            chunk[real..].fill(Complex::new(0.0, 0.0));
        }
        self.fft
            .process_with_scratch(&mut self.buf, &mut self.scratch);
        out.clear();
        out.resize(k, Complex::new(0.0, 0.0));
        twiddled_sums(&self.buf, &self.twiddle, n1, n2, out);
    }
}

/// `out[kk] += sum_a W^(a kk) Y_a[kk]` over the decimated sequences `a < n1`, whose
/// spectra come in pairs from the complex transforms in `buf` (`n2` entries each):
/// `Y_a = (c + d) / 2` and `Y_(a+1) = (c - d) / (2 i)` with `c` the bin and `d` the
/// conjugate of its mirror.
#[multiversion(targets("x86_64+avx+avx2"))]
fn twiddled_sums(
    buf: &[Complex<f64>],
    twiddle: &[Complex<f64>],
    n1: usize,
    n2: usize,
    out: &mut [Complex<f64>],
) {
    let k = out.len();
    for (p, chunk) in buf.chunks_exact(n2).enumerate() {
        let a = 2 * p;
        let ta = &twiddle[a * k..(a + 1) * k];
        if a + 1 < n1 {
            let tb = &twiddle[(a + 1) * k..(a + 2) * k];
            for kk in 0..k {
                let c = chunk[kk];
                let d = chunk[mirror(kk, n2)].conj();
                // the two real sequences' spectra: (c + d) / 2 and (c - d) / (2 i)
                let ya = (c + d) * 0.5;
                let diff = c - d;
                let yb = Complex::new(0.5 * diff.im, -0.5 * diff.re);
                out[kk] += ta[kk] * ya + tb[kk] * yb;
            }
        } else {
            for kk in 0..k {
                let c = chunk[kk];
                let d = chunk[mirror(kk, n2)].conj();
                out[kk] += ta[kk] * ((c + d) * 0.5);
            }
        }
    }
}

/// `exp(sign 2 pi i a b / n)` for `a < rows`, `b < cols`, row by row (`sign` is 1 or -1),
/// each angle from the exact residue of `a b` modulo `n`: the twiddle factors of the pruned
/// transforms ([`LowBins`], [`super::envelope::EnvelopePeak`]).
pub(super) fn unit_roots(rows: usize, cols: usize, n: usize, sign: f64) -> Vec<Complex<f64>> {
    (0..rows)
        .flat_map(|a| {
            (0..cols).map(move |b| {
                let r = ((a as u64 * b as u64) % n as u64) as f64;
                let (s, c) = (sign * 2.0 * std::f64::consts::PI * r / n as f64).sin_cos();
                Complex::new(c, s)
            })
        })
        .collect()
}

/// `(n - k) mod n` for `k < n`: the bin of frequency `-k` (no integer division).
#[inline]
fn mirror(k: usize, n: usize) -> usize {
    if k == 0 {
        0
    } else {
        n - k
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use realfft::RealFftPlanner;

    /// The low bins equal the whole real FFT's to round-off (relative to the largest bin),
    /// for odd and even lengths, records shorter than the transform and odd cofactors.
    #[test]
    fn low_bins_are_the_real_fft_bins() {
        let mut planner = FftPlanner::new();
        let mut real = RealFftPlanner::<f64>::new();
        for (n, k, len) in [
            (16875, 470, 3800),
            (16875, 90, 16875),
            (50625, 600, 9000),
            (2025, 30, 77),
        ] {
            let x: Vec<f64> = (0..len)
                .map(|i| {
                    let t = i as f64 / len as f64;
                    (37.0 * t).sin() * (1.0 - t) + 1e-3 * (0.3 * i as f64).cos() + 0.2
                })
                .collect();
            let mut plan = LowBins::plan(&mut planner, n, k).expect("a cheaper plan");
            assert_eq!((plan.size(), plan.bins()), (n, k));
            let mut low = Vec::new();
            plan.process(&x, &mut low);
            // the same input twice: no state carried between calls
            let mut again = Vec::new();
            plan.process(&x, &mut again);
            assert_eq!(low, again);
            let fft = real.plan_fft_forward(n);
            let mut input = x.clone();
            input.resize(n, 0.0);
            let mut spec = fft.make_output_vec();
            fft.process(&mut input, &mut spec).unwrap();
            let scale = spec.iter().fold(0.0f64, |m, c| m.max(c.norm()));
            for kk in 0..k {
                let e = (low[kk] - spec[kk]).norm();
                assert!(e <= 1e-13 * scale, "n {n} bin {kk}: {e:e} of {scale:e}");
            }
        }
    }

    #[test]
    fn no_plan_where_the_whole_transform_is_as_cheap() {
        let mut planner = FftPlanner::new();
        // k beyond half the length, a prime length, and bins near half of an even length
        assert!(LowBins::plan(&mut planner, 1000, 600).is_none());
        assert!(LowBins::plan(&mut planner, 1009, 10).is_none());
        assert!(LowBins::plan(&mut planner, 4096, 1500).is_none());
    }
}

//! A receiving transducer's response (model.md section 16.4): the second-order band-pass
//!
//! ```text
//! (16.4)  H(f) = (j f / (Q f_c)) / (1 - (f / f_c)^2 + j f / (Q f_c))
//! ```
//!
//! (gain 1 at the centre frequency `f_c`, bandwidth `f_c / Q`, causal: the response of a
//! damped resonator), applied in the frequency domain after zero padding to at least twice
//! the record (no wrap-around of the ringing). An identification from raw records
//! ([`crate::inverse`]) passes the forward model's signal through the same response as the
//! measured one went through, so that model and measurement are reduced alike; the
//! synthetic records of `contactwave identify --synthesize` go through it too.
//!
//! ```
//! use contactwave::measured::BandPass;
//! use std::f64::consts::PI;
//! let (dt, f) = (1e-8, 2e6);
//! let x: Vec<f64> = (0..20000).map(|k| (2.0 * PI * f * k as f64 * dt).sin()).collect();
//! let bp = BandPass { centre: 4e6, q: 0.7 };
//! let y = bp.apply(&x, dt);
//! // in the steady state the amplitude is |H(f)|
//! let peak = y[10000..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
//! assert!((peak / bp.gain(f) - 1.0).abs() < 1e-3);
//! ```

use crate::error::{Error, Result};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

/// A second-order band-pass (eq. 16.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandPass {
    /// Centre frequency `f_c`, Hz (> 0).
    pub centre: f64,
    /// Quality factor `Q` (> 0): the bandwidth is `f_c / Q`.
    pub q: f64,
}

impl BandPass {
    /// Checked: `centre` and `q` finite and > 0 (`field` names them in the error).
    pub fn new(centre: f64, q: f64, file: &str, field: &str) -> Result<BandPass> {
        if !(centre.is_finite() && centre > 0.0 && q.is_finite() && q > 0.0) {
            return Err(Error::invalid(
                file,
                field,
                format!("centre {centre}, q {q}"),
                "a centre frequency > 0 (Hz) and a quality factor > 0",
            ));
        }
        Ok(BandPass { centre, q })
    }

    /// The complex response at `f`, Hz.
    pub fn response(&self, f: f64) -> Complex<f64> {
        let r = f / self.centre;
        let num = Complex::new(0.0, r / self.q);
        num / Complex::new(1.0 - r * r, r / self.q)
    }

    /// `|H(f)|`.
    pub fn gain(&self, f: f64) -> f64 {
        self.response(f).norm()
    }

    /// `x` (sampled every `dt` s) through the band-pass: same length, same time base.
    pub fn apply(&self, x: &[f64], dt: f64) -> Vec<f64> {
        if x.is_empty() {
            return Vec::new();
        }
        let n = (2 * x.len()).next_power_of_two();
        let mut planner = RealFftPlanner::<f64>::new();
        let (fwd, inv) = (planner.plan_fft_forward(n), planner.plan_fft_inverse(n));
        let mut buf = vec![0.0; n];
        buf[..x.len()].copy_from_slice(x);
        let mut spec = fwd.make_output_vec();
        // lengths come from the plans: the transforms cannot fail
        if fwd.process(&mut buf, &mut spec).is_err() {
            return x.to_vec();
        }
        let df = 1.0 / (n as f64 * dt);
        for (k, s) in spec.iter_mut().enumerate() {
            *s *= self.response(k as f64 * df) / n as f64;
        }
        // the Nyquist bin of a real signal is real
        if let Some(last) = spec.last_mut() {
            last.im = 0.0;
        }
        spec[0].im = 0.0;
        if inv.process(&mut spec, &mut buf).is_err() {
            return x.to_vec();
        }
        buf.truncate(x.len());
        buf
    }
}

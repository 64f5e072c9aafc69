//! Windowed sinusoidal tone burst (thesis Figure 20, chapter 3 "smooth rectangular"
//! window; chapter 5 half-Hann ramps each covering 1/4 of the burst).

use super::{numeric_peak, Excitation};

/// Burst window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Window {
    /// Flat top with half-Hann ramps, each covering `ramp_fraction` of the burst.
    HannRamps {
        /// Fraction of the burst per ramp, in (0, 0.5].
        ramp_fraction: f64,
    },
    /// Full Hann window.
    Hann,
    /// No window.
    Rectangular,
}

impl Window {
    /// Window value at normalised time `s = t / duration` in [0, 1].
    pub fn value(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        match *self {
            Window::Rectangular => 1.0,
            Window::Hann => 0.5 * (1.0 - (2.0 * std::f64::consts::PI * s).cos()),
            Window::HannRamps { ramp_fraction: r } => {
                if s < r {
                    0.5 * (1.0 - (std::f64::consts::PI * s / r).cos())
                } else if s > 1.0 - r {
                    0.5 * (1.0 - (std::f64::consts::PI * (1.0 - s) / r).cos())
                } else {
                    1.0
                }
            }
        }
    }

    fn joints(&self) -> Vec<f64> {
        match *self {
            Window::HannRamps { ramp_fraction: r } => vec![r, 1.0 - r],
            _ => vec![],
        }
    }
}

/// `s_inc(t) = -A / n * window(t/D) * sin(2 pi f0 t)`, `D = cycles / f0`, where the
/// normalisation `n` makes the peak of |s_inc| exactly `A`.
#[derive(Debug, Clone)]
pub struct ToneBurst {
    amplitude: f64,
    frequency: f64,
    duration: f64,
    window: Window,
    norm: f64,
    /// `amplitude / norm`, Pa (computed once: the same value `stress` computed per call).
    scale: f64,
    /// `2 pi frequency`, rad/s.
    omega: f64,
}

impl ToneBurst {
    /// A burst of `cycles` cycles at `frequency` (Hz) whose |stress| peaks at `amplitude` (Pa).
    pub fn new(amplitude: f64, frequency: f64, cycles: f64, window: Window) -> Self {
        let duration = cycles / frequency;
        let mut b = ToneBurst {
            amplitude,
            frequency,
            duration,
            window,
            norm: 1.0,
            scale: amplitude,
            omega: 2.0 * std::f64::consts::PI * frequency,
        };
        let n = ((cycles * 64.0) as usize).clamp(256, 1 << 20);
        b.norm = numeric_peak(|t| b.raw(t), duration, n).max(1e-300);
        b.scale = b.amplitude / b.norm;
        b
    }

    #[inline]
    fn raw(&self, t: f64) -> f64 {
        -self.window.value(t / self.duration) * (self.omega * t).sin()
    }
}

impl Excitation for ToneBurst {
    #[inline]
    fn stress(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.duration {
            return 0.0;
        }
        self.scale * self.raw(t)
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn fundamental(&self) -> f64 {
        self.frequency
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut v = vec![0.0, self.duration];
        v.extend(self.window.joints().into_iter().map(|s| s * self.duration));
        v
    }
    fn peak(&self) -> f64 {
        self.amplitude
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn starts_compressive_and_peaks_at_amplitude() {
        for w in [
            Window::HannRamps {
                ramp_fraction: 0.25,
            },
            Window::Hann,
            Window::Rectangular,
        ] {
            let b = ToneBurst::new(2.0e6, 1e6, 15.0, w);
            assert!(b.stress(0.1e-6) <= 0.0);
            let peak = (0..100_000)
                .map(|i| b.stress(i as f64 * 15e-6 / 100_000.0).abs())
                .fold(0.0f64, f64::max);
            assert!((peak - 2.0e6).abs() < 1e-6 * 2.0e6, "{w:?} {peak}");
        }
    }
}

//! Two-tone burst for wave-modulation studies: `s_inc = -A/n window(t) (sin(2 pi f1 t) +
//! r sin(2 pi f2 t))`, peak of |s_inc| equal to `A`.

use super::{numeric_peak, Excitation, Window};

/// Windowed sum of two sinusoids.
#[derive(Debug, Clone)]
pub struct TwoTone {
    amplitude: f64,
    f1: f64,
    f2: f64,
    ratio: f64,
    duration: f64,
    window: Window,
    norm: f64,
}

impl TwoTone {
    /// Burst of duration `cycles / f1`, frequencies `f1`, `f2` (Hz), amplitude ratio
    /// `ratio` of the f2 component, peak |stress| `amplitude` (Pa).
    pub fn new(amplitude: f64, f1: f64, f2: f64, ratio: f64, cycles: f64, window: Window) -> Self {
        let duration = cycles / f1;
        let mut b = TwoTone {
            amplitude,
            f1,
            f2,
            ratio,
            duration,
            window,
            norm: 1.0,
        };
        let n = ((cycles * 64.0 * (f2 / f1).max(1.0)) as usize).clamp(256, 1 << 22);
        b.norm = numeric_peak(|t| b.raw(t), duration, n).max(1e-300);
        b
    }

    fn raw(&self, t: f64) -> f64 {
        let tau = 2.0 * std::f64::consts::PI * t;
        -self.window.value(t / self.duration)
            * ((tau * self.f1).sin() + self.ratio * (tau * self.f2).sin())
    }
}

impl Excitation for TwoTone {
    fn stress(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.duration {
            return 0.0;
        }
        self.amplitude / self.norm * self.raw(t)
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn fundamental(&self) -> f64 {
        self.f1
    }
    fn highest_frequency(&self) -> f64 {
        self.f1.max(self.f2)
    }
    fn second_frequency(&self) -> Option<f64> {
        Some(self.f2)
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut v = vec![0.0, self.duration];
        if let Window::HannRamps { ramp_fraction } = self.window {
            v.push(ramp_fraction * self.duration);
            v.push((1.0 - ramp_fraction) * self.duration);
        }
        v
    }
    fn peak(&self) -> f64 {
        self.amplitude
    }
}

//! A waveform arriving later: `s(t) = inner(t - delay)`. The bar-stack solver takes the
//! incident stress where the wave meets the first interface; a scenario gives it where it
//! enters the stack, one travel time of the first segment earlier.

use super::Excitation;
use std::sync::Arc;

/// `inner` delayed by `delay` seconds.
#[derive(Debug, Clone)]
pub struct Delayed {
    inner: Arc<dyn Excitation>,
    delay: f64,
}

impl Delayed {
    /// `inner` shifted later by `delay` (s, >= 0).
    pub fn new(inner: Arc<dyn Excitation>, delay: f64) -> Self {
        Delayed { inner, delay }
    }
}

impl Excitation for Delayed {
    fn stress(&self, t: f64) -> f64 {
        self.inner.stress(t - self.delay)
    }
    fn stress_nodes(&self, t: f64, h: f64, c: &[f64], out: &mut [f64]) {
        self.inner.stress_nodes(t - self.delay, h, c, out);
    }
    fn duration(&self) -> f64 {
        self.inner.duration() + self.delay
    }
    fn fundamental(&self) -> f64 {
        self.inner.fundamental()
    }
    fn highest_frequency(&self) -> f64 {
        self.inner.highest_frequency()
    }
    fn second_frequency(&self) -> Option<f64> {
        self.inner.second_frequency()
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.inner
            .breakpoints()
            .into_iter()
            .map(|t| t + self.delay)
            .collect()
    }
    fn peak(&self) -> f64 {
        self.inner.peak()
    }
    /// The inner shape, delayed.
    fn grid_key(&self) -> Option<Vec<u64>> {
        let mut k = self.inner.grid_key()?;
        k.extend([3, self.delay.to_bits()]);
        Some(k)
    }
    fn unit_shape(&self) -> Option<super::UnitShape> {
        let mut u = self.inner.unit_shape()?;
        u.key.extend([3, self.delay.to_bits()]);
        u.unit = Arc::new(Delayed::new(u.unit, self.delay));
        Some(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::excitation::{ToneBurst, Window};

    #[test]
    fn delay_shifts_the_waveform_and_keeps_its_spectrum_keys() {
        let b: Arc<dyn Excitation> = Arc::new(ToneBurst::new(2.0, 1e5, 5.0, Window::Rectangular));
        let d = Delayed::new(b.clone(), 3e-5);
        for k in 0..200 {
            let t = k as f64 * 1.3e-6;
            // equal up to the rounding of t + delay - delay
            assert!((d.stress(t + 3e-5) - b.stress(t)).abs() < 1e-9);
        }
        assert_eq!(d.stress(1e-5), 0.0);
        assert!((d.duration() - (b.duration() + 3e-5)).abs() < 1e-18);
        assert_eq!(d.fundamental(), 1e5);
        assert_eq!(d.peak(), 2.0);
        assert_eq!(d.breakpoints()[0], 3e-5);
    }
}

//! A waveform times a constant: the normal or tangential traction of an obliquely
//! incident plane wave at the interface (model.md section 14), and with factor -1 the
//! phase-inverted copy of a burst, the second burst of pulse inversion (thesis chapter 1;
//! model.md section 6.1).

use super::Excitation;
use std::sync::Arc;

/// `factor * inner(t)`.
#[derive(Debug, Clone)]
pub struct Scaled {
    inner: Arc<dyn Excitation>,
    factor: f64,
}

impl Scaled {
    /// `factor` (dimensionless) times `inner`.
    pub fn new(inner: Arc<dyn Excitation>, factor: f64) -> Self {
        Scaled { inner, factor }
    }

    /// The phase-inverted copy of `inner`, `-inner(t)` (same duration, breakpoints,
    /// frequencies and peak).
    pub fn negated(inner: Arc<dyn Excitation>) -> Self {
        Scaled::new(inner, -1.0)
    }
}

impl Excitation for Scaled {
    fn stress(&self, t: f64) -> f64 {
        self.factor * self.inner.stress(t)
    }
    fn stress_nodes(&self, t: f64, h: f64, c: &[f64], out: &mut [f64]) {
        self.inner.stress_nodes(t, h, c, out);
        for o in out.iter_mut() {
            *o *= self.factor;
        }
    }
    fn stress_grid(&self, h: f64, c: &[f64], steps: usize, out: &mut [f64]) {
        self.inner.stress_grid(h, c, steps, out);
        for o in out.iter_mut().take(steps * c.len()) {
            *o *= self.factor;
        }
    }
    fn duration(&self) -> f64 {
        self.inner.duration()
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
        self.inner.breakpoints()
    }
    fn peak(&self) -> f64 {
        self.factor.abs() * self.inner.peak()
    }
    /// The inner shape with the factor's sign.
    fn grid_key(&self) -> Option<Vec<u64>> {
        let mut k = self.inner.grid_key()?;
        k.extend([2, self.factor.to_bits()]);
        Some(k)
    }
    fn unit_shape(&self) -> Option<super::UnitShape> {
        let mut u = self.inner.unit_shape()?;
        let sign = self.factor.signum();
        u.key.extend([2, sign.to_bits()]);
        u.unit = Arc::new(Scaled::new(u.unit, sign));
        Some(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::excitation::{ToneBurst, Window};

    /// A waveform is its peak times its unit shape, and the shape's key depends on the
    /// shape only: the same for two amplitudes (and the same unit waveform, bit for bit),
    /// another for another window, cycle count, sign or delay.
    #[test]
    fn unit_shape_is_the_waveform_over_its_peak() {
        let w = Window::HannRamps {
            ramp_fraction: 0.25,
        };
        let burst = |a: f64, cycles: f64| -> Arc<dyn Excitation> {
            Arc::new(ToneBurst::new(a, 1e6, cycles, w))
        };
        let wrapped = |e: Arc<dyn Excitation>, f: f64| -> Arc<dyn Excitation> {
            Arc::new(Scaled::new(
                Arc::new(crate::excitation::Delayed::new(e, 2e-6)),
                f,
            ))
        };
        let (a, b) = (
            wrapped(burst(3e5, 15.0), -0.7),
            wrapped(burst(8e6, 15.0), -2.0),
        );
        let (ua, ub) = (a.unit_shape().unwrap(), b.unit_shape().unwrap());
        assert_eq!(ua.key, ub.key);
        assert_eq!(ua.unit.peak(), 1.0);
        for k in 0..2000 {
            let t = k as f64 * 1.1e-8;
            let (sa, su) = (a.stress(t), a.peak() * ua.unit.stress(t));
            assert!((sa - su).abs() <= 1e-12 * a.peak(), "{t}: {sa} vs {su}");
            assert_eq!(ua.unit.stress(t).to_bits(), ub.unit.stress(t).to_bits());
        }
        let others = [
            wrapped(burst(3e5, 15.0), 0.7),
            wrapped(burst(3e5, 10.0), -0.7),
            Arc::new(Scaled::new(burst(3e5, 15.0), -0.7)),
            Arc::new(ToneBurst::new(3e5, 1e6, 15.0, Window::Hann)),
        ];
        for o in others {
            assert_ne!(o.unit_shape().unwrap().key, ua.key, "{o:?}");
        }
    }

    #[test]
    fn scales_stress_and_peak() {
        let b: Arc<dyn Excitation> = Arc::new(ToneBurst::new(2.0, 1e6, 5.0, Window::Hann));
        let s = Scaled::new(b.clone(), -0.5);
        assert_eq!(s.stress(1.3e-6), -0.5 * b.stress(1.3e-6));
        assert!((s.peak() - 1.0).abs() < 1e-12);
        assert_eq!(s.duration(), b.duration());
    }

    #[test]
    fn negation_flips_the_sign_and_keeps_everything_else() {
        let b: Arc<dyn Excitation> = Arc::new(ToneBurst::new(2.0, 1e5, 5.0, Window::Hann));
        let n = Scaled::negated(b.clone());
        let mut largest = 0.0f64;
        for k in 0..500 {
            let t = k as f64 * 1.1e-6;
            assert_eq!(n.stress(t), -b.stress(t));
            largest = largest.max(b.stress(t).abs());
        }
        assert!(largest > 1.0, "the burst was sampled where it is not zero");
        assert_eq!(n.duration(), b.duration());
        assert_eq!(n.fundamental(), 1e5);
        assert_eq!(n.peak(), b.peak());
        assert_eq!(n.breakpoints(), b.breakpoints());
    }
}

//! A time gate around the echo of interest (model.md section 6.1): the record kept between
//! `start` and `end`, its edges tapered by half-cosines `taper` long inside the gate, and
//! zero outside (the thesis' records need none: their reflected wave is alone; a receiver
//! in 2D, or a measured record, sees several echoes).

use std::f64::consts::PI;

/// A time gate (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gate {
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// Length of the half-cosine ramps at each edge, inside `[start, end]`, s (0: a
    /// rectangular gate).
    pub taper: f64,
}

impl Gate {
    /// Weight of the sample at `t` (s): 0 outside the gate, 1 inside its flat part, a
    /// half-cosine ramp between.
    pub fn weight(&self, t: f64) -> f64 {
        if t < self.start || t > self.end {
            return 0.0;
        }
        let r = self.taper.min(0.5 * (self.end - self.start));
        if r <= 0.0 {
            return 1.0;
        }
        let edge = (t - self.start).min(self.end - t);
        if edge >= r {
            1.0
        } else {
            0.5 * (1.0 - (PI * edge / r).cos())
        }
    }

    /// `x` (samples at `t0 + k dt`, s) gated in place.
    pub fn apply(&self, x: &mut [f64], t0: f64, dt: f64) {
        for (k, v) in x.iter_mut().enumerate() {
            *v *= self.weight(t0 + k as f64 * dt);
        }
    }

    /// The gate of `[start, end]` (taper a tenth of the gate) or `[start, end, taper]`,
    /// s, when it is valid ([`Gate::is_valid`]); `None` otherwise.
    pub fn from_values(v: &[f64]) -> Option<Gate> {
        let g = match *v {
            [start, end] => Gate {
                start,
                end,
                taper: 0.1 * (end - start),
            },
            [start, end, taper] => Gate { start, end, taper },
            _ => return None,
        };
        g.is_valid().then_some(g)
    }

    /// Whether the gate is a non-empty finite interval with a taper in `[0, (end -
    /// start) / 2]`.
    pub fn is_valid(&self) -> bool {
        self.start.is_finite()
            && self.end.is_finite()
            && self.end > self.start
            && self.taper >= 0.0
            && self.taper <= 0.5 * (self.end - self.start)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gate_keeps_its_window_and_ramps_continuously() {
        let g = Gate {
            start: 1.0,
            end: 3.0,
            taper: 0.5,
        };
        assert!(g.is_valid());
        assert_eq!(g.weight(0.999), 0.0);
        assert_eq!(g.weight(3.001), 0.0);
        assert_eq!(g.weight(2.0), 1.0);
        assert!((g.weight(1.25) - 0.5).abs() < 1e-15);
        assert!((g.weight(2.75) - 0.5).abs() < 1e-15);
        // continuous at the ends of the ramps
        assert!(g.weight(1.0).abs() < 1e-15 && (g.weight(1.5) - 1.0).abs() < 1e-15);
        let mut x = vec![1.0; 41];
        g.apply(&mut x, 0.0, 0.1);
        assert_eq!(x[5], 0.0);
        assert_eq!(x[20], 1.0);
        assert!(!Gate {
            start: 1.0,
            end: 1.0,
            taper: 0.0
        }
        .is_valid());
        assert!(!Gate {
            start: 0.0,
            end: 1.0,
            taper: 0.6
        }
        .is_valid());
    }
}

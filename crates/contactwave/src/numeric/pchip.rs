//! Monotone piecewise-cubic Hermite interpolation (Fritsch-Carlson, PCHIP): used by the
//! tabulated compression law (stiffness vs pressure) and by waveforms read from files.

/// A monotone cubic interpolant through `(x_i, y_i)`, `x` strictly increasing.
/// Outside `[x_0, x_n]` it is constant (the end values).
#[derive(Debug, Clone)]
pub struct Pchip {
    x: Vec<f64>,
    y: Vec<f64>,
    d: Vec<f64>,
}

impl Pchip {
    /// Build the interpolant; `x` must be strictly increasing, lengths equal and >= 2
    /// (checked by the caller's validation; violations give `None`).
    pub fn new(x: &[f64], y: &[f64]) -> Option<Pchip> {
        let n = x.len();
        if n < 2 || y.len() != n || x.windows(2).any(|w| !(w[1] > w[0])) {
            return None;
        }
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let delta: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let mut d = vec![0.0; n];
        if n == 2 {
            d[0] = delta[0];
            d[1] = delta[0];
        } else {
            for i in 1..n - 1 {
                if delta[i - 1] * delta[i] <= 0.0 {
                    d[i] = 0.0;
                } else {
                    let w1 = 2.0 * h[i] + h[i - 1];
                    let w2 = h[i] + 2.0 * h[i - 1];
                    d[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
                }
            }
            d[0] = end_slope(h[0], h[1], delta[0], delta[1]);
            d[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
        }
        Some(Pchip {
            x: x.to_vec(),
            y: y.to_vec(),
            d,
        })
    }

    /// Value at `t`.
    pub fn eval(&self, t: f64) -> f64 {
        let n = self.x.len();
        if t <= self.x[0] {
            return self.y[0];
        }
        if t >= self.x[n - 1] {
            return self.y[n - 1];
        }
        let i = self.x.partition_point(|&v| v <= t) - 1;
        let h = self.x[i + 1] - self.x[i];
        let s = (t - self.x[i]) / h;
        let (h00, h10, h01, h11) = (
            (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s),
            s * (1.0 - s) * (1.0 - s),
            s * s * (3.0 - 2.0 * s),
            s * s * (s - 1.0),
        );
        h00 * self.y[i] + h10 * h * self.d[i] + h01 * self.y[i + 1] + h11 * h * self.d[i + 1]
    }

    /// The abscissae (breakpoints of the interpolant).
    pub fn knots(&self) -> &[f64] {
        &self.x
    }

    /// Largest |y|.
    pub fn max_abs(&self) -> f64 {
        self.y.iter().fold(0.0f64, |m, v| m.max(v.abs()))
    }
}

fn end_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if d * d0 <= 0.0 {
        0.0
    } else if d0 * d1 <= 0.0 && d.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn interpolates_and_stays_monotone() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [0.0, 0.1, 0.2, 5.0, 5.1];
        let p = Pchip::new(&x, &y).unwrap();
        for (xi, yi) in x.iter().zip(y.iter()) {
            assert!((p.eval(*xi) - yi).abs() < 1e-14);
        }
        let mut prev = p.eval(0.0);
        for k in 1..=400 {
            let v = p.eval(k as f64 * 0.01);
            assert!(v >= prev - 1e-15);
            prev = v;
        }
    }
    #[test]
    fn reproduces_linear_data() {
        let x = [0.0, 0.5, 2.0, 3.0];
        let y: Vec<f64> = x.iter().map(|v| 2.0 * v + 1.0).collect();
        let p = Pchip::new(&x, &y).unwrap();
        assert!((p.eval(1.3) - 3.6).abs() < 1e-12);
    }
}

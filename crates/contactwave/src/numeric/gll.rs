//! Gauss-Lobatto-Legendre (GLL) points, weights and the Lagrange derivative matrix on
//! [-1, 1]: the nodes and quadrature of the spectral elements of the 2D solver (diagonal
//! mass: the quadrature points are the interpolation nodes).

/// GLL rule of order `n` (`n + 1` points, `1 <= n <= 16`).
#[derive(Debug, Clone, PartialEq)]
pub struct Gll {
    /// Order n (polynomial degree).
    pub order: usize,
    /// Points, increasing, from -1 to 1.
    pub points: Vec<f64>,
    /// Quadrature weights (sum 2; exact for degree `2n - 1`).
    pub weights: Vec<f64>,
    /// Derivative matrix, row-major: `d[i * (n + 1) + j] = l_j'(x_i)`, with `l_j` the
    /// Lagrange polynomial of point j.
    pub derivative: Vec<f64>,
}

/// Legendre polynomial P_n(x) and its derivative.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    // P_n' = n (x P_n - P_{n-1}) / (x^2 - 1), away from the ends
    let dp = if (x * x - 1.0).abs() < 1e-300 {
        0.5 * x.powi(n as i32 + 1) * (n * (n + 1)) as f64
    } else {
        n as f64 * (x * p1 - p0) / (x * x - 1.0)
    };
    (p1, dp)
}

impl Gll {
    /// The rule of order `n` (1 to 16; `None` outside).
    pub fn new(n: usize) -> Option<Gll> {
        if !(1..=16).contains(&n) {
            return None;
        }
        let m = n + 1;
        let mut x = vec![0.0; m];
        x[0] = -1.0;
        x[n] = 1.0;
        // interior points: roots of P_n', Newton from the Chebyshev-Gauss-Lobatto guess on
        // (1 - x^2) P_n'(x) = n (P_{n-1} - x P_n)
        for i in 1..n {
            let mut xi = -(std::f64::consts::PI * i as f64 / n as f64).cos();
            for _ in 0..100 {
                let (p, _) = legendre(n, xi);
                let (pm, _) = legendre(n - 1, xi);
                // f = P_{n-1} - x P_n (zero at the interior points), f' = -n P_n... use
                // f'(x) = P_{n-1}' - P_n - x P_n'
                let (_, dpm) = legendre(n - 1, xi);
                let (_, dp) = legendre(n, xi);
                let f = pm - xi * p;
                let df = dpm - p - xi * dp;
                let step = f / df;
                xi -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = xi;
        }
        // symmetrise
        for i in 0..m / 2 {
            let a = 0.5 * (x[n - i] - x[i]);
            x[i] = -a;
            x[n - i] = a;
        }
        if m % 2 == 1 {
            x[n / 2] = 0.0;
        }
        let nn = (n * (n + 1)) as f64;
        let pn: Vec<f64> = x.iter().map(|&xi| legendre(n, xi).0).collect();
        let weights: Vec<f64> = pn.iter().map(|p| 2.0 / (nn * p * p)).collect();
        let mut d = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                d[i * m + j] = if i != j {
                    pn[i] / (pn[j] * (x[i] - x[j]))
                } else if i == 0 {
                    -nn / 4.0
                } else if i == n {
                    nn / 4.0
                } else {
                    0.0
                };
            }
        }
        Some(Gll {
            order: n,
            points: x,
            weights,
            derivative: d,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Known order-4 rule; quadrature exact to degree 2n - 1; the derivative matrix
    /// differentiates polynomials of degree n exactly.
    #[test]
    fn order_4_rule_and_exactness() {
        let g = Gll::new(4).unwrap();
        let s = (3.0f64 / 7.0).sqrt();
        for (a, b) in g.points.iter().zip([-1.0, -s, 0.0, s, 1.0]) {
            assert!((a - b).abs() < 1e-15, "{a} {b}");
        }
        for (a, b) in g
            .weights
            .iter()
            .zip([0.1, 49.0 / 90.0, 32.0 / 45.0, 49.0 / 90.0, 0.1])
        {
            assert!((a - b).abs() < 1e-15, "{a} {b}");
        }
        for n in 1..=12 {
            let g = Gll::new(n).unwrap();
            let m = n + 1;
            for deg in 0..2 * n {
                let q: f64 = g
                    .points
                    .iter()
                    .zip(&g.weights)
                    .map(|(x, w)| w * x.powi(deg as i32))
                    .sum();
                let exact = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg + 1) as f64
                };
                assert!((q - exact).abs() < 1e-13, "n {n} degree {deg}: {q} {exact}");
            }
            // d/dx x^n = n x^(n-1)
            for i in 0..m {
                let d: f64 = (0..m)
                    .map(|j| g.derivative[i * m + j] * g.points[j].powi(n as i32))
                    .sum();
                let exact = n as f64 * g.points[i].powi(n as i32 - 1);
                assert!(
                    (d - exact).abs() < 1e-11 * (n * n) as f64,
                    "n {n} i {i}: {d} {exact}"
                );
            }
        }
        assert!(Gll::new(0).is_none() && Gll::new(17).is_none());
    }
}

//! The grid of a sweep: evenly spaced axis values ([`linspace`], [`logspace`]) and the
//! cartesian product of the axes ([`grid`]), first axis slowest.
//!
//! Pure functions of numbers: nothing here knows the sweep file, the scenario or the CSV.

/// `n` evenly spaced values from `a` to `b` inclusive (`[a]` for `n = 1`, empty for 0).
/// The end points are exact.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![a],
        _ => (0..n)
            .map(|i| {
                if i == n - 1 {
                    b
                } else {
                    a + (b - a) * i as f64 / (n - 1) as f64
                }
            })
            .collect(),
    }
}

/// `n` values `10^e`, `e` evenly spaced from `a` to `b` inclusive. Integer exponents give
/// exact powers of ten (`logspace(9, 16, 8)` is exactly `1e9, 1e10, ..., 1e16`).
pub fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    linspace(a, b, n)
        .into_iter()
        .map(|e| {
            if e.fract() == 0.0 && e.abs() <= 308.0 {
                // exact decimal power of ten (powi accumulates rounding errors)
                format!("1e{}", e as i64).parse().unwrap_or(10f64.powf(e))
            } else {
                10f64.powf(e)
            }
        })
        .collect()
}

/// Cartesian product of axis values, first axis slowest: `grid(&[[1,2],[a,b]])` is
/// `[1,a], [1,b], [2,a], [2,b]`. No axes give one empty point.
pub fn grid(axes: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut points: Vec<Vec<f64>> = vec![vec![]];
    for values in axes {
        let mut next = Vec::with_capacity(points.len() * values.len());
        for p in &points {
            for &v in values {
                let mut q = p.clone();
                q.push(v);
                next.push(q);
            }
        }
        points = next;
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linspace_and_logspace_endpoints() {
        let v = linspace(0.05, 1.2, 47);
        assert_eq!(v.len(), 47);
        assert_eq!(v[0], 0.05);
        assert_eq!(v[46], 1.2);
        assert_eq!(linspace(2.0, 3.0, 1), vec![2.0]);
        let l = logspace(9.0, 16.0, 8);
        assert_eq!(l, vec![1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16]);
        let l = logspace(0.0, 1.0, 3);
        assert_eq!(l[0], 1.0);
        assert!((l[1] - 10f64.sqrt()).abs() < 1e-12);
        assert_eq!(l[2], 10.0);
    }

    #[test]
    fn grid_first_axis_slowest() {
        let g = grid(&[vec![1.0, 2.0], vec![10.0, 20.0, 30.0]]);
        assert_eq!(
            g,
            vec![
                vec![1.0, 10.0],
                vec![1.0, 20.0],
                vec![1.0, 30.0],
                vec![2.0, 10.0],
                vec![2.0, 20.0],
                vec![2.0, 30.0]
            ]
        );
    }
}

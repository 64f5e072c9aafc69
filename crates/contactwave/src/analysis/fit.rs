//! Stiffness-pressure laws from data: least-squares fit of `K = C p^m` in log-log
//! (thesis eq. 4.4; C = 1.81e10, m = 0.35 for the Al-Al data of Table 2).

use crate::error::{Error, Result};

/// A power-law fit `K = C p^m`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PowerLawFit {
    /// C, Pa^(1-m)/m.
    pub c: f64,
    /// m.
    pub m: f64,
    /// Coefficient of determination of the log-log regression.
    pub r2: f64,
}

/// Fit `K = C p^m` by least squares on `(ln p, ln K)`. Pressures in Pa, stiffnesses in
/// Pa/m, all > 0, at least 2 points with two distinct pressures.
///
/// ```
/// use contactwave::analysis::fit::fit_power_law;
/// // K = C p^m with the Al-Al values of thesis Table 2 (C = 1.81e10 Pa^(1-m)/m, m = 0.35),
/// // at 0.1 ... 12.8 MPa, with alternating +-2 % deviations
/// let p: Vec<f64> = (0..8).map(|i| 0.1e6 * 2f64.powi(i)).collect();
/// let k: Vec<f64> = p
///     .iter()
///     .enumerate()
///     .map(|(i, p)| 1.81e10 * p.powf(0.35) * if i % 2 == 0 { 1.02 } else { 0.98 })
///     .collect();
/// let fit = fit_power_law(&p, &k).unwrap();
/// assert!((fit.m - 0.35).abs() < 0.01);
/// assert!((fit.c / 1.81e10 - 1.0).abs() < 0.05);
/// assert!(fit.r2 > 0.99);
/// // exact data are recovered exactly
/// let exact: Vec<f64> = p.iter().map(|p| 1.81e10 * p.powf(0.35)).collect();
/// let fit = fit_power_law(&p, &exact).unwrap();
/// assert!((fit.m - 0.35).abs() < 1e-12 && (fit.c / 1.81e10 - 1.0).abs() < 1e-9);
/// // a single point, or a stiffness <= 0, is an error
/// assert!(fit_power_law(&[1e6], &[1e12]).is_err());
/// assert!(fit_power_law(&[1e6, 2e6], &[1e12, 0.0]).is_err());
/// ```
pub fn fit_power_law(pressure: &[f64], stiffness: &[f64]) -> Result<PowerLawFit> {
    if pressure.len() != stiffness.len() {
        return Err(Error::invalid(
            "<data>",
            "pressure, stiffness",
            format!(
                "{} pressures, {} stiffnesses",
                pressure.len(),
                stiffness.len()
            ),
            "give one stiffness per pressure (the two lists must have the same length)",
        ));
    }
    if pressure.len() < 2 {
        return Err(Error::invalid(
            "<data>",
            "pressure",
            format!("{} points", pressure.len()),
            "need at least 2 (pressure, stiffness) pairs",
        ));
    }
    for (i, (&p, &k)) in pressure.iter().zip(stiffness).enumerate() {
        if !(p > 0.0 && p.is_finite()) {
            return Err(Error::invalid(
                "<data>",
                format!("pressure.{i}"),
                p,
                "must be a finite number > 0 (Pa)",
            ));
        }
        if !(k > 0.0 && k.is_finite()) {
            return Err(Error::invalid(
                "<data>",
                format!("stiffness.{i}"),
                k,
                "must be a finite number > 0 (Pa/m)",
            ));
        }
    }
    let n = pressure.len() as f64;
    let x: Vec<f64> = pressure.iter().map(|p| p.ln()).collect();
    let y: Vec<f64> = stiffness.iter().map(|k| k.ln()).collect();
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let syy: f64 = y.iter().map(|v| (v - my).powi(2)).sum();
    if !(sxx > 0.0) {
        return Err(Error::invalid(
            "<data>",
            "pressure",
            "all equal",
            "need at least two distinct pressures",
        ));
    }
    let m = sxy / sxx;
    let c = (my - m * mx).exp();
    let r2 = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        1.0
    };
    Ok(PowerLawFit { c, m, r2 })
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn recovers_exact_power_law() {
        let p = [1e5, 2e5, 5e5, 1e6];
        let k: Vec<f64> = p.iter().map(|v: &f64| 2e10 * v.powf(0.4)).collect();
        let f = fit_power_law(&p, &k).unwrap();
        assert!((f.c / 2e10 - 1.0).abs() < 1e-9 && (f.m - 0.4).abs() < 1e-12 && f.r2 > 1.0 - 1e-12);
    }
    #[test]
    fn a_length_mismatch_says_so() {
        // three pressures, two stiffnesses: the lengths differ (there are 2 pairs and more)
        let e = fit_power_law(&[1.0, 2.0, 3.0], &[1.0, 2.0])
            .unwrap_err()
            .to_string();
        assert!(e.contains("3 pressures, 2 stiffnesses"), "{e}");
        assert!(e.contains("same length"), "{e}");
        assert!(!e.contains("at least 2"), "{e}");
        let e = fit_power_law(&[1.0], &[1.0]).unwrap_err().to_string();
        assert!(e.contains("at least 2"), "{e}");
    }
}

//! Validation cases of `contactwave validate`: each computes one number with the public
//! API and compares it with a reference (analytical, or a published finding of the thesis,
//! model.md section 7).

use crate::error::Result;
use crate::scenario::Scenario;
use rayon::prelude::*;

/// One validation case.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidationCase {
    /// Short description.
    pub name: String,
    /// Reference value.
    pub reference: f64,
    /// Value computed by contactwave.
    pub computed: f64,
    /// `|computed - reference| / |reference|` (absolute error if the reference is 0).
    pub rel_error: f64,
    /// Largest `rel_error` accepted.
    pub tolerance: f64,
}

impl ValidationCase {
    /// A case from its reference, computed value and tolerance.
    pub fn new(name: impl Into<String>, reference: f64, computed: f64, tolerance: f64) -> Self {
        let err = (computed - reference).abs();
        let rel_error = if reference != 0.0 {
            err / reference.abs()
        } else {
            err
        };
        ValidationCase {
            name: name.into(),
            reference,
            computed,
            rel_error,
            tolerance,
        }
    }

    /// Whether the relative error is within the tolerance (NaN fails).
    pub fn passed(&self) -> bool {
        self.rel_error <= self.tolerance
    }
}

/// Unilateral contact (rigid compression, free traction) on PMMA, p0 = 0.1 MPa, 1 MHz,
/// 15 cycles, probe at -0.03 m: the `A2/A_inc` maximum over xi in [0.2, 0.5] (step 0.01)
/// sits at xi ~ 0.35 (thesis chapter 3).
pub fn unilateral_a2_peak() -> Result<ValidationCase> {
    let xis: Vec<f64> = (20..=50).map(|k| k as f64 / 100.0).collect();
    let a2: Vec<f64> = xis
        .par_iter()
        .map(|xi| {
            let s = Scenario::from_toml_str(
                &format!(
                    r#"
                    [medium]
                    material = "pmma"
                    [interface]
                    static_pressure = 0.1e6
                    [incident]
                    frequency = 1e6
                    cycles = 15
                    xi = {xi:?}
                    "#
                ),
                "<validation: unilateral xi sweep>",
            )?;
            let summary = crate::simulate_summary(&s)?;
            Ok(summary.get("A2_over_Ainc").unwrap_or(f64::NAN))
        })
        .collect::<Result<Vec<f64>>>()?;
    let (k, _) = a2
        .iter()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |(kb, vb), (k, &v)| {
            if v > vb {
                (k, v)
            } else {
                (kb, vb)
            }
        });
    Ok(ValidationCase::new(
        "unilateral contact: xi of max A2/A_inc (thesis ch. 3)",
        0.35,
        xis[k],
        0.03,
    ))
}

/// Bonded interface against a rigid wall: the reflected stress equals the incident stress,
/// `max|s_ref| / max|s_inc| = 1`.
pub fn bonded_rigid_wall() -> Result<ValidationCase> {
    let s = Scenario::from_toml_str(
        r#"
        [medium]
        material = "pmma"
        [interface]
        static_pressure = 0.1e6
        traction = { law = "bonded" }
        [incident]
        frequency = 1e6
        cycles = 15
        amplitude = 1e6
        "#,
        "<validation: bonded rigid wall>",
    )?;
    let r = crate::simulate(&s)?;
    let peak = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let ratio = peak(&r.interface.reflected_stress) / peak(&r.interface.incident_stress);
    Ok(ValidationCase::new(
        "bonded rigid wall: max|s_ref| / max|s_inc|",
        1.0,
        ratio,
        1e-9,
    ))
}

/// Run every validation case.
pub fn run_all() -> Result<Vec<ValidationCase>> {
    Ok(vec![unilateral_a2_peak()?, bonded_rigid_wall()?])
}

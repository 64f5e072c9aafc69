//! The normal half of the contact update (thesis eqs. 2.23-2.37): given the predicted gap `g~` the two interface nodes would reach with no
//! interface force, and the compliance `chi` (gap change per unit dynamic stress), find the
//! gap `g` and the dynamic stress `S = sigma + p0` with
//!
//! ```text
//! g = g~ - chi S,    S = sigma(g, beta_new) + p0
//! ```
//!
//! exactly (to machine precision): Signorini with no penetration and no penalty, bonded
//! locking, compliant branches by a bracketing root-finder on the monotone function
//! `F(g) = S(g) + (g - g~)/chi` (safeguarded secant/bisection; never fails silently), and
//! damage by the law's unconditionally stable backward-Euler update inside `S(g)`.

use crate::error::{Error, Result};
use crate::law::{CompressionBranch, NormalPart, TractionBranch, WarmStart};
use crate::numeric::root::brent_past;

/// Result of one interface update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceUpdate {
    /// Gap `[u]`, m.
    pub gap: f64,
    /// Dynamic interface stress S = sigma + p0, Pa.
    pub dynamic_stress: f64,
    /// Adhesion beta after the step.
    pub adhesion: f64,
}

/// Stress of the law at gap `g` with adhesion updated from `beta_old` over `dt`.
fn s_of<N: NormalPart + ?Sized>(law: &N, g: f64, beta_old: f64, dt: f64) -> (f64, f64) {
    let uc = law.critical_gap();
    let p0 = law.static_pressure();
    if g <= uc {
        (law.compression().stress(g) + p0, beta_old)
    } else {
        let d = g - uc;
        let b = law.traction().update_adhesion(d, beta_old, dt);
        (law.traction().stress(d, b) + p0, b)
    }
}

/// Solve the interface update. With `warm` (what the previous updates of this interface
/// left), a compression branch with a solver of its own
/// ([`crate::law::CompressionBranch::solve_compressed`]) uses it; without, the Newton
/// iteration on the gap below. `t` is only used in error messages.
pub fn update<N: NormalPart + ?Sized>(
    law: &N,
    predicted_gap: f64,
    chi: f64,
    beta_old: f64,
    warm: Option<&mut WarmStart>,
    dt: f64,
    t: f64,
) -> Result<InterfaceUpdate> {
    let uc = law.critical_gap();
    let p0 = law.static_pressure();
    let gt = predicted_gap;
    let c_rigid = law.compression().is_rigid();
    let t_rigid = law.traction().is_rigid();
    // Where does the solution lie? F(uc) = p0 + (uc - g~)/chi: >= 0 -> compression side.
    let f_uc = p0 + (uc - gt) / chi;
    if f_uc >= 0.0 {
        if c_rigid {
            // closed: g = 0, S = g~/chi (sigma = S - p0 <= 0)
            return Ok(InterfaceUpdate {
                gap: 0.0,
                dynamic_stress: (gt - 0.0) / chi,
                adhesion: beta_old,
            });
        }
        let f = |g: f64| law.compression().stress(g) + p0 + (g - gt) / chi;
        if f_uc == 0.0 {
            return Ok(InterfaceUpdate {
                gap: uc,
                dynamic_stress: p0,
                adhesion: beta_old,
            });
        }
        // sigma(g) + (g - q)/chi = 0 with q = g~ - chi p0
        let own = warm.and_then(|w| law.compression().solve_compressed(gt - chi * p0, chi, w));
        if let Some(g) = own.filter(|g| *g <= uc) {
            return Ok(InterfaceUpdate {
                gap: g,
                dynamic_stress: (gt - g) / chi,
                adhesion: beta_old,
            });
        }
        // safeguarded Newton (thesis eq. 2.31) on F(g) = sigma(g) + p0 + (g - g~)/chi,
        // F' = K(g) + 1/chi > 0, from the guess S = p0 (the preload dominates the dynamic
        // stress); the root lies below uc. One law evaluation per iteration; the bracket
        // [a, b] tightens with each sign of F. Falls back to a bracketing root-finder if an
        // iterate leaves the bracket or the iteration stalls.
        let (mut a, mut b) = (f64::NEG_INFINITY, uc);
        let mut g = (gt - chi * p0).min(uc);
        let mut done = false;
        for _ in 0..40 {
            let (sigma, k) = law.compression().stress_tangent(g);
            let fg = sigma + p0 + (g - gt) / chi;
            // zero within the round-off of its terms: converged
            if fg.abs() <= 8.0 * f64::EPSILON * (p0 + sigma.abs() + ((g - gt) / chi).abs()) {
                done = true;
                break;
            }
            if fg < 0.0 {
                a = g;
            } else {
                b = g;
            }
            let ng = g - fg / (k + 1.0 / chi);
            if !(ng > a && ng < b) {
                break;
            }
            if (ng - g).abs() <= 4.0 * f64::EPSILON * g.abs().max(uc.abs()) {
                g = ng;
                done = true;
                break;
            }
            g = ng;
        }
        let g = if done {
            g
        } else {
            // a finite bracket below uc (step doubling), then the root-finder
            if !a.is_finite() {
                let mut step = (uc.abs() + (gt - uc).abs()).max(1e-15);
                a = uc - step;
                let mut k = 0;
                while f(a) > 0.0 {
                    step *= 2.0;
                    a = uc - step;
                    k += 1;
                    if k > 200 || !f(a).is_finite() {
                        return Err(Error::numerical(
                            t,
                            "cannot bracket the compression interface update",
                            format!("predicted gap = {gt:e} m"),
                        ));
                    }
                }
            }
            let (fa, fb) = (f(a), f(b));
            if fb == 0.0 {
                b
            } else {
                brent_past(f, a, b, fa.min(-f64::MIN_POSITIVE), fb, 300).ok_or_else(|| {
                    Error::numerical(
                        t,
                        "interface update (compression) failed",
                        format!("predicted gap = {gt:e} m"),
                    )
                })?
            }
        };
        return Ok(InterfaceUpdate {
            gap: g,
            dynamic_stress: (gt - g) / chi,
            adhesion: beta_old,
        });
    }
    // traction side
    if t_rigid {
        return Ok(InterfaceUpdate {
            gap: uc,
            dynamic_stress: (gt - uc) / chi,
            adhesion: beta_old,
        });
    }
    // F(uc) < 0; F(g~) = S(g~) >= 0 since S >= p0 >= 0 in traction
    traction_side(
        gt,
        chi,
        uc,
        f_uc,
        |g| s_of(law, g, beta_old, dt),
        || {
            Error::numerical(
                t,
                "interface update (traction) failed",
                format!("predicted gap = {gt:e} m, beta = {beta_old}"),
            )
        },
    )
}

/// The update on the traction side, `g >= uc` (m): the root of `F(g) = S(g) + (g - g~)/chi`
/// bracketed by `F(uc) = f_uc < 0` and `F(max(g~, uc))`, where `s_of(g)` gives the dynamic
/// stress `S` (Pa) and the adhesion of the new level at the gap `g`; `fail` is the error
/// when the root-finder fails. The normal law alone and the law whose damage the
/// tangential gap drives too ([`super::normal_update`]) differ only in `s_of`.
pub(super) fn traction_side(
    gt: f64,
    chi: f64,
    uc: f64,
    f_uc: f64,
    s_of: impl Fn(f64) -> (f64, f64),
    fail: impl FnOnce() -> Error,
) -> Result<InterfaceUpdate> {
    let f = |g: f64| s_of(g).0 + (g - gt) / chi;
    let hi = gt.max(uc);
    let fhi = f(hi);
    if fhi <= 0.0 {
        let (s, b) = s_of(hi);
        return Ok(InterfaceUpdate {
            gap: hi,
            dynamic_stress: s,
            adhesion: b,
        });
    }
    let g = brent_past(f, uc, hi, f_uc, fhi, 300).ok_or_else(fail)?;
    let (_s, b) = s_of(g);
    Ok(InterfaceUpdate {
        gap: g,
        dynamic_stress: (gt - g) / chi,
        adhesion: b,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::compression::modified_power::{ModifiedPower, ModifiedPowerStiffness};
    use crate::law::compression::StiffnessCurve;
    use crate::law::traction::Free;
    use crate::law::ContactLaw;

    /// The pressure iteration of a stiffness-curve branch, warm-started along a history of
    /// predictions (a slow oscillation through both branches of the modified power law,
    /// then jumps: a large compression, near contact loss, far beyond the tabulated
    /// pressures), gives the update of the Newton iteration on the gap: the same gap and
    /// stress to round-off, the law holds at the result, and the tangent read at the
    /// stress is the one at the gap.
    #[test]
    fn warm_started_curve_solve_matches_gap_newton() {
        let p0 = 0.137e6;
        let k = ModifiedPowerStiffness::new(1.81e10, 0.35, 0.2e6, 0.2);
        let curve: ModifiedPower = StiffnessCurve::new(k, p0, "modified_power");
        let law = ContactLaw {
            static_pressure: p0,
            compression: Box::new(curve),
            traction: Box::new(Free),
        };
        let uc = law.critical_gap();
        let chi = 1e-13;
        let mut warm = WarmStart::default();
        let mut gaps: Vec<f64> = (0..2000)
            .map(|i| -1.2 * uc * (i as f64 * 0.01).sin())
            .collect();
        gaps.extend([-50.0 * uc, 0.999 * uc, -1e6 * uc, 0.3 * uc, -0.3 * uc]);
        let (mut max_dev, mut compressed) = (0.0f64, 0);
        for gt in gaps {
            let fast = update(&law, gt, chi, 1.0, Some(&mut warm), 0.0, 0.0).unwrap();
            let slow = update(&law, gt, chi, 1.0, None, 0.0, 0.0).unwrap();
            let s = slow.dynamic_stress;
            let scale = p0 + s.abs();
            if fast.gap <= uc {
                // the law's stress at the gap is S - p0 (and g = g~ - chi S by construction)
                let law_s = law.compression.stress(fast.gap) + p0;
                assert!(
                    (fast.dynamic_stress - law_s).abs() <= 1e-12 * scale,
                    "{gt:e}"
                );
                // the tangent read at the recorded stress is the one at the gap
                let (kt, kg) = (
                    law.compression
                        .tangent_at(fast.gap, fast.dynamic_stress - p0),
                    law.compression.tangent(fast.gap),
                );
                assert!((kt - kg).abs() <= 1e-12 * kg, "{gt:e}: {kt:e} {kg:e}");
                compressed += 1;
            }
            max_dev = max_dev.max((fast.dynamic_stress - s).abs() / scale);
        }
        assert!(max_dev < 1e-13, "largest relative deviation {max_dev:e}");
        assert!(compressed > 1000);
        // the branch's own solver ran (it leaves its points)
        assert_eq!(warm.len, 2);
    }
}

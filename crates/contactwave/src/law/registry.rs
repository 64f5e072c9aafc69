//! Where the law tables meet the interface: whole contact laws built from a scenario's
//! specs. Each law registers itself in its kind's table (`compression/mod.rs`,
//! `traction/mod.rs`, `tangential/mod.rs`); nothing here names a law, except the checks
//! that tie a tangential branch to the normal law (the full RCCM branch needs the RCCM
//! traction branch).

use super::param::non_negative;
use super::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use super::{ContactLaw, TangentialLaw};
use crate::error::{Error, Result};

/// Build a whole contact law for static pressure `p0` (Pa, >= 0), validating every
/// parameter; `prefix` is the dotted key of the interface (for messages), e.g.
/// `interface`. See [`ContactLaw::curve`] for the law it returns.
///
/// ```
/// use contactwave::law::registry::build_law;
/// use contactwave::law::spec::{CompressionSpec, TractionSpec};
/// let law = build_law(0.1e6, &CompressionSpec::Rigid(Default::default()), &TractionSpec::Free(Default::default()), "<doc>", "interface")
///     .unwrap();
/// assert_eq!(law.critical_gap(), 0.0); // Signorini: contact is lost at [u] = 0
/// assert!(law.compression.stiffness_at_rest().is_infinite());
/// // an invalid parameter is an error naming its dotted key
/// let err = build_law(
///     0.1e6,
///     &CompressionSpec::Linear(contactwave::law::compression::linear::Spec { stiffness: -1.0 }),
///     &TractionSpec::Free(Default::default()),
///     "<doc>",
///     "interface",
/// )
/// .unwrap_err();
/// assert!(err.to_string().contains("interface.compression.stiffness"));
/// ```
pub fn build_law(
    p0: f64,
    compression: &CompressionSpec,
    traction: &TractionSpec,
    file: &str,
    prefix: &str,
) -> Result<ContactLaw> {
    non_negative(file, &format!("{prefix}.static_pressure"), p0)?;
    Ok(ContactLaw {
        static_pressure: p0,
        compression: compression.build(p0, file, &format!("{prefix}.compression"))?,
        traction: traction.build(p0, file, &format!("{prefix}.traction"))?,
    })
}

/// Build the tangential part of a law for static shear `q0` (Pa), checking it against the
/// normal law `normal` (static pressure `p0`): the full RCCM branch needs the RCCM
/// traction branch, and the static shear must be carried at rest (by the slider:
/// `|q0| <= mu p0`; by a spring alone: any value; free sliding: none). `prefix` is the interface's dotted key.
///
/// ```
/// use contactwave::law::registry::{build_law, build_tangential};
/// use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
/// let normal = build_law(10e6, &CompressionSpec::Rigid(Default::default()), &TractionSpec::Free(Default::default()), "<doc>", "interface")
///     .unwrap();
/// use contactwave::law::tangential::coulomb;
/// let coulomb = TangentialSpec::Coulomb(coulomb::Spec { friction: 0.3, stiffness: None });
/// let t = build_tangential(&coulomb, 1e6, &normal, "<doc>", "interface").unwrap();
/// assert_eq!(t.friction_limit(10e6, 0.0), 3e6); // mu N (no slip path yet)
/// // a static shear above mu p0 cannot be carried at rest
/// let err = build_tangential(&coulomb, 4e6, &normal, "<doc>", "interface").unwrap_err();
/// assert!(err.to_string().contains("interface.static_shear"));
/// ```
pub fn build_tangential(
    spec: &TangentialSpec,
    q0: f64,
    normal: &ContactLaw,
    file: &str,
    prefix: &str,
) -> Result<TangentialLaw> {
    let branch_key = format!("{prefix}.tangential");
    let branch = spec.build(normal.static_pressure, file, &branch_key)?;
    if !q0.is_finite() {
        return Err(Error::invalid(
            file,
            format!("{prefix}.static_shear"),
            q0,
            "must be finite",
        ));
    }
    if branch.needs_adhesion() && !normal.traction.has_damage() {
        return Err(Error::invalid(
            file,
            format!("{branch_key}.law"),
            branch.name(),
            format!(
                "the full RCCM tangential branch takes its adhesion from the RCCM traction \
                 branch; set {prefix}.traction.law = \"rccm\" (now \"{}\")",
                normal.traction.name()
            ),
        ));
    }
    let mu = branch.friction();
    if q0 != 0.0 {
        // (+ 0.0: no "-0" for a pressure of -0)
        let limit = mu * normal.static_pressure + 0.0;
        let spring = branch.spring_stiffness(1.0) > 0.0;
        if (mu > 0.0 || !spring) && q0.abs() > limit {
            let limit = if limit == 0.0 {
                format!(
                    "0 Pa (friction coefficient {mu}, static pressure {} Pa)",
                    normal.static_pressure + 0.0
                )
            } else {
                format!("{limit:e} Pa (friction coefficient times the static pressure)")
            };
            return Err(Error::invalid(
                file,
                format!("{prefix}.static_shear"),
                q0,
                format!("|q0| must be <= mu p0 = {limit} for the interface to stick at rest"),
            ));
        }
    }
    Ok(TangentialLaw {
        static_shear: q0,
        branch,
    })
}

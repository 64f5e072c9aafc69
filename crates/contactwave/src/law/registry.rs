//! Where law names meet law types: scenario specs become boxed branches. Adding a
//! compression or traction law = one new file in `compression/` or `traction/` + one match
//! arm here (and its spec variant and parameter names); a tangential law registers itself
//! in the table of `tangential/mod.rs`.

use super::compression::{self, ModifiedPower, StiffnessCurve};
use super::param::{non_negative, positive};
use super::spec::{CompressionSpec, TangentialSpec, TractionSpec};
use super::traction;
use super::{CompressionBranch, ContactLaw, TangentialBranch, TangentialLaw, TractionBranch};
use crate::error::{Error, Result};

fn exponent(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 && v < 1.0 {
        Ok(())
    } else {
        Err(Error::invalid(file, field, v, "must lie in (0, 1)"))
    }
}

/// Build a compression branch for static pressure `p0` (Pa), validating its parameters.
/// `prefix` is the dotted key of the spec (for messages), e.g. `interface.compression`.
pub fn build_compression(
    spec: &CompressionSpec,
    p0: f64,
    file: &str,
    prefix: &str,
) -> Result<Box<dyn CompressionBranch>> {
    let key = |k: &str| format!("{prefix}.{k}");
    Ok(match spec {
        CompressionSpec::Rigid => Box::new(compression::Rigid {
            static_pressure: p0,
        }),
        CompressionSpec::Linear { stiffness } => {
            positive(file, &key("stiffness"), *stiffness)?;
            Box::new(compression::Linear {
                static_pressure: p0,
                stiffness: *stiffness,
            })
        }
        CompressionSpec::Quadratic { k0, k1 } => {
            positive(file, &key("k0"), *k0)?;
            if !k1.is_finite() {
                return Err(Error::invalid(file, key("k1"), k1, "must be finite"));
            }
            Box::new(compression::Quadratic::new(p0, *k0, *k1).ok_or_else(|| {
                Error::invalid(
                    file,
                    key("k1"),
                    k1,
                    format!(
                        "must be <= k0^2 / (4 p0) = {:e} so that the stress reaches zero",
                        k0 * k0 / (4.0 * p0)
                    ),
                )
            })?)
        }
        CompressionSpec::Power { c, m } => {
            positive(file, &key("c"), *c)?;
            exponent(file, &key("m"), *m)?;
            Box::new(compression::Power {
                static_pressure: p0,
                c: *c,
                m: *m,
            })
        }
        CompressionSpec::ModifiedPower {
            c,
            m,
            transition_pressure,
            zero_pressure_fraction,
        } => {
            positive(file, &key("c"), *c)?;
            exponent(file, &key("m"), *m)?;
            positive(file, &key("transition_pressure"), *transition_pressure)?;
            exponent(
                file,
                &key("zero_pressure_fraction"),
                *zero_pressure_fraction,
            )?;
            let k = compression::modified_power::ModifiedPowerStiffness::new(
                *c,
                *m,
                *transition_pressure,
                *zero_pressure_fraction,
            );
            let b: ModifiedPower = StiffnessCurve::new(k, p0, "modified_power");
            Box::new(b)
        }
        CompressionSpec::Table {
            pressure,
            stiffness,
        } => {
            if pressure.len() < 2 || pressure.len() != stiffness.len() {
                return Err(Error::invalid(
                    file,
                    key("pressure"),
                    format!("{} values (stiffness: {})", pressure.len(), stiffness.len()),
                    "pressure and stiffness need the same length, at least 2",
                ));
            }
            for (i, p) in pressure.iter().enumerate() {
                non_negative(file, &format!("{}[{i}]", key("pressure")), *p)?;
                if i > 0 && !(*p > pressure[i - 1]) {
                    return Err(Error::invalid(
                        file,
                        format!("{}[{i}]", key("pressure")),
                        p,
                        "pressures must be strictly increasing",
                    ));
                }
            }
            for (i, k) in stiffness.iter().enumerate() {
                positive(file, &format!("{}[{i}]", key("stiffness")), *k)?;
            }
            let t = compression::table::TableStiffness::new(pressure, stiffness)
                .ok_or_else(|| Error::invalid(file, key("pressure"), "table", "invalid table"))?;
            Box::new(StiffnessCurve::new(t, p0, "table"))
        }
    })
}

/// Build a traction branch, validating its parameters.
pub fn build_traction(
    spec: &TractionSpec,
    file: &str,
    prefix: &str,
) -> Result<Box<dyn TractionBranch>> {
    let key = |k: &str| format!("{prefix}.{k}");
    Ok(match spec {
        TractionSpec::Free => Box::new(traction::Free),
        TractionSpec::Linear { stiffness } => {
            positive(file, &key("stiffness"), *stiffness)?;
            Box::new(traction::Linear {
                stiffness: *stiffness,
            })
        }
        TractionSpec::Rccm {
            stiffness,
            energy,
            viscosity,
        } => {
            positive(file, &key("stiffness"), *stiffness)?;
            non_negative(file, &key("energy"), *energy)?;
            non_negative(file, &key("viscosity"), *viscosity)?;
            Box::new(traction::Rccm {
                stiffness: *stiffness,
                energy: *energy,
                viscosity: *viscosity,
            })
        }
        TractionSpec::Bonded => Box::new(traction::Bonded),
    })
}

/// Build a whole contact law for static pressure `p0` (Pa, >= 0), validating every
/// parameter; `prefix` is the dotted key of the interface (for messages), e.g.
/// `interface`. See [`ContactLaw::curve`] for the law it returns.
///
/// ```
/// use contactwave::law::registry::build_law;
/// use contactwave::law::spec::{CompressionSpec, TractionSpec};
/// let law = build_law(0.1e6, &CompressionSpec::Rigid, &TractionSpec::Free, "<doc>", "interface")
///     .unwrap();
/// assert_eq!(law.critical_gap(), 0.0); // Signorini: contact is lost at [u] = 0
/// assert!(law.compression.stiffness_at_rest().is_infinite());
/// // an invalid parameter is an error naming its dotted key
/// let err = build_law(
///     0.1e6,
///     &CompressionSpec::Linear { stiffness: -1.0 },
///     &TractionSpec::Free,
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
        compression: build_compression(compression, p0, file, &format!("{prefix}.compression"))?,
        traction: build_traction(traction, file, &format!("{prefix}.traction"))?,
    })
}

/// Build a tangential branch, validating its parameters (each law's own
/// [`crate::law::tangential::TangentialLawSpec::build`]).
pub fn build_tangential_branch(
    spec: &TangentialSpec,
    file: &str,
    prefix: &str,
) -> Result<Box<dyn TangentialBranch>> {
    spec.build(file, prefix)
}

/// Build the tangential part of a law for static shear `q0` (Pa), checking it against the
/// normal law `normal` (static pressure `p0`): the full RCCM branch needs the RCCM
/// traction branch, and the static shear must be carried at rest (by the slider:
/// `|q0| <= mu p0`; by a spring alone: any value; free sliding: none). `prefix` is the interface's dotted key.
///
/// ```
/// use contactwave::law::registry::{build_law, build_tangential};
/// use contactwave::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};
/// let normal = build_law(10e6, &CompressionSpec::Rigid, &TractionSpec::Free, "<doc>", "interface")
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
    let branch = build_tangential_branch(spec, file, &branch_key)?;
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
        let limit = mu * normal.static_pressure;
        let spring = branch.spring_stiffness(1.0) > 0.0;
        if (mu > 0.0 || !spring) && q0.abs() > limit {
            return Err(Error::invalid(
                file,
                format!("{prefix}.static_shear"),
                q0,
                format!(
                    "|q0| must be <= mu p0 = {limit:e} Pa (friction coefficient times the \
                     static pressure) for the interface to stick at rest"
                ),
            ));
        }
    }
    Ok(TangentialLaw {
        static_shear: q0,
        branch,
    })
}

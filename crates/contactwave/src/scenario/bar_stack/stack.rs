//! Validation steps that build the stack: the model keys, the segments and their
//! materials, the interfaces and their laws at the static pressures, and the end
//! conditions.

use super::spec::{BarStackSpec, ModelSpec, SegmentSpec};
use super::{inv, pos};
use crate::error::Result;
use crate::excitation::Excitation;
use crate::law::registry::build_tangential;
use crate::law::ContactLaw;
use crate::scenario::spec::{MaterialSpec, TangentialSpec};
use crate::scenario::BuildCache;
use crate::solver::bar_stack::{End, Segment, ShearStack};
use std::sync::Arc;

/// Validate the model keys read before the segments: the cross-section, gravity and the
/// static force.
pub(super) fn validate_model(m: &ModelSpec, file: &str) -> Result<()> {
    pos(file, "model.area", m.area)?;
    if !m.gravity.is_finite() {
        return Err(inv(
            file,
            "model.gravity",
            m.gravity,
            "must be finite (m/s^2)",
        ));
    }
    if !m.static_shear_force.is_finite() {
        return Err(inv(
            file,
            "model.static_shear_force",
            m.static_shear_force,
            "must be finite (N)",
        ));
    }
    if !m.static_force.is_finite() {
        return Err(inv(
            file,
            "model.static_force",
            m.static_force,
            "must be finite (N)",
        ));
    }
    Ok(())
}

/// Build the segments and their materials (a preset or explicit E and density; `mass`
/// sets an equivalent density at the common cross-section `area`, with E scaled to keep
/// the wave speed), checking lengths, damping and unique names.
pub(super) fn build_segments(specs: &[SegmentSpec], area: f64, file: &str) -> Result<Vec<Segment>> {
    if specs.is_empty() {
        return Err(inv(file, "segment", "none", "at least one [[segment]]"));
    }
    let mut segments = Vec::new();
    for (i, s) in specs.iter().enumerate() {
        let key = |k: &str| format!("segment.{i}.{k}");
        pos(file, &key("length"), s.length)?;
        let mut mat = crate::scenario::material_of(
            &MaterialSpec {
                material: s.material.clone(),
                youngs_modulus: s.youngs_modulus,
                density: s.density,
                poisson_ratio: s.poisson_ratio,
                shear_modulus: s.shear_modulus,
                ct: s.ct,
                ..Default::default()
            },
            file,
            &format!("segment.{i}"),
            crate::scenario::Geometry::Bar,
        )?;
        if let Some(mass) = s.mass {
            pos(file, &key("mass"), mass)?;
            let rho_eq = mass / (area * s.length);
            mat.youngs_modulus *= rho_eq / mat.density;
            if let Some(g) = mat.shear_modulus.as_mut() {
                *g *= rho_eq / mat.density;
            }
            mat.density = rho_eq;
            crate::scenario::check_derived(&mat, file, &format!("segment.{i}"))?;
        }
        if !(s.damping.is_finite() && s.damping >= 0.0) {
            return Err(inv(file, key("damping"), s.damping, "must be >= 0 (1/s)"));
        }
        if specs[..i].iter().any(|o| o.name == s.name) || s.name == "obstacle" {
            return Err(inv(
                file,
                key("name"),
                &s.name,
                "segment names must be unique and not `obstacle`",
            ));
        }
        segments.push(Segment {
            name: s.name.clone(),
            length: s.length,
            material: mat,
            damping: s.damping,
        });
    }
    Ok(segments)
}

/// A transverse field needs the shear modulus of every segment.
pub(super) fn require_shear_moduli(segments: &[Segment], file: &str) -> Result<()> {
    match segments
        .iter()
        .position(|s| s.material.shear_modulus.is_none())
    {
        None => Ok(()),
        Some(i) => Err(inv(
            file,
            format!("segment.{i}.poisson_ratio"),
            "(missing)",
            "a transverse field ([shear_incident], a tangential law or a static shear force) \
             needs the shear modulus of every segment: give `poisson_ratio` in (-1, 0.5), \
             `shear_modulus` (Pa) or `ct` (m/s), or a preset `material`",
        )),
    }
}

/// The static equilibrium step: the pressure at the interface below segment `k` (Pa) is
/// the static force plus the weight of segments `0..=k`, over the cross-section.
fn static_pressure_at(m: &ModelSpec, segments: &[Segment], k: usize) -> f64 {
    let weight_above = segments[..=k]
        .iter()
        .map(|s| s.material.density * s.length * m.area * m.gravity)
        .sum::<f64>();
    (m.static_force + weight_above) / m.area
}

/// The interface laws by slot: slot `k < n - 1` joins segment `k` to segment `k + 1`, slot
/// `n - 1` joins the last segment to the obstacle (`n` segments); `None` where no
/// `[[interface]]` was given.
pub(super) struct InterfaceLaws {
    /// The law of each slot, built at its static pressure.
    laws: Vec<Option<Arc<ContactLaw>>>,
    /// The `[[interface]]` (its index in the file) of each slot.
    index: Vec<Option<usize>>,
    /// The static pressure of each slot, Pa (0 where there is no interface).
    pressures: Vec<f64>,
}

/// Build the interfaces and their laws: each `[[interface]]` must join two consecutive
/// segments in order (or the last segment and the obstacle), at most one per pair, and its
/// law is built at the static pressure of [`static_pressure_at`], which must not be
/// tensile.
pub(super) fn build_interface_laws(
    spec: &BarStackSpec,
    segments: &[Segment],
    file: &str,
    cache: &BuildCache,
) -> Result<InterfaceLaws> {
    let m = &spec.model;
    let n = segments.len();
    let mut laws: Vec<Option<Arc<ContactLaw>>> = vec![None; n];
    let mut index = vec![None; n];
    let mut pressures = vec![0.0; n];
    for (j, itf) in spec.interfaces.iter().enumerate() {
        let [a, b] = &itf.between;
        let ia = spec.segments.iter().position(|s| &s.name == a);
        let ib = if b == "obstacle" {
            Some(n)
        } else {
            spec.segments.iter().position(|s| &s.name == b)
        };
        let ia = match (ia, ib) {
            (Some(x), Some(y)) if y == x + 1 => x,
            _ => {
                return Err(inv(
                    file,
                    format!("interface.{j}.between"),
                    format!("[\"{a}\", \"{b}\"]"),
                    "must name two consecutive segments in order (or the last segment and \"obstacle\")",
                ));
            }
        };
        if laws[ia].is_some() {
            return Err(inv(
                file,
                format!("interface.{j}.between"),
                a,
                "one interface per pair of segments",
            ));
        }
        let p = static_pressure_at(m, segments, ia);
        if p < 0.0 {
            return Err(inv(
                file,
                format!("interface.{j}"),
                p,
                "the static step gives a tensile interface load: the stack would fall apart",
            ));
        }
        let law = cache.law(
            p,
            &itf.compression,
            &itf.traction,
            file,
            &format!("interface.{j}"),
        )?;
        pressures[ia] = p;
        laws[ia] = Some(law);
        index[ia] = Some(j);
    }
    Ok(InterfaceLaws {
        laws,
        index,
        pressures,
    })
}

impl InterfaceLaws {
    /// The laws between consecutive segments, in order: every pair needs one.
    pub(super) fn between_segments(
        &self,
        segments: &[Segment],
        file: &str,
    ) -> Result<Vec<Arc<ContactLaw>>> {
        let n = segments.len();
        let mut interfaces = Vec::new();
        for k in 0..n - 1 {
            match &self.laws[k] {
                Some(l) => interfaces.push(l.clone()),
                None => {
                    return Err(inv(
                        file,
                        "interface",
                        format!("{} / {}", segments[k].name, segments[k + 1].name),
                        "every pair of consecutive segments needs an [[interface]]",
                    ));
                }
            }
        }
        Ok(interfaces)
    }

    /// The end conditions `model.first_end` and `model.last_end`; an obstacle end takes the
    /// obstacle interface, which is an error with any other last end.
    pub(super) fn end_conditions(&self, m: &ModelSpec, file: &str) -> Result<(End, End)> {
        let obstacle = self.obstacle();
        let left = end_condition(&m.first_end, "model.first_end", false, obstacle, file)?;
        let right = end_condition(&m.last_end, "model.last_end", true, obstacle, file)?;
        // an obstacle interface with another far end would be silently unused
        if obstacle.is_some() && !matches!(right, End::Obstacle(_)) {
            return Err(inv(
                file,
                "model.last_end",
                &m.last_end,
                "\"obstacle\": an [[interface]] joins the last segment to the obstacle",
            ));
        }
        Ok((left, right))
    }

    /// The static interface pressures, Pa: between segments, then the obstacle's when the
    /// last end is one.
    pub(super) fn static_pressure(&self, right: &End) -> Vec<f64> {
        let n = self.laws.len();
        let mut static_pressure = self.pressures[..n - 1].to_vec();
        if matches!(right, End::Obstacle(_)) {
            static_pressure.push(self.pressures[n - 1]);
        }
        static_pressure
    }

    /// The tangential laws of a stack with a transverse field (model.md section 13): one
    /// per interface between segments and one for the obstacle (when there is one), each
    /// carrying the static shear `q0 = model.static_shear_force / area`; `None` when the
    /// stack has no transverse field (no `[shear_incident]`, every tangential branch
    /// `free` and no static shear force).
    pub(super) fn shear_stack(
        &self,
        spec: &BarStackSpec,
        right: &End,
        incident: Option<Arc<dyn Excitation>>,
        file: &str,
    ) -> Result<Option<ShearStack>> {
        let m = &spec.model;
        let active = incident.is_some()
            || m.static_shear_force != 0.0
            || spec
                .interfaces
                .iter()
                .any(|i| !matches!(i.tangential, TangentialSpec::Free(_)));
        if !active {
            return Ok(None);
        }
        let q0 = m.static_shear_force / m.area;
        if q0 != 0.0 && !matches!(right, End::Obstacle(_) | End::Fixed) {
            return Err(inv(
                file,
                "model.static_shear_force",
                m.static_shear_force,
                "a static transverse force needs a far end that holds it: model.last_end = \
                 \"obstacle\" (friction) or \"fixed\"",
            ));
        }
        let mut laws = Vec::with_capacity(self.laws.len());
        for (law, j) in self.laws.iter().zip(&self.index) {
            let (Some(law), Some(j)) = (law, j) else {
                laws.push(None);
                continue;
            };
            let prefix = format!("interface.{j}");
            let tl = build_tangential(&spec.interfaces[*j].tangential, q0, law, file, &prefix)
                .map_err(|e| match e {
                    // the static shear comes from the model's transverse force
                    crate::error::Error::Invalid { field, allowed, .. }
                        if field.ends_with(".static_shear") =>
                    {
                        inv(
                            file,
                            "model.static_shear_force",
                            m.static_shear_force,
                            &format!("at {prefix}: {allowed}"),
                        )
                    }
                    e => e,
                })?;
            laws.push(Some(Arc::new(tl)));
        }
        let n = laws.len();
        let obstacle = laws[n - 1].take();
        let interfaces = laws[..n - 1].iter().flatten().cloned().collect();
        Ok(Some(ShearStack {
            interfaces,
            obstacle,
            incident,
        }))
    }

    /// The law of the obstacle slot, if an `[[interface]]` names the obstacle.
    fn obstacle(&self) -> Option<&Arc<ContactLaw>> {
        self.laws.last().and_then(|l| l.as_ref())
    }
}

/// One end condition, `key = s`: `last` for the far end, the only one that can be an
/// obstacle (it then needs the obstacle law `obstacle`).
fn end_condition(
    s: &str,
    key: &str,
    last: bool,
    obstacle: Option<&Arc<ContactLaw>>,
    file: &str,
) -> Result<End> {
    Ok(match s {
        "free" => End::Free,
        "fixed" => End::Fixed,
        "transparent" => End::Transparent,
        "obstacle" if last => match obstacle {
            Some(l) => End::Obstacle(l.clone()),
            None => {
                return Err(inv(
                    file,
                    key,
                    s,
                    "an obstacle end needs an [[interface]] with between = [last segment, \"obstacle\"]",
                ));
            }
        },
        _ => {
            return Err(inv(
                file,
                key,
                s,
                if last {
                    "free, fixed, transparent or obstacle"
                } else {
                    "free, fixed or transparent"
                },
            ));
        }
    })
}

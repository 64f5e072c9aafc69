//! Oblique incidence of a scenario (model.md section 14): `incident.angle` (a P wave) or
//! `shear_incident.angle` (an SV wave), validated against the critical angles; the
//! incident wave becomes its normal and tangential tractions at the interface.

use super::spec::{Method, ScenarioSpec};
use super::ShearSetup;
use crate::analytic::oblique::{Elastic, Geometry, WaveType};
use crate::error::{Error, Result};
use crate::excitation::{Excitation, Scaled};
use crate::material::Material;
use std::sync::Arc;

/// The oblique incidence of a scenario.
#[derive(Debug, Clone)]
pub struct ObliqueSetup {
    /// Type of the incident wave.
    pub wave: WaveType,
    /// Angle of incidence, rad.
    pub angle: f64,
    /// The incident, reflected and transmitted plane waves at the interface.
    pub geometry: Geometry,
    /// The incident wave stress `s(t) = -rho c w(t)`, Pa (`w` the particle velocity
    /// along the polarisation).
    pub burst: Arc<dyn Excitation>,
}

/// An oblique incidence asked for: wave type, angle (rad) and the key that gave it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Request {
    wave: WaveType,
    angle: f64,
    key: &'static str,
}

/// The oblique incidence a spec asks for (`None` without an `angle` key; an angle of 0
/// gives the plane-wave setup with diagonal matrices, so that a sweep over the angle has
/// the same keys at every point), with the checks
/// that need no material: the range of the angle, a single incident wave, an amplitude
/// rather than xi, the exact solver.
pub(super) fn requested(spec: &ScenarioSpec, file: &str) -> Result<Option<Request>> {
    let mut found = None;
    let shear = spec.shear_incident.as_ref();
    for (angle, wave, key) in [
        (spec.incident.angle, WaveType::P, "incident.angle"),
        (
            shear.and_then(|s| s.angle),
            WaveType::Sv,
            "shear_incident.angle",
        ),
    ] {
        let Some(a) = angle else { continue };
        if !(a.is_finite() && (0.0..90.0).contains(&a)) {
            return Err(Error::invalid(file, key, a, "must lie in [0, 90) degrees"));
        }
        let other = match wave {
            WaveType::P => shear.is_some(),
            WaveType::Sv => !spec.incident.is_absent(),
        };
        if other {
            return Err(Error::invalid(
                file,
                key,
                a,
                "oblique incidence takes a single incident wave: give either [incident] \
                 (a P wave) or [shear_incident] (an SV wave), not both",
            ));
        }
        if wave == WaveType::P
            && let Some(x) = spec.incident.xi
        {
            return Err(Error::invalid(
                file,
                "incident.xi",
                x,
                "at oblique incidence give the wave's `amplitude` (Pa), not xi",
            ));
        }
        if spec.solver.method != Method::Exact {
            return Err(Error::invalid(
                file,
                "solver.method",
                "fd",
                "oblique incidence runs on the exact solver only (\"exact\")",
            ));
        }
        found = Some(Request {
            wave,
            angle: a.to_radians(),
            key,
        });
    }
    Ok(found)
}

fn elastic(m: &Material) -> Option<Elastic> {
    Some(Elastic {
        density: m.density,
        cp: m.wave_speed(),
        cs: m.shear_wave_speed()?,
    })
}

/// Apply an oblique request: the normal incident traction and the shear setup with the
/// tangential incident traction, and the setup itself. `incident` is the `[incident]`
/// wave (silent for an SV wave), `shear` the tangential half (its incident wave the
/// `[shear_incident]` one, silent for a P wave).
pub(super) fn apply(
    req: Request,
    medium: &Material,
    counterpart: Option<&Material>,
    incident: Arc<dyn Excitation>,
    shear: ShearSetup,
    file: &str,
) -> Result<(Arc<dyn Excitation>, ShearSetup, ObliqueSetup)> {
    let missing = |prefix: &str| {
        Error::invalid(
            file,
            format!("{prefix}.poisson_ratio"),
            "(missing)",
            format!("oblique incidence needs the shear modulus of {prefix}"),
        )
    };
    let e1 = elastic(medium).ok_or_else(|| missing("medium"))?;
    let e2 = match counterpart {
        Some(m) => Some(elastic(m).ok_or_else(|| missing("counterpart"))?),
        None => None,
    };
    let deg = crate::numeric::shown_degrees(req.angle);
    let geometry = Geometry::new(&e1, e2.as_ref(), req.wave, req.angle).map_err(|c| {
        Error::invalid(
            file,
            req.key,
            deg,
            format!(
                "must be below the critical angle {:.6} degrees, beyond which the {} {} wave \
                 in medium {} is evanescent (not implemented)",
                c.angle_deg,
                if c.medium == 1 {
                    "reflected"
                } else {
                    "transmitted"
                },
                c.wave.name(),
                c.medium
            ),
        )
    })?;
    let burst = match req.wave {
        WaveType::P => incident,
        WaveType::Sv => shear.incident.clone(),
    };
    let inc = &geometry.incident;
    let gn = -inc.traction[0] / inc.impedance;
    let gt = -inc.traction[1] / inc.impedance;
    let normal: Arc<dyn Excitation> = Arc::new(Scaled::new(burst.clone(), gn));
    let shear = ShearSetup {
        incident: Arc::new(Scaled::new(burst.clone(), gt)),
        has_wave: true,
        ..shear
    };
    Ok((
        normal,
        shear,
        ObliqueSetup {
            wave: req.wave,
            angle: req.angle,
            geometry,
            burst,
        },
    ))
}

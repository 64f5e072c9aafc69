//! A layer's material: a preset, or Young's modulus, Poisson's ratio and density, or the
//! P and S speeds and density, checked with errors naming the missing or bad key.

use super::{inv, positive, LayerSpec};
use crate::error::Result;
use crate::material::Material;
use crate::solver::solid_2d::Elastic;

/// The elastic solid of a layer.
pub(super) fn material(l: &LayerSpec, file: &str, key: &str) -> Result<Elastic> {
    let k = |f: &str| format!("{key}.{f}");
    if let Some(name) = &l.material {
        let moduli = [
            ("youngs_modulus", l.youngs_modulus),
            ("poisson_ratio", l.poisson_ratio),
            ("p_speed", l.p_speed),
            ("s_speed", l.s_speed),
        ];
        if let Some((field, Some(v))) = moduli.into_iter().find(|(_, v)| v.is_some()) {
            return Err(inv(
                file,
                k(field),
                v,
                &format!(
                    "no value beside `material = \"{name}\"`: give a preset (only its \
                     `density` may be changed) or the moduli, not both"
                ),
            ));
        }
        let m = Material::preset(name).ok_or_else(|| {
            inv(
                file,
                k("material"),
                name,
                &format!("one of {}", Material::PRESETS.join(", ")),
            )
        })?;
        let nu = m.poisson_ratio().unwrap_or(0.3);
        let rho = l.density.unwrap_or(m.density);
        return Ok(from_moduli(
            m.youngs_modulus,
            nu,
            positive(file, &k("density"), rho)?,
        ));
    }
    let density = || match l.density {
        Some(rho) => positive(file, &k("density"), rho),
        None => Err(inv(
            file,
            k("density"),
            "(missing)",
            "required with moduli or speeds: kg/m^3 > 0",
        )),
    };
    let missing = |field: &str, with: &str| {
        Err(inv(
            file,
            k(field),
            "(missing)",
            &format!("required with `{with}`"),
        ))
    };
    match (l.youngs_modulus, l.poisson_ratio, l.p_speed, l.s_speed) {
        (Some(e), Some(nu), None, None) => {
            positive(file, &k("youngs_modulus"), e)?;
            if !(nu > 0.0 && nu < 0.5) {
                return Err(inv(
                    file,
                    k("poisson_ratio"),
                    nu,
                    "in (0, 0.5) (the 2D solids need a positive Lame lambda)",
                ));
            }
            Ok(from_moduli(e, nu, density()?))
        }
        (None, None, Some(cp), Some(cs)) => {
            positive(file, &k("s_speed"), cs)?;
            if !(cp.is_finite() && cp > cs * 2f64.sqrt()) {
                return Err(inv(
                    file,
                    k("p_speed"),
                    cp,
                    &format!(
                        "a finite speed above sqrt(2) s_speed = {} m/s (a positive Lame lambda, \
                         nu > 0)",
                        cs * 2f64.sqrt()
                    ),
                ));
            }
            Ok(Elastic {
                density: density()?,
                p_speed: cp,
                s_speed: cs,
            })
        }
        (Some(_), None, None, None) => missing("poisson_ratio", "youngs_modulus"),
        (None, Some(_), None, None) => missing("youngs_modulus", "poisson_ratio"),
        (None, None, Some(_), None) => missing("s_speed", "p_speed"),
        (None, None, None, Some(_)) => missing("p_speed", "s_speed"),
        _ => Err(inv(
            file,
            key,
            "incomplete material",
            "a `material` preset, or `youngs_modulus` + `poisson_ratio` + `density`, or `p_speed` + `s_speed` + `density`",
        )),
    }
}

/// The solid of Young's modulus `e` (Pa), Poisson's ratio `nu` and density `rho`
/// (kg/m^3).
fn from_moduli(e: f64, nu: f64, rho: f64) -> Elastic {
    let g = e / (2.0 * (1.0 + nu));
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    Elastic {
        density: rho,
        p_speed: (m / rho).sqrt(),
        s_speed: (g / rho).sqrt(),
    }
}

//! A crack's static state: from a uniform far-field pre-stress (`[model] prestress`), or
//! along it as a table (`[[crack]] closure`, docs/scenario.md section 2b, docs/model.md
//! section 15.2): the specs, and the solver profile that builds each split node's law at
//! its interpolated pressure and shear, with its initial gap.

use super::CrackSpec;
use crate::error::{Error, Result};
use crate::law::point::SharedLaw;
use crate::law::spec::TractionSpec;
use crate::scenario::BuildCache;
use crate::solver::solid_2d::CrackProfile;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

fn inv(file: &str, field: impl Into<String>, v: impl std::fmt::Display, allowed: &str) -> Error {
    Error::invalid(file, field, v, allowed)
}

/// `[model] prestress`: a uniform far-field pre-stress (Pa, tension positive, the sign
/// convention of model.md section 2) whose traction on each crack's line is the crack's
/// static state: closure `p0 = -sigma_nn` and static shear `q0 = sigma_nt` (P-SV: `n`, `t`
/// = z, x for a horizontal crack, x, z for a vertical one; SH: `q0 = sigma_yn`).
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PrestressSpec {
    /// sigma_xx, Pa.
    #[serde(default)]
    pub xx: f64,
    /// sigma_zz, Pa.
    #[serde(default)]
    pub zz: f64,
    /// sigma_xz, Pa (P-SV runs).
    #[serde(default)]
    pub xz: f64,
    /// sigma_xy, Pa (SH runs: the shear on a vertical crack).
    #[serde(default)]
    pub xy: f64,
    /// sigma_yz, Pa (SH runs: the shear on a horizontal crack).
    #[serde(default)]
    pub yz: f64,
}

impl PrestressSpec {
    /// An error naming the first component that is not finite, or that the run's wave type
    /// has not (P-SV: `xx`, `zz`, `xz`; SH: `xx`, `zz`, `xy`, `yz`) given non-zero: it
    /// would be ignored.
    pub fn check(&self, antiplane: bool, file: &str) -> Result<()> {
        let all = [
            ("xx", self.xx),
            ("zz", self.zz),
            ("xz", self.xz),
            ("xy", self.xy),
            ("yz", self.yz),
        ];
        if let Some((c, v)) = all.into_iter().find(|(_, v)| !v.is_finite()) {
            return Err(inv(
                file,
                format!("model.prestress.{c}"),
                v,
                "a finite stress, Pa (tension positive)",
            ));
        }
        let sh = [("xz", self.xz)];
        let psv = [("xy", self.xy), ("yz", self.yz)];
        let foreign: &[(&str, f64)] = if antiplane { &sh } else { &psv };
        match foreign.iter().copied().find(|(_, v)| *v != 0.0) {
            Some((c, v)) => Err(inv(
                file,
                format!("model.prestress.{c}"),
                v,
                if antiplane {
                    "xx, zz, xy and yz in an antiplane (SH) run"
                } else {
                    "xx, zz and xz in a plane-strain (P-SV) run"
                },
            )),
            None => Ok(()),
        }
    }

    /// The static state `(p0, q0)` (Pa) of a crack whose line is horizontal (or vertical),
    /// in a plane-strain (or antiplane) run.
    pub fn on_line(&self, horizontal: bool, antiplane: bool) -> (f64, f64) {
        match (horizontal, antiplane) {
            (true, false) => (-self.zz, self.xz),
            (false, false) => (-self.xx, self.xz),
            (true, true) => (-self.zz, self.yz),
            (false, true) => (-self.xx, self.xy),
        }
    }
}

/// The key the static shear of a crack comes from: the pre-stress component on its line
/// (`model.prestress.xz`, `.yz` or `.xy`) when `pre` is given, else `{key}.static_shear`.
pub(super) fn static_shear_key(
    pre: Option<&PrestressSpec>,
    horizontal: bool,
    antiplane: bool,
    key: &str,
) -> String {
    match (pre, horizontal, antiplane) {
        (None, ..) => format!("{key}.static_shear"),
        (Some(_), _, false) => "model.prestress.xz".into(),
        (Some(_), true, true) => "model.prestress.yz".into(),
        (Some(_), false, true) => "model.prestress.xy".into(),
    }
}

/// The crack `c` with its static state from the pre-stress `pre` (when given): an error
/// where the crack gives its own (`static_pressure`, `static_shear`, a table's pressure or
/// shear) or where the pre-stress pulls it open.
pub(super) fn with_prestress(
    c: &CrackSpec,
    pre: Option<&PrestressSpec>,
    horizontal: bool,
    antiplane: bool,
    file: &str,
    key: &str,
) -> Result<CrackSpec> {
    let Some(pre) = pre else {
        return Ok(c.clone());
    };
    let table = c.closure.as_ref();
    let own = [
        ("static_pressure", c.static_pressure != 0.0),
        ("static_shear", c.static_shear != 0.0),
        (
            "closure.pressure",
            table.is_some_and(|t| t.pressure.is_some()),
        ),
        ("closure.shear", table.is_some_and(|t| t.shear.is_some())),
    ];
    if let Some((field, _)) = own.iter().find(|(_, given)| *given) {
        return Err(inv(
            file,
            format!("{key}.{field}"),
            "given",
            "left out with model.prestress (the pre-stress sets every crack's static state)",
        ));
    }
    let (p0, q0) = pre.on_line(horizontal, antiplane);
    if p0 < 0.0 {
        return Err(inv(
            file,
            "model.prestress",
            format!("{} MPa of tension across {key}", -p0 * 1e-6),
            "a compressive (or zero) normal stress on every crack: a crack under tension is \
             open at rest (give it a closure table with a gap instead)",
        ));
    }
    Ok(CrackSpec {
        static_pressure: p0,
        static_shear: q0,
        ..c.clone()
    })
}

/// `closure` of a `[[crack]]`: the static state at points along the crack, linear between
/// them and constant beyond the first and the last.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ClosureSpec {
    /// Positions from the crack's start along it, m (increasing, within its length).
    pub position: Vec<f64>,
    /// Static closure pressure p0 at each position, Pa (>= 0; default `static_pressure`).
    pub pressure: Option<Vec<f64>>,
    /// Static shear q0 at each position, Pa (default `static_shear`).
    pub shear: Option<Vec<f64>>,
    /// Initial normal gap at each position, m (>= 0, default 0); a point with a gap has
    /// no pressure, no shear and a traction-free law there.
    pub gap: Option<Vec<f64>>,
}

/// A crack's closure table as its solver profile: each point's law built (and cached by
/// its static pressure) from the crack's branches at the interpolated state.
#[derive(Debug)]
pub(super) struct ClosureProfile {
    crack: CrackSpec,
    table: ClosureSpec,
    file: String,
    key: String,
    cache: BuildCache,
}

/// `v` at `x` from the table `(xs, vs)`: linear between its points, constant beyond.
fn interpolate(xs: &[f64], vs: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&p| p <= x);
    if i == 0 {
        vs[0]
    } else if i == xs.len() {
        vs[xs.len() - 1]
    } else {
        let w = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
        vs[i - 1] + w * (vs[i] - vs[i - 1])
    }
}

impl ClosureProfile {
    /// The table of crack `c` (`length` m), checked: positions increasing within the
    /// crack, one value per position, pressures and gaps >= 0, a gap only where pressure,
    /// shear and the traction branch are all zero, and every table point's law valid.
    pub(super) fn new(
        c: &CrackSpec,
        t: &ClosureSpec,
        length: f64,
        file: &str,
        key: &str,
    ) -> Result<Self> {
        let k = |f: &str| format!("{key}.closure.{f}");
        let xs = &t.position;
        if xs.is_empty()
            || xs
                .iter()
                .any(|x| !(x.is_finite() && (0.0..=length).contains(x)))
            || xs.windows(2).any(|w| w[1] <= w[0])
        {
            return Err(inv(
                file,
                k("position"),
                format!("{xs:?}"),
                &format!("increasing positions along the crack, within [0, {length}] m"),
            ));
        }
        for (name, v, uniform) in [
            ("pressure", &t.pressure, c.static_pressure),
            ("shear", &t.shear, c.static_shear),
            ("gap", &t.gap, 0.0),
        ] {
            let Some(v) = v else { continue };
            if v.len() != xs.len() || v.iter().any(|x| !x.is_finite()) {
                return Err(inv(
                    file,
                    k(name),
                    format!("{} values", v.len()),
                    &format!("{} finite values, one per position", xs.len()),
                ));
            }
            if name != "gap" && uniform != 0.0 {
                return Err(inv(
                    file,
                    format!("{key}.static_{name}"),
                    uniform,
                    &format!("0 (the closure table gives the {name})"),
                ));
            }
            if name != "shear" && v.iter().any(|&x| x < 0.0) {
                return Err(inv(
                    file,
                    k(name),
                    format!("{v:?}"),
                    ">= 0 at every position",
                ));
            }
        }
        let profile = ClosureProfile {
            crack: c.clone(),
            table: t.clone(),
            file: file.to_string(),
            key: key.to_string(),
            cache: BuildCache::new(),
        };
        for &x in xs {
            let (p0, q0, g0) = profile.state(x);
            if g0 > 0.0 && (p0 != 0.0 || q0 != 0.0 || c.traction != TractionSpec::default()) {
                return Err(inv(
                    file,
                    k("gap"),
                    g0,
                    "0 where the pressure or the shear is not 0 or the traction branch is not free (an open point carries no stress)",
                ));
            }
            profile.at(x)?;
        }
        Ok(profile)
    }

    /// `(p0, q0, g0)` (Pa, Pa, m) at `position` (m).
    fn state(&self, position: f64) -> (f64, f64, f64) {
        let t = &self.table;
        let at = |v: &Option<Vec<f64>>, uniform: f64| {
            v.as_ref()
                .map_or(uniform, |v| interpolate(&t.position, v, position))
        };
        (
            at(&t.pressure, self.crack.static_pressure),
            at(&t.shear, self.crack.static_shear),
            at(&t.gap, 0.0),
        )
    }
}

impl CrackProfile<SharedLaw> for ClosureProfile {
    fn at(&self, position: f64) -> Result<(SharedLaw, f64)> {
        let (p0, q0, g0) = self.state(position);
        if g0 > 0.0 && (p0 != 0.0 || q0 != 0.0) {
            return Err(inv(
                &self.file,
                format!("{}.closure.gap", self.key),
                format!("{g0} m at {position} m where p0 = {p0} Pa, q0 = {q0} Pa"),
                "a gap only where the interpolated pressure and shear are 0 (between two \
                 positions the table interpolates linearly: a gap that falls to 0 where the \
                 pressure or the shear rises from 0 overlaps them; add a position where \
                 both the gap and the pressure are 0)",
            ));
        }
        let c = &self.crack;
        let normal = self
            .cache
            .law(p0, &c.compression, &c.traction, &self.file, &self.key)?;
        let tangential = crate::law::registry::build_tangential(
            &c.tangential,
            q0,
            &normal,
            &self.file,
            &self.key,
        )
        .map_err(|e| match self.table.shear {
            Some(_) => e.renamed_field(
                &format!("{}.static_shear", self.key),
                &format!("{}.closure.shear", self.key),
            ),
            None => e,
        })?;
        Ok((
            SharedLaw {
                normal,
                tangential: Arc::new(tangential),
            },
            g0,
        ))
    }
}

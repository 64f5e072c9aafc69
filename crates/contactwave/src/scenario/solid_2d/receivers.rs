//! `[[receiver]]` of a 2D scenario: points and lines where the velocity or the stress is
//! recorded and analysed, checked (names, quantity, component, inside the rectangle).

use super::inv;
use crate::analysis::HARMONIC_KEYS;
use crate::error::Result;
use crate::solver::solid_2d::region::Region;
use crate::solver::solid_2d::WaveType;
use serde::{Deserialize, Serialize};

/// The points a receiver line may have.
pub const LINE_POINTS: std::ops::RangeInclusive<usize> = 2..=10_000;

/// `[[receiver]]`: a point (or, with `to` and `count`, a line of points) where the
/// velocity or the stress is recorded and analysed.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReceiverSpec {
    /// Name (summary key prefix and CSV column prefix: letters, digits, `_`); a line's
    /// points are `<name>_0` ... `<name>_<count - 1>`.
    pub name: String,
    /// Position `[x, z]`, m; a line's first point (required unless `group`).
    #[serde(default = "super::mesh::unset_point")]
    pub at: [f64; 2],
    /// On a mesh: a line of `count` points evenly spaced along this physical curve (by
    /// arc length, from its first end: smaller x, then z), instead of `at` and `to`.
    pub group: Option<String>,
    /// A line's last point `[x, z]`, m (with `count`).
    pub to: Option<[f64; 2]>,
    /// Points of a line, evenly spaced from `at` to `to`, or along `group` (>= 2).
    pub count: Option<usize>,
    /// `velocity` (default, m/s) or `stress` (Pa).
    #[serde(default = "velocity")]
    pub quantity: String,
    /// The analysed component: velocity `x`, `z` (default in P-SV runs) or `y` (SH runs);
    /// stress `xx`, `zz` (default), `xz` (P-SV) or `yx`, `yz` (default, SH).
    pub component: Option<String>,
    /// `[start, end]` of this receiver's time gate, s (default: `[analysis] gate`):
    /// receivers before and after a crack see the wave at different times.
    pub gate: Option<[f64; 2]>,
    /// Half-cosine ramps of this receiver's gate, inside it, s (default: `[analysis]
    /// taper` with the analysis' gate, 0 with the receiver's own).
    pub taper: Option<f64>,
}

fn velocity() -> String {
    "velocity".into()
}

/// A receiver point of a validated scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Receiver2d {
    /// Name (a line's points carry their index).
    pub name: String,
    /// Records the stress (Pa) rather than the velocity (m/s).
    pub stress: bool,
    /// Index among the solver's velocity receivers or among its stress receivers.
    pub index: usize,
    /// The analysed component (index into the quantity's components).
    pub component: usize,
    /// The time gate of its analysis (its `[[receiver]]`'s, or `[analysis]`'s; `None`:
    /// the whole record).
    pub gate: Option<crate::analysis::Gate>,
    /// Index of its `[[receiver]]` table.
    pub table: usize,
}

/// Component names of a velocity or stress receiver in P-SV or SH runs.
pub fn component_names(stress: bool, wave: WaveType) -> &'static [&'static str] {
    match (stress, wave) {
        (false, WaveType::PSv) => &["x", "z"],
        (false, WaveType::Sh) => &["y"],
        (true, WaveType::PSv) => &["xx", "zz", "xz"],
        (true, WaveType::Sh) => &["yx", "yz"],
    }
}

/// The checked receivers of a scenario.
pub(super) struct Checked {
    /// The velocity receivers' points `[x, z]`, m.
    pub points: Vec<[f64; 2]>,
    /// Every receiver (a line's points one each).
    pub receivers: Vec<Receiver2d>,
    /// The stress receivers' points `[x, z]`, m.
    pub stress_points: Vec<[f64; 2]>,
}

/// The points of a receiver line along a named curve: `(table, group, count)` to the
/// points, or an error naming `receiver.<table>.group`.
pub(super) type Along<'a> = &'a dyn Fn(usize, &str, usize) -> Result<Vec<[f64; 2]>>;

/// The receivers `spec` of a run of `wave` type in a rectangle `width` x `depth` (m),
/// checked (errors name `file` and `receiver.<i>.<key>`): the velocity points, the
/// receivers (a line's points one each), the stress points.
pub(super) fn check(
    spec: &[ReceiverSpec],
    wave: WaveType,
    width: f64,
    depth: f64,
    file: &str,
) -> Result<Checked> {
    let along: Along<'_> = &|i, g, _| {
        Err(inv(
            file,
            format!("receiver.{i}.group"),
            g,
            "only with [mesh] (a physical curve); a line here is `at`, `to` and `count`",
        ))
    };
    check_in(spec, wave, Region::new(width, depth), along, file)
}

/// [`check`] in `region` (a mesh's bounding box), the lines along curves by `along`.
pub(super) fn check_in(
    spec: &[ReceiverSpec],
    wave: WaveType,
    region: Region,
    along: Along<'_>,
    file: &str,
) -> Result<Checked> {
    let mut points = Vec::new();
    let mut receivers = Vec::new();
    let mut stress_points = Vec::new();
    let mut names_taken = std::collections::HashSet::new();
    let mut keys_taken = std::collections::HashMap::new();
    for (i, r) in spec.iter().enumerate() {
        let key = format!("receiver.{i}");
        if r.name.is_empty()
            || !r
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            return Err(inv(
                file,
                format!("{key}.name"),
                &r.name,
                "letters, digits and `_`",
            ));
        }
        let stress = match r.quantity.as_str() {
            "velocity" => false,
            "stress" => true,
            v => {
                return Err(inv(
                    file,
                    format!("{key}.quantity"),
                    v,
                    "velocity or stress",
                ));
            }
        };
        let names = component_names(stress, wave);
        // defaults: z (P-SV) or y (SH) velocity, zz (P-SV) or yz (SH) stress
        let comp = match r.component.as_deref() {
            None if stress || wave == WaveType::PSv => 1,
            None => 0,
            Some(v) => names
                .iter()
                .position(|n| *n == v)
                .ok_or_else(|| inv(file, format!("{key}.component"), v, &names.join(", ")))?,
        };
        let at_set = !r.at[0].is_nan() || !r.at[1].is_nan();
        let named = |pts: Vec<[f64; 2]>| -> Vec<([f64; 2], String)> {
            pts.into_iter()
                .enumerate()
                .map(|(k, p)| (p, format!("{}_{k}", r.name)))
                .collect()
        };
        let line: Vec<([f64; 2], String)> = match (&r.group, r.to, r.count) {
            (Some(_), _, _) if at_set || r.to.is_some() => {
                let k = if at_set { "at" } else { "to" };
                return Err(inv(
                    file,
                    format!("{key}.{k}"),
                    "given",
                    "not with `group` (a line along the curve, of `count` points)",
                ));
            }
            (Some(_), _, Some(n)) | (None, Some(_), Some(n)) if !LINE_POINTS.contains(&n) => {
                return Err(inv(file, format!("{key}.count"), n, "2 to 10000 points"));
            }
            (Some(g), _, Some(n)) => named(along(i, g, n)?),
            (Some(_), _, None) => {
                return Err(inv(
                    file,
                    format!("{key}.count"),
                    "missing",
                    "the points of the line along `group`, >= 2",
                ));
            }
            (None, _, _) if !at_set => {
                return Err(inv(
                    file,
                    format!("{key}.at"),
                    "missing",
                    "the receiver's position [x, z], m (or, on a mesh, `group` and `count`)",
                ));
            }
            (None, None, None) => vec![(r.at, r.name.clone())],
            (None, Some(to), Some(n)) => (0..n)
                .map(|k| {
                    let w = k as f64 / (n - 1) as f64;
                    (
                        [
                            r.at[0] + w * (to[0] - r.at[0]),
                            r.at[1] + w * (to[1] - r.at[1]),
                        ],
                        format!("{}_{k}", r.name),
                    )
                })
                .collect(),
            (None, Some(_), None) => {
                return Err(inv(
                    file,
                    format!("{key}.count"),
                    "missing",
                    "the points of the line from `at` to `to`, >= 2",
                ));
            }
            (None, None, Some(_)) => {
                return Err(inv(
                    file,
                    format!("{key}.to"),
                    "missing",
                    "the line's last point [x, z], m (with `count`)",
                ));
            }
        };
        for (at, name) in line {
            if names_taken.contains(&name) {
                return Err(inv(
                    file,
                    format!("{key}.name"),
                    &name,
                    "a name no other receiver has",
                ));
            }
            // (`p` and `p_A2_over` would both write `p_A2_over_A1` into the summary; a
            // map of the keys written so far keeps the check linear in the points)
            let keys = HARMONIC_KEYS.map(|k| format!("{name}_{k}"));
            if let Some((shared, other)) =
                keys.iter().find_map(|k| keys_taken.get(k).map(|o| (k, o)))
            {
                return Err(inv(
                    file,
                    format!("{key}.name"),
                    &name,
                    &format!(
                        "a name whose summary keys differ from every other receiver's \
                         (receiver `{other}` writes `{shared}` too)"
                    ),
                ));
            }
            names_taken.insert(name.clone());
            for k in keys {
                keys_taken.insert(k, name.clone());
            }
            if r.group.is_none() && !region.contains(at) {
                // (a line's points between its ends are inside when its ends are)
                let same = at.iter().zip(r.at).all(|(a, b)| a.to_bits() == b.to_bits());
                let end = if same || r.to.is_none() { "at" } else { "to" };
                return Err(inv(
                    file,
                    format!("{key}.{end}"),
                    format!("[{}, {}]", at[0], at[1]),
                    &region.describe(),
                ));
            }
            let list = if stress {
                &mut stress_points
            } else {
                &mut points
            };
            receivers.push(Receiver2d {
                name,
                stress,
                index: list.len(),
                component: comp,
                gate: None,
                table: i,
            });
            list.push(at);
        }
    }
    Ok(Checked {
        points,
        receivers,
        stress_points,
    })
}

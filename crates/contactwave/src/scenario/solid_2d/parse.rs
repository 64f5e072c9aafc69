//! Reading a 2D scenario's table: serde with the hints of what a key takes, and the keys of
//! a source that belong to another kind.

use super::{inv, receivers, Solid2dSpec, SourceSpec};
use crate::error::Result;
use crate::solver::solid_2d::{Incidence, WaveType};

impl Solid2dSpec {
    /// Deserialize a table into a spec, naming the field path on failure. Unit strings
    /// (`width = "40 mm"`) are converted to SI first ([`crate::scenario::units`]).
    pub fn from_table(table: toml::Table, file: &str) -> Result<Self> {
        crate::scenario::value::deserialize_scenario(table, file, hint)
    }
}

/// What a 2D scenario's key takes where serde's own message would not say it (a count's
/// range, a required table).
fn hint(key: &str, problem: crate::scenario::value::FieldProblem) -> Option<String> {
    use crate::scenario::value::FieldProblem::{Missing, Wrong};
    let whole = crate::scenario::value::whole_numbers;
    Some(match (key, problem) {
        ("model", Missing) => {
            "a [model] table with kind = \"solid_2d\", width (m) and duration (s)".into()
        }
        ("model.width", Missing) => "the rectangle's width along x, m (> 0)".into(),
        ("model.duration", Missing) => "the simulated time, s (> 0)".into(),
        ("layer", Missing) => "at least one [[layer]] table, from the top: thickness (m) and a \
                               material preset, or E / nu / rho, or c_P / c_S / rho"
            .into(),
        ("layer.thickness", Missing) => "the layer's thickness, m (> 0)".into(),
        ("source", Missing) => "at least one [[source]] table: kind = \"transducer\" \
                                (default), \"force\" or \"plane_wave\", with its signal"
            .into(),
        ("source.signal", Missing) => {
            "the time function: signal = { frequency = ..., cycles = ..., amplitude = ... }".into()
        }
        ("crack.start", Missing) => "the crack's start [x, z], m".into(),
        ("receiver.name", Missing) => "a name of letters, digits and _".into(),
        ("receiver.at", Missing) => "the receiver's position [x, z], m".into(),
        ("model.order", Wrong) => whole(crate::solver::solid_2d::ORDERS),
        ("model.crack_every", Wrong) => "a whole number >= 1 (steps)".into(),
        ("snapshots.pixels", Wrong) => whole(crate::scenario::snapshots::PIXELS),
        ("receiver.count", Wrong) => whole(receivers::LINE_POINTS),
        _ => return None,
    })
}

/// The keys of each source kind beside `kind` and `signal`, and whether a source sets a
/// key of another kind (named, with the kind's own keys): such a key would be ignored.
pub(super) fn foreign_key(s: &SourceSpec) -> Option<(&'static str, &'static str)> {
    let set = [
        ("x0", s.x0.is_some()),
        ("x1", s.x1.is_some()),
        ("surface", s.surface.is_some()),
        ("component", s.component.is_some()),
        ("angle", s.angle != 0.0),
        ("at", s.at.is_some()),
        ("direction", s.direction.is_some()),
        ("wave", s.wave.is_some()),
        ("z", s.z.is_some()),
    ];
    let own = match s.kind.as_str() {
        "transducer" => "x0, x1, surface, component, angle",
        "force" => "at, direction",
        "plane_wave" => "wave, z, angle",
        _ => return None,
    };
    set.iter()
        .find(|(name, given)| *given && !own.split(", ").any(|o| o == *name))
        .map(|(name, _)| (*name, own))
}

/// A plane-wave source's `wave` (any case; P by default in P-SV runs, SH in SH ones),
/// refused where the run's wave type `wave` cannot carry it (the error names `key.wave`).
pub(super) fn incidence(
    s: &SourceSpec,
    wave: WaveType,
    file: &str,
    key: &str,
) -> Result<Incidence> {
    let name = s.wave.as_deref().map(str::to_ascii_uppercase);
    match (name.as_deref(), wave) {
        (None | Some("P"), WaveType::PSv) => Ok(Incidence::P),
        (Some("SV"), WaveType::PSv) => Ok(Incidence::Sv),
        (None | Some("SH"), WaveType::Sh) => Ok(Incidence::Sh),
        _ => Err(inv(
            file,
            format!("{key}.wave"),
            s.wave.as_deref().unwrap_or("P"),
            "P or SV in a P-SV run, SH in an SH run",
        )),
    }
}

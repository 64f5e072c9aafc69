//! `[snapshots]` of a 2D scenario (docs/scenario.md section 2b): when the wavefield is
//! kept, which value is drawn, and which picture files a run writes.

use crate::error::{Error, Result};
use crate::solver::solid_2d::snapshot::Field;
use crate::solver::solid_2d::WaveType;
use serde::{Deserialize, Serialize};

/// Frames when neither `times` nor `every` is given.
pub const DEFAULT_FRAMES: usize = 20;
/// Default picture width, pixels (the field's columns across the model's width).
pub const DEFAULT_PIXELS: usize = 800;
/// Most frames of one run.
pub const MAX_FRAMES: usize = 2000;
/// Pixel widths allowed.
pub const PIXELS: std::ops::RangeInclusive<usize> = 16..=4096;

/// `[snapshots]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SnapshotsSpec {
    /// Times of the frames, s (each in [0, duration]; the nearest half level is taken).
    pub times: Option<Vec<f64>>,
    /// A frame every this many seconds from `every` to the duration (instead of `times`).
    pub every: Option<f64>,
    /// `magnitude` (default), `vx`, `vz` (plane strain) or `vy` (antiplane).
    pub field: Option<String>,
    /// Width of the field in pixels (default 800, 16 to 4096; the height keeps them square).
    pub pixels: Option<usize>,
    /// Fixed colour scale, m/s (default: the largest value of all frames).
    pub scale: Option<f64>,
    /// Write the animated GIF `snapshots/snapshots.gif` (default true).
    pub gif: Option<bool>,
    /// Write the VTK files `snapshots/frame_NNNN.vti` and `snapshots/snapshots.pvd`
    /// (default true).
    pub vtk: Option<bool>,
}

/// The checked `[snapshots]` of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshots {
    /// Times asked for, s (increasing).
    pub times: Vec<f64>,
    /// The scenario key that set the times (`snapshots.times` or `snapshots.every`).
    pub key: &'static str,
    /// The value drawn.
    pub field: Field,
    /// Its name (`magnitude`, `vx`, `vz`, `vy`).
    pub field_name: String,
    /// Width in pixels.
    pub pixels: usize,
    /// Fixed colour scale, m/s.
    pub scale: Option<f64>,
    /// Write the GIF.
    pub gif: bool,
    /// Write the VTK files.
    pub vtk: bool,
}

impl SnapshotsSpec {
    /// Check against the run's `duration` (s) and wave type; errors name `file` and the key.
    pub fn check(&self, file: &str, duration: f64, wave: WaveType) -> Result<Snapshots> {
        let bad = |k: &str, v: String, allowed: &str| {
            Err(Error::invalid(file, format!("snapshots.{k}"), v, allowed))
        };
        let (times, key) = match (&self.times, self.every) {
            (Some(_), Some(_)) => {
                return bad(
                    "every",
                    "given with `times`".into(),
                    "either `times` or `every`",
                );
            }
            (Some(t), None) => {
                if t.is_empty() || t.len() > MAX_FRAMES {
                    return bad(
                        "times",
                        format!("{} values", t.len()),
                        &format!("1 to {MAX_FRAMES} times"),
                    );
                }
                if let Some(v) = t
                    .iter()
                    .find(|v| !(v.is_finite() && **v >= 0.0 && **v <= duration))
                {
                    return bad(
                        "times",
                        v.to_string(),
                        &format!("times in [0, {duration:e}] s"),
                    );
                }
                let mut t = t.clone();
                t.sort_by(f64::total_cmp);
                (t, "snapshots.times")
            }
            (None, Some(e)) => {
                let min = duration / MAX_FRAMES as f64;
                if !(e.is_finite() && e >= min && e <= duration) {
                    // the shortest decimal at or above the bound (2e-9, not
                    // 1.9999999999999997e-9): a value typed as shown is allowed
                    let shown = (0..17)
                        .map(|p| format!("{min:.p$e}"))
                        .find(|t| t.parse::<f64>().is_ok_and(|v| v >= min))
                        .unwrap_or_else(|| format!("{min:e}"));
                    return bad(
                        "every",
                        e.to_string(),
                        &format!("an interval in [{shown}, {duration:e}] s"),
                    );
                }
                let n = (duration / e * (1.0 + 1e-12)).floor() as usize;
                ((1..=n).map(|k| k as f64 * e).collect(), "snapshots.every")
            }
            (None, None) => (
                (1..=DEFAULT_FRAMES)
                    .map(|k| duration * k as f64 / DEFAULT_FRAMES as f64)
                    .collect(),
                "snapshots.every",
            ),
        };
        let sh = wave == WaveType::Sh;
        let name = self.field.clone().unwrap_or_else(|| "magnitude".into());
        let field = match (name.as_str(), sh) {
            ("magnitude", _) => Field::Magnitude,
            ("vx", false) | ("vy", true) => Field::Component(0),
            ("vz", false) => Field::Component(1),
            _ => {
                return bad(
                    "field",
                    name.clone(),
                    if sh {
                        "magnitude or vy"
                    } else {
                        "magnitude, vx or vz"
                    },
                );
            }
        };
        let pixels = self.pixels.unwrap_or(DEFAULT_PIXELS);
        if !PIXELS.contains(&pixels) {
            return bad(
                "pixels",
                pixels.to_string(),
                &format!("{} to {}", PIXELS.start(), PIXELS.end()),
            );
        }
        if let Some(s) = self.scale
            && !(s.is_finite() && s > 0.0)
        {
            return bad("scale", s.to_string(), "a speed > 0, m/s");
        }
        Ok(Snapshots {
            times,
            key,
            field,
            field_name: name,
            pixels,
            scale: self.scale,
            gif: self.gif.unwrap_or(true),
            vtk: self.vtk.unwrap_or(true),
        })
    }
}

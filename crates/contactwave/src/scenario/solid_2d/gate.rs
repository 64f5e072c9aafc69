//! The time gates of a 2D scenario's analysis: `[analysis]`'s, and each `[[receiver]]`'s
//! own (receivers before and after a crack see the wave at different times).

use super::receivers::Receiver2d;
use super::{inv, AnalysisSpec, Solid2dSpec};
use crate::analysis::{AnalysisMethod, Gate};
use crate::error::Result;

/// The gate of `[analysis]`, checked: inside `[0, duration]` (s), at least one period of
/// the fundamental `f0` (Hz) long, a taper at most half its length; `plateau_fit` needs
/// one (its fit window).
pub(super) fn analysis_gate(
    a: &AnalysisSpec,
    file: &str,
    duration: f64,
    f0: f64,
) -> Result<Option<Gate>> {
    let gate = a.gate.map(|[start, end]| Gate {
        start,
        end,
        taper: a.taper,
    });
    match gate {
        Some(g) if !(g.is_valid() && g.start >= 0.0 && g.end <= duration) => {
            if g.taper != 0.0 && g.start < g.end && g.end <= duration && g.start >= 0.0 {
                Err(inv(
                    file,
                    "analysis.taper",
                    g.taper,
                    "0 <= taper <= half the gate's length, s",
                ))
            } else {
                Err(inv(
                    file,
                    "analysis.gate",
                    format!("[{}, {}]", g.start, g.end),
                    "0 <= start < end <= model.duration, s",
                ))
            }
        }
        Some(g) if f0 > 0.0 && g.end - g.start < 1.0 / f0 => Err(inv(
            file,
            "analysis.gate",
            format!("[{}, {}]", g.start, g.end),
            &format!(
                "a window at least one period of the fundamental long (1 / f0 = {:e} s)",
                1.0 / f0
            ),
        )),
        None if a.method == AnalysisMethod::PlateauFit => Err(inv(
            file,
            "analysis.gate",
            "missing",
            "plateau_fit needs the window of the echo's flat top: [start, end], s",
        )),
        None if a.taper != 0.0 => Err(inv(
            file,
            "analysis.taper",
            a.taper,
            "0 without a gate (`analysis.gate` sets the window)",
        )),
        g => Ok(g),
    }
}

/// Each receiver's gate: its `[[receiver]]` table's own (`gate`, `taper`), or `gate`, the
/// analysis' (errors name `receiver.<i>.gate` and `.taper`).
pub(super) fn receiver_gates(
    spec: &Solid2dSpec,
    receivers: &mut [Receiver2d],
    gate: Option<Gate>,
    file: &str,
    duration: f64,
    f0: f64,
) -> Result<()> {
    for (i, r) in spec.receivers.iter().enumerate() {
        let own = match (r.gate, r.taper) {
            (None, None) => gate,
            (g, taper) => {
                let key = format!("receiver.{i}");
                // its own window (ramps 0 unless given), or the analysis' window with
                // its own ramps
                let own = AnalysisSpec {
                    method: spec.analysis.method,
                    gate: g.or(spec.analysis.gate),
                    taper: taper.unwrap_or(if g.is_some() {
                        0.0
                    } else {
                        spec.analysis.taper
                    }),
                };
                analysis_gate(&own, file, duration, f0).map_err(|e| {
                    e.renamed_field("analysis.gate", &format!("{key}.gate"))
                        .renamed_field("analysis.taper", &format!("{key}.taper"))
                })?
            }
        };
        for p in receivers.iter_mut().filter(|p| p.table == i) {
            p.gate = own;
        }
    }
    Ok(())
}

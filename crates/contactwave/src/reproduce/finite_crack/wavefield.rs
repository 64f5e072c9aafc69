//! Pictures of the wavefield: the reference case of [`super::length`] (a Signorini crack
//! of three P wavelengths under the plane P burst, p0 = 0.3 MPa, 1 MPa) run once more with
//! `[snapshots]` (model.md section 15.11): two frames (the burst on the crack; the
//! reflected burst on its way up with the tips' diffracted waves behind it), the GIF of
//! every frame, and the crack's open/closed state along its length in time, embedded in
//! the report beside the receiver's record.

use super::super::{fmt_value, panel, Figure, Picture};
use super::{c_p, Cost, Plane, Resolution, CYCLES, F0, SIGNORINI};
use crate::error::{Error, Result};
use crate::model::{self, RunControl};
use crate::output::plot::Series;
use crate::reproduce::Ctx;
use crate::scenario::parse_toml;
use std::path::Path;

/// Crack length, P wavelengths.
const LENGTH: usize = 3;
/// Frames per period of the burst (the GIF's time step).
const FRAMES_PER_PERIOD: f64 = 2.0;
/// Picture width, pixels.
const PIXELS: usize = 480;

/// What the run gives the figure: the receiver's record and the pictures.
struct Pictures {
    t: Vec<f64>,
    vz: Vec<f64>,
    frames: Vec<(f64, Vec<u8>)>,
    gif: Vec<u8>,
    state: Vec<u8>,
    closure: f64,
}

/// The scenario: the length study's at [`LENGTH`] wavelengths with snapshots of `v_z`.
fn text(res: Resolution) -> String {
    let plane = Plane {
        res,
        length: Some(LENGTH * res.per_wavelength()),
    };
    let law = &SIGNORINI;
    format!(
        "{}\n[snapshots]\nevery = {:e}\nfield = \"vz\"\npixels = {PIXELS}\nvtk = false\n",
        plane.text(law, law.p0, law.amplitude),
        1.0 / (F0 * FRAMES_PER_PERIOD)
    )
}

/// Run the case and pick its pictures.
fn pictures(res: Resolution) -> Result<Pictures> {
    let table = parse_toml(&text(res), "<finite_crack wavefield>")?;
    let outcome = model::plan(table, Path::new("<finite_crack wavefield>"))
        .base()?
        .run(&RunControl::default())?;
    let missing =
        |what: &str| Error::numerical(0.0, format!("the wavefield run has no {what}"), "");
    let w = outcome
        .waveform("reflected_vz")
        .ok_or_else(|| missing("receiver"))?;
    let t = (0..w.samples.len())
        .map(|k| w.t0 + k as f64 * w.dt)
        .collect();
    let mut frames = Vec::new();
    let (mut gif, mut state) = (Vec::new(), Vec::new());
    for f in outcome.binary_files()? {
        if let Some(k) = f
            .name
            .strip_prefix("snapshots/frame_")
            .and_then(|s| s.strip_suffix(".png"))
            .and_then(|s| s.parse::<usize>().ok())
        {
            // `every`: frame k at (k + 1) / (FRAMES_PER_PERIOD f0)
            frames.push(((k + 1) as f64 / (F0 * FRAMES_PER_PERIOD), f.bytes));
        } else if f.name == "snapshots/snapshots.gif" {
            gif = f.bytes;
        } else if f.name == "crack_state.png" {
            state = f.bytes;
        }
    }
    if frames.is_empty() || gif.is_empty() || state.is_empty() {
        return Err(missing("snapshots"));
    }
    Ok(Pictures {
        t,
        vz: w.samples,
        frames,
        gif,
        state,
        closure: outcome
            .summary()
            .get("energy_closure_error")
            .unwrap_or(f64::NAN),
    })
}

/// The frame nearest `t`, s.
fn nearest(frames: &[(f64, Vec<u8>)], t: f64) -> &(f64, Vec<u8>) {
    frames
        .iter()
        .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
        .unwrap_or(&frames[0])
}

/// Add the wavefield figure.
pub(super) fn run(ctx: &Ctx, res: Resolution, figures: &mut Vec<Figure>) -> Result<()> {
    let cost = Cost::start(ctx);
    let p = ctx
        .map("finite_crack wavefield", &[res], |r| pictures(*r))?
        .pop()
        .ok_or(Error::Interrupted)?;
    // the burst's centre at the crack, and 1.2 lambda on its way back (the geometry of
    // super::Plane: the front leaves one element above the line at t = 0)
    let (e, n) = (res.element(), res.per_wavelength() as f64);
    let z = |v: f64| (v * n).round() * e;
    let to_crack = (z(Plane::Z_C) - (z(Plane::Z_L) - e)) / c_p();
    let half_burst = 0.5 * CYCLES / F0;
    let t_on = to_crack + half_burst;
    let t_back = t_on + 1.2 * (z(Plane::Z_C) - z(Plane::Z_L)) / c_p();
    let on = nearest(&p.frames, t_on);
    let back = nearest(&p.frames, t_back);
    let us = |t: f64| t * 1e6;
    let t_us: Vec<f64> = p.t.iter().map(|t| us(*t)).collect();
    let lambda_mm = super::lambda() * 1e3;
    let mut fig = Figure::new(
        "finite_crack_wavefield",
        "The wavefield of a plane P burst at a finite Signorini crack",
        format!(
            "Beyond the thesis (model.md sections 15.8 and 15.11). The case of the length study \
             at L = {LENGTH} lambda (lambda = {} mm): a plane 1 MHz P burst (5-cycle Hann, 1 \
             MPa) injected by total-field/scattered-field {} mm above a Signorini crack under \
             p0 = 0.3 MPa (xi = 0.3) in an aluminium strip with periodic sides and absorbing \
             top and bottom. The plot: the vertical velocity v_z at the receiver 2 lambda \
             above the crack's centre (the scattered region: the reflected burst alone). The \
             pictures: v_z on a fixed blue-white-red scale (m/s, the colour bar), the crack as \
             a black-and-white line, the receiver as an orange dot, the time in each frame; \
             above the injection line only the scattered field. Frame 1: the burst on the \
             crack, which opens on its tensile half-cycles. Frame 2: the reflected burst on \
             its way up, the waves diffracted by the tips spreading behind it. The GIF: every \
             frame, one per half period. The crack's state map: open (gap > 0) or closed (a \
             frictionless crack never sticks) along it (horizontal) against time \
             (downwards). Resolution: {}.",
            fmt_value(lambda_mm),
            fmt_value((z(Plane::Z_C) - z(Plane::Z_L)) * 1e3),
            res.name()
        ),
        vec![panel(
            "reflected burst at the receiver",
            "t (us)",
            "v_z (m/s)",
            vec![Series::new(
                "receiver 2 lambda above the crack",
                &t_us,
                &p.vz,
            )],
        )],
    );
    let frame_caption = |what: &str, t: f64| format!("{what} (t = {} us).", fmt_value(us(t)));
    fig.pictures = vec![
        Picture {
            name: "finite_crack_wavefield_on_crack.png".into(),
            bytes: on.1.clone(),
            caption: frame_caption("Frame 1: the burst on the crack", on.0),
        },
        Picture {
            name: "finite_crack_wavefield_reflected.png".into(),
            bytes: back.1.clone(),
            caption: frame_caption(
                "Frame 2: the reflected burst and the tips' diffracted waves",
                back.0,
            ),
        },
        Picture {
            name: "finite_crack_wavefield.gif".into(),
            bytes: p.gif,
            caption: format!(
                "Every frame ({}, one per half period), looping.",
                p.frames.len()
            ),
        },
        Picture {
            name: "finite_crack_wavefield_crack_state.png".into(),
            bytes: p.state,
            caption: "The crack's state along its length in time: open or closed (frictionless)."
                .into(),
        },
    ];
    fig = fig.compare(format!(
        "energy closure of the run {} (model.md eq. 15.5); {} frames of {PIXELS} px",
        fmt_value(p.closure),
        p.frames.len()
    ));
    fig = fig.compare(cost.line(ctx, res));
    figures.push(fig);
    Ok(())
}

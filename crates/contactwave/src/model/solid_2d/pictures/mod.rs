//! Pictures of a 2D run (docs/scenario.md section 2b `[snapshots]`): the wavefield kept at
//! chosen times and resampled on a pixel grid; with the `plot` feature, the files
//! `snapshots/frame_NNNN.png` (the field, the cracks drawn, a colour bar in m/s, the time in
//! us, axes in mm, receivers and transducers marked), `snapshots/snapshots.gif`,
//! `snapshots/frame_NNNN.vti` with `snapshots/snapshots.pvd` (ParaView), and for every run
//! `receivers.svg`, `spectra.svg`, `crack_state.svg` (each crack's open/stick/slip state
//! along it against time, a vector map with a legend), `crack_map.png` and
//! `crack_state.png` (its normal gap and state as raster maps with colour bars).

use crate::error::Result;
use crate::scenario::snapshots::Snapshots;
use crate::scenario::solid_2d::Solid2dScenario;
use crate::solver::solid_2d::snapshot::{self, Capture, Field, Raster};
use crate::solver::solid_2d::Plan;

mod mesh;
pub use mesh::NodeFrames;

/// Margins and colour bar around a frame's field, px (an upper bound, for the budget).
const FRAME_EXTRA: (f64, f64) = (180.0, 120.0);

/// The least height of a frame's field, px (the colour bar's height, which is the
/// field's): a thin plate's few pixel rows are each drawn several pixels tall.
pub const MIN_FIELD_HEIGHT: usize = 120;

/// How many pixels tall each of a frame's `nz` pixel rows is drawn: 1, or for a field
/// lower than [`MIN_FIELD_HEIGHT`] the least whole number that makes it that tall (the
/// depth drawn stretched by as much; the raster, the VTK files and Python's arrays keep
/// square pixels).
pub fn row_height(nz: usize) -> usize {
    MIN_FIELD_HEIGHT.div_ceil(nz.max(1))
}

/// The snapshots of a run: the frames on their pixel grid and how they are drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshots2d {
    /// Times of the frames, s (the half levels nearest the times asked for).
    pub times: Vec<f64>,
    /// The value drawn: `magnitude`, `vx`, `vz` or `vy`.
    pub field: String,
    /// The frames, `[frame][iz][ix]`, m/s, with their pixel-centre coordinates (m).
    pub raster: Raster,
    /// The colour scale, m/s: `[0, scale]` for the magnitude, `[-scale, scale]` for a
    /// component (the same for every frame).
    pub scale: f64,
    /// The value is signed (a component): a diverging colour map.
    pub signed: bool,
    /// Write the GIF.
    pub gif: bool,
    /// Write the VTK files.
    pub vtk: bool,
    /// On a mesh: the frames at its nodes, for ParaView's `.vtu` files.
    pub nodes: Option<mesh::NodeFrames>,
}

impl Solid2dScenario {
    /// Before a run: check the snapshots' memory against the budget (the key named is the
    /// one that sets their number) and have `plan` keep the fields at their steps.
    pub(crate) fn prepare_snapshots<L>(&self, plan: &mut Plan<L>) -> Result<()> {
        let len = plan.components * plan.mesh.n_nodes;
        let size = [self.problem.width, self.problem.depth()];
        if let Some(steps) = self.snapshot_steps(plan.dt, plan.steps, len, size, 0.0)? {
            plan.capture_at(steps);
        }
        Ok(())
    }

    /// The steps of the snapshots of a run of `steps` steps of `dt` (s) whose field has
    /// `len` values, drawn over a box of `size` (m), with `per_value` more bytes a field
    /// value held for each frame (a mesh's ParaView files), once their memory is checked
    /// against the budget; `None` without `[snapshots]`.
    pub(crate) fn snapshot_steps(
        &self,
        dt: f64,
        steps: usize,
        len: usize,
        size: [f64; 2],
        per_value: f64,
    ) -> Result<Option<Vec<usize>>> {
        let Some(s) = &self.snapshots else {
            return Ok(None);
        };
        let steps: Vec<usize> = s
            .times
            .iter()
            .map(|&t| snapshot::step_at(t, dt, steps))
            .collect();
        let frames = steps.len() as f64;
        let [width, depth] = size;
        let nx = s.pixels as f64;
        let nz = (nx * depth / width).round().max(1.0);
        // the kept fields, their pixels, and the pictures (RGB and RGBA for the GIF), with
        // the files all held until written: each frame's PNG (at most about 3 bytes a
        // pixel) and `.vti` (base64 of float64: about 11 bytes a pixel)
        let drawn = nz * row_height(nz as usize) as f64;
        let pictures = (nx + FRAME_EXTRA.0) * (drawn + FRAME_EXTRA.1) * 10.0;
        let vti = if s.vtk { 11.0 } else { 0.0 };
        let vtu = if s.vtk { per_value * len as f64 } else { 0.0 };
        let bytes =
            Capture::bytes(steps.len(), len) + frames * (nx * nz * (16.0 + vti) + pictures + vtu);
        let change = if s.key == "snapshots.every" {
            "raise `snapshots.every` or lower `snapshots.pixels`"
        } else {
            "give fewer `snapshots.times` or lower `snapshots.pixels`"
        };
        // (the value as given: `every`, the first frame's time, or the number of `times`)
        let value = match s.times.first() {
            Some(every) if s.key == "snapshots.every" => {
                format!("{every:e} s ({} frames)", steps.len())
            }
            _ => format!("{} times", steps.len()),
        };
        crate::budget::check_or(
            &self.file,
            s.key,
            value,
            bytes,
            &format!(
                "{} snapshots of {len} values and {} x {} pixels",
                steps.len(),
                nx,
                nz
            ),
            change,
        )?;
        Ok(Some(steps))
    }

    /// After a run: the kept fields on the pixel grid.
    pub(crate) fn snapshots_of<L>(&self, plan: &Plan<L>, capture: &Capture) -> Option<Snapshots2d> {
        let s: &Snapshots = self.snapshots.as_ref()?;
        let size = [self.problem.width, self.problem.depth()];
        let raster = snapshot::raster(
            &plan.mesh,
            plan.components,
            capture,
            s.field,
            s.pixels,
            size,
        );
        Some(Self::snapshots_2d(s, capture.times.clone(), raster, None))
    }

    /// The snapshots of frames at `times` (s) on their pixel grid (and on a mesh, its
    /// nodes), their colour scale fixed or the largest value.
    fn snapshots_2d(
        s: &Snapshots,
        times: Vec<f64>,
        raster: Raster,
        nodes: Option<mesh::NodeFrames>,
    ) -> Snapshots2d {
        // (NaN: a pixel outside a mesh's specimen)
        let largest = raster
            .values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |a, b| a.max(b.abs()));
        let scale = s.scale.unwrap_or(if largest > 0.0 { largest } else { 1.0 });
        Snapshots2d {
            times,
            field: s.field_name.clone(),
            raster,
            scale,
            signed: s.field != Field::Magnitude,
            gif: s.gif,
            vtk: s.vtk,
            nodes,
        }
    }
}

#[cfg(feature = "plot")]
pub(crate) use files::{binary_files, text_files};

#[cfg(feature = "plot")]
mod files {
    use super::*;
    use crate::model::solid_2d::Solid2dResult;
    use crate::render::picture::{self, Heatmap};
    use crate::render::svg::{figure, Panel, Series};
    use crate::render::{vtk, BinaryFile, OutputFile};
    use crate::solver::solid_2d::SourceKind;

    /// Frame delay of the GIF, ms.
    const GIF_DELAY_MS: u32 = 150;

    fn frame_name(k: usize, ext: &str) -> String {
        format!("snapshots/frame_{k:04}.{ext}")
    }

    /// The label of the drawn value with its unit.
    fn field_label(s: &Snapshots2d) -> String {
        match s.field.as_str() {
            "magnitude" => "|v| (m/s)".into(),
            f => format!("{f} (m/s)"),
        }
    }

    /// The picture of frame `k`: the field in mm, the cracks, receivers and transducers;
    /// a thin plate's rows drawn [`row_height`] pixels tall, said in the title.
    fn frame(r: &Solid2dResult, s: &Snapshots2d, k: usize) -> image::RgbImage {
        let mm = 1e3;
        let (nx, nz) = (s.raster.x.len(), s.raster.z.len());
        let (width, depth) = (r.geometry.width, r.geometry.depth);
        let rows = row_height(nz);
        let field = s.raster.frame(k);
        let stretched: Vec<f64>;
        let (values, title) = if rows > 1 {
            stretched = field
                .chunks_exact(nx.max(1))
                .flat_map(|row| std::iter::repeat_n(row, rows).flatten().copied())
                .collect();
            (
                stretched.as_slice(),
                format!(
                    "t = {:.2} \u{b5}s (depth stretched {rows}x)",
                    s.times[k] * 1e6
                ),
            )
        } else {
            (field, format!("t = {:.2} \u{b5}s", s.times[k] * 1e6))
        };
        let [x0, z0] = r.geometry.origin;
        let seg = |c: &[f64; 4]| [(c[0] * mm, c[1] * mm), (c[2] * mm, c[3] * mm)];
        let lines = if r.geometry.crack_paths.is_empty() {
            r.geometry.cracks.iter().map(seg).collect()
        } else {
            (r.geometry.crack_paths.iter())
                .flat_map(|p| {
                    p.windows(2)
                        .map(|w| seg(&[w[0][0], w[0][1], w[1][0], w[1][1]]))
                })
                .collect()
        };
        let h = Heatmap {
            nx,
            nz: nz * rows,
            values,
            x_range: (x0 * mm, (x0 + width) * mm),
            y_range: (z0 * mm, (z0 + depth) * mm),
            scale: if s.signed {
                (-s.scale, s.scale)
            } else {
                (0.0, s.scale)
            },
            diverging: s.signed,
            title,
            xlabel: "x (mm)".into(),
            ylabel: "z (mm)".into(),
            bar_label: field_label(s),
            boundaries: r.geometry.layer_boundaries.iter().map(|z| z * mm).collect(),
            lines,
            outline: r.geometry.outline.iter().map(seg).collect(),
            marks: r
                .geometry
                .receivers
                .iter()
                .chain(&r.geometry.stress_receivers)
                .map(|p| (p[0] * mm, p[1] * mm))
                .collect(),
            sources: r.geometry.sources.iter().map(seg).collect(),
            classes: Vec::new(),
        };
        picture::heatmap(&h)
    }

    /// The crack's normal gap (nm; `state` false) or its contact state (open, stick, slip;
    /// open or closed on a frictionless crack; `state` true) along it (mm) against time
    /// (us, downwards).
    fn crack_map(r: &Solid2dResult, i: usize, state: bool) -> image::RgbImage {
        let c = &r.output.cracks[i];
        // an antiplane crack never opens: its map is the jump of u_y across it (signed)
        let antiplane = r.component_names == ["y"];
        let (field, unit) = if state {
            (&c.state, 1.0)
        } else if antiplane {
            (&c.tangential_gap, 1e9)
        } else {
            (&c.normal_gap, 1e9)
        };
        let (n, m) = (c.position.len(), c.time.len());
        let (nx, nz) = (600usize, 400usize);
        let mut values = vec![0.0; nx * nz];
        // tip to tip, as crack_state.svg: a pixel shows its nearest node (the tips are welded)
        let (p0, p1) = match r.geometry.cracks.get(i) {
            Some(&[x0, z0, x1, z1]) if c.points.is_empty() => (0.0, (x1 - x0).hypot(z1 - z0)),
            _ => (
                c.position.first().copied().unwrap_or(0.0),
                c.position.last().copied().unwrap_or(1.0),
            ),
        };
        let t1 = c.time.last().copied().unwrap_or(1.0);
        // nearest record and point of each pixel: the map shows the data as recorded
        for iz in 0..nz {
            let t = (iz as f64 + 0.5) / nz as f64 * t1;
            let k = c.time.partition_point(|&v| v < t).min(m.saturating_sub(1));
            for ix in 0..nx {
                let p = p0 + (ix as f64 + 0.5) / nx as f64 * (p1 - p0);
                let j = c
                    .position
                    .partition_point(|&v| v < p)
                    .min(n.saturating_sub(1));
                let j = if j > 0 && (p - c.position[j - 1]) < (c.position[j] - p) {
                    j - 1
                } else {
                    j
                };
                values[iz * nx + ix] = field.get(k * n + j).copied().unwrap_or(0.0) * unit;
            }
        }
        let classes = states(r, i);
        if state {
            // the picture's classes are drawn by their index: a state's value -> its row
            for v in &mut values {
                *v = classes.iter().position(|c| c.0 == *v).unwrap_or(0) as f64;
            }
        }
        let top = if state {
            (classes.len() - 1) as f64
        } else {
            values.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
        };
        let (title, bar) = if state {
            ("contact state", "state")
        } else if antiplane {
            ("tangential gap [u_y]", "gap (nm)")
        } else {
            ("normal gap", "gap (nm)")
        };
        let top = if top > 0.0 { top } else { 1.0 };
        let signed = antiplane && !state;
        // the states in the colours of crack_state.svg, named as in its legend
        let classes = if state {
            (classes.iter())
                .map(|(_, name, (r, g, b))| {
                    (
                        name.split(' ').next().unwrap_or(name).to_string(),
                        [*r, *g, *b],
                    )
                })
                .collect()
        } else {
            Vec::new()
        };
        picture::heatmap(&Heatmap {
            nx,
            nz,
            values: &values,
            x_range: (p0 * 1e3, p1 * 1e3),
            y_range: (0.0, t1 * 1e6),
            scale: (if signed { -top } else { 0.0 }, top),
            diverging: signed,
            title: format!("crack {i}: {title}"),
            xlabel: "position along the crack (mm)".into(),
            ylabel: "t (\u{b5}s)".into(),
            bar_label: bar.into(),
            classes,
            ..Default::default()
        })
    }

    /// The PNG frames, the GIF and the crack maps.
    pub(crate) fn binary_files(r: &Solid2dResult) -> Result<Vec<BinaryFile>> {
        let mut out = Vec::new();
        if let Some(s) = &r.snapshots {
            let frames: Vec<image::RgbImage> = (0..s.times.len()).map(|k| frame(r, s, k)).collect();
            for (k, f) in frames.iter().enumerate() {
                let name = frame_name(k, "png");
                out.push(BinaryFile {
                    bytes: picture::png(&name, f)?,
                    name,
                });
            }
            if s.gif && !frames.is_empty() {
                let name = "snapshots/snapshots.gif".to_string();
                out.push(BinaryFile {
                    bytes: picture::gif(&name, &frames, GIF_DELAY_MS)?,
                    name,
                });
            }
        }
        for i in 0..r.output.cracks.len() {
            if r.output.cracks[i].time.is_empty() {
                continue;
            }
            for (stem, state) in [("crack_map", false), ("crack_state", true)] {
                let name = if i == 0 {
                    format!("{stem}.png")
                } else {
                    format!("{stem}_{i}.png")
                };
                out.push(BinaryFile {
                    bytes: picture::png(&name, &crack_map(r, i, state))?,
                    name,
                });
            }
        }
        Ok(out)
    }

    /// The receivers' traces for the figures: per receiver its title, axis label, kind
    /// (0 velocity, 1 stress: the spectra are in dB re. the largest of their kind) and
    /// components (label, values: m/s, or MPa for stresses). At most [`MAX_PANELS`]
    /// receivers, evenly spread over a longer list (velocity receivers, then stress ones;
    /// the first and the last included): every trace is in `receivers.csv`.
    #[allow(clippy::type_complexity)]
    fn traces(r: &Solid2dResult) -> Vec<(String, &'static str, usize, Vec<(String, Vec<f64>)>)> {
        let o = &r.output;
        let nv = r.receivers.len();
        let n = nv + r.stress_receivers.len();
        let keep: Vec<usize> = if n <= MAX_PANELS {
            (0..n).collect()
        } else {
            (0..MAX_PANELS)
                .map(|k| (k * (n - 1) + (MAX_PANELS - 1) / 2) / (MAX_PANELS - 1))
                .collect()
        };
        keep.into_iter()
            .map(|j| {
                if j < nv {
                    let comps = r.component_names.iter().enumerate();
                    (
                        format!("receiver {}", r.receivers[j]),
                        "velocity (m/s)",
                        0,
                        comps
                            .map(|(c, comp)| (format!("v{comp}"), o.trace(j, c).to_vec()))
                            .collect(),
                    )
                } else {
                    let i = j - nv;
                    let comps = r.stress_component_names.iter().enumerate();
                    (
                        format!("stress receiver {}", r.stress_receivers[i]),
                        "stress (MPa)",
                        1,
                        comps
                            .map(|(c, comp)| {
                                let mpa = o.stress_trace(i, c).iter().map(|x| x * 1e-6).collect();
                                (format!("s{comp}"), mpa)
                            })
                            .collect(),
                    )
                }
            })
            .collect()
    }

    /// The most receivers `receivers.svg` and `spectra.svg` draw, one panel each.
    pub(super) const MAX_PANELS: usize = 16;

    /// The crack states of `crack.csv` with their legend labels and colours.
    pub(super) const STATES: [(f64, &str, (u8, u8, u8)); 3] = [
        (0.0, "open", (214, 39, 40)),
        (1.0, "stick", (31, 119, 180)),
        (2.0, "slip", (255, 187, 60)),
    ];

    /// The states of a frictionless crack: open, or closed (its state 2, which a crack
    /// with friction records for slip; it never sticks).
    pub(super) const FRICTIONLESS_STATES: [(f64, &str, (u8, u8, u8)); 2] =
        [STATES[0], (2.0, "closed (frictionless)", (150, 150, 150))];

    /// The state classes of crack `i` of `r`.
    fn states(r: &Solid2dResult, i: usize) -> &'static [(f64, &'static str, (u8, u8, u8))] {
        if r.geometry.frictionless.get(i).copied().unwrap_or(false) {
            &FRICTIONLESS_STATES
        } else {
            &STATES
        }
    }

    /// `receivers.svg` and `spectra.svg` (every velocity and stress receiver, one panel
    /// each), `crack_state.svg` (each crack's state along it against time), and the VTK
    /// files of the snapshots.
    pub(crate) fn text_files(r: &Solid2dResult, f0: f64) -> Result<Vec<OutputFile>> {
        let o = &r.output;
        let mut out = Vec::new();
        let us: Vec<f64> = o.time.iter().map(|t| t * 1e6).collect();
        let traces = traces(r);
        if !traces.is_empty() && !o.time.is_empty() {
            let panels: Vec<Panel> = traces
                .iter()
                .map(|(title, ylabel, _, comps)| Panel {
                    title: title.clone(),
                    xlabel: "t (\u{b5}s)".into(),
                    ylabel: (*ylabel).into(),
                    series: comps
                        .iter()
                        .map(|(label, y)| Series::new(label.clone(), &us, y))
                        .collect(),
                    markers: Vec::new(),
                })
                .collect();
            out.push(OutputFile::new(
                "receivers.svg",
                figure("receivers.svg", 900, &panels)?,
            ));
            // spectra in dB re. the largest magnitude of their kind, markers at n f0
            let f_max = 6.0 * f0;
            let spectra: Vec<Vec<(Vec<f64>, Vec<f64>)>> = traces
                .iter()
                .map(|(_, _, _, comps)| {
                    comps
                        .iter()
                        .map(|(_, y)| {
                            let s = crate::analysis::with_analyzer(|a| a.spectrum(y, o.dt, f_max));
                            (s.frequency, s.magnitude)
                        })
                        .collect()
                })
                .collect();
            let mut top = [f64::MIN_POSITIVE; 2];
            for (tr, sp) in traces.iter().zip(&spectra) {
                for (_, m) in sp {
                    top[tr.2] = m.iter().fold(top[tr.2], |a, &b| a.max(b.abs()));
                }
            }
            let panels: Vec<Panel> = traces
                .iter()
                .zip(&spectra)
                .map(|((title, _, kind, comps), sp)| Panel {
                    title: format!("{title} (dashed: harmonics n f0)"),
                    xlabel: "frequency (MHz)".into(),
                    ylabel: format!(
                        "magnitude (dB re. the largest {})",
                        if *kind == 0 { "velocity" } else { "stress" }
                    ),
                    series: sp
                        .iter()
                        .zip(comps)
                        .map(|((f, m), (label, _))| {
                            let mhz: Vec<f64> = f.iter().map(|v| v * 1e-6).collect();
                            let db: Vec<f64> = m
                                .iter()
                                .map(|v| (20.0 * (v.abs() / top[*kind]).log10()).max(-160.0))
                                .collect();
                            Series::new(label.clone(), &mhz, &db)
                        })
                        .collect(),
                    markers: (1..=5).map(|n| n as f64 * f0 * 1e-6).collect(),
                })
                .collect();
            out.push(OutputFile::new(
                "spectra.svg",
                figure("spectra.svg", 900, &panels)?,
            ));
        }
        // each crack's open/stick/slip state along it against time
        for (i, c) in o.cracks.iter().enumerate() {
            if c.time.is_empty() || c.position.is_empty() {
                continue;
            }
            let name = if i == 0 {
                "crack_state.svg".to_string()
            } else {
                format!("crack_state_{i}.svg")
            };
            let mm: Vec<f64> = c.position.iter().map(|p| p * 1e3).collect();
            let us: Vec<f64> = c.time.iter().map(|t| t * 1e6).collect();
            let map = crate::render::svg::StateMap {
                title: format!("crack {i}: contact state"),
                xlabel: "position along the crack (mm)".into(),
                ylabel: "t (\u{b5}s)".into(),
                positions: &mm,
                times: &us,
                states: &c.state,
                classes: states(r, i),
            };
            out.push(OutputFile::new(
                &name,
                crate::render::svg::state_map(&name, &map)?,
            ));
        }
        if let Some((s, nodes)) = r
            .snapshots
            .as_ref()
            .and_then(|s| Some((s, s.nodes.as_ref()?)))
        {
            // a mesh: the nodal fields on the GLL sub-cells
            let mut entries = Vec::new();
            for (k, &t) in s.times.iter().enumerate() {
                let name = frame_name(k, "vtu");
                out.push(OutputFile::new(
                    &name,
                    super::mesh::vtu(&name, s, nodes, k)?,
                ));
                entries.push((t, name.trim_start_matches("snapshots/").to_string()));
            }
            out.push(OutputFile::new(
                "snapshots/snapshots.pvd",
                vtk::collection(&entries),
            ));
        } else if let Some(s) = r.snapshots.as_ref().filter(|s| s.vtk) {
            let (x, z) = (&s.raster.x, &s.raster.z);
            let (nx, nz) = (x.len(), z.len());
            let dx = if nx > 1 { x[1] - x[0] } else { 2.0 * x[0] };
            let dz = if nz > 1 { z[1] - z[0] } else { 2.0 * z[0] };
            let depth = r.geometry.depth;
            let mut entries = Vec::new();
            for (k, &t) in s.times.iter().enumerate() {
                // VTK's y is the height above the bottom face (y = depth - z): its rows
                // go from the bottom up
                let f = s.raster.frame(k);
                let mut values = Vec::with_capacity(nx * nz);
                for iz in (0..nz).rev() {
                    values.extend_from_slice(&f[iz * nx..(iz + 1) * nx]);
                }
                let name = frame_name(k, "vti");
                let text = vtk::image_data(
                    &name,
                    &s.field,
                    nx,
                    nz,
                    [x[0], depth - z[nz - 1]],
                    [dx, dz],
                    values,
                )?;
                entries.push((t, name.trim_start_matches("snapshots/").to_string()));
                out.push(OutputFile::new(&name, text));
            }
            out.push(OutputFile::new(
                "snapshots/snapshots.pvd",
                vtk::collection(&entries),
            ));
        }
        Ok(out)
    }

    /// Transducer apertures as segments `[x0, z, x1, z]`, m.
    pub(crate) fn apertures(
        sources: &[crate::solver::solid_2d::Source],
        depth: f64,
    ) -> Vec<[f64; 4]> {
        sources
            .iter()
            .filter_map(|s| match s.kind {
                SourceKind::Traction { top, x0, x1, .. } => {
                    let z = if top { 0.0 } else { depth };
                    Some([x0, z, x1, z])
                }
                SourceKind::Force { .. } | SourceKind::PlaneWave { .. } => None,
            })
            .collect()
    }
}

/// What the pictures draw besides the field: the model's size, the cracks, receivers and
/// transducer apertures, m.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Geometry {
    /// The top left corner of the drawn box `[x, z]`, m (the rectangle's: `[0, 0]`; a
    /// mesh's: its nodes' least x and z).
    pub origin: [f64; 2],
    /// Width, m.
    pub width: f64,
    /// Depth, m.
    pub depth: f64,
    /// Cracks `[x0, z0, x1, z1]` (a mesh's: the chord from end to end).
    pub cracks: Vec<[f64; 4]>,
    /// A mesh's cracks as drawn: each one's points from end to end `[x, z]` (empty on the
    /// rectangle: its cracks are straight).
    pub crack_paths: Vec<Vec<[f64; 2]>>,
    /// A mesh's outline, segments `[x0, z0, x1, z1]` (its sides, holes and crack faces;
    /// empty on the rectangle).
    pub outline: Vec<[f64; 4]>,
    /// Whether each crack is frictionless (friction coefficient 0): its closed points
    /// slide freely, never stick, and the state maps name them `closed`, not `slip`.
    pub frictionless: Vec<bool>,
    /// Depths of the boundaries between layers, m.
    pub layer_boundaries: Vec<f64>,
    /// Velocity receivers `[x, z]`.
    pub receivers: Vec<[f64; 2]>,
    /// Stress receivers `[x, z]`.
    pub stress_receivers: Vec<[f64; 2]>,
    /// Transducer apertures `[x0, z, x1, z]`.
    pub sources: Vec<[f64; 4]>,
}

impl Geometry {
    /// The geometry of a scenario.
    pub fn of(s: &Solid2dScenario) -> Geometry {
        let p = &s.problem;
        let depth = p.depth();
        Geometry {
            origin: [0.0, 0.0],
            width: p.width,
            depth,
            crack_paths: Vec::new(),
            outline: Vec::new(),
            cracks: p
                .cracks
                .iter()
                .map(|c| {
                    if c.full_width {
                        [0.0, c.start[1], p.width, c.start[1]]
                    } else {
                        [c.start[0], c.start[1], c.end[0], c.end[1]]
                    }
                })
                .collect(),
            frictionless: p
                .cracks
                .iter()
                .map(|c| c.law.tangential.branch.friction() == 0.0)
                .collect(),
            layer_boundaries: p
                .layers
                .iter()
                .map(|l| l.bottom)
                .take(p.layers.len().saturating_sub(1))
                .collect(),
            receivers: p.receivers.clone(),
            stress_receivers: s.stress_points.clone(),
            #[cfg(feature = "plot")]
            sources: files::apertures(&p.sources, depth),
            #[cfg(not(feature = "plot"))]
            sources: Vec::new(),
        }
    }
}

#[cfg(all(test, feature = "plot"))]
mod tests;

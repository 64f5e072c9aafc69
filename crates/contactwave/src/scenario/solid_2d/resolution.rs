//! How well the mesh resolves each crack of a 2D scenario (docs/model.md section 15.4,
//! "Cracks"): its elements and split nodes, known before the run, and the warning of a
//! crack too short for the element size.
//!
//! The default element size comes from the bulk waves' dispersion alone (at the highest
//! analysed harmonic, `model.harmonic`: 1.18 S wavelengths at order 6). The convergence
//! study of model.md 15.4 (the plate of `plate_crack_quick.toml`, cracks 0.5 to 8 mm long,
//! the element size refined sixfold from its default, receivers on mesh nodes) gives the
//! criterion: a crack shorter than [`CRACK_ELEMENT_SIZES`] element size (`L < h`) is
//! under-resolved, its own second harmonic (pulse inversion) 2.4 to 10 % off the finest
//! mesh's at every receiver and every such level (the elements beside a crack are up to
//! `model.element_size` tall whatever its length: a 1 mm crack under the default 1.85 mm
//! elements is 3.5 to 4.7 % low). From one element size on, the error no longer depends on
//! the crack's length: 0.2 to 5 % at the default mesh, within about 2 % from 1.5 times finer.
//!
//! The count of split nodes alone is not the measure: a 0.5 mm crack keeps its 5 split nodes
//! while the element size falls from 1.85 to 0.62 mm, and its `A2/A1` still moves by 7 %.

use super::{Solid2dScenario, DEFAULT_HARMONIC};
use crate::scenario::Warning;
use crate::solver::solid_2d::{mesh, Side, WaveType};

/// Fewest element sizes (`model.element_size`) a crack is long, a ratio: shorter, its
/// harmonics are not converged (docs/model.md section 15.4).
pub const CRACK_ELEMENT_SIZES: f64 = 1.0;

/// How the mesh resolves one crack (before the run: from the mesh lines and the element
/// size, as the solver builds the mesh).
#[derive(Debug, Clone, PartialEq)]
pub struct CrackResolution {
    /// Index of the crack (`crack.<i>`).
    pub crack: usize,
    /// Length, m.
    pub length: f64,
    /// Across the whole width (a plane interface: no tips, not judged).
    pub full_width: bool,
    /// Elements along the crack.
    pub elements: usize,
    /// Split nodes (each two nodes, one per face): the nodes strictly between welded tips,
    /// an open end (a mouth on a free side) included, as the solver's mesh has them.
    pub split_nodes: usize,
    /// Widest element along the crack, m.
    pub widest: f64,
    /// The element size (`model.element_size`, or its default), m.
    pub element_size: f64,
    /// S wavelength at the highest analysed harmonic in the slowest layer the crack
    /// touches, m (NaN without a known fundamental).
    pub wavelength: f64,
}

impl CrackResolution {
    /// The crack's length over the element size (`L / h`).
    pub fn element_sizes(&self) -> f64 {
        self.length / self.element_size
    }

    /// The largest `model.element_size` that resolves the crack, m: its length over
    /// [`CRACK_ELEMENT_SIZES`].
    pub fn largest_element_size(&self) -> f64 {
        self.length / CRACK_ELEMENT_SIZES
    }
}

impl Solid2dScenario {
    /// How the mesh resolves each crack ([`CrackResolution`], in the order of the file):
    /// empty where the mesh lines cannot be found (an invalid problem, which the run refuses
    /// with its own error).
    ///
    /// ```
    /// use contactwave::scenario::solid_2d::Solid2dScenario;
    /// let m = contactwave::model::load(std::path::Path::new(concat!(
    ///     env!("CARGO_MANIFEST_DIR"),
    ///     "/../../examples/solid_2d/plate_crack_quick.toml"
    /// )))
    /// .unwrap()
    /// .base()
    /// .unwrap();
    /// let s = m.as_any().downcast_ref::<Solid2dScenario>().unwrap();
    /// let c = &s.crack_resolution()[0];
    /// // the 2 mm crack under the default 1.85 mm elements: two elements, 2 x 6 - 1 split nodes
    /// assert_eq!((c.elements, c.split_nodes), (2, 11));
    /// ```
    pub fn crack_resolution(&self) -> Vec<CrackResolution> {
        if self.mesh.is_some() {
            return Vec::new(); // (the rectangle's mesh lines; a mesh's are its own)
        }
        let p = &self.problem;
        let Ok((xs, zs)) = p.validate(&self.file) else {
            return Vec::new();
        };
        let depth = p.depth();
        let h = p.element_size;
        let x_edges = mesh::edges(p.width, &xs, h);
        let z_edges = mesh::edges(depth, &zs, h);
        let f_max = self.spec.model.harmonic.unwrap_or(DEFAULT_HARMONIC) * self.f0;
        let free = |s: Side| s == Side::Free;
        p.cracks
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let horizontal = c.full_width || c.start[1] == c.end[1];
                let (edges, a, b) = if horizontal {
                    (&x_edges, c.start[0], c.end[0])
                } else {
                    (&z_edges, c.start[1], c.end[1])
                };
                let (ia, ib) = if c.full_width {
                    (0, edges.len() - 1)
                } else {
                    let (ia, ib) = (mesh::edge_index(edges, a), mesh::edge_index(edges, b));
                    (ia.min(ib), ia.max(ib))
                };
                let elements = ib - ia;
                let widest = edges[ia..=ib]
                    .windows(2)
                    .map(|w| w[1] - w[0])
                    .fold(0.0, f64::max);
                // an open end (a mouth on a free side) is split too
                let mouth = |q: [f64; 2]| {
                    if horizontal {
                        (q[0] == 0.0 || q[0] == p.width) && free(p.sides)
                    } else {
                        (q[1] == 0.0 && free(p.top)) || (q[1] == depth && free(p.bottom))
                    }
                };
                let split_nodes = if c.full_width {
                    // every node of the line; periodic sides join its two ends
                    elements * p.order + usize::from(p.sides != Side::Periodic)
                } else {
                    (elements * p.order).saturating_sub(1)
                        + usize::from(mouth(c.start))
                        + usize::from(mouth(c.end))
                };
                // the slowest S wave of the layers the crack touches
                let (z0, z1) = (c.start[1].min(c.end[1]), c.start[1].max(c.end[1]));
                let mut top = 0.0;
                let cs = p
                    .layers
                    .iter()
                    .filter(|l| {
                        let touches = l.bottom >= z0 && top <= z1;
                        top = l.bottom;
                        touches
                    })
                    .map(|l| l.material.s_speed)
                    .fold(f64::INFINITY, f64::min);
                let wavelength = if f_max > 0.0 && f_max.is_finite() && cs.is_finite() {
                    cs / f_max
                } else {
                    f64::NAN
                };
                CrackResolution {
                    crack: i,
                    length: if c.full_width {
                        p.width
                    } else {
                        (c.end[0] - c.start[0]).abs() + (c.end[1] - c.start[1]).abs()
                    },
                    full_width: c.full_width,
                    elements,
                    split_nodes,
                    widest,
                    element_size: h,
                    wavelength,
                }
            })
            .collect()
    }

    /// A warning for each crack (not a full-width interface) shorter than
    /// [`CRACK_ELEMENT_SIZES`] element size, whose harmonics the mesh does not resolve
    /// (docs/model.md section 15.4). Its key is `model.element_size`, with the largest size
    /// that resolves the crack.
    pub fn crack_resolution_warnings(&self) -> Vec<Warning> {
        if self.mesh.is_some() {
            return Vec::new();
        }
        let p = &self.problem;
        let harmonic = self.spec.model.harmonic.unwrap_or(DEFAULT_HARMONIC);
        let wave = if p.wave == WaveType::Sh { "SH" } else { "S" };
        let chosen = self.spec.model.element_size.is_some();
        let mut out = Vec::new();
        for c in self.crack_resolution() {
            if c.full_width || c.element_sizes() >= CRACK_ELEMENT_SIZES {
                continue;
            }
            let size = if chosen {
                String::new()
            } else if c.wavelength.is_finite() {
                format!(
                    ", the default: {:.2} {wave} wavelengths at {} f0, model.harmonic",
                    c.element_size / c.wavelength,
                    crate::human::number(harmonic)
                )
            } else {
                ", the default".into()
            };
            out.push(Warning {
                blocking: false,
                file: self.file.clone(),
                field: "model.element_size".into(),
                value: format!("{:.3e} m", c.element_size),
                reason: format!(
                    "crack.{} ({:.3e} m long, {} split nodes) is shorter than the element size \
                     ({:.2} of it{size}): the elements beside it are that tall, and its harmonics \
                     A_n/A1 come out up to 10 % off (model.md 15.4); set model.element_size <= \
                     {:.3e} m, the crack's length (`contactwave convergence` measures what \
                     remains)",
                    c.crack,
                    c.length,
                    c.split_nodes,
                    c.element_sizes(),
                    c.largest_element_size()
                ),
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model;

    /// The plate of `examples/solid_2d/plate_crack_quick.toml` (40 x 10 mm aluminium, a
    /// 1 MHz transducer, `model.harmonic = 2`: 1.85 mm elements by default) with a crack
    /// from x = 19 mm of `length` (m) at depth `z` (m) and `extra` lines in `[model]`.
    fn plate(length: f64, z: f64, extra: &str) -> Solid2dScenario {
        let text = format!(
            r#"
            [model]
            kind = "solid_2d"
            width = 40e-3
            duration = 20e-6
            harmonic = 2
            {extra}
            [[layer]]
            thickness = 10e-3
            material = "aluminium"
            [[crack]]
            start = [19e-3, {z}]
            length = {length}
            vertical = {vertical}
            static_pressure = 1e6
            [[source]]
            x0 = 8e-3
            x1 = 12e-3
            signal = {{ frequency = 1e6, cycles = 5, amplitude = 10e6, window = "hann" }}
            [[receiver]]
            name = "bottom"
            at = [20e-3, 10e-3]
            "#,
            vertical = z == 0.0,
        );
        let m = model::from_toml_str(&text, "plate.toml")
            .and_then(|t| t.base())
            .unwrap_or_else(|e| panic!("{e}"));
        m.as_any()
            .downcast_ref::<Solid2dScenario>()
            .expect("a 2D scenario")
            .clone()
    }

    /// Issue 56 (5): a 1 mm crack under the default 1.85 mm elements is warned about
    /// (shorter than the element size, `model.element_size` named with the size that
    /// resolves it), the 2 mm crack of the example and a 1 mm crack under 0.5 mm elements
    /// are not; known before the run.
    #[test]
    fn a_crack_shorter_than_the_element_size_is_warned_about() {
        let short = plate(1e-3, 5e-3, "");
        let w = short.crack_resolution_warnings();
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].field, "model.element_size");
        assert!(!w[0].blocking);
        assert!(w[0].value.ends_with(" m"), "{}", w[0].value);
        assert!(
            w[0].reason
                .contains("the default: 1.18 S wavelengths at 2 f0"),
            "{}",
            w[0].reason
        );
        assert!(w[0].reason.contains("crack.0"), "{}", w[0].reason);
        assert!(
            w[0].reason.contains("shorter than the element size"),
            "{}",
            w[0].reason
        );
        assert!(
            w[0].reason.contains("model.element_size <= 1.000e-3 m"),
            "{}",
            w[0].reason
        );
        // the scenario's own warnings carry it (what `run` prints and summary.json lists)
        assert!(short
            .warnings()
            .iter()
            .any(|x| x.reason.contains("split nodes")));
        assert!(plate(2e-3, 5e-3, "").crack_resolution_warnings().is_empty());
        let fine = plate(1e-3, 5e-3, "element_size = 0.5e-3");
        assert!(fine.crack_resolution_warnings().is_empty());
        assert!(fine.warnings().is_empty(), "{:?}", fine.warnings());
    }

    /// A crack longer than the element size is not warned about, whatever its split
    /// nodes: a 4 mm crack under the default 1.85 mm elements (3 elements, 17 split nodes),
    /// nor a full-width interface.
    #[test]
    fn a_crack_longer_than_the_element_size_is_not_warned_about() {
        let long = plate(4e-3, 5e-3, "");
        let c = &long.crack_resolution()[0];
        assert_eq!((c.elements, c.split_nodes), (3, 17));
        assert!(c.element_sizes() > 2.0, "{c:?}");
        // the S wavelength at 2 f0 in aluminium, about 1.57 mm
        assert!((c.wavelength - 1.57e-3).abs() < 0.01e-3, "{c:?}");
        assert!(long.crack_resolution_warnings().is_empty());
    }

    /// The split nodes counted before the run are the mesh's: horizontal and vertical
    /// cracks, a mouth on the free top side split too.
    #[test]
    fn split_nodes_are_those_of_the_mesh() {
        for (length, z, extra) in [
            (1e-3, 5e-3, ""),
            (2e-3, 5e-3, ""),
            (3e-3, 5e-3, "element_size = 0.7e-3"),
            (3e-3, 0.0, ""),
            (2.5e-3, 0.0, "order = 4"),
        ] {
            let s = plate(length, z, extra);
            let c = &s.crack_resolution()[0];
            let plan = s.problem.plan(&s.file).unwrap();
            assert_eq!(
                c.split_nodes,
                plan.mesh.splits[0].len(),
                "{length} {z} {extra}"
            );
            assert!((c.length - length).abs() < 1e-15);
        }
    }
}

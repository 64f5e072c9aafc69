//! What a mesh generator gives the general quadrilateral path (docs/model.md section
//! 15.13): control nodes, quadrilaterals of first order (4 corners) or second order (9
//! nodes, curved edges), a material tag per element and named curves (chains of element
//! edges by their end nodes). The Gmsh reader ([`super::gmsh`]) and the structured
//! generator [`QuadInput::grid`] make one; [`super::geometry::Mesh::build`] turns it into
//! the solver's mesh. The solver never asks which generator made it.

/// The element nodes of a quadrilateral in Gmsh's order: corners 0-3 counter-clockwise,
/// then (second order) the mid-edge nodes of edges 0-1, 1-2, 2-3, 3-0 and the centre.
pub type QuadNodes = [u32; 9];

/// A mesh as generated: control nodes, elements, materials and named curves.
#[derive(Debug, Clone, Default)]
pub struct QuadInput {
    /// The file (or generator) it came from, for error messages.
    pub source: String,
    /// Control node coordinates `[x, z]`, m (z into the depth).
    pub nodes: Vec<[f64; 2]>,
    /// The elements' nodes (the last 5 unused for first-order elements).
    pub quads: Vec<QuadNodes>,
    /// Second-order (9-node) elements.
    pub second_order: bool,
    /// Material tag of each element: an index into `materials`.
    pub material: Vec<u16>,
    /// The materials' names (Gmsh physical surfaces).
    pub materials: Vec<String>,
    /// Named curves (Gmsh physical curves): segments `[a, b]` between control nodes (their
    /// end nodes; a second-order segment's middle node is the element's).
    pub curves: Vec<(String, Vec<[u32; 2]>)>,
    /// Named points (Gmsh physical points), m.
    pub points: Vec<(String, [f64; 2])>,
}

impl QuadInput {
    /// The curve named `name`.
    pub fn curve(&self, name: &str) -> Option<&[[u32; 2]]> {
        self.curves
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, s)| s.as_slice())
    }

    /// A structured mesh on the grid lines `xs` x `zs` (m, increasing) mapped by `map`
    /// (`[x, z]` -> `[x', z']`: identity for the rectangle, a rotation, a shear, a bend...)
    /// with elements of first order, or of second order (`second_order`: 9 nodes, each
    /// mapped, so that a nonlinear map curves the edges), one material per row band (`material(z_mid)`, an index into
    /// `materials`), and the named curves: "top" (z = zs[0]), "bottom", "left", "right", and
    /// each `(name, start, end)` of `lines` along grid lines (both ends on grid points; a
    /// horizontal or a vertical run of grid edges).
    pub fn grid(
        xs: &[f64],
        zs: &[f64],
        map: &dyn Fn([f64; 2]) -> [f64; 2],
        materials: Vec<String>,
        material: &dyn Fn(f64) -> u16,
        lines: &[(&str, [f64; 2], [f64; 2])],
        second_order: bool,
    ) -> QuadInput {
        let (nx, nz) = (xs.len(), zs.len());
        // the control grid: every grid line, and the mid-lines of second-order elements
        let q = if second_order { 2 } else { 1 };
        let fine = |v: &[f64]| -> Vec<f64> {
            let mut out = vec![v[0]];
            for w in v.windows(2) {
                if second_order {
                    out.push(0.5 * (w[0] + w[1]));
                }
                out.push(w[1]);
            }
            out
        };
        let (fx, fz) = (fine(xs), fine(zs));
        let fnx = fx.len();
        let cid = |i: usize, j: usize| (j * fnx + i) as u32;
        let id = |i: usize, j: usize| cid(q * i, q * j);
        let mut nodes = Vec::with_capacity(fx.len() * fz.len());
        for &z in &fz {
            for &x in &fx {
                nodes.push(map([x, z]));
            }
        }
        let mut quads = Vec::new();
        let mut mat = Vec::new();
        for j in 0..nz - 1 {
            for i in 0..nx - 1 {
                // counter-clockwise in (x, z) with z down is clockwise on the page; the
                // reader accepts either orientation
                let (a, b) = (2 * i, 2 * j);
                let mids = if second_order {
                    [
                        cid(a + 1, b),
                        cid(a + 2, b + 1),
                        cid(a + 1, b + 2),
                        cid(a, b + 1),
                        cid(a + 1, b + 1),
                    ]
                } else {
                    [0; 5]
                };
                let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                quads.push([
                    c[0], c[1], c[2], c[3], mids[0], mids[1], mids[2], mids[3], mids[4],
                ]);
                mat.push(material(0.5 * (zs[j] + zs[j + 1])));
            }
        }
        let near = |v: &[f64], x: f64| {
            (0..v.len())
                .min_by(|&a, &b| (v[a] - x).abs().total_cmp(&(v[b] - x).abs()))
                .unwrap_or(0)
        };
        let run = |a: [usize; 2], b: [usize; 2]| -> Vec<[u32; 2]> {
            let mut s = Vec::new();
            if a[1] == b[1] {
                let (lo, hi) = (a[0].min(b[0]), a[0].max(b[0]));
                for i in lo..hi {
                    s.push([id(i, a[1]), id(i + 1, a[1])]);
                }
            } else {
                let (lo, hi) = (a[1].min(b[1]), a[1].max(b[1]));
                for j in lo..hi {
                    s.push([id(a[0], j), id(a[0], j + 1)]);
                }
            }
            s
        };
        let mut curves = vec![
            ("top".to_string(), run([0, 0], [nx - 1, 0])),
            ("bottom".to_string(), run([0, nz - 1], [nx - 1, nz - 1])),
            ("left".to_string(), run([0, 0], [0, nz - 1])),
            ("right".to_string(), run([nx - 1, 0], [nx - 1, nz - 1])),
        ];
        for (name, p, q) in lines {
            let a = [near(xs, p[0]), near(zs, p[1])];
            let b = [near(xs, q[0]), near(zs, q[1])];
            curves.push((name.to_string(), run(a, b)));
        }
        QuadInput {
            source: "grid".into(),
            nodes,
            quads,
            second_order,
            material: mat,
            materials,
            curves,
            points: Vec::new(),
        }
    }
}

impl<L: Clone> super::QuadSolid<L> {
    /// The rectangle `p` (free sides, or periodic x sides; no absorbing layers;
    /// transducers, point forces and straight cracks, full-width ones with periodic sides)
    /// on a quadrilateral mesh of its own grid mapped by `map` (a rotation: the same
    /// problem turned; a shear along x keeps periodic sides translates): the general
    /// path's benchmark and its check against the rectangle's run. `None` for what it does
    /// not carry over (rigid or absorbing sides, plane waves, a crack profile).
    pub fn of_rectangle(
        p: &super::super::Solid2d<L>,
        map: &dyn Fn([f64; 2]) -> [f64; 2],
        file: &str,
    ) -> crate::error::Result<Option<Self>>
    where
        L: crate::law::NormalPart + crate::law::TangentialPart,
    {
        use super::super::{Side, SourceKind};
        use super::{QuadCrack, QuadSource, QuadSourceKind};
        let free = [p.top, p.bottom].iter().all(|&s| s == Side::Free);
        let periodic = p.sides == Side::Periodic;
        if !free
            || !(periodic || p.sides == Side::Free)
            || p.cracks.iter().any(|c| c.profile.is_some())
        {
            return Ok(None);
        }
        let plan = p.plan(file)?;
        let (xs, zs) = (plan.mesh.x_edges.clone(), plan.mesh.z_edges.clone());
        drop(plan);
        let mut lines = Vec::new();
        let names: Vec<String> = (0..p.cracks.len()).map(|i| format!("crack{i}")).collect();
        let wedges: Vec<String> = (0..p.sources.len()).map(|i| format!("wedge{i}")).collect();
        for (c, n) in p.cracks.iter().zip(&names) {
            lines.push((n.as_str(), c.start, c.end));
        }
        let depth = p.depth();
        let mut sources = Vec::new();
        for (s, n) in p.sources.iter().zip(&wedges) {
            let kind = match s.kind {
                SourceKind::Force { at, direction } => QuadSourceKind::Force {
                    at: map(at),
                    direction: {
                        let d = map(direction);
                        let o = map([0.0; 2]);
                        [d[0] - o[0], d[1] - o[1]]
                    },
                },
                SourceKind::Traction {
                    top,
                    x0,
                    x1,
                    normal,
                    delay_per_m,
                } => {
                    let z = if top { 0.0 } else { depth };
                    lines.push((n.as_str(), [x0, z], [x1, z]));
                    QuadSourceKind::Traction {
                        curve: n.clone(),
                        normal,
                        delay_per_m,
                    }
                }
                SourceKind::PlaneWave { .. } => return Ok(None),
            };
            sources.push(QuadSource {
                kind,
                signal: s.signal.clone(),
            });
        }
        let layers = p.layers.clone();
        let input = QuadInput::grid(
            &xs,
            &zs,
            map,
            (0..layers.len()).map(|i| format!("layer{i}")).collect(),
            &|z| {
                layers
                    .iter()
                    .position(|l| z < l.bottom)
                    .unwrap_or(layers.len() - 1) as u16
            },
            &lines,
            false,
        );
        Ok(Some(super::QuadSolid {
            input: std::sync::Arc::new(input),
            order: p.order,
            materials: p.layers.iter().map(|l| l.material).collect(),
            wave: p.wave,
            courant: p.courant,
            max_time_step: p.max_time_step,
            boundaries: Vec::new(),
            periodic: if periodic {
                vec![("left".into(), "right".into())]
            } else {
                Vec::new()
            },
            cracks: p
                .cracks
                .iter()
                .zip(&names)
                .map(|(c, n)| QuadCrack {
                    curve: n.clone(),
                    law: c.law.clone(),
                    profile: None,
                })
                .collect(),
            sources,
            receivers: p.receivers.iter().map(|&r| map(r)).collect(),
            stress_receivers: Vec::new(),
            duration: p.duration,
            crack_every: p.crack_every,
        }))
    }
}

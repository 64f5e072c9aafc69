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
    /// The length of each element side between its corners (a straight chord of a curved
    /// side), m: every side of every element, shared ones twice.
    pub fn side_lengths(&self) -> impl Iterator<Item = f64> + '_ {
        self.quads.iter().flat_map(move |q| {
            (0..4).map(move |k| {
                let (a, b) = (
                    self.nodes[q[k] as usize],
                    self.nodes[q[(k + 1) % 4] as usize],
                );
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
        })
    }

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

impl QuadInput {
    /// `count` points (>= 2) evenly spaced along the named curve `name`, by arc length on
    /// the curve itself (a second-order edge's own parabola), from its first end (the end
    /// of smaller x, then z) to its last; a closed curve (a hole's rim) from its point of
    /// smallest x, then z, once around (the last point one spacing short of the first).
    /// Coincident segments (an interface's two faces) count once. `None`: no such curve;
    /// `Err`: a curve that branches or is in pieces (what it is).
    pub fn along(&self, name: &str, count: usize) -> Option<Result<Vec<[f64; 2]>, String>> {
        let segments = self.curve(name)?;
        Some(self.chain_points(segments, count.max(2)))
    }

    fn chain_points(&self, segments: &[[u32; 2]], count: usize) -> Result<Vec<[f64; 2]>, String> {
        use std::collections::HashMap;
        let key = |k: u32| {
            let p = self.nodes[k as usize];
            (p[0].to_bits(), p[1].to_bits())
        };
        // second-order edges' middle nodes, by their corners' positions
        // (a position's bits: coincident nodes of parts meshed apart are one vertex)
        type Vertex = (u64, u64);
        let mut middle: HashMap<(Vertex, Vertex), u32> = HashMap::new();
        if self.second_order {
            for q in &self.quads {
                for k in 0..4 {
                    let (a, b) = (key(q[k]), key(q[(k + 1) % 4]));
                    middle.insert((a.min(b), a.max(b)), q[4 + k]);
                }
            }
        }
        // the segments once each, and the vertices' segments
        let mut seen = std::collections::HashSet::new();
        let mut segs: Vec<[u32; 2]> = Vec::new();
        for s in segments {
            let (a, b) = (key(s[0]), key(s[1]));
            if a != b && seen.insert((a.min(b), a.max(b))) {
                segs.push(*s);
            }
        }
        if segs.is_empty() {
            return Err("a curve without segments".into());
        }
        let mut touching: HashMap<Vertex, Vec<usize>> = HashMap::new();
        for (i, s) in segs.iter().enumerate() {
            for &v in s {
                touching.entry(key(v)).or_default().push(i);
            }
        }
        if touching.values().any(|t| t.len() > 2) {
            return Err("a curve that branches".into());
        }
        let first_of = |cands: &mut dyn Iterator<Item = u32>| {
            cands.min_by(|&a, &b| {
                let (p, q) = (self.nodes[a as usize], self.nodes[b as usize]);
                p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
            })
        };
        let ends: Vec<u32> = segs
            .iter()
            .flatten()
            .copied()
            .filter(|&v| touching[&key(v)].len() == 1)
            .collect();
        let closed = ends.is_empty();
        let start = if closed {
            first_of(&mut segs.iter().flatten().copied())
        } else {
            first_of(&mut ends.iter().copied())
        }
        .ok_or("a curve without segments")?;
        // walk the chain: each segment oriented along it, with its middle node
        let mut path: Vec<[u32; 3]> = Vec::with_capacity(segs.len());
        let mut used = vec![false; segs.len()];
        let mut at = start;
        while let Some(&i) = touching[&key(at)].iter().find(|&&i| !used[i]) {
            used[i] = true;
            let s = segs[i];
            let next = if key(s[0]) == key(at) { s[1] } else { s[0] };
            let (a, b) = (key(at), key(next));
            let mid = middle
                .get(&(a.min(b), a.max(b)))
                .copied()
                .unwrap_or(u32::MAX);
            path.push([at, mid, next]);
            at = next;
        }
        if used.iter().any(|u| !u) {
            return Err("a curve in pieces".into());
        }
        // each segment's map x(r), r in [-1, 1], its length (5-point Gauss-Legendre)
        let point = |seg: &[u32; 3], r: f64| -> [f64; 2] {
            let (a, b) = (self.nodes[seg[0] as usize], self.nodes[seg[2] as usize]);
            if seg[1] == u32::MAX {
                let w = 0.5 * (r + 1.0);
                return [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])];
            }
            let m = self.nodes[seg[1] as usize];
            let (fa, fm, fb) = (0.5 * r * (r - 1.0), 1.0 - r * r, 0.5 * r * (r + 1.0));
            [
                fa * a[0] + fm * m[0] + fb * b[0],
                fa * a[1] + fm * m[1] + fb * b[1],
            ]
        };
        let length = |seg: &[u32; 3]| -> f64 {
            let (a, b) = (self.nodes[seg[0] as usize], self.nodes[seg[2] as usize]);
            if seg[1] == u32::MAX {
                return (b[0] - a[0]).hypot(b[1] - a[1]);
            }
            let m = self.nodes[seg[1] as usize];
            const X: [f64; 5] = [
                -0.906_179_845_938_664,
                -0.538_469_310_105_683,
                0.0,
                0.538_469_310_105_683,
                0.906_179_845_938_664,
            ];
            const W: [f64; 5] = [
                0.236_926_885_056_189,
                0.478_628_670_499_366,
                0.568_888_888_888_889,
                0.478_628_670_499_366,
                0.236_926_885_056_189,
            ];
            X.iter()
                .zip(W)
                .map(|(&r, w)| {
                    let (da, dm, db) = (r - 0.5, -2.0 * r, r + 0.5);
                    let dx = da * a[0] + dm * m[0] + db * b[0];
                    let dz = da * a[1] + dm * m[1] + db * b[1];
                    w * dx.hypot(dz)
                })
                .sum()
        };
        let lengths: Vec<f64> = path.iter().map(length).collect();
        let total: f64 = lengths.iter().sum();
        let spacing = total / if closed { count } else { count - 1 } as f64;
        let mut out = Vec::with_capacity(count);
        let (mut j, mut s0) = (0usize, 0.0f64);
        for k in 0..count {
            let s = k as f64 * spacing;
            while j + 1 < path.len() && s > s0 + lengths[j] {
                s0 += lengths[j];
                j += 1;
            }
            let f = ((s - s0) / lengths[j]).clamp(0.0, 1.0);
            out.push(point(&path[j], 2.0 * f - 1.0));
        }
        Ok(out)
    }
}

impl<L: Clone> super::QuadSolid<L> {
    /// The rectangle `p` (free sides, periodic x sides, or absorbing ones as a PML frame of
    /// the same layers; transducers, point forces and straight cracks, full-width ones with
    /// periodic sides) on a quadrilateral mesh of its own grid mapped by `map` (a rotation:
    /// the same problem turned, where no side absorbs, the frame being Cartesian; a shear
    /// along x keeps periodic sides translates): the general path's benchmark and its check
    /// against the rectangle's run; a plane wave's line is a curve across the width.
    /// `None` for what it does not carry over (rigid sides, a crack profile).
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
        let carried = |s: Side| s == Side::Free || s == Side::Absorbing;
        let periodic = p.sides == Side::Periodic;
        if !carried(p.top)
            || !carried(p.bottom)
            || !(periodic || carried(p.sides))
            || p.cracks.iter().any(|c| c.profile.is_some())
        {
            return Ok(None);
        }
        let plan = p.plan(file)?;
        // the physical rectangle's edges (without the absorbing layers' bands)
        let depth = p.depth();
        let inside = |edges: &[f64], end: f64| -> Vec<f64> {
            let tol = 1e-9 * end;
            edges
                .iter()
                .copied()
                .filter(|&e| e >= -tol && e <= end + tol)
                .collect()
        };
        let (xs, zs) = (
            inside(&plan.mesh.x_edges, p.width),
            inside(&plan.mesh.z_edges, depth),
        );
        drop(plan);
        let mut boundaries = Vec::new();
        for (name, side) in [
            ("top", p.top),
            ("bottom", p.bottom),
            ("left", p.sides),
            ("right", p.sides),
        ] {
            if side == Side::Absorbing {
                boundaries.push((name.to_string(), super::Boundary::Pml));
            }
        }
        let mut lines = Vec::new();
        let names: Vec<String> = (0..p.cracks.len()).map(|i| format!("crack{i}")).collect();
        let wedges: Vec<String> = (0..p.sources.len()).map(|i| format!("wedge{i}")).collect();
        for (c, n) in p.cracks.iter().zip(&names) {
            lines.push((n.as_str(), c.start, c.end));
        }
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
                SourceKind::PlaneWave {
                    incidence,
                    angle,
                    z,
                } => {
                    lines.push((n.as_str(), [0.0, z], [p.width, z]));
                    let (o, d) = (map([0.0; 2]), map([angle.sin(), angle.cos()]));
                    QuadSourceKind::PlaneWave {
                        curve: n.clone(),
                        incidence,
                        angle: (d[0] - o[0]).atan2(d[1] - o[1]),
                    }
                }
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
            boundaries,
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
            pml: Some(p.pml),
        }))
    }
}

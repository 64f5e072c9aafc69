//! A Cartesian PML frame around a mesh (docs/model.md section 15.13, eq. 15.13i): the
//! rectangle's absorbing layers ([`crate::solver::solid_2d::pml`], section 15.7) added
//! outside the mesh's straight sides on its bounding box.
//!
//! Each element edge of a side of kind `pml` is extruded outward into a strip of
//! rectangular elements `t = L / ceil(L / h)` thick (`L` the thickness, `h` the mesh's
//! largest element edge), of the adjacent element's material; where two such sides meet
//! at a corner of the box, a block of square elements fills the corner. The strips'
//! inner nodes are the mesh's own nodes on the side (so the side's GLL nodes must be at
//! the GLL positions of the edge's chord: a straight edge, its second-order mid node at
//! the middle); every other node of the frame is added after the mesh's. The damping is
//! the rectangle's profile of the distance beyond the box, `d(s) = d0 (s / L)^2`; the
//! frame's outer edges are fixed, its ends where the side meets a side of another kind
//! free. What the mesh must provide: the `pml` sides straight on its bounding box
//! (`x = x_min`, `x = x_max`, `z = z_min` or `z = z_max`), reached by no crack or
//! interface, and not ending at a periodic side.

use super::geometry::{Mesh, NodeIndex};
use super::on_boundary;
use crate::error::{Error, Result};
use crate::solver::solid_2d::kernel::{max_frequency, ElementData, Stiffness};
use crate::solver::solid_2d::pml::{self, Band, Pml, Profile};
use crate::solver::solid_2d::Elastic;

/// The absorbing frame of a mesh.
#[derive(Debug)]
pub(super) struct Frame {
    /// The frame's elements and fields.
    pub band: Band,
    /// Nodes added after the mesh's.
    pub added: usize,
    /// Per node (the mesh's, then the added ones): the frame elements' share of its
    /// lumped mass, kg/m.
    pub mass: Vec<f64>,
    /// Added nodes on the frame's outer edges (held fixed).
    pub fixed: Vec<usize>,
    /// The largest angular frequency of the frame's elements alone (an upper bound of
    /// the frame's own `sqrt(lambda_max)` of `M^-1 K`), rad/s.
    pub omega: f64,
    /// Layers of elements across the frame.
    pub layers: usize,
}

/// A side of the mesh's bounding box: x or z, low or high.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct BoxSide {
    /// The coordinate that is constant along it: 0 (x) or 1 (z).
    axis: usize,
    /// The high side (else the low one).
    high: bool,
}

/// One element edge of a `pml` side: its curve, its nodes in increasing order along the side, their
/// coordinate along it (m), and its element's material.
struct Strip<'a> {
    curve: &'a str,
    side: BoxSide,
    nodes: Vec<usize>,
    along: [f64; 2],
    tag: u16,
}

/// The frame of the curves `curves` of `mesh` (their keys `boundary `name``), `pml` thick
/// (cut into elements of at most `h`, m), `materials` by the mesh's tags.
pub(super) fn build(
    mesh: &Mesh,
    curves: &[&str],
    pml: Pml,
    h: f64,
    materials: &[Elastic],
    antiplane: bool,
    file: &str,
) -> Result<Frame> {
    let n = mesh.gll.order;
    let m = n + 1;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &mesh.position {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let diag = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let tol = 1e-9 * diag;
    let l = pml.thickness;
    if !(l > 0.0 && l.is_finite()) {
        return Err(Error::invalid(
            file,
            "model.pml_thickness",
            l,
            "> 0 m, finite",
        ));
    }
    // the strips: each pml edge on a side of the box, its GLL nodes evenly mapped
    let mut strips: Vec<Strip> = Vec::new();
    for name in curves {
        let field = format!("boundary `{name}`");
        let set = on_boundary(mesh, name, &field, file)?;
        for (_, on) in &set.segments {
            let (e, s) = on[0];
            let mut pts: Vec<(usize, [f64; 2])> = (0..=n)
                .map(|k| {
                    let (g, _, _) = mesh.side_point(e as usize, s, k);
                    (g, mesh.position[g])
                })
                .collect();
            let side = (0..2)
                .flat_map(|axis| [false, true].map(|high| BoxSide { axis, high }))
                .find(|b| {
                    let at = if b.high { hi[b.axis] } else { lo[b.axis] };
                    pts.iter().all(|(_, p)| (p[b.axis] - at).abs() <= tol)
                });
            let p0 = pts[0].1;
            let Some(side) = side else {
                return Err(Error::invalid(
                    file,
                    field,
                    format!(
                        "`{name}` off the mesh's bounding box at x = {:.4e} m, z = {:.4e} m",
                        p0[0], p0[1]
                    ),
                    "for a pml frame, a straight side on the bounding box (x or z at its \
                     least or greatest)",
                ));
            };
            let a = 1 - side.axis;
            pts.sort_by(|p, q| p.1[a].total_cmp(&q.1[a]));
            let (s0, s1) = (pts[0].1[a], pts[n].1[a]);
            let uneven = pts.iter().zip(&mesh.gll.points).find(|((_, p), xi)| {
                (p[a] - (s0 + 0.5 * (1.0 + **xi) * (s1 - s0))).abs() > 1e-8 * diag
            });
            if let Some(((_, p), _)) = uneven {
                return Err(Error::invalid(
                    file,
                    field,
                    format!(
                        "an edge whose GLL nodes are not evenly mapped at x = {:.4e} m, \
                         z = {:.4e} m",
                        p[0], p[1]
                    ),
                    "for a pml frame, straight edges with second-order mid nodes at the \
                     middle",
                ));
            }
            strips.push(Strip {
                curve: name,
                side,
                nodes: pts.iter().map(|&(g, _)| g).collect(),
                along: [s0, s1],
                tag: mesh.material[e as usize],
            });
        }
    }
    let has = |side: BoxSide| strips.iter().any(|s| s.side == side);
    // the corners where two pml sides meet: (x side, z side, material)
    let mut corners: Vec<(BoxSide, BoxSide, u16)> = Vec::new();
    for xh in [false, true] {
        for zh in [false, true] {
            let (xs, zs) = (BoxSide { axis: 0, high: xh }, BoxSide { axis: 1, high: zh });
            let (cx, cz) = (
                if xh { hi[0] } else { lo[0] },
                if zh { hi[1] } else { lo[1] },
            );
            let touches = |side: BoxSide, at: f64| {
                strips
                    .iter()
                    .find(|s| s.side == side && s.along.iter().any(|&v| (v - at).abs() <= tol))
            };
            if let (Some(v), Some(_)) = (touches(xs, cz), touches(zs, cx)) {
                corners.push((xs, zs, v.tag));
            }
        }
    }
    let layers = ((l / h) - 1e-9).ceil().max(1.0) as usize;
    let t = l / layers as f64;
    let elements = (strips.len() + corners.len() * layers) * layers;
    // (per point: data, map, damping, 6 stresses, 4 force parts; per node: 10 values)
    let bytes = (elements * m * m) as f64 * (8.0 + 16.0 + 16.0 * 8.0 + 8.0 * 8.0);
    crate::budget::check_or(
        file,
        "model.pml_thickness",
        l,
        bytes,
        &format!("a pml frame of {elements} elements"),
        "a thinner frame",
    )?;
    // the elements: lower corner, size, material
    let mut rects: Vec<([f64; 2], [f64; 2], u16)> = Vec::with_capacity(elements);
    let out = |side: BoxSide, j: usize| {
        if side.high {
            hi[side.axis] + j as f64 * t
        } else {
            lo[side.axis] - (j + 1) as f64 * t
        }
    };
    for s in &strips {
        for j in 0..layers {
            let (across, along) = (out(s.side, j), s.along[0]);
            let size = s.along[1] - s.along[0];
            rects.push(if s.side.axis == 0 {
                ([across, along], [t, size], s.tag)
            } else {
                ([along, across], [size, t], s.tag)
            });
        }
    }
    for &(xs, zs, tag) in &corners {
        for j in 0..layers {
            for i in 0..layers {
                rects.push(([out(xs, i), out(zs, j)], [t, t], tag));
            }
        }
    }
    // the nodes: the strips' own first (each point one node: a crack's two faces would
    // meet at one), then the frame's
    let n_mesh = mesh.n_nodes();
    let mut index = NodeIndex::new(tol);
    let mut found: Vec<[f64; 2]> = Vec::new();
    let mut ids: Vec<usize> = Vec::new();
    for s in &strips {
        for &g in &s.nodes {
            let p = mesh.position[g];
            let k = index.find_or_insert(p, &mut found) as usize;
            if k == ids.len() {
                ids.push(g);
            } else if ids[k] != g {
                return Err(Error::invalid(
                    file,
                    format!("boundary `{}`", s.curve),
                    format!(
                        "a crack or interface reaches it at x = {:.4e} m, z = {:.4e} m",
                        p[0], p[1]
                    ),
                    "for a pml frame, a side that no crack or contact interface reaches",
                ));
            }
        }
    }
    let xi = &mesh.gll.points;
    let w = &mesh.gll.weights;
    let mut position: Vec<[f64; 2]> = Vec::new();
    let mut mass = vec![0.0; n_mesh];
    let mut conn = Vec::with_capacity(elements * m * m);
    let mut damp = Vec::with_capacity(elements * m * m);
    let mut data = Vec::with_capacity(elements);
    let mut densities = Vec::with_capacity(elements);
    let c_max = materials.iter().map(|m| m.p_speed).fold(0.0, f64::max);
    let profile = |axis: usize| Profile {
        lo: lo[axis],
        hi: hi[axis],
        l_lo: if has(BoxSide { axis, high: false }) {
            l
        } else {
            0.0
        },
        l_hi: if has(BoxSide { axis, high: true }) {
            l
        } else {
            0.0
        },
        c: c_max,
        r0: pml.reflection,
    };
    let (dx, dz) = (profile(0), profile(1));
    for &(p0, size, tag) in &rects {
        let mat = materials[tag as usize];
        for b in 0..m {
            for a in 0..m {
                let p = [
                    p0[0] + 0.5 * (1.0 + xi[a]) * size[0],
                    p0[1] + 0.5 * (1.0 + xi[b]) * size[1],
                ];
                let k = index.find_or_insert(p, &mut found) as usize;
                if k == ids.len() {
                    ids.push(n_mesh + position.len());
                    position.push(p);
                    mass.push(0.0);
                }
                let g = ids[k];
                conn.push(g as u32);
                mass[g] += mat.density * w[a] * w[b] * size[0] * size[1] / 4.0;
                damp.push(pml::multiaxial(dx.at(p[0]), dz.at(p[1])));
            }
        }
        data.push(ElementData {
            hx: size[0],
            hz: size[1],
            lambda: mat.lambda(),
            mu: mat.mu(),
        });
        densities.push(mat.density);
    }
    let added = position.len();
    let beyond = |p: [f64; 2]| {
        (0..2).any(|axis| {
            (has(BoxSide { axis, high: false }) && p[axis] <= lo[axis] - l + tol)
                || (has(BoxSide { axis, high: true }) && p[axis] >= hi[axis] + l - tol)
        })
    };
    let fixed = if pml::RIGID_EDGE {
        (0..added)
            .filter(|&i| beyond(position[i]))
            .map(|i| n_mesh + i)
            .collect()
    } else {
        Vec::new()
    };
    // the stability bound: each orientation's element with the shortest edge along the
    // side (the largest frequency falls as an element grows) and the corners' squares
    let omega = {
        let mut probe: Vec<(ElementData, f64)> = Vec::new();
        for (el, &rho) in data.iter().zip(&densities) {
            let same = probe.iter_mut().find(|(q, r)| {
                *r == rho
                    && q.lambda == el.lambda
                    && q.mu == el.mu
                    && (q.hx == t) == (el.hx == t)
                    && (q.hz == t) == (el.hz == t)
            });
            match same {
                Some((q, _)) => {
                    q.hx = q.hx.min(el.hx);
                    q.hz = q.hz.min(el.hz);
                }
                None => probe.push((*el, rho)),
            }
        }
        let k = Stiffness {
            order: n,
            dims: (probe.len(), 1),
            elements: probe.iter().map(|p| p.0).collect(),
            conn: Vec::new(),
            weights: w.clone(),
            derivative: mesh.gll.derivative.clone(),
            antiplane,
            regular: Vec::new(),
            coefs: Vec::new(),
        };
        let rho: Vec<f64> = probe.iter().map(|p| p.1).collect();
        if rho.is_empty() {
            0.0
        } else {
            max_frequency(&k, &rho)
        }
    };
    let total = n_mesh + added;
    let inner: Vec<bool> = (0..total).map(|g| g < n_mesh).collect();
    let node_damp = |g: usize| {
        let p = if g < n_mesh {
            mesh.position[g]
        } else {
            position[g - n_mesh]
        };
        pml::multiaxial(dx.at(p[0]), dz.at(p[1]))
    };
    let band = Band::new(n, antiplane, data, conn, damp, &inner, &mass, node_damp);
    Ok(Frame {
        band,
        added,
        mass,
        fixed,
        omega,
        layers,
    })
}

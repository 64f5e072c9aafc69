//! The structured spectral-element mesh of a rectangle (model.md section 9): x along the
//! surface (0 to `width`), z into the depth (0 at the top surface to `depth`), rectangular
//! elements of GLL order n whose edges fall on every layer boundary and crack line, the
//! global nodes a tensor grid of the elements' GLL points, and split nodes: every node
//! strictly inside a crack is two nodes, the second ("face 2": below a horizontal crack,
//! right of a vertical one) appended after the grid. Periodic x sides identify the last
//! node column with the first.

use crate::error::{Error, Result};
use crate::numeric::gll::Gll;

/// A crack line along element edges, in node-grid terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrackLine {
    /// `true`: horizontal (constant z, normal +z); `false`: vertical (constant x, normal +x).
    pub horizontal: bool,
    /// Node-grid index of the line (iz of a horizontal crack, ix of a vertical one).
    pub line: usize,
    /// First and last node-grid indices along the line of the crack's ends; a welded tip
    /// is not split, the split nodes are between the tips.
    pub tips: (usize, usize),
    /// Whether each end (`tips.0`, `tips.1`) is open: a mouth on a free side of the
    /// rectangle, split too (each face a free-surface corner node); `false`: a welded tip.
    pub open: (bool, bool),
    /// A horizontal crack across the whole width of a periodic mesh: no tips, every node
    /// of the line split (an interface).
    pub full_width: bool,
}

impl CrackLine {
    /// Whether node-grid position `k` along the line is split.
    fn splits(&self, k: usize) -> bool {
        self.full_width || self.range().contains(&k)
    }

    /// The node-grid positions along the line that are split (not a full-width line):
    /// strictly between the welded tips, an open end included.
    fn range(&self) -> std::ops::Range<usize> {
        let (lo, hi, open_lo, open_hi) = if self.tips.0 <= self.tips.1 {
            (self.tips.0, self.tips.1, self.open.0, self.open.1)
        } else {
            (self.tips.1, self.tips.0, self.open.1, self.open.0)
        };
        (if open_lo { lo } else { lo + 1 })..(if open_hi { hi + 1 } else { hi })
    }
}

/// The mesh: element edges, the GLL rule, node coordinates and the element-to-node map.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// GLL rule of the elements.
    pub gll: Gll,
    /// Element edges along x, m (increasing, from 0 to the width; from minus the absorbing
    /// layer's thickness to the width plus it where the sides absorb).
    pub x_edges: Vec<f64>,
    /// Element edges along z, m (increasing, from 0 to the depth, or beyond them by the
    /// absorbing layers at the top and bottom).
    pub z_edges: Vec<f64>,
    /// Node-grid coordinates along x (`n_ex * n + 1` values), m.
    pub x: Vec<f64>,
    /// Node-grid coordinates along z (`n_ez * n + 1` values), m.
    pub z: Vec<f64>,
    /// Periodic x sides: node column `x.len() - 1` is column 0.
    pub periodic: bool,
    /// Element-to-node map: element `e = ez * n_ex + ex`, local node `b * (n + 1) + a` (a
    /// along x, b along z) at `conn[e * (n + 1)^2 + b * (n + 1) + a]`.
    pub conn: Vec<u32>,
    /// Number of nodes (grid nodes, then split twins).
    pub n_nodes: usize,
    /// The twin (face-2 node) of each split node, per crack: `(grid node, twin node)`.
    pub splits: Vec<Vec<(usize, usize)>>,
}

/// Edges from 0 to `length` through every coordinate of `required` (inside (0, length)),
/// each interval cut into equal elements no longer than `h`.
pub fn edges(length: f64, required: &[f64], h: f64) -> Vec<f64> {
    let mut at: Vec<f64> = required
        .iter()
        .copied()
        .filter(|&v| v > 0.0 && v < length)
        .collect();
    at.push(0.0);
    at.push(length);
    at.sort_by(f64::total_cmp);
    // points closer than a millionth of an element are one point
    at.dedup_by(|a, b| (*a - *b).abs() <= 1e-6 * h);
    let mut e = vec![at[0]];
    for w in at.windows(2) {
        let n = ((w[1] - w[0]) / h - 1e-9).ceil().max(1.0) as usize;
        for k in 1..=n {
            e.push(if k == n {
                w[1]
            } else {
                w[0] + (w[1] - w[0]) * k as f64 / n as f64
            });
        }
    }
    e
}

/// Index of the edge nearest `v`: for a coordinate that [`edges`] was given, the edge it
/// became (itself, or the point it was merged with, within a millionth of an element).
pub fn edge_index(edges: &[f64], v: f64) -> usize {
    let mut best = 0;
    for (k, e) in edges.iter().enumerate() {
        if (e - v).abs() < (edges[best] - v).abs() {
            best = k;
        }
    }
    best
}

impl Mesh {
    /// Nodes of the grid along x and z.
    pub fn grid_dims(&self) -> (usize, usize) {
        (self.x.len(), self.z.len())
    }

    /// Elements along x and z.
    pub fn element_dims(&self) -> (usize, usize) {
        (self.x_edges.len() - 1, self.z_edges.len() - 1)
    }

    /// Grid node of node-grid position `(ix, iz)` (the periodic image of the last column
    /// is column 0).
    #[inline]
    pub fn grid_node(&self, ix: usize, iz: usize) -> usize {
        let nxn = self.x.len();
        let ix = if self.periodic && ix == nxn - 1 {
            0
        } else {
            ix
        };
        iz * nxn + ix
    }

    /// Build the mesh of GLL order `order` on the given edges, with the cracks' split
    /// nodes (an open end, a mouth on a free side, is split too). Refuses crossing or
    /// touching cracks (a node split twice) and a crack whose tips leave no node to split.
    pub fn new(
        order: usize,
        x_edges: Vec<f64>,
        z_edges: Vec<f64>,
        periodic: bool,
        cracks: &[CrackLine],
    ) -> Result<Mesh> {
        let gll = Gll::new(order)
            .ok_or_else(|| Error::invalid("", "mesh.order", order, "a GLL order from 1 to 16"))?;
        let n = order;
        let m = n + 1;
        let (nex, nez) = (x_edges.len() - 1, z_edges.len() - 1);
        let grid = |edges: &[f64]| {
            let mut c = Vec::with_capacity((edges.len() - 1) * n + 1);
            for w in edges.windows(2) {
                for a in 0..n {
                    c.push(w[0] + 0.5 * (gll.points[a] + 1.0) * (w[1] - w[0]));
                }
            }
            c.push(*edges.last().unwrap_or(&0.0));
            c
        };
        let x = grid(&x_edges);
        let z = grid(&z_edges);
        let (nxn, nzn) = (x.len(), z.len());
        let mut mesh = Mesh {
            gll,
            x_edges,
            z_edges,
            x,
            z,
            periodic,
            conn: vec![0; nex * nez * m * m],
            n_nodes: nxn * nzn,
            splits: Vec::new(),
        };
        // twins: per grid node, the twin index (u32::MAX: not split)
        let mut twin = vec![u32::MAX; nxn * nzn];
        let mut next = nxn * nzn;
        for (ci, c) in cracks.iter().enumerate() {
            let mut pairs = Vec::new();
            let range = if c.full_width {
                if !(periodic && c.horizontal) {
                    return Err(Error::invalid(
                        "",
                        format!("crack.{ci}.full_width"),
                        "across the whole width",
                        "a crack across the whole width needs periodic x sides and a horizontal line",
                    ));
                }
                // every distinct column: 0 to nxn - 2 (column nxn - 1 is column 0)
                0..nxn - 1
            } else {
                c.range()
            };
            if range.is_empty() {
                return Err(Error::invalid(
                    "",
                    format!("crack.{ci}.length"),
                    "shorter than one node spacing",
                    "a crack longer than a millionth of its elements (two node spacings between \
                     welded tips leave one node to split): a longer crack, or smaller elements \
                     (model.element_size)",
                ));
            }
            for k in range {
                let g = if c.horizontal {
                    mesh.grid_node(k, c.line)
                } else {
                    mesh.grid_node(c.line, k)
                };
                if twin[g] != u32::MAX {
                    return Err(Error::invalid(
                        "",
                        format!("crack.{ci}"),
                        format!(
                            "node at x = {} m, z = {} m",
                            mesh.x[g % nxn],
                            mesh.z[g / nxn]
                        ),
                        "cracks may not cross or overlap (they may meet at a tip, which stays welded)",
                    ));
                }
                twin[g] = next as u32;
                pairs.push((g, next));
                next += 1;
            }
            mesh.splits.push(pairs);
        }
        mesh.n_nodes = next;
        // the element map: face-2 elements of a crack (below a horizontal line, right of a
        // vertical one) take the twins of its nodes
        let below = |c: &CrackLine, ex: usize, ez: usize, a: usize, b: usize| -> bool {
            if c.horizontal {
                ez * n + b == c.line && b == 0 && c.splits(ex * n + a)
            } else {
                ex * n + a == c.line && a == 0 && c.splits(ez * n + b)
            }
        };
        for ez in 0..nez {
            for ex in 0..nex {
                let e = ez * nex + ex;
                for b in 0..m {
                    for a in 0..m {
                        let g = mesh.grid_node(ex * n + a, ez * n + b);
                        let node = if cracks.iter().any(|c| below(c, ex, ez, a, b)) {
                            twin[g] as usize
                        } else {
                            g
                        };
                        mesh.conn[e * m * m + b * m + a] = node as u32;
                    }
                }
            }
        }
        Ok(mesh)
    }
}

/// The boundary weight of node-grid position `k` along a line of element edges `edges`
/// (order `n`): the GLL weights times the half-lengths of the
/// elements it belongs to. `wrap`: the line closes on itself (periodic).
pub(super) fn edge_weight(edges: &[f64], w: &[f64], n: usize, k: usize, wrap: bool) -> f64 {
    let ne = edges.len() - 1;
    let (e, a) = (k / n, k % n);
    let h = |e: usize| 0.5 * (edges[e + 1] - edges[e]);
    if a != 0 {
        return w[a] * h(e);
    }
    // an element corner: the end of the element before and the start of the one after
    let mut s = 0.0;
    if e < ne {
        s += w[0] * h(e);
    } else if wrap {
        s += w[0] * h(0);
    }
    if e > 0 {
        s += w[n] * h(e - 1);
    } else if wrap {
        s += w[n] * h(ne - 1);
    }
    s
}

/// The boundary weights of surface node column `ix` restricted to the aperture `[x0, x1]`
/// (m; both on element edges): the GLL weights of the element edges inside it, from the
/// element on its left and from the one on its right (an element corner) or both from its
/// own element (inside one).
fn aperture_parts(mesh: &Mesh, ix: usize, x0: f64, x1: f64) -> (f64, f64) {
    let n = mesh.gll.order;
    let w = &mesh.gll.weights;
    let ne = mesh.x_edges.len() - 1;
    let (e, a) = (ix / n, ix % n);
    let inside = |e: usize| {
        let mid = 0.5 * (mesh.x_edges[e] + mesh.x_edges[e + 1]);
        mid > x0 && mid < x1
    };
    let h = |e: usize| 0.5 * (mesh.x_edges[e + 1] - mesh.x_edges[e]);
    if a != 0 {
        return (if inside(e) { w[a] * h(e) } else { 0.0 }, 0.0);
    }
    let left = if e > 0 && inside(e - 1) {
        w[n] * h(e - 1)
    } else {
        0.0
    };
    let right = if e < ne && inside(e) {
        w[0] * h(e)
    } else {
        0.0
    };
    (left, right)
}

/// The nodes and boundary weights of surface node `(ix, iz)` under the aperture `[x0, x1]`
/// (m): the grid node with the whole weight, or, at the mouth of a vertical crack (a split
/// surface node), face 1 (left) with the left element's share and face 2 its twin with the
/// right one's.
pub(super) fn aperture_faces(
    mesh: &Mesh,
    ix: usize,
    iz: usize,
    x0: f64,
    x1: f64,
) -> Vec<(usize, f64)> {
    let g = mesh.grid_node(ix, iz);
    let (left, right) = aperture_parts(mesh, ix, x0, x1);
    match mesh.splits.iter().flatten().find(|p| p.0 == g) {
        Some(&(_, twin)) => vec![(g, left), (twin, right)],
        None => vec![(g, left + right)],
    }
}

impl<L> super::Solid2d<L> {
    /// Whether the end `p = [x, z]` (m) of a crack (`horizontal` or vertical) is open: a
    /// mouth on a free side of the rectangle (a vertical crack's end on the top or bottom
    /// side, a horizontal one's on an x side), split like the crack's inner nodes; else a
    /// welded tip (docs/model.md 15.2).
    pub(super) fn mouth(&self, p: [f64; 2], horizontal: bool) -> bool {
        use super::Side::Free;
        let depth = self.layers.last().map_or(0.0, |l| l.bottom);
        if horizontal {
            (p[0] == 0.0 || p[0] == self.width) && self.sides == Free
        } else {
            (p[1] == 0.0 && self.top == Free) || (p[1] == depth && self.bottom == Free)
        }
    }
}

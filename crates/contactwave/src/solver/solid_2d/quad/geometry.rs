//! The mesh of the general quadrilateral path as data (docs/model.md section 15.13): the
//! GLL nodes' coordinates, the element-to-node map (one `(n+1)^2` block an element, local
//! node `b (n + 1) + a`, a along xi and b along eta), a material tag per element, the
//! geometry of every GLL point (`xi_x, xi_z, eta_x, eta_z, w J`), each element flagged an
//! axis-aligned rectangle (constant factors: the kernel's fast path) or general, the named
//! curves resolved to element edges, and a fixed element colouring (no two elements of a
//! colour share a node) for deterministic parallel assembly.
//!
//! Element edges ("sides") are numbered 0 (eta = -1), 1 (xi = +1), 2 (eta = +1), 3
//! (xi = -1), each traversed counter-clockwise in `(xi, eta)`; every element is oriented
//! so that its Jacobian `x_xi z_eta - x_eta z_xi` is positive, so that the outward normal
//! of a side is its traversal direction turned by -90 degrees, `(t_z, -t_x)`.

use super::input::{QuadInput, QuadNodes};
use crate::error::{Error, Result};
use crate::numeric::gll::Gll;
use std::collections::HashMap;

/// An element edge: element and side (0 to 3).
pub type Edge = (u32, u8);

/// A named curve resolved to the mesh: each segment's end nodes (global) and the element
/// edges along it (one on the mesh's boundary, two inside it).
#[derive(Debug, Clone)]
pub struct EdgeSet {
    /// The name (the Gmsh physical curve's).
    pub name: String,
    /// Each segment: its end nodes and the element edges on it (the elements on either
    /// side of an inner curve).
    pub segments: Vec<([u32; 2], Vec<Edge>)>,
}

/// The mesh.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// The file or generator it came from.
    pub source: String,
    /// GLL rule of the elements.
    pub gll: Gll,
    /// Node coordinates `[x, z]`, m (split twins after the others).
    pub position: Vec<[f64; 2]>,
    /// Element-to-node map, `(n + 1)^2` an element.
    pub conn: Vec<u32>,
    /// Material tag of each element.
    pub material: Vec<u16>,
    /// The material names.
    pub materials: Vec<String>,
    /// Per GLL point of every element (`e (n+1)^2 + b (n+1) + a`): `[xi_x, xi_z, eta_x,
    /// eta_z, w_a w_b J]` (1/m and m^2).
    pub metric: Vec<[f64; 5]>,
    /// Whether each element is an axis-aligned rectangle with xi along +x and eta along +z
    /// (its metric constant: `xi_x = 2 / h_x`, `eta_z = 2 / h_z`).
    pub rectangle: Vec<bool>,
    /// Tiles: ranges of consecutive elements ([`Mesh::colour`]).
    pub tiles: Vec<std::ops::Range<u32>>,
    /// Tiles by colour: no two tiles of a colour share a node.
    pub colours: Vec<Vec<u32>>,
    /// The named curves.
    pub sets: Vec<EdgeSet>,
    /// The points named in the input, m.
    pub points: Vec<(String, [f64; 2])>,
}

/// The 1D shape functions of an element of order `q` (1: linear on {-1, 1}; 2: quadratic
/// on {-1, 0, 1}) and their derivatives at `s`.
fn shape_1d(q: usize, s: f64) -> ([f64; 3], [f64; 3]) {
    if q == 1 {
        ([0.5 * (1.0 - s), 0.5 * (1.0 + s), 0.0], [-0.5, 0.5, 0.0])
    } else {
        (
            [0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)],
            [s - 0.5, -2.0 * s, s + 0.5],
        )
    }
}

/// The local (Gmsh) node of the element's control grid point `(i, j)` (i along xi, j along
/// eta; 0..=q).
fn control(q: usize, i: usize, j: usize) -> usize {
    if q == 1 {
        [[0, 3], [1, 2]][i][j]
    } else {
        [[0, 7, 3], [4, 8, 6], [1, 5, 2]][i][j]
    }
}

/// The element map at `(xi, eta)`: position `[x, z]` and `[x_xi, x_eta, z_xi, z_eta]`.
pub(super) fn map(
    nodes: &[[f64; 2]],
    quad: &QuadNodes,
    q: usize,
    xi: f64,
    eta: f64,
) -> ([f64; 2], [f64; 4]) {
    let (sx, dx) = shape_1d(q, xi);
    let (sz, dz) = shape_1d(q, eta);
    let mut p = [0.0; 2];
    let mut d = [0.0; 4];
    for i in 0..=q {
        for j in 0..=q {
            let c = nodes[quad[control(q, i, j)] as usize];
            let (f, fx, fz) = (sx[i] * sz[j], dx[i] * sz[j], sx[i] * dz[j]);
            p[0] += f * c[0];
            p[1] += f * c[1];
            d[0] += fx * c[0];
            d[1] += fz * c[0];
            d[2] += fx * c[1];
            d[3] += fz * c[1];
        }
    }
    (p, d)
}

/// The element's nodes reoriented: reversed (`flip`, a clockwise element) and turned by
/// `turn` quarter turns (corner `turn` first).
fn reorder(quad: &QuadNodes, flip: bool, turn: usize) -> QuadNodes {
    let mut q = *quad;
    if flip {
        q = [q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4], q[8]];
    }
    for _ in 0..turn {
        q = [q[1], q[2], q[3], q[0], q[5], q[6], q[7], q[4], q[8]];
    }
    q
}

/// Whether the element is an axis-aligned rectangle with xi along +x and eta along +z.
fn is_rectangle(nodes: &[[f64; 2]], quad: &QuadNodes, q: usize) -> bool {
    let c = |k: usize| nodes[quad[k] as usize];
    let (a, b, cc, d) = (c(0), c(1), c(2), c(3));
    let size = (b[0] - a[0]).abs() + (d[1] - a[1]).abs();
    let same = |u: f64, v: f64| (u - v).abs() <= 1e-12 * size;
    let corners = same(a[1], b[1])
        && same(b[0], cc[0])
        && same(cc[1], d[1])
        && same(d[0], a[0])
        && b[0] > a[0]
        && d[1] > a[1];
    if !corners || q == 1 {
        return corners;
    }
    let mid = |k: usize, u: [f64; 2], v: [f64; 2]| {
        let m = c(k);
        same(m[0], 0.5 * (u[0] + v[0])) && same(m[1], 0.5 * (u[1] + v[1]))
    };
    mid(4, a, b) && mid(5, b, cc) && mid(6, cc, d) && mid(7, d, a) && {
        let m = c(8);
        same(m[0], 0.5 * (a[0] + b[0])) && same(m[1], 0.5 * (a[1] + d[1]))
    }
}

/// Local node index of position `k` along side `s` (traversal order), order `n`.
#[inline]
pub fn side_node(n: usize, s: u8, k: usize) -> usize {
    let m = n + 1;
    let (a, b) = match s {
        0 => (k, 0),
        1 => (n, k),
        2 => (n - k, n),
        _ => (0, n - k),
    };
    b * m + a
}

impl Mesh {
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.position.len()
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.material.len()
    }

    /// GLL points per element, `(n + 1)^2`.
    pub fn per_element(&self) -> usize {
        (self.gll.order + 1) * (self.gll.order + 1)
    }

    /// The mapping's derivatives `[x_xi, x_eta, z_xi, z_eta]` and `J` at element point `p`
    /// (`e (n+1)^2 + b (n+1) + a`), from its metric.
    pub fn jacobian(&self, p: usize) -> ([f64; 4], f64) {
        let m = self.gll.order + 1;
        let w = &self.gll.weights;
        let l = p % (m * m);
        let [xx, xz, ex, ez, wj] = self.metric[p];
        let j = wj / (w[l % m] * w[l / m]);
        ([j * ez, -j * xz, -j * ex, j * xx], j)
    }

    /// Along side `s` of element `e`, at traversal position `k`: the global node, the
    /// outward unit normal `[x, z]` and the boundary weight (GLL weight times the edge's
    /// length per unit of its reference coordinate, m).
    pub fn side_point(&self, e: usize, s: u8, k: usize) -> (usize, [f64; 2], f64) {
        let n = self.gll.order;
        let l = side_node(n, s, k);
        let p = e * self.per_element() + l;
        let ([x_xi, x_eta, z_xi, z_eta], _) = self.jacobian(p);
        let t = match s {
            0 => [x_xi, z_xi],
            1 => [x_eta, z_eta],
            2 => [-x_xi, -z_xi],
            _ => [-x_eta, -z_eta],
        };
        let len = t[0].hypot(t[1]);
        let normal = [t[1] / len, -t[0] / len];
        (self.conn[p] as usize, normal, self.gll.weights[k] * len)
    }

    /// Build the mesh of GLL order `order` from a generator's input: the elements oriented
    /// (a clockwise element reversed), inverted or degenerate ones refused, coincident GLL
    /// nodes merged (two parts meshed separately with coincident nodes are joined; a crack
    /// or an interface later splits them again), the named curves resolved to element
    /// edges and the elements coloured.
    pub fn build(input: &QuadInput, order: usize) -> Result<Mesh> {
        let file = input.source.as_str();
        let gll = Gll::new(order)
            .ok_or_else(|| Error::invalid(file, "mesh.order", order, "a GLL order from 1 to 16"))?;
        let q = if input.second_order { 2 } else { 1 };
        let n = order;
        let m = n + 1;
        let ne = input.quads.len();
        if ne == 0 {
            return Err(Error::invalid(
                file,
                "mesh",
                "no quadrilateral",
                "a mesh with quadrilateral elements (Gmsh: a 2D mesh recombined into quads)",
            ));
        }
        let mut quads = Vec::with_capacity(ne);
        let mut rectangle = Vec::with_capacity(ne);
        let mut metric = Vec::with_capacity(ne * m * m);
        let mut points = Vec::with_capacity(ne * m * m);
        let w = &gll.weights;
        for (e, quad) in input.quads.iter().enumerate() {
            if let Some(&bad) = quad[..if q == 1 { 4 } else { 9 }]
                .iter()
                .find(|&&k| k as usize >= input.nodes.len())
            {
                return Err(Error::invalid(
                    file,
                    format!("element {}", e + 1),
                    format!("node {bad}"),
                    "nodes of the mesh",
                ));
            }
            // the Jacobian's sign at the GLL points: all of one sign (a clockwise element
            // is reversed), else inverted or degenerate
            let mut sign = (0usize, 0usize);
            let (mut jmin, mut jmax) = (f64::INFINITY, 0.0f64);
            for b in 0..m {
                for a in 0..m {
                    let (_, d) = map(&input.nodes, quad, q, gll.points[a], gll.points[b]);
                    let j = d[0] * d[3] - d[1] * d[2];
                    if j > 0.0 {
                        sign.0 += 1;
                    } else if j < 0.0 {
                        sign.1 += 1;
                    }
                    jmin = jmin.min(j.abs());
                    jmax = jmax.max(j.abs());
                }
            }
            if (sign.0 > 0 && sign.1 > 0) || !(jmin > 1e-8 * jmax) || !jmax.is_finite() {
                let c = input.nodes[quad[0] as usize];
                return Err(Error::invalid(
                    file,
                    format!("element {}", e + 1),
                    format!("at x = {:.4e} m, z = {:.4e} m", c[0], c[1]),
                    "an element whose Jacobian keeps one sign (inverted or degenerate: \
                     re-mesh, or check the order of its nodes)",
                ));
            }
            let flip = sign.1 > 0;
            let oriented = (0..4)
                .map(|turn| reorder(quad, flip, turn))
                .find(|r| is_rectangle(&input.nodes, r, q));
            let quad = oriented.unwrap_or_else(|| reorder(quad, flip, 0));
            let rect = oriented.is_some();
            for b in 0..m {
                for a in 0..m {
                    let (xi, eta) = (gll.points[a], gll.points[b]);
                    if rect {
                        // (as the structured mesh computes them: the same bits)
                        let c0 = input.nodes[quad[0] as usize];
                        let c2 = input.nodes[quad[2] as usize];
                        let (hx, hz) = (c2[0] - c0[0], c2[1] - c0[1]);
                        points.push([
                            c0[0] + 0.5 * (xi + 1.0) * hx,
                            c0[1] + 0.5 * (eta + 1.0) * hz,
                        ]);
                        metric.push([2.0 / hx, 0.0, 0.0, 2.0 / hz, w[a] * w[b] * hx * hz / 4.0]);
                    } else {
                        let (p, d) = map(&input.nodes, &quad, q, xi, eta);
                        let [x_xi, x_eta, z_xi, z_eta] = d;
                        let j = x_xi * z_eta - x_eta * z_xi;
                        points.push(p);
                        metric.push([z_eta / j, -x_eta / j, -z_xi / j, x_xi / j, w[a] * w[b] * j]);
                    }
                }
            }
            quads.push(quad);
            rectangle.push(rect);
        }
        // merge coincident points (within a millionth of the smallest GLL spacing)
        let spacing = (gll.points[1] - gll.points[0]) * 0.5;
        let h_min = input.side_lengths().fold(f64::INFINITY, f64::min);
        let tol = 1e-6 * spacing * h_min;
        let mut index = NodeIndex::new(tol);
        let mut position = Vec::new();
        let conn: Vec<u32> = points
            .iter()
            .map(|&p| index.find_or_insert(p, &mut position))
            .collect();
        let mut mesh = Mesh {
            source: input.source.clone(),
            gll,
            position,
            conn,
            material: input.material.clone(),
            materials: input.materials.clone(),
            metric,
            rectangle,
            tiles: Vec::new(),
            colours: Vec::new(),
            sets: Vec::new(),
            points: input.points.clone(),
        };
        // element edges by their end nodes
        let mut edges: HashMap<(u32, u32), Vec<Edge>> = HashMap::new();
        for e in 0..ne {
            for s in 0..4u8 {
                let a = mesh.conn[e * m * m + side_node(n, s, 0)];
                let b = mesh.conn[e * m * m + side_node(n, s, n)];
                edges
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push((e as u32, s));
            }
        }
        for (name, segments) in &input.curves {
            let mut set = EdgeSet {
                name: name.clone(),
                segments: Vec::with_capacity(segments.len()),
            };
            for seg in segments {
                let ends = seg.map(|k| index.find(input.nodes[k as usize]));
                let found = match ends {
                    [Some(a), Some(b)] => edges.get(&(a.min(b), a.max(b))).map(|l| ([a, b], l)),
                    _ => None,
                };
                let Some((ends, on)) = found else {
                    let p = input.nodes[seg[0] as usize];
                    return Err(Error::invalid(
                        file,
                        format!("curve `{name}`"),
                        format!("a segment at x = {:.4e} m, z = {:.4e} m", p[0], p[1]),
                        "a curve along element edges (mesh the curve with the surface: \
                         Gmsh's `Curve{..} In Surface{..}` for a crack inside it)",
                    ));
                };
                // (two coincident curves, an interface between parts meshed apart, are one)
                if !set.segments.iter().any(|(e, _)| {
                    e[0].min(e[1]) == ends[0].min(ends[1]) && e[0].max(e[1]) == ends[0].max(ends[1])
                }) {
                    set.segments.push((ends, on.clone()));
                }
            }
            mesh.sets.push(set);
        }
        Ok(mesh)
    }

    /// The named curve `name`, or an error naming the file and the curves it has.
    pub fn set(&self, name: &str, field: &str) -> Result<&EdgeSet> {
        self.sets.iter().find(|s| s.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.sets.iter().map(|s| s.name.as_str()).collect();
            Error::invalid(
                &self.source,
                field,
                format!("`{name}`"),
                format!("a physical curve of the mesh: {}", names.join(", ")),
            )
        })
    }

    /// Cut the elements into tiles of [`TILE`] consecutive elements (the generators'
    /// orders keep a tile's elements together in space, so that its gather and scatter stay
    /// in cache) and colour the tiles greedily in their order (the smallest colour no tile
    /// sharing a node has taken): a fixed colouring, so that assembling colour by colour,
    /// the tiles of a colour in parallel and each tile's elements in order, sums every
    /// node's contributions in one order whatever the threads. A tile that finds no free
    /// colour among 127 goes to the last, which runs its tiles one after another.
    pub fn colour(&mut self) {
        let mm = self.per_element();
        let ne = self.n_elements();
        self.tiles = (0..ne.div_ceil(TILE))
            .map(|t| (t * TILE) as u32..((t + 1) * TILE).min(ne) as u32)
            .collect();
        let mut used = vec![0u128; self.n_nodes()];
        let mut colours: Vec<Vec<u32>> = Vec::new();
        for (t, tile) in self.tiles.iter().enumerate() {
            let nodes = &self.conn[tile.start as usize * mm..tile.end as usize * mm];
            let taken = nodes.iter().fold(0u128, |acc, &g| acc | used[g as usize]);
            let c = ((!taken).trailing_zeros() as usize).min(SERIAL_COLOUR);
            for &g in nodes {
                used[g as usize] |= 1 << c;
            }
            if colours.len() <= c {
                colours.resize(c + 1, Vec::new());
            }
            colours[c].push(t as u32);
        }
        self.colours = colours;
    }
}

/// Elements per tile of the colouring.
pub const TILE: usize = 128;
/// The colour whose tiles run one after another (no free colour was left for them).
pub const SERIAL_COLOUR: usize = 127;

/// Coincident points found by a hash of their coordinates rounded to cells of the
/// tolerance (each point looked for in its cell and the 8 around it).
pub struct NodeIndex {
    tol: f64,
    cells: HashMap<(i64, i64), Vec<u32>>,
    position: Vec<[f64; 2]>,
}

impl NodeIndex {
    /// An empty index of points within `tol` (m) of each other.
    pub fn new(tol: f64) -> Self {
        NodeIndex {
            tol,
            cells: HashMap::new(),
            position: Vec::new(),
        }
    }

    fn cell(&self, p: [f64; 2]) -> (i64, i64) {
        (
            (p[0] / self.tol).round() as i64,
            (p[1] / self.tol).round() as i64,
        )
    }

    /// The point within the tolerance of `p`, if any.
    pub fn find(&self, p: [f64; 2]) -> Option<u32> {
        let (i, j) = self.cell(p);
        for di in -1..=1 {
            for dj in -1..=1 {
                if let Some(list) = self.cells.get(&(i + di, j + dj)) {
                    for &k in list {
                        let q = self.position[k as usize];
                        if (q[0] - p[0]).abs() <= self.tol && (q[1] - p[1]).abs() <= self.tol {
                            return Some(k);
                        }
                    }
                }
            }
        }
        None
    }

    /// The point within the tolerance of `p`, or `p` added (to `out` too).
    pub fn find_or_insert(&mut self, p: [f64; 2], out: &mut Vec<[f64; 2]>) -> u32 {
        if let Some(k) = self.find(p) {
            return k;
        }
        let k = self.position.len() as u32;
        self.position.push(p);
        out.push(p);
        let c = self.cell(p);
        self.cells.entry(c).or_default().push(k);
        k
    }
}

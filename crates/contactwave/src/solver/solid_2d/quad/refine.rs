//! Uniform refinement of a generated mesh (`mesh.refine = k`, docs/model.md eq. 15.13h):
//! each element split into `k x k` elements along its own reference coordinates, the new
//! control nodes (4 a first-order element, 9 a second-order one) its map's points, so that
//! the refined mesh has the same shape to the bit where the map is evaluated alike and to
//! round-off elsewhere: a second-order element's biquadratic map, restricted to a
//! sub-square, is biquadratic again. Named curves are split with the edges they run along;
//! nodes shared by neighbouring elements (and coincident nodes of parts meshed apart) are
//! one node, found by position within a millionth of the smallest new edge.

use super::geometry::{map, NodeIndex};
use super::input::{QuadInput, QuadNodes};
use std::collections::HashMap;

/// The reference coordinates of an element's control nodes, in Gmsh's order.
const AT: [(f64, f64); 9] = [
    (-1.0, -1.0),
    (1.0, -1.0),
    (1.0, 1.0),
    (-1.0, 1.0),
    (0.0, -1.0),
    (1.0, 0.0),
    (0.0, 1.0),
    (-1.0, 0.0),
    (0.0, 0.0),
];

/// The reference point of side `s` (from corner `s` to corner `s + 1`) at `t` in [0, 1].
fn side_at(s: usize, t: f64) -> (f64, f64) {
    let u = 2.0 * t - 1.0;
    match s {
        0 => (u, -1.0),
        1 => (1.0, u),
        2 => (-u, 1.0),
        _ => (-1.0, -u),
    }
}

impl QuadInput {
    /// The mesh with each element split into `k x k` (k >= 1; 1: a copy). The element
    /// count grows by `k^2`: check the budget on [`Self::refined_nodes`] first.
    pub fn refine(&self, k: usize) -> QuadInput {
        let k = k.max(1);
        if k == 1 {
            return self.clone();
        }
        let q = if self.second_order { 2 } else { 1 };
        let used = if self.second_order { 9 } else { 4 };
        let kf = k as f64;
        // the tolerance: a millionth of the shortest new edge
        let shortest = self.side_lengths().fold(f64::INFINITY, f64::min);
        let mut index = NodeIndex::new(1e-6 * shortest / kf);
        let mut nodes = Vec::new();
        let mut quads = Vec::with_capacity(self.quads.len() * k * k);
        let mut material = Vec::with_capacity(quads.capacity());
        for (e, quad) in self.quads.iter().enumerate() {
            for j in 0..k {
                for i in 0..k {
                    let mut sub: QuadNodes = [0; 9];
                    for (n, &(a, b)) in AT.iter().enumerate().take(used) {
                        let xi = -1.0 + (2.0 * i as f64 + 1.0 + a) / kf;
                        let eta = -1.0 + (2.0 * j as f64 + 1.0 + b) / kf;
                        let (p, _) = map(&self.nodes, quad, q, xi, eta);
                        sub[n] = index.find_or_insert(p, &mut nodes);
                    }
                    quads.push(sub);
                    material.push(self.material[e]);
                }
            }
        }
        // each curve segment along the side of an element that has both its ends as
        // consecutive corners, split at that side's points
        let mut sides: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
        for (e, quad) in self.quads.iter().enumerate() {
            for s in 0..4 {
                sides.entry((quad[s], quad[(s + 1) % 4])).or_insert((e, s));
            }
        }
        let curves = self
            .curves
            .iter()
            .map(|(name, segments)| {
                let mut out = Vec::with_capacity(segments.len() * k);
                for &[a, b] in segments {
                    let (pa, pb) = (self.nodes[a as usize], self.nodes[b as usize]);
                    let ids: Option<Vec<u32>> = if let Some(&(e, s)) = sides.get(&(a, b)) {
                        (0..=k)
                            .map(|t| self.side_node(&index, e, s, t as f64 / kf))
                            .collect()
                    } else if let Some(&(e, s)) = sides.get(&(b, a)) {
                        (0..=k)
                            .rev()
                            .map(|t| self.side_node(&index, e, s, t as f64 / kf))
                            .collect()
                    } else {
                        None
                    };
                    match ids {
                        Some(ids) => out.extend(ids.windows(2).map(|w| [w[0], w[1]])),
                        // not along an element side: kept as it was (between its ends'
                        // new nodes), for Mesh::build to refuse by name
                        None => {
                            if let (Some(x), Some(y)) = (index.find(pa), index.find(pb)) {
                                out.push([x, y]);
                            }
                        }
                    }
                }
                (name.clone(), out)
            })
            .collect();
        QuadInput {
            source: self.source.clone(),
            nodes,
            quads,
            second_order: self.second_order,
            material,
            materials: self.materials.clone(),
            curves,
            points: self.points.clone(),
        }
    }

    /// The refined mesh's node at `t` (0 to 1) along side `s` of element `e`.
    fn side_node(&self, index: &NodeIndex, e: usize, s: usize, t: f64) -> Option<u32> {
        let q = if self.second_order { 2 } else { 1 };
        let (xi, eta) = side_at(s, t);
        index.find(map(&self.nodes, &self.quads[e], q, xi, eta).0)
    }

    /// The control nodes of the mesh refined by `k` (no more than
    /// `k^2` times the elements' own, each shared by up to four).
    pub fn refined_nodes(&self, k: usize) -> f64 {
        let per = if self.second_order { 2 * k + 1 } else { k + 1 };
        (self.quads.len() * per * per) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::super::geometry::Mesh;
    use super::*;

    /// A bent, second-order grid refined by 3: nine times the elements, its curves three
    /// times the segments and still chains along element sides, the same area and the
    /// same curve lengths (to round-off: the map is the same biquadratic), and the GLL
    /// nodes of a refined first-order grid are the grid's of a third of the spacing.
    #[test]
    fn refining_splits_elements_and_curves_and_keeps_the_shape() {
        let bend = |p: [f64; 2]| [p[0] + 0.1 * p[1] * p[1], p[1] + 0.05 * p[0] * p[1]];
        let xs = [0.0, 1.0, 2.0, 3.0];
        let zs = [0.0, 1.0, 2.0];
        let lines = [("cut", [1.0, 1.0], [3.0, 1.0])];
        let g = QuadInput::grid(&xs, &zs, &bend, vec!["m".into()], &|_| 0, &lines, true);
        let r = g.refine(3);
        assert_eq!(r.quads.len(), 9 * g.quads.len());
        for (name, segs) in &g.curves {
            assert_eq!(r.curve(name).unwrap().len(), 3 * segs.len(), "{name}");
        }
        let (a, b) = (Mesh::build(&g, 4).unwrap(), Mesh::build(&r, 4).unwrap());
        let area = |m: &Mesh| m.metric.iter().map(|x| x[4]).sum::<f64>();
        assert!((area(&a) - area(&b)).abs() < 1e-13 * area(&a));
        for name in ["cut", "top", "left"] {
            let len = |m: &Mesh| {
                let set = m.set(name, "curve").unwrap();
                let side = |&(e, s): &(u32, u8)| {
                    (0..=m.gll.order)
                        .map(|k| m.side_point(e as usize, s, k).2)
                        .sum::<f64>()
                };
                set.segments.iter().map(|(_, e)| side(&e[0])).sum::<f64>()
            };
            assert!((len(&a) - len(&b)).abs() < 1e-12 * len(&a), "{name}");
        }
        // first order, straight: the refined GLL nodes are the finer grid's
        let id = |p: [f64; 2]| p;
        let fine: Vec<f64> = (0..=9).map(|i| i as f64 / 3.0).collect();
        let fz: Vec<f64> = (0..=6).map(|i| i as f64 / 3.0).collect();
        let coarse = QuadInput::grid(&xs, &zs, &id, vec!["m".into()], &|_| 0, &[], false);
        let direct = QuadInput::grid(&fine, &fz, &id, vec!["m".into()], &|_| 0, &[], false);
        let (c, d) = (
            Mesh::build(&coarse.refine(3), 3).unwrap(),
            Mesh::build(&direct, 3).unwrap(),
        );
        assert_eq!(c.n_nodes(), d.n_nodes());
        for p in &c.position {
            assert!(
                d.position
                    .iter()
                    .any(|q| (p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12),
                "{p:?}"
            );
        }
    }
}

//! A crack or contact interface along any chain of element edges (docs/model.md section
//! 15.13): its nodes are duplicated and the twins renumbered in the elements on one side
//! ("face 2"). A chain's vertex is split where the crack cuts the ring of elements around
//! it in two: always inside the chain, at an end on the mesh's boundary (a mouth: a
//! surface-breaking crack, an interface reaching a free side), never at an end inside the
//! mesh (a welded tip). Each split point carries its own unit normal (from face 1 to face
//! 2: the chain's direction turned by +90 degrees, from +x toward +z), averaged over the
//! two edges at a vertex by their weights, exact at the GLL points of a curved edge, its
//! tangent `t = (n_z, -n_x)` (along the chain) and its boundary weight (the GLL weights
//! times the edges' lengths).

use super::geometry::{side_node, Edge, Mesh};
use crate::error::{Error, Result};
use std::collections::HashMap;

/// A split crack's points in order along it.
#[derive(Debug, Clone, Default)]
pub struct SplitCrack {
    /// Face-1 and face-2 node of each point.
    pub faces: Vec<(usize, usize)>,
    /// Unit normal (face 1 to face 2) of each point, `[x, z]`.
    pub normal: Vec<[f64; 2]>,
    /// Unit tangent of each point, `[x, z]`.
    pub tangent: Vec<[f64; 2]>,
    /// Boundary weight of each point, m.
    pub weight: Vec<f64>,
    /// Distance of each point along the crack from its start (chords between the points), m.
    pub position: Vec<f64>,
    /// Where the crack starts and ends, `[x, z]`, m.
    pub ends: [[f64; 2]; 2],
}

/// Split the curve `name` of `mesh` (its `field` in the scenario, for errors): refuses a
/// curve on the mesh's boundary, one that branches or is in pieces, and one that crosses
/// or overlaps an earlier crack (`split`: the nodes split so far, grown as nodes are).
pub fn split(
    mesh: &mut Mesh,
    name: &str,
    field: &str,
    split: &mut Vec<bool>,
) -> Result<SplitCrack> {
    let file = mesh.source.clone();
    let set = mesh.set(name, field)?.clone();
    let n = mesh.gll.order;
    let mm = mesh.per_element();
    let at = |mesh: &Mesh, g: u32| {
        let p = mesh.position[g as usize];
        format!("x = {:.4e} m, z = {:.4e} m", p[0], p[1])
    };
    if set.segments.is_empty() {
        return Err(Error::invalid(
            &file,
            field,
            format!("`{name}`"),
            "a curve with segments",
        ));
    }
    // the chain: vertices and their segments
    let mut touching: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, (ends, on)) in set.segments.iter().enumerate() {
        if on.len() != 2 {
            return Err(Error::invalid(
                &file,
                field,
                format!("`{name}` at {}", at(mesh, ends[0])),
                "a crack or interface inside the mesh, with elements on both sides (a curve on \
                 the boundary is a side, not a crack)",
            ));
        }
        for &v in ends {
            touching.entry(v).or_default().push(i);
        }
    }
    if let Some((v, _)) = touching.iter().find(|(_, s)| s.len() > 2) {
        return Err(Error::invalid(
            &file,
            field,
            format!("`{name}` branches at {}", at(mesh, *v)),
            "a chain of element edges (one crack a curve; cracks may meet only at a tip)",
        ));
    }
    let lexi = |mesh: &Mesh, a: u32, b: u32| {
        let (p, q) = (mesh.position[a as usize], mesh.position[b as usize]);
        p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
    };
    let mut ends: Vec<u32> = touching
        .iter()
        .filter(|(_, s)| s.len() == 1)
        .map(|(v, _)| *v)
        .collect();
    ends.sort_by(|&a, &b| lexi(mesh, a, b));
    let closed = ends.is_empty();
    let start = if closed {
        let mut all: Vec<u32> = touching.keys().copied().collect();
        all.sort_by(|&a, &b| lexi(mesh, a, b));
        all[0]
    } else {
        ends[0]
    };
    // walk: segments in order, each from P to Q
    let mut order: Vec<(usize, u32, u32)> = Vec::with_capacity(set.segments.len());
    let mut used = vec![false; set.segments.len()];
    let mut v = start;
    while let Some(&i) = touching[&v].iter().find(|&&i| !used[i]) {
        used[i] = true;
        let [a, b] = set.segments[i].0;
        let q = if a == v { b } else { a };
        order.push((i, v, q));
        v = q;
    }
    if order.len() != set.segments.len() {
        return Err(Error::invalid(
            &file,
            field,
            format!("`{name}` in pieces"),
            "one chain of element edges (give each piece its own physical curve and crack)",
        ));
    }
    // each segment's face-1 and face-2 edges: the face-1 element's side runs from Q to P
    // (its outward normal is the crack's +n), the face-2 one's from P to Q
    let start_of = |mesh: &Mesh, (e, s): Edge| mesh.conn[e as usize * mm + side_node(n, s, 0)];
    let mut faces: Vec<(Edge, Edge)> = Vec::with_capacity(order.len());
    for &(i, p, _) in &order {
        let on = &set.segments[i].1;
        let (a, b) = (on[0], on[1]);
        faces.push(if start_of(mesh, a) == p {
            (b, a)
        } else {
            (a, b)
        });
    }
    // which vertices split, and which elements take their twins
    let vertices: Vec<u32> = {
        let mut v: Vec<u32> = order.iter().map(|o| o.1).collect();
        if !closed {
            v.push(order.last().map_or(start, |o| o.2));
        }
        v
    };
    let mut around: HashMap<u32, Vec<u32>> = vertices.iter().map(|&v| (v, Vec::new())).collect();
    for e in 0..mesh.n_elements() {
        for c in 0..4u8 {
            let g = mesh.conn[e * mm + side_node(n, c, 0)];
            if let Some(list) = around.get_mut(&g) {
                list.push(e as u32);
            }
        }
    }
    let crack_edges: std::collections::HashSet<(u32, u32)> = order
        .iter()
        .map(|&(_, p, q)| (p.min(q), p.max(q)))
        .collect();
    let new_twin = |mesh: &mut Mesh, g: u32, split: &mut Vec<bool>| -> Result<u32> {
        if split.get(g as usize).copied().unwrap_or(true) {
            return Err(Error::invalid(
                &file,
                field,
                format!("`{name}` at {}", at(mesh, g)),
                "cracks that do not cross or overlap (they may meet at a welded tip)",
            ));
        }
        split[g as usize] = true;
        let t = mesh.position.len() as u32;
        let p = mesh.position[g as usize];
        mesh.position.push(p);
        split.push(true);
        Ok(t)
    };
    let mut vertex_twin: HashMap<u32, u32> = HashMap::new();
    for (vi, &v) in vertices.iter().enumerate() {
        let elems = &around[&v];
        // union-find over the ring, joined through the sides at v that are not the crack
        let mut parent: Vec<usize> = (0..elems.len()).collect();
        fn root(p: &mut [usize], i: usize) -> usize {
            let mut r = i;
            while p[r] != r {
                r = p[r];
            }
            p[i] = r;
            r
        }
        let sides_at = |mesh: &Mesh, e: u32| -> Vec<(u32, u32)> {
            let mut out = Vec::new();
            for s in 0..4u8 {
                let a = mesh.conn[e as usize * mm + side_node(n, s, 0)];
                let b = mesh.conn[e as usize * mm + side_node(n, s, n)];
                if a == v || b == v {
                    out.push((a.min(b), a.max(b)));
                }
            }
            out
        };
        let sides: Vec<Vec<(u32, u32)>> = elems.iter().map(|&e| sides_at(mesh, e)).collect();
        for i in 0..elems.len() {
            for j in i + 1..elems.len() {
                if sides[i]
                    .iter()
                    .any(|s| sides[j].contains(s) && !crack_edges.contains(s))
                {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri] = rj;
                }
            }
        }
        // the segments at v: the one ending there (vi - 1, or the last of a loop) and the
        // one starting there
        let mut incident = Vec::new();
        if vi < order.len() {
            incident.push(vi);
        }
        if vi > 0 {
            incident.push(vi - 1);
        } else if closed {
            incident.push(order.len() - 1);
        }
        let comp = |parent: &mut Vec<usize>, e: u32| {
            let i = elems.iter().position(|&x| x == e).unwrap_or(0);
            root(parent, i)
        };
        let f2: Vec<usize> = incident
            .iter()
            .map(|&s| comp(&mut parent, faces[s].1 .0))
            .collect();
        let f1: Vec<usize> = incident
            .iter()
            .map(|&s| comp(&mut parent, faces[s].0 .0))
            .collect();
        if f1.iter().any(|c| f2.contains(c)) {
            continue; // one ring: a welded tip
        }
        let t = new_twin(mesh, v, split)?;
        vertex_twin.insert(v, t);
        for (i, &e) in elems.iter().enumerate() {
            if f2.contains(&root(&mut parent, i)) {
                for l in 0..mm {
                    let g = &mut mesh.conn[e as usize * mm + l];
                    if *g == v {
                        *g = t;
                    }
                }
            }
        }
    }
    // the points in order: each split vertex, then its segment's inner GLL nodes
    let mut out = SplitCrack::default();
    let add = |out: &mut SplitCrack, pair: (usize, usize), parts: &[([f64; 2], f64)]| {
        let b: f64 = parts.iter().map(|p| p.1).sum();
        let nx: f64 = parts.iter().map(|p| p.0[0] * p.1).sum();
        let nz: f64 = parts.iter().map(|p| p.0[1] * p.1).sum();
        let len = nx.hypot(nz);
        let normal = [nx / len, nz / len];
        out.faces.push(pair);
        out.normal.push(normal);
        out.tangent.push([normal[1], -normal[0]]);
        out.weight.push(b);
    };
    for (si, &(_, p, _)) in order.iter().enumerate() {
        let ((e1, s1), (e2, s2)) = faces[si];
        // vertex P: the face-1 side's end (k = n) of this segment, and the start (k = 0)
        // of the previous one's
        if let Some(&t) = vertex_twin.get(&p) {
            let mut parts = vec![side(mesh, e1, s1, n)];
            let prev = if si > 0 {
                Some(si - 1)
            } else if closed {
                Some(order.len() - 1)
            } else {
                None
            };
            if let Some(pi) = prev {
                let ((pe, ps), _) = faces[pi];
                parts.push(side(mesh, pe, ps, 0));
            }
            add(&mut out, (p as usize, t as usize), &parts);
        }
        for j in 1..n {
            let k = n - j;
            let g = mesh.conn[e1 as usize * mm + side_node(n, s1, k)];
            let l2 = e2 as usize * mm + side_node(n, s2, j);
            if mesh.conn[l2] != g {
                return Err(Error::invalid(
                    &file,
                    field,
                    format!("`{name}` at {}", at(mesh, g)),
                    "a conforming mesh (the elements on both sides share the edge's nodes)",
                ));
            }
            let t = new_twin(mesh, g, split)?;
            mesh.conn[l2] = t;
            let part = side(mesh, e1, s1, k);
            add(&mut out, (g as usize, t as usize), &[part]);
        }
    }
    if !closed
        && let Some(&(_, _, q)) = order.last()
        && let Some(&t) = vertex_twin.get(&q)
    {
        let ((e1, s1), _) = faces[order.len() - 1];
        add(&mut out, (q as usize, t as usize), &[side(mesh, e1, s1, 0)]);
    }
    let mut s = 0.0;
    for (i, &(g, _)) in out.faces.iter().enumerate() {
        if i > 0 {
            let (a, b) = (mesh.position[out.faces[i - 1].0], mesh.position[g]);
            s += (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        out.position.push(s);
    }
    let end = order.last().map_or(start, |o| o.2);
    out.ends = [mesh.position[start as usize], mesh.position[end as usize]];
    Ok(out)
}

/// The face-1 side point `k` of element `e`'s side `s`: its outward normal and weight.
fn side(mesh: &Mesh, e: u32, s: u8, k: usize) -> ([f64; 2], f64) {
    let (_, normal, w) = mesh.side_point(e as usize, s, k);
    (normal, w)
}

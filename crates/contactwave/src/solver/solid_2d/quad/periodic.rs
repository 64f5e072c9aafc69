//! Periodic sides on a mesh (docs/model.md section 15.13): two named boundary curves that
//! are translates of each other (the same length, the same element edges, the GLL points
//! of each edge on the partner's moved by one vector). Their nodes stay separate in the
//! mesh (each element keeps its own positions, for receivers, pictures and files) and are
//! joined as one degree of freedom in the time loop: each group of joined nodes has a
//! primary (its smallest node number) and mirrors; the mirrors' forces are added to the
//! primary's, the primary moves with the group's summed mass, and the mirrors take its
//! displacement and velocity after the step. A crack that ends on a periodic side must end
//! on its partner at the matching point: both mouths' faces are then joined face by face
//! (edge by edge, so that a split mouth pairs face 1 with face 1), and the crack's point
//! there is one point with the summed boundary weight.

use super::geometry::{EdgeSet, Mesh};
use crate::error::{Error, Result};

/// The joined nodes: each mirror with its primary, sorted by mirror (a fixed order: the
/// sums run the same way whatever the threads).
pub type Mirrors = Vec<(usize, usize)>;

/// The ends of an open curve (its vertices on one segment only), `[x, z]`, m, in the
/// order smaller x, then z; empty for a closed curve.
pub(super) fn ends(mesh: &Mesh, set: &EdgeSet) -> Vec<[f64; 2]> {
    let mut count: std::collections::HashMap<u32, usize> = Default::default();
    for (e, _) in &set.segments {
        for &v in e {
            *count.entry(v).or_default() += 1;
        }
    }
    let mut out: Vec<[f64; 2]> = count
        .iter()
        .filter(|(_, c)| **c == 1)
        .map(|(&v, _)| mesh.position[v as usize])
        .collect();
    out.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    out
}

/// The node pairs of the periodic curves `a` and `b` (the key `field` of `file`, for
/// errors): each GLL point of `a`'s edges with the point of `b`'s edge it is moved onto.
pub fn pairs(mesh: &Mesh, a: &str, b: &str, field: &str, file: &str) -> Result<Vec<[usize; 2]>> {
    let sa = super::on_boundary(mesh, a, field, file)?;
    let sb = super::on_boundary(mesh, b, field, file)?;
    let refuse = |what: String| {
        Err(Error::invalid(
            file,
            field,
            what,
            "two open curves on the boundary, one the other moved by a translation, with \
             the same element edges (Gmsh: `Periodic Curve{b} = {a} Translate{dx, dy, 0};`)",
        ))
    };
    let (ea, eb) = (ends(mesh, sa), ends(mesh, sb));
    if ea.len() != 2 || eb.len() != 2 {
        return refuse(format!("`{a}` and `{b}`: a closed or broken curve"));
    }
    if sa.segments.len() != sb.segments.len() {
        return refuse(format!(
            "`{a}` has {} edges, `{b}` {}",
            sa.segments.len(),
            sb.segments.len()
        ));
    }
    // the edges' shortest length sets the tolerance
    let edge = |set: &EdgeSet, i: usize| {
        let ([p, q], _) = set.segments[i];
        let (p, q) = (mesh.position[p as usize], mesh.position[q as usize]);
        (p, q)
    };
    let mut h = f64::INFINITY;
    for i in 0..sa.segments.len() {
        let (p, q) = edge(sa, i);
        h = h.min((q[0] - p[0]).hypot(q[1] - p[1]));
    }
    let tol = 1e-6 * h;
    let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol;
    let sub = |p: [f64; 2], q: [f64; 2]| [p[0] - q[0], p[1] - q[1]];
    let add = |p: [f64; 2], d: [f64; 2]| [p[0] + d[0], p[1] + d[1]];
    // the translation: the ends matched in one order or the other
    let d = [sub(eb[0], ea[0]), sub(eb[1], ea[0])]
        .into_iter()
        .zip([eb[1], eb[0]])
        .find(|&(d, other)| near(add(ea[1], d), other))
        .map(|(d, _)| d);
    let Some(d) = d else {
        return refuse(format!("`{b}` is not `{a}` moved by a translation"));
    };
    // b's edges by the projection of their midpoints on the chord, for a binary search
    let chord = sub(ea[1], ea[0]);
    let len = chord[0].hypot(chord[1]);
    let u = [chord[0] / len, chord[1] / len];
    let key = |p: [f64; 2], q: [f64; 2]| 0.5 * ((p[0] + q[0]) * u[0] + (p[1] + q[1]) * u[1]);
    let mut order: Vec<(f64, usize)> = (0..sb.segments.len())
        .map(|i| {
            let (p, q) = edge(sb, i);
            (key(p, q), i)
        })
        .collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0));
    let n = mesh.gll.order;
    let mut out = Vec::with_capacity(sa.segments.len() * (n + 1));
    for i in 0..sa.segments.len() {
        let (p, q) = edge(sa, i);
        let (pt, qt) = (add(p, d), add(q, d));
        let k0 = key(pt, qt);
        let start = order.partition_point(|x| x.0 < k0 - tol);
        let found = order[start..]
            .iter()
            .take_while(|x| x.0 <= k0 + tol)
            .map(|x| x.1)
            .find(|&j| {
                let (bp, bq) = edge(sb, j);
                (near(bp, pt) && near(bq, qt)) || (near(bp, qt) && near(bq, pt))
            });
        let Some(j) = found else {
            return refuse(format!(
                "no edge of `{b}` at x = {:.4e} m, z = {:.4e} m",
                pt[0], pt[1]
            ));
        };
        let ((ea_, sa_), (eb_, sb_)) = (sa.segments[i].1[0], sb.segments[j].1[0]);
        // the partner's GLL points, in its own traversal (the same or the reverse)
        let first = mesh.position[mesh.side_point(ea_ as usize, sa_, 0).0];
        let same = near(
            add(first, d),
            mesh.position[mesh.side_point(eb_ as usize, sb_, 0).0],
        );
        for k in 0..=n {
            let ga = mesh.side_point(ea_ as usize, sa_, k).0;
            let gb = mesh
                .side_point(eb_ as usize, sb_, if same { k } else { n - k })
                .0;
            if !near(add(mesh.position[ga], d), mesh.position[gb]) {
                return refuse(format!(
                    "the edges at x = {:.4e} m, z = {:.4e} m are not translates (curved \
                     differently)",
                    pt[0], pt[1]
                ));
            }
            out.push([ga, gb]);
        }
    }
    Ok(out)
}

/// The groups of joined nodes from every periodic pair of curves (`(a, b)` with its key
/// `field` of `file`): each mirror with its primary (the group's smallest node).
pub fn join(mesh: &Mesh, curves: &[(String, String)], file: &str) -> Result<Mirrors> {
    if curves.is_empty() {
        return Ok(Vec::new());
    }
    let mut parent: Vec<usize> = (0..mesh.n_nodes()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (a, b) in curves {
        let field = format!("boundary `{a}` (periodic with `{b}`)");
        for [p, q] in pairs(mesh, a, b, &field, file)? {
            let (rp, rq) = (root(&mut parent, p), root(&mut parent, q));
            // the smaller node is the root: the primary of its group
            if rp != rq {
                parent[rp.max(rq)] = rp.min(rq);
            }
        }
    }
    let mut out = Vec::new();
    for i in 0..parent.len() {
        let r = root(&mut parent, i);
        if r != i {
            out.push((i, r));
        }
    }
    Ok(out)
}

/// A split crack with its points on mirror nodes folded onto their primaries' points (the
/// boundary weights summed: a mouth on each of two joined sides is one point), refused
/// (the crack's key `field` of `file`) where a crack ends on a periodic side but not on
/// the partner at the matching point, or where its two faces are joined.
pub fn fold_crack(
    mut crack: super::split::SplitCrack,
    mirrors: &Mirrors,
    field: &str,
    file: &str,
) -> Result<super::split::SplitCrack> {
    if mirrors.is_empty() {
        return Ok(crack);
    }
    let primary = |g: usize| match mirrors.binary_search_by_key(&g, |m| m.0) {
        Ok(i) => mirrors[i].1,
        Err(_) => g,
    };
    let refuse = |j: usize, crack: &super::split::SplitCrack| {
        Err(Error::invalid(
            file,
            field,
            format!(
                "a point on a periodic side at {:.4e} m along the crack",
                crack.position[j]
            ),
            "a crack that crosses a periodic side onto its partner at the matching point \
             (both mouths split), or that stays away from periodic sides",
        ))
    };
    let mut keep = vec![true; crack.faces.len()];
    for j in 0..crack.faces.len() {
        let (g1, g2) = crack.faces[j];
        let (p1, p2) = (primary(g1), primary(g2));
        if p1 == p2 {
            return refuse(j, &crack);
        }
        if (p1, p2) == (g1, g2) {
            continue;
        }
        let Some(i) = crack.faces.iter().position(|&f| f == (p1, p2)) else {
            return refuse(j, &crack);
        };
        crack.weight[i] += crack.weight[j];
        keep[j] = false;
    }
    let mut out = super::split::SplitCrack {
        ends: crack.ends,
        ..Default::default()
    };
    for (j, keep) in keep.into_iter().enumerate() {
        if keep {
            out.faces.push(crack.faces[j]);
            out.normal.push(crack.normal[j]);
            out.tangent.push(crack.tangent[j]);
            out.weight.push(crack.weight[j]);
            out.position.push(crack.position[j]);
        }
    }
    Ok(out)
}

//! Pictures of a run on a mesh (docs/model.md section 15.13): the kept velocity fields
//! resampled on a uniform pixel grid over the mesh's box by each element's GLL Lagrange
//! interpolant (every pixel centre located once in its element, [`Mesh::finder`]; pixels
//! outside the specimen, in a hole or beyond a curved side, are NaN), the mesh's outline
//! (the element sides that belong to one element: the outer sides, holes, and the two faces
//! of each crack) and the GLL sub-cells for ParaView.

use super::geometry::{side_node, Mesh};
use super::locate::basis;
use crate::solver::solid_2d::snapshot::{pixel_centres, Capture, Field, Raster};
use std::collections::HashMap;

/// The frames of `capture` (fields of `components` values per node of `mesh`) on `nx`
/// pixel columns across the box `lo..hi` (m; `[x, z]`) and as many rows as keep the
/// pixels square (at least one); `field` picks the value drawn. A pixel takes the element
/// it lies in (a crack's two faces show their own motion on each side of it); a pixel
/// centre in no element is NaN.
pub fn raster(
    mesh: &Mesh,
    components: usize,
    capture: &Capture,
    field: Field,
    nx: usize,
    lo: [f64; 2],
    hi: [f64; 2],
) -> Raster {
    let size = [(hi[0] - lo[0]).max(0.0), (hi[1] - lo[1]).max(0.0)];
    let (x, z) = pixel_centres(nx, lo, size);
    let (nx, nz) = (x.len(), z.len());
    let m = mesh.gll.order + 1;
    let mm = m * m;
    let pts = &mesh.gll.points;
    // each pixel's element (u32::MAX: none) and its basis along xi and eta
    let per = nx * nz;
    let mut elem = vec![u32::MAX; per];
    let mut wx = vec![0.0; per * m];
    let mut wz = vec![0.0; per * m];
    let mut finder = mesh.finder();
    let mut d = vec![0.0; m];
    for iz in 0..nz {
        for ix in 0..nx {
            let k = iz * nx + ix;
            if let Some((e, r)) = finder.reference(mesh, [x[ix], z[iz]]) {
                elem[k] = e as u32;
                basis(pts, r[0], &mut wx[k * m..(k + 1) * m], &mut d);
                basis(pts, r[1], &mut wz[k * m..(k + 1) * m], &mut d);
            }
        }
    }
    let c = components;
    let len = c * mesh.n_nodes();
    let frames = capture.times.len();
    let mut values = vec![f64::NAN; frames * per];
    for (f, out) in values.chunks_exact_mut(per.max(1)).enumerate().take(frames) {
        let v = &capture.frames[f * len..(f + 1) * len];
        for (k, o) in out.iter_mut().enumerate() {
            let e = elem[k];
            if e == u32::MAX {
                continue;
            }
            let nodes = &mesh.conn[e as usize * mm..(e as usize + 1) * mm];
            let (lx, lz) = (&wx[k * m..(k + 1) * m], &wz[k * m..(k + 1) * m]);
            let mut comp = [0.0; 2];
            for (b, &wb) in lz.iter().enumerate() {
                for (a, &wa) in lx.iter().enumerate() {
                    let g = nodes[b * m + a] as usize;
                    for (cc, s) in comp.iter_mut().enumerate().take(c) {
                        *s += wa * wb * v[c * g + cc];
                    }
                }
            }
            *o = field.of(&comp[..c]);
        }
    }
    Raster { x, z, values }
}

/// The mesh's outline as segments `[x0, z0, x1, z1]` (m) between consecutive GLL nodes of
/// every element side that no other element shares (by its end nodes): the outer sides,
/// holes' rims and, after splitting, both faces of every crack. Curved sides follow their
/// GLL nodes.
pub fn outline(mesh: &Mesh) -> Vec<[f64; 4]> {
    let n = mesh.gll.order;
    let mm = mesh.per_element();
    let key = |e: usize, s: u8| {
        let a = mesh.conn[e * mm + side_node(n, s, 0)];
        let b = mesh.conn[e * mm + side_node(n, s, n)];
        (a.min(b), a.max(b))
    };
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for e in 0..mesh.n_elements() {
        for s in 0..4u8 {
            *count.entry(key(e, s)).or_insert(0) += 1;
        }
    }
    let mut out = Vec::new();
    for e in 0..mesh.n_elements() {
        for s in 0..4u8 {
            if count[&key(e, s)] != 1 {
                continue;
            }
            for k in 0..n {
                let p = mesh.position[mesh.conn[e * mm + side_node(n, s, k)] as usize];
                let q = mesh.position[mesh.conn[e * mm + side_node(n, s, k + 1)] as usize];
                out.push([p[0], p[1], q[0], q[1]]);
            }
        }
    }
    out
}

/// The GLL sub-cells of every element: the quadrilaterals between neighbouring GLL nodes
/// (`n^2` an element, counter-clockwise in the element's reference frame), as global node
/// indices: the cells ParaView draws the nodal fields on.
pub fn sub_cells(mesh: &Mesh) -> Vec<[u32; 4]> {
    let n = mesh.gll.order;
    let m = n + 1;
    let mm = m * m;
    let mut out = Vec::with_capacity(mesh.n_elements() * n * n);
    for e in 0..mesh.n_elements() {
        let c = &mesh.conn[e * mm..(e + 1) * mm];
        for b in 0..n {
            for a in 0..n {
                out.push([
                    c[b * m + a],
                    c[b * m + a + 1],
                    c[(b + 1) * m + a + 1],
                    c[(b + 1) * m + a],
                ]);
            }
        }
    }
    out
}

/// The box of the mesh's nodes, `([x, z] lowest, [x, z] highest)`, m.
pub fn bounds(mesh: &Mesh) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in &mesh.position {
        for c in 0..2 {
            lo[c] = lo[c].min(q[c]);
            hi[c] = hi[c].max(q[c]);
        }
    }
    (lo, hi)
}

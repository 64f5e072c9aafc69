//! Wavefield snapshots of a 2D run: the nodal velocities copied at chosen steps inside the
//! time loop into room reserved before it starts (a capture allocates nothing), and their
//! resampling onto a uniform pixel grid after the run ([`raster`]) by each element's GLL
//! Lagrange interpolant (exact for the field the scheme represents, not nearest-node).

use super::mesh::Mesh;
use super::Plan;

/// Steps at which a run keeps the whole velocity field, and the fields it kept.
#[derive(Debug, Clone, Default)]
pub struct Capture {
    /// Steps (increasing, distinct) after which the velocities `v^{n+1/2}` are kept.
    steps: Vec<usize>,
    /// The next entry of `steps` to take.
    next: usize,
    /// Values per frame (components times nodes).
    len: usize,
    /// Times of the kept frames (the half levels `(n + 1/2) dt`), s.
    pub times: Vec<f64>,
    /// The kept frames, frame-major, each `v` as the solver holds it (node-major, its
    /// components together; split twins after the grid nodes), m/s.
    pub frames: Vec<f64>,
}

impl Capture {
    /// Room for the frames of `steps` (sorted and made distinct here) of a field of `len`
    /// values, reserved now.
    pub fn new(mut steps: Vec<usize>, len: usize) -> Capture {
        steps.sort_unstable();
        steps.dedup();
        Capture {
            times: Vec::with_capacity(steps.len()),
            frames: Vec::with_capacity(steps.len() * len),
            steps,
            next: 0,
            len,
        }
    }

    /// Whether step `n` (0-based) is the next chosen one (what [`Capture::take`] keeps).
    #[inline]
    pub fn wants(&self, n: usize) -> bool {
        self.steps.get(self.next) == Some(&n)
    }

    /// After step `n` (0-based), at half level `t` (s): keep `v` if `n` is a chosen step.
    /// A copy into the reserved room: no allocation.
    #[inline]
    pub fn take(&mut self, n: usize, t: f64, v: &[f64]) {
        if self.wants(n) && v.len() == self.len {
            self.next += 1;
            self.times.push(t);
            self.frames.extend_from_slice(v);
        }
    }

    /// Bytes the frames take, for the memory budget.
    pub fn bytes(steps: usize, len: usize) -> f64 {
        steps as f64 * len as f64 * 8.0
    }
}

impl<L> Plan<L> {
    /// Keep the velocity field after each of `steps` (0-based step numbers; the field is the
    /// half level `(n + 1/2) dt`); steps at or beyond [`Plan::steps`] are never reached.
    /// The caller checks [`Capture::bytes`] against the memory budget first.
    pub fn capture_at(&mut self, steps: Vec<usize>) {
        self.snapshot_steps = steps;
    }

    /// The step whose half level `(n + 1/2) dt` is nearest to `t` (s), within the run.
    pub fn step_at(&self, t: f64) -> usize {
        step_at(t, self.dt, self.steps)
    }
}

/// The step of a run of `steps` steps of `dt` (s) whose half level `(n + 1/2) dt` is
/// nearest to `t` (s).
pub fn step_at(t: f64, dt: f64, steps: usize) -> usize {
    let n = (t / dt - 0.5).round().max(0.0);
    (n as usize).min(steps.saturating_sub(1))
}

/// Which value a picture shows of the velocity field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// `|v|` (plane strain: `sqrt(vx^2 + vz^2)`; antiplane: `|vy|`), m/s.
    Magnitude,
    /// Component `k` of the node's velocity (plane strain: 0 = vx, 1 = vz; antiplane:
    /// 0 = vy), m/s.
    Component(usize),
}

impl Field {
    /// The value drawn of a node's or a pixel's velocity `v` (its components), m/s.
    #[inline]
    pub fn of(self, v: &[f64]) -> f64 {
        match self {
            Field::Magnitude => v.iter().map(|s| s * s).sum::<f64>().sqrt(),
            Field::Component(k) => v[k.min(v.len() - 1)],
        }
    }
}

/// The centres of `nx` pixel columns (at least one) across the box from `lo` of `size`
/// (m; `[x, z]`) and of as many rows as keep the pixels square (at least one; one for a
/// box of no width), m.
pub fn pixel_centres(nx: usize, lo: [f64; 2], size: [f64; 2]) -> (Vec<f64>, Vec<f64>) {
    let [width, depth] = size;
    let nx = nx.max(1);
    let nz = if width > 0.0 {
        ((nx as f64 * depth / width).round() as usize).max(1)
    } else {
        1
    };
    let centres = |n: usize, o: f64, len: f64| -> Vec<f64> {
        (0..n)
            .map(|i| o + (i as f64 + 0.5) * len / n as f64)
            .collect()
    };
    (centres(nx, lo[0], width), centres(nz, lo[1], depth))
}

/// Frames resampled on a uniform grid of pixel centres.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Raster {
    /// Pixel-centre coordinates along x, m (`nx` values, increasing).
    pub x: Vec<f64>,
    /// Pixel-centre coordinates along z (depth), m (`nz` values, increasing).
    pub z: Vec<f64>,
    /// Values, `[frame][iz][ix]` flattened (row-major, the top row first), m/s.
    pub values: Vec<f64>,
}

impl Raster {
    /// Number of frames.
    pub fn frames(&self) -> usize {
        let n = self.x.len() * self.z.len();
        self.values.len().checked_div(n).unwrap_or(0)
    }

    /// Frame `k` as rows `[iz][ix]`.
    pub fn frame(&self, k: usize) -> &[f64] {
        let n = self.x.len() * self.z.len();
        &self.values[k * n..(k + 1) * n]
    }
}

/// Lagrange basis of the GLL points `p` at `xi` in [-1, 1], into `out`.
fn basis(p: &[f64], xi: f64, out: &mut [f64]) {
    for (a, o) in out.iter_mut().enumerate() {
        let mut l = 1.0;
        for (j, &pj) in p.iter().enumerate() {
            if j != a {
                l *= (xi - pj) / (p[a] - pj);
            }
        }
        *o = l;
    }
}

/// For each coordinate of `at`: its element along `edges` and the Lagrange basis there.
fn locate(edges: &[f64], points: &[f64], at: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let m = points.len();
    let ne = edges.len() - 1;
    let mut elem = Vec::with_capacity(at.len());
    let mut w = vec![0.0; at.len() * m];
    for (i, &x) in at.iter().enumerate() {
        // the element whose [e0, e1) holds x (the last one takes its right edge)
        let e = edges
            .partition_point(|&v| v <= x)
            .saturating_sub(1)
            .min(ne - 1);
        let xi = 2.0 * (x - edges[e]) / (edges[e + 1] - edges[e]) - 1.0;
        basis(points, xi, &mut w[i * m..(i + 1) * m]);
        elem.push(e);
    }
    (elem, w)
}

/// Resample the frames of `capture` (fields of `components` values per node on `mesh`) onto
/// `nx` pixel columns across the rectangle `[0, width] x [0, depth]` (m; `size`, the
/// solid without its absorbing layers, which the mesh extends beyond it) and as many rows
/// as keep the pixels square (at least one), by each element's GLL interpolant at the
/// pixel centres; `field` picks the value drawn. A pixel takes the element it lies in, so
/// a crack's two faces show their own motion on each side of it.
pub fn raster(
    mesh: &Mesh,
    components: usize,
    capture: &Capture,
    field: Field,
    nx: usize,
    size: [f64; 2],
) -> Raster {
    let (x, z) = pixel_centres(nx, [0.0; 2], size);
    let (nx, nz) = (x.len(), z.len());
    let p = &mesh.gll.points;
    let m = p.len();
    let (ex, wx) = locate(&mesh.x_edges, p, &x);
    let (ez, wz) = locate(&mesh.z_edges, p, &z);
    let (nex, _) = mesh.element_dims();
    let c = components;
    let frames = capture.times.len();
    let per = nx * nz;
    let mut values = vec![0.0; frames * per];
    let len = c * mesh.n_nodes;
    for (k, out) in values.chunks_exact_mut(per.max(1)).enumerate().take(frames) {
        let v = &capture.frames[k * len..(k + 1) * len];
        for iz in 0..nz {
            let lz = &wz[iz * m..(iz + 1) * m];
            for ix in 0..nx {
                let lx = &wx[ix * m..(ix + 1) * m];
                let e = ez[iz] * nex + ex[ix];
                let nodes = &mesh.conn[e * m * m..(e + 1) * m * m];
                let mut comp = [0.0; 2];
                for (b, &wb) in lz.iter().enumerate() {
                    for (a, &wa) in lx.iter().enumerate() {
                        let g = nodes[b * m + a] as usize;
                        for (cc, s) in comp.iter_mut().enumerate().take(c) {
                            *s += wa * wb * v[c * g + cc];
                        }
                    }
                }
                out[iz * nx + ix] = field.of(&comp[..c]);
            }
        }
    }
    Raster { x, z, values }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::solid_2d::mesh;

    /// The relative error (largest over the pixels and both frames) of the rasters of the
    /// field `f` (component vz = 2 f, and the magnitude) on an order-4 mesh of elements no
    /// larger than `h` (m) with a 10 mm crack, of a 40 x 10 mm solid whose mesh goes on
    /// into absorbing layers at the sides and the bottom (the pictures show the solid).
    fn raster_error(f: &dyn Fn(f64, f64) -> f64, h: f64) -> f64 {
        let order = 4;
        let (x_edges, _) =
            super::super::pml::extend(mesh::edges(0.04, &[0.015, 0.025], h), 3e-3, 3e-3, h);
        let (z_edges, _) = super::super::pml::extend(mesh::edges(0.01, &[0.005], h), 0.0, 2e-3, h);
        let cracks = [mesh::CrackLine {
            horizontal: true,
            line: mesh::edge_index(&z_edges, 0.005) * order,
            tips: (
                mesh::edge_index(&x_edges, 0.015) * order,
                mesh::edge_index(&x_edges, 0.025) * order,
            ),
            open: (false, false),
            full_width: false,
        }];
        let mesh = Mesh::new(order, x_edges, z_edges, false, &cracks).unwrap();
        let (nxn, nzn) = mesh.grid_dims();
        let node_xz = |g: usize| -> (f64, f64) {
            // a split twin sits where its grid node does
            let g = if g < nxn * nzn {
                g
            } else {
                mesh.splits[0].iter().find(|s| s.1 == g).unwrap().0
            };
            (mesh.x[g % nxn], mesh.z[g / nxn])
        };
        let mut v = vec![0.0; 2 * mesh.n_nodes];
        for g in 0..mesh.n_nodes {
            let (x, z) = node_xz(g);
            v[2 * g] = f(x, z);
            v[2 * g + 1] = 2.0 * f(x, z);
        }
        // frames at steps 3 and 7 only; the second one's field negated
        let mut cap = Capture::new(vec![7, 3], v.len());
        cap.take(3, 1e-6, &v);
        let neg: Vec<f64> = v.iter().map(|a| -a).collect();
        cap.take(5, 2e-6, &neg);
        cap.take(7, 3e-6, &neg);
        assert_eq!(cap.times, [1e-6, 3e-6]);
        let size = [0.04, 0.01];
        let r = raster(&mesh, 2, &cap, Field::Component(1), 160, size);
        assert_eq!((r.x.len(), r.z.len(), r.frames()), (160, 40, 2));
        assert!((r.x[0] - 0.125e-3).abs() < 1e-15 && (r.z[39] - 9.875e-3).abs() < 1e-15);
        let mag = raster(&mesh, 2, &cap, Field::Magnitude, 160, size);
        let mut worst = 0.0f64;
        let scale = r.values.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (iz, &z) in r.z.iter().enumerate() {
            for (ix, &x) in r.x.iter().enumerate() {
                let exact = 2.0 * f(x, z);
                let k = iz * 160 + ix;
                worst = worst.max((r.frame(0)[k] - exact).abs());
                worst = worst.max((r.frame(1)[k] + exact).abs());
                worst = worst.max((mag.frame(1)[k] - 5f64.sqrt() * f(x, z).abs()).abs());
            }
        }
        worst / scale
    }

    /// A field polynomial of degree <= 4 in x and in z is reproduced at every pixel centre
    /// to round-off (the order-4 GLL interpolant is exact for it); a smooth wave converges
    /// at the interpolant's order 5 with the element size.
    #[test]
    fn the_raster_reproduces_polynomials_and_converges_on_smooth_fields() {
        let poly =
            |x: f64, z: f64| 1.0 + 3e2 * x - 4e5 * x * x * z + 2e8 * x.powi(4) + 1e7 * z.powi(4);
        let e = raster_error(&poly, 0.005);
        println!("raster of a degree-4 polynomial: relative error {e:.3e}");
        assert!(e < 1e-13, "{e:e}");
        let wave = |x: f64, z: f64| (2.0 * std::f64::consts::PI * (x + 0.5 * z) / 0.01).sin();
        let (e1, e2) = (raster_error(&wave, 0.005), raster_error(&wave, 0.0025));
        let order = (e1 / e2).log2();
        println!(
            "raster of a 10 mm wave: {e1:.3e} (5 mm elements), {e2:.3e} (2.5 mm), order {order:.2}"
        );
        assert!(e1 < 1e-2 && e2 < 5e-4, "{e1:e} {e2:e}");
        assert!(order > 4.5, "observed order {order}");
    }
}

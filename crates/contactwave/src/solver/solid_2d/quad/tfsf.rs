//! Plane waves on a mesh by total-field/scattered-field injection (docs/model.md section
//! 15.8 on the meshes of section 15.13, eq. 15.13j): the rectangle's injection
//! ([`crate::solver::solid_2d::plane_wave::Injection`]) across any named curve of element
//! edges that cuts the mesh in two.
//!
//! The curve's nodes `L` and one of the two parts of the mesh it leaves hold the total
//! field, the other part the scattered field alone: inside a closed curve the total
//! field (a TF/SF box: the incident wave enters and leaves it exactly, nothing radiates
//! from it), and for an open curve from side to side the part the wave comes from (whose
//! elements along the curve lie first on the wave's path) is the scattered one. The elements of
//! the scattered side that touch the curve (along an edge or at a node) see both, and
//! receive the stiffness coupling across the curve applied to the incident displacement,
//! `f_S += K_SL u_inc,L`, `f_L -= K_LS u_inc,S` (eq. 15.8c), each element's `K` probed
//! from the mesh's own kernel once when the plan is built. Where the mesh allows it: the
//! curve inside one material, crossing no crack or interface, closed, or from one side
//! of the mesh to another. An open curve is exact between periodic sides whose
//! translation is along the wave's fronts; where it ends on any other side the incident
//! wave is cut there, and its ends radiate into both parts (on the example block, 19 %
//! of the incident peak above the line): use a closed curve there.

use super::geometry::{Mesh, NodeIndex};
use super::kernel::Operator;
use super::periodic::Mirrors;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::solver::solid_2d::plane_wave::{Incidence, Injection};
use crate::solver::solid_2d::Elastic;
use std::sync::Arc;

/// A plane wave's line, checked: its nodes, the scattered side's elements that touch it,
/// the material along it.
pub(super) struct Line {
    /// Per node: on the line.
    on_line: Vec<bool>,
    /// The scattered side's elements with a node on the line.
    elements: Vec<usize>,
    /// The material along the line.
    pub material: Elastic,
}

/// The wave's unit propagation direction at `angle` (rad from +z toward +x).
fn direction(angle: f64) -> [f64; 2] {
    let (sin, cos) = angle.sin_cos();
    [sin, cos]
}

/// Union-find root of `i`.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Check the curve `curve` of `mesh` as the line of a plane wave at `angle` (rad): inside
/// the mesh, crossing no crack, cutting the mesh in two, in one material, its fronts
/// repeating across the periodic sides (`mirrors`). Errors name `key` (the source's).
pub(super) fn line(
    mesh: &Mesh,
    curve: &str,
    angle: f64,
    materials: &[Elastic],
    mirrors: &Mirrors,
    file: &str,
    key: &str,
) -> Result<Line> {
    let field = format!("{key}.group");
    let bad = |value: String, allowed: &str| Error::invalid(file, &field, value, allowed);
    let across = |p: [f64; 2]| {
        bad(
            format!(
                "`{curve}` across a crack or interface near x = {:.4e} m, z = {:.4e} m",
                p[0], p[1]
            ),
            "a line that no crack or contact interface crosses",
        )
    };
    let set = mesh.set(curve, &field)?;
    let n = mesh.gll.order;
    let mut on_line = vec![false; mesh.n_nodes()];
    for (_, on) in &set.segments {
        let [a, b] = match on.as_slice() {
            [a, b] => [*a, *b],
            _ => {
                return Err(bad(
                    format!("`{curve}` on the mesh's boundary"),
                    "a curve inside the mesh from one side to another (the \
                     total-field/scattered-field line)",
                ))
            }
        };
        let nodes = |(e, s): (u32, u8)| {
            let mut v: Vec<usize> = (0..=n)
                .map(|k| mesh.side_point(e as usize, s, k).0)
                .collect();
            v.sort_unstable();
            v
        };
        let na = nodes(a);
        if na != nodes(b) {
            return Err(across(mesh.position[na[0]]));
        }
        for g in na {
            on_line[g] = true;
        }
    }
    // (a crack that crosses the line gives it two nodes at one point)
    let (lo, hi) = mesh.position.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    let mut index = NodeIndex::new(1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]));
    let mut seen = Vec::new();
    for (g, _) in on_line.iter().enumerate().filter(|(_, on)| **on) {
        let before = seen.len();
        index.find_or_insert(mesh.position[g], &mut seen);
        if seen.len() == before {
            return Err(across(mesh.position[g]));
        }
    }
    // the parts the line leaves: elements joined through nodes off the line (and across
    // the periodic sides)
    let mm = mesh.per_element();
    let ne = mesh.n_elements();
    let mut parent: Vec<usize> = (0..ne).collect();
    let mut owner = vec![usize::MAX; mesh.n_nodes()];
    for e in 0..ne {
        for &g in &mesh.conn[e * mm..(e + 1) * mm] {
            let g = g as usize;
            if on_line[g] {
                continue;
            }
            if owner[g] == usize::MAX {
                owner[g] = e;
            } else {
                let (r1, r2) = (root(&mut parent, e), root(&mut parent, owner[g]));
                parent[r1] = r2;
            }
        }
    }
    for &(q, r) in mirrors {
        if owner[q] != usize::MAX && owner[r] != usize::MAX {
            let (r1, r2) = (root(&mut parent, owner[q]), root(&mut parent, owner[r]));
            parent[r1] = r2;
        }
    }
    let roots: Vec<usize> = (0..ne).map(|e| root(&mut parent, e)).collect();
    let mut parts: Vec<usize> = roots.clone();
    parts.sort_unstable();
    parts.dedup();
    if parts.len() != 2 {
        return Err(bad(
            format!(
                "`{curve}`, which leaves the mesh in {} part(s)",
                parts.len()
            ),
            "a line from one side of the mesh to another, cutting it in two",
        ));
    }
    let k = direction(angle);
    let touching: Vec<usize> = (0..ne)
        .filter(|&e| {
            mesh.conn[e * mm..(e + 1) * mm]
                .iter()
                .any(|&g| on_line[g as usize])
        })
        .collect();
    // each part's mean k . x over its elements along the line
    let mut mean = [(0.0, 0usize); 2];
    for &e in &touching {
        let side = usize::from(roots[e] == parts[1]);
        let c = &mesh.conn[e * mm..(e + 1) * mm];
        let kx: f64 = c
            .iter()
            .map(|&g| {
                let p = mesh.position[g as usize];
                k[0] * p[0] + k[1] * p[1]
            })
            .sum::<f64>()
            / mm as f64;
        mean[side].0 += kx;
        mean[side].1 += 1;
    }
    let avg = |s: usize| mean[s].0 / mean[s].1.max(1) as f64;
    let scattered = if super::periodic::ends(mesh, set).is_empty() {
        // a closed curve: the scattered field outside it (the part of the mesh's
        // leftmost node off the curve)
        let outer = (0..mesh.n_nodes())
            .filter(|&g| !on_line[g] && owner[g] != usize::MAX)
            .min_by(|&a, &b| {
                let (p, q) = (mesh.position[a], mesh.position[b]);
                p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
            });
        outer.map_or(parts[0], |g| roots[owner[g]])
    } else {
        parts[usize::from(avg(1) < avg(0))]
    };
    let tag = mesh.material[touching[0]];
    if let Some(&e) = touching.iter().find(|&&e| mesh.material[e] != tag) {
        let p = mesh.position[mesh.conn[e * mm] as usize];
        return Err(bad(
            format!(
                "`{curve}` between materials near x = {:.4e} m, z = {:.4e} m",
                p[0], p[1]
            ),
            "a line inside one material",
        ));
    }
    for &(q, r) in mirrors {
        let (pq, pr) = (mesh.position[q], mesh.position[r]);
        let d = [pq[0] - pr[0], pq[1] - pr[1]];
        if (k[0] * d[0] + k[1] * d[1]).abs() > 1e-9 * d[0].hypot(d[1]) {
            return Err(Error::invalid(
                file,
                format!("{key}.angle"),
                crate::numeric::shown_degrees(angle),
                "fronts along the periodic sides' translation (0 degrees across a \
                 horizontal period: an oblique burst does not repeat across it)",
            ));
        }
    }
    Ok(Line {
        on_line,
        elements: touching
            .into_iter()
            .filter(|&e| roots[e] == scattered)
            .collect(),
        material: materials[tag as usize],
    })
}

/// The injection of source `source` (`incidence` at `angle`, rad, with `signal`, the
/// wave's stress at its front, Pa) across `line`, its couplings probed from `op`;
/// `timing = (dt, duration)` (s).
#[allow(clippy::too_many_arguments)]
pub(super) fn injection(
    mesh: &Mesh,
    op: &Operator,
    line: &Line,
    incidence: Incidence,
    angle: f64,
    signal: &Arc<dyn Excitation>,
    source: usize,
    timing: (f64, f64),
    file: &str,
    key: &str,
) -> Result<Injection> {
    let comps = if op.antiplane { 1 } else { 2 };
    let mat = line.material;
    let speed = match incidence {
        Incidence::P => mat.p_speed,
        _ => mat.s_speed,
    };
    let k = direction(angle);
    let pol: [f64; 2] = match incidence {
        Incidence::P => k,
        Incidence::Sv => [k[1], -k[0]],
        Incidence::Sh => [1.0, 0.0],
    };
    let amp = -1.0 / (mat.density * speed);
    let mm = mesh.per_element();
    let len = comps * mesh.n_nodes();
    let mut unit = vec![0.0; len];
    let mut col = vec![0.0; len];
    let mut sample_of = std::collections::BTreeMap::new();
    let (mut kx, mut scale) = (Vec::new(), Vec::new());
    let mut raw: Vec<(usize, usize, f64)> = Vec::new();
    for &e in &line.elements {
        let conn = &mesh.conn[e * mm..(e + 1) * mm];
        for &gj in conn {
            let gj = gj as usize;
            let j_on = line.on_line[gj];
            for cj in 0..comps {
                let p = if comps == 1 { 1.0 } else { pol[cj] };
                if p == 0.0 {
                    continue;
                }
                let dof = comps * gj + cj;
                let sample = *sample_of.entry(dof).or_insert_with(|| {
                    let x = mesh.position[gj];
                    kx.push(k[0] * x[0] + k[1] * x[1]);
                    scale.push(amp * p);
                    kx.len() - 1
                });
                // column (j, cj) of the element's -K
                unit[dof] = 1.0;
                op.add_element_forces(mesh, e, &unit, &mut col);
                unit[dof] = 0.0;
                for &gi in conn {
                    let gi = gi as usize;
                    for ci in 0..comps {
                        let w = std::mem::take(&mut col[comps * gi + ci]);
                        if line.on_line[gi] == j_on || w == 0.0 {
                            continue;
                        }
                        // K = -col; S rows: +K_SL u_L; L rows: -K_LS u_S
                        let sign = if j_on { -1.0 } else { 1.0 };
                        raw.push((comps * gi + ci, sample, sign * w));
                    }
                }
            }
        }
    }
    Injection::from_couplings(
        source,
        (kx, scale),
        raw,
        (speed, k),
        signal,
        timing,
        file,
        key,
    )
}

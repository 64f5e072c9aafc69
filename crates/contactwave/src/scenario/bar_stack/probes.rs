//! Validation step for the probes: names, positions, and the mesh nodes they record.

use super::inv;
use super::spec::ProbeSpec;
use crate::error::Result;
use crate::solver::bar_stack::{BarStack, Mesh};

/// A probe resolved to the mesh.
#[derive(Debug, Clone)]
pub struct BarProbe {
    /// Name.
    pub name: String,
    /// Requested position, m.
    pub x: f64,
    /// Global node recorded.
    pub node: usize,
    /// The neighbouring node of the same segment used for the strain, and the signed
    /// distance to it (m): `stress = E (u[other] - u[node]) / distance`.
    pub other: usize,
    /// Signed distance from `node` to `other`, m.
    pub distance: f64,
    /// Young's modulus of the probe's segment, Pa.
    pub youngs_modulus: f64,
    /// The probe on the transverse field's mesh, when the stack has one.
    pub shear: Option<ShearProbe>,
}

/// A probe on the transverse field's mesh: `shear stress = G (u[other] - u[node]) /
/// distance`.
#[derive(Debug, Clone, Copy)]
pub struct ShearProbe {
    /// Global node recorded (of [`BarStack::shear_mesh`]).
    pub node: usize,
    /// Neighbouring node of the same segment.
    pub other: usize,
    /// Signed distance from `node` to `other`, m.
    pub distance: f64,
    /// Shear modulus of the probe's segment, Pa.
    pub shear_modulus: f64,
}

/// The node nearest `x` (m from the start of segment `seg`) on `mesh` and its neighbour in
/// the same segment with the signed distance to it, m.
fn nodes_at(stack: &BarStack, mesh: &Mesh, seg: usize, x: f64) -> (usize, usize, f64) {
    let node = stack.node_at(mesh, seg, x);
    let last = mesh.offset[seg] + mesh.cells[seg];
    if node < last {
        (node, node + 1, mesh.dx[seg])
    } else {
        (node, node - 1, -mesh.dx[seg])
    }
}

/// Resolve the probes to the mesh of `stack` at time step `dt`: each needs a unique name
/// of letters, digits and `_`, and a position on the stack; it records the nearest node
/// (on the first segment at a shared boundary) and takes the strain towards its
/// neighbour in the same segment.
pub(super) fn resolve_probes(
    specs: &[ProbeSpec],
    stack: &BarStack,
    dt: f64,
    file: &str,
) -> Result<Vec<BarProbe>> {
    let segments = &stack.segments;
    let mesh = stack.mesh(dt);
    let shear_mesh = stack.shear_mesh(dt);
    let total: f64 = segments.iter().map(|s| s.length).sum();
    let mut probes = Vec::with_capacity(specs.len());
    for (k, p) in specs.iter().enumerate() {
        let ok_name = !p.name.is_empty()
            && p.name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !ok_name || specs[..k].iter().any(|q| q.name == p.name) {
            return Err(inv(
                file,
                format!("probe.{k}.name"),
                &p.name,
                "a unique name of letters, digits and _",
            ));
        }
        if !(p.x.is_finite() && p.x >= 0.0 && p.x <= total) {
            return Err(inv(
                file,
                format!("probe.{k}.x"),
                p.x,
                &format!("in [0, {total}] m (the length of the stack)"),
            ));
        }
        let mut start = 0.0;
        let mut seg = segments.len() - 1;
        for (i, sg) in segments.iter().enumerate() {
            if p.x <= start + sg.length {
                seg = i;
                break;
            }
            start += sg.length;
        }
        let (node, other, distance) = nodes_at(stack, &mesh, seg, p.x - start);
        let shear = shear_mesh.as_ref().map(|sm| {
            let (node, other, distance) = nodes_at(stack, sm, seg, p.x - start);
            ShearProbe {
                node,
                other,
                distance,
                shear_modulus: segments[seg].material.shear_modulus.unwrap_or(f64::NAN),
            }
        });
        probes.push(BarProbe {
            shear,
            name: p.name.clone(),
            x: p.x,
            node,
            other,
            distance,
            youngs_modulus: segments[seg].material.youngs_modulus,
        });
    }
    Ok(probes)
}

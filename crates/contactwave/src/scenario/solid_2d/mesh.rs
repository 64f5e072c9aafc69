//! 2D scenarios on a mesh (`[mesh] file = "part.msh"`, docs/mesh.md): the Gmsh file read,
//! its physical surfaces given materials (`[[material]] group`), its physical curves made
//! sides (`[[boundary]] group, kind`), cracks and contact interfaces (`[[crack]] group` with
//! every law key of a rectangle's crack and a closure table along the arc length) and
//! transducer apertures (`[[source]] group`); point forces and receivers anywhere in the
//! mesh. The scenario's `problem` stands for the mesh (its bounding box, materials and
//! largest element, the cracks' laws and the sources' signals) so that the analysis, the
//! twins of the analysis methods and the summary are the rectangle's.

use super::closure::ClosureProfile;
use super::{
    gate, inv, material, parse, positive, receivers, CrackSpec, LayerSpec, Solid2dScenario,
    Solid2dSpec, DEFAULT_HARMONIC, DEFAULT_ORDER, PHASE_STEP,
};
use crate::error::Result;
use crate::excitation::Excitation;
use crate::law::point::SharedLaw;
use crate::scenario::BuildCache;
use crate::solver::solid_2d::pml;
use crate::solver::solid_2d::quad::input::QuadInput;
use crate::solver::solid_2d::quad::{
    gmsh, Boundary, QuadCrack, QuadSolid, QuadSource, QuadSourceKind,
};
use crate::solver::solid_2d::region::Region;
use crate::solver::solid_2d::{
    Backend, Crack, CrackProfile, Layer, Pml, Side, Solid2d, Source, SourceKind, WaveType,
};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// `[mesh]`: the mesh file and the GLL order of its elements.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// A Gmsh MSH 4.1 ASCII file (relative to the scenario's folder): quadrilaterals of
    /// first or second order in physical surfaces, named physical curves.
    pub file: String,
    /// GLL order of the elements, 2 to 8 (default 6, as the rectangle's `model.order`).
    pub order: Option<usize>,
    /// Each element of the file split into `refine x refine` along its own map, 1 to 8
    /// (default 1: the file's elements; docs/model.md eq. 15.13h).
    pub refine: Option<usize>,
}

/// The range of `mesh.refine`.
pub const REFINE: std::ops::RangeInclusive<usize> = 1..=8;

/// `[[material]]`: the material of a physical surface (the keys of a `[[layer]]` without
/// its thickness).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// The physical surface's name.
    pub group: String,
    /// A named material (`aluminium`, `steel`, ...).
    pub material: Option<String>,
    /// Young's modulus, Pa.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio.
    pub poisson_ratio: Option<f64>,
    /// Density, kg/m^3.
    pub density: Option<f64>,
    /// P-wave speed, m/s.
    pub p_speed: Option<f64>,
    /// S-wave speed, m/s.
    pub s_speed: Option<f64>,
}

/// `[[boundary]]`: what a physical curve of the mesh is (every curve not named is free).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// The physical curve's name.
    pub group: String,
    /// `free`, `rigid`, `absorbing` (Lysmer's dashpots), `pml` (a Cartesian PML frame
    /// outside a straight side on the mesh's bounding box) or `periodic` (with `partner`).
    pub kind: String,
    /// The periodic partner: the physical curve that is `group` moved by a translation.
    #[serde(default)]
    pub partner: Option<String>,
}

/// The start of a crack that gives none (a mesh's crack, by its group).
pub(super) fn unset_point() -> [f64; 2] {
    [f64::NAN; 2]
}

/// The mesh file's bytes: its size checked against the memory budget before it is read.
fn read_mesh(path: &Path, shown: &str, file: &str) -> Result<QuadInput> {
    let size = std::fs::metadata(path)
        .map_err(|e| inv(file, "mesh.file", shown, &format!("a readable file ({e})")))?
        .len();
    // (the text, the nodes and elements it holds: about 3 times its size)
    crate::budget::check_or(
        file,
        "mesh.file",
        shown,
        3.0 * size as f64,
        "the mesh file",
        "a smaller mesh",
    )?;
    let bytes = std::fs::read(path)
        .map_err(|e| inv(file, "mesh.file", shown, &format!("a readable file ({e})")))?;
    gmsh::read(&bytes, shown)
}

/// A key of the rectangle that a mesh scenario does not take, if given.
fn rectangle_key(spec: &Solid2dSpec) -> Option<(String, &'static str)> {
    let m = &spec.model;
    let named = [
        ("model.width", m.width != 0.0),
        ("model.element_size", m.element_size.is_some()),
        ("model.order", m.order.is_some()),
        ("model.top", m.top != "free"),
        ("model.bottom", m.bottom != "free"),
        ("model.sides", m.sides != "free"),
        ("model.prestress", m.prestress.is_some()),
        ("layer", !spec.layers.is_empty()),
    ];
    named.iter().find(|(_, set)| *set).map(|(k, _)| {
        let why = match *k {
            "model.width" | "layer" => {
                "not with [mesh]: the mesh is the specimen ([[material]] for its surfaces)"
            }
            "model.element_size" => {
                "not with [mesh]: the element size is the mesh's (re-mesh with a smaller h)"
            }
            "model.order" => "not with [mesh]: the order is `mesh.order`",
            "model.top" | "model.bottom" | "model.sides" => {
                "not with [mesh]: the sides are its physical curves ([[boundary]] group, kind)"
            }
            _ => "not with [mesh] (the prestress of a rectangle's cracks)",
        };
        (k.to_string(), why)
    })
}

/// Validate a mesh scenario (`[mesh]` given).
pub(super) fn from_spec(
    spec: Solid2dSpec,
    file: &str,
    dir: &Path,
    cache: &BuildCache,
) -> Result<Solid2dScenario> {
    let m = &spec.model;
    if let Some((key, why)) = rectangle_key(&spec) {
        return Err(inv(file, key, "given", why));
    }
    let wave = match m.wave.as_str() {
        "p_sv" => WaveType::PSv,
        "sh" => WaveType::Sh,
        w => return Err(inv(file, "model.wave", w, "p_sv or sh")),
    };
    positive(file, "model.duration", m.duration)?;
    let ms = spec.mesh.as_ref().expect("a mesh scenario");
    let input = read_mesh(&dir.join(&ms.file), &ms.file, file)?;
    let order = ms.order.unwrap_or(DEFAULT_ORDER);
    if !crate::solver::solid_2d::ORDERS.contains(&order) {
        return Err(inv(file, "mesh.order", order, "2 to 8"));
    }
    let refine = ms.refine.unwrap_or(1);
    if !REFINE.contains(&refine) {
        return Err(inv(
            file,
            "mesh.refine",
            refine,
            "1 to 8 (each element split into refine x refine)",
        ));
    }
    let input = if refine > 1 {
        // (the refined control nodes and elements, before they are made: 16 bytes a node,
        // 40 an element)
        let elements = (input.quads.len() * refine * refine) as f64;
        crate::budget::check_or(
            file,
            "mesh.refine",
            refine,
            16.0 * input.refined_nodes(refine) + 40.0 * elements,
            &format!("the refined mesh of {elements:.3e} elements"),
            "a smaller `mesh.refine`",
        )?;
        input.refine(refine)
    } else {
        input
    };
    // materials: one for each physical surface
    for (i, mat) in spec.materials.iter().enumerate() {
        if !input.materials.contains(&mat.group) {
            return Err(inv(
                file,
                format!("material.{i}.group"),
                &mat.group,
                &format!(
                    "a physical surface of {}: {}",
                    ms.file,
                    input.materials.join(", ")
                ),
            ));
        }
    }
    let mut materials = Vec::new();
    for name in &input.materials {
        let Some(i) = spec.materials.iter().position(|s| &s.group == name) else {
            return Err(inv(
                file,
                "material",
                format!("none for `{name}`"),
                &format!(
                    "a [[material]] for each physical surface of {}: {}",
                    ms.file,
                    input.materials.join(", ")
                ),
            ));
        };
        let s = &spec.materials[i];
        let layer = LayerSpec {
            thickness: 1.0,
            material: s.material.clone(),
            youngs_modulus: s.youngs_modulus,
            poisson_ratio: s.poisson_ratio,
            density: s.density,
            p_speed: s.p_speed,
            s_speed: s.s_speed,
        };
        materials.push(material::material(&layer, file, &format!("material.{i}"))?);
    }
    let curves: Vec<&str> = input.curves.iter().map(|c| c.0.as_str()).collect();
    let curve = |key: String, name: &str| -> Result<String> {
        if curves.contains(&name) {
            Ok(name.to_string())
        } else {
            Err(inv(
                file,
                key,
                name,
                &format!("a physical curve of {}: {}", ms.file, curves.join(", ")),
            ))
        }
    };
    let mut boundaries = Vec::new();
    let mut periodic = Vec::new();
    for (i, b) in spec.boundaries.iter().enumerate() {
        let group = curve(format!("boundary.{i}.group"), &b.group)?;
        let kind = match (b.kind.as_str(), &b.partner) {
            ("periodic", Some(partner)) => {
                let partner = curve(format!("boundary.{i}.partner"), partner)?;
                if partner == group {
                    return Err(inv(
                        file,
                        format!("boundary.{i}.partner"),
                        &partner,
                        "another physical curve than `group`",
                    ));
                }
                periodic.push((group, partner));
                continue;
            }
            ("periodic", None) => {
                return Err(inv(
                    file,
                    format!("boundary.{i}.partner"),
                    "missing",
                    "the physical curve that is `group` moved by a translation",
                ))
            }
            (_, Some(_)) => {
                return Err(inv(
                    file,
                    format!("boundary.{i}.partner"),
                    "given",
                    "only with kind = \"periodic\"",
                ))
            }
            ("free", None) => Boundary::Free,
            ("rigid", None) => Boundary::Rigid,
            ("absorbing", None) => Boundary::Absorbing,
            ("pml", None) => Boundary::Pml,
            (k, None) => {
                return Err(inv(
                    file,
                    format!("boundary.{i}.kind"),
                    k,
                    "free, rigid, absorbing, pml or periodic",
                ))
            }
        };
        boundaries.push((group, kind));
    }
    // the bounding box, the largest element edge
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &input.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let h_max = input.side_lengths().fold(0.0f64, f64::max);
    // the PML frame's keys: only with a pml side
    let framed = boundaries.iter().any(|(_, k)| *k == Boundary::Pml);
    for (key, given) in [
        ("model.pml_thickness", m.pml_thickness.is_some()),
        ("model.pml_reflection", m.pml_reflection.is_some()),
    ] {
        if given && !framed {
            return Err(inv(
                file,
                key,
                "given",
                "only with a [[boundary]] of kind = \"pml\" (the frame's thickness and reflection)",
            ));
        }
    }
    let pml = if framed {
        let reflection = m.pml_reflection.unwrap_or(pml::DEFAULT_REFLECTION);
        if !(reflection > 0.0 && reflection < 1.0) {
            return Err(inv(file, "model.pml_reflection", reflection, "in (0, 1)"));
        }
        Some(Pml {
            thickness: match m.pml_thickness {
                Some(l) => positive(file, "model.pml_thickness", l)?,
                None => pml::DEFAULT_ELEMENTS * h_max,
            },
            reflection,
        })
    } else {
        None
    };
    // sources
    if spec.sources.is_empty() {
        return Err(inv(file, "source", "none", "at least one [[source]]"));
    }
    let mut sources = Vec::new();
    let mut quad_sources = Vec::new();
    let mut f0 = 0.0;
    for (i, s) in spec.sources.iter().enumerate() {
        let key = format!("source.{i}");
        let signal: Arc<dyn Excitation> = crate::scenario::build_wave(
            &s.signal,
            &format!("{key}.signal"),
            file,
            dir,
            None,
            cache,
            Some(m.duration),
        )?
        .0;
        if i == 0 {
            f0 = signal.fundamental();
        }
        for (k, set) in [
            ("x0", s.x0.is_some()),
            ("x1", s.x1.is_some()),
            ("surface", s.surface.is_some()),
        ] {
            if set {
                return Err(inv(
                    file,
                    format!("{key}.{k}"),
                    "given",
                    "not with [mesh]: a transducer's aperture is `group`, a physical curve",
                ));
            }
        }
        let kind = match s.kind.as_str() {
            "transducer" => {
                let group = s.group.as_deref().ok_or_else(|| {
                    inv(
                        file,
                        format!("{key}.group"),
                        "missing",
                        "the physical curve of the aperture",
                    )
                })?;
                let normal = match s.component.as_deref().unwrap_or("normal") {
                    "normal" => true,
                    "shear" => false,
                    v => return Err(inv(file, format!("{key}.component"), v, "normal or shear")),
                };
                if normal && wave == WaveType::Sh {
                    return Err(inv(
                        file,
                        format!("{key}.component"),
                        "normal",
                        "shear (an SH run has no normal motion)",
                    ));
                }
                if !(s.angle.abs() < 90.0) {
                    return Err(inv(
                        file,
                        format!("{key}.angle"),
                        s.angle,
                        "in (-90, 90) degrees",
                    ));
                }
                let mat = materials[0];
                let c = if normal { mat.p_speed } else { mat.s_speed };
                QuadSourceKind::Traction {
                    curve: curve(format!("{key}.group"), group)?,
                    normal,
                    delay_per_m: s.angle.to_radians().sin() / c,
                }
            }
            "force" => {
                let at = s.at.ok_or_else(|| {
                    inv(
                        file,
                        format!("{key}.at"),
                        "missing",
                        "the force's position [x, z], m",
                    )
                })?;
                let d = s.direction.unwrap_or([0.0, 1.0]);
                let n = d[0].hypot(d[1]);
                if !(n > 0.0 && n.is_finite()) {
                    return Err(inv(
                        file,
                        format!("{key}.direction"),
                        format!("{d:?}"),
                        "a nonzero direction [x, z]",
                    ));
                }
                QuadSourceKind::Force {
                    at,
                    direction: [d[0] / n, d[1] / n],
                }
            }
            "plane_wave" => {
                if s.z.is_some() {
                    return Err(inv(
                        file,
                        format!("{key}.z"),
                        "given",
                        "not with [mesh]: a plane wave's line is `group`, a physical curve",
                    ));
                }
                let group = s.group.as_deref().ok_or_else(|| {
                    inv(
                        file,
                        format!("{key}.group"),
                        "missing",
                        "the physical curve the plane wave is injected across (a line of \
                         element edges that cuts the mesh in two)",
                    )
                })?;
                let incidence = parse::incidence(s, wave, file, &key)?;
                if !(s.angle.abs() < 90.0) {
                    return Err(inv(
                        file,
                        format!("{key}.angle"),
                        s.angle,
                        "in (-90, 90) degrees",
                    ));
                }
                QuadSourceKind::PlaneWave {
                    curve: curve(format!("{key}.group"), group)?,
                    incidence,
                    angle: s.angle.to_radians(),
                }
            }
            k => {
                return Err(inv(
                    file,
                    format!("{key}.kind"),
                    k,
                    "transducer, force or plane_wave",
                ));
            }
        };
        sources.push(Source {
            kind: SourceKind::Force {
                at: [0.0; 2],
                direction: [0.0, 1.0],
            },
            signal: signal.clone(),
        });
        quad_sources.push(QuadSource { kind, signal });
    }
    // cracks
    let mut cracks = Vec::new();
    let mut quad_cracks = Vec::new();
    for (i, c) in spec.cracks.iter().enumerate() {
        let key = format!("crack.{i}");
        if !c.start[0].is_nan() || c.end.is_some() || c.length.is_some() || c.full_width {
            return Err(inv(
                file,
                format!("{key}.start"),
                "given",
                "not with [mesh]: a crack is `group`, a physical curve",
            ));
        }
        let group = c.group.as_deref().ok_or_else(|| {
            inv(
                file,
                format!("{key}.group"),
                "missing",
                "the crack's physical curve",
            )
        })?;
        let group = curve(format!("{key}.group"), group)?;
        let segments = input.curve(&group).unwrap_or(&[]);
        let length: f64 = segments
            .iter()
            .map(|s| {
                let (a, b) = (input.nodes[s[0] as usize], input.nodes[s[1] as usize]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .sum();
        let normal = cache.law(c.static_pressure, &c.compression, &c.traction, file, &key)?;
        let tangential = crate::law::registry::build_tangential(
            &c.tangential,
            c.static_shear,
            &normal,
            file,
            &key,
        )?;
        let profile = match &c.closure {
            Some(t) => {
                // (positions along the arc length; the table's check reads a crack from 0)
                let along = CrackSpec {
                    start: [0.0, 0.0],
                    end: Some([length, 0.0]),
                    ..c.clone()
                };
                Some(
                    Arc::new(ClosureProfile::new(&along, t, length, file, &key)?)
                        as Arc<dyn CrackProfile<SharedLaw>>,
                )
            }
            None => None,
        };
        let law = SharedLaw {
            normal,
            tangential: Arc::new(tangential),
        };
        let ends = segments
            .first()
            .zip(segments.last())
            .map(|(a, b)| (input.nodes[a[0] as usize], input.nodes[b[1] as usize]))
            .unwrap_or(([0.0; 2], [0.0; 2]));
        cracks.push(Crack {
            start: ends.0,
            end: ends.1,
            full_width: false,
            law: law.clone(),
            profile: profile.clone(),
        });
        quad_cracks.push(QuadCrack {
            curve: group,
            law,
            profile,
        });
    }
    let receivers::Checked {
        points,
        receivers,
        stress_points,
    } = {
        let along = |i: usize, g: &str, n: usize| -> Result<Vec<[f64; 2]>> {
            let field = format!("receiver.{i}.group");
            match input.along(g, n) {
                Some(Ok(points)) => Ok(points),
                Some(Err(what)) => Err(inv(
                    file,
                    field,
                    format!("`{g}`: {what}"),
                    "a chain of element edges, open or closed",
                )),
                None => {
                    let names: Vec<&str> = input.curves.iter().map(|(n, _)| n.as_str()).collect();
                    Err(inv(
                        file,
                        field,
                        g,
                        &format!("a physical curve of {}: {}", ms.file, names.join(", ")),
                    ))
                }
            }
        };
        receivers::check_in(&spec.receivers, wave, Region::bounds(lo, hi), &along, file)?
    };
    let harmonic = m.harmonic.unwrap_or(DEFAULT_HARMONIC);
    if !(harmonic.is_finite() && harmonic >= 1.0) {
        return Err(inv(file, "model.harmonic", harmonic, ">= 1"));
    }
    let max_time_step = match m.time_step {
        Some(dt) => positive(file, "model.time_step", dt)?,
        None => PHASE_STEP / (2.0 * std::f64::consts::PI * harmonic * f0),
    };
    let courant = m.courant.unwrap_or(0.9);
    let crack_every = match m.crack_every.unwrap_or(10) {
        0 => {
            return Err(inv(
                file,
                "model.crack_every",
                0,
                "a whole number >= 1 (steps)",
            ))
        }
        n => n,
    };
    if let Some(b) = m.backend.as_deref()
        && b != "cpu"
    {
        return Err(inv(
            file,
            "model.backend",
            b,
            "`cpu` (the GPU backend is the rectangle's)",
        ));
    }
    let problem = Solid2d {
        width: hi[0] - lo[0],
        layers: materials
            .iter()
            .map(|&material| Layer {
                bottom: hi[1] - lo[1],
                material,
            })
            .collect(),
        wave,
        top: Side::Free,
        bottom: Side::Free,
        sides: Side::Free,
        element_size: h_max,
        order,
        courant,
        max_time_step,
        cracks,
        sources,
        receivers: points.clone(),
        duration: m.duration,
        crack_every,
        pml: Pml {
            thickness: 0.0,
            reflection: crate::solver::solid_2d::pml::DEFAULT_REFLECTION,
        },
    };
    let quad = QuadSolid {
        input: Arc::new(input),
        order,
        materials,
        wave,
        courant,
        max_time_step,
        boundaries,
        periodic,
        cracks: quad_cracks,
        sources: quad_sources,
        receivers: points,
        stress_receivers: stress_points.clone(),
        duration: m.duration,
        crack_every,
        pml,
    };
    let split = quad.check(file)?;
    // every receiver inside the mesh, named by its table (a line's points by its first)
    for r in &receivers {
        let at = if r.stress {
            quad.stress_receivers[r.index]
        } else {
            quad.receivers[r.index]
        };
        if split.locate(at).is_none() {
            return Err(inv(
                file,
                format!("receiver.{}.at", r.table),
                format!("[{:e}, {:e}]", at[0], at[1]),
                "a point inside the mesh",
            ));
        }
    }
    let gate = gate::analysis_gate(&spec.analysis, file, m.duration, f0)?;
    let mut receivers = receivers;
    gate::receiver_gates(&spec, &mut receivers, gate, file, m.duration, f0)?;
    let snapshots = match &spec.snapshots {
        Some(s) => Some(s.check(file, m.duration, wave)?),
        None => None,
    };
    Ok(Solid2dScenario {
        spec,
        file: file.to_string(),
        problem,
        f0,
        receivers,
        stress_points,
        gate,
        snapshots,
        backend: Backend::Cpu,
        mesh: Some(quad),
    })
}

impl Solid2dScenario {
    /// The mesh problem as it runs: the cracks' laws and the sources' signals of
    /// `problem` (the scenario's, or a twin's).
    pub fn mesh_problem(&self, problem: &Solid2d<SharedLaw>) -> Option<QuadSolid<SharedLaw>> {
        let mut q = self.mesh.clone()?;
        for (c, p) in q.cracks.iter_mut().zip(&problem.cracks) {
            c.law = p.law.clone();
            c.profile = p.profile.clone();
        }
        for (s, p) in q.sources.iter_mut().zip(&problem.sources) {
            s.signal = p.signal.clone();
        }
        Some(q)
    }
}

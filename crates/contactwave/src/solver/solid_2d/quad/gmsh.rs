//! The reader of Gmsh MSH 4.1 ASCII files: quadrilaterals of first (4-node) or second
//! order (9-node), physical surfaces as materials, physical curves as named curves (their
//! line elements' end nodes), physical points as named points. Gmsh's `(x, y)` is the
//! solver's `(x, z)`: z, the depth, is Gmsh's y (docs/mesh.md). (The `mshio` crate was
//! tried first: it drops the node tags of a file whose tags are dense, which Gmsh's
//! blocks do not list in order, so the reader is ours: a token scanner over the four
//! sections it needs.)

use super::input::QuadInput;
use crate::error::{Error, Result};
use std::collections::HashMap;

/// The nodes of a Gmsh element of type `t` (the types a 2D mesh holds), or `None`.
fn nodes_of(t: u32) -> Option<usize> {
    Some(match t {
        1 => 2,
        2 => 3,
        3 => 4,
        8 => 3,
        9 => 6,
        10 => 9,
        15 => 1,
        16 => 8,
        20 => 9,
        21 => 10,
        26 => 4,
        36 => 16,
        _ => return None,
    })
}

/// The whitespace-separated tokens of a section's body.
struct Tokens<'a> {
    it: std::str::SplitAsciiWhitespace<'a>,
    file: &'a str,
    section: &'static str,
}

impl Tokens<'_> {
    fn next<T: std::str::FromStr>(&mut self) -> Result<T> {
        let tok = self.it.next();
        tok.and_then(|t| t.parse().ok()).ok_or_else(|| {
            Error::invalid(
                self.file,
                format!("${}", self.section),
                tok.unwrap_or("the end").to_string(),
                "a valid MSH 4.1 ASCII section",
            )
        })
    }
}

/// The body of section `name` (between `$name` and `$Endname`).
fn section<'a>(text: &'a str, name: &str) -> Option<&'a str> {
    let open = format!("${name}\n");
    let start = text.find(&open)? + open.len();
    let end = text[start..].find(&format!("$End{name}"))?;
    Some(&text[start..start + end])
}

/// The physical names of `$PhysicalNames`: `(dimension, tag) -> name`.
fn physical_names(bytes: &[u8]) -> HashMap<(i32, i32), String> {
    let mut names = HashMap::new();
    let text = String::from_utf8_lossy(bytes);
    let Some(start) = text.find("$PhysicalNames") else {
        return names;
    };
    let body = &text[start..];
    let end = body.find("$EndPhysicalNames").unwrap_or(body.len());
    for line in body[..end].lines().skip(2) {
        let mut it = line.splitn(3, char::is_whitespace);
        let (Some(d), Some(t), Some(n)) = (it.next(), it.next(), it.next()) else {
            continue;
        };
        if let (Ok(d), Ok(t)) = (d.parse(), t.parse()) {
            names.insert((d, t), n.trim().trim_matches('"').to_string());
        }
    }
    names
}

/// Read the mesh in `bytes` (the contents of `file`).
pub fn read(bytes: &[u8], file: &str) -> Result<QuadInput> {
    let bad =
        |field: &str, value: String, allowed: &str| Error::invalid(file, field, value, allowed);
    if !bytes.starts_with(b"$MeshFormat") {
        return Err(bad(
            "mesh.file",
            "not a Gmsh mesh".into(),
            "a Gmsh MSH 4.1 file (`gmsh -2 -format msh41 part.geo`)",
        ));
    }
    let text = String::from_utf8_lossy(bytes);
    let text = text.replace("\r\n", "\n");
    let format = section(&text, "MeshFormat").unwrap_or("");
    let mut head = format.split_ascii_whitespace();
    let version = head.next().unwrap_or("").to_string();
    if !version.starts_with("4.1") {
        return Err(bad(
            "mesh.file",
            format!("MSH version {version}"),
            "MSH 4.1 (Gmsh: Mesh.MshFileVersion = 4.1, or `-format msh41`)",
        ));
    }
    if head.next() != Some("0") {
        return Err(bad(
            "mesh.file",
            "a binary MSH file".into(),
            "an ASCII MSH 4.1 file (Gmsh: Mesh.Binary = 0)",
        ));
    }
    let tokens = |name: &'static str| -> Result<Tokens<'_>> {
        let body = section(&text, name).ok_or_else(|| {
            bad(
                "mesh.file",
                format!("no ${name}"),
                "a meshed MSH 4.1 file (gmsh -2)",
            )
        })?;
        Ok(Tokens {
            it: body.split_ascii_whitespace(),
            file,
            section: name,
        })
    };
    let names = physical_names(bytes);
    let name_of = |dim: i32, tag: i32| {
        names
            .get(&(dim, tag))
            .cloned()
            .unwrap_or_else(|| format!("{tag}"))
    };
    // entities: the physical groups of each point, curve and surface
    let mut groups: HashMap<(i32, i32), Vec<i32>> = HashMap::new();
    let mut t = tokens("Entities")?;
    let counts: [usize; 4] = [t.next()?, t.next()?, t.next()?, t.next()?];
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag: i32 = t.next()?;
            for _ in 0..if dim == 0 { 3 } else { 6 } {
                t.next::<f64>()?;
            }
            let np: usize = t.next()?;
            let mut phys = Vec::with_capacity(np.min(64));
            for _ in 0..np {
                phys.push(t.next::<i32>()?);
            }
            if dim > 0 {
                let nb: usize = t.next()?;
                for _ in 0..nb {
                    t.next::<i64>()?;
                }
            }
            groups.insert((dim as i32, tag), phys);
        }
    }
    // nodes by tag
    let mut t = tokens("Nodes")?;
    let (blocks, total): (usize, usize) = (t.next()?, t.next()?);
    let _: (u64, u64) = (t.next()?, t.next()?);
    if total > bytes.len() {
        return Err(bad(
            "$Nodes",
            total.to_string(),
            "as many nodes as the file holds",
        ));
    }
    let mut nodes = Vec::with_capacity(total);
    let mut index: HashMap<u64, u32> = HashMap::with_capacity(total);
    for _ in 0..blocks {
        let dim: usize = t.next()?;
        let _tag: i32 = t.next()?;
        let parametric: u32 = t.next()?;
        let count: usize = t.next()?;
        let first = nodes.len();
        let mut tags = Vec::with_capacity(count.min(total));
        for _ in 0..count {
            tags.push(t.next::<u64>()?);
        }
        for _ in 0..count {
            let (x, y, _z): (f64, f64, f64) = (t.next()?, t.next()?, t.next()?);
            for _ in 0..if parametric == 1 { dim } else { 0 } {
                t.next::<f64>()?;
            }
            nodes.push([x, y]);
        }
        for (k, tag) in tags.into_iter().enumerate() {
            index.insert(tag, (first + k) as u32);
        }
    }
    let mut input = QuadInput {
        source: file.to_string(),
        nodes,
        ..Default::default()
    };
    let node = |tag: u64| -> Result<u32> {
        index.get(&tag).copied().ok_or_else(|| {
            bad(
                "mesh.file",
                format!("node {tag}"),
                "elements whose nodes are in $Nodes",
            )
        })
    };
    let mut materials: Vec<i32> = Vec::new();
    let mut curves: Vec<(i32, Vec<[u32; 2]>)> = Vec::new();
    let mut order = None;
    let mut t = tokens("Elements")?;
    let blocks: usize = t.next()?;
    let _: (u64, u64, u64) = (t.next()?, t.next()?, t.next()?);
    let mut el = [0u64; 16];
    for _ in 0..blocks {
        let dim: i32 = t.next()?;
        let entity: i32 = t.next()?;
        let kind: u32 = t.next()?;
        let count: usize = t.next()?;
        let Some(k) = nodes_of(kind) else {
            return Err(bad(
                &format!("entity {entity}"),
                format!("element type {kind}"),
                "quadrilaterals of 4 or 9 nodes, and lines and points (a 2D mesh)",
            ));
        };
        let phys = groups.get(&(dim, entity)).cloned().unwrap_or_default();
        let material = if dim == 2 && matches!(kind, 3 | 10) {
            let second = kind == 10;
            if *order.get_or_insert(second) != second {
                return Err(bad(
                    "mesh.file",
                    "first- and second-order elements".into(),
                    "one element order (Gmsh: Mesh.ElementOrder)",
                ));
            }
            let Some(&group) = phys.first() else {
                return Err(bad(
                    &format!("surface {entity}"),
                    "no physical group".into(),
                    "every meshed surface in a physical surface (its material)",
                ));
            };
            Some(match materials.iter().position(|&g| g == group) {
                Some(i) => i,
                None => {
                    materials.push(group);
                    materials.len() - 1
                }
            } as u16)
        } else {
            None
        };
        for _ in 0..count {
            let tag: u64 = t.next()?;
            for slot in el.iter_mut().take(k) {
                *slot = t.next()?;
            }
            match (dim, kind) {
                (2, 3 | 10) => {
                    let mut q = [0u32; 9];
                    for i in 0..k {
                        q[i] = node(el[i])?;
                    }
                    input.quads.push(q);
                    input.material.push(material.unwrap_or(0));
                }
                (2, _) => {
                    let hint = if matches!(kind, 2 | 9) {
                        "quadrilaterals: recombine the triangles in Gmsh (Mesh.RecombineAll = 1; \
                         Mesh.SubdivisionAlgorithm = 1 leaves none)"
                    } else {
                        "4-node or complete 9-node quadrilaterals (Mesh.SecondOrderIncomplete = 0)"
                    };
                    return Err(bad(
                        &format!("element {tag}"),
                        format!("type {kind} in surface {entity}"),
                        hint,
                    ));
                }
                (1, 1 | 8) => {
                    let seg = [node(el[0])?, node(el[1])?];
                    for &g in &phys {
                        match curves.iter_mut().find(|c| c.0 == g) {
                            Some(c) => c.1.push(seg),
                            None => curves.push((g, vec![seg])),
                        }
                    }
                }
                (0, 15) => {
                    let p = input.nodes[node(el[0])? as usize];
                    for &g in &phys {
                        input.points.push((name_of(0, g), p));
                    }
                }
                _ => {}
            }
        }
    }
    input.second_order = order.unwrap_or(false);
    input.materials = materials.iter().map(|&g| name_of(2, g)).collect();
    input.curves = curves
        .into_iter()
        .map(|(g, s)| (name_of(1, g), s))
        .collect();
    if input.quads.is_empty() {
        return Err(bad(
            "mesh.file",
            "no quadrilateral".into(),
            "a 2D mesh of quadrilaterals in physical surfaces",
        ));
    }
    Ok(input)
}

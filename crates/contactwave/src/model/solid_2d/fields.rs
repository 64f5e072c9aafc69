//! The numbers of a 2D scenario that sweeps, identifications and experiment designs set by
//! their dotted keys (`crack.0.static_pressure`, `mesh.order`): [`Fields`] of its spec.

use crate::model::{Fields, Slot};
use crate::scenario::solid_2d::{
    CrackSpec, LayerSpec, ModelSpec, ReceiverSpec, Solid2dSpec, SourceSpec,
};

/// The number at `path` in an array of tables: the item named by a leading decimal index
/// (`source.1.angle`), or the only item when the array has one and the key gives no index
/// (`source.angle` for `source.0.angle`).
fn nth<'a, T: Fields>(items: &'a mut [T], path: &[&str]) -> Option<Slot<'a>> {
    match path {
        [i, rest @ ..] if !i.is_empty() && i.bytes().all(|b| b.is_ascii_digit()) => {
            items.get_mut(i.parse::<usize>().ok()?)?.slot(rest)
        }
        _ => match items {
            [only] => only.slot(path),
            _ => None,
        },
    }
}

impl Fields for Solid2dSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["model", rest @ ..] => self.model.slot(rest),
            ["mesh", "order"] => self
                .mesh
                .as_mut()
                .map(|m| Slot::OptUsize(&mut m.order, crate::solver::solid_2d::ORDERS)),
            ["mesh", "refine"] => self
                .mesh
                .as_mut()
                .map(|m| Slot::OptUsize(&mut m.refine, crate::scenario::solid_2d::mesh::REFINE)),
            ["layer", rest @ ..] => nth(&mut self.layers, rest),
            ["crack", rest @ ..] => nth(&mut self.cracks, rest),
            ["source", rest @ ..] => nth(&mut self.sources, rest),
            ["receiver", rest @ ..] => nth(&mut self.receivers, rest),
            _ => None,
        }
    }
}

impl Fields for ModelSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["width"] => Some(Slot::F64(&mut self.width)),
            ["duration"] => Some(Slot::F64(&mut self.duration)),
            ["element_size"] => Some(Slot::OptF64(&mut self.element_size)),
            ["harmonic"] => Some(Slot::OptF64(&mut self.harmonic)),
            ["courant"] => Some(Slot::OptF64(&mut self.courant)),
            ["time_step"] => Some(Slot::OptF64(&mut self.time_step)),
            ["order"] => Some(Slot::OptUsize(
                &mut self.order,
                crate::solver::solid_2d::ORDERS,
            )),
            ["prestress", c] => {
                let p = self.prestress.get_or_insert_with(Default::default);
                match *c {
                    "xx" => Some(Slot::F64(&mut p.xx)),
                    "zz" => Some(Slot::F64(&mut p.zz)),
                    "xz" => Some(Slot::F64(&mut p.xz)),
                    "xy" => Some(Slot::F64(&mut p.xy)),
                    "yz" => Some(Slot::F64(&mut p.yz)),
                    _ => None,
                }
            }
            _ => None,
        }
    }
}

impl Fields for LayerSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["thickness"] => Some(Slot::F64(&mut self.thickness)),
            ["density"] => Some(Slot::OptF64(&mut self.density)),
            ["youngs_modulus"] => Some(Slot::OptF64(&mut self.youngs_modulus)),
            ["poisson_ratio"] => Some(Slot::OptF64(&mut self.poisson_ratio)),
            ["p_speed"] => Some(Slot::OptF64(&mut self.p_speed)),
            ["s_speed"] => Some(Slot::OptF64(&mut self.s_speed)),
            _ => None,
        }
    }
}

impl Fields for CrackSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["static_pressure"] => Some(Slot::F64(&mut self.static_pressure)),
            ["static_shear"] => Some(Slot::F64(&mut self.static_shear)),
            // the crack's length from its left (top) tip, along its line (a given end
            // becomes the length and the orientation it implies; an end left of or above
            // the start becomes the start, so that the crack keeps its place)
            ["length"] => {
                if let Some(e) = self.end.take() {
                    self.vertical = e[0] == self.start[0] && e[1] != self.start[1];
                    let k = usize::from(self.vertical);
                    if e[k] < self.start[k] {
                        self.length = Some(self.start[k] - e[k]);
                        self.start = e;
                    } else {
                        self.length = Some(e[k] - self.start[k]);
                    }
                }
                Some(Slot::OptF64(&mut self.length))
            }
            // the crack's end (a given length becomes the end it implies)
            ["end", c @ ("x" | "z")] => {
                if let (None, Some(l)) = (self.end, self.length.take()) {
                    let [x, z] = self.start;
                    self.end = Some(if self.vertical {
                        [x, z + l]
                    } else {
                        [x + l, z]
                    });
                    // the end gives the direction now
                    self.vertical = false;
                }
                let e = self.end.as_mut()?;
                Some(Slot::F64(&mut e[usize::from(*c == "z")]))
            }
            ["start", "x"] => Some(Slot::F64(&mut self.start[0])),
            ["start", "z"] => Some(Slot::F64(&mut self.start[1])),
            ["compression", rest @ ..] => self.compression.slot(rest),
            ["traction", rest @ ..] => self.traction.slot(rest),
            ["tangential", rest @ ..] => self.tangential.slot(rest),
            _ => None,
        }
    }
}

impl Fields for SourceSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["angle"] => Some(Slot::F64(&mut self.angle)),
            ["x0"] => Some(Slot::OptF64(&mut self.x0)),
            ["x1"] => Some(Slot::OptF64(&mut self.x1)),
            ["signal", rest @ ..] => self.signal.slot(rest),
            _ => None,
        }
    }
}

impl Fields for ReceiverSpec {
    fn slot(&mut self, path: &[&str]) -> Option<Slot<'_>> {
        match path {
            ["x"] => Some(Slot::F64(&mut self.at[0])),
            ["z"] => Some(Slot::F64(&mut self.at[1])),
            _ => None,
        }
    }
}

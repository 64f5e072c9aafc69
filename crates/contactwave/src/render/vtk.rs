//! VTK files of pictures (the `plot` feature): a field on a uniform grid as XML ImageData
//! (`.vti`, written by `vtkio`), nodal fields on quadrilateral cells as XML
//! UnstructuredGrid (`.vtu`), and the ParaView collection (`.pvd`) that makes a time
//! series of them.

use crate::error::Result;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, Extent, ImageDataPiece, Piece,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// The `.vti` text of one frame: `values` (`[row][column]`, `nx` columns, `ny` rows, the
/// first row at the origin's y) at the points `origin + (i dx, j dy)`, named `name`.
pub fn image_data(
    file: &str,
    name: &str,
    nx: usize,
    ny: usize,
    origin: [f64; 2],
    spacing: [f64; 2],
    values: Vec<f64>,
) -> Result<String> {
    let extent = Extent::Ranges([0..=(nx as i32 - 1), 0..=(ny as i32 - 1), 0..=0]);
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::ImageData {
            extent: extent.clone(),
            origin: [origin[0] as f32, origin[1] as f32, 0.0],
            spacing: [spacing[0] as f32, spacing[1] as f32, 1.0],
            meta: None,
            pieces: vec![Piece::Inline(Box::new(ImageDataPiece {
                extent,
                data: Attributes {
                    point: vec![Attribute::scalars(name, 1).with_data(values)],
                    cell: vec![],
                },
            }))],
        },
    };
    let mut out = Vec::new();
    vtk.write_xml(&mut out)
        .map_err(|e| crate::render::svg::plot_error(file, e.to_string().into()))?;
    String::from_utf8(out).map_err(|e| crate::render::svg::plot_error(file, e.to_string().into()))
}

/// The `.vtu` text of one frame: quadrilateral `cells` (4 point indices each) on `points`
/// (`[x, y]`, z = 0), with the point fields `fields` (name, components (1 or 3), values
/// point-major).
pub fn unstructured(
    file: &str,
    points: &[[f64; 2]],
    cells: &[[u32; 4]],
    fields: Vec<(&str, u32, Vec<f64>)>,
) -> Result<String> {
    let coords: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    let connectivity: Vec<u64> = cells.iter().flatten().map(|&i| i as u64).collect();
    let offsets: Vec<u64> = (1..=cells.len() as u64).map(|k| 4 * k).collect();
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: coords.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML {
                    connectivity,
                    offsets,
                },
                types: vec![CellType::Quad; cells.len()],
            },
            data: Attributes {
                point: fields
                    .into_iter()
                    .map(|(name, n, v)| {
                        if n == 3 {
                            Attribute::vectors(name).with_data(v)
                        } else {
                            Attribute::scalars(name, 1).with_data(v)
                        }
                    })
                    .collect(),
                cell: vec![],
            },
        }),
    };
    let mut out = Vec::new();
    vtk.write_xml(&mut out)
        .map_err(|e| crate::render::svg::plot_error(file, e.to_string().into()))?;
    String::from_utf8(out).map_err(|e| crate::render::svg::plot_error(file, e.to_string().into()))
}

/// A ParaView collection (`.pvd`) of `(time s, file name)` entries.
pub fn collection(entries: &[(f64, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (t, f) in entries {
        s.push_str(&format!(
            "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{f}\"/>\n"
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use vtkio::model::IOBuffer;

    /// A frame written and parsed back by vtkio keeps its grid and values.
    #[test]
    fn a_frame_parses_back_with_its_values() {
        let values: Vec<f64> = (0..12).map(|i| i as f64 * 0.25 - 1.0).collect();
        let text = image_data(
            "t.vti",
            "vx",
            4,
            3,
            [0.5e-3, 0.25e-3],
            [1e-3, 0.5e-3],
            values.clone(),
        )
        .unwrap();
        let back = Vtk::parse_xml(text.as_bytes()).unwrap();
        let DataSet::ImageData {
            extent,
            spacing,
            pieces,
            ..
        } = back.data
        else {
            panic!("not image data");
        };
        assert_eq!(extent, Extent::Ranges([0..=3, 0..=2, 0..=0]));
        assert!((spacing[0] - 1e-3).abs() < 1e-9 && (spacing[1] - 0.5e-3).abs() < 1e-9);
        let Piece::Inline(p) = &pieces[0] else {
            panic!("not inline");
        };
        let Attribute::DataArray(a) = &p.data.point[0] else {
            panic!("no array");
        };
        assert_eq!(a.name, "vx");
        let got: Vec<f64> = match &a.data {
            IOBuffer::F64(v) => v.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(got, values);
        assert!(collection(&[(1e-6, "f.vti".into())]).contains("timestep=\"1e-6\""));
    }
}

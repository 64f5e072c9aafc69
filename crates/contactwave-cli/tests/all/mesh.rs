//! A run on a Gmsh mesh from the command line: snapshots over the specimen's real shape
//! (the reference plate meshed by Gmsh rotated by 30 degrees): PNG frames with the outside
//! of the plate blank (the no-value grey), the GIF, and ParaView `.vtu` frames of the GLL
//! sub-cells that read back with the mesh's node and cell counts, listed in a `.pvd`.

use crate::common::{bin, examples, stderr, tmpdir};

/// The picture's colour for a pixel without a value (outside the specimen).
const NO_VALUE: [u8; 3] = [190, 190, 190];

#[test]
fn a_mesh_run_writes_snapshots_over_the_real_shape() {
    let d = tmpdir("mesh-snapshots");
    let msh = examples().join("solid_2d/mesh/rotated/plate_30.msh");
    let text = format!(
        r#"
[model]
kind = "solid_2d"
duration = 1.5e-6
harmonic = 2

[mesh]
file = "{}"
order = 4

[[material]]
group = "aluminium"
material = "aluminium"

[[crack]]
group = "crack"
static_pressure = 0.2e6

[[source]]
kind = "transducer"
group = "wedge"
signal = {{ frequency = 2e6, cycles = 3, amplitude = 10e6, window = "hann" }}

[snapshots]
every = 0.5e-6
field = "magnitude"
"#,
        msh.display()
    );
    let file = d.join("plate_30.toml");
    std::fs::write(&file, text).unwrap();
    let out = d.join("out");
    let o = bin()
        .arg("run")
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let snaps = out.join("snapshots");
    for f in [
        "frame_0000.png",
        "frame_0002.png",
        "snapshots.gif",
        "snapshots.pvd",
    ] {
        assert!(snaps.join(f).is_file(), "{f} missing");
    }
    // the plate is rotated in its box: the box's corners are outside it, its centre inside
    let img = image::open(snaps.join("frame_0002.png")).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    let greys = img.pixels().filter(|p| p.0 == NO_VALUE).count();
    let share = greys as f64 / (w * h) as f64;
    assert!(share > 0.2 && share < 0.8, "no-value share {share}");
    // ParaView: three frames of the same mesh, the sub-cells of order-4 elements
    let pvd = std::fs::read_to_string(snaps.join("snapshots.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), 3, "{pvd}");
    let vtk = vtkio::Vtk::import(snaps.join("frame_0001.vtu")).unwrap();
    let vtkio::model::DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid")
    };
    let vtkio::model::Piece::Inline(piece) = &pieces[0] else {
        panic!("not an inline piece")
    };
    let points = piece.points.len() / 3;
    let cells = piece.cells.types.len();
    assert_eq!(cells % 16, 0, "{cells} sub-cells: not 16 an element");
    assert!(points > cells, "{points} points, {cells} cells");
    let names: Vec<&str> = piece.data.point.iter().map(|a| a.name()).collect();
    assert!(
        names.contains(&"magnitude") && names.contains(&"velocity"),
        "{names:?}"
    );
}

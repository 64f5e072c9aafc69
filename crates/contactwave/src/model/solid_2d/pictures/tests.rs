//! The pictures of a 2D run: sizes, legends, the frames of thin plates.

use crate::model::{self, RunControl, Value};
use image::AnimationDecoder;

/// A 2 x 1 mm plate with a clapping 0.6 mm crack under a 10 MHz burst (as
/// tests/all/solid_2d.rs), with `extra` appended.
fn small(extra: &str) -> String {
    format!(
        r#"
[model]
kind = "solid_2d"
width = 2e-3
duration = 0.6e-6
element_size = 0.1e-3

[[layer]]
thickness = 1e-3
material = "aluminium"

[[crack]]
start = [0.7e-3, 0.5e-3]
end = [1.3e-3, 0.5e-3]
static_pressure = 0.2e6
tangential = {{ law = "coulomb", friction = 0.3 }}

[[source]]
x0 = 0.6e-3
x1 = 1.4e-3
signal = {{ frequency = 10e6, cycles = 2, amplitude = 10e6, window = "hann" }}

[[receiver]]
name = "top"
at = [1e-3, 0.0]

[[receiver]]
name = "under"
at = [1e-3, 1e-3]
{extra}
"#
    )
}

fn run(text: &str) -> Box<dyn model::Outcome> {
    let t = model::from_toml_str(text, "small.toml").unwrap();
    t.base().unwrap().run(&RunControl::default()).unwrap()
}

/// The frames mark stress receivers as well as velocity ones.
#[test]
fn the_pictures_know_every_receiver() {
    let text = small("[[receiver]]\nname = \"s\"\nat = [0.5e-3, 0.25e-3]\nquantity = \"stress\"\n");
    let m = model::from_toml_str(&text, "small.toml")
        .unwrap()
        .base()
        .unwrap();
    let s = m
        .as_any()
        .downcast_ref::<crate::scenario::solid_2d::Solid2dScenario>()
        .unwrap();
    let g = super::Geometry::of(s);
    assert_eq!(g.receivers.len(), 2);
    assert_eq!(g.stress_receivers.len(), 1);
    let [x, z] = g.stress_receivers[0];
    assert!(
        (x - 0.5e-3).abs() < 0.06e-3 && (z - 0.25e-3).abs() < 0.06e-3,
        "{x} {z}"
    );
}

/// An SH crack never opens: its gap map is the signed jump of u_y, drawn blue-white-red
/// about zero (the normal gap would be one flat colour), and it slips both ways.
#[test]
fn an_antiplane_crack_map_draws_the_signed_tangential_gap() {
    let text = small("")
        .replace("kind = \"solid_2d\"", "kind = \"solid_2d\"\nwave = \"sh\"")
        .replace("x1 = 1.4e-3", "x1 = 1.4e-3\ncomponent = \"shear\"")
        .replace("at = [1e-3, 0.0]", "at = [1e-3, 0.0]\ncomponent = \"y\"")
        .replace("at = [1e-3, 1e-3]", "at = [1e-3, 1e-3]\ncomponent = \"y\"");
    let out = run(&text);
    let bin = out.binary_files().unwrap();
    let map = bin.iter().find(|f| f.name == "crack_map.png").unwrap();
    let img = image::load_from_memory(&map.bytes).unwrap().to_rgb8();
    // reddish (positive jump) and bluish (negative) pixels in the field
    let (mut red, mut blue) = (0, 0);
    for y in 40..40 + 400 {
        for x in 64..64 + 600 {
            let [r, _, b] = img.get_pixel(x, y).0;
            red += usize::from(r > b + 40);
            blue += usize::from(b > r + 40);
        }
    }
    assert!(red > 0 && blue > 0, "red {red}, blue {blue}");
}

/// A run with snapshots writes its PNG frames (decoding at the expected size), a GIF of
/// as many frames, VTK frames that parse back to the raster's values, the plots and the
/// crack map; keeping the snapshots changes no other output.
#[test]
fn snapshots_write_their_pictures_and_change_nothing_else() {
    let with = run(&small(
        "[snapshots]\ntimes = [0.2e-6, 0.4e-6, 0.6e-6]\nfield = \"vz\"\npixels = 100\n",
    ));
    let without = run(&small(""));
    // the same receivers, crack fields and summary, bit for bit
    for key in ["receivers", "cracks", "t", "summary"] {
        assert_eq!(with.record().get(key), without.record().get(key), "{key}");
    }
    let (fw, fo) = (with.files().unwrap(), without.files().unwrap());
    for f in &fo {
        let g = fw.iter().find(|g| g.name == f.name).unwrap();
        assert_eq!(g.contents, f.contents, "{}", f.name);
    }
    let r = with
        .as_any()
        .downcast_ref::<crate::model::solid_2d::Solid2dResult>()
        .unwrap();
    let s = r.snapshots.as_ref().unwrap();
    let dt = r.output.dt;
    for (t, want) in s.times.iter().zip([0.2e-6, 0.4e-6, 0.6e-6]) {
        assert!((t - want).abs() <= 0.5 * dt + 1e-15, "{t} {want}");
    }
    // 100 px across 2 mm: 50 rows; the field is a component, the scale symmetric
    assert_eq!(
        (s.raster.x.len(), s.raster.z.len(), s.raster.frames()),
        (100, 50, 3)
    );
    let largest = s.raster.values.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(s.signed && s.scale == largest && largest > 0.0);
    let bin = with.binary_files().unwrap();
    let names: Vec<&str> = bin.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "snapshots/frame_0000.png",
            "snapshots/frame_0001.png",
            "snapshots/frame_0002.png",
            "snapshots/snapshots.gif",
            "crack_map.png",
            "crack_state.png"
        ]
    );
    // the field's 100 x 50 px, each row drawn 3 px tall (at least 120 px: 150), margins
    // of 176 x 88 px around it
    let png = image::load_from_memory(&bin[1].bytes).unwrap();
    assert_eq!((png.width(), png.height()), (100 + 176, 150 + 88));
    // the state map draws only the three states' colours (no blend of a continuous
    // scale), and a clapping crack shows at least two of them
    let state = image::load_from_memory(&bin[5].bytes).unwrap().to_rgb8();
    let colours: Vec<[u8; 3]> = super::files::STATES
        .iter()
        .map(|(_, _, (r, g, b))| [*r, *g, *b])
        .collect();
    let mut seen = std::collections::BTreeSet::new();
    for y in 40..40 + 400 {
        for x in 64..64 + 600 {
            let c = state.get_pixel(x, y).0;
            assert!(colours.contains(&c), "{c:?} at ({x}, {y})");
            seen.insert(c);
        }
    }
    assert!(seen.len() >= 2, "{seen:?}");
    let gif = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(&bin[3].bytes))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(gif.len(), 3);
    assert_eq!(gif[0].buffer().dimensions(), (276, 238));
    // the VTK frame parses back with the raster's values (rows from the bottom up)
    let vti = fw
        .iter()
        .find(|f| f.name == "snapshots/frame_0001.vti")
        .unwrap();
    let back = vtkio::Vtk::parse_xml(vti.contents.as_bytes()).unwrap();
    let vtkio::model::DataSet::ImageData { pieces, .. } = back.data else {
        panic!("not image data")
    };
    let vtkio::model::Piece::Inline(p) = &pieces[0] else {
        panic!("not inline")
    };
    let vtkio::model::Attribute::DataArray(a) = &p.data.point[0] else {
        panic!("no array")
    };
    let vtkio::model::IOBuffer::F64(v) = &a.data else {
        panic!("not f64")
    };
    let f = s.raster.frame(1);
    assert_eq!(v.len(), 100 * 50);
    assert_eq!(v[..100], f[49 * 100..50 * 100]);
    assert_eq!(v[49 * 100..], f[..100]);
    let pvd = fw
        .iter()
        .find(|f| f.name == "snapshots/snapshots.pvd")
        .unwrap();
    assert_eq!(pvd.contents.matches("<DataSet ").count(), 3);
    for name in ["receivers.svg", "spectra.svg"] {
        assert!(fw
            .iter()
            .any(|f| f.name == name && f.contents.contains("<svg")));
    }
    // Python's arrays: the frames flattened with their coordinates
    let rec = with.record();
    let Some(Value::Array(frames)) = rec.get("snapshots") else {
        panic!("snapshots")
    };
    assert_eq!(frames.len(), 3 * 50 * 100);
    let Some(Value::Array(z)) = rec.get("snapshot_z") else {
        panic!("snapshot_z")
    };
    assert!((z[0] - 1e-5).abs() < 1e-18);
}

/// A frictionless crack (no tangential law) never sticks: its state maps name its
/// closed points `closed`, in a colour of their own, not `slip`; a crack with friction
/// keeps open, stick and slip.
#[test]
fn a_frictionless_crack_is_closed_not_slipping() {
    let coulomb = "tangential = { law = \"coulomb\", friction = 0.3 }";
    assert!(small("").contains(coulomb));
    let legend = |label: &str| format!("\n{label}\n</text>");
    for friction in [false, true] {
        let text = if friction {
            small("")
        } else {
            small("").replace(coulomb, "")
        };
        let out = run(&text);
        let r = out
            .as_any()
            .downcast_ref::<crate::model::solid_2d::Solid2dResult>()
            .unwrap();
        assert_eq!(r.geometry.frictionless, [!friction]);
        let files = out.files().unwrap();
        let svg = &files
            .iter()
            .find(|f| f.name == "crack_state.svg")
            .unwrap()
            .contents;
        let named = |label: &str| svg.contains(&legend(label));
        assert!(named("open"), "{svg}");
        assert_eq!(named("closed (frictionless)"), !friction, "{friction}");
        assert_eq!(named("slip") && named("stick"), friction, "{friction}");
        let want = if friction {
            &super::files::STATES[..]
        } else {
            &super::files::FRICTIONLESS_STATES[..]
        };
        let colours: Vec<[u8; 3]> = want.iter().map(|(_, _, (r, g, b))| [*r, *g, *b]).collect();
        let bin = out.binary_files().unwrap();
        let png = bin.iter().find(|f| f.name == "crack_state.png").unwrap();
        let state = image::load_from_memory(&png.bytes).unwrap().to_rgb8();
        let mut seen = std::collections::BTreeSet::new();
        for y in 40..40 + 400 {
            for x in 64..64 + 600 {
                let c = state.get_pixel(x, y).0;
                assert!(colours.contains(&c), "{friction}: {c:?} at ({x}, {y})");
                seen.insert(c);
            }
        }
        // the crack under 0.2 MPa is shut at rest: stuck with friction, closed without
        assert!(seen.contains(&colours[1]), "{friction}: {seen:?}");
    }
}

/// A thin plate's frames: its few pixel rows each drawn several pixels tall, so that
/// the field is [`super::MIN_FIELD_HEIGHT`] px tall, and the colour bar as tall as the
/// field (not taller); the raster itself keeps square pixels.
#[test]
fn a_thin_plate_frame_has_a_readable_field_and_a_bar_of_its_height() {
    // 4 mm x 0.2 mm, 200 px across: 10 rows of 20 um, each drawn 12 px tall
    let text = r#"
[model]
kind = "solid_2d"
width = 4e-3
duration = 0.3e-6
element_size = 0.1e-3

[[layer]]
thickness = 0.2e-3
material = "aluminium"

[[crack]]
start = [1.7e-3, 0.1e-3]
end = [2.3e-3, 0.1e-3]
static_pressure = 0.2e6

[[source]]
x0 = 1.6e-3
x1 = 2.4e-3
signal = { frequency = 10e6, cycles = 2, amplitude = 10e6, window = "hann" }

[snapshots]
times = [0.3e-6]
pixels = 200
vtk = false
gif = false
"#;
    let out = run(text);
    let r = out
        .as_any()
        .downcast_ref::<crate::model::solid_2d::Solid2dResult>()
        .unwrap();
    let s = r.snapshots.as_ref().unwrap();
    assert_eq!((s.raster.x.len(), s.raster.z.len()), (200, 10));
    assert_eq!(super::row_height(10), 12);
    let bin = out.binary_files().unwrap();
    let png = bin
        .iter()
        .find(|f| f.name == "snapshots/frame_0000.png")
        .unwrap();
    let img = image::load_from_memory(&png.bytes).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (200 + 176, 120 + 88));
    // the rows (not white, not the black frame) of a column of the field, away from
    // the crack and the transducer, and of the colour bar, between the title and the
    // tick labels: the same 120, from the top margin down
    let coloured = |x: u32| -> Vec<u32> {
        (35..170)
            .filter(|&y| {
                let c = img.get_pixel(x, y).0;
                c != [255, 255, 255] && c != [0, 0, 0]
            })
            .collect()
    };
    let field = coloured(64 + 25);
    let bar = coloured(64 + 200 + 16 + 8);
    let rows: Vec<u32> = (40..40 + 120).collect();
    assert_eq!(field, rows);
    // (the bar's black outline takes its last row)
    assert_eq!(bar, rows[..119]);
    // each raster row is 12 identical pixel rows
    for iz in 0..10 {
        let first = img.get_pixel(64 + 25, 40 + 12 * iz).0;
        for j in 1..12 {
            assert_eq!(
                img.get_pixel(64 + 25, 40 + 12 * iz + j).0,
                first,
                "{iz} {j}"
            );
        }
    }
}

/// A stress receiver has its panel in `receivers.svg` and `spectra.svg`, in MPa and
/// in dB re. the largest stress spectrum, beside the velocity receivers'.
#[test]
fn stress_receivers_are_plotted_beside_the_velocities() {
    let text = small("[[receiver]]\nname = \"mid\"\nat = [1e-3, 0.3e-3]\nquantity = \"stress\"\n");
    let files = run(&text).files().unwrap();
    let svg = |name: &str| {
        files
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.contents.clone())
            .unwrap()
    };
    let traces = svg("receivers.svg");
    assert!(traces.contains("stress receiver mid"), "receivers.svg");
    assert!(traces.contains("receiver under") && traces.contains("stress (MPa)"));
    for comp in ["sxx", "szz", "sxz"] {
        assert!(traces.contains(comp), "{comp}");
    }
    let spectra = svg("spectra.svg");
    assert!(spectra.contains("stress receiver mid (dashed"));
    assert!(spectra.contains("the largest stress") && spectra.contains("the largest velocity"));
}

/// Snapshots beyond the memory budget are refused before the run, naming the key.
#[test]
fn too_many_snapshots_are_refused_before_the_run() {
    // 2000 frames of 4096 x 2048 px: hundreds of GB
    let text = small("[snapshots]\nevery = 0.0003e-6\npixels = 4096\n");
    let t = model::from_toml_str(&text, "small.toml").unwrap();
    let e = t
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("snapshots.every") && e.contains("raise"), "{e}");
}

/// Bad `[snapshots]` keys are one-line errors naming the key and the allowed values.
#[test]
fn bad_snapshot_keys_are_refused() {
    for (extra, key) in [
        ("field = \"vy\"", "snapshots.field"),
        ("pixels = 5", "snapshots.pixels"),
        ("times = [1.0]", "snapshots.times"),
        ("every = -1e-7", "snapshots.every"),
        ("scale = 0.0", "snapshots.scale"),
        ("colour = 1", "colour"),
    ] {
        let text = small(&format!("[snapshots]\n{extra}\n"));
        let e = model::from_toml_str(&text, "small.toml")
            .and_then(|t| t.base().map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(e.contains(key), "{extra}: {e}");
    }
}

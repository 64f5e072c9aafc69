//! Sweep keys of 2D cracks (issue 27): a crack's end is a sweep key as well as its length,
//! whichever of the two the scenario gives, and the 2D model estimates its memory.

use contactwave::model::{self, Model};
use contactwave::scenario::solid_2d::Solid2dScenario;
use std::path::Path;
use std::sync::Arc;

fn quick() -> Arc<dyn model::Template> {
    model::load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/solid_2d/plate_crack_quick.toml"),
    )
    .unwrap()
}

fn crack_end(m: &Arc<dyn Model>) -> [f64; 2] {
    let s = m.as_any().downcast_ref::<Solid2dScenario>().unwrap();
    s.problem.cracks[0].end
}

#[test]
fn crack_end_and_length_are_sweep_keys() {
    let t = quick();
    // the file gives start [19, 5] mm and end [21, 5] mm
    let end_x = t.param("crack.0.end.x").unwrap();
    assert_eq!(
        crack_end(&t.build(&[(&end_x, 25e-3)]).unwrap()),
        [25e-3, 5e-3]
    );
    let length = t.param("crack.0.length").unwrap();
    let m = t.build(&[(&length, 6e-3)]).unwrap();
    assert!((crack_end(&m)[0] - 25e-3).abs() < 1e-15);
    // a crack given by its length: its end is the one the length implies, then moved
    let mut table = t.table().clone();
    let crack = table["crack"].as_array_mut().unwrap()[0]
        .as_table_mut()
        .unwrap();
    crack.remove("end");
    crack.insert("length".into(), toml::Value::Float(4e-3));
    let t2 = model::plan(table, Path::new("by_length.toml"));
    assert_eq!(crack_end(&t2.base().unwrap()), [23e-3, 5e-3]);
    let end_z = t2.param("crack.0.end.z").unwrap();
    // a crack must run along x or z: moving a horizontal crack's end down is refused,
    // naming the key
    let e = t2.build(&[(&end_z, 6e-3)]).unwrap_err().to_string();
    assert!(e.contains("crack.0.end"), "{e}");
    let end_x = t2.param("crack.0.end.x").unwrap();
    assert_eq!(
        crack_end(&t2.build(&[(&end_x, 30e-3)]).unwrap()),
        [30e-3, 5e-3]
    );
    // the end outside the plate is refused like any invalid value
    assert!(t2.build(&[(&end_x, 50e-3)]).is_err());
    // a crack written from right to left keeps its place when its length is set: it grows
    // from its left tip
    let mut table = t.table().clone();
    let crack = table["crack"].as_array_mut().unwrap()[0]
        .as_table_mut()
        .unwrap();
    crack.insert(
        "start".into(),
        toml::Value::try_from([21e-3, 5e-3]).unwrap(),
    );
    crack.insert("end".into(), toml::Value::try_from([19e-3, 5e-3]).unwrap());
    let t3 = model::plan(table, Path::new("reversed.toml"));
    let length = t3.param("crack.0.length").unwrap();
    let s3 = t3.build(&[(&length, 2e-3)]).unwrap();
    let c = &s3
        .as_any()
        .downcast_ref::<Solid2dScenario>()
        .unwrap()
        .problem
        .cracks[0];
    assert_eq!(c.start, [19e-3, 5e-3]);
    assert!(
        (c.end[0] - 21e-3).abs() < 1e-15 && c.end[1] == 5e-3,
        "{:?}",
        c.end
    );
    // a vertical crack given by its length: its end moves down along its line
    let mut table = t.table().clone();
    let crack = table["crack"].as_array_mut().unwrap()[0]
        .as_table_mut()
        .unwrap();
    crack.remove("end");
    crack.insert(
        "start".into(),
        toml::Value::try_from([20e-3, 4e-3]).unwrap(),
    );
    crack.insert("length".into(), toml::Value::Float(2e-3));
    crack.insert("vertical".into(), toml::Value::Boolean(true));
    let t4 = model::plan(table, Path::new("vertical.toml"));
    assert_eq!(crack_end(&t4.base().unwrap()), [20e-3, 6e-3]);
    let end_z = t4.param("crack.0.end.z").unwrap();
    assert_eq!(
        crack_end(&t4.build(&[(&end_z, 7e-3)]).unwrap()),
        [20e-3, 7e-3]
    );
}

#[test]
fn the_2d_model_estimates_its_memory_before_it_runs() {
    let t = quick();
    let base = t.base().unwrap().memory_estimate().unwrap().unwrap();
    // 5 600 nodes (order 6, 1.85 mm elements) and 2 100 steps: a mesh of under 1 MB
    // and its records
    assert!(base > 0.5e6 && base < 5e6, "{base}");
    // a third of the element size gives about nine times the nodes (the mesh lines at the
    // crack's ends and the transducer's edges stay) and a third of the time step: the
    // mesh's part grows about ninefold, the records' threefold
    let h = t.param("model.element_size").unwrap();
    let fine = t.build(&[(&h, 0.615e-3)]).unwrap();
    let fine = fine.memory_estimate().unwrap().unwrap();
    assert!(fine > 4.0 * base && fine < 12.0 * base, "{base} -> {fine}");
    // a mesh beyond any machine is refused when the model is built, before anything is
    // allocated, naming the key
    let e = t.build(&[(&h, 1e-7)]).unwrap_err().to_string();
    assert!(
        e.contains("field `model.element_size`") && e.contains("needs about"),
        "{e}"
    );
    // a second run (linear_reference) doubles it
    let mut table = t.table().clone();
    table.insert(
        "analysis".into(),
        toml::Value::Table(toml::toml! { method = "linear_reference" }),
    );
    let twin = model::plan(table, Path::new("twin.toml")).base().unwrap();
    assert_eq!(twin.memory_estimate().unwrap().unwrap(), 2.0 * base);
}

/// Every point of a 2D sweep is checked against the memory budget before any runs: a
/// duration of 1000 s (a unit slip) is refused up front, naming the key, the sweep file
/// and the point, rather than failing when its turn comes.
#[test]
fn a_sweep_checks_every_points_memory_before_it_runs() {
    let d = std::env::temp_dir().join(format!("contactwave-sweep-budget-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/solid_2d/plate_crack_quick.toml");
    std::fs::write(
        d.join("sweep.toml"),
        format!(
            "base = {:?}\n[[axis]]\nparameter = \"model.duration\"\nvalues = [20e-6, 1e3]\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    let s = contactwave::study::Sweep::load(&d.join("sweep.toml")).unwrap();
    let e = s.validate().map(drop).unwrap_err().to_string();
    assert!(
        e.contains("field `model.duration` = 1000: needs about")
            && e.contains("in sweep")
            && e.contains("at point 1"),
        "{e}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// The numbers of `table` by dotted key (arrays of tables by index; arrays of numbers,
/// such as `at = [x, z]`, are positions, swept as `.x`/`.z` or not at all).
fn number_keys(prefix: &str, v: &toml::Value, out: &mut Vec<(String, f64)>) {
    match v {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                number_keys(&key, v, out);
            }
        }
        toml::Value::Array(a) if a.iter().all(toml::Value::is_table) => {
            for (i, v) in a.iter().enumerate() {
                number_keys(&format!("{prefix}.{i}"), v, out);
            }
        }
        toml::Value::Float(x) => out.push((prefix.to_string(), *x)),
        toml::Value::Integer(n) => out.push((prefix.to_string(), *n as f64)),
        _ => {}
    }
}

/// The sweep keys are the scenario's own schema, not a list: every number the 2D example
/// writes, and the model's optional numbers it leaves at their defaults (the absorbing
/// layers' thickness and reflection among them), can be swept, each point built with the
/// value set; the layers' thickness reaches the problem; a key the schema lacks is
/// refused with the keys it has.
#[test]
fn every_number_of_the_schema_is_a_sweep_key() {
    let t = quick();
    let mut table = t.table().clone();
    let model = table["model"].as_table_mut().unwrap();
    model.insert("sides".into(), toml::Value::String("absorbing".into()));
    let t = model::plan(table.clone(), Path::new("absorbing.toml"));
    let mut keys = Vec::new();
    number_keys("", &toml::Value::Table(table), &mut keys);
    for (k, v) in [
        ("model.pml_thickness", 2e-3),
        ("model.pml_reflection", 1e-4),
        ("model.courant", 0.5),
        ("model.crack_every", 5.0),
        ("model.element_size", 0.5e-3),
        ("model.time_step", 5e-9),
        ("model.order", 5.0),
    ] {
        keys.push((k.to_string(), v));
    }
    assert!(keys.len() >= 18, "{keys:?}");
    for (key, value) in &keys {
        let p = t
            .param(key)
            .unwrap_or_else(|e| panic!("{key} is not a sweep key: {e}"));
        t.build(&[(&p, *value)])
            .unwrap_or_else(|e| panic!("{key} = {value}: {e}"));
    }
    let p = t.param("model.pml_thickness").unwrap();
    let m = t.build(&[(&p, 2e-3)]).unwrap();
    let s = m.as_any().downcast_ref::<Solid2dScenario>().unwrap();
    assert_eq!(s.problem.pml.thickness, 2e-3);
    let e = t
        .param("model.pml_thicknes")
        .and_then(|p| t.build(&[(&p, 1e-3)]).map(|_| ()));
    let e = e.unwrap_err().to_string();
    assert!(e.contains("pml_thickness"), "{e}");
}

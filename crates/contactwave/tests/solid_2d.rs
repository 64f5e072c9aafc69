//! The `solid_2d` kind through the model contract: a scenario file runs, its summary
//! closes the energy, its files and arrays are there, sweep keys reach it, and bad input
//! is a one-line error naming the key.

use contactwave::model::{self, RunControl, Value};

/// A small clapping case: a 2 x 1 mm plate, a 0.6 mm crack under 0.2 MPa, a 10 MHz
/// 10 MPa burst from a transducer above it.
const SMALL: &str = r#"
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
tangential = { law = "coulomb", friction = 0.3 }

[[source]]
x0 = 0.6e-3
x1 = 1.4e-3
signal = { frequency = 10e6, cycles = 2, amplitude = 10e6, window = "hann" }

[[receiver]]
name = "top"
at = [1e-3, 0.0]

[[receiver]]
name = "under"
at = [1e-3, 1e-3]
"#;

#[test]
fn a_scenario_runs_closes_its_energy_and_writes_its_files() {
    let t = model::from_toml_str(SMALL, "small.toml").unwrap();
    assert_eq!(t.kind(), "solid_2d");
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_input").unwrap() > 0.0);
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
    // the crack claps: it opens, and Signorini holds in its records
    assert!(s.get("crack_max_gap_0").unwrap() > 0.0, "{s:?}");
    for key in ["top_A1", "under_A2_over_A1", "nodes", "steps", "dt"] {
        assert!(s.get(key).is_some_and(f64::is_finite), "{key}");
    }
    let files = outcome.files().unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["summary.json", "receivers.csv", "crack.csv"]);
    assert!(files[1]
        .contents
        .starts_with("t,top_vx,top_vz,under_vx,under_vz\n"));
    assert!(files[2]
        .contents
        .starts_with("crack,t,position,normal_gap,"));
    let r = outcome.record();
    let Some(Value::Rows(rec)) = r.get("receivers") else {
        panic!("receivers rows")
    };
    let Some(Value::Array(time)) = r.get("t") else {
        panic!("t")
    };
    assert_eq!(rec.len(), 4);
    assert!(rec.iter().all(|row| row.len() == time.len()));
    let Some(Value::Tuple(cracks)) = r.get("cracks") else {
        panic!("cracks")
    };
    let Value::Map(c) = &cracks[0] else {
        panic!("crack map")
    };
    let (Some(Value::Rows(gap)), Some(Value::Rows(stress))) =
        (c.get("normal_gap"), c.get("normal_stress"))
    else {
        panic!("crack rows")
    };
    assert!(gap.iter().flatten().all(|&g| g >= 0.0));
    assert!(gap
        .iter()
        .flatten()
        .zip(stress.iter().flatten())
        .all(|(&g, &s)| g == 0.0 || s.abs() < 1e-3));
}

/// With absorbing sides and bottom (perfectly matched layers outside the plate) the run
/// closes its audit at round-off, the flux into the layers counted.
#[test]
fn absorbing_sides_close_the_energy_with_the_flux_into_the_layers() {
    let text = SMALL.replace(
        "duration = 0.6e-6",
        "duration = 0.6e-6\nsides = \"absorbing\"\nbottom = \"absorbing\"\npml_thickness = 0.3e-3",
    );
    let t = model::from_toml_str(&text, "small.toml").unwrap();
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_absorbed").unwrap() > 0.0, "{s:?}");
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
}

#[test]
fn sweep_keys_reach_the_crack_and_the_source() {
    let t = model::from_toml_str(SMALL, "small.toml").unwrap();
    // a closure far above the wave's stress keeps the crack shut
    let p0 = t.param("crack.0.static_pressure").unwrap();
    let shut = t.build(&[(&p0, 1e9)]).unwrap().summary().unwrap();
    assert_eq!(shut.get("crack_max_gap_0"), Some(0.0));
    // a shorter crack by its length
    let len = t.param("crack.0.length").unwrap();
    assert!(t.build(&[(&len, 0.4e-3)]).is_ok());
    for key in [
        "source.0.signal.amplitude",
        "crack.0.tangential.friction",
        "model.duration",
        "layer.0.thickness",
    ] {
        assert!(t.param(key).is_ok(), "{key}");
    }
}

#[test]
fn bad_input_is_an_error_naming_the_key() {
    let cases = [
        (
            "start = [0.7e-3, 0.5e-3]",
            "start = [0.7e-3, 2e-3]",
            "crack.0.start",
        ),
        (
            "end = [1.3e-3, 0.5e-3]",
            "end = [1.3e-3, 0.6e-3]",
            "crack.0.end",
        ),
        ("x1 = 1.4e-3", "x1 = 3e-3", "source.0.x1"),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\nsides = \"absorbing\"\npml_reflection = 2.0",
            "model.pml_reflection",
        ),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\nbottom = \"absorbing\"\npml_thickness = -1e-3",
            "model.pml_thickness",
        ),
        ("width = 2e-3", "width = -2e-3", "model.width"),
        ("at = [1e-3, 1e-3]", "at = [1e-3, 5e-3]", "receiver.1.at"),
        (
            "element_size = 0.1e-3",
            "element_size = 1e-9",
            "model.element_size",
        ),
        (
            "thickness = 1e-3\nmaterial = \"aluminium\"",
            "thickness = 1e-3\nmaterial = \"cheese\"",
            "layer.0.material",
        ),
    ];
    for (from, to, key) in cases {
        assert!(SMALL.contains(from), "{from}");
        let text = SMALL.replace(from, to);
        let err = model::from_toml_str(&text, "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(key), "{key}: {err}");
        assert!(err.starts_with("bad.toml"), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

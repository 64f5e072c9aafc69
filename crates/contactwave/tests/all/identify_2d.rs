//! Identification with the 2D model as the forward model:
//! examples/identify/crack_closure_friction.toml's data CSV is what its documented
//! `--synthesize` command makes (synthesised receiver harmonics, A2/A1 and A3/A1 at two
//! receivers over six drive amplitudes, 2% noise). That the example recovers the crack's
//! closure pressure p0 and friction coefficient mu (estimates within 5 %, narrow 95 %
//! intervals holding the truth) is asserted on its `identify` run in the reference outputs
//! (scripts/reference_outputs.py, FINDINGS): the 636 forward runs happen once per CI run.

#![cfg(feature = "identify")]

use contactwave::inverse::{synthesize, IdentifySpec};
use std::path::{Path, PathBuf};

const P0: &str = "crack.0.static_pressure";
const MU: &str = "crack.0.tangential.friction";
/// The values the example's data were made with (its header comment).
const TRUE_P0: f64 = 1.5e6;
const TRUE_MU: f64 = 0.4;

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/identify/crack_closure_friction.toml")
}

#[test]
fn the_example_data_are_what_its_synthesize_command_makes() {
    // 6 rows of two 2D runs each (linear_reference): a few seconds
    let spec = IdentifySpec::load(&example()).unwrap();
    let truth = [(P0.to_string(), TRUE_P0), (MU.to_string(), TRUE_MU)];
    let made = synthesize(&spec, &truth, 0.02, 7).unwrap();
    assert_eq!(made.measured.conditions, spec.measured.conditions);
    assert_eq!(made.measured.rows, spec.measured.rows);
    for (a, b) in made.measured.observed.iter().zip(&spec.measured.observed) {
        assert_eq!(a.key, b.key);
        for (x, y) in a.values.iter().zip(&b.values) {
            // the CSV holds the shortest text that parses back to the same f64
            assert_eq!(x.to_bits(), y.to_bits(), "{}: {x} != {y}", a.key);
        }
    }
    // the harmonics come from the crack: none while it sticks, and they grow with the
    // drive once it slips and claps (A/p0 from 1.7 to 5.3)
    let a2 = &spec.measured.observed[0];
    assert_eq!(a2.key, "bottom_A2_over_A1");
    assert!(a2.values.windows(2).all(|w| w[0] < w[1]), "{:?}", a2.values);
    assert!(a2.values[0] < 1e-3 && a2.values[5] > 0.1, "{:?}", a2.values);
}

/// On a 2D base an experiment design without a key varies the first source's frequency
/// (a 2D scenario has no `incident`), and a `[set]` the base cannot take names the
/// identification file as well as the base.
#[test]
fn a_2d_design_varies_the_source_frequency_and_set_errors_name_the_file() {
    let mut table: toml::Table =
        toml::from_str(&std::fs::read_to_string(example()).unwrap()).unwrap();
    table.insert(
        "design".into(),
        toml::Value::Table(toml::toml! { values = [4e6, 6e6] }),
    );
    let spec = IdentifySpec::from_table(table.clone(), &example()).unwrap();
    assert_eq!(
        spec.design.unwrap().key,
        "source.0.signal.frequency".to_string()
    );
    let set = table
        .entry("set")
        .or_insert(toml::Value::Table(Default::default()))
        .as_table_mut()
        .unwrap();
    set.insert("crack.0.static_shear".into(), toml::Value::Float(5e7));
    let e = IdentifySpec::from_table(table, &example())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("crack.0.static_shear")
            && e.contains("[set] of")
            && e.contains("crack_closure_friction.toml"),
        "{e}"
    );
}

//! Issue 24 items 3, 6 and 12: unit strings everywhere a number with a unit is read,
//! plausibility warnings for likely unit slips (and none for the shipped examples),
//! presets that give a half-space its P-wave speed, and error messages in plain words.

use contactwave::model;
use contactwave::scenario::Scenario;
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

const SI: &str = r#"
[medium]
material = "aluminium"
youngs_modulus = 71e9
[interface]
static_pressure = 0.082e6
traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 15
amplitude = 0.5e6
delay = 2e-6
[probe]
x = -0.03
"#;

/// The same scenario with every number that has a unit written as a unit string.
const WITH_UNITS: &str = r#"
[medium]
material = "aluminium"
youngs_modulus = "71 GPa"
[interface]
static_pressure = "0.082 MPa"
traction = { law = "rccm", stiffness = "20 TPa/m", energy = "0.1 J/m^2", viscosity = "10 nJ s/m^2" }
[incident]
frequency = "1 MHz"
cycles = 15
amplitude = "0.5MPa"
delay = "2 us"
[probe]
x = "-30 mm"
"#;

#[test]
fn unit_strings_read_as_their_si_values() {
    let a = Scenario::from_toml_str(SI, "si.toml").unwrap();
    let b = Scenario::from_toml_str(WITH_UNITS, "units.toml").unwrap();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
    assert!(close(b.spec.interface.static_pressure, 0.082e6));
    assert!(close(b.medium.youngs_modulus, a.medium.youngs_modulus));
    assert!(close(b.incident.fundamental(), 1e6));
    assert!(close(b.incident.peak(), 0.5e6));
    assert!(close(b.incident.duration(), a.incident.duration()));
    assert!(close(b.probe_x, -0.03));
    assert!(close(b.xi, a.xi));
    let (sa, sb) = (
        contactwave::simulate_summary(&a).unwrap(),
        contactwave::simulate_summary(&b).unwrap(),
    );
    let key = "A2_over_Ainc";
    assert!(close(sb.get(key).unwrap(), sa.get(key).unwrap()));
}

#[test]
fn unknown_or_mismatched_units_are_errors_naming_file_field_value_and_unit() {
    let bad = WITH_UNITS.replace("\"1 MHz\"", "\"0.082 MPa\"");
    let e = Scenario::from_toml_str(&bad, "slip.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("slip.toml: field `incident.frequency` = \"0.082 MPa\": `MPa` is a unit of"),
        "{e}"
    );
    assert!(e.contains("Hz") && e.contains("\"1 MHz\""), "{e}");
    let bad = WITH_UNITS.replace("\"71 GPa\"", "\"71 Gpa\"");
    let e = Scenario::from_toml_str(&bad, "slip.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("field `medium.youngs_modulus` = \"71 Gpa\": unknown unit `Gpa`"),
        "{e}"
    );
    assert!(e.contains("Pa"), "{e}");
}

#[test]
fn a_string_for_a_number_says_a_number_not_f64() {
    let bad = SI.replace("cycles = 15", "cycles = \"15\"");
    let e = Scenario::from_toml_str(&bad, "s.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("field `incident.cycles`"), "{e}");
    assert!(e.contains("expected a number"), "{e}");
    assert!(!e.contains("f64"), "{e}");
    // a bar stack likewise
    let stack = r#"
[model]
kind = "bar_stack"
area = 1.0
static_force = "82 kN"
[[segment]]
name = "a"
length = "5 mm"
material = "pmma"
damping = "0"
"#;
    let e = model::from_toml_str(stack, "stack.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("segment.0.damping") || e.contains("damping"),
        "{e}"
    );
    assert!(e.contains("expected a number") && !e.contains("f64"), "{e}");
}

#[test]
fn sweeps_take_unit_strings() {
    let d = std::env::temp_dir().join(format!("contactwave-units-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("base.toml"), SI).unwrap();
    std::fs::write(
        d.join("sweep.toml"),
        "base = \"base.toml\"\n[set]\n\"incident.delay\" = \"0 s\"\n\
         [[axis]]\nparameter = \"incident.frequency\"\nvalues = [\"0.5 MHz\", 1e6, \"2MHz\"]\n\
         [[axis]]\nparameter = \"interface.static_pressure\"\nlinspace = [\"0.1 MPa\", \"0.3 MPa\", 3]\n",
    )
    .unwrap();
    let s = contactwave::study::Sweep::load(&d.join("sweep.toml")).unwrap();
    assert_eq!(s.axes[0].values, vec![0.5e6, 1e6, 2e6]);
    assert_eq!(s.axes[1].values, vec![0.1e6, 0.2e6, 0.3e6]);
    // a mismatched unit in a sweep names the file, the axis and the unit expected
    std::fs::write(
        d.join("bad.toml"),
        "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.frequency\"\nvalues = [\"1 mm\"]\n",
    )
    .unwrap();
    let e = contactwave::study::Sweep::load(&d.join("bad.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bad.toml: field `axis.0.values` = \"1 mm\": `mm` is a unit of a length"),
        "{e}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// An identification file takes unit strings in bounds, initial and design values.
#[cfg(feature = "identify")]
#[test]
fn identifications_take_unit_strings() {
    let d = std::env::temp_dir().join(format!("contactwave-units-id-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("base.toml"), SI).unwrap();
    std::fs::write(
        d.join("identify.toml"),
        "base = \"base.toml\"\nobserved = [\"A1_over_Ainc\"]\n\
         [data]\n\"incident.xi\" = [0.2, 0.4]\nA1_over_Ainc = [0.9, 0.95]\n\
         [[parameter]]\nkey = \"interface.traction.stiffness\"\n\
         bounds = [\"1 TPa/m\", \"100 TPa/m\"]\nscale = \"log\"\ninitial = \"20 TPa/m\"\n\
         [design]\nvalues = [\"1 MHz\", \"2 MHz\"]\n",
    )
    .unwrap();
    let spec = contactwave::inverse::IdentifySpec::load(&d.join("identify.toml")).unwrap();
    assert_eq!(
        (spec.parameters[0].lower, spec.parameters[0].upper),
        (1e12, 1e14)
    );
    assert_eq!(spec.parameters[0].initial, 2e13);
    assert_eq!(spec.design.unwrap().values, vec![1e6, 2e6]);
    std::fs::remove_dir_all(&d).unwrap();
}

/// The two reproductions of the issue: `frequency = 1` (meant 1 MHz) and
/// `static_pressure = 0.082` (meant MPa) run, with a warning each.
#[test]
fn likely_unit_slips_warn() {
    let base = std::fs::read_to_string(examples().join("rccm_0.82MPa.toml")).unwrap();
    let slow = base.replacen("frequency = 1e6 ", "frequency = 1 ", 1);
    assert_ne!(slow, base);
    let s = Scenario::from_toml_str(&slow, "slow.toml").unwrap();
    let w: Vec<String> = s.warnings().iter().map(|w| w.to_string()).collect();
    assert!(
        w.iter()
            .any(|w| w.starts_with("slow.toml: incident.frequency = 1 Hz: below the audio range")),
        "{w:?}"
    );
    assert!(w.iter().any(|w| w.contains("15.000 s")), "{w:?}");
    let soft = base.replacen("static_pressure = 0.082e6 ", "static_pressure = 0.082 ", 1);
    assert_ne!(soft, base);
    let s = Scenario::from_toml_str(&soft, "soft.toml").unwrap();
    let w: Vec<String> = s.warnings().iter().map(|w| w.to_string()).collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].starts_with("soft.toml: interface.static_pressure = 0.082 Pa: below 1 kPa"));
    // a modulus below 1 MPa and a density in g/cm^3
    let s = Scenario::from_toml_str(
        &SI.replace(
            "youngs_modulus = 71e9",
            "youngs_modulus = 71\ndensity = 2.71",
        ),
        "m.toml",
    )
    .unwrap();
    let w: Vec<String> = s.warnings().iter().map(|w| w.to_string()).collect();
    assert!(
        w.iter()
            .any(|w| w.starts_with("m.toml: medium.youngs_modulus = 71 Pa")),
        "{w:?}"
    );
    assert!(
        w.iter()
            .any(|w| w.starts_with("m.toml: medium.density = 2.71 kg/m^3")),
        "{w:?}"
    );
    // the model (what the CLI and Python ask) reports the same
    let m = model::from_toml_str(&soft, "soft.toml")
        .unwrap()
        .base()
        .unwrap();
    assert_eq!(m.warnings().len(), 1);
}

fn scenario_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            scenario_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "toml") {
            out.push(p);
        }
    }
}

/// No false positives: no shipped scenario (nor the base of a shipped sweep) warns.
#[test]
fn shipped_examples_do_not_warn() {
    let mut files = Vec::new();
    scenario_files(&examples(), &mut files);
    let mut checked = 0;
    for p in files {
        let table = contactwave::scenario::read_table(&p).unwrap();
        if table.contains_key("axis") || table.contains_key("observed") {
            continue; // sweeps and identifications: their bases are examples too
        }
        let m = model::plan_valid(table, &p)
            .and_then(|t| t.base())
            .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let w: Vec<String> = m.warnings().iter().map(|w| w.to_string()).collect();
        assert!(w.is_empty(), "{}: {w:?}", p.display());
        checked += 1;
    }
    assert!(checked >= 15, "{checked}");
}

/// A preset in a half-space carries the P-wave modulus (aluminium c_P = 6230 m/s, not the
/// bar speed 5118 m/s); the same preset in a bar stack keeps E; the thesis' scenarios
/// state E and keep the bar speed of the 1D model.
#[test]
fn presets_give_a_half_space_the_p_wave_speed() {
    let s = Scenario::from_toml_str(&SI.replace("youngs_modulus = 71e9\n", ""), "al.toml").unwrap();
    let (e, nu, rho): (f64, f64, f64) = (71e9, 0.33, 2710.0);
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let c = s.medium.wave_speed();
    assert!((c / (m / rho).sqrt() - 1.0).abs() < 1e-12, "{c}");
    assert!((c - 6230.4).abs() < 0.1, "{c}");
    // the shear wave keeps G = E / (2 (1 + nu))
    let ct = s.medium.shear_wave_speed().unwrap();
    assert!((ct - (e / (2.0 * (1.0 + nu)) / rho).sqrt()).abs() < 1e-9);
    // the wave table names what the run used
    let t = s.wave_table();
    assert_eq!(t[0], ("medium_wave_speed".to_string(), c));
    assert_eq!(t[1].0, "medium_impedance");
    assert!((t[1].1 - rho * c).abs() < 1e-6 * rho * c);
    // a stated modulus is used as given (the thesis' 1D convention)
    let stated = Scenario::from_toml_str(SI, "si.toml").unwrap();
    assert!((stated.medium.wave_speed() - (e / rho).sqrt()).abs() < 1e-9);
    let thesis = Scenario::load(&examples().join("thesis/ch3_rccm.toml")).unwrap();
    assert!((thesis.medium.wave_speed() - 2049.80).abs() < 0.01);
    // a bar keeps Young's modulus
    let stack = r#"
[model]
kind = "bar_stack"
area = 1.0
first_end = "transparent"
last_end = "transparent"
[[segment]]
name = "a"
length = 0.01
material = "aluminium"
[[segment]]
name = "b"
length = 0.01
material = "aluminium"
[[interface]]
between = ["a", "b"]
traction = { law = "bonded" }
[incident]
frequency = 1e6
cycles = 5
amplitude = 1e6
"#;
    let p = std::env::temp_dir().join(format!("contactwave-bar-{}.toml", std::process::id()));
    std::fs::write(&p, stack).unwrap();
    let table = contactwave::scenario::read_table(&p).unwrap();
    let b = contactwave::scenario::bar_stack::BarStackScenario::from_table(table, &p).unwrap();
    std::fs::remove_file(&p).unwrap();
    let cb = b.stack.segments[0].material.wave_speed();
    assert!((cb - (e / rho).sqrt()).abs() < 1e-9, "{cb}");
}

/// The warnings the model of `text` (read as `file`) gives, one line each (what the CLI
/// prints and Python warns with).
fn model_warnings(text: &str, file: &str) -> Vec<String> {
    model::from_toml_str(text, file)
        .unwrap()
        .base()
        .unwrap()
        .warnings()
        .iter()
        .map(|w| w.to_string())
        .collect()
}

/// A bar stack's unit slips warn too: a segment length in mm, a modulus in GPa, a density
/// in g/cm^3 (what the CLI and Python ask of the model).
#[test]
fn bar_stack_unit_slips_warn() {
    let read = |f: &str| std::fs::read_to_string(examples().join(f)).unwrap();
    let warnings = |text: &str| model_warnings(text, "bars.toml");
    let (hammer, burst) = (read("tribobrake.toml"), read("bar_stack_incident.toml"));
    assert!(warnings(&hammer).is_empty() && warnings(&burst).is_empty());
    let long = hammer.replacen("length = 0.229 ", "length = 229 ", 1);
    assert_ne!(long, hammer);
    let w = warnings(&long);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].starts_with(
            "bars.toml: segment.0.length = 229 m: a bar longer than 10 m; a length in mm?"
        ),
        "{w:?}"
    );
    let light = burst.replacen(
        "material = \"pmma\" ",
        "material = \"pmma\"\ndensity = 1.19\nshear_modulus = 2 ",
        1,
    );
    assert_ne!(light, burst);
    let w = warnings(&light);
    for start in [
        "bars.toml: segment.0.density = 1.19 kg/m^3: lighter than any solid",
        "bars.toml: segment.0.shear_modulus = 2 Pa: below 1 MPa",
    ] {
        assert!(w.iter().any(|w| w.starts_with(start)), "{start}: {w:?}");
    }
}

/// A small 2D scenario in SI numbers: a crack, a transducer, a line receiver, an
/// absorbing bottom.
const SOLID_2D: &str = r#"
[model]
kind = "solid_2d"
width = 2e-3
duration = 0.6e-6
element_size = 0.1e-3
pml_thickness = 0.4e-3
bottom = "absorbing"
[[layer]]
thickness = 1e-3
p_speed = 6300.0
s_speed = 3100.0
density = 2700.0
[[crack]]
start = [0.7e-3, 0.5e-3]
end = [1.3e-3, 0.5e-3]
static_pressure = 0.2e6
[[source]]
x0 = 0.6e-3
x1 = 1.4e-3
signal = { frequency = 10e6, cycles = 2, amplitude = 10e6 }
[[receiver]]
name = "top"
at = [1e-3, 0.0]
to = [1.2e-3, 0.0]
count = 3
"#;

/// A 2D scenario's geometry, speeds and times take unit strings too: the same problem as
/// with SI numbers.
#[test]
fn solid_2d_geometry_takes_unit_strings() {
    use contactwave::scenario::solid_2d::{Solid2dScenario, Solid2dSpec};
    use contactwave::scenario::BuildCache;
    let si = SOLID_2D;
    let units = si
        .replace("width = 2e-3", "width = \"2 mm\"")
        .replace("element_size = 0.1e-3", "element_size = \"100 um\"")
        .replace("pml_thickness = 0.4e-3", "pml_thickness = \"0.4 mm\"")
        .replace("thickness = 1e-3", "thickness = \"1 mm\"")
        .replace("p_speed = 6300.0", "p_speed = \"6.3 km/s\"")
        .replace("s_speed = 3100.0", "s_speed = \"3.1 km/s\"")
        .replace("[0.7e-3, 0.5e-3]", "[\"0.7 mm\", \"0.5 mm\"]")
        .replace("[1.3e-3, 0.5e-3]", "[\"1.3 mm\", \"0.5 mm\"]")
        .replace("x0 = 0.6e-3", "x0 = \"0.6 mm\"")
        .replace("x1 = 1.4e-3", "x1 = \"1.4 mm\"")
        .replace("[1e-3, 0.0]", "[\"1 mm\", 0.0]")
        .replace("[1.2e-3, 0.0]", "[\"1.2 mm\", \"0 m\"]");
    assert!(units.matches(" mm\"").count() == 11, "{units}");
    let build = |text: &str| {
        let table: toml::Table = toml::from_str(text).unwrap();
        let spec = Solid2dSpec::from_table(table, "u.toml").unwrap();
        Solid2dScenario::from_spec(spec, "u.toml", Path::new("."), &BuildCache::new()).unwrap()
    };
    let (a, b) = (build(si), build(&units));
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs().max(1e-3);
    let (pa, pb) = (&a.problem, &b.problem);
    assert!(close(pb.width, pa.width) && close(pb.element_size, pa.element_size));
    assert!(close(pb.pml.thickness, pa.pml.thickness));
    assert!(close(pb.depth(), pa.depth()));
    let (ma, mb) = (pa.layers[0].material, pb.layers[0].material);
    assert!(close(mb.p_speed, ma.p_speed) && close(mb.s_speed, ma.s_speed));
    for k in 0..2 {
        assert!(close(pb.cracks[0].start[k], pa.cracks[0].start[k]));
        assert!(close(pb.cracks[0].end[k], pa.cracks[0].end[k]));
    }
    assert_eq!(pa.receivers.len(), 3);
    for (ra, rb) in pa.receivers.iter().zip(&pb.receivers) {
        assert!(close(rb[0], ra[0]) && close(rb[1], ra[1]), "{ra:?} {rb:?}");
    }
    // a unit of another dimension is an error naming the field
    let wrong = units.replace("\"2 mm\"", "\"2 MHz\"");
    let table: toml::Table = toml::from_str(&wrong).unwrap();
    let e = Solid2dSpec::from_table(table, "u.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("model.width") && e.contains("a length"), "{e}");
}

/// `[snapshots]` takes unit strings in `every` as in `times` (docs/scenario.md: every key
/// with a unit does): the same frames as the SI numbers.
#[test]
fn solid_2d_snapshot_times_take_unit_strings() {
    use contactwave::scenario::solid_2d::{Solid2dScenario, Solid2dSpec};
    use contactwave::scenario::BuildCache;
    let times = |snapshots: &str| -> Vec<f64> {
        let text = format!("{SOLID_2D}\n[snapshots]\n{snapshots}\n");
        let table: toml::Table = toml::from_str(&text).unwrap();
        let spec = Solid2dSpec::from_table(table, "u.toml").unwrap_or_else(|e| panic!("{e}"));
        let s = Solid2dScenario::from_spec(spec, "u.toml", Path::new("."), &BuildCache::new())
            .unwrap_or_else(|e| panic!("{e}"));
        s.snapshots.unwrap().times
    };
    let close = |a: &[f64], b: &[f64]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(x, y)| (x - y).abs() <= 1e-12 * y.abs())
    };
    let every = times("every = 0.2e-6");
    assert_eq!(every.len(), 3, "{every:?}");
    for text in [
        "every = \"0.2 us\"",
        "every = \"200 ns\"",
        "every = \"0.2 µs\"",
    ] {
        let t = times(text);
        assert!(close(&t, &every), "{text}: {t:?} against {every:?}");
    }
    let listed = times("times = [0.2e-6, 0.4e-6]");
    let t = times("times = [\"0.2 us\", \"400 ns\"]");
    assert!(close(&t, &listed), "{t:?} against {listed:?}");
    // a unit of another dimension is an error naming the key
    let text = format!("{SOLID_2D}\n[snapshots]\nevery = \"0.2 mm\"\n");
    let e = Solid2dSpec::from_table(toml::from_str(&text).unwrap(), "u.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("snapshots.every") && e.contains("a time"), "{e}");
}

/// The 2D model's plausibility warnings (model.md section 15, `Solid2dScenario::warnings`):
/// a speed in km/s, a width in mm, a closure in MPa, a frequency in MHz, absorbing layers
/// tens of wavelengths thick, each one line naming its key; an element size too coarse for
/// the harmonics (a phase error over the budget, then beyond the elements' band edge) with
/// the default that would do; and none for the same scenario written right.
#[test]
fn solid_2d_slips_are_warned() {
    let warnings = |edits: &[(&str, &str)]| -> Vec<String> {
        let mut text = SOLID_2D.to_string();
        for (from, to) in edits {
            assert!(text.contains(from), "{from}");
            text = text.replace(from, to);
        }
        model_warnings(&text, "w.toml")
    };
    assert!(warnings(&[]).is_empty(), "{:?}", warnings(&[]));
    let (h, coarse) = ("element_size = 0.1e-3", "element_size = 5e-3");
    for (edits, key) in [
        (
            &[("s_speed = 3100.0", "s_speed = 3.1")][..],
            "layer.0.s_speed = 3.1 m/s",
        ),
        // (with elements the memory budget takes: it names its key too)
        (
            &[("width = 2e-3", "width = 40.0"), (h, coarse)],
            "model.width = 40 m",
        ),
        (
            &[("static_pressure = 0.2e6", "static_pressure = 0.2")],
            "crack.0.static_pressure = 0.2 Pa",
        ),
        (
            &[("frequency = 10e6", "frequency = 10.0")],
            "source.0.signal.frequency = 10 Hz",
        ),
        // (with the default elements, metres wide for 30 Hz: the slip is named, not the
        // transducer's aperture against those elements)
        (
            &[(h, "order = 6"), ("frequency = 10e6", "frequency = 10.0")],
            "source.0.signal.frequency = 10 Hz",
        ),
        (
            &[("pml_thickness = 0.4e-3", "pml_thickness = 0.02")],
            "model.pml_thickness = 0.02 m",
        ),
        // a layer of thousands of wavelengths, under 10 m
        (
            &[("thickness = 1e-3", "thickness = 2.0"), (h, coarse)],
            "layer.0.thickness = 2 m",
        ),
        // stresses beyond small strains, a friction coefficient of 30, a stress receiver
        // of a traction component on the free top
        (
            &[("amplitude = 10e6", "amplitude = 10e9")],
            "source.0.signal.amplitude = 10000000000 Pa",
        ),
        (
            &[("static_pressure = 0.2e6", "static_pressure = 2e10")],
            "crack.0.static_pressure = 20000000000 Pa",
        ),
        (
            &[(
                "static_pressure = 0.2e6",
                "static_pressure = 0.2e6\ntangential = { law = \"coulomb\", friction = 30.0 }",
            )],
            "crack.0.tangential.friction = 30",
        ),
        (
            &[("count = 3", "count = 3\nquantity = \"stress\"")],
            "receiver.0.at = [0.001, 0] m",
        ),
    ] {
        let w = warnings(edits);
        assert!(
            w.iter().any(|w| w.starts_with(&format!("w.toml: {key}"))),
            "{key}: {w:?}"
        );
        assert!(w.iter().all(|w| w.lines().count() == 1), "{w:?}");
    }
    // the default at 10 MHz, order 6, 3 f0 is about 0.12 mm
    let w = warnings(&[(h, "element_size = 0.15e-3")]);
    assert!(
        w.len() == 1
            && w[0].starts_with("w.toml: model.element_size = 0.00015 m: the phase velocity")
            && w[0].contains("the default element_size for it would be"),
        "{w:?}"
    );
    let w = warnings(&[(h, "element_size = 0.5e-3")]);
    assert!(
        w.len() == 1 && w[0].contains("do not resolve the waves at 3 f0"),
        "{w:?}"
    );
}

/// A wrong value inside a law table is named by its own key (`crack.0.tangential.friction`,
/// not the table), as are an unknown key and an unknown law; a count written as a whole
/// float (`order = 6.0`, `crack_every = 1e1`) is that count, a fractional one is refused.
#[test]
fn law_parameters_are_named_by_their_keys_and_whole_floats_count() {
    let error = |from: &str, to: &str| -> String {
        assert!(SOLID_2D.contains(from), "{from}");
        let text = SOLID_2D.replace(from, to);
        match model::from_toml_str(&text, "k.toml").and_then(|t| t.base().map(|_| ())) {
            Err(e) => e.to_string(),
            Ok(()) => String::new(),
        }
    };
    let crack = "static_pressure = 0.2e6\n";
    for (law, field) in [
        (
            "tangential = { law = \"coulomb\", friction = \"0.3\" }",
            "crack.0.tangential.friction",
        ),
        (
            "tangential = { law = \"coulomb\", frict = 0.3 }",
            "crack.0.tangential.frict",
        ),
        (
            "tangential = { law = \"colomb\", friction = 0.3 }",
            "crack.0.tangential.law",
        ),
        (
            "compression = { law = \"power\", c = \"1e10\", m = 0.5 }",
            "crack.0.compression.c",
        ),
        // a stiffness beyond 1e24 Pa/m is rigid (and far beyond, below the solver's
        // precision): refused with the rigid law named
        (
            "tangential = { law = \"coulomb\", friction = 0.3, stiffness = 1e120 }",
            "crack.0.tangential.stiffness",
        ),
        (
            "traction = { law = \"linear\", stiffness = 2e24 }",
            "crack.0.traction.stiffness",
        ),
    ] {
        let e = error(crack, &format!("{crack}{law}\n"));
        assert!(
            e.starts_with(&format!("k.toml: field `{field}`")),
            "{law}: {e}"
        );
        assert_eq!(e.lines().count(), 1, "{e}");
    }
    assert_eq!(
        error(
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\norder = 6.0\ncrack_every = 1e1"
        ),
        ""
    );
    let e = error(
        "element_size = 0.1e-3",
        "element_size = 0.1e-3\ncrack_every = 2.5",
    );
    assert!(e.contains("model.crack_every") && e.contains("2.5"), "{e}");
}

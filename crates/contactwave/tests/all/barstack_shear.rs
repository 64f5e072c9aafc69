//! Shear waves in the bar stack (issue 11, item 4; model.md sections 5 and 13): the
//! finite-difference stack with a transverse field against the exact coupled half-space
//! solver (clipping by rigid-stick friction, the full RCCM law under a longitudinal and a
//! shear burst), the limits of friction, the energy balance with frictional dissipation,
//! a layered part with one frictional interface, and the checks of the new keys.

use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::Scenario;
use contactwave::{simulate_bar_stack, simulate_summary, Error};
use std::path::Path;

fn load(text: &str) -> Result<BarStackScenario, Error> {
    let table: toml::Table = text.parse().expect("toml");
    BarStackScenario::from_table(table, Path::new("shear_stack.toml"))
}

fn stack_summary(text: &str) -> contactwave::analysis::Summary {
    simulate_bar_stack(&load(text).expect("valid stack"))
        .expect("run")
        .summary
}

fn exact_summary(text: &str) -> contactwave::analysis::Summary {
    simulate_summary(&Scenario::from_toml_str(text, "h.toml").expect("valid")).expect("run")
}

fn get(s: &contactwave::analysis::Summary, k: &str) -> f64 {
    s.get(k).unwrap_or_else(|| panic!("missing {k}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Two aluminium bars (transparent ends: two half-spaces) at p0 = 10 MPa with the given
/// tangential law and shear burst amplitude (Pa).
fn two_bars(tangential: &str, amplitude: f64) -> String {
    format!(
        r#"
[model]
kind = "bar_stack"
area = 1.0
static_force = 10e6
first_end = "transparent"
last_end = "transparent"
samples_per_period = 500

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
tangential = {tangential}

[shear_incident]
frequency = 1e6
cycles = 10
window = "rectangular"
amplitude = {amplitude}
"#
    )
}

/// The same interface between two aluminium half-spaces, for the exact solver (given the
/// bars' modulus E: a preset alone gives a half-space the P-wave modulus).
fn half_spaces(tangential: &str, amplitude: f64) -> String {
    format!(
        r#"
[medium]
material = "aluminium"
youngs_modulus = 71e9
[counterpart]
kind = "medium"
material = "aluminium"
youngs_modulus = 71e9
[interface]
static_pressure = 10e6
tangential = {tangential}
[shear_incident]
frequency = 1e6
cycles = 10
window = "rectangular"
amplitude = {amplitude}
[solver]
samples_per_period = 500
"#
    )
}

#[test]
fn clipping_by_rigid_stick_friction_matches_the_exact_solver() {
    let law = r#"{ law = "coulomb", friction = 0.3 }"#;
    let fd = stack_summary(&two_bars(law, 5e6));
    let ex = exact_summary(&half_spaces(law, 5e6));
    for key in [
        "shear_A1_over_Ainc",
        "shear_A3_over_A1",
        "shear_A5_over_Ainc",
        "shear_tr_A1_over_Ainc",
        "shear_tr_A3_over_A1",
        "friction_dissipation",
    ] {
        let (a, b) = (get(&fd, key), get(&ex, key));
        eprintln!(
            "clipping {key}: stack {a:e}, exact {b:e}, rel {:.2e}",
            rel(a, b)
        );
        assert!(rel(a, b) < 2e-3, "{key}: stack {a:e}, exact {b:e}");
    }
    assert_eq!(get(&fd, "friction_ratio"), get(&ex, "friction_ratio"));
    // the rectangular burst's own leakage at 2 f0, the same in both
    assert!(rel(get(&fd, "shear_A2_over_A1"), get(&ex, "shear_A2_over_A1")) < 2e-3);
    // what came in left as waves or was dissipated by friction
    assert!(get(&fd, "energy_closure_error") < 1e-5);
    assert!(get(&fd, "friction_dissipation_fraction") > 0.1);
    // the interface never opened
    assert_eq!(get(&fd, "min_contact_pressure"), 10e6);
}

#[test]
fn friction_limits_free_bonded_and_below_the_slip_threshold() {
    // mu = 0: a free interface, total reflection of the shear wave
    let free = stack_summary(&two_bars(r#"{ law = "coulomb", friction = 0.0 }"#, 5e6));
    assert!((get(&free, "shear_energy_reflected_fraction") - 1.0).abs() < 1e-3);
    assert!(get(&free, "shear_energy_transmitted_fraction") < 1e-9);
    assert_eq!(get(&free, "friction_dissipation"), 0.0);
    // mu -> infinity: bonded; between identical media nothing is reflected
    let bonded = stack_summary(&two_bars(r#"{ law = "coulomb", friction = 1e6 }"#, 5e6));
    assert!((get(&bonded, "shear_energy_transmitted_fraction") - 1.0).abs() < 1e-3);
    // (the rigid-stick constraint is first order in time: O((w dt)^2) of reflection)
    assert!(get(&bonded, "shear_energy_reflected_fraction") < 1e-6);
    // below the slip threshold (tau_inc < mu p0): linear, no harmonics, no dissipation
    let stick = stack_summary(&two_bars(r#"{ law = "coulomb", friction = 0.3 }"#, 2.9e6));
    assert_eq!(get(&stick, "friction_dissipation"), 0.0);
    // the transmitted wave is the incident one: its A3 is the rectangular burst's own
    // leakage, as with the bonded interface
    let a3 = |s: &contactwave::analysis::Summary| get(s, "shear_tr_A3_over_A1");
    assert!((a3(&stick) - a3(&bonded)).abs() < 1e-6 * a3(&bonded).max(1e-3));
    assert!(get(&stick, "shear_energy_reflected_fraction") < 1e-6);
}

const RCCM_STACK: &str = r#"
[model]
kind = "bar_stack"
area = 1.0
static_force = 0.82e6
first_end = "transparent"
last_end = "transparent"

[[segment]]
name = "a"
length = 0.005
material = "aluminium"

[[segment]]
name = "b"
length = 0.005
material = "aluminium"

[[interface]]
between = ["a", "b"]
traction = { law = "rccm", stiffness = 2e13, energy = 0.1 }
tangential = { law = "rccm", stiffness = 1e13, friction = 0.4 }

[incident]
frequency = 1e6
cycles = 15
amplitude = 3e6

[shear_incident]
frequency = 1e6
cycles = 15
amplitude = 2e6
delay = 2e-6
"#;

#[test]
fn full_rccm_under_both_waves_matches_the_exact_solver_to_one_percent() {
    // both bursts defined at x = 0 cross the first bar at their own speeds: delay the
    // shear burst so that it meets the interface 2 us after the longitudinal one, as in
    // the half-space example
    let s = load(RCCM_STACK).unwrap();
    let m = s.stack.segments[0].material;
    let len = s.stack.segments[0].length;
    let delay = 2e-6 - (len / m.shear_wave_speed().unwrap() - len / m.wave_speed());
    let fd = stack_summary(&RCCM_STACK.replace("delay = 2e-6", &format!("delay = {delay:e}")));
    let ex = exact_summary(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/shear/rccm_shear.toml"),
        )
        .unwrap()
        // the bars' modulus E (a preset alone gives a half-space the P-wave modulus)
        .replace(
            "material = \"aluminium\"",
            "material = \"aluminium\"\nyoungs_modulus = 71e9",
        ),
    );
    for (k_fd, k_ex) in [
        ("A1_over_Ainc", "A1_over_Ainc"),
        ("A2_over_Ainc", "A2_over_Ainc"),
        ("beta_end_0", "beta_end"),
        ("shear_A1_over_Ainc", "shear_A1_over_Ainc"),
        ("shear_A3_over_Ainc", "shear_A3_over_Ainc"),
        ("shear_tr_A1_over_Ainc", "shear_tr_A1_over_Ainc"),
        ("friction_dissipation", "friction_dissipation"),
    ] {
        let (a, b) = (get(&fd, k_fd), get(&ex, k_ex));
        eprintln!(
            "rccm {k_fd}: stack {a:e}, exact {b:e}, rel {:.2e}",
            rel(a, b)
        );
        assert!(rel(a, b) < 0.01, "{k_fd}: stack {a:e}, exact {b:e}");
    }
    // damage and friction close the balance of both wave types
    assert!(get(&fd, "energy_closure_error") < 1e-3);
    assert!(get(&fd, "damage_dissipation_0") > 0.0);
}

#[test]
fn without_shear_the_full_rccm_reproduces_the_normal_stack() {
    let normal = RCCM_STACK
        .replace(
            r#"tangential = { law = "rccm", stiffness = 1e13, friction = 0.4 }"#,
            "",
        )
        .replace("[shear_incident]", "[unused]");
    let normal: String = normal.split("[unused]").next().unwrap().replace(
        "last_end = \"transparent\"",
        "last_end = \"transparent\"\nduration = 2e-4",
    );
    let coupled = normal.replace(
        r#"traction = { law = "rccm", stiffness = 2e13, energy = 0.1 }"#,
        r#"traction = { law = "rccm", stiffness = 2e13, energy = 0.1 }
tangential = { law = "rccm", stiffness = 0.0, friction = 0.0 }"#,
    );
    let a = simulate_bar_stack(&load(&normal).unwrap()).unwrap();
    let b = simulate_bar_stack(&load(&coupled).unwrap()).unwrap();
    assert!(a.shear.is_none() && b.shear.is_some());
    for key in ["A1_over_Ainc", "A2_over_Ainc", "A3_over_Ainc", "beta_end_0"] {
        let (x, y) = (get(&a.summary, key), get(&b.summary, key));
        assert!(rel(y, x) < 1e-9, "{key}: {x:e} vs {y:e}");
    }
    // no shear motion at all
    let sh = b.shear.unwrap();
    assert!(sh.gap[0].iter().all(|g| *g == 0.0));
}

#[test]
fn a_layered_part_dissipates_only_at_its_frictional_interface() {
    let text = r#"
[model]
kind = "bar_stack"
area = 1e-4
static_force = 500.0
first_end = "transparent"
last_end = "transparent"

[[segment]]
name = "top"
length = 0.01
material = "steel"

[[segment]]
name = "layer"
length = 0.002
material = "aluminium"

[[segment]]
name = "base"
length = 0.01
material = "steel"

[[interface]]
between = ["top", "layer"]
compression = { law = "linear", stiffness = 1e15 }
tangential = { law = "linear", stiffness = 5e14 }

[[interface]]
between = ["layer", "base"]
tangential = { law = "coulomb", friction = 0.2 }

[shear_incident]
frequency = 2e6
cycles = 10
amplitude = 2e6

[[probe]]
name = "mid"
x = 0.011
"#;
    let r = simulate_bar_stack(&load(text).unwrap()).unwrap();
    let s = &r.summary;
    // p0 = 5 MPa, mu p0 = 1 MPa below the burst: the second interface slips
    assert!(get(s, "friction_dissipation_1") > 0.0);
    assert_eq!(get(s, "friction_dissipation_0"), 0.0);
    assert!(get(s, "max_slip_1") > 0.0);
    assert!(
        get(s, "energy_closure_error") < 1e-4,
        "{}",
        get(s, "energy_closure_error")
    );
    assert!(get(s, "shear_tr_A3_over_A1") > 1e-3);
    let p = r.probes[0].shear.as_ref().expect("transverse probe");
    assert!(p.velocity.iter().any(|v| v.abs() > 0.0));
}

#[test]
fn malformed_transverse_input_names_the_field() {
    let field = |text: &str| match load(text) {
        Err(Error::Invalid { field, .. }) => field,
        other => panic!("expected an invalid field, got {other:?}"),
    };
    let law = r#"{ law = "coulomb", friction = 0.3 }"#;
    // a segment with no shear modulus
    let t = two_bars(law, 5e6).replacen(
        "material = \"aluminium\"",
        "youngs_modulus = 7.1e10\ndensity = 2710.0",
        1,
    );
    assert_eq!(field(&t), "segment.0.poisson_ratio");
    // negative friction
    let t = two_bars(r#"{ law = "coulomb", friction = -0.3 }"#, 5e6);
    assert_eq!(field(&t), "interface.0.tangential.friction");
    // Poisson's ratio out of (-1, 0.5)
    let t = two_bars(law, 5e6).replacen(
        "material = \"aluminium\"",
        "material = \"aluminium\"\npoisson_ratio = 0.7",
        1,
    );
    assert_eq!(field(&t), "segment.0.poisson_ratio");
    // a static shear force with nothing to hold it
    let t = two_bars(law, 5e6).replace(
        "static_force = 10e6",
        "static_force = 10e6\nstatic_shear_force = 1e6",
    );
    assert_eq!(field(&t), "model.static_shear_force");
    // above mu p0 the stack would slide at rest
    let t = two_bars(law, 5e6)
        .replace(
            "static_force = 10e6",
            "static_force = 10e6\nstatic_shear_force = 4e6",
        )
        .replace("last_end = \"transparent\"", "last_end = \"fixed\"");
    assert_eq!(field(&t), "model.static_shear_force");
    // a shear wave needs a transparent first end
    let t = two_bars(law, 5e6).replace("first_end = \"transparent\"", "first_end = \"free\"");
    assert_eq!(field(&t), "model.first_end");
    // a shear wave takes an amplitude, not xi
    let t = two_bars(law, 5e6).replace("amplitude = 5000000", "xi = 0.5");
    assert!(load(&t).is_err());
}

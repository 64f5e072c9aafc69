//! The 1D-reduction example (`examples/solid_2d/interface_reduction.toml`), shortened: a
//! full-width RCCM interface under a plane P wave injected by total-field/scattered-field
//! reproduces the exact half-space solver's max gap, and the energy closes. The 1D
//! half-spaces take the 2D preset's P-wave modulus `E (1 - nu) / ((1 + nu) (1 - 2 nu))`
//! (E = 71 GPa, nu = 0.33: 1.05197e11 Pa, c_P = 6230.4 m/s) as their Young's modulus.

use contactwave::model::{self, RunControl};

const ONE_D: &str = r#"
[medium]
material = "aluminium"
youngs_modulus = 1.05197e11
[counterpart]
kind = "medium"
material = "aluminium"
youngs_modulus = 1.05197e11
[interface]
static_pressure = 0.3e6
compression = { law = "rigid" }
traction = { law = "rccm", stiffness = 2e13, energy = 0.01, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 5
window = "hann"
amplitude = 3e6
"#;

/// The text of `examples/solid_2d/interface_reduction.toml`.
fn reduction_example() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/solid_2d/interface_reduction.toml"
    );
    std::fs::read_to_string(path).unwrap()
}

#[test]
fn interface_reduction_example_matches_the_exact_solver() {
    let text = reduction_example();
    // shortened: the gap's history ends within 8 us
    let short = text.replace("duration = 11e-6", "duration = 8e-6");
    assert_ne!(short, text, "the example's duration line changed");
    let two_d = model::from_toml_str(&short, "interface_reduction.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s2 = two_d.summary();
    eprintln!("{s2:?}");
    assert!(s2.get("energy_closure_error").unwrap() < 1e-9, "{s2:?}");
    let one_d = model::from_toml_str(ONE_D, "one_d.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s1 = one_d.summary();
    eprintln!("{s1:?}");
    let (g2, g1) = (
        s2.get("crack_max_gap_0").unwrap(),
        s1.get("max_gap").unwrap(),
    );
    eprintln!(
        "max gap 2D {g2:e}, exact {g1:e}, error {:.2e}",
        g2 / g1 - 1.0
    );
    // measured +0.20% (+0.93% at 0.5 mm, +0.06% at 0.125 mm: docs/model.md table 15.8-3)
    assert!((g2 / g1 - 1.0).abs() < 5e-3, "2D {g2:e} exact {g1:e}");
    // the bond is damaged (beta falls), as in the exact solution
    let (b2, b1) = (
        s2.get("crack_min_adhesion_0").unwrap(),
        s1.get("beta_end").unwrap(),
    );
    eprintln!("adhesion 2D {b2}, exact {b1}");
    assert!(b1 < 0.99 && (b2 - b1).abs() < 5e-3, "2D {b2} exact {b1}");
    // the reflected wave's A2/A1 (the 2D receiver in the scattered-field region)
    let (r2, r1) = (
        s2.get("reflected_A2_over_A1").unwrap(),
        s1.get("A2_over_A1").unwrap(),
    );
    eprintln!("reflected A2/A1 2D {r2}, exact {r1}");
    assert!((r2 / r1 - 1.0).abs() < 0.01, "2D {r2} exact {r1}");
}

/// A plane wave's type may be written in any case (`"p"`, `"Sv"`); a type the run does
/// not carry stays an error whatever its case.
#[test]
fn plane_wave_types_may_be_written_in_any_case() {
    let text = reduction_example();
    assert!(text.contains("wave = \"P\" "));
    for name in ["p", "sv", "Sv"] {
        let text = text.replace("wave = \"P\" ", &format!("wave = \"{name}\" "));
        let built = model::from_toml_str(&text, "case.toml").and_then(|t| t.base().map(|_| ()));
        assert!(built.is_ok(), "{name}: {built:?}");
    }
    let text = text.replace("wave = \"P\" ", "wave = \"sh\" ");
    let err = model::from_toml_str(&text, "case.toml")
        .and_then(|t| t.base().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(err.contains("source.0.wave") && err.contains("sh"), "{err}");
}

/// A bad plane-wave source is a one-line error naming its key, before any step.
#[test]
fn bad_plane_wave_sources_are_errors_naming_the_key() {
    let text = reduction_example();
    for (from, to, key) in [
        ("wave = \"P\" ", "wave = \"SH\" ", "source.0.wave"),
        ("angle = 0 ", "angle = 10 ", "source.0.angle"),
        ("z = 6e-3 ", "z = 16e-3 ", "source.0.z"),
        ("z = 6e-3 ", "z = 40e-3 ", "source.0.z"),
        ("z = 6e-3 ", "# ", "source.0.z"),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = text.replace(from, to);
        let err = model::from_toml_str(&bad, "bad.toml")
            .and_then(|t| t.base()?.run(&RunControl::default()).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(err.contains(key), "{key}: {err}");
        assert!(err.starts_with("bad.toml"), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

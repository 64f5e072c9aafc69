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
    // measured +0.10% (+0.37% at 0.5 mm, +0.04% at 0.125 mm: docs/model.md table 15.8-3)
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

/// One crack's recorded field `name`, `[point][record]`.
fn crack_rows(outcome: &dyn model::Outcome, name: &str) -> Vec<Vec<f64>> {
    let record = outcome.record();
    let Some(model::Value::Tuple(cracks)) = record.get("cracks") else {
        panic!("cracks")
    };
    let model::Value::Map(c) = &cracks[0] else {
        panic!("crack map")
    };
    let Some(model::Value::Rows(rows)) = c.get(name) else {
        panic!("{name}")
    };
    rows.clone()
}

/// A plane wave at normal incidence on a full-width interface of a periodic strip moves
/// every node of it alike, through the bond's damage and the clapping after it: the whole
/// example (11 us; the bond breaks near 4 us), its crack fields uniform across the width at
/// every record, one contact state a record, and the crack's energy at least the damage it
/// tallies (what the interface takes is damage plus what it stores and loses at impacts).
/// Before a spring's stress stopped being averaged with a rigid contact's reaction
/// (model.md section 9.2), a mode of the element's period grew here from round-off to
/// 1.2 MPa between neighbouring nodes, open and closed side by side.
#[test]
fn a_full_width_interface_stays_uniform_after_its_bond_breaks() {
    let outcome = model::from_toml_str(&reduction_example(), "interface_reduction.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s = outcome.summary();
    assert!(s.get("crack_min_adhesion_0").unwrap() < 0.1, "{s:?}");
    let stress = crack_rows(outcome.as_ref(), "normal_stress");
    let state = crack_rows(outcome.as_ref(), "state");
    let gap = crack_rows(outcome.as_ref(), "normal_gap");
    let (n_points, n_records) = (stress.len(), stress[0].len());
    assert!(n_points > 10 && n_records > 1000);
    let mut worst = 0.0f64;
    for k in 0..n_records {
        let column = |f: &Vec<Vec<f64>>| (0..n_points).map(|i| f[i][k]).collect::<Vec<f64>>();
        let (sk, stk, gk) = (column(&stress), column(&state), column(&gap));
        let spread = |v: &[f64]| {
            v.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
                - v.iter().cloned().fold(f64::INFINITY, f64::min)
        };
        worst = worst.max(spread(&sk));
        assert!(
            stk.iter().all(|&x| x == stk[0]),
            "record {k}: states {stk:?}"
        );
        assert!(spread(&gk) <= 1e-9 * 9.2e-8, "record {k}: gaps {gk:?}");
    }
    eprintln!("largest stress spread along the interface {worst:e} Pa");
    // measured 1.9e-6 Pa (3 MPa wave, 0.3 MPa closure)
    assert!(worst < 1.0, "{worst:e} Pa");
    let (cracks, damage) = (
        s.get("energy_cracks").unwrap(),
        s.get("energy_damage").unwrap(),
    );
    eprintln!("crack energy {cracks:e}, damage {damage:e} J/m");
    assert!(damage > 0.0 && cracks >= damage, "{cracks:e} {damage:e}");
}

/// A compliant compression branch still presses its faces at a positive gap from rest: a
/// point is open (state 0) only beyond the law's contact-loss gap, where it carries no
/// compression. A quadratic law under 1 MPa closure (contact lost at 1.1e-8 m), a wave
/// that does not open it: closed everywhere, every record; shaken harder it opens, and
/// every open point carries no compression.
#[test]
fn a_compliant_crack_is_open_only_beyond_its_contact_loss_gap() {
    let text = reduction_example()
        .replace(
            "compression = { law = \"rigid\" }",
            "compression = { law = \"quadratic\", k0 = 1e14, k1 = 1e21 }",
        )
        .replace(
            "traction = { law = \"rccm\", stiffness = 2e13, energy = 0.01, viscosity = 1e-8 }",
            "traction = { law = \"free\" }",
        )
        .replace("static_pressure = 0.3e6", "static_pressure = 1e6")
        .replace("duration = 11e-6", "duration = 5e-6");
    for (amplitude, opens) in [("0.4e6", false), ("6e6", true)] {
        let text = text.replace("amplitude = 3e6", &format!("amplitude = {amplitude}"));
        let outcome = model::from_toml_str(&text, "compliant.toml")
            .unwrap()
            .base()
            .unwrap()
            .run(&RunControl::default())
            .unwrap();
        let (gap, stress, state) = (
            crack_rows(outcome.as_ref(), "normal_gap"),
            crack_rows(outcome.as_ref(), "normal_stress"),
            crack_rows(outcome.as_ref(), "state"),
        );
        let cells = || {
            gap.iter()
                .flatten()
                .zip(stress.iter().flatten())
                .zip(state.iter().flatten())
        };
        // the faces move apart under compression (a positive gap, still closed)
        assert!(cells().any(|((&g, &s), &st)| g > 0.0 && s < -1e3 && st != 0.0));
        let open = cells().filter(|&(_, &st)| st == 0.0).count();
        assert_eq!(open > 0, opens, "{amplitude}: {open} open cells");
        for ((&g, &s), &st) in cells() {
            if st == 0.0 {
                assert!(g > 0.0 && s >= -1e-6, "open with gap {g:e}, stress {s:e}");
            } else {
                assert!(s <= 1e-6, "closed with stress {s:e}");
            }
        }
    }
}

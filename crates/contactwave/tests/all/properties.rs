//! Property tests over random valid scenarios (issue 2, item 9): no panic, finite
//! outputs, beta in [0, 1] and non-increasing, Signorini with rigid compression.

use contactwave::{scenario::Scenario, simulate};
use proptest::prelude::*;

fn compression() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("{ law = \"rigid\" }".to_string()),
        (1e10f64..1e14).prop_map(|k| format!("{{ law = \"linear\", stiffness = {k} }}")),
        (1e10f64..1e12, 0.1f64..0.9)
            .prop_map(|(c, m)| format!("{{ law = \"power\", c = {c}, m = {m} }}")),
        (1e10f64..1e11, 0.2f64..0.6, 0.05f64..0.9).prop_map(|(c, m, f)| format!(
            "{{ law = \"modified_power\", c = {c}, m = {m}, zero_pressure_fraction = {f} }}"
        )),
        (1e11f64..1e13).prop_map(|k| format!("{{ law = \"quadratic\", k0 = {k}, k1 = 0.0 }}")),
        (1e11f64..1e12).prop_map(|k| format!(
            "{{ law = \"table\", pressure = [0.0, 1e5, 1e6], stiffness = [{}, {k}, {}] }}",
            0.2 * k,
            2.0 * k
        )),
    ]
}

fn traction() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("{ law = \"free\" }".to_string()),
        Just("{ law = \"bonded\" }".to_string()),
        (1e8f64..1e15).prop_map(|k| format!("{{ law = \"linear\", stiffness = {k} }}")),
        (
            1e9f64..1e16,
            0.0f64..1.0,
            prop_oneof![Just(0.0), 1e-10f64..1e-6]
        )
            .prop_map(|(c, w, b)| format!(
                "{{ law = \"rccm\", stiffness = {c}, energy = {w}, viscosity = {b} }}"
            )),
    ]
}

prop_compose! {
    fn scenario_text()(
        comp in compression(),
        trac in traction(),
        p0 in 1e4f64..1e6,
        xi in 0.05f64..2.0,
        f in 1e5f64..2e6,
        cycles in 2.0f64..8.0,
        medium in prop_oneof![Just("pmma"), Just("aluminium")],
        counterpart in prop_oneof![Just(""), Just("[counterpart]\nkind = \"medium\"\nmaterial = \"steel\"\n")],
        window in prop_oneof![Just("hann_ramps"), Just("hann"), Just("rectangular")],
    ) -> String {
        format!(
            "[medium]\nmaterial = \"{medium}\"\n[interface]\nstatic_pressure = {p0}\ncompression = {comp}\ntraction = {trac}\n[incident]\nfrequency = {f}\ncycles = {cycles}\nxi = {xi}\nwindow = \"{window}\"\n[solver]\nsamples_per_period = 64\n{counterpart}"
        )
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    #[test]
    fn random_valid_scenarios_are_physical(text in scenario_text()) {
        let s = Scenario::from_toml_str(&text, "random.toml").expect("valid");
        let rigid = s.law.compression.is_rigid();
        let bonded = s.law.traction.is_rigid();
        let p0 = s.law.static_pressure;
        let r = simulate(&s).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let io = &r.interface;
        for (k, v) in r.summary.iter() {
            prop_assert!(v.is_finite(), "{} not finite\n{}", k, text);
        }
        for series in [&io.gap, &io.contact_stress, &io.beta, &io.reflected_stress, &io.transmitted_stress] {
            prop_assert!(series.iter().all(|v| v.is_finite()));
        }
        for w in io.beta.windows(2) {
            prop_assert!(w[1] <= w[0] && w[1] >= 0.0 && w[0] <= 1.0);
        }
        if rigid {
            let scale = p0 + s.incident.peak() * 2.0;
            for (g, sig) in io.gap.iter().zip(&io.contact_stress) {
                prop_assert!(*g >= 0.0, "penetration {}", g);
                if *g == 0.0 && !bonded {
                    prop_assert!(*sig <= 1e-9 * scale, "tension while closed {}", sig);
                }
            }
        }
        // coarse sampling (64 per period) and very stiff branches: a sanity bound only (a
        // damaging RCCM branch of C_N = 2e15 Pa/m at 229 kHz closes to 1.7e-3 at this
        // sampling: the regression file keeps it); the 1e-6 closure at default resolution is
        // asserted in tests/all/validation.rs
        prop_assert!(r.summary.get("energy_closure_error").unwrap() < 1e-2, "closure\n{}", text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]
    /// A unit string of any text is a value or an error, never a panic; a number with an
    /// SI prefix on a unit of the key's dimension is that number times the prefix.
    #[test]
    fn unit_strings_parse_or_refuse_without_panicking(
        text in "\\PC{0,12}",
        x in -1e6f64..1e6,
        prefix in prop::sample::select(vec![("k", 1e3), ("M", 1e6), ("G", 1e9), ("m", 1e-3), ("u", 1e-6), ("", 1.0)]),
    ) {
        use contactwave::scenario::units::{parse, Dimension};
        for dim in Dimension::ALL {
            let _ = parse(&text, dim);
        }
        let (p, f) = prefix;
        let v = parse(&format!("{x} {p}Pa"), Dimension::Pressure).unwrap();
        prop_assert!((v - x * f).abs() <= 1e-12 * (x * f).abs());
        let wrong = format!("{x} {p}Hz");
        prop_assert!(parse(&wrong, Dimension::Pressure).is_err());
    }
}

/// A TOML value of any type, nested up to two levels, with numbers, unit strings and
/// garbage.
fn toml_value() -> impl Strategy<Value = toml::Value> {
    let leaf = prop_oneof![
        any::<i64>().prop_map(toml::Value::Integer),
        prop_oneof![
            Just(0.3),
            Just(f64::NAN),
            Just(-1.0),
            Just(1e300),
            -10.0f64..10.0
        ]
        .prop_map(toml::Value::Float),
        prop_oneof![
            Just("incident.xi".to_string()),
            Just("1 MHz".to_string()),
            Just("log".to_string()),
            Just("rccm_0.82MPa.toml".to_string()),
            "\\PC{0,8}",
        ]
        .prop_map(toml::Value::String),
        any::<bool>().prop_map(toml::Value::Boolean),
    ];
    leaf.prop_recursive(2, 16, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(toml::Value::Array),
            prop::collection::btree_map(file_key(), inner, 0..4)
                .prop_map(|m| toml::Value::Table(m.into_iter().collect())),
        ]
    })
}

/// Keys of sweep and identification files, and some that are not.
fn file_key() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "base",
        "axis",
        "set",
        "parameter",
        "values",
        "linspace",
        "logspace",
        "data",
        "observed",
        "fit",
        "design",
        "key",
        "bounds",
        "scale",
        "initial",
        "also",
        "particles",
        "seed",
        "frequencies",
        "control",
        "incident.xi",
        "A2_over_A1",
        "foo",
    ])
    .prop_map(str::to_string)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Random tables read as a sweep file or an identification file give a sweep, a spec or
    /// an error naming the file, never a panic (issue 25, item 7: the derived formats and
    /// their validation pass).
    #[test]
    fn garbage_sweep_and_identification_files_are_errors_not_panics(
        entries in prop::collection::btree_map(file_key(), toml_value(), 0..6),
    ) {
        use contactwave::{study::Sweep, Error};
        let table: toml::Table = entries.into_iter().collect();
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
        let path = dir.join("garbage.toml");
        let named = |e: &Error| match e {
            Error::Invalid { file, field, .. } => !file.is_empty() && !field.is_empty(),
            Error::Parse { file, .. } => !file.is_empty(),
            Error::Io { .. } => true,
            _ => false,
        };
        if let Err(e) = Sweep::from_table(table.clone(), &path) {
            prop_assert!(named(&e), "{e:?}");
        }
        #[cfg(feature = "identify")]
        if let Err(e) = contactwave::inverse::IdentifySpec::from_table(table, &path) {
            prop_assert!(named(&e), "{e:?}");
        }
    }
}

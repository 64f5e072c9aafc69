//! Weak nonlinearity (issue 15; model.md sections 6.1 and 8.1): the analysis methods
//! against the second-order perturbation solution of a smooth compression law without
//! contact loss between two aluminium half-spaces, and the floor every run reports.

use contactwave::analysis::methods::{method_bands, Records};
use contactwave::analysis::AnalysisMethod;
use contactwave::model::half_space::methods::{inverted, signal};
use contactwave::scenario::Scenario;
use contactwave::study::validation::{
    perturbation_of, weak_laws, weak_nonlinearity, weak_scenario,
};

const P0: f64 = 10e6;

fn run(law: &str, cycles: f64, m: AnalysisMethod) -> (f64, f64, contactwave::analysis::Summary) {
    let s = weak_scenario(P0, law, cycles, m).unwrap();
    let reference = perturbation_of(&s).beta_reflected();
    let sm = contactwave::simulate_summary(&s).unwrap();
    (sm.get("beta_star").unwrap(), reference, sm)
}

#[test]
fn leakage_free_methods_match_the_closed_form_within_one_percent_at_15_cycles() {
    for (name, law) in weak_laws(P0) {
        for m in [
            AnalysisMethod::PulseInversion,
            AnalysisMethod::LinearReference,
            AnalysisMethod::PlateauFit,
        ] {
            let (b, r, sm) = run(&law, 15.0, m);
            assert!(
                (b / r - 1.0).abs() < 0.01,
                "{name} {}: beta* {b:e} vs closed form {r:e}",
                m.name()
            );
            assert_eq!(sm.get("analysis_method"), Some(m.code()));
            assert_eq!(
                sm.get("contact_loss_fraction"),
                Some(0.0),
                "{name}: no contact loss"
            );
        }
    }
}

#[test]
fn band_peak_sits_on_its_leakage_floor_and_says_so() {
    let law = &weak_laws(P0)[0].1;
    let (b15, r, s15) = run(law, 15.0, AnalysisMethod::BandPeak);
    let (b40, _, s40) = run(law, 40.0, AnalysisMethod::BandPeak);
    // the floor (band_peak of the linearised interface's response) dominates A2 here
    for s in [&s15, &s40] {
        let floor = s.get("A2_floor_over_Ainc").unwrap();
        assert!(floor > 0.1 * s.get("A2_over_Ainc").unwrap());
        assert_eq!(s.get("harmonic_floor_warning"), Some(1.0));
    }
    // the floor falls with a longer burst, and so does the error
    assert!(s40.get("A2_floor_over_Ainc").unwrap() < s15.get("A2_floor_over_Ainc").unwrap());
    assert!(b15 / r - 1.0 > 1.0 && b40 / r - 1.0 > 0.1 && b40 < b15);
    // pulse inversion: no floor for the even harmonics
    let (_, _, pi) = run(law, 15.0, AnalysisMethod::PulseInversion);
    assert_eq!(pi.get("A2_floor_over_Ainc"), Some(0.0));
    assert_eq!(pi.get("A4_floor_over_Ainc"), Some(0.0));
    assert!(pi.get("A3_floor_over_Ainc").unwrap() > 0.0);
}

#[test]
fn transmitted_wave_matches_the_closed_form_by_pulse_inversion() {
    let law = &weak_laws(P0)[0].1;
    let s = weak_scenario(P0, law, 15.0, AnalysisMethod::PulseInversion).unwrap();
    let plus = contactwave::simulate(&s).unwrap();
    let minus = contactwave::simulate(&inverted(&s)).unwrap();
    let sig = signal(&s, &plus.interface);
    let b = method_bands(
        AnalysisMethod::PulseInversion,
        &Records {
            response: &plus.interface.transmitted_displacement,
            inverse: Some(&minus.interface.transmitted_displacement),
            linear: None,
        },
        &sig,
    )
    .unwrap();
    let beta = b.harmonic[2] / (b.harmonic[1] * b.harmonic[1]);
    let r = perturbation_of(&s).beta_transmitted();
    assert!((beta / r - 1.0).abs() < 0.01, "{beta:e} vs {r:e}");
    // identical media: the same A2 leaves on both sides, A1 differs by the transmission
    // and reflection coefficients, so beta*_T / beta*_R = (omega Z / 2K)^2
    let p = perturbation_of(&s);
    let ratio = (p.omega * p.z1 / (2.0 * p.stiffness)).powi(2);
    assert!((r / p.beta_reflected() / ratio - 1.0).abs() < 1e-12);
}

#[test]
fn validate_cases_pass() {
    let cases = weak_nonlinearity().unwrap();
    assert_eq!(cases.len(), 12);
    for c in &cases {
        // band_peak is shown, with its (large) error, as an informational row: no
        // criterion, neither passed nor failed, never counted as a check
        let band = c.name.contains("band_peak");
        assert_eq!(c.is_check(), !band, "{c:?}");
        if band {
            assert!(c.tolerance.is_none() && c.rel_error > 0.1, "{c:?}");
            assert!(!c.passed() && !c.failed(), "{c:?}");
        } else {
            assert!(c.passed(), "{c:?}");
        }
    }
}

#[test]
fn a_power_law_at_zero_pressure_has_no_linear_reference() {
    let text = "[medium]\nmaterial = \"aluminium\"\n[interface]\nstatic_pressure = 0\ncompression = { law = \"power\", c = 1.81e10, m = 0.35 }\n[incident]\nfrequency = 5e6\namplitude = 1e3\n";
    let with = |m: &str| {
        Scenario::from_toml_str(
            &format!("{text}[analysis]\nmethod = \"{m}\"\n"),
            "zero.toml",
        )
    };
    let e = contactwave::simulate_summary(&with("linear_reference").unwrap()).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("zero.toml") && msg.contains("analysis.method"),
        "{msg}"
    );
    // the floors are then unknown (NaN), and pulse inversion still runs
    let s = contactwave::simulate_summary(&with("pulse_inversion").unwrap()).unwrap();
    assert!(s.get("A2_floor_over_Ainc").unwrap().is_nan());
    assert_eq!(s.get("harmonic_floor_warning"), Some(0.0));
    let bad = with("fft").unwrap_err().to_string();
    assert!(bad.contains("zero.toml") && bad.contains("fft"), "{bad}");
}

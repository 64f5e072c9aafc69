//! Identification from raw waveforms (issue 28 item 2, docs/identify.md section 8):
//! examples/identify/raw_records.toml recovers the RCCM stiffness C_N of an adhesive PMMA
//! interface from eight reflected echoes recorded behind a band-pass transducer with noise;
//! its records are what its documented `--synthesize` command makes; the forward signal is
//! reduced exactly as the records (a noise-free record of the forward model gives zero
//! residual); the 2D model's receivers are waveforms too; and bad `[records]` tables are
//! one-line errors.

#![cfg(feature = "identify")]

use contactwave::inverse::{identify, synthesize_records, IdentifySpec, Model};
use contactwave::model::{self, RunControl, Value};
use std::path::{Path, PathBuf};

const CN: &str = "interface.traction.stiffness";
/// The value the example's records were made with (its header comment).
const TRUE_CN: f64 = 2e13;

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify/raw_records.toml")
}

/// A copy of the example in a fresh folder with `edit` applied to its text and `records`
/// written as its records file (`None`: the example's own records copied).
fn variant(tag: &str, edit: impl Fn(String) -> String, records: Option<&str>) -> PathBuf {
    let src = example();
    let dir = std::env::temp_dir().join(format!("cw-records-{tag}-{}", std::process::id()));
    let sub = dir.join("identify");
    std::fs::create_dir_all(&sub).unwrap();
    let base = src.parent().unwrap().join("../rccm_0.82MPa.toml");
    std::fs::copy(base, dir.join("rccm_0.82MPa.toml")).unwrap();
    let text = std::fs::read_to_string(&src).unwrap();
    std::fs::write(sub.join("raw_records.toml"), edit(text)).unwrap();
    let data = match records {
        Some(r) => r.to_string(),
        None => std::fs::read_to_string(src.with_extension("csv")).unwrap(),
    };
    std::fs::write(sub.join("raw_records.csv"), data).unwrap();
    sub.join("raw_records.toml")
}

fn columns(csv: &str) -> Vec<Vec<f64>> {
    let mut cols: Vec<Vec<f64>> = Vec::new();
    for line in csv.lines().filter(|l| !l.starts_with('#')).skip(1) {
        for (c, v) in line.split(',').enumerate() {
            if cols.len() <= c {
                cols.push(Vec::new());
            }
            cols[c].push(v.parse().unwrap());
        }
    }
    cols
}

#[test]
fn the_example_records_are_what_its_synthesize_command_makes() {
    let spec = IdentifySpec::load_unmeasured(&example()).unwrap();
    let made = synthesize_records(&spec, &[(CN.to_string(), TRUE_CN)], 0.001, 11, "").unwrap();
    let committed = std::fs::read_to_string(example().with_extension("csv")).unwrap();
    let (a, b) = (columns(&made), columns(&committed));
    assert_eq!(a.len(), 9, "t and eight records");
    assert_eq!((a.len(), a[0].len()), (b.len(), b[0].len()));
    for (ca, cb) in a.iter().zip(&b) {
        let peak = cb.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in ca.iter().zip(cb) {
            assert!((x - y).abs() <= 1e-12 * peak, "{x} != {y}");
        }
    }
}

#[test]
#[ignore = "slow: full tier"]
fn c_n_is_recovered_from_raw_records_within_five_percent() {
    let spec = IdentifySpec::load(&example()).unwrap();
    // the records' analysis: large drives open the interface (A2/A1 ~ 0.9), the two
    // smallest stay closed (A2 at the floor)
    let a2 = &spec.measured.observed[0];
    assert_eq!(a2.key, "A2_over_A1");
    assert!(a2.values[0] > 0.5 && a2.values[7] < 0.02, "{:?}", a2.values);
    let r = identify(&spec, &|_| {}).unwrap();
    let est = r.estimate_of(CN).unwrap();
    eprintln!("{:?} ({} runs)", r.verdict_lines(), r.forward_runs);
    assert!(r.identified(CN), "{:?}", r.verdict_lines());
    assert!((est / TRUE_CN - 1.0).abs() < 0.05, "C_N = {est:e}");
    let (lo, hi) = r.interval_of(CN).unwrap();
    assert!(lo < TRUE_CN * 1.05 && hi > TRUE_CN * 0.95 && lo < est && est < hi);
}

#[test]
fn ignoring_the_transducer_biases_the_estimate() {
    // the same records, the forward signals not passed through the transducer: model and
    // measurement are no longer reduced alike, and the fit says so (a large residual) and
    // lands far from the truth
    let path = variant(
        "nobp",
        |t| {
            t.lines()
                .filter(|l| !l.starts_with("band_pass"))
                .collect::<Vec<_>>()
                .join("\n")
        },
        None,
    );
    let spec = IdentifySpec::load(&path).unwrap();
    let model = Model::new(&spec);
    let z = [TRUE_CN.log10()];
    let r_true = model.residuals(&z).unwrap();
    let norm = r_true.iter().map(|r| r * r).sum::<f64>().sqrt();
    let spec_bp = IdentifySpec::load(&example()).unwrap();
    let r_bp = Model::new(&spec_bp).residuals(&z).unwrap();
    let norm_bp = r_bp.iter().map(|r| r * r).sum::<f64>().sqrt();
    assert!(norm > 20.0 * norm_bp, "{norm} vs {norm_bp}");
    std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
}

#[test]
fn a_noise_free_record_of_the_forward_model_gives_zero_residual() {
    // records made by the forward model itself at C_N, without noise: the measured and the
    // forward values come from the same signal through the same analysis
    let spec = IdentifySpec::load_unmeasured(&example()).unwrap();
    let made = synthesize_records(&spec, &[(CN.to_string(), 3e12)], 0.0, 1, "").unwrap();
    for method in ["band_peak", "plateau_fit"] {
        let path = variant(
            &format!("exact-{method}"),
            |t| t.replace("method = \"band_peak\"", &format!("method = \"{method}\"")),
            Some(&made),
        );
        let spec = IdentifySpec::load(&path).unwrap();
        let r = Model::new(&spec).residuals(&[3e12f64.log10()]).unwrap();
        assert!(r.iter().all(|r| r.abs() < 1e-9), "{method}: {r:?}");
        // and a different C_N does not fit
        let far = Model::new(&spec).residuals(&[3e13f64.log10()]).unwrap();
        assert!(far.iter().any(|r| r.abs() > 1.0), "{method}: {far:?}");
        std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
    }
}

#[test]
fn bad_records_tables_are_one_line_errors() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "waveform = \"reflected_velocity\"",
            "waveform = \"echo\"",
            "records.waveform",
        ),
        (
            "method = \"band_peak\"",
            "method = \"peak\"",
            "records.method",
        ),
        (
            "gate = [1.2e-5, 3.2e-5, 2e-6]",
            "gate = [3e-5, 1e-5]",
            "records.gate",
        ),
        (
            "observed = [\"A2_over_A1\"]",
            "observed = [\"max_gap\"]",
            "observed",
        ),
        (
            "condition = \"incident.xi\"",
            "condition = \"xi\"",
            "records.condition",
        ),
        (
            "values = [0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0, 1.3]",
            "values = [0.1, 0.2]",
            "values",
        ),
        (
            "observed = [\"A2_over_A1\"]",
            "observed = [\"A2_over_A1\"]\ndata = \"raw_records.csv\"",
            "records",
        ),
        ("centre = 2e6", "centre = -2e6", "records.band_pass"),
    ];
    for (i, (from, to, field)) in cases.iter().enumerate() {
        let path = variant(&format!("bad{i}"), |t| t.replace(from, to), None);
        let err = IdentifySpec::load(&path).unwrap_err().to_string();
        assert!(err.contains(field), "{to}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
    }
}

#[test]
fn the_2d_receivers_are_waveforms_with_twins() {
    // a small clapping crack (tests/all/solid_2d.rs): each receiver component is a waveform
    // equal to its row of the run's arrays, and pulse inversion's twin is the run with the
    // source negated (at a closed, linear crack it is exactly the opposite signal)
    let text = r#"
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
static_pressure = 50e6
compression = { law = "linear", stiffness = 1e15 }

[[source]]
x0 = 0.6e-3
x1 = 1.4e-3
signal = { frequency = 10e6, cycles = 2, amplitude = 1e6, window = "hann" }

[[receiver]]
name = "under"
at = [1e-3, 1e-3]
"#;
    let m = model::from_toml_str(text, "small.toml")
        .unwrap()
        .base()
        .unwrap();
    let o = m.run(&RunControl::default()).unwrap();
    assert_eq!(o.waveform_names(), ["under_vx", "under_vz"]);
    let w = o.waveform("under_vz").unwrap();
    let rec = o.record();
    let Some(Value::Rows(rows)) = rec.get("receivers") else {
        panic!("receivers")
    };
    assert_eq!(w.samples, rows[1]);
    assert!(o.waveform("under_vy").is_none());
    let twin = m
        .twin(contactwave::analysis::AnalysisMethod::PulseInversion)
        .unwrap()
        .unwrap();
    let t = twin.run(&RunControl::default()).unwrap();
    let tw = t.waveform("under_vz").unwrap();
    let peak = w.samples.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!(peak > 0.0);
    for (a, b) in w.samples.iter().zip(&tw.samples) {
        assert!((a + b).abs() <= 1e-9 * peak, "{a} {b}");
    }
    // the half-space probe's names are probe.csv's columns
    let hs = model::from_toml_str(
        "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.1e6\n\
         [incident]\nfrequency = 1e6\ncycles = 5\nxi = 0.5\n",
        "hs.toml",
    )
    .unwrap()
    .base()
    .unwrap()
    .run(&RunControl::default())
    .unwrap();
    assert_eq!(
        hs.waveform_names(),
        [
            "incident_stress",
            "reflected_stress",
            "incident_velocity",
            "reflected_velocity",
            "displacement"
        ]
    );
    let Some(Value::Array(v)) = hs.record().get("probe_reflected_velocity").cloned() else {
        panic!("probe")
    };
    assert_eq!(hs.waveform("reflected_velocity").unwrap().samples, v);
}

/// Issue 56 item 1: an identification from raw records refuses a clipped record (its
/// harmonics are the clipping's), naming it, the samples and the level, unless
/// `allow_clipped = true`; the example's own records are not taken for clipped ones.
#[test]
fn clipped_records_are_refused_unless_allowed() {
    let committed = std::fs::read_to_string(example().with_extension("csv")).unwrap();
    let cols = columns(&committed);
    // record_8 (the largest drive) clipped at 60 % of its peak, as an overranged scope
    let peak = cols[8].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let level = 0.6 * peak;
    let mut text =
        String::from("t,record_1,record_2,record_3,record_4,record_5,record_6,record_7,record_8\n");
    for k in 0..cols[0].len() {
        let row: Vec<String> = cols
            .iter()
            .enumerate()
            .map(|(c, col)| {
                let v = col[k];
                let v = if c == 8 { v.clamp(-level, level) } else { v };
                format!("{v:e}")
            })
            .collect();
        text.push_str(&row.join(","));
        text.push('\n');
    }
    let path = variant("clipped", |t| t, Some(&text));
    let err = IdentifySpec::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("record_8") && err.contains("clipped") && err.contains("allow_clipped"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
    let path = variant(
        "clipped-allowed",
        |t| {
            t.replace(
                "method = \"band_peak\"",
                "method = \"band_peak\"\nallow_clipped = true",
            )
        },
        Some(&text),
    );
    IdentifySpec::load(&path).unwrap();
    std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
    // the example's records, unclipped
    let path = variant("unclipped", |t| t, None);
    let spec = IdentifySpec::load(&path).unwrap();
    std::fs::remove_dir_all(path.parent().unwrap().parent().unwrap()).ok();
    drop(spec);
}

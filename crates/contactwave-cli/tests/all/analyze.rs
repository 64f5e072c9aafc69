//! `contactwave analyze`: measured records through the simulator's analysis, from the
//! command line: its files with provenance, and one-line errors with exit code 2 that
//! write nothing.

use crate::common::tmpdir;
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../contactwave/tests/data/measured")
        .join(name)
}

/// `contactwave analyze FILE EXTRA... --out OUT`: its exit code and stderr.
fn analyze(file: &Path, extra: &[&str], out: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_contactwave"))
        .arg("analyze")
        .arg(file)
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn analyze_writes_its_files_with_provenance() {
    let out = tmpdir("analyze");
    let o = Command::new(env!("CARGO_BIN_EXE_contactwave"))
        .args(["analyze"])
        .arg(fixture("records_v73.mat"))
        .args([
            "--amplitudes",
            "amplitude",
            "--f0",
            "2e6",
            "--gate",
            "1e-6,9e-6",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "summary.json",
        "records.csv",
        "spectrum.csv",
        "record.svg",
        "spectrum.svg",
        "fit.svg",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["records"].as_array().unwrap().len(), 3);
    assert_eq!(s["records"][2]["amplitude"], 3.0);
    assert!(s["records"][0]["A2_over_A1"].as_f64().unwrap() > 0.0);
    assert!(s["fit"]["slope"].as_f64().is_some());
    let p = &s["provenance"];
    assert_eq!(p["contactwave_version"], env!("CARGO_PKG_VERSION"));
    let bytes = std::fs::read(fixture("records_v73.mat")).unwrap();
    let sha = contactwave::output::provenance::sha256_hex(&bytes);
    assert_eq!(p["data_files"][0]["sha256"], sha.as_str());
    assert!(p["command_line"].as_str().unwrap().contains("analyze"));
    let csv = std::fs::read_to_string(out.join("records.csv")).unwrap();
    assert!(csv.starts_with("name,amplitude,A1,"));
    assert_eq!(csv.lines().count(), 4);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn bad_records_are_one_line_errors_with_exit_code_2_and_nothing_written() {
    for (file, extra, word) in [
        ("complex.npz", vec![], "complex"),
        ("gap.csv", vec![], "uniform time base"),
        ("records.csv", vec!["--gate", "5,1"], "--gate"),
        (
            "records.csv",
            vec!["--method", "pulse-inversion"],
            "--inverse",
        ),
        // a negative start is a value, not an option (a record may start before 0); this
        // one lies before the record
        (
            "records.csv",
            vec!["--gate", "-4e-6,5e-6"],
            "inside the record",
        ),
        // a sampling rate beside a time column would make the time a record
        ("records.csv", vec!["--sample-rate", "50e6"], "sample_rate"),
        // ... and beside a time column named with --time, too
        (
            "records.csv",
            vec!["--sample-rate", "50e6", "--time", "t"],
            "sample_rate",
        ),
        // a gate shorter than 3 periods of f0
        (
            "records.csv",
            vec!["--f0", "2e6", "--gate", "2e-6,2.5e-6"],
            "inside the gate",
        ),
        // negative numbers reach the range checks (one line, not clap's report)
        ("records.csv", vec!["--f0", "-2e6"], "--f0"),
        ("records.csv", vec!["--colour", "red"], "--colour"),
    ] {
        let out = tmpdir("analyze_bad");
        let (code, err) = analyze(&fixture(file), &extra, &out);
        assert_eq!(code, Some(2), "{file}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(word), "{file}: {err}");
        assert!(!out.join("summary.json").exists());
    }
}

/// An output folder where a result would replace an input (`records.csv` analysed into its
/// own folder) is refused, and the input is left as it was.
#[test]
fn an_output_that_would_replace_an_input_is_refused() {
    let d = tmpdir("analyze_overwrite");
    std::fs::create_dir_all(&d).unwrap();
    let input = d.join("records.csv");
    std::fs::copy(fixture("records.csv"), &input).unwrap();
    let before = std::fs::read(&input).unwrap();
    let (code, err) = analyze(&input, &[], &d);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("--out") && err.contains("replace the input"),
        "{err}"
    );
    assert_eq!(std::fs::read(&input).unwrap(), before);
    assert!(!d.join("summary.json").exists());
    std::fs::remove_dir_all(&d).ok();
}

/// Column headers: a header of numbers (a file without one), an empty name and a name
/// given twice are one-line errors naming the column.
#[test]
fn csv_headers_name_every_column_once() {
    let d = tmpdir("analyze_headers");
    std::fs::create_dir_all(&d).unwrap();
    let rows: String = (0..400)
        .map(|k| {
            let t = k as f64 * 1e-8;
            format!("{t:e},{}\n", (2e6 * std::f64::consts::TAU * t).sin())
        })
        .collect();
    for (name, header, word) in [
        ("numbers.csv", "", "header line"),
        ("empty.csv", "t,\n", "column 2"),
        ("twice.csv", "t,t\n", "named once"),
    ] {
        let file = d.join(name);
        std::fs::write(&file, format!("{header}{rows}")).unwrap();
        let out = d.join(format!("out_{name}"));
        let (code, err) = analyze(&file, &["--sample-rate", "1e8"], &out);
        assert_eq!(code, Some(2), "{name}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{name}: {err}");
        assert!(err.contains(name) && err.contains(word), "{name}: {err}");
        assert!(!out.exists(), "{name}");
    }
    std::fs::remove_dir_all(&d).ok();
}

/// A time column written in microseconds reads as a 1 Hz fundamental: the analysis runs and
/// warns that the time stamps are read in s.
#[test]
fn a_time_column_in_microseconds_is_warned_about() {
    let d = tmpdir("analyze_units");
    std::fs::create_dir_all(&d).unwrap();
    let rows: String = (0..2000)
        .map(|k| {
            let t_us = k as f64 * 0.01;
            format!("{t_us},{}\n", (std::f64::consts::TAU * t_us).sin())
        })
        .collect();
    let file = d.join("us.csv");
    std::fs::write(&file, format!("t,v\n{rows}")).unwrap();
    let (code, err) = analyze(&file, &[], &d.join("out"));
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("below the audio range") && err.contains("in s"),
        "{err}"
    );
    std::fs::remove_dir_all(&d).ok();
}

//! `contactwave analyze`: measured records through the simulator's analysis, from the
//! command line: its files with provenance, and one-line errors with exit code 2 that
//! write nothing.

mod common;
use common::tmpdir;
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../contactwave/tests/data/measured")
        .join(name)
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
    ] {
        let out = tmpdir("analyze_bad");
        let o = Command::new(env!("CARGO_BIN_EXE_contactwave"))
            .arg("analyze")
            .arg(fixture(file))
            .args(&extra)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{file}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(word), "{file}: {err}");
        assert!(!out.join("summary.json").exists());
    }
}

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

/// A tone burst at 1 MHz sampled at 50 MHz: `cycles` Hann-windowed cycles from `start`
/// (s) in a 40 us record, with a second harmonic `r2` times the fundamental, a seeded
/// noise of `noise` (fraction of the peak) and clipped at `clip` times the peak; as a CSV
/// of `t,echo` in `dir`.
fn burst_csv(dir: &Path, name: &str, start: f64, r2: f64, noise: f64, clip: f64) -> PathBuf {
    use std::f64::consts::PI;
    let (f0, dt, n, cycles) = (1e6, 2e-8, 2000, 10.0);
    let len = cycles / f0;
    let mut state = 12345u64;
    let mut rand = || {
        // xorshift: uniform in [-1, 1)
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let mut text = String::from("t,echo\n");
    for k in 0..n {
        let t = k as f64 * dt;
        let u = t - start;
        let w = if (0.0..len).contains(&u) {
            (PI * u / len).sin().powi(2)
        } else {
            0.0
        };
        let s = w * ((2.0 * PI * f0 * u).sin() - r2 * w * (4.0 * PI * f0 * u).cos());
        let v = (s + noise * rand()).clamp(-clip, clip);
        text.push_str(&format!("{t:e},{v:e}\n"));
    }
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn stdout_of(file: &Path, extra: &[&str], out: &Path) -> (bool, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_contactwave"))
        .arg("analyze")
        .arg(file)
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Issue 56 item 1: a burst clipped at 60 % of its peak (A3/A1 0.18 from the clipping)
/// is flagged: the samples and the level, `harmonics_reliable = 0` in summary.json, a
/// warning and the mark in the pictures; the same burst unclipped is not flagged; a full
/// scale given flags the samples at it.
#[test]
fn a_clipped_record_is_flagged() {
    let d = tmpdir("analyze-clipped");
    let clipped = burst_csv(&d, "clipped.csv", 5e-6, 0.0, 0.0, 0.6);
    let out = d.join("out");
    let (ok, stdout, stderr) = stdout_of(&clipped, &[], &out);
    assert!(ok, "{stderr}");
    let s = summary(&out);
    let r = &s["records"][0];
    assert!(r["A3_over_A1"].as_f64().unwrap() > 0.1, "{r}");
    let n = r["clipped_samples"].as_u64().unwrap();
    assert!(n > 50, "{r}");
    assert!((r["clip_high"].as_f64().unwrap() - 0.6).abs() < 1e-9, "{r}");
    assert!((r["clip_low"].as_f64().unwrap() + 0.6).abs() < 1e-9, "{r}");
    assert_eq!(r["harmonics_reliable"], 0.0);
    assert!(
        stderr.contains(&format!("clipped: {n} samples")),
        "{stderr}"
    );
    assert!(stdout.contains("CLIPPED"), "{stdout}");
    let svg = std::fs::read_to_string(out.join("record.svg")).unwrap();
    assert!(svg.contains("CLIPPED"));
    assert!(s["warnings"].to_string().contains("clipped"));
    // unclipped, and unclipped but quantised to 8 bits: not flagged
    let clean = burst_csv(&d, "clean.csv", 5e-6, 0.0, 0.0, 2.0);
    let out2 = d.join("out2");
    let (ok, _, stderr) = stdout_of(&clean, &[], &out2);
    assert!(ok && !stderr.contains("clipped"), "{stderr}");
    assert_eq!(summary(&out2)["records"][0]["clipped_samples"], 0);
    let text = std::fs::read_to_string(&clean).unwrap();
    let mut q = String::from("t,echo\n");
    for line in text.lines().skip(1) {
        let (t, v) = line.split_once(',').unwrap();
        let v: f64 = v.parse().unwrap();
        q.push_str(&format!("{t},{}\n", (v * 127.0).round() / 127.0));
    }
    let quantised = d.join("quantised.csv");
    std::fs::write(&quantised, q).unwrap();
    let out3 = d.join("out3");
    let (ok, _, stderr) = stdout_of(&quantised, &[], &out3);
    assert!(ok && !stderr.contains("clipped"), "{stderr}");
    // a full scale of 0.9 given: the crests above it are at the scope's full scale
    let (ok, _, stderr) = stdout_of(&clean, &["--full-scale", "0.9"], &out2);
    assert!(ok && stderr.contains("clipped"), "{stderr}");
    std::fs::remove_dir_all(&d).ok();
}

/// Issue 56 item 2: without a gate, the noise floor comes from the quiet part before the
/// arrival and every ratio is printed with its floor; a record without one says the noise
/// floor is unknown.
#[test]
fn every_ratio_has_its_floor() {
    let d = tmpdir("analyze-floor");
    let late = burst_csv(&d, "late.csv", 10e-6, 0.02, 1e-3, 10.0);
    let out = d.join("out");
    let (ok, stdout, stderr) = stdout_of(&late, &[], &out);
    assert!(ok, "{stderr}");
    let s = summary(&out);
    let r = &s["records"][0];
    let noise = r["A2_noise_floor"].as_f64().unwrap();
    assert!(noise > 0.0, "{r}");
    let w = r["noise_window"].as_array().unwrap();
    assert!(w[1].as_f64().unwrap() < 10e-6, "{r}");
    let ratio = r["A2_over_A1"].as_f64().unwrap();
    assert!((ratio - 0.02).abs() < 0.005, "{r}");
    assert!(
        stdout.contains("A2/A1 = ") && stdout.contains("(floor "),
        "{stdout}"
    );
    assert!(!stdout.contains("noise unknown"), "{stdout}");
    // the burst from the first sample: no quiet part, no gate
    let early = burst_csv(&d, "early.csv", 0.0, 0.02, 1e-3, 10.0);
    let out2 = d.join("out2");
    let (ok, stdout, stderr) = stdout_of(&early, &[], &out2);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("noise unknown"), "{stdout}");
    assert!(stderr.contains("noise floor is unknown"), "{stderr}");
    assert!(summary(&out2)["records"][0]["noise_window"].is_null());
    std::fs::remove_dir_all(&d).ok();
}

/// Issue 56 item 3: two records fit a line exactly: a slope, no R^2 and no interval.
#[test]
fn two_records_give_no_fit_statistics() {
    let d = tmpdir("analyze-two");
    let a = burst_csv(&d, "a.csv", 10e-6, 0.01, 1e-4, 10.0);
    let b = burst_csv(&d, "b.csv", 10e-6, 0.02, 1e-4, 10.0);
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_contactwave"))
        .arg("analyze")
        .args([&a, &b])
        .args(["--amplitudes", "1,2", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("no fit statistics") && !stdout.contains("R^2 ="),
        "{stdout}"
    );
    let s = summary(&out);
    assert!(
        s["fit"]["r_squared"].is_null() && s["fit"]["slope"].is_number(),
        "{}",
        s["fit"]
    );
    std::fs::remove_dir_all(&d).ok();
}

/// Issue 56 item 11: `--keep-dc` detects f0 on the record without its mean (a DC of 5
/// times the burst today hid the fundamental and the error named `f0`, which the user
/// never gave); `plateau_fit` with a gate whose ramps leave no flat part says so.
#[test]
fn keep_dc_detects_f0_and_a_plateau_needs_a_flat_part() {
    let d = tmpdir("analyze-keep-dc");
    let clean = burst_csv(&d, "b.csv", 10e-6, 0.02, 1e-4, 10.0);
    let text = std::fs::read_to_string(&clean).unwrap();
    let mut offset = String::from("t,echo\n");
    for line in text.lines().skip(1) {
        let (t, v) = line.split_once(',').unwrap();
        let v: f64 = v.parse().unwrap();
        offset.push_str(&format!("{t},{:e}\n", v + 5.0));
    }
    let dc = d.join("dc.csv");
    std::fs::write(&dc, offset).unwrap();
    let out = d.join("out");
    let (ok, _, stderr) = stdout_of(&dc, &["--keep-dc"], &out);
    assert!(ok, "{stderr}");
    let f0 = summary(&out)["f0"].as_f64().unwrap();
    assert!((f0 - 1e6).abs() < 1e3, "{f0}");
    let (code, stderr) = analyze(
        &clean,
        &["--method", "plateau-fit", "--gate", "10e-6,20e-6,5e-6"],
        &d.join("out2"),
    );
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("flat part") && stderr.contains("`gate`"),
        "{stderr}"
    );
    assert!(!d.join("out2").exists());
    std::fs::remove_dir_all(&d).ok();
}

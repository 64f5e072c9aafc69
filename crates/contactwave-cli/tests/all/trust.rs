//! What misleads a researcher (issue 56, items 8 and 9): slips that cannot be meant stop
//! the run (a source whose wave does not fit the plate, a plate in mm read as m, a memory
//! budget above the machine's memory), every warning is kept in `summary.json`, and the
//! time a run reports can be trusted (progress lines with the time left in a log, for runs,
//! sweeps and `reproduce`; a wall time that counts the files written).

use crate::common::{examples, stderr, tmpdir};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Instant;

/// The binary with a fixed memory budget (the refusals do not depend on the machine) and
/// the default progress threshold, whatever the environment of the tests.
fn bin() -> Command {
    let mut c = crate::common::bin();
    c.env("CONTACTWAVE_MEMORY_BUDGET", "2G")
        .env_remove("CONTACTWAVE_PROGRESS_AFTER");
    c
}

/// `examples/solid_2d/plate_crack_quick.toml` (a 40 x 10 mm plate, a 1 MHz transducer, a
/// fraction of a second) with each `(from, to)` replaced, written into `dir` as `name`.
fn plate(dir: &Path, name: &str, edits: &[(&str, &str)]) -> std::path::PathBuf {
    let mut text =
        std::fs::read_to_string(examples().join("solid_2d/plate_crack_quick.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `run FILE --out DIR` and any further arguments.
fn run(file: &Path, out: &Path, more: &[&str]) -> Output {
    bin()
        .arg("run")
        .arg(file)
        .arg("--out")
        .arg(out)
        .args(more)
        .output()
        .unwrap()
}

/// The lines of a command's stdout and stderr that start with `warning: `, without it (the
/// manifest's note on foreign files left out: it is about the folder, not the run).
fn warning_lines(o: &Output) -> Vec<String> {
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut w: Vec<String> = out
        .lines()
        .chain(stderr(o).lines().collect::<Vec<_>>())
        .filter_map(|l| l.strip_prefix("warning: "))
        .filter(|l| !l.contains("also holds files contactwave did not write"))
        .map(str::to_string)
        .collect();
    w.sort();
    w
}

/// The `warnings` of `DIR/summary.json`, sorted (none: empty).
fn summary_warnings(out: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut w: Vec<String> = v["warnings"]
        .as_array()
        .map(|a| a.iter().map(|x| x.as_str().unwrap().to_string()).collect())
        .unwrap_or_default();
    w.sort();
    w
}

/// A refusal: exit 2, one `error:` line holding every needle, no output folder.
fn assert_refused(o: &Output, out: &Path, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.starts_with("error: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in {err}");
    }
    assert!(!out.exists(), "an output folder was written: {err}");
}

/// Issue 56, 8a and 8b: a 5 Hz source in a 60 mm plate (no wave fits: every A2/A1 null)
/// and a 60 m plate whose positions are in mm (a run of minutes) are refused, naming the
/// key and its value; `--yes` runs the first as it is, its warnings in summary.json.
#[test]
fn slips_that_cannot_be_meant_stop_the_run_unless_yes() {
    let d = tmpdir("slips");
    let five = plate(
        &d,
        "five_hz.toml",
        &[
            ("width = 40e-3 ", "width = 60e-3 "),
            ("frequency = 1e6", "frequency = 5"),
        ],
    );
    let out = d.join("out");
    let o = run(&five, &out, &[]);
    assert_refused(
        &o,
        &out,
        &[
            "five_hz.toml: field `source.0.signal.frequency` = 5 Hz",
            "no wave",
            "--yes",
        ],
    );
    // every length along the plate in mm, read as m
    let metres = plate(
        &d,
        "sixty_m.toml",
        &[
            ("width = 40e-3 ", "width = 60 "),
            ("start = [19e-3, 5e-3]", "start = [29, 5e-3]"),
            ("end = [21e-3, 5e-3]", "end = [31, 5e-3]"),
            ("x0 = 8e-3 ", "x0 = 18 "),
            ("x1 = 12e-3", "x1 = 22"),
            ("at = [30e-3, 0.0]", "at = [40, 0.0]"),
            ("at = [20e-3, 10e-3]", "at = [30, 10e-3]"),
        ],
    );
    let t0 = Instant::now();
    let o = run(&metres, &out, &[]);
    assert_refused(
        &o,
        &out,
        &["sixty_m.toml: field `model.width` = 60 m", "mm", "--yes"],
    );
    assert!(t0.elapsed().as_secs_f64() < 5.0, "{:?}", t0.elapsed());
    // a sweep on such a base is refused alike
    let sweep = d.join("sweep.toml");
    std::fs::write(
        &sweep,
        "base = \"five_hz.toml\"\n[[axis]]\nparameter = \"source.0.signal.amplitude\"\nvalues = [1e6, 2e6]\n",
    )
    .unwrap();
    let o = bin()
        .arg("sweep")
        .arg(&sweep)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_refused(&o, &out, &["`source.0.signal.frequency` = 5 Hz", "--yes"]);
    // --yes: the run as it is, the slip a warning on stderr and in summary.json
    let o = run(&five, &out, &["--yes"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let w = warning_lines(&o);
    assert!(
        w.iter()
            .any(|w| w.contains("five_hz.toml: source.0.signal.frequency = 5 Hz")),
        "{w:?}"
    );
    assert_eq!(summary_warnings(&out), w);
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 56, 8c: a budget raised above the machine's memory lets no run through that the
/// machine cannot hold: a mesh of petabytes is refused before any allocation (under a
/// 4 GB address-space limit an allocation would abort), naming the key, the budget as set
/// and the machine's memory (Linux: the machine's memory is read from /proc/meminfo).
#[cfg(target_os = "linux")]
#[test]
fn a_budget_above_the_machine_is_refused_naming_it() {
    let d = tmpdir("machine");
    let fine = plate(
        &d,
        "fine.toml",
        &[(
            "duration = 20e-6 ",
            "duration = 20e-6\nelement_size = 2e-8 ",
        )],
    );
    let out = d.join("out");
    let line = format!(
        "ulimit -v 4000000; exec '{}' run '{}' --out '{}'",
        env!("CARGO_BIN_EXE_contactwave"),
        fine.display(),
        out.display()
    );
    let o = Command::new("sh")
        .arg("-c")
        .arg(line)
        .env("CONTACTWAVE_MEMORY_BUDGET", "1e18")
        .output()
        .unwrap();
    assert_refused(
        &o,
        &out,
        &[
            "fine.toml: field `model.element_size` = 2e-8",
            "above this machine's memory of",
            "CONTACTWAVE_MEMORY_BUDGET=1e18",
        ],
    );
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 56, 8d: every warning a run prints (the scenario's likely slips on stderr, the
/// results' floor warnings in the report) is in its summary.json, for every kind: a
/// half-space, an oblique half-space, a bar stack and a 2D run; a run without one has no
/// `warnings` key.
#[test]
fn every_warning_of_a_run_is_in_its_summary() {
    let d = tmpdir("warnings");
    let half_space = d.join("p0.toml");
    std::fs::write(
        &half_space,
        "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082\n[incident]\nfrequency = 1e6\ncycles = 10\nxi = 0.5\n",
    )
    .unwrap();
    let stack = d.join("stack.toml");
    let text = std::fs::read_to_string(examples().join("bar_stack_incident.toml")).unwrap();
    let light = text.replacen(
        "material = \"pmma\"",
        "material = \"pmma\"\ndensity = 1.19",
        1,
    );
    std::fs::write(&stack, light).unwrap();
    let cut = plate(&d, "cut.toml", &[("duration = 20e-6 ", "duration = 2e-6 ")]);
    for (i, (file, at_least)) in [
        (half_space, 1),
        (examples().join("oblique/p_45deg.toml"), 1),
        (stack, 1),
        (cut, 1),
        (examples().join("unilateral.toml"), 0),
    ]
    .into_iter()
    .enumerate()
    {
        let out = d.join(format!("out{i}"));
        let o = run(&file, &out, &[]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}: {}",
            file.display(),
            stderr(&o)
        );
        let printed = warning_lines(&o);
        assert!(printed.len() >= at_least, "{}: {printed:?}", file.display());
        assert_eq!(summary_warnings(&out), printed, "{}", file.display());
        if printed.is_empty() {
            let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
            assert!(!text.contains("\"warnings\""), "{text}");
        }
    }
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 56, 9g: in a log (stderr not a terminal) a run's progress lines say how long it
/// has run and how long it has left (here from the first tenth on,
/// `CONTACTWAVE_PROGRESS_AFTER=0`).
#[test]
fn progress_lines_in_a_log_give_the_time_left() {
    let d = tmpdir("log");
    let out = d.join("out");
    let o = bin()
        .env("CONTACTWAVE_PROGRESS_AFTER", "0")
        .arg("run")
        .arg(examples().join("solid_2d/plate_crack_quick.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("progress: "))
        .collect();
    assert_eq!(lines.len(), 9, "{err}");
    for (k, l) in lines.iter().enumerate() {
        let head = format!("progress: {} % (", 10 * (k + 1));
        assert!(l.starts_with(&head), "{l}");
        assert!(
            l.contains(" of 2095 steps, ") && l.contains(" elapsed, about "),
            "{l}"
        );
        assert!(l.ends_with(" left)"), "{l}");
    }
    // by default a run of a second says nothing in a log
    let o = run(
        &examples().join("solid_2d/plate_crack_quick.toml"),
        &out,
        &[],
    );
    assert!(!stderr(&o).contains("progress: "), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 56, 9h: a sweep and `reproduce` report their progress in a log too (a sweep of
/// 47 points here; `reproduce` is stopped at its first line).
#[test]
fn sweeps_and_reproduce_report_progress_in_a_log() {
    let d = tmpdir("sweep_log");
    let o = bin()
        .env("CONTACTWAVE_PROGRESS_AFTER", "0")
        .arg("sweep")
        .arg(examples().join("unilateral_xi_sweep.toml"))
        .arg("--out")
        .arg(d.join("sweep"))
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("progress: "))
        .collect();
    assert!(lines.len() >= 5, "{err}");
    assert!(
        lines
            .iter()
            .all(|l| l.contains(" of 47 points, ") && l.ends_with(" left)")),
        "{err}"
    );
    // reproduce: its first progress line names the study, then it is stopped
    let mut child = bin()
        .env("CONTACTWAVE_PROGRESS_AFTER", "0")
        .args(["reproduce", "chapter4", "--out"])
        .arg(d.join("reproduce"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let first = BufReader::new(child.stderr.take().unwrap())
        .lines()
        .map_while(Result::ok)
        .find(|l| l.starts_with("progress: "));
    let _ = child.kill();
    let _ = child.wait();
    let first = first.unwrap_or_default();
    assert!(
        first.starts_with("progress: chapter 4: ")
            && first.contains(" runs, ")
            && first.ends_with(" left)"),
        "{first}"
    );
    let _ = std::fs::remove_dir_all(d);
}

/// Seconds of a duration as the CLI prints it (`3.1 ms`, `1.4 s`, `2 minutes`).
fn seconds(text: &str) -> f64 {
    let (v, unit) = text.trim().split_once(' ').unwrap();
    let v: f64 = v.parse().unwrap();
    v * match unit {
        "ms" => 1e-3,
        "s" => 1.0,
        "minutes" => 60.0,
        "hours" => 3600.0,
        other => panic!("{other}"),
    }
}

/// Issue 56, 9j: the wall time a run prints is the whole command's, the files rendered
/// and written included (here most of it: every time sample into CSV and HDF5), and says
/// how it splits.
#[test]
fn the_wall_time_counts_the_files_written() {
    let d = tmpdir("wall");
    let out = d.join("out");
    let t0 = Instant::now();
    let o = run(
        &examples().join("unilateral.toml"),
        &out,
        &["--record", "full", "--hdf5"],
    );
    let measured = t0.elapsed().as_secs_f64();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix("wall time"))
        .unwrap_or_else(|| panic!("{stdout}"));
    // `wall time  33 ms (simulation 2.5 ms, files 30 ms)`
    let (total, parts) = line.split_once(" (simulation ").unwrap();
    let (simulation, files) = parts.trim_end_matches(')').split_once(", files ").unwrap();
    let (total, simulation, files) = (seconds(total), seconds(simulation), seconds(files));
    assert!(total >= 0.5 * measured, "{line}: {measured} s measured");
    assert!(files > simulation, "{line}");
    assert!(
        (simulation + files - total).abs() <= 0.1 * total + 1e-3,
        "{line}"
    );
    let _ = std::fs::remove_dir_all(d);
}

//! `contactwave convergence` on 2D scenarios (issue 56, item 5): the levels, the observed
//! order and the default's error printed, the files written, the options checked, Ctrl-C.

use crate::common::{bin, examples, stderr, tmpdir};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A plate 6 x 2 mm with a 1 mm crack, a 5 MHz burst, a receiver under the crack (on a
/// node at every level) and one on the top surface: under a second per level.
const TINY: &str = r#"
[model]
kind = "solid_2d"
width = 6e-3
duration = 1.5e-6
harmonic = 2
[[layer]]
thickness = 2e-3
material = "aluminium"
[[crack]]
start = [2.5e-3, 1e-3]
length = 1e-3
static_pressure = 1e6
[[source]]
x0 = 1e-3
x1 = 2e-3
signal = { frequency = 5e6, cycles = 3, amplitude = 10e6, window = "hann" }
[[receiver]]
name = "below"
at = [3e-3, 2e-3]
[[receiver]]
name = "top"
at = [5e-3, 0.0]
"#;

/// The study prints a row per level (element size, nodes, split nodes), each receiver's
/// A2/A1 and A3/A1 with its change, the observed order and the default's error, and writes
/// convergence.csv (a row per level, the finest's change 0), convergence_order.csv and
/// convergence.svg; a rerun into its own folder replaces them.
#[test]
fn convergence_of_a_2d_scenario_prints_and_writes_its_levels() {
    let d = tmpdir("convergence_2d");
    let scenario = d.join("tiny.toml");
    std::fs::write(&scenario, TINY).unwrap();
    let out = d.join("conv");
    for _ in 0..2 {
        let o = bin()
            .args(["convergence", "--levels", "3"])
            .arg(&scenario)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("3 element sizes"), "{text}");
        assert!(
            text.contains("below A2/A1") && text.contains("top A3/A1"),
            "{text}"
        );
        assert!(text.contains("order"), "{text}");
        assert!(text.contains("wrote 3 files"), "{text}");
    }
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4, "{csv}");
    assert!(lines[0].starts_with("level,element_size_m,nodes,steps,dt_s,split_nodes_0,below_A2_over_A1,below_A2_over_A1_change"));
    let col = lines[0]
        .split(',')
        .position(|c| c == "below_A2_over_A1_change")
        .unwrap();
    let change: f64 = lines[3].split(',').nth(col).unwrap().parse().unwrap();
    assert_eq!(change, 0.0);
    let h = |l: &str| -> f64 { l.split(',').nth(1).unwrap().parse().unwrap() };
    assert!(h(lines[1]) > h(lines[2]) && h(lines[2]) > h(lines[3]));
    let order = std::fs::read_to_string(out.join("convergence_order.csv")).unwrap();
    assert_eq!(order.lines().count(), 5, "{order}");
    assert!(out.join("convergence.svg").is_file());
    let _ = std::fs::remove_dir_all(d);
}

/// Options of the other kind, and a bad level count, are refused before any run.
#[test]
fn convergence_of_a_2d_scenario_checks_its_options() {
    let d = tmpdir("convergence_2d_options");
    let scenario = d.join("tiny.toml");
    std::fs::write(&scenario, TINY).unwrap();
    for (args, field) in [
        (vec!["--levels", "2"], "--levels"),
        (vec!["--ratio", "0.5"], "--ratio"),
        (vec!["--xi", "0.5"], "--xi"),
        (vec!["--method", "exact"], "--method"),
        (vec!["--harmonic", "1"], "--harmonic"),
    ] {
        let o = bin()
            .arg("convergence")
            .args(&args)
            .arg(&scenario)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("field `{field}`")),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    // and the 2D options on a half-space scenario
    let o = bin()
        .args(["convergence", "--levels", "4"])
        .arg(examples().join("unilateral.toml"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("only for 2D"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(d);
}

/// Ctrl-C stops a 2D study at once (the runs' time loops check it): exit 130, no output
/// folder.
#[test]
fn ctrl_c_stops_a_2d_convergence_study() {
    let d = tmpdir("convergence_2d_int");
    let out = d.join("out");
    let child = bin()
        .args(["convergence", "--levels", "7"])
        .arg(examples().join("solid_2d/plate_crack_quick.toml"))
        .arg("--out")
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let t0 = Instant::now();
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    let took = t0.elapsed();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(took < Duration::from_secs(2), "{took:?}");
    assert!(!out.exists(), "output written");
    let _ = std::fs::remove_dir_all(d);
}

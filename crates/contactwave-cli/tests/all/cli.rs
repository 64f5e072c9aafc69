//! End-to-end tests of the `contactwave` binary: outputs of `run`, one-line errors with
//! exit code 2 and no output folder on bad input, resumable sweeps.

use crate::common::{bin, cli, examples, stderr, tmpdir};
use std::path::{Path, PathBuf};

const BASE: &str = r#"[medium]
material = "pmma"

[interface]
static_pressure = 0.1e6

[incident]
frequency = 1e6
cycles = 5
xi = 0.35
"#;

#[test]
fn run_writes_summary_and_timeseries() {
    let d = tmpdir("run");
    // a fast copy of the chapter-3 example (5 cycles)
    let text = std::fs::read_to_string(examples().join("rccm_1.6MPa.toml"))
        .unwrap()
        .replace("cycles = 15", "cycles = 5");
    let scenario = d.join("rccm.toml");
    std::fs::write(&scenario, text).unwrap();
    let out = d.join("out");
    let o = cli("run", &scenario, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<String> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(str::to_string)
        .collect();
    assert!(lines.iter().any(|l| l.starts_with("wall time")));
    assert_headline_units(&scenario, &lines);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    for key in [
        "xi",
        "A1_over_Ainc",
        "A2_over_Ainc",
        "A3_over_Ainc",
        "A2_over_A1",
        "beta_star",
        "beta_end",
        "max_gap",
        "contact_loss_fraction",
        "energy_closure_error",
    ] {
        assert!(summary[key].is_number(), "summary.json lacks {key}");
    }
    let ts = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    let mut lines = ts.lines();
    assert_eq!(
        lines.next(),
        Some("t,gap,contact_stress,beta,incident_stress,reflected_stress,transmitted_stress")
    );
    let first: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(first.len(), 7);
    for f in [
        "probe.csv",
        "spectrum.csv",
        "time_histories.svg",
        "waves.svg",
        "spectrum.svg",
        "stress_gap.svg",
    ] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("beta_end"), "{stdout}");
    // law curve
    let law = d.join("law");
    let o = cli("law", &scenario, &law);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(law.join("law_curve.csv")).unwrap();
    assert!(csv.starts_with("gap,stress\n"));
    assert!(law.join("law_curve.svg").is_file());
    let _ = std::fs::remove_dir_all(d);
}

/// `law` on a 2D scenario draws each crack's law at its static state: the SH example's
/// Coulomb crack (p0 = 1 MPa, mu = 0.3) slides at mu p0 = 0.3 MPa; `convergence` refuses
/// a half-space option on it by name.
#[test]
fn law_draws_each_crack_of_a_2d_scenario() {
    let d = tmpdir("law_2d");
    let scenario = examples().join("solid_2d/sh_friction.toml");
    let out = d.join("law");
    let o = cli("law", &scenario, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("law_tangential_0.csv")).unwrap();
    let tau_max = csv
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').nth(1)?.parse::<f64>().ok())
        .fold(0.0f64, f64::max);
    assert!((tau_max - 0.3e6).abs() < 1e-6 * 0.3e6, "{tau_max}");
    assert!(out.join("law_curve_0.csv").is_file());
    // (the 2D study refines the element size: a half-space option is refused by name)
    let o = bin()
        .args(["convergence", "--spp", "100,200,400"])
        .arg(&scenario)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("field `--spp`") && stderr(&o).contains("only for half-space"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(d);
}

/// The quantities of a run headline (`contactwave run`) that carry a physical unit, and
/// the unit that follows their number (friction dissipation: J over a bar stack's area,
/// J/m^2 on a half-space; the wall time in the unit that reads best: one of `|`).
const HEADLINE_UNITS: [(&str, &str); 7] = [
    ("static pressure", "Pa"),
    ("first mode", "Hz"),
    ("second harmonic", "Hz"),
    ("guide mode", "Hz"),
    ("friction dissipation", "J"),
    ("min contact pressure", "Pa"),
    ("wall time", "ms|s|minutes|hours|days"),
];

/// Issue 24: every number of a run headline with a physical unit is printed with it.
fn assert_headline_units(file: &Path, lines: &[String]) {
    for line in lines {
        for (label, unit) in HEADLINE_UNITS {
            if !line.starts_with(label) {
                continue;
            }
            let words: Vec<&str> = line[label.len()..].split_whitespace().collect();
            let number = words.iter().position(|w| w.parse::<f64>().is_ok());
            let follows = number.and_then(|k| words.get(k + 1));
            assert!(
                follows.is_some_and(|w| unit.split('|').any(|u| w.split('/').next() == Some(u))),
                "{}: `{line}` has no unit {unit}",
                file.display()
            );
        }
    }
}

#[test]
fn every_example_loads_and_runs() {
    use contactwave::model::Outcome;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let p = entry.unwrap().path();
        if p.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let table: toml::Table = std::fs::read_to_string(&p).unwrap().parse().unwrap();
        if contactwave::scenario::bar_stack::BarStackScenario::is_bar_stack(&table) {
            let s =
                contactwave::scenario::bar_stack::BarStackScenario::from_table(table, &p).unwrap();
            let r = contactwave::simulate_bar_stack(&s).unwrap();
            assert_headline_units(&p, &r.report());
            let key = if s.incident.is_some() {
                "A1_over_Ainc"
            } else {
                "first_mode_hz"
            };
            assert!(r.summary.get(key).unwrap().is_finite(), "{}", p.display());
            continue;
        }
        let scenarios = if table.contains_key("axis") {
            // every point must validate; bar-stack sweeps are run by tests/all/barstack.rs
            let points = contactwave::study::Sweep::load(&p)
                .unwrap()
                .runnable()
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            points
                .into_iter()
                .filter_map(|m| {
                    m.as_any()
                        .downcast_ref::<contactwave::scenario::Scenario>()
                        .cloned()
                })
                .collect()
        } else {
            vec![contactwave::scenario::Scenario::load(&p).unwrap()]
        };
        for s in &scenarios {
            let summary =
                contactwave::simulate_summary(s).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(summary.get("A1_over_Ainc").unwrap().is_finite());
        }
    }
    // shear waves and friction (examples/shear): every scenario and sweep point runs
    for entry in std::fs::read_dir(examples().join("shear")).unwrap() {
        let p = entry.unwrap().path();
        if p.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let table: toml::Table = std::fs::read_to_string(&p).unwrap().parse().unwrap();
        if contactwave::scenario::bar_stack::BarStackScenario::is_bar_stack(&table) {
            // the shear waves on the FD bar stack (model.md section 9.7)
            let s = contactwave::scenario::bar_stack::BarStackScenario::from_table(table, &p)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let r = contactwave::simulate_bar_stack(&s)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert_headline_units(&p, &r.report());
            let summary = r.summary;
            assert!(summary.get("shear_A1_over_Ainc").unwrap().is_finite());
            assert!(summary.get("energy_closure_error").unwrap() < 1e-5);
            continue;
        }
        let scenarios: Vec<contactwave::scenario::Scenario> = if table.contains_key("axis") {
            contactwave::study::Sweep::load(&p)
                .unwrap()
                .runnable()
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
                .into_iter()
                .filter_map(|m| {
                    m.as_any()
                        .downcast_ref::<contactwave::scenario::Scenario>()
                        .cloned()
                })
                .collect()
        } else {
            vec![contactwave::scenario::Scenario::load(&p).unwrap()]
        };
        assert!(!scenarios.is_empty(), "{}", p.display());
        for s in scenarios.iter().take(3) {
            let summary =
                contactwave::simulate_summary(s).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(summary.get("shear_A1_over_Ainc").unwrap().is_finite());
            assert!(summary.get("energy_closure_error").unwrap() < 1e-6);
        }
    }
}

/// A bar stack driven by an incident wave: the reflected and transmitted waves in
/// `waves.csv`, no FRF (there is no force); an incident wave with a free first end is
/// refused with one line naming the field, exit 2, nothing written.
#[test]
fn bar_stack_incident_run_writes_waves_and_rejects_a_closed_end() {
    let d = tmpdir("incident");
    let out = d.join("out");
    let o = cli("run", examples().join("bar_stack_incident.toml"), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("A2/Ainc (reflected)"), "{stdout}");
    let waves = std::fs::read_to_string(out.join("waves.csv")).unwrap();
    assert!(waves
        .starts_with("t,incident_displacement,reflected_displacement,transmitted_displacement\n"));
    assert!(!out.join("frf.csv").exists());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(summary["A2_over_Ainc"].as_f64().unwrap() > 0.1);
    assert!(
        summary["beta_end"][0].as_f64().unwrap() < 0.5,
        "the bond is peeled off"
    );
    let text = std::fs::read_to_string(examples().join("bar_stack_incident.toml"))
        .unwrap()
        .replace("first_end = \"transparent\"", "first_end = \"free\"");
    let file = d.join("closed.toml");
    std::fs::write(&file, text).unwrap();
    let bad = d.join("bad");
    let o = cli("run", &file, &bad);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("closed.toml") && err.contains("model.first_end"),
        "{err}"
    );
    assert!(!bad.exists());
    let _ = std::fs::remove_dir_all(d);
}

/// Replace `from` by `to` in the base scenario (asserting that `from` occurs).
fn edit(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from}");
    BASE.replacen(from, to, 1)
}

#[test]
fn bad_inputs_fail_with_one_line_and_no_output() {
    let with_traction = |t: &str| {
        edit(
            "static_pressure = 0.1e6",
            &format!("static_pressure = 0.1e6\n{t}"),
        )
    };
    let cases: Vec<(&str, String, &str)> = vec![
        ("syntax", edit("[medium]", "[medium"), "line"),
        (
            "unknown_key",
            edit("cycles = 5", "cycles = 5\ncolour = 1"),
            "colour",
        ),
        (
            "unknown_law",
            with_traction("traction = { law = \"glue\" }"),
            "interface.traction",
        ),
        (
            "missing_field",
            edit("frequency = 1e6\n", ""),
            "incident.frequency",
        ),
        (
            "zero_stiffness",
            with_traction("traction = { law = \"linear\", stiffness = 0.0 }"),
            "interface.traction.stiffness",
        ),
        (
            "negative_stiffness",
            with_traction("compression = { law = \"linear\", stiffness = -1e12 }"),
            "interface.compression.stiffness",
        ),
        (
            "negative_density",
            edit(
                "material = \"pmma\"",
                "material = \"pmma\"\ndensity = -1190.0",
            ),
            "medium.density",
        ),
        (
            "zero_frequency",
            edit("frequency = 1e6", "frequency = 0.0"),
            "incident.frequency",
        ),
        (
            "negative_cycles",
            edit("cycles = 5", "cycles = -3"),
            "incident.cycles",
        ),
        (
            "m_above_one",
            with_traction("compression = { law = \"power\", c = 1.81e10, m = 1.5 }"),
            "interface.compression.m",
        ),
        (
            "m_zero",
            with_traction("compression = { law = \"power\", c = 1.81e10, m = 0.0 }"),
            "interface.compression.m",
        ),
        (
            "nan_amplitude",
            edit("xi = 0.35", "amplitude = nan"),
            "incident.amplitude",
        ),
        (
            "inf_pressure",
            edit("static_pressure = 0.1e6", "static_pressure = inf"),
            "interface.static_pressure",
        ),
        ("nan_xi", edit("xi = 0.35", "xi = nan"), "incident.xi"),
        ("zero_xi", edit("xi = 0.35", "xi = 0.0"), "incident.xi"),
        ("negative_xi", edit("xi = 0.35", "xi = -0.2"), "incident.xi"),
        (
            "probe_x_zero",
            format!("{BASE}\n[probe]\nx = 0.0\n"),
            "probe.x",
        ),
        (
            "probe_x_positive",
            format!("{BASE}\n[probe]\nx = 0.03\n"),
            "probe.x",
        ),
        // tangential contact (model.md section 13)
        (
            "negative_friction",
            with_traction("tangential = { law = \"coulomb\", friction = -0.3 }"),
            "interface.tangential.friction",
        ),
        (
            "poisson_above_half",
            edit(
                "material = \"pmma\"",
                "material = \"pmma\"\npoisson_ratio = 0.6",
            ),
            "medium.poisson_ratio",
        ),
        (
            "poisson_below_minus_one",
            edit(
                "material = \"pmma\"",
                "material = \"pmma\"\npoisson_ratio = -1.5",
            ),
            "medium.poisson_ratio",
        ),
        (
            "shear_wave_without_shear_modulus",
            format!(
                "{}\n[shear_incident]\nfrequency = 1e6\namplitude = 1e5\n",
                edit(
                    "material = \"pmma\"",
                    "youngs_modulus = 5e9\ndensity = 1190.0",
                )
            ),
            "medium.poisson_ratio",
        ),
        (
            "static_shear_above_friction_limit",
            with_traction(
                "tangential = { law = \"coulomb\", friction = 0.3 }\nstatic_shear = 0.05e6",
            ),
            "interface.static_shear",
        ),
        (
            "full_rccm_without_rccm_traction",
            with_traction("tangential = { law = \"rccm\", stiffness = 1e13, friction = 0.3 }"),
            "interface.tangential.law",
        ),
        (
            "shear_xi",
            format!("{BASE}\n[shear_incident]\nfrequency = 1e6\nxi = 0.5\n"),
            "shear_incident.xi",
        ),
        (
            "negative_shear_delay",
            format!("{BASE}\n[shear_incident]\nfrequency = 1e6\namplitude = 1e5\ndelay = -1e-6\n"),
            "shear_incident.delay",
        ),
    ];
    let d = tmpdir("bad");
    for (name, text, field) in &cases {
        let file = d.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        for cmd in ["run", "law"] {
            let out = d.join(format!("out_{cmd}_{name}"));
            let o = cli(cmd, &file, &out);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{cmd} {name}: {err}");
            assert_eq!(err.lines().count(), 1, "{cmd} {name}: {err}");
            assert!(err.starts_with("error: "), "{cmd} {name}: {err}");
            assert!(err.contains(&format!("{name}.toml")), "{cmd} {name}: {err}");
            assert!(err.contains(field), "{cmd} {name}: {err}");
            assert!(!out.exists(), "{cmd} {name}: output folder created");
            assert!(o.stdout.is_empty(), "{cmd} {name}: stdout not empty");
        }
    }
    // missing scenario file
    let out = d.join("out_missing");
    let o = cli("run", d.join("nope.toml"), &out);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).lines().count(), 1);
    assert!(stderr(&o).contains("nope.toml"));
    assert!(!out.exists());
    // a negative sampling step is a value out of range, not an unknown flag
    let file = d.join("good.toml");
    std::fs::write(&file, BASE).unwrap();
    let out = d.join("out_step");
    let o = bin()
        .args([
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--record-step", "-1"])
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("record-step") && err.contains("> 0"), "{err}");
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(d);
}

fn write_sweep(d: &Path, axis: &str) -> PathBuf {
    std::fs::write(d.join("base.toml"), BASE).unwrap();
    let s = d.join("sweep.toml");
    std::fs::write(&s, format!("base = \"base.toml\"\n\n[[axis]]\n{axis}\n")).unwrap();
    s
}

fn csv_points(csv: &Path) -> Vec<usize> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    assert!(lines.next().unwrap().starts_with("point,incident.xi,"));
    lines
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect()
}

#[test]
fn sweep_resume_computes_only_missing_points() {
    let d = tmpdir("sweep");
    let s = write_sweep(&d, "parameter = \"incident.xi\"\nlinspace = [0.1, 1.1, 6]");
    let out = d.join("out");
    let o = bin()
        .args([
            "sweep",
            s.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--threads",
            "2",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = out.join("sweep.csv");
    let mut pts = csv_points(&csv);
    pts.sort();
    assert_eq!(pts, (0..6).collect::<Vec<_>>());
    assert!(out.join("sweep.csv.hash").is_file());
    assert!(out.join("sweep.svg").is_file());
    // keep the header and the rows of points 0, 1, 2 (in grid order), drop the rest
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let mut rows: Vec<&str> = lines.collect();
    rows.sort_by_key(|l| l.split(',').next().unwrap().parse::<usize>().unwrap());
    let kept = format!("{header}\n{}\n{}\n{}\n", rows[0], rows[1], rows[2]);
    std::fs::write(&csv, &kept).unwrap();
    let o = bin()
        .args([
            "sweep",
            s.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--resume",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("3 computed, 3 already done"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with(&kept), "resume rewrote existing rows");
    let mut pts = csv_points(&csv);
    assert_eq!(pts.len(), 6);
    pts.sort();
    pts.dedup();
    assert_eq!(pts, (0..6).collect::<Vec<_>>());
    // a changed sweep refuses to resume into the old CSV and leaves it untouched
    std::fs::write(
        &s,
        "base = \"base.toml\"\n\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.1, 1.1, 7]\n",
    )
    .unwrap();
    let o = bin()
        .args([
            "sweep",
            s.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--resume",
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1);
    assert!(stderr(&o).contains("hash"));
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), text);
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn bad_sweeps_fail_fast_without_output() {
    let cases = [
        (
            "parameter = \"incident.xi\"\nlinspace = [0.1, 1.1]",
            "axis.0.linspace",
        ),
        (
            "parameter = \"incident.xi\"\nlogspace = [-1, 0, 0]",
            "axis.0.logspace",
        ),
        (
            "parameter = \"incident.xi\"\nvalues = [0.2]\nstep = 1",
            "axis.0.step",
        ),
        ("parameter = \"incident.xi\"", "axis.0"),
        // a grid point that is not a valid scenario
        (
            "parameter = \"incident.xi\"\nvalues = [0.3, -0.1]",
            "incident.xi",
        ),
        (
            "parameter = \"interface.static_pressure\"\nvalues = [1e5, inf]",
            "axis.0.values",
        ),
    ];
    for (k, (axis, field)) in cases.iter().enumerate() {
        let d = tmpdir(&format!("badsweep{k}"));
        let s = write_sweep(&d, axis);
        let out = d.join("out");
        let o = bin()
            .args(["sweep", s.to_str().unwrap(), "--out", out.to_str().unwrap()])
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{axis}: {err}");
        assert_eq!(err.lines().count(), 1, "{axis}: {err}");
        assert!(err.starts_with("error: "), "{err}");
        assert!(err.contains(field), "{axis}: {err}");
        assert!(err.contains("sweep.toml"), "{axis}: {err}");
        assert!(!out.exists(), "{axis}: output folder created");
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn convergence_reports_first_order_fd_and_rejects_bad_resolutions() {
    let d = tmpdir("convergence");
    let out = d.join("out");
    let o = bin()
        .arg("convergence")
        .arg(examples().join("rccm_1.6MPa.toml"))
        .args(["--spp", "62,125,250,500", "--xi", "0.2,0.5,0.8", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = text
        .lines()
        .find(|l| l.starts_with("observed order:"))
        .unwrap_or_else(|| panic!("no order line in\n{text}"));
    let order: f64 = line
        .split_whitespace()
        .nth(2)
        .and_then(|v| v.parse().ok())
        .unwrap();
    // above the comparison's plateau (about 2e-5 relative, the exact solver's own
    // tolerance: reached near 1000 samples a period) the FD error against the exact
    // solver falls as dt^2 (measured 2.35: the average interface update, and the backward
    // one only at switches onto or off a constraint, model.md section 9.2)
    assert!(
        (1.7..3.0).contains(&order),
        "observed order {order}\n{text}"
    );
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let err: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(4).unwrap().parse().unwrap())
        .collect();
    assert_eq!(err.len(), 4);
    assert!(err.windows(2).all(|w| w[1] < w[0]), "{err:?}");
    // FD within 1% (eq. 2.43) of the exact solver at the default FD resolution
    assert!(err[3] < 0.01, "{err:?}");
    assert!(out.join("convergence.svg").exists() && out.join("efficiency.csv").exists());

    let bad = d.join("bad");
    let o = bin()
        .arg("convergence")
        .arg(examples().join("rccm_1.6MPa.toml"))
        .args(["--spp", "4,250,500", "--out"])
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("--spp") && e.contains(">= 8"), "{e}");
    assert!(!bad.exists());
}

/// `bench` times each issue-13 target and prints one line per target; a missing
/// identification file is a one-line error with exit code 2. The 2D case shorter than
/// the example's snapshot interval (1 us) runs too (it was refused).
#[test]
fn bench_prints_every_target_and_rejects_a_missing_file() {
    let o = bin()
        .args([
            "bench",
            "--runs",
            "2",
            "--points",
            "3",
            "--tribobrake-runs",
            "1",
            "--solid-2d-us",
            "0.2",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for head in [
        "single simulation",
        "single simulation, cold",
        "xi sweep (3 points",
        "Tribobrake hammer test",
        "2D solid, plate crack",
    ] {
        assert!(out.contains(head), "{head} missing in\n{out}");
    }
    let line = out.lines().find(|l| l.starts_with("2D solid")).unwrap();
    let rate: f64 = line
        .strip_suffix(" node-updates/s")
        .and_then(|l| l.rsplit(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no rate in {line}"));
    assert!(rate > 0.0 && line.contains(" steps, "), "{line}");
    assert!(!out.contains("identification"));
    let o = bin()
        .args([
            "bench",
            "--runs",
            "1",
            "--points",
            "1",
            "--tribobrake-runs",
            "0",
        ])
        .arg("--identify")
        .arg(examples().join("identify/missing.toml"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).trim().lines().count(), 1, "{}", stderr(&o));
    assert!(stderr(&o).contains("missing.toml"));
}

/// Issue 24: a shard missing its last row was merged ("merged 5 points", exit 0), and
/// shard 1 merged alone (no --sweep) was taken for a grid ending at its largest point.
#[test]
fn merge_refuses_a_truncated_or_lone_shard_naming_the_missing_points() {
    let d = tmpdir("merge-truncated");
    let s = write_sweep(&d, "parameter = \"incident.xi\"\nlinspace = [0.1, 1.1, 6]");
    let shard = |k: usize| {
        let out = d.join(format!("s{k}"));
        let o = bin()
            .arg("sweep")
            .arg(&s)
            .arg("--out")
            .arg(&out)
            .args(["--shard", &format!("{k}/2")])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        out.join("sweep.csv")
    };
    let (s1, s2) = (shard(1), shard(2));
    let text = std::fs::read_to_string(&s2).unwrap();
    let kept: Vec<&str> = text.lines().collect();
    assert!(kept[3].starts_with("5,"), "{text}");
    std::fs::write(&s2, kept[..3].join("\n") + "\n").unwrap();
    let merged = d.join("merged.csv");
    let merge = |shards: &[&Path], sweep: bool| {
        let mut c = bin();
        c.arg("merge").arg(&merged).args(shards);
        if sweep {
            c.arg("--sweep").arg(&s);
        }
        c.output().unwrap()
    };
    for sweep in [false, true] {
        let o = merge(&[&s1, &s2], sweep);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let err = stderr(&o);
        assert_eq!(err.lines().count(), 1, "{err}");
        let lacks = format!("{} (shard 2/2) lacks 1 of its 3 points: 5", s2.display());
        assert!(
            err.contains("1 of 6 points") && err.contains(&lacks),
            "{err}"
        );
        assert!(!merged.exists());
    }
    let o = merge(&[&s1], false);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("3 of 6 points")
            && err.contains("shard 2/2 (not given) lacks 3 of its 3 points: 1, 3, 5"),
        "{err}"
    );
    // the whole shard again: the merge goes through and says so
    std::fs::write(&s2, &text).unwrap();
    let o = merge(&[&s1, &s2], false);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("merged 6 points from 2 shards"));
    let side = std::fs::read_to_string(d.join("merged.csv.shard")).unwrap();
    assert_eq!(side, "shard = \"1/1\"\npoints = 6\n");
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 24: the Tribobrake run then a half-space run into the same folder left the bar
/// stack's frf.csv/frf.svg beside the new summary.json. Issue 56 item 7: a run into a folder
/// holding another run's results is refused (exit 2, one line, nothing touched) unless
/// `--overwrite`; then it removes what the first wrote (its manifest) and leaves a file of
/// the user's alone, naming it. The same run re-run into its own folder replaces its files.
#[test]
fn a_reused_output_folder_holds_one_runs_files_only() {
    let d = tmpdir("reused-out");
    let out = d.join("out");
    let o = cli("run", examples().join("tribobrake.toml"), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("frf.csv").is_file() && out.join("frf.svg").is_file());
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    // the same scenario again: its own folder
    let o = cli("run", examples().join("tribobrake.toml"), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(out.join("frf.csv")).unwrap();
    // another scenario: refused, nothing touched
    let o = cli("run", examples().join("rccm_0.82MPa.toml"), &out);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("--out") && err.contains("tribobrake.toml") && err.contains("--overwrite"),
        "{err}"
    );
    assert_eq!(std::fs::read(out.join("frf.csv")).unwrap(), before);
    assert!(!out.join("probe.csv").exists());
    let o = bin()
        .arg("run")
        .arg(examples().join("rccm_0.82MPa.toml"))
        .arg("--out")
        .arg(&out)
        .arg("--overwrite")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("summary.json").is_file() && out.join("probe.csv").is_file());
    assert!(!out.join("frf.csv").exists() && !out.join("frf.svg").exists());
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    let err = stderr(&o);
    assert!(
        err.contains("removed 2 file(s)") && err.contains("frf.csv, frf.svg"),
        "{err}"
    );
    assert!(
        err.contains("did not write (left untouched): notes.txt"),
        "{err}"
    );
    let manifest = std::fs::read_to_string(out.join(".contactwave-manifest.json")).unwrap();
    assert!(
        manifest.contains("\"summary.json\"") && !manifest.contains("frf"),
        "{manifest}"
    );
    // a sweep into the same folder (told to overwrite), resumed: its files stay, the
    // run's go
    let s = write_sweep(&d, "parameter = \"incident.xi\"\nvalues = [0.3, 0.6]");
    for extra in [Some("--overwrite"), Some("--resume")] {
        let o = bin()
            .arg("sweep")
            .arg(&s)
            .arg("--out")
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let mut names: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                ".contactwave-manifest.json",
                "notes.txt",
                "provenance.json",
                "sweep.csv",
                "sweep.csv.hash",
                "sweep.csv.shard",
                "sweep.svg"
            ]
        );
    }
    let _ = std::fs::remove_dir_all(d);
}

/// An oblique run's headline shows the outgoing waves (reflected and transmitted P and SV:
/// A1/Ainc, A2/A1, A3/A1 over the incident wave), the values of `summary.json`, and no
/// line of the normal traction component (issue 24 item 5: at 45 degrees that read
/// "A1/Ainc 1.030" where the reflected P wave has 0.529).
#[test]
fn oblique_run_headlines_the_outgoing_waves() {
    let d = tmpdir("oblique-headline");
    let o = cli(
        "run",
        examples().join("oblique/p_45deg.toml"),
        d.join("out"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("out/summary.json")).unwrap())
            .unwrap();
    assert!(!out.lines().any(|l| l.starts_with("A1/Ainc")), "{out}");
    for w in [
        "reflected_P",
        "reflected_SV",
        "transmitted_P",
        "transmitted_SV",
    ] {
        let label = w.replace('_', " ");
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("{label} ")))
            .unwrap_or_else(|| panic!("no {label} line in\n{out}"));
        let cols: Vec<f64> = line[label.len()..]
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        for (i, k) in ["A1_over_Ainc", "A2_over_A1", "A3_over_A1"]
            .iter()
            .enumerate()
        {
            let v = summary[format!("{w}_{k}")].as_f64().unwrap();
            assert!((cols[i] / v - 1.0).abs() < 1e-6, "{w}_{k}: {line}");
        }
    }
    // the reflected P wave, not the interface's normal component (which also holds the
    // reflected SV wave's share): at 45 degrees in aluminium they differ
    let rp = summary["reflected_P_A1_over_Ainc"].as_f64().unwrap();
    let normal = summary["reflected_normal_A1_over_Ainc"].as_f64().unwrap();
    assert!(rp < 1.0 && (rp - normal).abs() > 0.02, "{rp} vs {normal}");
    assert_eq!(summary["amplitude"].as_f64(), Some(1e6));
}

/// Issue 56 item 7: a file of the user's under a name a run writes (a `summary.json` of
/// their own, no manifest) is not replaced without `--overwrite`.
#[test]
fn a_users_file_under_a_run_files_name_is_kept() {
    let d = tmpdir("users-file");
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("summary.json"), "mine").unwrap();
    let o = cli("run", examples().join("rccm_0.82MPa.toml"), &out);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("summary.json"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(out.join("summary.json")).unwrap(),
        "mine"
    );
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(d);
}

/// Issue 56 item 11: `reproduce --help` and the command list of `contactwave --help` say
/// what each study is, `finite_crack` (the 2D study, the longest) and `shear` included,
/// not only the thesis' chapters.
#[test]
fn reproduce_help_names_every_study() {
    let text = |args: &[&str]| {
        let o = bin().args(args).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let help = text(&["reproduce", "--help"]);
    // the description (before the usage line) names the studies beyond the thesis
    let (about, rest) = help.split_once("Usage:").unwrap();
    for name in ["`shear`", "`finite_crack`", "finite cracks in 2D"] {
        assert!(about.contains(name), "{name}: {help}");
    }
    // the argument's help says what each value runs
    let which = rest
        .lines()
        .find(|l| l.trim_start().starts_with("[WHICH]"))
        .unwrap();
    for name in ["chapter3", "shear", "finite_crack", "all", "--quick"] {
        assert!(which.contains(name), "{name}: {which}");
    }
    let top = text(&["--help"]);
    let line = top
        .lines()
        .find(|l| l.trim_start().starts_with("reproduce"))
        .unwrap();
    assert!(line.contains("finite_crack"), "{line}");
}

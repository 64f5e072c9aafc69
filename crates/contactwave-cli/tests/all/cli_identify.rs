//! End-to-end tests of `contactwave identify`: its report and design files, and one-line
//! errors with exit code 2 and no output on bad identification inputs (split from cli.rs).

use crate::common::{bin, cli, examples, stderr, tmpdir};
use std::path::{Path, PathBuf};

/// An identification file in `d` on the chapter-3 example, with a quick fit.
fn write_identify(d: &Path, data: &str, params: &str) -> PathBuf {
    let base = examples().join("rccm_0.82MPa.toml");
    std::fs::write(d.join("data.csv"), data).unwrap();
    let spec = d.join("identify.toml");
    std::fs::write(
        &spec,
        format!(
            "base = {:?}\ndata = \"data.csv\"\n[set]\n\"interface.traction.energy\" = 1e3\n\
             \"solver.samples_per_period\" = 100\n{params}\n[fit]\nparticles = 4\n\
             iterations = 3\nlocal_iterations = 20\nlocal_starts = 1\nbootstrap = 3\n\
             bootstrap_iterations = 5\n[design]\nfrequencies = [0.5e6, 1e6, 2e6]\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    spec
}

const CN_PARAM: &str = "[[parameter]]\nkey = \"interface.traction.stiffness\"\n\
                        bounds = [1e8, 1e17]\nscale = \"log\"\ninitial = 1e12\n";

#[test]
fn identify_writes_report_and_design() {
    let d = tmpdir("identify");
    // the committed synthetic data of the example (C_N = 2e13, 1% noise)
    let data = std::fs::read_to_string(examples().join("identify/rccm_undamaged.csv")).unwrap();
    let spec = write_identify(&d, &data, CN_PARAM);
    let out = d.join("out");
    let o = cli("identify", &spec, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("interface.traction.stiffness: identified, 95% CI"),
        "{stdout}"
    );
    for f in [
        "identification.json",
        "fit.csv",
        "fit.svg",
        "sensitivity.svg",
        "identification.html",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("identification.json")).unwrap())
            .unwrap();
    let est = j["estimates"]["interface.traction.stiffness"]
        .as_f64()
        .unwrap();
    assert!((est / 2e13 - 1.0).abs() < 0.05, "{est:e}");
    let ci = &j["intervals"]["interface.traction.stiffness"];
    assert!(ci[0].as_f64().unwrap() < est && est < ci[1].as_f64().unwrap());
    assert!(j["forward_runs"].as_u64().unwrap() > 0);
    // design: a ranked table and its files
    let dout = d.join("design");
    let o = bin()
        .arg("identify")
        .arg(&spec)
        .arg("--design")
        .arg("--out")
        .arg(&dout)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("rank"));
    assert!(dout.join("design.json").is_file() && dout.join("design.csv").is_file());
}

#[test]
fn bad_identification_inputs_fail_with_one_line_and_no_output() {
    let good_rows = "incident.xi,A2_over_A1\n0.1,0.5\n0.2,0.6\n0.3,0.5\n";
    let energy = "[[parameter]]\nkey = \"interface.traction.energy\"\nbounds = [1.0, 1e4]\n";
    let cases: Vec<(&str, String, String, &str)> = vec![
        (
            "NaN",
            "incident.xi,A2_over_A1\n0.1,0.5\n0.2,NaN\n".into(),
            CN_PARAM.into(),
            "A2_over_A1",
        ),
        (
            "negative",
            "incident.xi,A2_over_A1\n0.1,0.5\n0.2,-0.3\n".into(),
            CN_PARAM.into(),
            "-0.3",
        ),
        (
            "too few points",
            "incident.xi,A2_over_A1\n0.1,0.5\n".into(),
            format!("{CN_PARAM}{energy}"),
            "rows",
        ),
        (
            "unknown key",
            good_rows.into(),
            CN_PARAM.replace("traction.stiffness", "traction.stifness"),
            "parameter.0.key",
        ),
        (
            "bounds exclude the base",
            good_rows.into(),
            CN_PARAM.replace("1e17", "1e12").replace("1e12\n", "1e10\n"),
            "parameter.0.bounds",
        ),
        // a stiffness beyond 1e24 Pa/m inside the bounds: refused when they are read (it
        // once let the fit run into stiffnesses the solver integrates wrongly, for minutes)
        (
            "bounds beyond the stiffest interface",
            good_rows.into(),
            CN_PARAM.replace("1e17", "1e300"),
            "at most 1e24 Pa/m",
        ),
    ];
    for (name, data, params, needle) in cases {
        let d = tmpdir("identify-bad");
        let spec = write_identify(&d, &data, &params);
        let out = d.join("out");
        let o = cli("identify", &spec, &out);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        let err = stderr(&o);
        assert_eq!(err.trim_end().lines().count(), 1, "{name}: {err}");
        assert!(err.starts_with("error: "), "{name}: {err}");
        assert!(err.contains(needle), "{name}: {err}");
        assert!(
            err.contains("data.csv") || err.contains("identify.toml"),
            "{name}: no file named: {err}"
        );
        assert!(!out.exists(), "{name}: output folder created");
    }
}

/// Options of one mode given to the other are refused, not ignored: `--noise` and `--seed`
/// without `--synthesize`, `--out` with it; a log-scale parameter synthesized at a value
/// <= 0 is named as the --synthesize value.
#[test]
fn misplaced_options_and_impossible_synthetic_values_are_refused() {
    let d = tmpdir("identify-misplaced");
    let spec = write_identify(
        &d,
        "incident.xi,A2_over_A1\n0.1,0.5\n0.2,0.4\n0.3,0.3\n",
        CN_PARAM,
    );
    let spec = spec.to_str().unwrap();
    let out = d.join("out");
    let out = out.to_str().unwrap();
    for (args, needle) in [
        (vec![spec, "--out", out, "--noise", "0.1"], "--noise"),
        (vec![spec, "--out", out, "--seed", "3"], "--seed"),
        (
            vec![
                spec,
                "--out",
                out,
                "--synthesize",
                "interface.traction.stiffness=2e13",
            ],
            "--out",
        ),
        (
            vec![
                spec,
                "--synthesize",
                "interface.traction.stiffness=2e13",
                "--noise",
                "-1",
            ],
            "--noise",
        ),
        (
            vec![spec, "--synthesize", "interface.traction.stiffness=-2e13"],
            "scale is log",
        ),
    ] {
        let o = bin().arg("identify").args(&args).output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert!(!d.join("out").exists(), "{args:?}");
    }
}

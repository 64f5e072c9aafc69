//! Issue 28 item 4: every output of run / sweep / identify carries the provenance keys
//! (version, commit, the SHA-256 of the input file and of each data file read, the
//! command line, the date); `--hdf5` writes result.h5 / sweep.h5 that read back with
//! their units and the provenance as root attributes.

use crate::common::{examples, tmpdir};
use sha2::{Digest, Sha256};
use std::path::Path;
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_contactwave"))
}

/// SHA-256 of a file, computed here (not by contactwave).
fn sha256(path: &Path) -> String {
    let d = Sha256::digest(std::fs::read(path).unwrap());
    d.iter().map(|b| format!("{b:02x}")).collect()
}

const KEYS: [&str; 8] = [
    "contactwave_version",
    "git_commit",
    "git_dirty",
    "input",
    "scenario_sha256",
    "data_files",
    "command_line",
    "created",
];

/// The `provenance` object of a JSON file, with every key checked.
fn provenance(file: &Path) -> serde_json::Value {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let p = v["provenance"].clone();
    for k in KEYS {
        assert!(
            p.get(k).is_some(),
            "{}: provenance.{k} missing",
            file.display()
        );
    }
    assert_eq!(p["contactwave_version"], env!("CARGO_PKG_VERSION"));
    let created = p["created"].as_str().unwrap();
    assert!(created.len() == 20 && created.ends_with('Z'), "{created}");
    if let Some(c) = p["git_commit"].as_str() {
        assert!(
            c.len() == 40 && c.chars().all(|x| x.is_ascii_hexdigit()),
            "{c}"
        );
    }
    p
}

fn has_data_file(p: &serde_json::Value, path: &Path) -> bool {
    let want = sha256(path);
    p["data_files"].as_array().unwrap().iter().any(|d| {
        d["sha256"] == want.as_str()
            && d["path"]
                .as_str()
                .unwrap()
                .ends_with(path.file_name().unwrap().to_str().unwrap())
    })
}

fn str_attr(a: &std::collections::HashMap<String, hdf5_pure::AttrValue>, k: &str) -> String {
    a.get(k)
        .and_then(|v| v.as_str())
        .unwrap_or_default()
        .to_string()
}

#[test]
fn run_summary_and_result_h5_carry_the_provenance() {
    let d = tmpdir("prov-run");
    // a waveform file: the data file of the scenario
    let mut wave = String::from("t,s\n");
    for k in 0..400 {
        let t = k as f64 * 5e-9;
        let s = (2.0 * std::f64::consts::PI * 1e6 * t).sin()
            * (std::f64::consts::PI * t / 2e-6).sin().powi(2);
        wave.push_str(&format!("{t:e},{s:e}\n"));
    }
    std::fs::write(d.join("wave.csv"), &wave).unwrap();
    let scenario = d.join("case.toml");
    std::fs::write(
        &scenario,
        "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.082e6\n\
         [incident]\nkind = \"file\"\nfrequency = 1e6\nxi = 0.5\npath = \"wave.csv\"\n",
    )
    .unwrap();
    let out = d.join("out");
    let o = bin()
        .arg("run")
        .arg(&scenario)
        .arg("--out")
        .arg(&out)
        .arg("--hdf5")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p = provenance(&out.join("summary.json"));
    assert_eq!(p["scenario_sha256"], sha256(&scenario).as_str());
    assert_eq!(p["input"], scenario.display().to_string().as_str());
    assert!(has_data_file(&p, &d.join("wave.csv")), "{p}");
    let cmd = p["command_line"].as_str().unwrap();
    assert!(cmd.contains(" run ") && cmd.ends_with("--hdf5"), "{cmd}");

    // result.h5: the tables with units, the summary, the provenance at the root
    let f = hdf5_pure::File::open(out.join("result.h5")).unwrap();
    let root = f.root().attrs().unwrap();
    assert_eq!(str_attr(&root, "scenario_sha256"), sha256(&scenario));
    assert_eq!(str_attr(&root, "created"), p["created"].as_str().unwrap());
    assert_eq!(
        str_attr(&root, "data_file_0_sha256"),
        sha256(&d.join("wave.csv"))
    );
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    let rows = csv.lines().count() - 1;
    let t = f.dataset("timeseries/t").unwrap();
    let tv = t.read_f64().unwrap();
    assert_eq!(tv.len(), rows);
    let first: f64 = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(tv[0], first);
    assert_eq!(str_attr(&t.attrs().unwrap(), "units"), "s");
    let gap = f.dataset("timeseries/gap").unwrap();
    assert_eq!(str_attr(&gap.attrs().unwrap(), "units"), "m");
    let refl = f.dataset("probe/reflected_stress").unwrap();
    assert_eq!(str_attr(&refl.attrs().unwrap(), "units"), "Pa");
    let spec = f.dataset("spectrum/frequency").unwrap();
    assert_eq!(str_attr(&spec.attrs().unwrap(), "units"), "Hz");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let s = f.group("summary").unwrap().attrs().unwrap();
    assert_eq!(
        s["A2_over_Ainc"].as_f64().unwrap(),
        summary["A2_over_Ainc"].as_f64().unwrap()
    );
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn sweep_writes_a_provenance_sidecar_and_sweep_h5() {
    let d = tmpdir("prov-sweep");
    std::fs::write(
        d.join("base.toml"),
        "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.1e6\n\
         [incident]\nfrequency = 1e6\ncycles = 5\nxi = 0.35\n",
    )
    .unwrap();
    let sweep = d.join("sweep.toml");
    std::fs::write(
        &sweep,
        "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.2, 0.8, 3]\n",
    )
    .unwrap();
    let out = d.join("out");
    let o = bin()
        .arg("sweep")
        .arg(&sweep)
        .arg("--out")
        .arg(&out)
        .args(["--threads", "1", "--hdf5"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p = provenance(&out.join("provenance.json"));
    assert_eq!(p["scenario_sha256"], sha256(&sweep).as_str());
    assert!(has_data_file(&p, &d.join("base.toml")), "{p}");
    // sweep.csv stays a plain table (first line its header)
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(header[..2], ["point", "incident.xi"]);
    let f = hdf5_pure::File::open(out.join("sweep.h5")).unwrap();
    let mut cols = f.group("sweep").unwrap().datasets().unwrap();
    cols.sort();
    let mut want: Vec<String> = header.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(cols, want);
    let xi = f.dataset("sweep/incident.xi").unwrap().read_f64().unwrap();
    assert_eq!(xi, vec![0.2, 0.5, 0.8]);
    let p0 = f.dataset("sweep/A2_over_Ainc").unwrap();
    assert_eq!(str_attr(&p0.attrs().unwrap(), "units"), "1");
    assert_eq!(
        str_attr(&f.root().attrs().unwrap(), "scenario_sha256"),
        sha256(&sweep)
    );
    // the same sweep again without --hdf5: the stale sweep.h5 is removed
    let o = bin()
        .arg("sweep")
        .arg(&sweep)
        .arg("--out")
        .arg(&out)
        .args(["--threads", "1"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!out.join("sweep.h5").exists());
    assert!(out.join("provenance.json").is_file());
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn identification_json_carries_the_provenance() {
    let d = tmpdir("prov-identify");
    let base = examples().join("rccm_0.82MPa.toml");
    // three rows of the example's synthetic data: a quick fit
    let data: String = std::fs::read_to_string(examples().join("identify/rccm_undamaged.csv"))
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .take(4)
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(d.join("data.csv"), data).unwrap();
    let spec = d.join("identify.toml");
    std::fs::write(
        &spec,
        format!(
            "base = {:?}\ndata = \"data.csv\"\n[set]\n\"interface.traction.energy\" = 1e3\n\
             \"solver.samples_per_period\" = 60\n[[parameter]]\n\
             key = \"interface.traction.stiffness\"\nbounds = [1e8, 1e17]\nscale = \"log\"\n\
             initial = 1e12\n[fit]\nparticles = 3\niterations = 2\nlocal_iterations = 10\n\
             local_starts = 1\nbootstrap = 2\nbootstrap_iterations = 2\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    let out = d.join("out");
    let o = bin()
        .arg("identify")
        .arg(&spec)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p = provenance(&out.join("identification.json"));
    assert_eq!(p["scenario_sha256"], sha256(&spec).as_str());
    assert!(has_data_file(&p, &base), "{p}");
    assert!(has_data_file(&p, &d.join("data.csv")), "{p}");
    let _ = std::fs::remove_dir_all(d);
}

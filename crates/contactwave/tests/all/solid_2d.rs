//! The `solid_2d` kind through the model contract: a scenario file runs, its summary
//! closes the energy, its files and arrays are there, sweep keys reach it, and bad input
//! is a one-line error naming the key.

use contactwave::model::{self, RunControl, Value};

/// A small clapping case: a 2 x 1 mm plate, a 0.6 mm crack under 0.2 MPa, a 10 MHz
/// 10 MPa burst from a transducer above it.
const SMALL: &str = r#"
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
static_pressure = 0.2e6
tangential = { law = "coulomb", friction = 0.3 }

[[source]]
x0 = 0.6e-3
x1 = 1.4e-3
signal = { frequency = 10e6, cycles = 2, amplitude = 10e6, window = "hann" }

[[receiver]]
name = "top"
at = [1e-3, 0.0]

[[receiver]]
name = "under"
at = [1e-3, 1e-3]
"#;

#[test]
fn a_scenario_runs_closes_its_energy_and_writes_its_files() {
    let t = model::from_toml_str(SMALL, "small.toml").unwrap();
    assert_eq!(t.kind(), "solid_2d");
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_input").unwrap() > 0.0);
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
    // the crack claps: it opens, and Signorini holds in its records
    assert!(s.get("crack_max_gap_0").unwrap() > 0.0, "{s:?}");
    for key in ["top_A1", "under_A2_over_A1", "nodes", "steps", "dt"] {
        assert!(s.get(key).is_some_and(f64::is_finite), "{key}");
    }
    let files = outcome.files().unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names[..3], ["summary.json", "receivers.csv", "crack.csv"]);
    // the plots (the `plot` feature); no snapshots without `[snapshots]`
    #[cfg(feature = "plot")]
    assert_eq!(
        names[3..],
        ["receivers.svg", "spectra.svg", "crack_state.svg"]
    );
    // the crack's state map: its states in the legend
    #[cfg(feature = "plot")]
    assert!(files[5].contents.contains("\nstick\n</text>"));
    #[cfg(not(feature = "plot"))]
    assert_eq!(names.len(), 3);
    assert!(files[1]
        .contents
        .starts_with("t,top_vx,top_vz,under_vx,under_vz\n"));
    assert!(files[2]
        .contents
        .starts_with("crack,t,position,normal_gap,"));
    // the crack index and state are written as integers (0, 1, 2), as in summary.json
    let row = files[2].contents.lines().nth(1).unwrap();
    let cells: Vec<&str> = row.split(',').collect();
    assert_eq!(cells[0], "0", "{row}");
    assert!(["0", "1", "2"].contains(&cells[8]), "{row}");
    let r = outcome.record();
    let Some(Value::Rows(rec)) = r.get("receivers") else {
        panic!("receivers rows")
    };
    let Some(Value::Array(time)) = r.get("t") else {
        panic!("t")
    };
    assert_eq!(rec.len(), 4);
    assert!(rec.iter().all(|row| row.len() == time.len()));
    let Some(Value::Tuple(cracks)) = r.get("cracks") else {
        panic!("cracks")
    };
    let Value::Map(c) = &cracks[0] else {
        panic!("crack map")
    };
    let (Some(Value::Rows(gap)), Some(Value::Rows(stress))) =
        (c.get("normal_gap"), c.get("normal_stress"))
    else {
        panic!("crack rows")
    };
    assert!(gap.iter().flatten().all(|&g| g >= 0.0));
    assert!(gap
        .iter()
        .flatten()
        .zip(stress.iter().flatten())
        .all(|(&g, &s)| g == 0.0 || s.abs() < 1e-3));
}

/// A run without receivers writes no empty `receivers.csv` (its crack fields still come).
#[test]
fn a_run_without_receivers_writes_no_receivers_file() {
    let text = SMALL.split("[[receiver]]").next().unwrap();
    let t = model::from_toml_str(text, "small.toml").unwrap();
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let files = outcome.files().unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
    assert!(!names.contains(&"receivers.csv"), "{names:?}");
    assert_eq!(names[..2], ["summary.json", "crack.csv"]);
}

/// The crack's extrema in the summary are over every step, not only the recorded ones:
/// recording the fields every step or once gives the same largest gap and slip.
#[test]
fn crack_extrema_do_not_depend_on_the_recording_interval() {
    let summary = |every: usize| {
        let text = SMALL.replace(
            "element_size = 0.1e-3\n",
            &format!("element_size = 0.1e-3\ncrack_every = {every}\n"),
        );
        let t = model::from_toml_str(&text, "small.toml").unwrap();
        t.base()
            .unwrap()
            .run(&RunControl::default())
            .unwrap()
            .summary()
            .clone()
    };
    let (each, rare) = (summary(1), summary(1_000_000));
    for key in [
        "crack_max_gap_0",
        "crack_max_slip_0",
        "crack_min_adhesion_0",
    ] {
        assert_eq!(each.get(key), rare.get(key), "{key}");
    }
    assert!(rare.get("crack_max_gap_0").unwrap() > 1e-12, "{rare:?}");
    assert!(rare.get("crack_max_slip_0").unwrap() > 0.0, "{rare:?}");
}

/// With absorbing sides and bottom (perfectly matched layers outside the plate) the run
/// closes its audit at round-off, the flux into the layers counted.
/// The summary states the run's dispersion at its highest analysed harmonic (model.md
/// section 15.4): within the budget at the default element size, and the larger error of
/// a coarser mesh (0.15 mm elements of order 6 are 0.7 per S wavelength at 30 MHz, 4.2
/// points, against the default's 5.1).
#[test]
fn the_summary_states_the_phase_error_of_the_mesh() {
    let short = SMALL.replace("duration = 0.6e-6", "duration = 0.02e-6");
    let error = |text: &str| {
        let t = model::from_toml_str(text, "small.toml").unwrap();
        let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
        outcome.summary().get("phase_error_max").unwrap()
    };
    let default = error(&short.replace("element_size = 0.1e-3\n", ""));
    let coarse = error(&short.replace("element_size = 0.1e-3", "element_size = 0.15e-3"));
    eprintln!("largest phase error: default {default:e}, 0.15 mm elements {coarse:e}");
    assert!(default.abs() <= 9e-4 && default != 0.0, "{default:e}");
    assert!(coarse.is_nan() || coarse.abs() > 1e-3, "{coarse:e}");
}

#[test]
fn absorbing_sides_close_the_energy_with_the_flux_into_the_layers() {
    let text = SMALL.replace(
        "duration = 0.6e-6",
        "duration = 0.6e-6\nsides = \"absorbing\"\nbottom = \"absorbing\"\npml_thickness = 0.3e-3",
    );
    let t = model::from_toml_str(&text, "small.toml").unwrap();
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_absorbed").unwrap() > 0.0, "{s:?}");
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
}

#[test]
fn sweep_keys_reach_the_crack_and_the_source() {
    let t = model::from_toml_str(SMALL, "small.toml").unwrap();
    // a closure far above the wave's stress keeps the crack shut
    let p0 = t.param("crack.0.static_pressure").unwrap();
    let shut = t.build(&[(&p0, 1e9)]).unwrap().summary().unwrap();
    assert_eq!(shut.get("crack_max_gap_0"), Some(0.0));
    // a shorter crack by its length
    let len = t.param("crack.0.length").unwrap();
    assert!(t.build(&[(&len, 0.4e-3)]).is_ok());
    for key in [
        "source.0.signal.amplitude",
        "crack.0.tangential.friction",
        "model.duration",
        "layer.0.thickness",
    ] {
        assert!(t.param(key).is_ok(), "{key}");
    }
    // with one crack and one source the index may be left out, and the friction
    // coefficient answers to `mu` too: the same run as the spelled-out key, not the base
    let summary = |key: &str, v: f64| {
        let p = t.param(key).unwrap();
        t.build(&[(&p, v)]).unwrap().summary().unwrap()
    };
    let gap = |s: &contactwave::analysis::Summary| s.get("crack_max_gap_0").unwrap();
    let base = t.base().unwrap().summary().unwrap();
    let angled = summary("source.0.angle", 20.0);
    assert_ne!(gap(&angled), gap(&base));
    assert_eq!(gap(&summary("source.angle", 20.0)), gap(&angled));
    let slippery = summary("crack.0.tangential.friction", 0.05);
    assert_ne!(gap(&slippery), gap(&base));
    for key in [
        "crack.0.tangential.mu",
        "crack.tangential.mu",
        "crack.tangential.friction",
    ] {
        assert_eq!(gap(&summary(key, 0.05)), gap(&slippery), "{key}");
    }
    let written = SMALL.replace("friction = 0.3", "mu = 0.05");
    let t_mu = model::from_toml_str(&written, "small.toml").unwrap();
    assert_eq!(
        gap(&t_mu.base().unwrap().summary().unwrap()),
        gap(&slippery)
    );
}

#[test]
fn bad_input_is_an_error_naming_the_key() {
    let cases = [
        // (a horizontal crack below the plate: moving its start alone would incline it)
        (
            "start = [0.7e-3, 0.5e-3]\nend = [1.3e-3, 0.5e-3]",
            "start = [0.7e-3, 2e-3]\nend = [1.3e-3, 2e-3]",
            "crack.0.start",
        ),
        (
            "end = [1.3e-3, 0.5e-3]",
            "end = [1.3e-3, 0.6e-3]",
            "crack.0.end",
        ),
        ("x1 = 1.4e-3", "x1 = 3e-3", "source.0.x1"),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\nsides = \"absorbing\"\npml_reflection = 2.0",
            "model.pml_reflection",
        ),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\nbottom = \"absorbing\"\npml_thickness = -1e-3",
            "model.pml_thickness",
        ),
        ("width = 2e-3", "width = -2e-3", "model.width"),
        ("at = [1e-3, 1e-3]", "at = [1e-3, 5e-3]", "receiver.1.at"),
        // a line receiver whose far end is outside names `to`
        (
            "at = [1e-3, 1e-3]",
            "at = [1e-3, 1e-3]\nto = [3e-3, 1e-3]\ncount = 3",
            "receiver.1.to",
        ),
        (
            "element_size = 0.1e-3",
            "element_size = 1e-9",
            "model.element_size",
        ),
        (
            "thickness = 1e-3\nmaterial = \"aluminium\"",
            "thickness = 1e-3\nmaterial = \"cheese\"",
            "layer.0.material",
        ),
        // moduli without what completes them: the missing key, not a NaN density
        (
            "material = \"aluminium\"",
            "youngs_modulus = 71e9\ndensity = 2700.0",
            "layer.0.poisson_ratio",
        ),
        // a typo in the kind names the kind, not the first table a half-space lacks
        ("kind = \"solid_2d\"", "kind = \"solid2d\"", "model.kind"),
        // a key of another source kind would be ignored
        (
            "x1 = 1.4e-3",
            "x1 = 1.4e-3\nat = [1e-3, 0.0]",
            "source.0.at",
        ),
        // a transducer on a rigid surface does no work
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\ntop = \"rigid\"",
            "source.0.surface",
        ),
        // a vertical crack on a free side is half a crack
        (
            "start = [0.7e-3, 0.5e-3]\nend = [1.3e-3, 0.5e-3]",
            "start = [2e-3, 0.2e-3]\nend = [2e-3, 0.6e-3]",
            "crack.0.start",
        ),
        // a crack of zero length names its index
        (
            "end = [1.3e-3, 0.5e-3]",
            "end = [0.7e-3, 0.5e-3]",
            "positive length",
        ),
        (
            "end = [1.3e-3, 0.5e-3]",
            "end = [1.3e-3, 0.5e-3]\nfull_width = true",
            "crack.0.full_width",
        ),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\ncrack_every = 0",
            "model.crack_every",
        ),
        // a time step beyond the mesh's stability limit is refused, not shortened
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\ntime_step = 1e-6",
            "field `model.time_step` = 1e-6: (0,",
        ),
        // the angle of a 2D source is its own key, not its signal's
        (
            "amplitude = 10e6, window",
            "amplitude = 10e6, angle = 30, window",
            "source.0.signal.angle",
        ),
        // an unknown key is named with the dotted path of every other key
        (
            "static_pressure = 0.2e6",
            "static_pressur = 0.2e6",
            "field `crack.0.static_pressur`",
        ),
        // the pre-stress sets the cracks' static state: not both
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\nprestress = { zz = -1e6 }",
            "crack.0.static_pressure",
        ),
        // keys that would be ignored are refused: a preset's Poisson ratio, a pre-stress
        // component of the other wave type, `vertical` beside an `end`
        (
            "material = \"aluminium\"",
            "material = \"aluminium\"\npoisson_ratio = 0.45",
            "field `layer.0.poisson_ratio` = 0.45",
        ),
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\nprestress = { zz = -1e6, yz = 5e5 }",
            "field `model.prestress.yz`",
        ),
        (
            "end = [1.3e-3, 0.5e-3]",
            "end = [1.3e-3, 0.5e-3]\nvertical = true",
            "field `crack.0.vertical`",
        ),
        // two receivers whose summary keys would collide (`top_A2_over_A1`)
        (
            "name = \"under\"",
            "name = \"top_A2_over\"",
            "receiver `top` writes `top_A2_over_A1` too",
        ),
        // a count of the wrong sign or type names its range, a missing table what it takes
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\norder = -3",
            "field `model.order` = -3: a whole number from 2 to 8",
        ),
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\ncrack_every = 2.5",
            "field `model.crack_every` = 2.5: a whole number >= 1",
        ),
        (
            "[[layer]]\nthickness = 1e-3\nmaterial = \"aluminium\"\n",
            "",
            "field `layer` = (missing): required: at least one [[layer]] table",
        ),
        // an amplitude far beyond any solid's strength (its energies would overflow)
        (
            "amplitude = 10e6, window",
            "amplitude = 1e300, window",
            "field `source.0.signal.amplitude` = 1e300: a number > 0 and <= 1e12",
        ),
        // a sliver of an aperture would make slivers of elements
        ("x1 = 1.4e-3", "x1 = 0.6000001e-3", "field `source.0.x1`"),
        // the elements resolve f0 at least; a gate holds a period of it at least
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\nharmonic = 1e-9",
            "field `model.harmonic` = 1e-9: a finite number >= 1",
        ),
        (
            "at = [1e-3, 1e-3]",
            "at = [1e-3, 1e-3]\n[analysis]\ngate = [0.2e-6, 0.2000001e-6]",
            "field `analysis.gate`",
        ),
        // a pre-stress that is not a number names its own key, not the crack's
        (
            "element_size = 0.1e-3",
            "element_size = 0.1e-3\nprestress = { zz = nan }",
            "field `model.prestress.zz` = NaN",
        ),
        // a receiver at NaN names `at` (NaN equals nothing, not even itself)
        (
            "at = [1e-3, 1e-3]",
            "at = [nan, 1e-3]",
            "field `receiver.1.at`",
        ),
        // a law given as a name, not a table: what it takes, in plain words
        (
            "tangential = { law = \"coulomb\", friction = 0.3 }",
            "tangential = { law = \"coulomb\", friction = 0.3 }\ntraction = \"free\"",
            "expected a table naming its law",
        ),
        // absorbing layers in mm given in m: a mesh beyond the budget names their key
        (
            "duration = 0.6e-6",
            "duration = 0.6e-6\nsides = \"absorbing\"\npml_thickness = 100.0",
            "field `model.pml_thickness` = 100: needs about",
        ),
    ];
    for (from, to, key) in cases {
        assert!(SMALL.contains(from), "{from}");
        let text = SMALL.replace(from, to);
        let err = model::from_toml_str(&text, "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(key), "{key}: {err}");
        assert!(err.starts_with("bad.toml"), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

/// A far-field pre-stress sets each crack's static state by its traction on the crack's
/// line: `prestress = { zz = -p, xz = q }` on a horizontal crack is `static_pressure = p`,
/// `static_shear = q` (the same bits), and `xx` is what a vertical crack feels (a tension
/// along z does not open it).
#[test]
fn a_prestress_is_the_static_state_it_puts_on_each_crack() {
    let run = |text: &str| {
        model::from_toml_str(text, "p.toml")
            .unwrap()
            .base()
            .unwrap()
            .run(&RunControl::default())
            .unwrap()
            .summary()
            .clone()
    };
    let own = SMALL.replace(
        "static_pressure = 0.2e6",
        "static_pressure = 0.2e6\nstatic_shear = 0.03e6",
    );
    let pre = SMALL.replace("static_pressure = 0.2e6\n", "").replace(
        "element_size = 0.1e-3",
        "element_size = 0.1e-3\nprestress = { zz = -0.2e6, xz = 0.03e6, xx = 5e6 }",
    );
    assert_ne!(pre, SMALL);
    let (a, b) = (run(&own), run(&pre));
    for key in [
        "crack_max_gap_0",
        "crack_max_slip_0",
        "top_A1",
        "under_A2_over_A1",
    ] {
        assert_eq!(a.get(key), b.get(key), "{key}");
    }
    // a vertical crack feels sigma_xx (compressive here) and not the tension along z
    let vertical = pre.replace(
        "start = [0.7e-3, 0.5e-3]\nend = [1.3e-3, 0.5e-3]",
        "start = [1e-3, 0.2e-3]\nend = [1e-3, 0.8e-3]",
    );
    let text = vertical
        .replace("xx = 5e6", "xx = -1e6")
        .replace("zz = -0.2e6", "zz = 3e6");
    assert!(run(&text).get("crack_max_gap_0").is_some());
    let open = vertical.replace("xx = 5e6", "xx = 1e6");
    let err = model::from_toml_str(&open, "p.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("model.prestress") && err.contains("crack.0"),
        "{err}"
    );
}

/// `model.backend`: a name other than `cpu` or `gpu` is refused; `gpu` is refused by a
/// build without the feature `gpu` when the file is read, naming the key (a build with it
/// takes every 2D scenario: its device errors are the GPU tests' business).
#[test]
fn the_backend_key_is_checked() {
    let with =
        |extra: &str| SMALL.replace("duration = 0.6e-6", &format!("duration = 0.6e-6\n{extra}"));
    let err = model::from_toml_str(&with("backend = \"tpu\""), "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("model.backend") && err.contains("`cpu` or `gpu`"),
        "{err}"
    );
    if contactwave::solver::solid_2d::Backend::GPU_BUILT {
        return;
    }
    let err = model::from_toml_str(&with("backend = \"gpu\""), "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("bad.toml: field `model.backend` = gpu") && err.contains("--features gpu"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// The receivers' summary of `SMALL` run for 1.2 us with `[analysis]` `extra` and the
/// crack's static pressure `p0` (Pa).
fn methods_summary(p0: f64, extra: &str) -> contactwave::Result<contactwave::analysis::Summary> {
    let text = SMALL
        .replace("duration = 0.6e-6", "duration = 1.5e-6")
        .replace("cycles = 2,", "cycles = 4,")
        .replace(
            "static_pressure = 0.2e6",
            &format!("static_pressure = {p0:e}"),
        )
        + "\n[analysis]\n"
        + extra;
    let t = model::from_toml_str(&text, "methods.toml")?;
    let outcome = t.base()?.run(&RunControl::default())?;
    Ok(outcome.summary().clone())
}

#[test]
fn analysis_methods_reach_the_receivers() {
    let get = |s: &contactwave::analysis::Summary, k: &str| s.get(k).unwrap_or(f64::NAN);
    // a crack that opens over part of each cycle: every method sees its second harmonic,
    // and the fundamental is the same to a few per cent whether it comes from one run or
    // from the difference of two
    let band = methods_summary(5e6, "method = \"band_peak\"").unwrap();
    let pi = methods_summary(5e6, "method = \"pulse_inversion\"").unwrap();
    let lr = methods_summary(5e6, "method = \"linear_reference\"").unwrap();
    assert_eq!(get(&pi, "analysis_method"), 1.0);
    for s in [&band, &pi, &lr] {
        assert!(get(s, "under_A2_over_A1") > 1e-3, "{s:?}");
    }
    let a1 = get(&band, "under_A1");
    let e1 = (get(&pi, "under_A1") / a1 - 1.0).abs();
    // measured: A1 0.960 (band peak, linear reference) and 0.918 (pulse inversion); A2/A1
    // 0.513, 0.522 and 0.513
    assert!(e1 < 0.06, "{e1}");
    let r2 = get(&band, "under_A2_over_A1");
    assert!(
        (get(&pi, "under_A2_over_A1") / r2 - 1.0).abs() < 0.05,
        "{pi:?}"
    );
    assert!(
        (get(&lr, "under_A2_over_A1") / r2 - 1.0).abs() < 0.05,
        "{lr:?}"
    );
    assert_eq!(get(&lr, "under_A1"), a1);
    // a crack held shut far beyond the wave's stress is linear: the pulse-inversion sum
    // and the residual against the bonded crack vanish (the contact update does not
    // chatter), while a band peak still sees the burst's own leakage
    for m in ["pulse_inversion", "linear_reference"] {
        let s = methods_summary(1e9, &format!("method = \"{m}\"")).unwrap();
        assert_eq!(get(&s, "crack_max_gap_0"), 0.0);
        let r = get(&s, "under_A2_over_A1");
        assert!(r < 1e-9, "{m}: A2/A1 = {r:e}");
    }
    // a gate and plateau fit over it
    let pf = methods_summary(
        0.2e6,
        "method = \"plateau_fit\"\ngate = [0.2e-6, 1.0e-6]\ntaper = 0.1e-6",
    )
    .unwrap();
    assert!(
        get(&pf, "under_A1").is_finite() && get(&pf, "under_A1") > 0.0,
        "{pf:?}"
    );
    // bad input names the key
    for (extra, key) in [
        ("method = \"plateau_fit\"", "analysis.gate"),
        ("gate = [1e-6, 0.5e-6]", "analysis.gate"),
        ("gate = [0.0, 2e-6]", "analysis.gate"),
        ("gate = [0.0, 1e-6]\ntaper = 0.6e-6", "analysis.taper"),
        ("taper = 1e-7", "analysis.taper"),
        ("method = \"nope\"", "analysis.method"),
    ] {
        let err = methods_summary(0.2e6, extra).unwrap_err().to_string();
        assert!(err.contains(key), "{extra}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
}

/// The crack's records of `SMALL` (1 us) with its `static_pressure` line replaced by
/// `closure`: `(position, normal gap, normal stress, state)` per node and record.
fn crack_rows(closure: &str) -> contactwave::Result<Vec<(f64, f64, f64, f64)>> {
    let text = SMALL
        .replace("duration = 0.6e-6", "duration = 1.0e-6")
        .replace("static_pressure = 0.2e6", closure);
    let t = model::from_toml_str(&text, "closure.toml")?;
    let outcome = t.base()?.run(&RunControl::default())?;
    let files = outcome.files()?;
    let crack = files.iter().find(|f| f.name == "crack.csv").unwrap();
    Ok(crack
        .contents
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[2], v[3], v[5], v[8])
        })
        .collect())
}

#[test]
fn a_closure_table_sets_the_static_state_along_the_crack() {
    // a table of one constant value is the uniform closure, bit for bit
    let uniform = crack_rows("static_pressure = 0.2e6").unwrap();
    let table =
        crack_rows("closure = { position = [0.0, 0.6e-3], pressure = [0.2e6, 0.2e6] }").unwrap();
    assert_eq!(uniform, table);
    // pressure rising along the crack from 0 to 100 MPa (ten times the burst): the crack
    // opens only on its low-pressure side, and never penetrates
    let ramp =
        crack_rows("closure = { position = [0.0, 0.6e-3], pressure = [0.0, 100e6] }").unwrap();
    let opened = |rows: &[(f64, f64, f64, f64)], a: f64, b: f64| {
        rows.iter()
            .filter(|r| (a..=b).contains(&r.0))
            .fold(0.0f64, |m, r| m.max(r.1))
    };
    assert!(opened(&ramp, 0.0, 0.1e-3) > 0.0);
    assert_eq!(opened(&ramp, 0.3e-3, 0.6e-3), 0.0);
    assert!(ramp.iter().all(|r| r.1 >= 0.0));
    // an initial gap wider than the wave's motion: the faces never touch, so no stress,
    // and the gap stays open everywhere
    let open = crack_rows("closure = { position = [0.0], gap = [1e-6] }").unwrap();
    assert!(
        open.iter().all(|r| r.1 > 0.0 && r.2 == 0.0),
        "{:?}",
        &open[..3]
    );
    // a gap must sit where nothing presses
    for (closure, key) in [
        (
            "closure = { position = [0.0, 0.6e-3], pressure = [1e6, 0.0], gap = [0.0, 1e-9] }",
            "crack.0.closure.gap",
        ),
        (
            "closure = { position = [0.5e-3, 0.1e-3] }",
            "crack.0.closure.position",
        ),
        (
            "closure = { position = [0.0, 0.7e-3] }",
            "crack.0.closure.position",
        ),
        (
            "closure = { position = [0.0], pressure = [-1.0] }",
            "crack.0.closure.pressure",
        ),
        (
            "closure = { position = [0.0, 0.1e-3], shear = [0.0] }",
            "crack.0.closure.shear",
        ),
        (
            "static_pressure = 1e6\nclosure = { position = [0.0], pressure = [1e6] }",
            "crack.0.static_pressure",
        ),
    ] {
        let err = crack_rows(closure).unwrap_err().to_string();
        assert!(err.contains(key), "{closure}: {err}");
    }
}

#[test]
fn stress_and_line_receivers_see_a_plane_p_wave() {
    // a plane P wave down a periodic strip: sigma_zz = -rho c_P v_z and sigma_xx = lambda /
    // (lambda + 2 mu) sigma_zz (tension positive); a line of receivers across the strip
    // records the same trace at every point
    let text = r#"
[model]
kind = "solid_2d"
width = 0.5e-3
duration = 0.8e-6
sides = "periodic"
bottom = "absorbing"

[[layer]]
thickness = 4e-3
p_speed = 6000.0
s_speed = 3000.0
density = 2000.0

[[source]]
x0 = 0.0
x1 = 0.5e-3
signal = { frequency = 5e6, cycles = 2, amplitude = 1e6, window = "hann" }

[[receiver]]
name = "v"
at = [0.25e-3, 1.5e-3]

[[receiver]]
name = "s"
at = [0.25e-3, 1.5e-3]
quantity = "stress"

[[receiver]]
name = "line"
at = [0.0, 1.5e-3]
to = [0.5e-3, 1.5e-3]
count = 3
"#;
    let t = model::from_toml_str(text, "plane.toml").unwrap();
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let r = outcome.record();
    let (Some(Value::Rows(v)), Some(Value::Rows(st))) = (r.get("receivers"), r.get("stresses"))
    else {
        panic!("rows")
    };
    assert_eq!(v.len(), 2 * 4); // v and line_0..2, two components each
    assert_eq!(st.len(), 3);
    let (vz, szz, sxx) = (&v[1], &st[1], &st[0]);
    let peak = |x: &[f64]| x.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let z = 2000.0 * 6000.0;
    let err = vz
        .iter()
        .zip(szz)
        .map(|(a, b)| (b + z * a).abs())
        .fold(0.0f64, f64::max)
        / peak(szz);
    assert!(peak(szz) > 0.5e6, "{}", peak(szz));
    // measured 3.3e-4 and 6e-15
    assert!(err < 2e-3, "sigma_zz + rho c v_z: {err:.3e} of the peak");
    let (lambda, m) = (2000.0 * (36e6 - 2.0 * 9e6), 2000.0 * 36e6);
    let err_xx = sxx
        .iter()
        .zip(szz)
        .map(|(a, b)| (a - lambda / m * b).abs())
        .fold(0.0f64, f64::max)
        / peak(szz);
    assert!(err_xx < 1e-12, "sigma_xx: {err_xx:.3e}");
    for k in 1..3 {
        let d = v[2 * k + 1]
            .iter()
            .zip(&v[7])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        assert!(d < 1e-9 * peak(vz), "line point {k}: {d:e}");
    }
    let files = outcome.files().unwrap();
    assert!(files[1].contents.starts_with(
        "t,v_vx,v_vz,line_0_vx,line_0_vz,line_1_vx,line_1_vz,line_2_vx,line_2_vz,s_sxx,s_szz,s_sxz\n"
    ));
    for key in ["s_A1", "line_2_A1", "v_A1"] {
        assert!(outcome.summary().get(key).is_some_and(|a| a > 0.0), "{key}");
    }
}

/// A vertical crack from the free top surface (surface-breaking, model.md 15.2) runs and
/// closes its energy; the same crack under an absorbing top is refused naming its start.
#[test]
fn a_surface_breaking_crack_runs_and_is_refused_under_an_absorbing_top() {
    let crack = "start = [0.7e-3, 0.5e-3]\nend = [1.3e-3, 0.5e-3]";
    assert!(SMALL.contains(crack));
    let text = SMALL.replace(crack, "start = [1.5e-3, 0.0]\nend = [1.5e-3, 0.5e-3]");
    let t = model::from_toml_str(&text, "mouth.toml").unwrap();
    let outcome = t.base().unwrap().run(&RunControl::default()).unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
    assert!(s.get("crack_max_gap_0").unwrap() > 0.0, "{s:?}");
    let absorbing = text.replace(
        "duration = 0.6e-6",
        "duration = 0.6e-6\ntop = \"absorbing\"\npml_thickness = 0.3e-3",
    );
    let err = model::from_toml_str(&absorbing, "bad.toml")
        .and_then(|t| t.base().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(err.contains("crack.0.start"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// An inclined crack is refused first, with what cracks can be: before the checks of its
/// position, static shear or closure table, which read it as a vertical crack (a crack
/// reaching the top surface got "only a vertical crack may end there", a static shear got
/// the friction limit).
#[test]
fn an_inclined_crack_is_said_to_be_one_first() {
    let end = "end = [1.3e-3, 0.5e-3]";
    assert!(SMALL.contains(end));
    for (what, replace) in [
        ("inclined", "end = [1.3e-3, 0.6e-3]"),
        ("to the top surface", "end = [1.3e-3, 0.0]"),
        ("out of the plate", "end = [3e-3, 2e-3]"),
        (
            "beyond the friction limit",
            "end = [1.3e-3, 0.6e-3]\nstatic_shear = 1e6",
        ),
        (
            "with a closure table",
            "end = [1.3e-3, 0.6e-3]\nclosure = { position = [0.0, 1e-3], pressure = [0.1e6, 0.2e6] }",
        ),
    ] {
        let text = SMALL.replace(end, replace);
        let err = model::from_toml_str(&text, "inclined.toml")
            .and_then(|t| t.base().map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("inclined.toml: field `crack.0.end`")
                && err.contains("cracks are horizontal or vertical"),
            "{what}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    // a later crack is named by its own index, before the first crack's other checks
    let text = SMALL.replace("static_pressure = 0.2e6", "static_pressure = -1.0")
        + "\n[[crack]]\nstart = [0.2e-3, 0.2e-3]\nend = [0.4e-3, 0.3e-3]\n";
    let err = run_error(&text, "two.toml");
    assert!(
        err.starts_with("two.toml: field `crack.1.end`") && err.contains("horizontal or vertical"),
        "{err}"
    );
    // horizontal and vertical cracks still pass this check
    for ok in ["end = [1.3e-3, 0.5e-3]", "end = [0.7e-3, 0.8e-3]"] {
        let text = SMALL.replace(end, ok);
        assert!(
            model::from_toml_str(&text, "ok.toml")
                .and_then(|t| t.base().map(|_| ()))
                .is_ok(),
            "{ok}"
        );
    }
}

/// An end within a millionth of an element of the start is merged with it (one element
/// edge): a crack with no node to split is refused when the mesh is built, not read as a
/// crack from another edge (it once became one from x = 0).
#[test]
fn a_crack_end_merged_with_its_start_is_refused() {
    for end in ["0.70000000001e-3", "0.69999999999e-3"] {
        let text = SMALL.replace("end = [1.3e-3, 0.5e-3]", &format!("end = [{end}, 0.5e-3]"));
        let err = run_error(&text, "short.toml");
        assert!(
            err.starts_with("short.toml: field `crack.0.length`"),
            "{end}: {err}"
        );
    }
}

/// A run whose records exceed the memory budget because of the scenario's own
/// `time_step` names that key (not `model.duration`), and nothing else is printed first.
#[test]
fn a_time_step_that_makes_the_records_too_large_is_named() {
    let text = SMALL.replace(
        "element_size = 0.1e-3",
        "element_size = 0.1e-3\ntime_step = 1e-16",
    );
    let err = run_error(&text, "tiny_step.toml");
    assert!(
        err.starts_with("tiny_step.toml: field `model.time_step` = 1e-16: needs about"),
        "{err}"
    );
    assert!(err.contains("raise `model.time_step`"), "{err}");
}

/// A run that ends before its source's burst does is warned about (its harmonics are those
/// of a cut burst), and a run that holds the burst is not.
#[test]
fn a_duration_shorter_than_the_burst_is_warned_about() {
    let fields = |duration: &str| -> Vec<String> {
        let text = SMALL.replace("duration = 0.6e-6", &format!("duration = {duration}"));
        let m = model::from_toml_str(&text, "short.toml")
            .unwrap()
            .base()
            .unwrap();
        m.warnings().into_iter().map(|w| w.field).collect()
    };
    // the burst: 2 cycles at 10 MHz, 0.2 us
    assert!(fields("0.1e-6").contains(&"model.duration".to_string()));
    assert!(!fields("0.6e-6").contains(&"model.duration".to_string()));
}

/// A snapshot interval below its bound (the run's duration over 2000 frames) names the
/// bound as it can be typed: 2e-9 s, not the quotient's 1.9999999999999997e-9.
#[test]
fn the_snapshot_interval_bound_is_shown_as_typed() {
    let text =
        SMALL.replace("duration = 0.6e-6", "duration = 4e-6") + "\n[snapshots]\nevery = 1e-12\n";
    let err = model::from_toml_str(&text, "snap.toml")
        .and_then(|t| t.base().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("field `snapshots.every` = 1e-12: an interval in [2e-9, 4e-6] s"),
        "{err}"
    );
    // and 2e-9 itself is allowed
    let ok =
        SMALL.replace("duration = 0.6e-6", "duration = 4e-6") + "\n[snapshots]\nevery = 2e-9\n";
    assert!(model::from_toml_str(&ok, "snap.toml")
        .and_then(|t| t.base().map(|_| ()))
        .is_ok());
}

/// The one-line error of running the scenario `text` (named `file`), which must fail.
fn run_error(text: &str, file: &str) -> String {
    model::from_toml_str(text, file)
        .and_then(|t| t.base())
        .and_then(|b| b.run(&RunControl::default()))
        .map(|_| ())
        .unwrap_err()
        .to_string()
}

/// Issue 56 item 4: every 2D receiver gets its analysis floor (`<name>_A<n>_floor`, the
/// method on its fundamental alone) and the floor flag; a `[[receiver]]` gate of its own
/// (receivers before and after a crack see the wave at different times) replaces the
/// analysis' for that receiver only; and each receiver's position is the node it records
/// at, in summary.json.
#[test]
fn each_receiver_has_its_floor_gate_and_position() {
    let gated = SMALL.replace(
        "name = \"under\"\nat = [1e-3, 1e-3]",
        "name = \"under\"\nat = [1.03e-3, 1e-3]\ngate = [0.1e-6, 0.6e-6]\ntaper = 0.05e-6",
    );
    assert_ne!(gated, SMALL);
    let run = |text: &str| {
        let t = model::from_toml_str(text, "small.toml").unwrap();
        t.base().unwrap().run(&RunControl::default()).unwrap()
    };
    let (plain, own) = (run(SMALL), run(&gated));
    let (p, o) = (plain.summary(), own.summary());
    for n in 2..=5 {
        for name in ["top", "under"] {
            let f = o.get(&format!("{name}_A{n}_floor")).unwrap();
            assert!(f.is_finite() && f >= 0.0, "{name} A{n} floor {f}");
        }
    }
    assert!(o.get("under_harmonic_floor_warning").is_some());
    // the gate changes the gated receiver's harmonics, not the other's
    assert_eq!(p.get("top_A2"), o.get("top_A2"));
    assert_ne!(p.get("under_A1"), o.get("under_A1"));
    // the node it records at: on the mesh, not the position asked for, and within half an
    // element of it
    let x = o.get("under_x").unwrap();
    assert!(x != 1.03e-3 && (x - 1.03e-3).abs() < 0.05e-3, "{x}");
    assert_eq!(o.get("under_z"), Some(1e-3));
    assert!(
        own.report()
            .iter()
            .any(|l| l.contains("record at the node nearest")),
        "{:?}",
        own.report()
    );
    // a bad gate names the receiver's key
    let bad = gated.replace("gate = [0.1e-6, 0.6e-6]", "gate = [0.5e-6, 0.2e-6]");
    let e = model::from_toml_str(&bad, "small.toml")
        .and_then(|t| t.base().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("receiver.1.gate"), "{e}");
}

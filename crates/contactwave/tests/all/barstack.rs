//! Bar-stack model (issue 3): static step, Tribobrake FRF peaks, amplitude trends of
//! thesis chapter 4, bad input.

use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::{simulate_bar_stack, Error, FRF_FORCE_FLOOR_DB};
use std::path::Path;

fn tribobrake() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tribobrake.toml"),
    )
    .unwrap()
}

fn load(text: &str) -> Result<BarStackScenario, Error> {
    let table: toml::Table = text.parse().expect("toml");
    BarStackScenario::from_table(table, Path::new("tribobrake.toml"))
}

fn with(law: &str, peak: f64) -> String {
    let t = tribobrake().replace("peak = 32.0", &format!("peak = {peak:?}"));
    match law {
        "power" => t.replace("law = \"modified_power\"", "law = \"power\""),
        "linear" => t.replace(
            "{ law = \"modified_power\", c = 1.81e10, m = 0.35 }",
            "{ law = \"linear\", stiffness = 8.5e11 }",
        ),
        _ => t,
    }
}

/// The static step: the gravity load equals the interface pressure times the area.
#[test]
fn static_equilibrium_under_gravity() {
    let s = load(&tribobrake()).unwrap();
    let g = 9.81;
    let area = 1.15e-4;
    let m_sample = 2710.0 * 0.015 * area;
    assert!((s.static_pressure[0] * area - 1.61 * g).abs() < 1e-9 * 1.61 * g);
    assert!((s.static_pressure[1] * area - (1.61 + m_sample) * g).abs() < 1e-9 * 1.61 * g);
    assert!(
        (s.static_pressure[0] - 0.137e6).abs() < 0.001e6,
        "p0 = {}",
        s.static_pressure[0]
    );
}

/// FRF of the default Tribobrake example (modified power law, 32 N): mass-spring mode
/// between 780 and 900 Hz, its second harmonic at twice it, the guide mode near 11 kHz,
/// interfaces closed throughout.
#[test]
fn tribobrake_modes() {
    let r = simulate_bar_stack(&load(&tribobrake()).unwrap()).unwrap();
    let g = |k: &str| r.summary.get(k).unwrap();
    let f1 = g("first_mode_hz");
    assert!((780.0..=900.0).contains(&f1), "f1 = {f1}");
    // the ringing frequency drifts with amplitude: the harmonic peak is near, not at, 2 f1
    assert!(
        (g("second_harmonic_hz") / f1 - 2.0).abs() < 0.05,
        "{}",
        g("second_harmonic_hz")
    );
    assert!(
        g("A2_over_A1") > 1e-2,
        "a nonlinear law makes a second harmonic"
    );
    let fg = g("guide_mode_hz");
    assert!((10.0e3..=12.5e3).contains(&fg), "guide mode {fg}");
    // the H1 receptance peaks at the first mode (below the first zero of the pulse's
    // spectrum, 1.32 kHz): a sharp peak, the vibration keeps its frequency
    let k = (0..r.frf.frequency.len())
        .filter(|&k| r.frf.frequency[k] > 300.0 && r.frf.frequency[k] < 1250.0)
        .max_by(|&a, &b| r.frf.receptance[a].total_cmp(&r.frf.receptance[b]))
        .unwrap();
    assert!(
        (r.frf.frequency[k] / f1 - 1.0).abs() < 0.01,
        "FRF peak {} Hz vs first mode {f1} Hz",
        r.frf.frequency[k]
    );
    // thesis Figure 70: closed at 32 N, minimum contact pressure about 0.025 MPa
    let pmin = g("min_contact_pressure");
    assert!((0.02e6..=0.03e6).contains(&pmin), "min pressure {pmin}");
}

/// Issue 24: the FRF holds only where the force carries energy. Bins where the hammer's
/// spectrum is below FRF_FORCE_FLOOR_DB of its peak (around the zeros of the half-sine at
/// (2k+1)/(2 tau) = 1.32, 2.20, 3.08 kHz, and above its lobes) are masked (NaN), so the
/// largest receptance below 5 kHz is the first mode, not a division by almost nothing.
#[test]
fn frf_is_masked_where_the_force_has_no_energy() {
    let r = simulate_bar_stack(&load(&tribobrake()).unwrap()).unwrap();
    let f1 = r.summary.get("first_mode_hz").unwrap();
    let frf = &r.frf;
    let n = frf.frequency.len();
    let k = (0..n)
        .filter(|&k| frf.frequency[k] < 5e3 && !frf.receptance[k].is_nan())
        .max_by(|&a, &b| frf.receptance[a].total_cmp(&frf.receptance[b]))
        .unwrap();
    assert!(
        (frf.frequency[k] / f1 - 1.0).abs() < 0.01,
        "largest receptance below 5 kHz at {} Hz, first mode {f1} Hz",
        frf.frequency[k]
    );
    // the force level is the half-sine's spectrum re its peak (at 0 Hz):
    // |F(f) / F(0)| = |cos(pi f tau) / (1 - (2 f tau)^2)|
    let tau = 1.135e-3;
    let level = |f: f64| {
        let c = (std::f64::consts::PI * f * tau).cos() / (1.0 - (2.0 * f * tau).powi(2));
        20.0 * c.abs().log10()
    };
    let bin = |f: f64| {
        (0..n).min_by(|&a, &b| {
            (frf.frequency[a] - f)
                .abs()
                .total_cmp(&(frf.frequency[b] - f).abs())
        })
    };
    for f in [500.0, 1000.0, 1800.0, 2600.0] {
        let k = bin(f).unwrap();
        let want = level(frf.frequency[k]);
        assert!(
            (frf.force_db[k] - want).abs() < 0.1,
            "force level at {f} Hz: {} dB, half-sine {want} dB",
            frf.force_db[k]
        );
    }
    // masked exactly where the force is below the floor: all three FRF columns NaN
    for k in 0..n {
        let low = frf.force_db[k] < FRF_FORCE_FLOOR_DB || frf.force_db[k].is_nan();
        assert_eq!(low, frf.masked(k));
        for v in [frf.receptance[k], frf.phase[k], frf.accelerance[k]] {
            assert_eq!(low, v.is_nan(), "bin {} Hz", frf.frequency[k]);
        }
    }
    // the zeros of the half-sine are masked; the band ends below 5 kHz (the last lobe
    // above -40 dB is the one near 4.4 kHz: 1 / ((2 f tau)^2 - 1) = 1 / 99 at 2 f tau = 10)
    for j in [3.0, 5.0, 7.0] {
        let k = bin(j / (2.0 * tau)).unwrap();
        assert!(
            frf.receptance[k].is_nan(),
            "zero at {} Hz",
            frf.frequency[k]
        );
    }
    let top = frf.band_limit();
    assert!((4.0e3..5.0e3).contains(&top), "band limit {top} Hz");
}

/// A constant 8.5e11 Pa/m interface gives about 840 Hz and no second harmonic while the
/// interfaces stay closed.
#[test]
fn linear_interface_has_no_second_harmonic() {
    let r = simulate_bar_stack(&load(&with("linear", 9.0)).unwrap()).unwrap();
    let g = |k: &str| r.summary.get(k).unwrap();
    assert!(
        (800.0..=880.0).contains(&g("first_mode_hz")),
        "{}",
        g("first_mode_hz")
    );
    assert!(g("min_contact_pressure") > 0.0);
    assert!(g("A2_over_A1") < 1e-3, "A2/A1 = {}", g("A2_over_A1"));
    // the static step's gap: a linear spring closes by p0 / K under its pre-load
    let closure = g("static_interface_closure_0");
    let p0 = g("static_interface_pressure_0");
    assert!(
        (closure / (p0 / 8.5e11) - 1.0).abs() < 1e-12,
        "closure {closure}"
    );
    // the H1 receptance peaks at the first mode (below the first zero of the force
    // spectrum of the 1.135 ms half-sine, 1.3 kHz)
    let k = (0..r.frf.frequency.len())
        .filter(|&k| r.frf.frequency[k] > 300.0 && r.frf.frequency[k] < 1300.0)
        .max_by(|&a, &b| r.frf.receptance[a].total_cmp(&r.frf.receptance[b]))
        .unwrap();
    let f1 = g("first_mode_hz");
    assert!(
        (r.frf.frequency[k] - f1).abs() < 0.01 * f1,
        "FRF peak {} vs {f1}",
        r.frf.frequency[k]
    );
}

/// Thesis chapter 4: the first-mode frequency falls from 9 N to 32 N for both laws, more
/// with the modified power law; A2/A1 grows with the force.
#[test]
fn amplitude_trends_of_chapter_4() {
    let run = |law: &str, f: f64| {
        let r = simulate_bar_stack(&load(&with(law, f)).unwrap()).unwrap();
        (
            r.summary.get("first_mode_hz").unwrap(),
            r.summary.get("A2_over_A1").unwrap(),
        )
    };
    let (m9, ma9) = run("modified_power", 9.0);
    let (m32, ma32) = run("modified_power", 32.0);
    let (p9, pa9) = run("power", 9.0);
    let (p32, pa32) = run("power", 32.0);
    let drop_m = 1.0 - m32 / m9;
    let drop_p = 1.0 - p32 / p9;
    assert!(drop_m > 0.0 && drop_p > 0.0, "drops {drop_m} {drop_p}");
    assert!(drop_m > drop_p, "modified PL drop {drop_m} vs PL {drop_p}");
    assert!(ma32 > ma9 && pa32 > pa9);
}

/// Bad input: one error naming the field.
#[test]
fn bad_bar_stack_input() {
    let cases = [
        (
            tribobrake().replace("length = 0.015", "length = 0.0"),
            "segment.1.length",
        ),
        (
            tribobrake().replace(
                "between = [\"guide\", \"sample\"]",
                "between = [\"guide\", \"obstacle\"]",
            ),
            "interface.0.between",
        ),
        (
            tribobrake().replace("area = 1.15e-4", "area = -1.0"),
            "model.area",
        ),
        (
            tribobrake().replace("mass = 1.61", "mass = nan"),
            "segment.0.mass",
        ),
        (
            tribobrake().replace("last_end = \"obstacle\"", "last_end = \"wall\""),
            "model.last_end",
        ),
        // an obstacle interface that a free far end would leave unused
        (
            tribobrake().replace("last_end = \"obstacle\"", "last_end = \"free\""),
            "model.last_end",
        ),
    ];
    for (text, field) in cases {
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
    // a time step above the stability limit: the sample (0.015 m of aluminium, c = 5119
    // m/s) cannot hold one cell at Courant <= 1 for dt > 2.93e-6 s
    let text = tribobrake().replace("duration = 0.2", "duration = 0.2\ntime_step = 5e-6");
    let e = load(&text).unwrap_err().to_string();
    assert!(e.contains("model.time_step") && e.contains("sample"), "{e}");
    let ok = tribobrake().replace("duration = 0.2", "duration = 0.2\ntime_step = 2e-6");
    assert!(load(&ok).is_ok());
    // a force file with non-monotone time, or NaN
    let dir = std::env::temp_dir().join(format!("contactwave-force-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, body) in [
        (
            "backwards.csv",
            "time,force\n0,0\n1e-4,10\n5e-5,20\n2e-4,0\n",
        ),
        ("nan.csv", "time,force\n0,0\n1e-4,nan\n2e-4,0\n"),
    ] {
        std::fs::write(dir.join(name), body).unwrap();
        let text = tribobrake().replace(
            "kind = \"force_pulse\"",
            &format!(
                "kind = \"force_file\"\npath = \"{}\"",
                dir.join(name).display()
            ),
        );
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A probe in the guide sees the hammer's stress wave: before the first reflection comes
/// back, stress = -F(t - x/c)/S and velocity = -stress/Z (Courant 1: exact transport).
#[test]
fn probes_see_the_travelling_hammer_wave() {
    let text = tribobrake()
        .replace("duration = 1.135e-3", "duration = 1.0e-5")
        .replace("duration = 0.2 ", "duration = 0.001 ")
        + "\n[[probe]]\nname = \"mid\"\nx = 0.1\n";
    let s = load(&text).unwrap();
    let r = contactwave::simulate_bar_stack(&s).unwrap();
    let p = &r.probes[0];
    assert_eq!(p.name, "mid");
    let seg = &s.stack.segments[0];
    let c = seg.material.wave_speed();
    let z = seg.material.impedance();
    let area = s.stack.area;
    let peak = 32.0 / area;
    // window: after the front has passed and before the reflection from the far end of
    // the guide (and from the top) can come back
    let t_end = (2.0 * 0.229 - 0.1) / c;
    let (mut smin, mut vmax) = (0.0f64, 0.0f64);
    for (k, &t) in r.t.iter().enumerate() {
        if t < t_end {
            smin = smin.min(p.stress[k]);
            vmax = vmax.max(p.velocity[k].abs());
        }
    }
    assert!((-smin / peak - 1.0).abs() < 0.03, "stress {smin} vs {peak}");
    assert!(
        (vmax * z / peak - 1.0).abs() < 0.03,
        "velocity {vmax} vs {}",
        peak / z
    );
    // interface histories: beta stays 1 (free traction), stiffness is the law's tangent
    assert!(r.beta[0].iter().all(|b| *b == 1.0));
    assert!(r.stiffness[0].iter().all(|k| k.is_finite() && *k >= 0.0));
    // a probe outside the stack is an error naming the field
    let bad = tribobrake() + "\n[[probe]]\nname = \"out\"\nx = 1.0\n";
    let e = load(&bad).unwrap_err().to_string();
    assert!(e.contains("probe.0.x"), "{e}");
}

/// Imposed displacement of the first end (thesis eq. 2.39): the guide carries the wave
/// u = f(t - x/c) unchanged (Courant 1), with stress -Z f' and the end's reaction S Z f'.
#[test]
fn imposed_displacement_drives_a_travelling_wave() {
    let (d, tau) = (1e-7, 1e-5);
    let text = tribobrake()
        .replace("kind = \"force_pulse\"", "kind = \"displacement_pulse\"")
        .replace("peak = 32.0", &format!("peak = {d:e}"))
        .replace("duration = 1.135e-3", &format!("duration = {tau:e}"))
        .replace("duration = 0.2 ", "duration = 0.001 ")
        + "\n[[probe]]\nname = \"mid\"\nx = 0.1\n";
    let s = load(&text).unwrap();
    let r = contactwave::simulate_bar_stack(&s).unwrap();
    let seg = &s.stack.segments[0];
    let (c, z) = (seg.material.wave_speed(), seg.material.impedance());
    let v_peak = d * std::f64::consts::PI / tau;
    let t_end = (2.0 * 0.229 - 0.1) / c;
    let p = &r.probes[0];
    let (mut umax, mut smax) = (0.0f64, 0.0f64);
    for (k, &t) in r.t.iter().enumerate() {
        if t < t_end {
            umax = umax.max(p.displacement[k]);
            smax = smax.max(p.stress[k].abs());
        }
    }
    assert!((umax / d - 1.0).abs() < 0.01, "displacement {umax} vs {d}");
    assert!(
        (smax / (z * v_peak) - 1.0).abs() < 0.03,
        "stress {smax} vs {}",
        z * v_peak
    );
    // the driven node follows the imposed history exactly
    let k = r.t.iter().position(|&t| t >= 0.5 * tau).unwrap();
    let f = d * (std::f64::consts::PI * r.t[k] / tau).sin();
    assert!(
        (r.displacement[k] - f).abs() < 1e-12 * d.max(1.0),
        "{} vs {f}",
        r.displacement[k]
    );
    // the end's reaction before the first echo returns (a held end doubles the echo)
    let fmax =
        r.t.iter()
            .zip(&r.force)
            .filter(|(t, _)| **t < 2.0 * 0.229 / c)
            .fold(0.0f64, |m, (_, f)| m.max(f.abs()));
    let expect = s.stack.area * z * v_peak;
    assert!(
        (fmax / expect - 1.0).abs() < 0.05,
        "reaction {fmax} vs {expect}"
    );
    // an imposed displacement needs a free first end
    let bad = text.replace("first_end = \"free\"", "first_end = \"fixed\"");
    let e = load(&bad).unwrap_err().to_string();
    assert!(e.contains("model.first_end"), "{e}");
}

/// Long runs report progress: the callback sees the steps advance to the end.
#[test]
fn bar_stack_runs_report_progress() {
    let text = tribobrake().replace("duration = 0.2 ", "duration = 0.02 ");
    let s = load(&text).unwrap();
    let seen = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let sink = seen.clone();
    let p = contactwave::solver::bar_stack::StepProgress(std::sync::Arc::new(
        move |done: usize, total: usize| sink.lock().unwrap().push((done, total)),
    ));
    let r = contactwave::simulate_bar_stack_with_progress(&s, Some(p)).unwrap();
    let seen = seen.lock().unwrap();
    let total = seen[0].1;
    assert!(total >= r.t.len() - 1, "{total} {}", r.t.len());
    assert!(seen.len() >= total / 4096 && seen.windows(2).all(|w| w[1].0 > w[0].0));
    assert!(seen.last().unwrap().0 + 4096 > total);
}

/// Without damping the Tribobrake's mass-spring vibration keeps its amplitude with the
/// default `average` interface update (no numerical dissipation), so the first mode of the
/// nonlinear law is converged at the default mesh; the thesis' `backward` update damps it
/// numerically (model.md section 9.2).
#[test]
fn undamped_vibration_keeps_its_amplitude() {
    let run = |law: &str, settings: &str| {
        let text = with(law, 9.0).replace(
            "duration = 0.2 ",
            &format!("duration = 0.1\n{settings}\n# "),
        );
        simulate_bar_stack(&load(&text).unwrap()).unwrap()
    };
    let amplitude_ratio = |r: &contactwave::BarStackResult| {
        let p = &r.pressure[0];
        let swing = |a: f64| {
            let w: Vec<f64> =
                r.t.iter()
                    .zip(p)
                    .filter(|(t, _)| **t >= a && **t < a + 0.01)
                    .map(|(_, v)| *v)
                    .collect();
            let max = w.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let min = w.iter().cloned().fold(f64::INFINITY, f64::min);
            max - min
        };
        swing(0.089) / swing(0.01)
    };
    let avg = amplitude_ratio(&run("linear", ""));
    assert!((avg - 1.0).abs() < 0.01, "average: amplitude ratio {avg}");
    let bwd = amplitude_ratio(&run("linear", "interface_update = \"backward\""));
    assert!(bwd < 0.8, "backward: amplitude ratio {bwd}");
    let f1 = |settings: &str| {
        run("modified_power", settings)
            .summary
            .get("first_mode_hz")
            .unwrap()
    };
    let (coarse, fine) = (f1(""), f1("cell_size = 1.875e-3"));
    assert!(
        (coarse / fine - 1.0).abs() < 2e-3,
        "first mode {coarse} Hz at the default mesh, {fine} Hz at half the cell size"
    );
}

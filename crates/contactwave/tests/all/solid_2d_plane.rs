//! The 1D-reduction example (`examples/solid_2d/interface_reduction.toml`), shortened: a
//! full-width RCCM interface under a plane P wave injected by total-field/scattered-field
//! reproduces the exact half-space solver's max gap, and the energy closes. The 1D
//! half-spaces take the 2D preset's P-wave modulus `E (1 - nu) / ((1 + nu) (1 - 2 nu))`
//! (E = 71 GPa, nu = 0.33: 1.05197e11 Pa, c_P = 6230.4 m/s) as their Young's modulus.

use crate::common::crack_rows;
use contactwave::excitation::{Excitation, ToneBurst, Window};
use contactwave::model::{self, RunControl};

const ONE_D: &str = r#"
[medium]
material = "aluminium"
youngs_modulus = 1.05197e11
[counterpart]
kind = "medium"
material = "aluminium"
youngs_modulus = 1.05197e11
[interface]
static_pressure = 0.3e6
compression = { law = "rigid" }
traction = { law = "rccm", stiffness = 2e13, energy = 0.01, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 5
window = "hann"
amplitude = 3e6
"#;

/// The text of `examples/solid_2d/interface_reduction.toml`.
fn reduction_example() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/solid_2d/interface_reduction.toml"
    );
    std::fs::read_to_string(path).unwrap()
}

#[test]
fn interface_reduction_example_matches_the_exact_solver() {
    let text = reduction_example();
    // shortened: the gap's history ends within 8 us
    let short = text.replace("duration = 11e-6", "duration = 8e-6");
    assert_ne!(short, text, "the example's duration line changed");
    let two_d = model::from_toml_str(&short, "interface_reduction.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s2 = two_d.summary();
    eprintln!("{s2:?}");
    assert!(s2.get("energy_closure_error").unwrap() < 1e-9, "{s2:?}");
    let one_d = model::from_toml_str(ONE_D, "one_d.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s1 = one_d.summary();
    eprintln!("{s1:?}");
    let (g2, g1) = (
        s2.get("crack_max_gap_0").unwrap(),
        s1.get("max_gap").unwrap(),
    );
    eprintln!(
        "max gap 2D {g2:e}, exact {g1:e}, error {:.2e}",
        g2 / g1 - 1.0
    );
    // measured +0.10% (+0.37% at 0.5 mm, +0.04% at 0.125 mm: docs/model.md table 15.8-3)
    assert!((g2 / g1 - 1.0).abs() < 5e-3, "2D {g2:e} exact {g1:e}");
    // the bond is damaged (beta falls), as in the exact solution
    let (b2, b1) = (
        s2.get("crack_min_adhesion_0").unwrap(),
        s1.get("beta_end").unwrap(),
    );
    eprintln!("adhesion 2D {b2}, exact {b1}");
    assert!(b1 < 0.99 && (b2 - b1).abs() < 5e-3, "2D {b2} exact {b1}");
    // the reflected wave's A2/A1 (the 2D receiver in the scattered-field region)
    let (r2, r1) = (
        s2.get("reflected_A2_over_A1").unwrap(),
        s1.get("A2_over_A1").unwrap(),
    );
    eprintln!("reflected A2/A1 2D {r2}, exact {r1}");
    assert!((r2 / r1 - 1.0).abs() < 0.01, "2D {r2} exact {r1}");
}

/// A plane wave's type may be written in any case (`"p"`, `"Sv"`); a type the run does
/// not carry stays an error whatever its case.
#[test]
fn plane_wave_types_may_be_written_in_any_case() {
    let text = reduction_example();
    assert!(text.contains("wave = \"P\" "));
    for name in ["p", "sv", "Sv"] {
        let text = text.replace("wave = \"P\" ", &format!("wave = \"{name}\" "));
        let built = model::from_toml_str(&text, "case.toml").and_then(|t| t.base().map(|_| ()));
        assert!(built.is_ok(), "{name}: {built:?}");
    }
    let text = text.replace("wave = \"P\" ", "wave = \"sh\" ");
    let err = model::from_toml_str(&text, "case.toml")
        .and_then(|t| t.base().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(err.contains("source.0.wave") && err.contains("sh"), "{err}");
}

/// A bad plane-wave source is a one-line error naming its key, before any step.
#[test]
fn bad_plane_wave_sources_are_errors_naming_the_key() {
    let text = reduction_example();
    for (from, to, key) in [
        ("wave = \"P\" ", "wave = \"SH\" ", "source.0.wave"),
        ("angle = 0 ", "angle = 10 ", "source.0.angle"),
        ("z = 6e-3 ", "z = 16e-3 ", "source.0.z"),
        ("z = 6e-3 ", "z = 40e-3 ", "source.0.z"),
        ("z = 6e-3 ", "# ", "source.0.z"),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = text.replace(from, to);
        let err = model::from_toml_str(&bad, "bad.toml")
            .and_then(|t| t.base()?.run(&RunControl::default()).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(err.contains(key), "{key}: {err}");
        assert!(err.starts_with("bad.toml"), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

/// A plane wave at normal incidence on a full-width interface of a periodic strip moves
/// every node of it alike, through the bond's damage and the clapping after it: the whole
/// example (11 us; the bond breaks near 4 us), its crack fields uniform across the width at
/// every record, one contact state a record, and the crack's energy at least the damage it
/// tallies (what the interface takes is damage plus what it stores and loses at impacts).
/// Before a spring's stress stopped being averaged with a rigid contact's reaction
/// (model.md section 9.2), a mode of the element's period grew here from round-off to
/// 1.2 MPa between neighbouring nodes, open and closed side by side.
#[test]
fn a_full_width_interface_stays_uniform_after_its_bond_breaks() {
    let outcome = model::from_toml_str(&reduction_example(), "interface_reduction.toml")
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s = outcome.summary();
    assert!(s.get("crack_min_adhesion_0").unwrap() < 0.1, "{s:?}");
    let stress = crack_rows(outcome.as_ref(), "normal_stress");
    let state = crack_rows(outcome.as_ref(), "state");
    let gap = crack_rows(outcome.as_ref(), "normal_gap");
    let (n_points, n_records) = (stress.len(), stress[0].len());
    assert!(n_points > 10 && n_records > 1000);
    let mut worst = 0.0f64;
    for k in 0..n_records {
        let column = |f: &Vec<Vec<f64>>| (0..n_points).map(|i| f[i][k]).collect::<Vec<f64>>();
        let (sk, stk, gk) = (column(&stress), column(&state), column(&gap));
        let spread = |v: &[f64]| {
            v.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
                - v.iter().cloned().fold(f64::INFINITY, f64::min)
        };
        worst = worst.max(spread(&sk));
        assert!(
            stk.iter().all(|&x| x == stk[0]),
            "record {k}: states {stk:?}"
        );
        assert!(spread(&gk) <= 1e-9 * 9.2e-8, "record {k}: gaps {gk:?}");
    }
    eprintln!("largest stress spread along the interface {worst:e} Pa");
    // measured 1.9e-6 Pa (3 MPa wave, 0.3 MPa closure)
    assert!(worst < 1.0, "{worst:e} Pa");
    let (cracks, damage) = (
        s.get("energy_cracks").unwrap(),
        s.get("energy_damage").unwrap(),
    );
    eprintln!("crack energy {cracks:e}, damage {damage:e} J/m");
    assert!(damage > 0.0 && cracks >= damage, "{cracks:e} {damage:e}");
}

/// A compliant compression branch still presses its faces at a positive gap from rest: a
/// point is open (state 0) only beyond the law's contact-loss gap, where it carries no
/// compression. A quadratic law under 1 MPa closure (contact lost at 1.1e-8 m), a wave
/// that does not open it: closed everywhere, every record; shaken harder it opens, and
/// every open point carries no compression.
#[test]
fn a_compliant_crack_is_open_only_beyond_its_contact_loss_gap() {
    let text = reduction_example()
        .replace(
            "compression = { law = \"rigid\" }",
            "compression = { law = \"quadratic\", k0 = 1e14, k1 = 1e21 }",
        )
        .replace(
            "traction = { law = \"rccm\", stiffness = 2e13, energy = 0.01, viscosity = 1e-8 }",
            "traction = { law = \"free\" }",
        )
        .replace("static_pressure = 0.3e6", "static_pressure = 1e6")
        .replace("duration = 11e-6", "duration = 5e-6");
    for (amplitude, opens) in [("0.4e6", false), ("6e6", true)] {
        let text = text.replace("amplitude = 3e6", &format!("amplitude = {amplitude}"));
        let outcome = model::from_toml_str(&text, "compliant.toml")
            .unwrap()
            .base()
            .unwrap()
            .run(&RunControl::default())
            .unwrap();
        let (gap, stress, state) = (
            crack_rows(outcome.as_ref(), "normal_gap"),
            crack_rows(outcome.as_ref(), "normal_stress"),
            crack_rows(outcome.as_ref(), "state"),
        );
        let cells = || {
            gap.iter()
                .flatten()
                .zip(stress.iter().flatten())
                .zip(state.iter().flatten())
        };
        // the faces move apart under compression (a positive gap, still closed)
        assert!(cells().any(|((&g, &s), &st)| g > 0.0 && s < -1e3 && st != 0.0));
        let open = cells().filter(|&(_, &st)| st == 0.0).count();
        assert_eq!(open > 0, opens, "{amplitude}: {open} open cells");
        for ((&g, &s), &st) in cells() {
            if st == 0.0 {
                assert!(g > 0.0 && s >= -1e-6, "open with gap {g:e}, stress {s:e}");
            } else {
                assert!(s <= 1e-6, "closed with stress {s:e}");
            }
        }
    }
}

/// `crack.csv` as the run writes it: each record's time (s) and its first node's
/// `normal_gap`, `tangential_gap` (m), `normal_stress`, `shear_stress` (Pa), after checking
/// that every node of the record carries the same values within 1e-6 of each column's
/// largest (a plane wave at normal incidence on a full-width interface moves the whole
/// line alike).
/// Run the strip `text` (named `name` in errors): its time step (s), with the energy
/// closed, and its crack.csv series ([`crack_csv_series`]).
fn run_strip(text: &str, name: &str) -> (f64, Vec<f64>, Vec<[f64; 4]>) {
    let outcome = model::from_toml_str(text, name)
        .unwrap()
        .base()
        .unwrap()
        .run(&RunControl::default())
        .unwrap();
    let s = outcome.summary();
    assert!(s.get("energy_closure_error").unwrap() < 1e-9, "{s:?}");
    let dt = s.get("dt").unwrap();
    let (t, rows) = crack_csv_series(outcome.as_ref());
    (dt, t, rows)
}

fn crack_csv_series(outcome: &dyn model::Outcome) -> (Vec<f64>, Vec<[f64; 4]>) {
    let files = outcome.files().unwrap();
    let csv = files.iter().find(|f| f.name == "crack.csv").unwrap();
    let mut lines = csv.contents.lines();
    assert_eq!(
        lines.next().unwrap(),
        "crack,t,position,normal_gap,tangential_gap,normal_stress,shear_stress,adhesion,state"
    );
    let (mut times, mut rows): (Vec<f64>, Vec<[f64; 4]>) = (Vec::new(), Vec::new());
    let (mut spread, mut largest) = ([0.0f64; 4], [0.0f64; 4]);
    for line in lines {
        let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        let values = [cells[3], cells[4], cells[5], cells[6]];
        if times.last() != Some(&cells[1]) {
            times.push(cells[1]);
            rows.push(values);
        }
        let first = rows[rows.len() - 1];
        for i in 0..4 {
            spread[i] = spread[i].max((values[i] - first[i]).abs());
            largest[i] = largest[i].max(values[i].abs());
        }
    }
    for i in 0..4 {
        assert!(
            spread[i] <= 1e-6 * largest[i],
            "column {i}: {spread:?} {largest:?}"
        );
    }
    (times, rows)
}

/// Aluminium as the scenario's preset gives it (E = 71 GPa, nu = 0.33, rho = 2710 kg/m^3):
/// density (kg/m^3), P and S wave speeds (m/s).
fn aluminium() -> (f64, f64, f64) {
    let (e, nu, rho) = (71e9, 0.33, 2710.0);
    let mu = e / (2.0 * (1.0 + nu));
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    (rho, (m / rho).sqrt(), (mu / rho).sqrt())
}

/// The largest `|x_k - exact(t_k)|` over the records at times `t` (s), over `scale`.
fn max_error(t: &[f64], x: &[f64], exact: impl Fn(f64) -> f64, scale: f64) -> f64 {
    t.iter()
        .zip(x)
        .fold(0.0f64, |e, (&t, &x)| e.max((x - exact(t)).abs()))
        / scale
}

/// `integral_0^t f`, s times the unit of `f`, by the midpoint rule on steps of 0.1 ns
/// from a table that `at(t)` reads (linear between the table's points).
struct Primitive {
    step: f64,
    values: Vec<f64>,
}

impl Primitive {
    fn new(f: impl Fn(f64) -> f64, end: f64) -> Self {
        let step = 1e-10;
        let n = (end / step).ceil() as usize + 1;
        let mut values = Vec::with_capacity(n + 1);
        let mut acc = 0.0;
        values.push(acc);
        for k in 0..n {
            acc += step * f((k as f64 + 0.5) * step);
            values.push(acc);
        }
        Primitive { step, values }
    }

    fn at(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let x = t / self.step;
        let k = (x.floor() as usize).min(self.values.len() - 2);
        let s = x - k as f64;
        self.values[k] + s * (self.values[k + 1] - self.values[k])
    }
}

/// The scenario of a periodic aluminium strip one element wide, elements of `h` (m), `depth`
/// (m) deep (absorbing top and bottom, layers of 2 mm: what they reflect reaches the
/// interface after the bursts) with a full-width rigid (Signorini) interface at `z_crack`
/// (m) under `p0` (Pa) with rigid-stick Coulomb friction `mu`, run for `duration` (s) under
/// the plane-wave sources `sources` (TOML).
fn clipping_strip(
    wave: &str,
    [h, depth, z_crack]: [f64; 3],
    [p0, mu]: [f64; 2],
    duration: f64,
    sources: &str,
) -> String {
    format!(
        r#"
[model]
kind = "solid_2d"
wave = "{wave}"
width = {h:e}
duration = {duration:e}
element_size = {h:e}
top = "absorbing"
bottom = "absorbing"
sides = "periodic"
pml_thickness = 2e-3
pml_reflection = 1e-6
crack_every = 1

[[layer]]
thickness = {depth:e}
material = "aluminium"

[[crack]]
start = [0.0, {z_crack:e}]
full_width = true
static_pressure = {p0:e}
compression = {{ law = "rigid" }}
traction = {{ law = "free" }}
tangential = {{ law = "coulomb", friction = {mu} }}
{sources}
"#
    )
}

/// The relative error of the complex amplitude at `f` (Hz) of the records `x` at times
/// `t` (s) against `exact` at the same times: `|X(f) - E(f)| / |E(f)|` with
/// `X(f) = sum_k x_k exp(-i 2 pi f t_k)`. A series stamped a time `d` late carries the
/// phase error `2 pi f d`; the ringing of the elements after a stick-slip switch (well above
/// `f`) averages out.
fn harmonic_error(t: &[f64], x: &[f64], exact: impl Fn(f64) -> f64, f: f64) -> f64 {
    let w = 2.0 * std::f64::consts::PI * f;
    let (mut d, mut e) = ([0.0f64; 2], [0.0f64; 2]);
    for (&t, &x) in t.iter().zip(x) {
        let (s, c) = (w * t).sin_cos();
        let y = exact(t);
        d[0] += (x - y) * c;
        d[1] -= (x - y) * s;
        e[0] += y * c;
        e[1] -= y * s;
    }
    d[0].hypot(d[1]) / e[0].hypot(e[1])
}

/// The errors of a recorded series against `exact` on the written times and with the
/// exact values taken one step `dt` (s) earlier (what a series one level late matches),
/// printed under `name`: `[max error / scale; complex amplitude at each of freqs]`.
fn timing_errors(
    name: &str,
    t: &[f64],
    x: &[f64],
    exact: &dyn Fn(f64) -> f64,
    scale: f64,
    freqs: &[f64],
    dt: f64,
) -> [Vec<f64>; 2] {
    let errors = |shift: f64| -> Vec<f64> {
        let at = |t: f64| exact(t - shift);
        let mut v = vec![max_error(t, x, at, scale)];
        v.extend(freqs.iter().map(|&f| harmonic_error(t, x, at, f)));
        v
    };
    let (on, late) = (errors(0.0), errors(dt));
    let e = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    eprintln!(
        "{name}: max error / scale, then at {freqs:?} Hz: on the written times {}; \
         against the exact series one step earlier {}",
        e(&on),
        e(&late)
    );
    [on, late]
}

/// crack.csv's stresses at their own time levels (issue 56): a plane SH wave on a
/// full-width rigid-stick Coulomb interface is the 1D clipping problem (model.md 13.5,
/// `analytic::friction::ClippedShear`): between identical solids the contact shear stress
/// is the incident wave's, clipped at `+-mu p0`, and the tangential gap grows at
/// `(2 / Z_S) (s - clip(s))` while it slips. Both are compared at the written times with
/// the closed form at the wave's arrival (the plane wave leaves the top of the element row
/// above its injection line at t = 0, model.md 15.8). The stick and slip stresses are
/// the slider's constraint reaction, which the step from level n to n + 1 finds for level
/// n. Measured (dt = 3.7 ns, order-6 elements of 0.25 mm): the shear stress's complex
/// amplitudes at f0 and 3 f0 within 2.9e-4 and 4.6e-4 of the closed form's; written one
/// level late, as they were, 2.3e-2 and 6.9e-2 (the phase `omega dt`): the bounds 2e-3 and
/// 3e-3 leave the measured error a margin of 7 and 6 and fail by 11 and 23 one level
/// late. The max error is the elements' ringing after each stick-slip switch (first order
/// in the element size, model.md 15.8): 4.0e-2 of `mu p0` (7.3e-2 one level late), bound
/// 5e-2. The tangential gap, on time before and after: 2.7e-3 of its largest (a level late
/// it would be 2.0e-2), bound 5e-3.
#[test]
fn sh_clipping_on_a_full_width_coulomb_interface_is_written_on_time() {
    let (rho, _, cs) = aluminium();
    let (h, z_line, z_crack, depth) = (0.25e-3, 2e-3, 6e-3, 12e-3);
    let (p0, mu, amplitude, f0, cycles) = (10e6, 0.3, 5e6, 1e6, 3.0);
    let delay = (z_crack - z_line + h) / cs;
    let duration = delay + cycles / f0 + 0.5e-6;
    let sources = format!(
        r#"
[[source]]
kind = "plane_wave"
wave = "SH"
z = {z_line:e}
signal = {{ frequency = {f0:e}, cycles = {cycles}, amplitude = {amplitude:e}, window = "hann" }}
"#
    );
    let text = clipping_strip("sh", [h, depth, z_crack], [p0, mu], duration, &sources);
    let (dt, t, rows) = run_strip(&text, "sh_clipping.toml");
    assert!(t.len() > 500, "{} records", t.len());
    let incident = ToneBurst::new(amplitude, f0, cycles, Window::Hann);
    let limit = mu * p0;
    let tau = |t: f64| incident.stress(t - delay).clamp(-limit, limit);
    let z_s = rho * cs;
    let slip = Primitive::new(
        |t| 2.0 / z_s * (incident.stress(t) - incident.stress(t).clamp(-limit, limit)),
        duration,
    );
    let gap = |t: f64| slip.at(t - delay);
    let gap_scale = t.iter().fold(0.0f64, |a, &t| a.max(gap(t).abs()));
    let col = |i: usize| rows.iter().map(|r| r[i]).collect::<Vec<f64>>();
    let (ut, sn, st) = (col(1), col(2), col(3));
    // the closure holds, the wave clips
    assert!(sn.iter().all(|&x| (x + p0).abs() < 1e-6 * p0));
    assert!(st.iter().any(|&x| (x.abs() - limit).abs() < 1e-9 * limit));
    let [on, late] = timing_errors("shear stress", &t, &st, &tau, limit, &[f0, 3.0 * f0], dt);
    // the measure sees one level: against the exact series a step earlier (what a record
    // one level late matches) it is off by about omega dt
    assert!(late[1] > 1e-2, "{late:?}");
    assert!(on[0] < 5e-2 && on[1] < 2e-3 && on[2] < 3e-3, "{on:?}");
    let [gap_on, _] = timing_errors("tangential gap", &t, &ut, &gap, gap_scale, &[], dt);
    assert!(gap_on[0] < 5e-3, "{gap_on:?}");
}

/// The same in plane strain with both reactions at once: a plane P wave that never opens
/// the interface (a 0.5 MHz burst of 4 MPa under 10 MPa closure) and a plane SV wave that
/// it clips (1 MHz, 4 MPa, delayed so that the bursts overlap there). Closed by the
/// Signorini constraint the interface passes the P wave as the bulk would: the contact
/// stress is `-p0 + s_P`, the reaction; the shear is the SV wave's clipped at the friction
/// limit of that pressure, `mu (p0 - s_P)`. Measured (dt = 1.9 ns): the normal stress
/// within 5.5e-6 of the P wave's amplitude at every written time and 3.3e-6 in its complex
/// amplitude at its f0 (one level late: 7.3e-3 and 6.4e-3; bounds 1e-4); the shear
/// stress's complex amplitudes at the SV wave's f0 and 3 f0 within 6.0e-5 and 3.1e-3 (one
/// level late 1.3e-2 and 4.0e-2; bounds 1e-3 and 1e-2); the tangential gap within 1.9e-3
/// of its largest (1.1e-2 a level off; bound 4e-3).
#[test]
fn p_sv_reactions_on_a_full_width_signorini_coulomb_interface_are_written_on_time() {
    let (rho, cp, cs) = aluminium();
    let (h, z_line, z_crack, depth) = (0.25e-3, 2e-3, 6e-3, 12e-3);
    let (p0, mu) = (10e6, 0.3);
    let (a_p, f_p, cycles_p) = (4e6, 0.5e6, 2.0);
    let (a_s, f_s, cycles_s) = (4e6, 1e6, 3.0);
    let travel = z_crack - z_line + h;
    let tau_s = travel / cs;
    // the P burst's middle on the SV burst's
    let delay_p = tau_s + 0.5 * cycles_s / f_s - 0.5 * cycles_p / f_p - travel / cp;
    assert!(delay_p > 0.0);
    let tau_p = travel / cp + delay_p;
    let duration = tau_s + cycles_s / f_s + 0.5e-6;
    let sources = format!(
        r#"
[[source]]
kind = "plane_wave"
wave = "P"
z = {z_line:e}
signal = {{ frequency = {f_p:e}, cycles = {cycles_p}, amplitude = {a_p:e}, window = "hann", delay = {delay_p:e} }}

[[source]]
kind = "plane_wave"
wave = "SV"
z = {z_line:e}
signal = {{ frequency = {f_s:e}, cycles = {cycles_s}, amplitude = {a_s:e}, window = "hann" }}
"#
    );
    let text = clipping_strip("p_sv", [h, depth, z_crack], [p0, mu], duration, &sources);
    let (dt, t, rows) = run_strip(&text, "p_sv_clipping.toml");
    let p_wave = ToneBurst::new(a_p, f_p, cycles_p, Window::Hann);
    let s_wave = ToneBurst::new(a_s, f_s, cycles_s, Window::Hann);
    let limit = |t: f64| mu * (p0 - p_wave.stress(t - tau_p));
    let sigma = |t: f64| p_wave.stress(t - tau_p);
    let tau = |t: f64| s_wave.stress(t - tau_s).clamp(-limit(t), limit(t));
    let z_s = rho * cs;
    let slip = Primitive::new(
        |t| 2.0 / z_s * (s_wave.stress(t - tau_s) - tau(t)),
        duration,
    );
    let gap = |t: f64| slip.at(t);
    let gap_scale = t.iter().fold(0.0f64, |a, &t| a.max(gap(t).abs()));
    let col = |i: usize| rows.iter().map(|r| r[i]).collect::<Vec<f64>>();
    let (un, ut, sn, st) = (col(0), col(1), col(2), col(3));
    // closed throughout (no tension reaches it), and slipping at times
    assert!(un.iter().all(|&g| g == 0.0));
    let dynamic: Vec<f64> = sn.iter().map(|&x| x + p0).collect();
    assert!(t
        .iter()
        .zip(&st)
        .any(|(&t, &x)| (x.abs() - limit(t)).abs() < 1e-3 * p0));
    let [n_on, n_late] = timing_errors("normal stress", &t, &dynamic, &sigma, a_p, &[f_p], dt);
    assert!(n_late[0] > 1e-3, "{n_late:?}");
    assert!(n_on[0] < 1e-4 && n_on[1] < 1e-4, "{n_on:?}");
    let [s_on, s_late] = timing_errors("shear stress", &t, &st, &tau, a_s, &[f_s, 3.0 * f_s], dt);
    assert!(s_late[1] > 5e-3, "{s_late:?}");
    assert!(s_on[1] < 1e-3 && s_on[2] < 1e-2, "{s_on:?}");
    let [g_on, _] = timing_errors("tangential gap", &t, &ut, &gap, gap_scale, &[], dt);
    assert!(g_on[0] < 4e-3, "{g_on:?}");
}

use contactwave::analysis::velocity_bands;
use contactwave::scenario::Scenario;
use contactwave::solver::halfspace::HalfSpaceSettings;
use std::time::Instant;
const RCCM: &str = r#"
[medium]
material = "pmma"
[interface]
static_pressure = 0.082e6
traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
[incident]
frequency = 1e6
cycles = 15
amplitude = 0.82e6
"#;
const UNI: &str = r#"
[medium]
material = "pmma"
[interface]
static_pressure = 0.1e6
[incident]
frequency = 1e6
cycles = 15
xi = 0.35
"#;
fn main() {
    if let Some(w) = std::env::args().nth(1) {
        let s =
            Scenario::from_toml_str(if w.starts_with("r") { RCCM } else { UNI }, "x.toml").unwrap();
        let hs = contactwave::half_space(&s);
        let set = HalfSpaceSettings {
            summary_only: true,
            ..contactwave::settings(&s)
        };
        let mut out = hs.solve(&set).unwrap();
        if w.ends_with("g") {
            let h = out.dt;
            let steps = (hs.incident.duration() / h).ceil() as usize;
            let mut tab = vec![0.0; 7 * steps];
            let c = [0.155, 0.645, 1.0, 0.07, 0.33, 0.67, 0.93];
            for _ in 0..100000 {
                hs.incident.stress_grid(h, &c, steps, &mut tab);
                std::hint::black_box(&tab);
            }
            return;
        }
        if w.ends_with("b") {
            for _ in 0..100000 {
                std::hint::black_box(velocity_bands(
                    &out.reflected_displacement,
                    out.dt,
                    1e6,
                    None,
                ));
            }
            return;
        }
        for _ in 0..50000 {
            out = hs.solve(&set).unwrap();
        }
        std::hint::black_box(out);
        return;
    }
    for (name, txt) in [("rccm", RCCM), ("uni", UNI)] {
        let s = Scenario::from_toml_str(txt, "x.toml").unwrap();
        let hs = contactwave::half_space(&s);
        let set = HalfSpaceSettings {
            summary_only: true,
            ..contactwave::settings(&s)
        };
        let n = 3000;
        let mut out = hs.solve(&set).unwrap();
        let t = Instant::now();
        for _ in 0..n {
            out = hs.solve(&set).unwrap();
        }
        let ts = t.elapsed().as_secs_f64() / n as f64;
        let t = Instant::now();
        let mut b = None;
        for _ in 0..n {
            b = Some(velocity_bands(
                &out.reflected_displacement,
                out.dt,
                1e6,
                None,
            ));
        }
        let ta = t.elapsed().as_secs_f64() / n as f64;
        let t = Instant::now();
        for _ in 0..n {
            let _ = contactwave::simulate_summary(&s).unwrap();
        }
        let tt = t.elapsed().as_secs_f64() / n as f64;
        let h = out.dt;
        let steps = (hs.incident.duration() / h).ceil() as usize;
        let mut tab = vec![0.0; 7 * steps];
        let c = [0.155, 0.645, 1.0, 0.07, 0.33, 0.67, 0.93];
        let t = Instant::now();
        for _ in 0..n {
            hs.incident.stress_grid(h, &c, steps, &mut tab);
            std::hint::black_box(&tab);
        }
        println!("grid {:.1} us", t.elapsed().as_secs_f64() / n as f64 * 1e6);
        let t = Instant::now();
        for _ in 0..n {
            let _ = hs.incident.clone();
            let g = contactwave::half_space(&s);
            std::hint::black_box(g);
        }
        let th = t.elapsed().as_secs_f64() / n as f64;
        println!("{name}: solve {:.1} us, bands {:.1} us, total {:.1} us, hs {:.2} us, len {} events {} {:?}", ts*1e6, ta*1e6, tt*1e6, th*1e6, out.t.len(), out.events, b.unwrap().harmonic[2]);
    }
}
#[allow(dead_code)]
fn unused() {}

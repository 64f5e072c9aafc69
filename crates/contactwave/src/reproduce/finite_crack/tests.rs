//! The length study at `--quick`: the plane-interface limit and the finite-crack trend.

use super::super::{Ctx, Figure, Finding};
use super::{length, Resolution};
use std::sync::atomic::AtomicUsize;

fn value(findings: &[Finding], key: &str) -> f64 {
    findings
        .iter()
        .find(|f| f.key == key)
        .map(|f| f.value)
        .unwrap_or(f64::NAN)
}

/// At normal incidence a long crack reflects the 1D interface's A2/A1 (the tips' diffraction
/// comes after the burst), a crack of half a wavelength clearly more (its fundamental
/// spreads more than its second harmonic); the crack across the strip is the 1D interface
/// within 2 % and the energy closes. About 15 s of CPU in release.
#[test]
#[ignore = "slow: full tier"]
fn a_long_crack_reflects_what_the_plane_interface_does() {
    let ctx = Ctx {
        progress: &|_, _, _| {},
        runs: AtomicUsize::new(0),
    };
    let mut figures: Vec<Figure> = Vec::new();
    let mut findings: Vec<Finding> = Vec::new();
    length::run(
        &ctx,
        Resolution { quick: true },
        &mut figures,
        &mut findings,
    )
    .unwrap();
    assert_eq!(figures.len(), 1);
    for law in ["signorini", "rccm"] {
        let longest = value(
            &findings,
            &format!("finite_crack_length_a2a1_longest_over_1d_{law}"),
        );
        let shortest = value(
            &findings,
            &format!("finite_crack_length_a2a1_shortest_over_1d_{law}"),
        );
        let plane = value(
            &findings,
            &format!("finite_crack_plane_interface_a2a1_error_{law}"),
        );
        let from = value(&findings, &format!("finite_crack_length_within_5pct_{law}"));
        eprintln!("{law}: longest {longest}, shortest {shortest}, plane {plane}, from {from}");
        assert!((longest - 1.0).abs() < 0.1, "{law}: {longest}");
        assert!(shortest > longest + 0.2, "{law}: {shortest} {longest}");
        assert!(plane.abs() < 0.02, "{law}: {plane}");
        assert!(from > 0.5 && from <= 20.0, "{law}: {from}");
    }
    assert!(value(&findings, "finite_crack_length_energy_closure_error") < 1e-9);
}

/// The wavefield figure: two PNG frames at different times, the GIF of every frame and the
/// crack's state map, embedded in the report page as data URIs (the page stays
/// self-contained) and written under `figures/`; the run closes its energy. About 5 s of
/// CPU in release.
#[test]
fn the_wavefield_pictures_reach_the_report() {
    use super::super::{report_html, Chapter, ChapterResult};
    let ctx = Ctx {
        progress: &|_, _, _| {},
        runs: AtomicUsize::new(0),
    };
    let mut figures: Vec<Figure> = Vec::new();
    super::wavefield::run(&ctx, Resolution { quick: true }, &mut figures).unwrap();
    let fig = &figures[0];
    let names: Vec<&str> = fig.pictures.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "finite_crack_wavefield_on_crack.png",
            "finite_crack_wavefield_reflected.png",
            "finite_crack_wavefield.gif",
            "finite_crack_wavefield_crack_state.png"
        ]
    );
    let png = b"\x89PNG\r\n\x1a\n";
    for p in &fig.pictures {
        let sig: &[u8] = if p.name.ends_with(".gif") {
            b"GIF89a"
        } else {
            png
        };
        assert!(p.bytes.starts_with(sig), "{}", p.name);
    }
    assert_ne!(fig.pictures[0].bytes, fig.pictures[1].bytes);
    // the frames' times are in their captions, the burst first on the crack, then back
    let t = |c: &str| -> f64 {
        let s = c.split("t = ").nth(1).unwrap();
        s.split(' ').next().unwrap().parse().unwrap()
    };
    assert!(t(&fig.pictures[0].caption) < t(&fig.pictures[1].caption));
    let closure: f64 = fig.comparisons[0]
        .split_whitespace()
        .nth(5)
        .unwrap()
        .parse()
        .unwrap();
    assert!(closure.abs() < 1e-9, "{}", fig.comparisons[0]);
    let chapter = ChapterResult {
        chapter: Chapter::FiniteCrack,
        title: "t".into(),
        intro: String::new(),
        figures,
        findings: Vec::new(),
        seconds: 0.0,
        runs: 1,
    };
    let html = report_html(std::slice::from_ref(&chapter), &[vec![String::new()]], 0.0);
    assert_eq!(html.matches("src=\"data:image/png;base64,").count(), 3);
    assert_eq!(html.matches("src=\"data:image/gif;base64,").count(), 1);
    assert!(html.contains("figures/finite_crack_wavefield.gif"));
}

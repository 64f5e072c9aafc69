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

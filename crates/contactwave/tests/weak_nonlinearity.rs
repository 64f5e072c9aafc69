//! Weak nonlinearity (issue 15, model.md section 8.1): the analysis methods against the
//! second-order perturbation solution of a smooth compression law without contact loss.

use contactwave::analysis::AnalysisMethod;
use contactwave::study::validation::{perturbation_of, weak_laws, weak_scenario};

fn beta(law: &str, cycles: f64, m: AnalysisMethod) -> (f64, f64, contactwave::analysis::Summary) {
    let s = weak_scenario(10e6, law, cycles, m).unwrap();
    let reference = perturbation_of(&s).beta_reflected();
    let sm = contactwave::simulate_summary(&s).unwrap();
    (sm.get("beta_star").unwrap(), reference, sm)
}

#[test]
fn explore() {
    for (name, law) in weak_laws(10e6) {
        for cycles in [15.0, 40.0] {
            for m in AnalysisMethod::ALL {
                let (b, r, sm) = beta(&law, cycles, m);
                println!(
                    "{name:10} {cycles:4} {:18} beta {b:.5e} ref {r:.5e} err {:+.4}% floor2 {:.3e} A2 {:.3e} warn {}",
                    m.name(),
                    100.0 * (b / r - 1.0),
                    sm.get("A2_floor_over_Ainc").unwrap(),
                    sm.get("A2_over_Ainc").unwrap(),
                    sm.get("harmonic_floor_warning").unwrap()
                );
            }
        }
    }
}

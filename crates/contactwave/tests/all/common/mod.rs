#![allow(dead_code)]
use contactwave::scenario::Scenario;
use contactwave::{simulate, RunResult};

/// Build a scenario from TOML text (panics in tests only).
pub fn scenario(text: &str) -> Scenario {
    Scenario::from_toml_str(text, "test.toml").expect("valid scenario")
}

pub fn run(text: &str) -> RunResult {
    simulate(&scenario(text)).expect("simulation")
}

pub fn get(r: &RunResult, k: &str) -> f64 {
    r.summary.get(k).unwrap_or_else(|| panic!("missing {k}"))
}

/// PMMA half-space against a rigid wall, 1 MHz, with the given interface and incident
/// lines.
pub fn pmma(interface: &str, incident: &str) -> String {
    format!(
        "[medium]\nmaterial = \"pmma\"\n[interface]\n{interface}\n[incident]\nfrequency = 1e6\n{incident}\n"
    )
}

pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Crack 0's recorded field `name` of a 2D run, `[point][record]`.
pub fn crack_rows(outcome: &dyn contactwave::model::Outcome, name: &str) -> Vec<Vec<f64>> {
    use contactwave::model::Value;
    let record = outcome.record();
    let Some(Value::Tuple(cracks)) = record.get("cracks") else {
        panic!("cracks")
    };
    let Value::Map(c) = &cracks[0] else {
        panic!("crack map")
    };
    let Some(Value::Rows(rows)) = c.get(name) else {
        panic!("{name}")
    };
    rows.clone()
}

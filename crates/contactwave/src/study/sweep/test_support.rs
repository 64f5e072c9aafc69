//! Fixtures shared by the sweep unit tests: a fresh temporary folder, a small base
//! scenario ([`BASE`], a few cheap half-space runs) and a sweep file written beside it.

use std::path::PathBuf;

pub(super) fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "contactwave-sweep-{name}-{}-{:?}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0)
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

pub(super) const BASE: &str = r#"
[medium]
material = "pmma"
[interface]
static_pressure = 0.1e6
[incident]
frequency = 1e6
cycles = 3
amplitude = 0.2e6
[solver]
samples_per_period = 32
tail_periods = 5
"#;

pub(super) fn setup(name: &str, sweep: &str) -> (PathBuf, PathBuf) {
    let d = tmpdir(name);
    std::fs::write(d.join("base.toml"), BASE).unwrap();
    let s = d.join("sweep.toml");
    std::fs::write(&s, sweep).unwrap();
    (d, s)
}

//! Helpers shared by the CLI's integration tests (`mod common;` in each test file).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh, unique temporary folder: `contactwave-<test file>-<name>-<process>-<n>`.
pub fn tmpdir(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!(
        "contactwave-{}-{name}-{}-{}",
        env!("CARGO_CRATE_NAME"),
        std::process::id(),
        N.fetch_add(1, Ordering::SeqCst)
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The repository's `examples/` folder.
#[allow(dead_code)]
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The `contactwave` binary under test.
#[allow(dead_code)]
pub fn bin() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_contactwave"))
}

/// `contactwave CMD FILE --out OUT`.
#[allow(dead_code)]
pub fn cli(
    cmd: impl AsRef<std::ffi::OsStr>,
    file: impl AsRef<Path>,
    out: impl AsRef<Path>,
) -> std::process::Output {
    bin()
        .arg(cmd)
        .arg(file.as_ref())
        .arg("--out")
        .arg(out.as_ref())
        .output()
        .unwrap()
}

/// A command's stderr as text.
#[allow(dead_code)]
pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

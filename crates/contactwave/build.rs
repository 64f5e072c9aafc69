//! Build script: the git commit the library is built from, for the provenance of its
//! outputs (`output::provenance`): `CONTACTWAVE_GIT_COMMIT` (40 hex digits, empty when the
//! crate is not built inside a git checkout that tracks it, e.g. from a published
//! package) and `CONTACTWAVE_GIT_DIRTY` (`1` when tracked files differ from that commit,
//! `0` when not, empty when unknown). Any failure of git leaves both empty: the build
//! never fails on it. It reruns when HEAD, the branch it points to, the index or this
//! crate's sources change, not on every build.

use std::path::{Path, PathBuf};
use std::process::Command;

fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .current_dir(dir)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn main() {
    let dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src");
    // rerun when HEAD moves (a commit, a checkout) or the index changes
    if let Some(git_dir) = git(&dir, &["rev-parse", "--absolute-git-dir"]) {
        let git_dir = PathBuf::from(git_dir);
        println!("cargo:rerun-if-changed={}", git_dir.join("HEAD").display());
        println!("cargo:rerun-if-changed={}", git_dir.join("index").display());
        let common = git(&dir, &["rev-parse", "--git-common-dir"])
            .map(|c| dir.join(c))
            .unwrap_or_else(|| git_dir.clone());
        if let Some(r) = git(&dir, &["symbolic-ref", "-q", "HEAD"]) {
            let reference = common.join(&r);
            if reference.exists() {
                println!("cargo:rerun-if-changed={}", reference.display());
            }
        }
        let packed = common.join("packed-refs");
        if packed.exists() {
            println!("cargo:rerun-if-changed={}", packed.display());
        }
    }
    // only a checkout that tracks this crate (not an unrelated repository around it)
    let tracked = git(&dir, &["ls-files", "--error-unmatch", "build.rs"]).is_some();
    let commit = tracked
        .then(|| git(&dir, &["rev-parse", "HEAD"]))
        .flatten()
        .filter(|c| c.len() == 40 && c.chars().all(|ch| ch.is_ascii_hexdigit()))
        .unwrap_or_default();
    let mut dirty = String::new();
    if !commit.is_empty()
        && let Some(s) = git(
            &dir,
            &[
                "--no-optional-locks",
                "status",
                "--porcelain",
                "--untracked-files=no",
            ],
        )
    {
        dirty = if s.is_empty() { "0" } else { "1" }.to_string();
    }
    println!("cargo:rustc-env=CONTACTWAVE_GIT_COMMIT={commit}");
    println!("cargo:rustc-env=CONTACTWAVE_GIT_DIRTY={dirty}");
}

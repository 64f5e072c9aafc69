//! Bit-for-bit determinism of the CLI's outputs: the same input run by the same binary
//! writes identical bytes, whatever the number of threads (RAYON_NUM_THREADS = 1 and 2,
//! `sweep --threads 1` and `2`) and when run twice in a row. The reference outputs
//! (`scripts/reference_outputs.py`) compare values within 1e-9; this test holds the bytes.

use crate::common::{examples, tmpdir};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// Every file under `dir` by its path relative to `dir`, with its bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                let mut bytes = std::fs::read(&path).unwrap();
                // the "provenance" object (the last key of a JSON output: its command
                // line names the folder and the thread count, its date the second) is
                // the one part that may differ
                if rel.ends_with(".json") {
                    let text = String::from_utf8(bytes).unwrap();
                    let cut = text.find("\n  \"provenance\": ").unwrap_or(text.len());
                    bytes = text.as_bytes()[..cut].to_vec();
                }
                out.insert(rel, bytes);
            }
        }
    }
    out
}

/// Runs `contactwave CMD EXAMPLE --out OUT [--threads N]` with RAYON_NUM_THREADS = N for
/// N = 1, 2 and 2 again, and asserts that the three output folders hold the same files,
/// byte for byte.
fn same_bytes_for_any_thread_count(cmd: &str, example: &str, threads_flag: bool) {
    let mut runs = Vec::new();
    for threads in [1, 2, 2] {
        let out = tmpdir(cmd).join("out");
        let mut c = Command::new(env!("CARGO_BIN_EXE_contactwave"));
        c.arg(cmd)
            .arg(examples().join(example))
            .arg("--out")
            .arg(&out)
            .env("RAYON_NUM_THREADS", threads.to_string());
        if threads_flag {
            c.arg("--threads").arg(threads.to_string());
        }
        let o = c.output().unwrap();
        assert!(
            o.status.success(),
            "{cmd} {example} with {threads} threads: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        runs.push((threads, files(&out)));
        let _ = std::fs::remove_dir_all(out.parent().unwrap());
    }
    let (_, first) = &runs[0];
    assert!(
        first.len() >= 3,
        "{cmd} {example}: only {} files",
        first.len()
    );
    for (k, (threads, run)) in runs.iter().enumerate().skip(1) {
        let names_a: Vec<_> = first.keys().collect();
        let names_b: Vec<_> = run.keys().collect();
        assert_eq!(
            names_a,
            names_b,
            "{cmd} {example}: other files with {threads} threads (run {})",
            k + 1
        );
        for (name, bytes) in first {
            let other = &run[name];
            if bytes != other {
                let at = bytes
                    .iter()
                    .zip(other.iter())
                    .position(|(a, b)| a != b)
                    .unwrap_or(bytes.len().min(other.len()));
                panic!(
                    "{cmd} {example}: {name} differs with {threads} threads (run {}) from \
                     byte {at} on ({} and {} bytes)",
                    k + 1,
                    bytes.len(),
                    other.len()
                );
            }
        }
    }
}

#[test]
fn half_space_run_is_bit_identical_for_any_thread_count() {
    same_bytes_for_any_thread_count("run", "rccm_1.6MPa.toml", false);
}

#[test]
fn coupled_half_space_run_is_bit_identical_for_any_thread_count() {
    same_bytes_for_any_thread_count("run", "shear/rccm_shear.toml", false);
}

#[test]
fn bar_stack_run_is_bit_identical_for_any_thread_count() {
    same_bytes_for_any_thread_count("run", "bar_stack_incident.toml", false);
}

#[test]
fn sweep_is_bit_identical_for_any_thread_count() {
    same_bytes_for_any_thread_count("sweep", "unilateral_xi_sweep.toml", true);
    same_bytes_for_any_thread_count("sweep", "shear/friction_ratio_sweep.toml", true);
}

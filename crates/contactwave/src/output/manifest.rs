//! The manifest of an output folder: `.contactwave-manifest.json` lists the files the
//! last contactwave command wrote into the folder (paths relative to it, `/`-separated),
//! so that the next command into the same folder removes them when it does not write them
//! again: a folder never holds one run's files beside another's (a bar-stack `frf.csv`
//! beside a half-space `summary.json`). Files contactwave did not write (not in the
//! manifest) are never touched; [`claim`] names them so that the caller can warn.
//!
//! The manifest also names the run that wrote the files (`source`: the command and its
//! input, e.g. `run /abs/path/scenario.toml`): [`check_owner`] refuses, before any work, to
//! run into a folder that holds another run's results unless told to overwrite them, and
//! [`check_collisions`] refuses to write over a file no contactwave command wrote; the same
//! run re-run into its own folder replaces its files.
//!
//! ```json
//! {"command": "run", "source": "run /data/plate.toml", "files": ["summary.json", ...]}
//! ```

use crate::error::{Error, Result};
use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

/// File name of the manifest in an output folder.
pub const MANIFEST: &str = ".contactwave-manifest.json";

/// What [`claim`] did to a folder.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Claimed {
    /// Files of the previous manifest that this command did not write: removed.
    pub removed: Vec<PathBuf>,
    /// Entries of the folder (and of its subfolders written into) that no contactwave
    /// command wrote: left untouched.
    pub foreign: Vec<PathBuf>,
}

/// A manifest entry as a path under the folder: relative, no `..`, no root (an entry
/// that is not such a path is ignored: a manifest never removes anything outside).
fn inside(dir: &Path, name: &str) -> Option<PathBuf> {
    let rel = Path::new(name);
    let plain = rel.components().all(|c| matches!(c, Component::Normal(_)));
    (plain && !name.is_empty()).then(|| dir.join(rel))
}

/// The files of `dir`'s manifest (empty without one, or for one that cannot be read).
pub fn read(dir: &Path) -> Vec<String> {
    std::fs::read_to_string(dir.join(MANIFEST))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|v| {
            v.get("files")?.as_array().map(|a| {
                a.iter()
                    .filter_map(|x| x.as_str().map(str::to_string))
                    .collect()
            })
        })
        .unwrap_or_default()
}

/// The run that wrote `dir`'s files: the manifest's `source` (its `command` for a manifest
/// written before sources were recorded) and its number of files; `None` without a
/// manifest, or with one that names no file.
pub fn owner(dir: &Path) -> Option<(String, usize)> {
    let v = std::fs::read_to_string(dir.join(MANIFEST))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())?;
    let files = read(dir).len();
    let source = v
        .get("source")
        .or_else(|| v.get("command"))
        .and_then(|s| s.as_str())
        .unwrap_or("an unknown command")
        .to_string();
    (files > 0).then_some((source, files))
}

/// Refuse to run `source` (the command and its input, as [`claim`] records it) into `dir`
/// when `dir` holds the results of another run (a manifest with another source), unless
/// `overwrite`: they would be replaced or removed.
pub fn check_owner(dir: &Path, source: &str, overwrite: bool) -> Result<()> {
    match owner(dir) {
        Some((other, files)) if !overwrite && other != source => Err(Error::invalid(
            "<command line>",
            "--out",
            dir.display(),
            format!(
                "holds the results of `{other}` ({files} files): a new or empty folder, or \
                 --overwrite to replace them"
            ),
        )),
        _ => Ok(()),
    }
}

/// Refuse to write `files` (relative to `dir`) where a file of that name exists that no
/// contactwave command wrote (not in the manifest), unless `overwrite`.
pub fn check_collisions(dir: &Path, files: &[String], overwrite: bool) -> Result<()> {
    if overwrite {
        return Ok(());
    }
    let ours: BTreeSet<String> = read(dir).into_iter().collect();
    let clash: Vec<&String> = files
        .iter()
        .filter(|f| !ours.contains(*f) && inside(dir, f).is_some_and(|p| p.exists()))
        .collect();
    match clash.first() {
        Some(first) => Err(Error::invalid(
            "<command line>",
            "--out",
            dir.display(),
            format!(
                "holds {} file(s) contactwave did not write under the names this run writes \
                 ({first}): another folder, or --overwrite to replace them",
                clash.len()
            ),
        )),
        None => Ok(()),
    }
}

/// Record that `command` wrote `files` (paths relative to `dir`, `/`-separated) into
/// `dir`: remove the files of the previous manifest that are not among `files` (and the
/// subfolders they leave empty), write the new manifest, and return what was removed and
/// the entries contactwave did not write (top-level entries of `dir` and entries of the
/// subfolders written into, other than `files` and the manifest).
/// `source` names the run (the command and its input) for [`check_owner`].
pub fn claim(dir: &Path, command: &str, source: &str, files: &[String]) -> Result<Claimed> {
    let now: BTreeSet<&str> = files.iter().map(String::as_str).collect();
    let mut removed = Vec::new();
    for old in read(dir) {
        if now.contains(old.as_str()) {
            continue;
        }
        let Some(path) = inside(dir, &old) else {
            continue;
        };
        if path.is_file() {
            std::fs::remove_file(&path).map_err(|e| Error::io(&path, e))?;
            removed.push(path.clone());
            // a subfolder the old run created and nothing else uses
            let mut parent = path.parent();
            while let Some(p) = parent.filter(|p| *p != dir && p.starts_with(dir)) {
                if std::fs::remove_dir(p).is_err() {
                    break;
                }
                parent = p.parent();
            }
        }
    }
    let json = serde_json::json!({ "command": command, "source": source, "files": files });
    let path = dir.join(MANIFEST);
    std::fs::write(&path, format!("{json}\n")).map_err(|e| Error::write_in(dir, e))?;
    // folders written into: the top and every parent of a file
    let mut folders: BTreeSet<PathBuf> = BTreeSet::from([PathBuf::new()]);
    for f in files {
        let mut p = Path::new(f).parent();
        while let Some(q) = p.filter(|q| !q.as_os_str().is_empty()) {
            folders.insert(q.to_path_buf());
            p = q.parent();
        }
    }
    let mut foreign = Vec::new();
    for folder in &folders {
        let Ok(entries) = std::fs::read_dir(dir.join(folder)) else {
            continue;
        };
        let mut names: Vec<PathBuf> = entries
            .filter_map(|e| e.ok())
            .map(|e| folder.join(e.file_name()))
            .collect();
        names.sort();
        for rel in names {
            let text = rel.to_string_lossy().replace('\\', "/");
            if text == MANIFEST || now.contains(text.as_str()) || folders.contains(&rel) {
                continue;
            }
            foreign.push(dir.join(rel));
        }
    }
    Ok(Claimed { removed, foreign })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_command_removes_the_first_ones_files_only() {
        let d = std::env::temp_dir().join(format!("contactwave-manifest-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("figures")).unwrap();
        for f in ["frf.csv", "summary.json", "figures/a.svg", "notes.txt"] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        let first: Vec<String> = ["frf.csv", "summary.json", "figures/a.svg"]
            .map(String::from)
            .to_vec();
        let c = claim(&d, "run", "run a.toml", &first).unwrap();
        assert!(c.removed.is_empty());
        assert_eq!(c.foreign, vec![d.join("notes.txt")]);
        assert_eq!(read(&d), first);
        let c = claim(&d, "run", "run a.toml", &["summary.json".to_string()]).unwrap();
        assert_eq!(c.removed, vec![d.join("frf.csv"), d.join("figures/a.svg")]);
        assert!(!d.join("frf.csv").exists() && !d.join("figures").exists());
        assert!(d.join("summary.json").exists() && d.join("notes.txt").exists());
        assert_eq!(c.foreign, vec![d.join("notes.txt")]);
        // a manifest entry outside the folder is never removed
        std::fs::write(d.join(MANIFEST), r#"{"files": ["../x", "/etc/passwd"]}"#).unwrap();
        assert!(claim(&d, "run", "run a.toml", &[])
            .unwrap()
            .removed
            .is_empty());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn another_runs_results_are_kept_unless_overwritten() {
        let d = std::env::temp_dir().join(format!("contactwave-owner-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        // an empty folder and a folder without a manifest are free
        check_owner(&d, "run /a.toml", false).unwrap();
        std::fs::write(d.join("mine.csv"), "x").unwrap();
        check_owner(&d, "run /a.toml", false).unwrap();
        // a file of the user's under a name the run writes is not replaced
        let names = ["mine.csv".to_string(), "summary.json".to_string()];
        let e = check_collisions(&d, &names, false).unwrap_err().to_string();
        assert!(e.contains("mine.csv") && e.contains("--overwrite"), "{e}");
        check_collisions(&d, &names, true).unwrap();
        std::fs::write(d.join("summary.json"), "x").unwrap();
        claim(&d, "run", "run /a.toml", &names[1..]).unwrap();
        // the same run again may replace its own files; another one may not
        check_owner(&d, "run /a.toml", false).unwrap();
        check_collisions(&d, &names[1..], false).unwrap();
        let e = check_owner(&d, "run /b.toml", false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("run /a.toml") && e.contains("1 files"), "{e}");
        check_owner(&d, "run /b.toml", true).unwrap();
        let _ = std::fs::remove_dir_all(&d);
    }
}

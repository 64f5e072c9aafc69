//! Provenance of an output: which contactwave, built from which commit, made it from which
//! input files, by which command, when.
//!
//! Every result file that describes a computation carries a `"provenance"` object:
//! `summary.json` (every model kind's run), `findings.json` (`reproduce`),
//! `identification.json` and `design.json` (`identify`), the sweep's sidecar
//! `provenance.json` beside `sweep.csv` (the CSV stays a plain table), and the root
//! group's attributes of the HDF5 files (`result.h5`). Its keys:
//!
//! | key | value |
//! |---|---|
//! | `contactwave_version` | the library's version (`CARGO_PKG_VERSION`) |
//! | `git_commit` | the commit the library was built from (40 hex digits) when it was built inside a git checkout, else `null` |
//! | `git_dirty` | `true` when tracked files differed from that commit at build time, `false` when not, `null` when unknown |
//! | `input` | the input file of the command (scenario, sweep or identification file), `null` without one (`reproduce`, a scenario given as a dict) |
//! | `scenario_sha256` | SHA-256 (hex) of the bytes of that file, `null` without one |
//! | `data_files` | `[{"path", "sha256"}]`: every other file the command read: a sweep's or identification's base scenario, waveform CSV files (the `path` keys of a scenario: `incident.path`, `source.path`, ...), an identification's data CSV or its `[records]` files |
//! | `command_line` | the command line (the CLI's arguments, shell-quoted where needed), or what a library caller gives (e.g. `python: contactwave.identify(...)`) |
//! | `created` | UTC date and time the output was made, ISO 8601 / RFC 3339 (`2026-11-25T22:41:38Z`) |
//!
//! The JSON files get the object as their last key, inserted into the rendered text
//! ([`Provenance::stamp`]): every byte before it is what the file would be without it.

use crate::error::{Error, Result};
use crate::render::OutputFile;
use serde_json::{json, Value};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// Name of a sweep's provenance sidecar (beside `sweep.csv`).
pub const SIDECAR: &str = "provenance.json";

/// The JSON files that carry a `"provenance"` object ([`Provenance::stamp`]).
pub const STAMPED: [&str; 4] = [
    "summary.json",
    "findings.json",
    "identification.json",
    "design.json",
];

/// The version of the library.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The commit the library was built from (build.rs), `None` outside a git checkout.
pub fn git_commit() -> Option<&'static str> {
    let c = env!("CONTACTWAVE_GIT_COMMIT");
    (!c.is_empty()).then_some(c)
}

/// Whether tracked files differed from [`git_commit`] at build time (`None`: unknown).
pub fn git_dirty() -> Option<bool> {
    match env!("CONTACTWAVE_GIT_DIRTY") {
        "1" => Some(true),
        "0" => Some(false),
        _ => None,
    }
}

/// A file read by the command and the SHA-256 of its bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DataFile {
    /// The path as the command resolved it.
    pub path: String,
    /// SHA-256 of the file's bytes, lower-case hex.
    pub sha256: String,
}

/// The provenance of an output (see the module doc for the keys).
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// `contactwave_version`.
    pub contactwave_version: String,
    /// `git_commit`.
    pub git_commit: Option<String>,
    /// `git_dirty`.
    pub git_dirty: Option<bool>,
    /// `input`: the command's input file.
    pub input: Option<String>,
    /// `scenario_sha256`: SHA-256 of the input file.
    pub scenario_sha256: Option<String>,
    /// `data_files`: the other files read, each once, in the order read.
    pub data_files: Vec<DataFile>,
    /// `command_line`.
    pub command_line: String,
    /// `created`: UTC, RFC 3339.
    pub created: String,
}

/// SHA-256 of bytes, lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let d = Sha256::digest(bytes);
    d.iter().map(|b| format!("{b:02x}")).collect()
}

/// SHA-256 of a file's bytes, lower-case hex.
pub fn sha256_file(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    Ok(sha256_hex(&bytes))
}

/// The current UTC date and time, RFC 3339 to the second (`2026-11-25T22:41:38Z`).
pub fn now_utc() -> String {
    let t = time::OffsetDateTime::now_utc()
        .replace_nanosecond(0)
        .unwrap_or_else(|_| time::OffsetDateTime::now_utc());
    t.format(&time::format_description::well_known::Rfc3339)
        .unwrap_or_default()
}

/// This process's command line: its arguments joined by spaces, those holding a space,
/// a quote or another shell character in single quotes.
pub fn process_command_line() -> String {
    std::env::args_os()
        .map(|a| shell_quote(&a.to_string_lossy()))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `arg` as a POSIX shell word.
fn shell_quote(arg: &str) -> String {
    let plain = !arg.is_empty()
        && arg
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%^".contains(c));
    if plain {
        arg.to_string()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    }
}

/// The waveform files a scenario reads: every string value of a `path` key at any depth
/// of its table, relative to `dir` (the scenario file's folder), that names a file.
pub fn scenario_data_files(table: &toml::Table, dir: &Path) -> Vec<PathBuf> {
    fn walk(v: &toml::Value, key: &str, dir: &Path, out: &mut Vec<PathBuf>) {
        match v {
            toml::Value::String(s) if key == "path" => {
                let p = dir.join(s);
                if p.is_file() && !out.contains(&p) {
                    out.push(p);
                }
            }
            toml::Value::Table(t) => {
                for (k, x) in t {
                    walk(x, k, dir, out);
                }
            }
            toml::Value::Array(a) => {
                for x in a {
                    walk(x, key, dir, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for (k, v) in table {
        walk(v, k, dir, &mut out);
    }
    out
}

/// The folder of a file (`.` for a bare name).
fn folder(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

impl Provenance {
    /// Provenance without an input file, made now, by `command_line`.
    pub fn new(command_line: impl Into<String>) -> Provenance {
        Provenance {
            contactwave_version: VERSION.to_string(),
            git_commit: git_commit().map(str::to_string),
            git_dirty: git_dirty(),
            input: None,
            scenario_sha256: None,
            data_files: Vec::new(),
            command_line: command_line.into(),
            created: now_utc(),
        }
    }

    /// Provenance of a command on the scenario file `path` (its waveform files among the
    /// data files).
    pub fn of_scenario(path: &Path, command_line: impl Into<String>) -> Result<Provenance> {
        let mut p = Provenance::new(command_line).with_input(path)?;
        let table = crate::scenario::read_table(path)?;
        p.add_scenario_files(&table, folder(path))?;
        Ok(p)
    }

    /// Provenance of a sweep (`path` is the sweep file; its base scenario and the base's
    /// waveform files are data files).
    pub fn of_sweep(sweep: &crate::study::Sweep, command_line: impl Into<String>) -> Result<Self> {
        let mut p = Provenance::new(command_line).with_input(&sweep.file)?;
        p.add_data_file(&sweep.base)?;
        p.add_scenario_files(&sweep.base_table, folder(&sweep.base))?;
        Ok(p)
    }

    /// Provenance of an identification (`path` is the identification file; its base
    /// scenario, the base's waveform files and its data CSV are data files).
    #[cfg(feature = "identify")]
    pub fn of_identification(
        path: &Path,
        spec: &crate::inverse::IdentifySpec,
        command_line: impl Into<String>,
    ) -> Result<Provenance> {
        let mut p = Provenance::new(command_line).with_input(path)?;
        p.add_data_file(&spec.base)?;
        p.add_scenario_files(&spec.base_table, folder(&spec.base))?;
        if let Some(d) = &spec.data_file {
            p.add_data_file(d)?;
        }
        for f in spec
            .records
            .iter()
            .flat_map(crate::inverse::records::record_files)
        {
            p.add_data_file(&f)?;
        }
        Ok(p)
    }

    /// Record `path` as the input file and hash it.
    pub fn with_input(mut self, path: &Path) -> Result<Provenance> {
        self.scenario_sha256 = Some(sha256_file(path)?);
        self.input = Some(path.display().to_string());
        Ok(self)
    }

    /// Record a file read (once; hashed now).
    pub fn add_data_file(&mut self, path: &Path) -> Result<()> {
        let shown = path.display().to_string();
        if self.data_files.iter().any(|d| d.path == shown) {
            return Ok(());
        }
        self.data_files.push(DataFile {
            sha256: sha256_file(path)?,
            path: shown,
        });
        Ok(())
    }

    /// Refuse to write the output files `names` into the folder `out` where one of them
    /// would replace a file this command read (`contactwave analyze out/records.csv --out
    /// out`): the error names the output folder and the input, and nothing is written.
    pub fn check_inputs_kept<'a>(
        &self,
        out: &Path,
        names: impl IntoIterator<Item = &'a str>,
    ) -> Result<()> {
        let inputs: Vec<(PathBuf, &str)> = (self.input.iter())
            .chain(self.data_files.iter().map(|d| &d.path))
            .filter_map(|p| Some((std::fs::canonicalize(p).ok()?, p.as_str())))
            .collect();
        if inputs.is_empty() || !out.is_dir() {
            return Ok(());
        }
        for name in names {
            let Ok(target) = std::fs::canonicalize(out.join(name)) else {
                continue; // not there yet: nothing replaced
            };
            if let Some((_, shown)) = inputs.iter().find(|(p, _)| *p == target) {
                return Err(Error::invalid(
                    "<command line>",
                    "--out",
                    out.display(),
                    format!(
                        "a folder where no output replaces an input: its {name} would \
                         replace the input {shown} (choose another --out)"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Record the waveform files of a scenario table whose file lies in `dir`
    /// ([`scenario_data_files`]).
    pub fn add_scenario_files(&mut self, table: &toml::Table, dir: &Path) -> Result<()> {
        for f in scenario_data_files(table, dir) {
            self.add_data_file(&f)?;
        }
        Ok(())
    }

    /// The `"provenance"` object.
    pub fn to_json(&self) -> Value {
        let files: Vec<Value> = self
            .data_files
            .iter()
            .map(|d| json!({"path": d.path, "sha256": d.sha256}))
            .collect();
        json!({
            "contactwave_version": self.contactwave_version,
            "git_commit": self.git_commit,
            "git_dirty": self.git_dirty,
            "input": self.input,
            "scenario_sha256": self.scenario_sha256,
            "data_files": files,
            "command_line": self.command_line,
            "created": self.created,
        })
    }

    /// The flat `(name, text)` pairs of the HDF5 root attributes: the keys above, with
    /// `data_files` as `data_file_N_path` and `data_file_N_sha256`, and `null` as `""`.
    pub fn attributes(&self) -> Vec<(String, String)> {
        let s = |o: &Option<String>| o.clone().unwrap_or_default();
        let mut a = vec![
            (
                "contactwave_version".into(),
                self.contactwave_version.clone(),
            ),
            ("git_commit".into(), s(&self.git_commit)),
            (
                "git_dirty".into(),
                self.git_dirty.map(|d| d.to_string()).unwrap_or_default(),
            ),
            ("input".into(), s(&self.input)),
            ("scenario_sha256".into(), s(&self.scenario_sha256)),
            ("command_line".into(), self.command_line.clone()),
            ("created".into(), self.created.clone()),
        ];
        for (i, d) in self.data_files.iter().enumerate() {
            a.push((format!("data_file_{i}_path"), d.path.clone()));
            a.push((format!("data_file_{i}_sha256"), d.sha256.clone()));
        }
        a
    }

    /// The sweep's sidecar `provenance.json`: `{"provenance": {...}}`.
    pub fn sidecar(&self) -> OutputFile {
        let text = serde_json::to_string_pretty(&json!({ "provenance": self.to_json() }))
            .unwrap_or_default();
        OutputFile::new(SIDECAR, text + "\n")
    }

    /// Insert the `"provenance"` object as the last key of a rendered JSON object (the
    /// text before it unchanged). Text that is not a JSON object is returned as it is.
    pub fn stamp_json(&self, text: &str) -> String {
        let body = text.trim_end();
        let Some(inner) = body.strip_suffix('}') else {
            return text.to_string();
        };
        if !body.trim_start().starts_with('{') {
            return text.to_string();
        }
        let inner = inner.trim_end();
        let pretty = serde_json::to_string_pretty(&self.to_json()).unwrap_or_default();
        let indented = pretty.replace('\n', "\n  ");
        let sep = if inner.trim_start() == "{" { "" } else { "," };
        let tail = &text[body.len()..];
        let tail = if tail.is_empty() { "" } else { "\n" };
        format!("{inner}{sep}\n  \"provenance\": {indented}\n}}{tail}")
    }

    /// Stamp every file of [`STAMPED`] among `files` ([`Provenance::stamp_json`]).
    pub fn stamp(&self, files: &mut [OutputFile]) {
        for f in files.iter_mut() {
            if STAMPED.contains(&f.name.as_str()) {
                f.contents = self.stamp_json(&f.contents);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamping_keeps_the_text_before_and_parses() {
        let p = Provenance::new("contactwave run a.toml --out 'my out'");
        for text in [
            "{\"a\": 1.5, \"b\": null}\n",
            "{\n  \"x\": [1, 2]\n}",
            "{}\n",
        ] {
            let s = p.stamp_json(text);
            let v: Value = serde_json::from_str(&s).unwrap();
            assert_eq!(v["provenance"]["contactwave_version"], VERSION);
            assert_eq!(
                v["provenance"]["command_line"],
                "contactwave run a.toml --out 'my out'"
            );
            let head = text.trim_end().trim_end_matches('}').trim_end();
            assert!(s.starts_with(head), "{s}");
            assert_eq!(s.ends_with('\n'), text.ends_with('\n'));
        }
        // not an object: unchanged
        assert_eq!(p.stamp_json("[1, 2]"), "[1, 2]");
    }

    #[test]
    fn created_is_rfc3339_utc_and_quoting_is_posix() {
        let c = now_utc();
        assert_eq!(c.len(), 20, "{c}");
        assert!(c.ends_with('Z') && c.as_bytes()[10] == b'T', "{c}");
        let year: i32 = c[..4].parse().unwrap();
        assert!(year >= 2024, "{c}");
        assert_eq!(shell_quote("a.toml"), "a.toml");
        assert_eq!(shell_quote("my dir"), "'my dir'");
        assert_eq!(shell_quote("it's"), r"'it'\''s'");
        assert_eq!(shell_quote(""), "''");
    }

    #[test]
    fn hashes_are_sha256_of_the_bytes() {
        // FIPS 180-2 test vector
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        if let Some(c) = git_commit() {
            assert!(c.len() == 40 && c.chars().all(|x| x.is_ascii_hexdigit()));
        }
    }

    #[test]
    fn a_scenarios_waveform_files_are_found() {
        let d = std::env::temp_dir().join(format!("contactwave-prov-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("w")).unwrap();
        std::fs::write(d.join("w/burst.csv"), "t,s\n0,0\n1e-6,1\n").unwrap();
        let t: toml::Table = toml::from_str(
            "[incident]\nkind = \"file\"\npath = \"w/burst.csv\"\n[medium]\nmaterial = \"path\"\n[x]\npath = \"missing.csv\"\n",
        )
        .unwrap();
        assert_eq!(scenario_data_files(&t, &d), vec![d.join("w/burst.csv")]);
        let mut p = Provenance::new("test");
        p.add_scenario_files(&t, &d).unwrap();
        p.add_scenario_files(&t, &d).unwrap();
        assert_eq!(p.data_files.len(), 1);
        assert_eq!(p.data_files[0].sha256, sha256_hex(b"t,s\n0,0\n1e-6,1\n"));
        let _ = std::fs::remove_dir_all(&d);
    }
}

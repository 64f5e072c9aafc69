//! The files of a sweep's output, written and read back: the rows of `sweep.csv`
//! ([`Writer`], [`read_sweep_csv`], [`SweepTable`]), the hash side file ([`hash_path`]) and
//! the canonical serialisation behind the hash ([`hash_sweep`]), and the errors file
//! ([`errors_path`]). The formats are described in the `study::sweep` module doc.
//!
//! This module knows rows of numbers, dotted keys and TOML tables, not the `Sweep` type:
//! the file format builds the hash from its parts and the driver hands each row over.

use crate::analysis::{push_csv_number, Summary};
use crate::error::{Error, Result};
use sha2::{Digest, Sha256};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Version tag of the canonical serialisation behind the sweep hash ([`hash_sweep`]).
const HASH_FORMAT: &str = "contactwave-sweep-hash-1";

/// A `sweep.csv` read back: header and numeric rows (in file order).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows; every row has `header.len()` values.
    pub rows: Vec<Vec<f64>>,
}

impl SweepTable {
    /// Index of a column.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }
}

/// Canonical text of a TOML value: tables with sorted keys, floats by their bits.
fn canonical(v: &toml::Value, out: &mut String) {
    use std::fmt::Write as _;
    match v {
        toml::Value::String(s) => {
            let _ = write!(out, "s{}:{s}", s.len());
        }
        toml::Value::Integer(i) => {
            let _ = write!(out, "i{i};");
        }
        toml::Value::Float(x) => {
            let _ = write!(out, "f{:016x};", x.to_bits());
        }
        toml::Value::Boolean(b) => {
            let _ = write!(out, "b{b};");
        }
        toml::Value::Datetime(d) => {
            let d = d.to_string();
            let _ = write!(out, "d{}:{d}", d.len());
        }
        toml::Value::Array(a) => {
            let _ = write!(out, "a{}[", a.len());
            for x in a {
                canonical(x, out);
            }
            out.push(']');
        }
        toml::Value::Table(t) => canonical_table(t, out),
    }
}

fn canonical_table(t: &toml::Table, out: &mut String) {
    use std::fmt::Write as _;
    let mut keys: Vec<&String> = t.keys().collect();
    keys.sort();
    let _ = write!(out, "t{}{{", keys.len());
    for k in keys {
        let _ = write!(out, "k{}:{k}", k.len());
        canonical(&t[k], out);
    }
    out.push('}');
}

/// SHA-256 (hex) of the canonical serialisation of a sweep: [`HASH_FORMAT`], the
/// contactwave version, the base table, the axes (dotted key and values, in file order)
/// and the grid points. This is `Sweep::hash`.
pub(super) fn hash_sweep(
    base: &toml::Table,
    axes: &[(&str, &[f64])],
    points: &[Vec<f64>],
) -> String {
    let mut h = Sha256::new();
    let mut s = String::new();
    s.push_str(HASH_FORMAT);
    s.push('\n');
    s.push_str(env!("CARGO_PKG_VERSION"));
    s.push('\n');
    canonical_table(base, &mut s);
    s.push('\n');
    for (parameter, values) in axes {
        s.push_str(&format!("axis {}:{}", parameter.len(), parameter));
        for v in *values {
            s.push_str(&format!(" {:016x}", v.to_bits()));
        }
        s.push('\n');
    }
    h.update(s.as_bytes());
    let mut line = String::new();
    for p in points {
        line.clear();
        for v in p {
            line.push_str(&format!("{:016x} ", v.to_bits()));
        }
        line.push('\n');
        h.update(line.as_bytes());
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A float that parses back to itself (`NaN`, `inf`, `-inf` for non-finite values).
pub(super) fn fmt_f64(v: f64) -> String {
    format!("{v:?}")
}

/// Path of the hash side file of a sweep CSV (`<csv>.hash`).
pub fn hash_path(csv: &Path) -> PathBuf {
    let mut s = csv.as_os_str().to_owned();
    s.push(".hash");
    PathBuf::from(s)
}

/// Path of the errors file of a sweep CSV (`<stem>_errors.csv` beside it).
pub fn errors_path(csv: &Path) -> PathBuf {
    let stem = csv
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".to_string());
    csv.with_file_name(format!("{stem}_errors.csv"))
}

/// Read a `sweep.csv` (header, then numeric rows). A last line without its newline (a
/// write cut short) is ignored.
pub fn read_sweep_csv(path: &Path) -> Result<SweepTable> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_sweep_csv(&text, path)
}

/// Parse the text of a `sweep.csv` read from `path` (see [`read_sweep_csv`]).
pub(super) fn parse_sweep_csv(text: &str, path: &Path) -> Result<SweepTable> {
    let file = path.display().to_string();
    let complete = match text.rfind('\n') {
        Some(k) => &text[..=k],
        None => "",
    };
    let mut lines = complete.lines();
    let header: Vec<String> = match lines.next() {
        Some(h) if !h.trim().is_empty() => h.split(',').map(|s| s.trim().to_string()).collect(),
        _ => {
            return Ok(SweepTable {
                header: vec![],
                rows: vec![],
            });
        }
    };
    let mut rows = Vec::new();
    for (k, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let row: std::result::Result<Vec<f64>, _> =
            line.split(',').map(|s| s.trim().parse::<f64>()).collect();
        match row {
            Ok(r) if r.len() == header.len() => rows.push(r),
            _ => {
                return Err(Error::Parse {
                    file,
                    message: format!(
                        "line {}: expected {} numbers separated by commas",
                        k + 2,
                        header.len()
                    ),
                });
            }
        }
    }
    Ok(SweepTable { header, rows })
}

/// The open output files of a running sweep (shared by the workers behind one lock): the CSV
/// and, once a point has failed, the errors file.
pub(super) struct Writer {
    /// The CSV, open for writing or appending.
    pub(super) csv: File,
    /// Its path (for error messages).
    pub(super) csv_path: PathBuf,
    /// The header, once written (or found in a resumed CSV).
    pub(super) header: Option<Vec<String>>,
    /// The errors file, created at the first failed point.
    pub(super) errors: Option<File>,
    /// Its path.
    pub(super) errors_path: PathBuf,
    /// Number of axis columns after `point`.
    pub(super) n_axes: usize,
    /// Rows written.
    pub(super) computed: usize,
    /// Failed points listed.
    pub(super) failed: usize,
}

impl Writer {
    /// Append the row of grid point `i`: the index, the point's axis values `point`, then the
    /// summary values in header order. Writes the header (`make_header()`) first if the CSV
    /// has none yet.
    pub(super) fn row(
        &mut self,
        i: usize,
        point: &[f64],
        summary: &Summary,
        make_header: impl FnOnce() -> Vec<String>,
    ) -> Result<()> {
        if self.header.is_none() {
            let h = make_header();
            let line = format!("{}\n", h.join(","));
            self.csv
                .write_all(line.as_bytes())
                .map_err(|e| Error::io(&self.csv_path, e))?;
            self.header = Some(h);
        }
        let header = self.header.as_deref().unwrap_or(&[]);
        let n_axes = self.n_axes;
        let mut line = i.to_string();
        let mut buf = zmij::Buffer::new();
        for v in point {
            line.push(',');
            push_csv_number(&mut line, &mut buf, *v);
        }
        for key in header.iter().skip(1 + n_axes) {
            line.push(',');
            push_csv_number(&mut line, &mut buf, summary.get(key).unwrap_or(f64::NAN));
        }
        line.push('\n');
        self.csv
            .write_all(line.as_bytes())
            .and_then(|_| self.csv.flush())
            .map_err(|e| Error::io(&self.csv_path, e))?;
        self.computed += 1;
        Ok(())
    }

    /// List grid point `i` with its error `message` in the errors file (created, with its
    /// header, at the first call).
    pub(super) fn error(&mut self, i: usize, message: &str) -> Result<()> {
        if self.errors.is_none() {
            let mut f =
                File::create(&self.errors_path).map_err(|e| Error::io(&self.errors_path, e))?;
            f.write_all(b"point,message\n")
                .map_err(|e| Error::io(&self.errors_path, e))?;
            self.errors = Some(f);
        }
        let msg = message.replace('"', "\"\"").replace(['\n', '\r'], " ");
        if let Some(f) = self.errors.as_mut() {
            f.write_all(format!("{i},\"{msg}\"\n").as_bytes())
                .and_then(|_| f.flush())
                .map_err(|e| Error::io(&self.errors_path, e))?;
        }
        self.failed += 1;
        Ok(())
    }
}

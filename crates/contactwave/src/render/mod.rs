//! Rendering results into files in memory: CSV columns, `summary.json`, and SVG figures
//! (`svg`, with the `plot` feature). Nothing here touches the disk or knows the physics;
//! models and studies describe their files with these primitives and [`crate::output`]
//! writes them.

#[cfg(feature = "plot")]
pub mod svg;

use crate::analysis::Summary;
use serde::ser::{Serialize, SerializeMap, Serializer};
use std::fmt::Write as _;

/// A rendered output file: its name in the output folder and its contents.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputFile {
    /// File name (no folder).
    pub name: String,
    /// Contents.
    pub contents: String,
}

impl OutputFile {
    /// A file named `name` with `contents`.
    pub fn new(name: &str, contents: String) -> Self {
        OutputFile {
            name: name.to_string(),
            contents,
        }
    }
}

/// CSV text from a header and equally long columns (the shortest column sets the length).
pub fn csv_columns(header: &str, columns: &[&[f64]]) -> String {
    let n = columns.iter().map(|c| c.len()).min().unwrap_or(0);
    let mut s = String::with_capacity(header.len() + 1 + n * columns.len() * 24);
    s.push_str(header);
    s.push('\n');
    for i in 0..n {
        for (k, c) in columns.iter().enumerate() {
            if k > 0 {
                s.push(',');
            }
            let _ = write!(s, "{:?}", c[i]);
        }
        s.push('\n');
    }
    s
}

struct SummaryJson<'a> {
    scenario: &'a str,
    summary: &'a Summary,
}

impl Serialize for SummaryJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("scenario", self.scenario)?;
        for (k, v) in self.summary.iter() {
            if v.is_finite() {
                m.serialize_entry(k, &v)?;
            } else {
                m.serialize_entry(k, &Option::<f64>::None)?;
            }
        }
        m.end()
    }
}

/// `summary.json`: `{"scenario": <file>, <summary keys in order>...}`.
pub fn summary_json(scenario_file: &str, summary: &Summary) -> String {
    let mut s = serde_json::to_string_pretty(&SummaryJson {
        scenario: scenario_file,
        summary,
    })
    .unwrap_or_else(|_| "{}".to_string());
    s.push('\n');
    s
}

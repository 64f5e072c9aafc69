//! Rendering results into files in memory: CSV columns, `summary.json`, and SVG figures
//! (`svg`, with the `plot` feature). Nothing here touches the disk or knows the physics;
//! models and studies describe their files with these primitives and [`crate::output`]
//! writes them.

#[cfg(feature = "plot")]
pub mod picture;
#[cfg(feature = "plot")]
pub mod svg;
#[cfg(feature = "plot")]
pub mod vtk;

use crate::analysis::{push_csv_number, Summary};

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

/// A rendered binary file (a PNG image, a GIF animation): its name in the output folder
/// (a subfolder allowed: `snapshots/frame_0000.png`) and its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct BinaryFile {
    /// File name, relative to the output folder.
    pub name: String,
    /// Contents.
    pub bytes: Vec<u8>,
}

/// CSV text from a header and equally long columns (the shortest column sets the length).
/// Numbers are written by [`push_csv_number`]: whole numbers as integers, others in their
/// shortest round-trip form (parsing a cell gives the same `f64` back).
pub fn csv_columns(header: &str, columns: &[&[f64]]) -> String {
    let n = columns.iter().map(|c| c.len()).min().unwrap_or(0);
    csv_rows(header, columns, 0..n)
}

/// The CSV text of the rows `rows` of `columns` (each index below every column's length).
///
/// Large tables (a 2D receiver line records tens of thousands of columns) are formatted in
/// parallel, a band of rows a task, and appended in order a few bands at a time: the same
/// text for any thread count. A band reads its columns a group at a time for all its rows
/// (a column's neighbouring rows share a cache line), not row by row across every column.
fn csv_rows(
    header: &str,
    columns: &[&[f64]],
    rows: impl ExactSizeIterator<Item = usize>,
) -> String {
    use rayon::prelude::*;
    /// Cells a band formats at least (about 1.5 MB of text), and rows it takes at least.
    const BAND_CELLS: usize = 1 << 16;
    const BAND_ROWS: usize = 8;
    /// Columns read together for a band's rows.
    const GROUP: usize = 256;
    let mut s = String::with_capacity(header.len() + 1 + rows.len() * columns.len() * 22);
    s.push_str(header);
    s.push('\n');
    let rows: Vec<usize> = rows.collect();
    let per_band = (BAND_CELLS / columns.len().max(1)).max(BAND_ROWS);
    let wave = per_band * 2 * rayon::current_num_threads().max(1);
    for rows in rows.chunks(wave) {
        let bands: Vec<Vec<String>> = rows
            .par_chunks(per_band)
            .map(|band| {
                let mut lines: Vec<String> = (0..band.len())
                    .map(|_| String::with_capacity(columns.len() * 22 + 1))
                    .collect();
                let mut buf = zmij::Buffer::new();
                for (g, group) in columns.chunks(GROUP).enumerate() {
                    for (line, &i) in lines.iter_mut().zip(band) {
                        for (k, c) in group.iter().enumerate() {
                            if g > 0 || k > 0 {
                                line.push(',');
                            }
                            push_csv_number(line, &mut buf, c[i]);
                        }
                    }
                }
                lines
            })
            .collect();
        for line in bands.iter().flatten() {
            s.push_str(line);
            s.push('\n');
        }
    }
    s
}

/// Files that hold recorded series, one row per time sample (time in s in the first
/// column): the rows they keep are chosen by [`Rows`].
pub const TIME_SERIES_FILES: [&str; 5] = [
    "timeseries.csv",
    "probe.csv",
    "probes.csv",
    "waves.csv",
    "shear.csv",
];

/// Which rows of a time-series file ([`TIME_SERIES_FILES`]) are written
/// (`contactwave run --record`, `--record-step`; `output::recording`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Rows {
    /// No such file.
    None,
    /// Every row.
    #[default]
    All,
    /// Every k-th row from the first, and the last, k the smallest integer that leaves at
    /// most this many rows.
    AtMost(usize),
    /// One row every this many seconds (rounded to a whole number of time steps, at least
    /// one, the time step read from the first two times), and the last.
    Every(f64),
}

impl Rows {
    /// The indices kept of `t.len()` rows at times `t` (s), in order (none for
    /// [`Rows::None`]).
    pub fn pick(self, t: &[f64]) -> impl ExactSizeIterator<Item = usize> + use<> {
        let n = t.len();
        let k = match self {
            Rows::None | Rows::All => 1,
            Rows::AtMost(m) => n.div_ceil(m.max(1)).max(1),
            Rows::Every(step) => {
                let dt = match (t.first(), t.get(1)) {
                    (Some(a), Some(b)) if b > a => b - a,
                    _ => step,
                };
                ((step / dt).round() as usize).max(1)
            }
        };
        let n = if self == Rows::None { 0 } else { n };
        // every k-th from the first, and the last when the stride misses it
        let last = usize::from(n > 0 && (n - 1) % k != 0);
        let count = n.div_ceil(k) + last;
        (0..count).map(move |j| if j * k < n { j * k } else { n - 1 })
    }
}

/// A time-series file: its CSV with the rows picked by `rows` from `columns`, the first
/// column the time (s); `None` for [`Rows::None`].
pub fn time_series(name: &str, header: &str, columns: &[&[f64]], rows: Rows) -> Option<OutputFile> {
    if rows == Rows::None {
        return None;
    }
    let n = columns.iter().map(|c| c.len()).min().unwrap_or(0);
    let t = columns.first().map_or(&[][..], |c| &c[..n]);
    Some(OutputFile::new(
        name,
        csv_rows(header, columns, rows.pick(t)),
    ))
}

/// A rendered file with the rows of a time-series file picked by `rows` (read back from its
/// text: time in the first column); any other file as it is.
pub fn pick_rows(file: OutputFile, rows: Rows) -> Option<OutputFile> {
    if !TIME_SERIES_FILES.contains(&file.name.as_str()) || rows == Rows::All {
        return Some(file);
    }
    if rows == Rows::None {
        return None;
    }
    let mut lines = file.contents.lines();
    let Some(header) = lines.next() else {
        return Some(file);
    };
    let body: Vec<&str> = lines.collect();
    let time = |r: &str| {
        r.split(',')
            .next()
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    // the pick needs the number of rows and the first two times only
    let t: Vec<f64> = (0..body.len())
        .map(|i| if i < 2 { time(body[i]) } else { f64::NAN })
        .collect();
    let mut out = String::with_capacity(file.contents.len() + 64);
    out.push_str(header);
    out.push('\n');
    for i in rows.pick(&t) {
        out.push_str(body[i]);
        out.push('\n');
    }
    Some(OutputFile::new(&file.name, out))
}

/// `summary.json`'s object: the scenario, then the summary's keys in order (written by
/// [`Summary`]'s own serializer).
#[derive(serde::Serialize)]
struct SummaryJson<'a> {
    scenario: &'a str,
    #[serde(flatten)]
    summary: &'a Summary,
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

/// Write the warnings of a run into its `summary.json` among `files`: the key `warnings`, a
/// list of strings (one per warning, as `contactwave run` prints it after `warning: `),
/// after the summary's keys (a provenance stamped later comes after it). Without warnings,
/// or without a `summary.json` holding an object, the files are left as they are.
///
/// ```
/// use contactwave::render::{stamp_warnings, summary_json, OutputFile};
/// use contactwave::analysis::Summary;
/// let mut s = Summary::new();
/// s.set("xi", 0.5);
/// let mut files = vec![OutputFile::new("summary.json", summary_json("a.toml", &s))];
/// stamp_warnings(&mut files, &["a.toml: model.width = 60 m: longer than 10 m".to_string()]);
/// let v: serde_json::Value = serde_json::from_str(&files[0].contents).unwrap();
/// assert_eq!(v["xi"], 0.5);
/// assert_eq!(v["warnings"][0], "a.toml: model.width = 60 m: longer than 10 m");
/// ```
pub fn stamp_warnings(files: &mut [OutputFile], warnings: &[String]) {
    if warnings.is_empty() {
        return;
    }
    let Some(f) = files.iter_mut().find(|f| f.name == "summary.json") else {
        return;
    };
    let body = f.contents.trim_end();
    let Some(inner) = body.strip_suffix('}') else {
        return;
    };
    if !body.trim_start().starts_with('{') {
        return;
    }
    let inner = inner.trim_end();
    let list = serde_json::to_string_pretty(warnings)
        .unwrap_or_default()
        .replace('\n', "\n  ");
    let sep = if inner.trim_start() == "{" { "" } else { "," };
    f.contents = format!("{inner}{sep}\n  \"warnings\": {list}\n}}\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The warnings come after every key of the summary, which keeps its text, and an
    /// empty list leaves the file as it was.
    #[test]
    fn warnings_follow_the_summary_keys() {
        let mut s = Summary::new();
        s.set("A2_over_A1", f64::NAN);
        let text = summary_json("a.toml", &s);
        let mut files = vec![OutputFile::new("summary.json", text.clone())];
        stamp_warnings(&mut files, &[]);
        assert_eq!(files[0].contents, text);
        let w = ["one \"quoted\"".to_string(), "two".to_string()];
        stamp_warnings(&mut files, &w);
        let t = &files[0].contents;
        assert!(
            t.starts_with(text.trim_end().trim_end_matches('}').trim_end()),
            "{t}"
        );
        let v: serde_json::Value = serde_json::from_str(t).unwrap();
        assert!(t.find("\"warnings\"") > t.find("\"A2_over_A1\""), "{t}");
        assert_eq!(v["A2_over_A1"], serde_json::Value::Null);
        assert_eq!(v["warnings"], serde_json::json!(["one \"quoted\"", "two"]));
        assert!(t.ends_with("]\n}\n"), "{t}");
    }

    /// A wide table (formatted in bands of rows and groups of columns, in parallel) is the
    /// row-by-row text, read back to the same numbers, for any thread count.
    #[test]
    fn wide_tables_are_written_row_by_row() {
        for (n_rows, n_cols) in [(0usize, 3usize), (1, 1), (9, 700), (130, 600), (37, 2)] {
            let cols: Vec<Vec<f64>> = (0..n_cols)
                .map(|k| {
                    (0..n_rows)
                        .map(|i| (i * n_cols + k) as f64 / 7.0 - 3.0)
                        .collect()
                })
                .collect();
            let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
            let header = (0..n_cols)
                .map(|k| format!("c{k}"))
                .collect::<Vec<_>>()
                .join(",");
            let mut plain = format!("{header}\n");
            for i in 0..n_rows {
                let row: Vec<String> = cols.iter().map(|c| c[i].to_string()).collect();
                plain.push_str(&row.join(","));
                plain.push('\n');
            }
            let one = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .unwrap();
            let two = rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap();
            let a = one.install(|| csv_columns(&header, &refs));
            let b = two.install(|| csv_columns(&header, &refs));
            assert_eq!(a, b);
            let parse = |t: &str| -> Vec<f64> {
                t.lines()
                    .skip(1)
                    .flat_map(|l| {
                        l.split(',')
                            .map(|x| x.parse::<f64>().unwrap())
                            .collect::<Vec<_>>()
                    })
                    .collect()
            };
            assert_eq!(a.lines().count(), n_rows + 1);
            assert_eq!(parse(&a), parse(&plain), "{n_rows} x {n_cols}");
        }
    }

    /// The rows rendered from columns are those picked from the full text: every k-th from
    /// the first and the last, for every row count and choice.
    #[test]
    fn rows_from_columns_match_rows_from_text() {
        for n in [0usize, 1, 2, 3, 7, 20, 21, 40, 41, 100] {
            let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.25).collect();
            let x: Vec<f64> = (0..n).map(|i| (i as f64).sqrt()).collect();
            let full = csv_columns("t,x", &[&t, &x]);
            for rows in [
                Rows::None,
                Rows::All,
                Rows::AtMost(1),
                Rows::AtMost(10),
                Rows::AtMost(1000),
                Rows::Every(0.25),
                Rows::Every(1.1),
                Rows::Every(100.0),
            ] {
                let direct = time_series("timeseries.csv", "t,x", &[&t, &x], rows);
                let picked = pick_rows(OutputFile::new("timeseries.csv", full.clone()), rows);
                assert_eq!(direct, picked, "{n} rows, {rows:?}");
                // the rule: every k-th row from the first, and the last
                if let Some(f) = direct {
                    let kept = f.contents.lines().count() - 1;
                    let k = match rows {
                        Rows::AtMost(m) => n.div_ceil(m).max(1),
                        Rows::Every(s) => ((s / 0.25f64).round() as usize).max(1),
                        _ => 1,
                    };
                    let want = (0..n).filter(|i| i % k == 0 || i + 1 == n).count();
                    assert_eq!(kept, want, "{n} rows, {rows:?}");
                }
            }
        }
    }
}

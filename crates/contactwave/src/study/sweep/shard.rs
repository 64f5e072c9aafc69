//! Sharded sweeps: run one slice of a sweep's grid per machine (`contactwave sweep --shard
//! K/N`) and merge the shard CSVs back into one `sweep.csv` (`contactwave merge`).
//!
//! Shard `K/N` (`1 <= K <= N`) holds the grid points `i` with `i % N == K - 1`: every
//! shard gets an even share of every region of the grid. A shard's CSV has the header and
//! the hash side file of the whole sweep, so [`merge_sweep_csvs`] can check that the shards
//! belong together, that no point is missing and none appears twice, and write one CSV
//! sorted by point with its hash file, exactly what an unsharded run would have written
//! (rows in grid order instead of completion order).
//!
//! Below the driver: it reads what the CSV I/O wrote and checks it against a [`Sweep`];
//! the driver runs a shard's points, this module never runs anything.

use super::csv_io::{errors_path, hash_path, read_sweep_csv};
use super::format::Sweep;
use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One slice of a sweep's grid: shard `index` of `count` (1-based, `1 <= index <= count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, 1-based.
    pub index: usize,
    /// N, the number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole grid (shard 1/1).
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// A shard `K/N`; `None` unless `1 <= K <= N`.
    pub fn new(index: usize, count: usize) -> Option<Shard> {
        (count >= 1 && (1..=count).contains(&index)).then_some(Shard { index, count })
    }

    /// Parse `K/N` (e.g. `2/8`); the error says what is allowed.
    pub fn parse(text: &str) -> std::result::Result<Shard, String> {
        let bad = || format!("`{text}`: expected K/N with integers 1 <= K <= N, e.g. 2/8");
        let (k, n) = text.trim().split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        Shard::new(k, n).ok_or_else(bad)
    }

    /// Whether grid point `i` (0-based) belongs to this shard: `i % N == K - 1`.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What [`merge_sweep_csvs`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeReport {
    /// Rows (points) in the merged CSV.
    pub points: usize,
    /// Shard CSVs merged.
    pub shards: usize,
    /// The merged CSV.
    pub csv: PathBuf,
    /// Its hash side file.
    pub hash_file: PathBuf,
}

fn invalid(file: &Path, field: &str, value: impl std::fmt::Display, allowed: String) -> Error {
    Error::invalid(file.display().to_string(), field, value, allowed)
}

/// Listed briefly: `3, 7, 12, ... (40 in all)`.
fn brief(points: &[usize]) -> String {
    let mut s = points
        .iter()
        .take(10)
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    if points.len() > 10 {
        s.push_str(&format!(", ... ({} in all)", points.len()));
    }
    s
}

/// Merge shard CSVs of one sweep into `out` (sorted by point) and write `out`'s hash side
/// file.
///
/// Checks, each failing with an error that names the file: every shard has a hash side
/// file and all hashes are equal (and equal to `sweep`'s hash when given); the headers of
/// all shards with rows are equal; no point appears twice (in one shard or across shards);
/// no point is missing: with `sweep`, the points are exactly `0..sweep.points.len()`,
/// without it `0..=max point`. Points missing because their simulation failed are named as
/// such when a shard's errors file lists them. Rows are copied unchanged (numbers keep
/// their text, hence their bits). Nothing is written when a check fails.
pub fn merge_sweep_csvs(
    out: &Path,
    shards: &[PathBuf],
    sweep: Option<&Sweep>,
) -> Result<MergeReport> {
    if shards.is_empty() {
        return Err(invalid(
            out,
            "shards",
            "(none)",
            "give at least one shard CSV to merge".into(),
        ));
    }
    let mut hash: Option<(String, PathBuf)> = None;
    let mut header: Option<(String, PathBuf)> = None;
    let mut rows: BTreeMap<usize, (String, usize)> = BTreeMap::new();
    let mut failed: BTreeMap<usize, String> = BTreeMap::new();
    for (s, path) in shards.iter().enumerate() {
        let hp = hash_path(path);
        let h = std::fs::read_to_string(&hp).map_err(|e| Error::io(&hp, e))?;
        let h = h.trim().to_string();
        match &hash {
            None => {
                if let Some(sw) = sweep {
                    if sw.hash != h {
                        return Err(invalid(
                            path,
                            "hash",
                            &h,
                            format!(
                                "the shard was written by a different sweep (base scenario, \
                                 axes or contactwave version) than {} (hash {})",
                                sw.file.display(),
                                sw.hash
                            ),
                        ));
                    }
                }
                hash = Some((h, path.clone()));
            }
            Some((h0, p0)) if *h0 != h => {
                return Err(invalid(
                    path,
                    "hash",
                    &h,
                    format!(
                        "differs from the hash of {} ({h0}): the shards come from different \
                         sweeps",
                        p0.display()
                    ),
                ))
            }
            Some(_) => {}
        }
        // validate the numbers, then keep each row's text as written
        let table = read_sweep_csv(path)?;
        if table.header.is_empty() {
            continue;
        }
        if table.header.first().map(String::as_str) != Some("point") {
            return Err(Error::Parse {
                file: path.display().to_string(),
                message: "not a sweep CSV: the first column must be `point`".into(),
            });
        }
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let complete = match text.rfind('\n') {
            Some(k) => &text[..=k],
            None => "",
        };
        let mut lines = complete.lines();
        let head = lines.next().unwrap_or_default().trim().to_string();
        match &header {
            None => header = Some((head, path.clone())),
            Some((h0, p0)) if *h0 != head => {
                return Err(Error::Parse {
                    file: path.display().to_string(),
                    message: format!(
                        "the header differs from that of {}: `{head}` vs `{h0}`",
                        p0.display()
                    ),
                })
            }
            Some(_) => {}
        }
        for line in lines.filter(|l| !l.trim().is_empty()) {
            let first = line.split(',').next().unwrap_or_default().trim();
            let p: f64 = first.parse().unwrap_or(f64::NAN);
            if !(p >= 0.0 && p.fract() == 0.0 && p < 1e15) {
                return Err(invalid(
                    path,
                    "point",
                    first,
                    "must be a grid index (an integer >= 0)".into(),
                ));
            }
            let p = p as usize;
            if let Some((_, other)) = rows.get(&p) {
                return Err(invalid(
                    path,
                    "point",
                    p,
                    format!(
                        "appears twice (also in {}): the shards overlap",
                        shards[*other].display()
                    ),
                ));
            }
            rows.insert(p, (line.trim_end().to_string(), s));
        }
        let ep = errors_path(path);
        if let Ok(t) = std::fs::read_to_string(&ep) {
            for line in t.lines().skip(1) {
                if let Some((p, msg)) = line.split_once(',') {
                    if let Ok(p) = p.trim().parse::<usize>() {
                        failed.insert(p, format!("{}: {}", ep.display(), msg.trim_matches('"')));
                    }
                }
            }
        }
    }
    let expected = match sweep {
        Some(sw) => sw.points.len(),
        None => rows.keys().next_back().map(|m| m + 1).unwrap_or(0),
    };
    if let Some((&p, _)) = rows.range(expected..).next() {
        return Err(invalid(
            &shards[rows[&p].1],
            "point",
            p,
            format!("is outside the sweep's grid of {expected} points"),
        ));
    }
    let missing: Vec<usize> = (0..expected).filter(|p| !rows.contains_key(p)).collect();
    if !missing.is_empty() {
        let nfailed = missing.iter().filter(|p| failed.contains_key(p)).count();
        let why = if nfailed > 0 {
            let first = missing.iter().find_map(|p| failed.get(p)).cloned();
            format!(
                "; {nfailed} of them failed in their shard (first: {})",
                first.unwrap_or_default()
            )
        } else {
            "; run the missing shards, or resume them with --resume".to_string()
        };
        return Err(invalid(
            out,
            "point",
            brief(&missing),
            format!(
                "missing from the shards: {} of {expected} points have no row{why}",
                missing.len()
            ),
        ));
    }
    let (hash, _) = hash.unwrap_or_default();
    let mut text = String::new();
    if let Some((h, _)) = &header {
        text.push_str(h);
        text.push('\n');
    }
    for (line, _) in rows.values() {
        text.push_str(line);
        text.push('\n');
    }
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let hash_file = hash_path(out);
    let tmp = {
        let mut s = out.as_os_str().to_owned();
        s.push(".merging");
        PathBuf::from(s)
    };
    std::fs::write(&tmp, text).map_err(|e| Error::io(&tmp, e))?;
    std::fs::write(&hash_file, format!("{hash}\n")).map_err(|e| Error::io(&hash_file, e))?;
    std::fs::rename(&tmp, out).map_err(|e| Error::io(out, e))?;
    Ok(MergeReport {
        points: rows.len(),
        shards: shards.len(),
        csv: out.to_path_buf(),
        hash_file,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_and_contains() {
        assert_eq!(Shard::parse("2/8"), Ok(Shard { index: 2, count: 8 }));
        assert_eq!(Shard::parse(" 1 / 1 ").unwrap(), Shard::ALL);
        for bad in ["0/3", "4/3", "1/0", "a/b", "3", "1/2/3", ""] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let s = Shard::new(2, 3).unwrap();
        let mine: Vec<usize> = (0..10).filter(|&i| s.contains(i)).collect();
        assert_eq!(mine, vec![1, 4, 7]);
        assert!((0..100).all(|i| Shard::ALL.contains(i)));
        assert_eq!(s.to_string(), "2/3");
    }
}

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

/// What a sweep CSV holds of its sweep, from its side file `<csv>.shard`
/// ([`shard_path`]): which shard, and the size of the whole grid. Every `contactwave
/// sweep` writes it (`1/1` for a whole sweep) and `merge` writes it for the merged CSV, so
/// that a merge knows which points each shard must hold even without the sweep file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShardFile {
    /// The shard the CSV holds.
    pub shard: Shard,
    /// Points of the whole sweep's grid.
    pub points: usize,
}

/// Path of the shard side file of a sweep CSV (`<csv>.shard`).
pub fn shard_path(csv: &Path) -> PathBuf {
    let mut s = csv.as_os_str().to_owned();
    s.push(".shard");
    PathBuf::from(s)
}

impl ShardFile {
    /// The side file's text: `shard = "K/N"` and `points = TOTAL` (TOML).
    fn text(&self) -> String {
        format!("shard = \"{}\"\npoints = {}\n", self.shard, self.points)
    }

    /// Write the side file of `csv`.
    pub fn write(&self, csv: &Path) -> Result<()> {
        let p = shard_path(csv);
        std::fs::write(&p, self.text()).map_err(|e| Error::io(&p, e))
    }

    /// Read the side file of `csv`; `None` when there is none (a CSV written before the
    /// side file existed).
    pub fn read(csv: &Path) -> Result<Option<ShardFile>> {
        let p = shard_path(csv);
        let text = match std::fs::read_to_string(&p) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(Error::io(&p, e)),
        };
        let bad = |field: &str, value: String| {
            invalid(
                &p,
                field,
                value,
                "expected `shard = \"K/N\"` and `points = TOTAL`, as `contactwave sweep` \
                 writes them"
                    .into(),
            )
        };
        let table: toml::Table = text
            .parse()
            .map_err(|_| bad("shard", text.trim().replace('\n', " ")))?;
        let shard = match table.get("shard") {
            Some(toml::Value::String(s)) => Shard::parse(s).map_err(|_| bad("shard", s.clone()))?,
            other => return Err(bad("shard", format!("{other:?}"))),
        };
        let points = match table.get("points") {
            Some(toml::Value::Integer(n)) if *n >= 0 => *n as usize,
            other => return Err(bad("points", format!("{other:?}"))),
        };
        Ok(Some(ShardFile { shard, points }))
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
    /// Its shard side file ([`ShardFile`], shard `1/1` of the whole grid).
    pub shard_file: PathBuf,
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
/// file and all hashes are equal (and equal to `sweep`'s hash when given); every shard's
/// side file ([`ShardFile`]) gives the same grid size and shard count (and the size of
/// `sweep`'s grid when given; without `sweep` a shard without side file is refused, its
/// grid being unknown); every row belongs to its shard; the headers of all shards with
/// rows are equal; no point appears twice (in one shard or across shards); no point is
/// missing: the points are exactly `0..N` for the grid's `N` points, and the error names
/// the missing points of each shard (given or not). Points missing because their
/// simulation failed are named as such when a shard's errors file lists them. Rows are
/// copied unchanged (numbers keep their text, hence their bits). Nothing is written when a
/// check fails.
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
    let mut sides: Vec<Option<ShardFile>> = Vec::with_capacity(shards.len());
    let mut grid: Option<(usize, String)> =
        sweep.map(|sw| (sw.points.len(), format!("the sweep {}", sw.file.display())));
    let mut count: Option<(usize, &Path)> = None;
    for (s, path) in shards.iter().enumerate() {
        let side = ShardFile::read(path)?;
        match (side, &grid) {
            (None, None) => {
                return Err(invalid(
                    path,
                    "shard",
                    "(no side file)",
                    format!(
                        "{} is missing, so the size of the sweep is unknown: give the sweep \
                         file with --sweep, or rerun the shard",
                        shard_path(path).display()
                    ),
                ));
            }
            (Some(f), Some((n, from))) if f.points != *n => {
                return Err(invalid(
                    path,
                    "points",
                    f.points,
                    format!("{from} has {n} points: the shards come from different sweeps"),
                ));
            }
            (Some(f), None) => {
                grid = Some((f.points, path.display().to_string()));
            }
            _ => {}
        }
        if let Some(f) = side {
            match count {
                Some((n, p0)) if n != f.shard.count => {
                    return Err(invalid(
                        path,
                        "shard",
                        f.shard,
                        format!(
                            "{} is a shard of {n}: the shards were cut differently",
                            p0.display()
                        ),
                    ));
                }
                None => count = Some((f.shard.count, path.as_path())),
                _ => {}
            }
        }
        sides.push(side);
        let hp = hash_path(path);
        let h = std::fs::read_to_string(&hp).map_err(|e| Error::io(&hp, e))?;
        let h = h.trim().to_string();
        match &hash {
            None => {
                if let Some(sw) = sweep
                    && sw.hash != h
                {
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
                ));
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
                });
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
            if let Some(f) = side.filter(|f| !f.shard.contains(p)) {
                return Err(invalid(
                    path,
                    "point",
                    p,
                    format!(
                        "does not belong to shard {} (points i with i % {} == {})",
                        f.shard,
                        f.shard.count,
                        f.shard.index - 1
                    ),
                ));
            }
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
                if let Some((p, msg)) = line.split_once(',')
                    && let Ok(p) = p.trim().parse::<usize>()
                {
                    failed.insert(p, format!("{}: {}", ep.display(), msg.trim_matches('"')));
                }
            }
        }
    }
    let expected = grid.map(|(n, _)| n).unwrap_or(0);
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
                "missing from the shards: {} of {expected} points have no row: {}{why}",
                missing.len(),
                missing_by_shard(&missing, expected, shards, &sides, count.map(|(n, _)| n))
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
    let folder = out.parent().unwrap_or(Path::new("."));
    std::fs::write(&tmp, text).map_err(|e| Error::write_in(folder, e))?;
    std::fs::write(&hash_file, format!("{hash}\n")).map_err(|e| Error::io(&hash_file, e))?;
    let whole = ShardFile {
        shard: Shard::ALL,
        points: expected,
    };
    whole.write(out)?;
    std::fs::rename(&tmp, out).map_err(|e| Error::io(out, e))?;
    Ok(MergeReport {
        points: rows.len(),
        shards: shards.len(),
        csv: out.to_path_buf(),
        hash_file,
        shard_file: shard_path(out),
    })
}

/// The missing points grouped by the shard that should hold them (of a grid of `total`
/// points): `FILE (shard K/N) lacks 2 of its 40 points: 3, 7` for a shard given, `shard
/// K/N (not given) lacks ...` for one of `count` shards that is not, `the shards lack
/// ...` when no side file says.
fn missing_by_shard(
    missing: &[usize],
    total: usize,
    shards: &[PathBuf],
    sides: &[Option<ShardFile>],
    count: Option<usize>,
) -> String {
    let mut groups: BTreeMap<(usize, usize), (String, Shard, Vec<usize>)> = BTreeMap::new();
    for &p in missing {
        let given = sides
            .iter()
            .position(|f| f.is_some_and(|f| f.shard.contains(p)));
        let (key, name, shard) = match (given, count) {
            (Some(s), _) => {
                let f = sides[s].map(|f| f.shard).unwrap_or(Shard::ALL);
                (
                    (f.index, 0),
                    format!("{} (shard {f})", shards[s].display()),
                    f,
                )
            }
            (None, Some(n)) => {
                let f = Shard::new(p % n + 1, n).unwrap_or(Shard::ALL);
                ((f.index, 1), format!("shard {f} (not given)"), f)
            }
            (None, None) => ((0, 2), "the shards".to_string(), Shard::ALL),
        };
        groups.entry(key).or_insert((name, shard, vec![])).2.push(p);
    }
    groups
        .into_values()
        .map(|(name, shard, pts)| {
            let of = (0..total).filter(|&i| shard.contains(i)).count();
            format!(
                "{name} lacks {} of its {of} points: {}",
                pts.len(),
                brief(&pts)
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
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

//! The sweep driver: [`run_sweep`] and [`run_sweep_shard`] plan the sweep and validate
//! every grid point, open (or resume) the CSV, run the points on the [`Executor`] and hand
//! each finished row or error to the CSV writer (the executor's observer), honouring the
//! cancel flag.
//!
//! The top of the sweep modules: it uses the file format, the CSV I/O and the shard
//! arithmetic; nothing imports it back.

use super::csv_io::{errors_path, hash_path, parse_sweep_csv, Writer};
use super::format::Sweep;
use super::shard::{Shard, ShardFile};
use crate::analysis::Summary;
use crate::error::{Error, Result};
use crate::run::{Executor, Observer, Workspaces};
use std::fs::{File, OpenOptions};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The sweep's observer: writes each finished point's row (or error) to the CSV as it
/// ends, reports progress counting the points of a resumed CSV, cancels on the flag.
struct Rows<'a> {
    sweep: &'a Sweep,
    todo: &'a [usize],
    writer: &'a Mutex<Writer>,
    skipped: usize,
    total: usize,
    progress: &'a (dyn Fn(usize, usize) + Sync),
    cancel: &'a AtomicBool,
}

impl Observer<Summary> for Rows<'_> {
    fn point(&self, k: usize, result: &Result<Summary>) -> Result<()> {
        let i = self.todo[k];
        let _writing = crate::interrupt::Writing::start();
        let mut w = self.writer.lock().unwrap_or_else(|p| p.into_inner());
        match result {
            Ok(summary) => w.row(i, &self.sweep.points[i], summary, || {
                self.sweep.header(summary.keys())
            }),
            // a point stopped by an interruption is not a failure: --resume runs it
            Err(Error::Interrupted) => Ok(()),
            Err(e) => w.error(i, &e.to_string()),
        }
    }

    fn progress(&self, done: usize, _total: usize) {
        (self.progress)(self.skipped + done, self.total)
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }
}

/// Options of [`run_sweep`].
#[derive(Debug, Clone, Copy, Default)]
pub struct SweepOptions {
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// Append to an existing CSV of the same sweep, skipping its points.
    pub resume: bool,
    /// The caller validated every point already ([`Sweep::validate_with`], e.g. with a
    /// progress bar): the driver does not validate them again.
    pub validated: bool,
}

/// What a finished [`run_sweep`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport {
    /// Grid points of the sweep.
    pub total: usize,
    /// Points found in the CSV already (resume) and not run again.
    pub skipped: usize,
    /// Points run now that produced a row.
    pub computed: usize,
    /// Points run now whose simulation failed (listed in the errors file).
    pub failed: usize,
    /// The CSV written.
    pub csv: PathBuf,
    /// The errors file, if any point failed.
    pub errors_csv: Option<PathBuf>,
}

/// Run a sweep, writing `out_csv` (and its hash and errors files, see the `study::sweep`
/// module doc).
///
/// The sweep is planned once ([`Sweep::plan`]) and every point is validated first
/// ([`Sweep::runnable`]); nothing is written if one is invalid. Points run on the
/// [`Executor`] with `opts.threads` threads (all cores by default), each with
/// [`crate::model::Model::summary`]; rows are appended and flushed as points finish.
/// `progress(done, total)` is called once at the start (with the points already in a
/// resumed CSV) and after each point. `cancel` is checked before each point; once it is
/// set, the running points finish and are written, and the call returns
/// [`Error::Interrupted`].
///
/// With `opts.resume` and an existing CSV whose hash file matches [`Sweep::hash`], the
/// points already in the CSV are skipped and the others appended; a different or missing
/// hash is an error and the CSV is left untouched. Without `resume`, an existing CSV is
/// overwritten. A point whose simulation fails is listed in the errors file and counted in
/// [`SweepReport::failed`]; the sweep goes on.
///
/// ```
/// use contactwave::scenario::parse_toml;
/// use contactwave::study::{read_sweep_csv, run_sweep, Sweep, SweepOptions};
/// use std::path::{Path, PathBuf};
/// use std::sync::atomic::AtomicBool;
/// let base = parse_toml(r#"
///     [medium]
///     material = "pmma"
///     [interface]
///     static_pressure = 0.1e6     # Pa
///     [incident]
///     frequency = 1e6             # Hz
///     cycles = 10
///     xi = 0.5
///     [solver]
///     samples_per_period = 64
/// "#, "base.toml").unwrap();
/// let sweep = Sweep::from_parts(
///     Path::new("xi_sweep"),
///     PathBuf::from("base.toml"),
///     base,
///     vec![("incident.xi".into(), vec![0.25, 0.5, 2.0])],
/// )
/// .unwrap();
/// let dir = std::env::temp_dir().join(format!("contactwave-doc-sweep-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let csv = dir.join("sweep.csv");
/// let (quiet, cancel) = (|_: usize, _: usize| {}, AtomicBool::new(false));
/// let report = run_sweep(&sweep, &csv, &SweepOptions::default(), &quiet, &cancel).unwrap();
/// assert_eq!((report.total, report.computed, report.failed), (3, 3, 0));
/// // rows come in completion order: sort them by `point` to get grid order
/// let table = read_sweep_csv(&csv).unwrap();
/// let mut rows = table.rows.clone();
/// rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
/// let loss = table.column("contact_loss_fraction").unwrap();
/// let a2 = table.column("A2_over_Ainc").unwrap();
/// // xi < 1 opens the interface (strong second harmonic); xi = 2 keeps it closed
/// assert!(rows[0][loss] > 0.0 && rows[0][a2] > 0.1);
/// assert!(rows[1][loss] > 0.0 && rows[1][a2] > 0.1);
/// assert_eq!(rows[2][loss], 0.0);
/// assert!(rows[2][a2] < 0.01);
/// // resuming the same sweep (same hash) skips the points already in the CSV
/// let resume = SweepOptions { resume: true, ..SweepOptions::default() };
/// let again = run_sweep(&sweep, &csv, &resume, &quiet, &cancel).unwrap();
/// assert_eq!((again.skipped, again.computed), (3, 0));
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn run_sweep(
    sweep: &Sweep,
    out_csv: &Path,
    opts: &SweepOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<SweepReport> {
    run_sweep_shard(sweep, Shard::ALL, out_csv, opts, progress, cancel)
}

/// [`run_sweep`] restricted to one shard of the grid: only the points `i` with
/// `shard.contains(i)` (`i % N == K - 1` for shard `K/N`) run and are written. The CSV's
/// header and hash file are those of the whole sweep, the same for every shard, so shard
/// CSVs can be merged ([`crate::study::merge_sweep_csvs`]) and resumed like whole ones.
/// [`SweepReport::total`] and `progress`'s total count the shard's points.
pub fn run_sweep_shard(
    sweep: &Sweep,
    shard: Shard,
    out_csv: &Path,
    opts: &SweepOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<SweepReport> {
    // every point validated before anything is written, none kept (flat memory)
    let plan = if opts.validated {
        sweep.plan()?
    } else {
        sweep.validate()?
    };
    let grid_total = sweep.points.len();
    if let Some(dir) = out_csv.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let total = (0..grid_total).filter(|&i| shard.contains(i)).count();
    let hash_file = hash_path(out_csv);
    let errors_file = errors_path(out_csv);
    let mut done = vec![false; grid_total];
    let mut header = None;
    let csv = if opts.resume && out_csv.exists() {
        let stored = std::fs::read_to_string(&hash_file).map_err(|e| {
            Error::invalid(
                out_csv.display().to_string(),
                "hash",
                "(unreadable)",
                format!(
                    "cannot resume: {} cannot be read ({e}); remove the CSV or run \
                     without --resume",
                    hash_file.display()
                ),
            )
        })?;
        let stored = stored.trim();
        if stored != sweep.hash {
            return Err(Error::invalid(
                out_csv.display().to_string(),
                "hash",
                stored,
                format!(
                    "cannot resume: the CSV was written by a different sweep (base scenario, \
                     axes or contactwave version); this sweep's hash is {}; remove the CSV \
                     or run without --resume",
                    sweep.hash
                ),
            ));
        }
        if let Some(f) = ShardFile::read(out_csv)?.filter(|f| f.shard != shard) {
            return Err(Error::invalid(
                out_csv.display().to_string(),
                "shard",
                f.shard,
                format!(
                    "cannot resume: the CSV holds shard {}, not {shard}; resume it with \
                     --shard {}",
                    f.shard, f.shard
                ),
            ));
        }
        let text = std::fs::read_to_string(out_csv).map_err(|e| Error::io(out_csv, e))?;
        let table = parse_sweep_csv(&text, out_csv)?;
        if !table.header.is_empty() {
            let expected: Vec<String> = sweep.header(std::iter::empty());
            if table.header.len() < expected.len() || table.header[..expected.len()] != expected {
                return Err(Error::Parse {
                    file: out_csv.display().to_string(),
                    message: format!(
                        "cannot resume: the header does not start with `{}`",
                        expected.join(",")
                    ),
                });
            }
            for r in &table.rows {
                let p = r[0];
                if p >= 0.0 && p.fract() == 0.0 && (p as usize) < grid_total {
                    done[p as usize] = true;
                }
            }
            header = Some(table.header);
        }
        // drop a last line cut short by an interruption
        let keep = text.rfind('\n').map(|k| k + 1).unwrap_or(0);
        let f = OpenOptions::new()
            .write(true)
            .open(out_csv)
            .map_err(|e| Error::io(out_csv, e))?;
        f.set_len(keep as u64).map_err(|e| Error::io(out_csv, e))?;
        drop(f);
        OpenOptions::new()
            .append(true)
            .open(out_csv)
            .map_err(|e| Error::io(out_csv, e))?
    } else {
        std::fs::write(&hash_file, format!("{}\n", sweep.hash))
            .map_err(|e| Error::write_in(out_csv.parent().unwrap_or(Path::new(".")), e))?;
        File::create(out_csv).map_err(|e| Error::io(out_csv, e))?
    };
    ShardFile {
        shard,
        points: grid_total,
    }
    .write(out_csv)?;
    if errors_file.exists() {
        std::fs::remove_file(&errors_file).map_err(|e| Error::io(&errors_file, e))?;
    }
    let todo: Vec<usize> = (0..grid_total)
        .filter(|&i| shard.contains(i) && !done[i])
        .collect();
    let skipped = total - todo.len();
    let writer = Mutex::new(Writer {
        csv,
        csv_path: out_csv.to_path_buf(),
        header,
        errors: None,
        errors_path: errors_file.clone(),
        n_axes: sweep.axes.len(),
        computed: 0,
        failed: 0,
    });
    let observer = Rows {
        sweep,
        todo: &todo,
        writer: &writer,
        skipped,
        total,
        progress,
        cancel,
    };
    // one workspace per worker, kept from point to point
    let workspaces = Workspaces::new();
    let ran = Executor::new().threads(opts.threads).for_each(
        &todo,
        |&i| {
            let model = sweep.model(&plan, i)?;
            workspaces.with(|ws| model.summary_in(ws))
        },
        &observer,
    )?;
    let _ = ran;
    let w = writer.into_inner().unwrap_or_else(|p| p.into_inner());
    let processed = skipped + w.computed + w.failed;
    let _ = w.csv.sync_data();
    if (cancel.load(Ordering::SeqCst) || crate::interrupt::requested()) && processed < total {
        return Err(Error::Interrupted);
    }
    drop(w.csv);
    sort_rows(out_csv)?;
    Ok(SweepReport {
        total,
        skipped,
        computed: w.computed,
        failed: w.failed,
        csv: out_csv.to_path_buf(),
        errors_csv: (w.failed > 0).then_some(errors_file),
    })
}

/// Rewrite a finished sweep CSV with its rows in point order (they were appended in
/// completion order), byte for byte otherwise, through a temporary file and a rename. A
/// CSV whose sorting would exceed the memory budget stays in completion order.
fn sort_rows(csv: &Path) -> Result<()> {
    if crate::budget::check_file(csv, "sweep.csv", 3.0).is_err() {
        return Ok(());
    }
    let text = std::fs::read_to_string(csv).map_err(|e| Error::io(csv, e))?;
    let mut lines = text.lines();
    let Some(header) = lines.next() else {
        return Ok(());
    };
    let mut rows: Vec<(u64, &str)> = lines
        .map(|l| {
            let point = l
                .split(',')
                .next()
                .and_then(|p| p.trim().parse::<u64>().ok())
                .unwrap_or(u64::MAX);
            (point, l)
        })
        .collect();
    if rows.windows(2).all(|w| w[0].0 <= w[1].0) {
        return Ok(());
    }
    rows.sort_by_key(|r| r.0);
    let mut sorted = String::with_capacity(text.len());
    sorted.push_str(header);
    sorted.push('\n');
    for (_, l) in rows {
        sorted.push_str(l);
        sorted.push('\n');
    }
    let tmp = csv.with_extension(format!("csv.sorting{}", std::process::id()));
    let _writing = crate::interrupt::Writing::start();
    std::fs::write(&tmp, sorted).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, csv).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(csv, e)
    })
}

#[cfg(test)]
mod tests {
    use super::super::csv_io::read_sweep_csv;
    use super::super::shard::{merge_sweep_csvs, shard_path};
    use super::super::test_support::{setup, tmpdir, BASE};
    use super::*;

    #[test]
    fn run_and_resume_skip_done_points() {
        let (d, s) = setup(
            "resume",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.3, 1.2, 4]\n",
        );
        let sweep = Sweep::load(&s).unwrap();
        let csv = d.join("sweep.csv");
        let cancel = AtomicBool::new(false);
        let opts = SweepOptions {
            threads: Some(2),
            resume: false,
            validated: false,
        };
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.total, r.skipped, r.computed, r.failed), (4, 0, 4, 0));
        let t = read_sweep_csv(&csv).unwrap();
        assert_eq!(t.header[0], "point");
        assert_eq!(t.header[1], "incident.xi");
        assert_eq!(t.header[2], "xi");
        assert_eq!(t.rows.len(), 4);
        // keep the header and two rows plus half a line, then resume
        let text = std::fs::read_to_string(&csv).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let partial = format!(
            "{}\n{}\n{}\n{}",
            lines[0],
            lines[1],
            lines[2],
            &lines[3][..5]
        );
        std::fs::write(&csv, partial).unwrap();
        let opts = SweepOptions {
            threads: Some(1),
            resume: true,
            validated: false,
        };
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.skipped, r.computed), (2, 2));
        let t = read_sweep_csv(&csv).unwrap();
        let mut pts: Vec<usize> = t.rows.iter().map(|r| r[0] as usize).collect();
        pts.sort();
        assert_eq!(pts, vec![0, 1, 2, 3]);
        // nothing left to do
        let r = run_sweep(&sweep, &csv, &opts, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.skipped, r.computed), (4, 0));
        // a different sweep refuses to resume into this CSV and leaves it alone
        std::fs::write(
            &s,
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.3, 1.2, 5]\n",
        )
        .unwrap();
        let other = Sweep::load(&s).unwrap();
        let before = std::fs::read_to_string(&csv).unwrap();
        let e = run_sweep(&other, &csv, &opts, &|_, _| {}, &cancel).unwrap_err();
        assert!(e.to_string().contains("hash"), "{e}");
        assert_eq!(std::fs::read_to_string(&csv).unwrap(), before);
        let _ = std::fs::remove_dir_all(d);
    }

    #[test]
    fn cancel_before_start_is_interrupted() {
        let (d, s) = setup(
            "cancel",
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nvalues = [0.3, 0.5]\n",
        );
        let sweep = Sweep::load(&s).unwrap();
        let cancel = AtomicBool::new(true);
        let e = run_sweep(
            &sweep,
            &d.join("sweep.csv"),
            &SweepOptions::default(),
            &|_, _| {},
            &cancel,
        )
        .unwrap_err();
        assert!(matches!(e, Error::Interrupted));
        let _ = std::fs::remove_dir_all(d);
    }

    // sharded runs and their merge (moved from the shard module, which sits below the driver)

    fn shard_setup(name: &str) -> (PathBuf, Sweep) {
        let d = tmpdir(name);
        std::fs::write(d.join("base.toml"), BASE).unwrap();
        let s = d.join("sweep.toml");
        std::fs::write(
            &s,
            "base = \"base.toml\"\n[[axis]]\nparameter = \"incident.xi\"\nlinspace = [0.2, 1.0, 5]\n\
             [[axis]]\nparameter = \"interface.static_pressure\"\nvalues = [1e5, 2e5]\n",
        )
        .unwrap();
        let sweep = Sweep::load(&s).unwrap();
        (d, sweep)
    }

    fn opts() -> SweepOptions {
        SweepOptions {
            threads: Some(2),
            resume: false,
            validated: false,
        }
    }

    #[test]
    fn shards_merge_to_the_whole_sweep() {
        let (d, sweep) = shard_setup("shard-merge");
        let cancel = AtomicBool::new(false);
        let whole = d.join("whole.csv");
        run_sweep(&sweep, &whole, &opts(), &|_, _| {}, &cancel).unwrap();
        let mut parts = vec![];
        for k in 1..=3 {
            let p = d.join(format!("shard{k}.csv"));
            let r = run_sweep_shard(
                &sweep,
                Shard::new(k, 3).unwrap(),
                &p,
                &opts(),
                &|_, _| {},
                &cancel,
            )
            .unwrap();
            assert_eq!(r.total, [4, 3, 3][k - 1]);
            let t = read_sweep_csv(&p).unwrap();
            assert!(t.rows.iter().all(|r| r[0] as usize % 3 == k - 1));
            assert_eq!(
                std::fs::read_to_string(hash_path(&p)).unwrap().trim(),
                sweep.hash
            );
            parts.push(p);
        }
        // shards in any order; with and without the sweep for the completeness check
        parts.reverse();
        let out = d.join("merged/sweep.csv");
        let r = merge_sweep_csvs(&out, &parts, Some(&sweep)).unwrap();
        assert_eq!((r.points, r.shards), (10, 3));
        merge_sweep_csvs(&out, &parts, None).unwrap();
        let merged = read_sweep_csv(&out).unwrap();
        let mut reference = read_sweep_csv(&whole).unwrap();
        reference.rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_eq!(merged.header, reference.header);
        let bits = |rows: &[Vec<f64>]| -> Vec<Vec<u64>> {
            rows.iter()
                .map(|r| r.iter().map(|v| v.to_bits()).collect())
                .collect()
        };
        assert_eq!(bits(&merged.rows), bits(&reference.rows));
        assert_eq!(
            std::fs::read_to_string(hash_path(&out)).unwrap().trim(),
            sweep.hash
        );

        // a missing shard
        let e = merge_sweep_csvs(&d.join("m2.csv"), &parts[..2], Some(&sweep))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing"), "{e}");
        assert!(!d.join("m2.csv").exists());
        // a duplicated shard
        let dup = vec![parts[0].clone(), parts[1].clone(), parts[0].clone()];
        let e = merge_sweep_csvs(&d.join("m3.csv"), &dup, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("twice"), "{e}");
        // a shard of another sweep
        std::fs::write(hash_path(&parts[1]), "0123\n").unwrap();
        let e = merge_sweep_csvs(&d.join("m4.csv"), &parts, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("hash") && e.contains("different sweeps"), "{e}");
        let e = merge_sweep_csvs(&d.join("m5.csv"), &parts[1..], Some(&sweep))
            .unwrap_err()
            .to_string();
        assert!(e.contains("different sweep"), "{e}");
        let _ = std::fs::remove_dir_all(d);
    }

    /// Issue 24: a shard missing its last row was merged ("merged 9 points") and, without
    /// the sweep file, shard 1 alone was taken for a grid ending at its largest point.
    #[test]
    fn merge_refuses_a_truncated_or_lone_shard_with_or_without_the_sweep() {
        let (d, sweep) = shard_setup("shard-truncated");
        let cancel = AtomicBool::new(false);
        let mut parts = vec![];
        for k in 1..=2 {
            let p = d.join(format!("shard{k}.csv"));
            let shard = Shard::new(k, 2).unwrap();
            run_sweep_shard(&sweep, shard, &p, &opts(), &|_, _| {}, &cancel).unwrap();
            assert_eq!(
                ShardFile::read(&p).unwrap(),
                Some(ShardFile { shard, points: 10 })
            );
            parts.push(p);
        }
        // drop the last row (point 9) of shard 2/2
        let text = std::fs::read_to_string(&parts[1]).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[lines.len() - 1].starts_with("9,"));
        std::fs::write(&parts[1], lines[..lines.len() - 1].join("\n") + "\n").unwrap();
        let out = d.join("m.csv");
        for sw in [Some(&sweep), None] {
            let e = merge_sweep_csvs(&out, &parts, sw).unwrap_err().to_string();
            let name = format!(
                "{} (shard 2/2) lacks 1 of its 5 points: 9",
                parts[1].display()
            );
            assert!(e.contains("1 of 10 points") && e.contains(&name), "{e}");
            assert!(!out.exists());
        }
        // shard 1/2 alone: the grid has 10 points, not 9
        let e = merge_sweep_csvs(&out, &parts[..1], None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("5 of 10 points")
                && e.contains("shard 2/2 (not given) lacks 5 of its 5 points: 1, 3, 5, 7, 9"),
            "{e}"
        );
        // a shard without side file: its grid is unknown without the sweep file
        std::fs::remove_file(shard_path(&parts[0])).unwrap();
        let e = merge_sweep_csvs(&out, &parts[..1], None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("shard1.csv.shard") && e.contains("--sweep"),
            "{e}"
        );
        assert!(!out.exists());
        let _ = std::fs::remove_dir_all(d);
    }

    #[test]
    fn resume_a_shard() {
        let (d, sweep) = shard_setup("shard-resume");
        let cancel = AtomicBool::new(false);
        let p = d.join("s.csv");
        let shard = Shard::new(2, 2).unwrap();
        run_sweep_shard(&sweep, shard, &p, &opts(), &|_, _| {}, &cancel).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let keep: Vec<&str> = text.lines().take(3).collect();
        std::fs::write(&p, keep.join("\n") + "\n").unwrap();
        let o = SweepOptions {
            threads: Some(1),
            resume: true,
            validated: false,
        };
        let r = run_sweep_shard(&sweep, shard, &p, &o, &|_, _| {}, &cancel).unwrap();
        assert_eq!((r.total, r.skipped, r.computed), (5, 2, 3));
        let _ = std::fs::remove_dir_all(d);
    }
}

//! Result files: CSV tables, `summary.json`, SVG plots.
//!
//! This module owns the layout of an output folder. Everything is rendered in memory first
//! ([`crate::model::Outcome::files`], [`law_files`], `sweep_svg`) and only then written
//! ([`write_files`]), so a failure while computing or rendering never creates or touches
//! the output folder. Each file is written to a temporary name in the folder and renamed
//! into place.
//!
//! The files of a run are the model's own ([`crate::model::Outcome::files`]; the
//! half-space run's are listed in [`crate::model::half_space::files`], the bar stack's in
//! [`crate::model::bar_stack::files`]); this module writes them ([`write_outcome`]).
//!
//! Files of a law (`contactwave law`): `law_curve.csv` (`gap,stress`: m, Pa; monotone
//! loading, damage in its rate-independent limit, see [`ContactLaw::curve`]) and
//! `law_curve.svg`.
//!
//! SVG files need the `plot` feature (on by default): without it the files of a run or a
//! law are their CSV and JSON files only, and `plot`, `sweep_svg` and `identify` (which
//! also needs the `identify` feature) are absent.
//!
//! Numbers are written so that they parse back to the same `f64`.

pub mod analyze;
#[cfg(feature = "hdf5")]
pub mod hdf5;
#[cfg(feature = "identify")]
pub mod identify;
pub mod labels;
pub mod manifest;
#[cfg(feature = "plot")]
pub mod plot;
pub mod provenance;
pub mod recording;

use crate::error::{Error, Result};
use crate::law::ContactLaw;
use crate::model::Outcome;
pub use crate::render::{csv_columns, summary_json, BinaryFile, OutputFile};
use std::path::{Path, PathBuf};

/// Header of `law_curve.csv`.
pub const LAW_CURVE_HEADER: &str = "gap,stress";

/// Gap range `(min, max)`, m, that shows a law's shape: the compression branch down to
/// `-[u]_c` (or a little below zero for a rigid branch) and the traction branch up to
/// four times its length scale (`sqrt(w / C_N)` with damage, `p0 / K_t` for a linear
/// branch, `[u]_c` otherwise).
pub fn law_gap_range(law: &ContactLaw) -> (f64, f64) {
    let uc = law.critical_gap().max(0.0);
    let p0 = law.static_pressure;
    let t = &law.traction;
    let kt = if t.is_rigid() {
        f64::INFINITY
    } else {
        t.stiffness_at_contact()
    };
    let mut d = 0.0f64;
    if t.has_damage() {
        let w = t.damage_driving_force(0.0, 1.0);
        if w.is_finite() && w > 0.0 && kt.is_finite() && kt > 0.0 {
            d = (w / kt).sqrt();
        }
    }
    if d == 0.0 && kt.is_finite() && kt > 0.0 && p0 > 0.0 {
        d = p0 / kt;
    }
    if d == 0.0 || !d.is_finite() {
        d = uc;
    }
    if d == 0.0 {
        let k = law.compression.stiffness_at_rest();
        d = if k.is_finite() && k > 0.0 && p0 > 0.0 {
            p0 / k
        } else {
            1e-9
        };
    }
    let low = if uc > 0.0 { -uc } else { -0.5 * d };
    (low, uc + 4.0 * d)
}

/// `law_curve.csv` and (with the `plot` feature) `law_curve.svg` of a law, rendered in
/// memory.
pub fn law_files(law: &ContactLaw) -> Result<Vec<OutputFile>> {
    let (g0, g1) = law_gap_range(law);
    let (gap, stress) = law.curve(g0, g1, 801);
    let mut files = vec![OutputFile::new(
        "law_curve.csv",
        csv_columns(LAW_CURVE_HEADER, &[&gap, &stress]),
    )];
    files.extend(law_figures(law, &gap, &stress)?);
    Ok(files)
}

/// The files of [`law_files`] plus, for a tangential law, `law_tangential.csv`
/// (tangential gap m, shear stress Pa: monotone loading at the static pressure) and
/// `law_tangential.svg`.
pub fn law_files_with(
    law: &ContactLaw,
    tangential: Option<&crate::law::TangentialLaw>,
) -> Result<Vec<OutputFile>> {
    let mut files = law_files(law)?;
    if let Some(t) = tangential {
        let (gap, tau) = t.curve(law, t.curve_gap_range(law), 801);
        files.push(OutputFile::new(
            "law_tangential.csv",
            csv_columns("tangential_gap,shear_stress", &[&gap, &tau]),
        ));
        #[cfg(feature = "plot")]
        files.push(OutputFile::new(
            "law_tangential.svg",
            plot::tangential_law_curve(law, t, &gap, &tau)?,
        ));
    }
    Ok(files)
}

/// `law_curve.svg` of a law's curve (nothing without the `plot` feature).
#[cfg(feature = "plot")]
fn law_figures(law: &ContactLaw, gap: &[f64], stress: &[f64]) -> Result<Vec<OutputFile>> {
    let svg = plot::law_curve(law, gap, stress)?;
    Ok(vec![OutputFile::new("law_curve.svg", svg)])
}

/// `law_curve.svg` of a law's curve (nothing without the `plot` feature).
#[cfg(not(feature = "plot"))]
fn law_figures(_law: &ContactLaw, _gap: &[f64], _stress: &[f64]) -> Result<Vec<OutputFile>> {
    Ok(Vec::new())
}

/// Plot of a sweep CSV: `A1_over_Ainc` and `A2_over_Ainc` (two panels) against the first
/// axis, one curve per combination of the other axes' values. `None` when the CSV has no
/// rows (every point failed).
#[cfg(feature = "plot")]
pub fn sweep_svg(sweep: &crate::study::Sweep, csv: &Path) -> Result<Option<String>> {
    let table = crate::study::read_sweep_csv(csv)?;
    if table.rows.is_empty() {
        return Ok(None);
    }
    plot::sweep(sweep, &table).map(Some)
}

/// Plot of a merged sweep CSV (`merge`): as [`sweep_svg`] with the sweep file's axes when
/// given, else the axes read from the CSV header (the dotted-key columns after `point`).
#[cfg(feature = "plot")]
pub fn merged_sweep_svg(sweep: Option<&crate::study::Sweep>, csv: &Path) -> Result<Option<String>> {
    let table = crate::study::read_sweep_csv(csv)?;
    if table.rows.is_empty() {
        return Ok(None);
    }
    match sweep {
        Some(sw) => plot::sweep(sw, &table).map(Some),
        None => plot::sweep_table(&plot::axes_of_table(&table), &table).map(Some),
    }
}

/// Create `dir` (and its parents) and write the files into it, each through a temporary
/// name and a rename. Returns the paths written.
pub fn write_files(dir: &Path, files: &[OutputFile]) -> Result<Vec<PathBuf>> {
    write_named(
        dir,
        files
            .iter()
            .map(|f| (f.name.as_str(), f.contents.as_bytes())),
    )
}

/// [`write_files`] and [`write_binary_files`] in one go: all of them or none.
pub fn write_all(dir: &Path, files: &[OutputFile], binary: &[BinaryFile]) -> Result<Vec<PathBuf>> {
    write_named(
        dir,
        files
            .iter()
            .map(|f| (f.name.as_str(), f.contents.as_bytes()))
            .chain(binary.iter().map(|f| (f.name.as_str(), f.bytes.as_slice()))),
    )
}

/// [`write_files`] for binary files (names may hold a subfolder, created if needed).
pub fn write_binary_files(dir: &Path, files: &[BinaryFile]) -> Result<Vec<PathBuf>> {
    write_named(
        dir,
        files.iter().map(|f| (f.name.as_str(), f.bytes.as_slice())),
    )
}

/// Write `(name, bytes)` pairs into `dir`, all or none: each is staged under a temporary
/// name beside its place, and once every one is staged they are renamed into place; an
/// interruption (Ctrl-C) or an error while staging removes what was staged (and the
/// subfolders it created), so that a command's files are either all new or all as they
/// were. A name with a subfolder (`snapshots/frame_0000.png`) creates the subfolder.
fn write_named<'a>(
    dir: &Path,
    files: impl Iterator<Item = (&'a str, &'a [u8])>,
) -> Result<Vec<PathBuf>> {
    crate::interrupt::check()?;
    std::fs::create_dir_all(dir).map_err(|e| Error::create_dir(dir, e))?;
    let mut staged: Vec<(PathBuf, PathBuf)> = Vec::new();
    let mut created: Vec<PathBuf> = Vec::new();
    // (called while a `Writing` guard holds the process's exit back)
    let undo = |staged: &[(PathBuf, PathBuf)], created: &[PathBuf]| {
        for (tmp, _) in staged {
            let _ = std::fs::remove_file(tmp);
        }
        for folder in created.iter().rev() {
            let _ = std::fs::remove_dir(folder);
        }
    };
    for (name, bytes) in files {
        let _writing = crate::interrupt::Writing::start();
        if let Err(e) = crate::interrupt::check() {
            undo(&staged, &created);
            return Err(e);
        }
        let path = dir.join(name);
        let folder = path.parent().unwrap_or(dir).to_path_buf();
        if folder != dir && !folder.is_dir() {
            if let Err(e) = std::fs::create_dir_all(&folder) {
                undo(&staged, &created);
                return Err(Error::io(&folder, e));
            }
            created.push(folder.clone());
        }
        let base = path.file_name().map(|n| n.to_string_lossy().into_owned());
        let tmp = folder.join(format!(
            ".{}.tmp{}",
            base.unwrap_or_default(),
            std::process::id()
        ));
        if let Err(e) = std::fs::write(&tmp, bytes) {
            let _ = std::fs::remove_file(&tmp);
            undo(&staged, &created);
            return Err(Error::write_in(dir, e));
        }
        staged.push((tmp, path));
    }
    let _writing = crate::interrupt::Writing::start();
    let mut written = Vec::with_capacity(staged.len());
    for (k, (tmp, path)) in staged.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            undo(&staged[k..], &[]);
            return Err(Error::io(path, e));
        }
        written.push(path.clone());
    }
    Ok(written)
}

/// Render and write every file of a run's outcome into `dir` (created if needed).
pub fn write_outcome(outcome: &dyn Outcome, dir: &Path) -> Result<Vec<PathBuf>> {
    write_all(dir, &outcome.files()?, &outcome.binary_files()?)
}

/// Render and write the files of a law ([`law_files`]) into `dir` (created if needed).
pub fn write_law_curve(law: &ContactLaw, dir: &Path) -> Result<Vec<PathBuf>> {
    let files = law_files(law)?;
    write_files(dir, &files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::Summary;
    use crate::scenario::Scenario;

    /// A command's files are written all or none: a file that cannot be staged (its
    /// temporary name is taken by a folder) leaves the files before it unwritten too, no
    /// temporary file and no subfolder behind, and the earlier contents in place.
    #[test]
    fn files_are_written_all_or_none() {
        let d = std::env::temp_dir().join(format!("contactwave-all-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("a.csv"), "old\n").unwrap();
        std::fs::create_dir_all(d.join(format!(".c.csv.tmp{}", std::process::id()))).unwrap();
        let file = |name: &str| OutputFile {
            name: name.into(),
            contents: "new\n".into(),
        };
        let files = [file("a.csv"), file("sub/b.csv"), file("c.csv")];
        assert!(write_files(&d, &files).is_err());
        assert_eq!(std::fs::read_to_string(d.join("a.csv")).unwrap(), "old\n");
        assert!(!d.join("sub").exists());
        let left: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(left.len(), 2, "{left:?}");
        // and once the way is clear, all of them
        std::fs::remove_dir(d.join(format!(".c.csv.tmp{}", std::process::id()))).unwrap();
        assert_eq!(write_files(&d, &files).unwrap().len(), 3);
        for f in &files {
            assert_eq!(std::fs::read_to_string(d.join(&f.name)).unwrap(), "new\n");
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// Issue 24: a folder that cannot take the files was reported under the temporary
    /// name (`.summary.json.tmp1234: ...`); the error names the user's folder.
    #[test]
    fn a_failed_write_names_the_folder_not_the_temporary_file() {
        let d = std::env::temp_dir().join(format!("contactwave-out-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        // a folder where the temporary file goes: the write fails (even for root)
        std::fs::create_dir_all(d.join(format!(".a.csv.tmp{}", std::process::id()))).unwrap();
        let f = OutputFile {
            name: "a.csv".into(),
            contents: "x\n".into(),
        };
        let e = write_files(&d, &[f]).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!(
                "{}: cannot write into the output folder",
                d.display()
            )),
            "{e}"
        );
        assert!(!e.contains(".tmp"), "{e}");
        let denied = std::io::Error::from(std::io::ErrorKind::PermissionDenied);
        let e = Error::write_in(Path::new("results/ro"), denied).to_string();
        assert!(
            e.starts_with("results/ro: the output folder is not writable"),
            "{e}"
        );
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn csv_round_trips_floats() {
        let a = [0.1, 1e-8, -2.5e300, f64::NAN];
        let b = [1.0, 2.0, 3.0, 4.0, 5.0];
        let s = csv_columns("a,b", &[&a, &b]);
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 5);
        assert_eq!(lines[0], "a,b");
        for (i, l) in lines[1..].iter().enumerate() {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert!(v[0] == a[i] || (v[0].is_nan() && a[i].is_nan()));
            assert_eq!(v[1], b[i]);
        }
    }

    #[test]
    fn summary_json_keeps_order_and_nulls_nan() {
        let mut s = Summary::new();
        s.set("xi", 0.35);
        s.set("bad", f64::NAN);
        let j = summary_json("a.toml", &s);
        let v: serde_json::Value = serde_json::from_str(&j).unwrap();
        assert_eq!(v["scenario"], "a.toml");
        assert_eq!(v["xi"], 0.35);
        assert!(v["bad"].is_null());
        assert!(j.find("scenario").unwrap() < j.find("xi").unwrap());
    }

    #[test]
    fn run_and_law_files_render() {
        let s = Scenario::from_toml_str(
            r#"
            [medium]
            material = "pmma"
            [interface]
            static_pressure = 0.082e6
            traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
            [incident]
            frequency = 1e6
            cycles = 3
            amplitude = 0.82e6
            "#,
            "t.toml",
        )
        .unwrap();
        let r = crate::simulate(&s).unwrap();
        let files = crate::model::Outcome::files(&r).unwrap();
        // 4 CSV/JSON files, and 4 SVG files with the `plot` feature
        let svgs = if cfg!(feature = "plot") { 4 } else { 0 };
        assert_eq!(files.len(), 4 + svgs);
        assert_eq!(
            files.iter().filter(|f| f.name.ends_with(".svg")).count(),
            svgs
        );
        let ts = &files[1].contents;
        let header = crate::model::half_space::files::TIMESERIES_HEADER;
        assert!(ts.starts_with(&format!("{header}\n")));
        for f in &files {
            if f.name.ends_with(".svg") {
                assert!(f.contents.contains("<svg"), "{}", f.name);
                assert!(f.contents.len() < 3_000_000, "{} too big", f.name);
            }
        }
        let law = law_files(&s.law).unwrap();
        assert_eq!(law.len(), if cfg!(feature = "plot") { 2 } else { 1 });
        assert!(law[0].contents.starts_with("gap,stress\n"));
        assert!(law[0].contents.lines().count() > 100);
        // rigid compression + free traction and a bonded law render too
        for toml in [
            "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.1e6\n[incident]\nfrequency = 1e6\nxi = 0.3\n",
            "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = 0.1e6\ntraction = { law = \"bonded\" }\ncompression = { law = \"linear\", stiffness = 1e12 }\n[incident]\nfrequency = 1e6\nxi = 0.3\n",
        ] {
            let s = Scenario::from_toml_str(toml, "u.toml").unwrap();
            let (g0, g1) = law_gap_range(&s.law);
            assert!(g0 < 0.0 && g1 > 0.0 && g1.is_finite());
            law_files(&s.law).unwrap();
        }
    }
}

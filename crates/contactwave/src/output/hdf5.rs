//! HDF5 result files (`run --hdf5`: `result.h5`; `sweep --hdf5`: `sweep.h5`), for MATLAB
//! (`h5read`, `h5readatt`) and Python (h5py, xarray). Written by the pure-Rust `hdf5-pure`
//! crate (no C library), behind the `hdf5` feature.
//!
//! Layout (docs/outputs.md):
//!
//! - the root group's attributes: the provenance ([`Provenance::attributes`]: variable-length UTF-8 strings,
//!   `""` for an unknown value) and `file_format = "contactwave result"`;
//! - one group per CSV table of the run, named after the file without `.csv`
//!   (`/timeseries`, `/probe`, `/spectrum`, `/receivers`, `/crack`, `/frf`, ...), holding
//!   one 1-D `float64` dataset per column, named as the column (`/timeseries/t`,
//!   `/receivers/top_vz`); columns of text cells are left out;
//! - `/summary`: the scalars of `summary.json` as `float64` attributes (arrays of numbers
//!   as arrays; `null` as NaN);
//! - a sweep: `/sweep`, one dataset per column of `sweep.csv` (rows sorted by point).
//!
//! Every dataset has the attributes `units` (SI, `"1"` for a dimensionless quantity) and
//! `description` (`"<column> (<file>.csv): <quantity>"`).

use crate::error::{Error, Result};
use crate::output::labels;
use crate::output::provenance::Provenance;
use crate::render::{BinaryFile, OutputFile};
use hdf5_pure::{AttrValue, FileBuilder};

/// File name of a run's HDF5 file.
pub const RUN_FILE: &str = "result.h5";
/// File name of a sweep's HDF5 file.
pub const SWEEP_FILE: &str = "sweep.h5";

/// The SI unit of a column of a result table (`"1"`: dimensionless; `""`: not known).
pub fn column_units(table: &str, column: &str) -> &'static str {
    let c = column.to_ascii_lowercase();
    // the receivers' `<name>_v<x|z|y>` and `<name>_s<xx|zz|xz|yx|yz>`
    if let Some((_, comp)) = c.rsplit_once('_')
        && table == "receivers"
    {
        if comp.len() == 2 && comp.starts_with('v') {
            return "m/s";
        }
        if comp.len() == 3 && comp.starts_with('s') {
            return "Pa";
        }
    }
    if c == "t" || c == "time" || c.ends_with("_time") {
        return "s";
    }
    if table == "spectrum" && (c == "incident" || c == "reflected" || c == "transmitted") {
        // |V(f)| of a velocity: m/s per Hz
        return "m";
    }
    // beta* = A2/A1^2 (also a 2D receiver's `<name>_beta`); `beta`, `beta_i`: adhesion
    if c == "beta_star" || c.ends_with("_beta") {
        return "s/m";
    }
    let unit = if c.contains("receptance_phase") || c.ends_with("phase") {
        "rad"
    } else if c.contains("receptance") {
        "m/N"
    } else if c.contains("accelerance") {
        "(m/s^2)/N"
    } else if c.ends_with("_db") {
        "dB"
    } else if c.contains("slip_state") || c.contains("state") || c.starts_with("beta") {
        "1"
    } else if c.contains("stiffness") {
        "Pa/m"
    } else if c.contains("stress") || c.contains("pressure") || c.contains("traction") {
        "Pa"
    } else if c.contains("acceleration") {
        "m/s^2"
    } else if c.contains("velocity") {
        "m/s"
    } else if c.contains("force") {
        "N"
    } else if c.contains("gap")
        || c.contains("displacement")
        || c.contains("slip")
        || c.contains("opening")
        || c == "x"
        || c == "z"
        || c == "y"
        || c.contains("position")
    {
        "m"
    } else if c.contains("frequency") || c.ends_with("_hz") {
        "Hz"
    } else if c == "point" || c.contains("_over_") || c.contains("ratio") {
        "1"
    } else {
        labels::quantity(column).1
    };
    if unit.is_empty() && (c.contains("beta") || c.contains("warning")) {
        "1"
    } else {
        unit
    }
}

/// The columns of CSV text: header names and values (`#` lines skipped; an empty cell is
/// NaN); columns holding a cell that is not a number are left out.
fn csv_columns_of(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty());
    let Some(head) = lines.next() else {
        return (Vec::new(), Vec::new());
    };
    let names: Vec<String> = head.split(',').map(|s| s.trim().to_string()).collect();
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let mut text_col = vec![false; names.len()];
    for line in lines {
        for (j, cell) in line.split(',').enumerate().take(names.len()) {
            let cell = cell.trim();
            let v = if cell.is_empty() {
                Some(f64::NAN)
            } else {
                cell.parse::<f64>().ok()
            };
            match v {
                Some(v) => cols[j].push(v),
                None => text_col[j] = true,
            }
        }
    }
    names
        .into_iter()
        .zip(cols)
        .zip(text_col)
        .filter(|(_, text)| !text)
        .map(|(nc, _)| nc)
        .unzip()
}

/// A dataset name: the column, with `/` (HDF5's separator) as `_`.
fn dataset_name(column: &str) -> String {
    column.replace('/', "_")
}

fn dataset_attrs(table: &str, column: &str) -> (AttrValue, AttrValue) {
    let mut units = column_units(table, column);
    if units.is_empty() {
        units = "1";
    }
    let (name, _) = labels::quantity(column);
    (
        AttrValue::VarLenString(units.to_string()),
        AttrValue::VarLenString(format!("{column} ({table}.csv): {name}")),
    )
}

fn root(provenance: &Provenance) -> FileBuilder {
    let mut b = FileBuilder::new();
    b.set_attr(
        "file_format",
        AttrValue::VarLenString("contactwave result".into()),
    );
    for (k, v) in provenance.attributes() {
        b.set_attr(&k, AttrValue::VarLenString(v));
    }
    b
}

fn finish(b: FileBuilder, name: &str) -> Result<BinaryFile> {
    let bytes = b
        .finish()
        .map_err(|e| Error::io(name, std::io::Error::other(e.to_string())))?;
    Ok(BinaryFile {
        name: name.into(),
        bytes,
    })
}

/// Add the CSV table `table` (its text) as a group of column datasets.
fn add_table(b: &mut FileBuilder, table: &str, text: &str) {
    let (names, cols) = csv_columns_of(text);
    if names.is_empty() {
        return;
    }
    let mut g = b.create_group(table);
    for (name, col) in names.iter().zip(&cols) {
        let (units, description) = dataset_attrs(table, name);
        g.create_dataset(&dataset_name(name))
            .with_f64_data(col)
            .with_shape(&[col.len() as u64])
            .set_attr("units", units)
            .set_attr("description", description);
    }
    b.add_group(g.finish());
}

/// `/summary` from the text of `summary.json` (numbers and arrays of numbers).
fn add_summary(b: &mut FileBuilder, text: &str) {
    let Ok(serde_json::Value::Object(map)) = serde_json::from_str::<serde_json::Value>(text) else {
        return;
    };
    let num = |v: &serde_json::Value| match v {
        serde_json::Value::Number(n) => n.as_f64(),
        serde_json::Value::Null => Some(f64::NAN),
        _ => None,
    };
    let mut g = b.create_group("summary");
    for (k, v) in &map {
        if k == "provenance" {
            continue;
        }
        match v {
            serde_json::Value::Number(_) | serde_json::Value::Null => {
                if let Some(x) = num(v) {
                    g.set_attr(k, AttrValue::F64(x));
                }
            }
            serde_json::Value::Array(a) if !a.is_empty() => {
                let xs: Option<Vec<f64>> = a.iter().map(num).collect();
                if let Some(xs) = xs {
                    g.set_attr(k, AttrValue::F64Array(xs));
                }
            }
            serde_json::Value::String(s) if k == "scenario" => {
                g.set_attr(k, AttrValue::VarLenString(s.clone()));
            }
            _ => {}
        }
    }
    b.add_group(g.finish());
}

/// `result.h5` of a run from its rendered files (every CSV table, the summary) and its
/// provenance.
pub fn run_file(files: &[OutputFile], provenance: &Provenance) -> Result<BinaryFile> {
    let mut b = root(provenance);
    for f in files {
        if let Some(table) = f.name.strip_suffix(".csv") {
            if !table.contains('/') {
                add_table(&mut b, table, &f.contents);
            }
        } else if f.name == "summary.json" {
            add_summary(&mut b, &f.contents);
        }
    }
    finish(b, RUN_FILE)
}

/// `sweep.h5` of a sweep: every column of its table (`/sweep/<column>`) and its
/// provenance.
pub fn sweep_file(table: &crate::study::SweepTable, provenance: &Provenance) -> Result<BinaryFile> {
    let mut b = root(provenance);
    let mut g = b.create_group("sweep");
    for (j, name) in table.header.iter().enumerate() {
        let col: Vec<f64> = table
            .rows
            .iter()
            .map(|r| r.get(j).copied().unwrap_or(f64::NAN))
            .collect();
        let units = match column_units("sweep", name) {
            "" => "1",
            u => u,
        };
        let (quantity, _) = labels::quantity(name);
        g.create_dataset(&dataset_name(name))
            .with_f64_data(&col)
            .with_shape(&[col.len() as u64])
            .set_attr("units", AttrValue::VarLenString(units.into()))
            .set_attr(
                "description",
                AttrValue::VarLenString(format!("{name} (sweep.csv): {quantity}")),
            );
    }
    b.add_group(g.finish());
    finish(b, SWEEP_FILE)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn str_attr(a: &std::collections::HashMap<String, AttrValue>, k: &str) -> String {
        a.get(k)
            .and_then(|v| v.as_str())
            .unwrap_or_else(|| panic!("attribute {k}"))
            .to_string()
    }

    #[test]
    fn a_runs_tables_read_back_with_units_and_provenance() {
        let files = vec![
            OutputFile::new(
                "summary.json",
                "{\"scenario\": \"a.toml\", \"A2_over_A1\": 0.125, \"bad\": null, \"per\": [1.0, 2.5]}\n".into(),
            ),
            OutputFile::new(
                "timeseries.csv",
                "t,gap,contact_stress,beta\n0,0,-1e5,1\n1e-7,2.5e-9,,0.5\n".into(),
            ),
            OutputFile::new("receivers.csv", "t,top_vz,top_sxz\n0,1e-3,2\n".into()),
            OutputFile::new("crack.csv", "t,x,state\n0,0.01,open\n".into()),
            OutputFile::new("plot.svg", "<svg/>".into()),
        ];
        let p = Provenance::new("contactwave run a.toml --hdf5");
        let h5 = run_file(&files, &p).unwrap();
        assert_eq!(h5.name, "result.h5");
        let f = hdf5_pure::File::from_bytes(h5.bytes).unwrap();
        let root = f.root().attrs().unwrap();
        assert_eq!(
            str_attr(&root, "contactwave_version"),
            p.contactwave_version
        );
        assert_eq!(str_attr(&root, "command_line"), p.command_line);
        assert_eq!(str_attr(&root, "created"), p.created);
        let gap = f.dataset("timeseries/gap").unwrap();
        assert_eq!(gap.read_f64().unwrap(), vec![0.0, 2.5e-9]);
        assert_eq!(str_attr(&gap.attrs().unwrap(), "units"), "m");
        let s = f.dataset("timeseries/contact_stress").unwrap();
        let v = s.read_f64().unwrap();
        assert_eq!(v[0], -1e5);
        assert!(v[1].is_nan());
        assert_eq!(str_attr(&s.attrs().unwrap(), "units"), "Pa");
        let t = f.dataset("timeseries/t").unwrap();
        assert_eq!(str_attr(&t.attrs().unwrap(), "units"), "s");
        assert!(str_attr(&t.attrs().unwrap(), "description").starts_with("t (timeseries.csv)"));
        let vz = f.dataset("receivers/top_vz").unwrap();
        assert_eq!(str_attr(&vz.attrs().unwrap(), "units"), "m/s");
        let sxz = f.dataset("receivers/top_sxz").unwrap();
        assert_eq!(str_attr(&sxz.attrs().unwrap(), "units"), "Pa");
        // a text column is left out, the numeric ones kept
        let mut crack = f.group("crack").unwrap().datasets().unwrap();
        crack.sort();
        assert_eq!(crack, ["t", "x"]);
        let sum = f.group("summary").unwrap().attrs().unwrap();
        assert_eq!(sum["A2_over_A1"].as_f64(), Some(0.125));
        assert!(sum["bad"].as_f64().unwrap().is_nan());
        assert_eq!(sum["per"].to_f64s(), Some(vec![1.0, 2.5]));
    }

    #[test]
    fn units_of_the_columns() {
        assert_eq!(column_units("timeseries", "incident_stress"), "Pa");
        assert_eq!(column_units("probe", "reflected_velocity"), "m/s");
        assert_eq!(column_units("spectrum", "frequency"), "Hz");
        assert_eq!(column_units("spectrum", "reflected"), "m");
        assert_eq!(column_units("frf", "receptance"), "m/N");
        assert_eq!(column_units("frf", "receptance_phase"), "rad");
        assert_eq!(column_units("frf", "force_db"), "dB");
        assert_eq!(column_units("timeseries", "force"), "N");
        assert_eq!(column_units("timeseries", "stiffness_0"), "Pa/m");
        assert_eq!(column_units("sweep", "interface.static_pressure"), "Pa");
        assert_eq!(column_units("sweep", "A2_over_Ainc"), "1");
        assert_eq!(column_units("sweep", "beta_star"), "s/m");
    }
}

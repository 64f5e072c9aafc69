//! Named numeric arrays read from the files experimentalists keep their records in:
//! CSV (one array per column), NumPy `.npy` / `.npz`, MATLAB `.mat` v5 and v7.3, and HDF5.
//! Every array comes back as `f64` in row-major order with its shape (MATLAB's
//! column-major matrices transposed, so that `rows x cols` in MATLAB is `rows x cols`
//! here). What cannot be read as real numbers (complex data, strings, structs, cells, a
//! MAT class or HDF5 type outside the numeric ones, more than two dimensions) is a
//! one-line [`Error::Invalid`] naming the file, the array and what is allowed.
//!
//! Crates: `npyz` (NPY/NPZ), `matfile` (MAT v5), `hdf5-pure` (HDF5 and MAT v7.3, which is
//! HDF5 behind a 512-byte header), all pure Rust; CSV through [`crate::numeric::table`].

use crate::budget;
use crate::error::{Error, Result};
use crate::numeric::table::{read_table, CsvReader, Header};
use std::path::Path;

/// A named array of real numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedArray {
    /// Name: the CSV column's header, the NPZ/MAT variable or the HDF5 dataset path.
    pub name: String,
    /// Shape, at most two dimensions (`[n]` or `[rows, cols]`).
    pub shape: Vec<usize>,
    /// Values, row-major.
    pub data: Vec<f64>,
}

impl NamedArray {
    /// The array's columns (a vector is one column; a `1 x n` row is one column too):
    /// `(column index, values)`.
    pub fn columns(&self) -> Vec<Vec<f64>> {
        match self.shape.as_slice() {
            [_] => vec![self.data.clone()],
            [1, _] | [_, 1] => vec![self.data.clone()],
            [r, c] => (0..*c)
                .map(|j| (0..*r).map(|i| self.data[i * c + j]).collect())
                .collect(),
            _ => vec![self.data.clone()],
        }
    }

    /// The array's rows (`[rows, cols]`; a vector is one row).
    pub fn rows(&self) -> Vec<Vec<f64>> {
        match self.shape.as_slice() {
            [r, c] if *r > 1 && *c > 1 => self.data.chunks(*c).map(<[f64]>::to_vec).collect(),
            _ => vec![self.data.clone()],
        }
    }
}

/// The file formats [`read_arrays`] knows, from the file's extension (and, for `.mat`,
/// its header).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header (`.csv`, `.txt`).
    Csv,
    /// One NumPy array (`.npy`).
    Npy,
    /// A NumPy archive of named arrays (`.npz`).
    Npz,
    /// MATLAB v5 (`.mat` saved by `save` with `-v7` or earlier).
    MatV5,
    /// MATLAB v7.3 (`.mat` saved with `-v7.3`: HDF5).
    MatV73,
    /// HDF5 (`.h5`, `.hdf5`, `.hdf`).
    Hdf5,
}

impl Format {
    /// Name shown to users.
    pub fn name(self) -> &'static str {
        match self {
            Format::Csv => "CSV",
            Format::Npy => "NumPy .npy",
            Format::Npz => "NumPy .npz",
            Format::MatV5 => "MATLAB .mat v5",
            Format::MatV73 => "MATLAB .mat v7.3",
            Format::Hdf5 => "HDF5",
        }
    }

    /// The format of `path`, from its extension (a `.mat` file's header tells v5 from v7.3).
    pub fn of(path: &Path) -> Result<Format> {
        let shown = path.display().to_string();
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        Ok(match ext.as_str() {
            "csv" | "txt" => Format::Csv,
            "npy" => Format::Npy,
            "npz" => Format::Npz,
            "h5" | "hdf5" | "hdf" => Format::Hdf5,
            "mat" => {
                let mut head = [0u8; 128];
                let n = {
                    use std::io::Read;
                    let mut f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
                    f.read(&mut head).map_err(|e| Error::io(path, e))?
                };
                let text = String::from_utf8_lossy(&head[..n.min(116)]);
                if text.starts_with("MATLAB 7.3") {
                    Format::MatV73
                } else if text.starts_with("MATLAB") {
                    Format::MatV5
                } else {
                    return Err(Error::invalid(
                        &shown,
                        "file",
                        &shown,
                        "a MATLAB .mat file saved with -v6, -v7 or -v7.3 (the v4 format and files without the MATLAB header are not read)",
                    ));
                }
            }
            _ => {
                return Err(Error::invalid(
                    &shown,
                    "file",
                    &shown,
                    "a record file ending in .csv, .txt, .npy, .npz, .mat, .h5, .hdf5 or .hdf",
                ));
            }
        })
    }
}

/// Bytes of memory per byte of file while it is read (its values, their copies into
/// records and the analysis' buffers; a compressed file expands, so generously).
const READ_FACTOR: f64 = 24.0;

/// Every array of `path` (for CSV, each column named by its header; for HDF5 and MAT
/// v7.3, the datasets `names` or, when `names` is empty, every numeric dataset at the
/// root). Refuses, before reading, a file whose size exceeds the memory budget.
pub fn read_arrays(path: &Path, names: &[String]) -> Result<(Format, Vec<NamedArray>)> {
    budget::check_file(path, "file", READ_FACTOR)?;
    let format = Format::of(path)?;
    let shown = path.display().to_string();
    let arrays = match format {
        Format::Csv => read_csv(path)?,
        Format::Npy => {
            let f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
            let npy = npyz::NpyFile::new(std::io::BufReader::new(f))
                .map_err(|e| bad(&shown, "file", "not a NumPy .npy file", e))?;
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            vec![npy_array(&shown, &name, npy)?]
        }
        Format::Npz => {
            let mut z = npyz::npz::NpzArchive::open(path)
                .map_err(|e| bad(&shown, "file", "not a NumPy .npz archive", e))?;
            let all: Vec<String> = z.array_names().map(str::to_string).collect();
            let mut out = Vec::new();
            for name in all {
                let npy = z
                    .by_name(&name)
                    .map_err(|e| bad(&shown, &name, "a readable array", e))?
                    .ok_or_else(|| {
                        Error::invalid(&shown, &name, &name, "an array of the archive")
                    })?;
                out.push(npy_array(&shown, &name, npy)?);
            }
            out
        }
        Format::MatV5 => {
            let f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
            let mat = matfile::MatFile::parse(std::io::BufReader::new(f))
                .map_err(|e| bad(&shown, "file", "a MATLAB v5 file", e))?;
            mat.arrays()
                .iter()
                .map(|a| mat_v5_array(&shown, a))
                .collect::<Result<_>>()?
        }
        Format::MatV73 | Format::Hdf5 => read_hdf5(path, names, format == Format::MatV73)?,
    };
    Ok((format, arrays))
}

fn bad(file: &str, field: &str, allowed: &str, e: impl std::fmt::Display) -> Error {
    let msg = e.to_string();
    let msg = msg.lines().next().unwrap_or("");
    Error::invalid(file, field, msg, allowed)
}

/// The columns of a CSV file with a header line naming them.
fn read_csv(path: &Path) -> Result<Vec<NamedArray>> {
    let table = read_table(CsvReader::open(path, Header::Required)?)?;
    let n = table.rows.len();
    Ok(table
        .header
        .iter()
        .enumerate()
        .map(|(c, name)| NamedArray {
            name: name.clone(),
            shape: vec![n],
            data: table.rows.iter().map(|r| r[c]).collect(),
        })
        .collect())
}

fn shape2(file: &str, name: &str, shape: &[usize]) -> Result<Vec<usize>> {
    let kept: Vec<usize> = shape.to_vec();
    match kept.len() {
        1 | 2 => Ok(kept),
        0 => Ok(vec![1]),
        _ => Err(Error::invalid(
            file,
            name,
            format!("{shape:?}"),
            "an array of one or two dimensions (samples, or samples x records)",
        )),
    }
}

fn npy_array<R: std::io::Read>(
    file: &str,
    name: &str,
    npy: npyz::NpyFile<R>,
) -> Result<NamedArray> {
    use npyz::{DType, TypeChar};
    let shape: Vec<usize> = npy.shape().iter().map(|&s| s as usize).collect();
    let shape = shape2(file, name, &shape)?;
    let fortran = npy.order() == npyz::Order::Fortran;
    let dtype = npy.dtype();
    let DType::Plain(ts) = &dtype else {
        return Err(Error::invalid(
            file,
            name,
            dtype.descr(),
            "an array of real numbers (not a structured array)",
        ));
    };
    let io = |e: std::io::Error| bad(file, name, "readable array data", e);
    let data: Vec<f64> = match (ts.type_char(), ts.size_field()) {
        (TypeChar::Float, 8) => npy.into_vec::<f64>().map_err(io)?,
        (TypeChar::Float, 4) => npy
            .into_vec::<f32>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, 8) => npy
            .into_vec::<i64>()
            .map_err(io)?
            .into_iter()
            .map(|v| v as f64)
            .collect(),
        (TypeChar::Int, 4) => npy
            .into_vec::<i32>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, 2) => npy
            .into_vec::<i16>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, 1) => npy
            .into_vec::<i8>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Uint, 2) => npy
            .into_vec::<u16>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Uint, 1) => npy
            .into_vec::<u8>()
            .map_err(io)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Complex, _) => {
            return Err(Error::invalid(
                file,
                name,
                ts.to_string(),
                "real data (complex records are not analysed: pass the real part)",
            ));
        }
        _ => {
            return Err(Error::invalid(
                file,
                name,
                ts.to_string(),
                "an array of real numbers: float64, float32, or integers of 8 to 64 bits",
            ));
        }
    };
    let data = if fortran && shape.len() == 2 {
        transpose(&data, shape[1], shape[0])
    } else {
        data
    };
    Ok(NamedArray {
        name: name.to_string(),
        shape,
        data,
    })
}

/// Row-major `[rows, cols]` of column-major data (`rows` x `cols`, stored column by column).
fn transpose(col_major: &[f64], cols: usize, rows: usize) -> Vec<f64> {
    let mut out = vec![0.0; col_major.len()];
    for j in 0..cols {
        for i in 0..rows {
            out[i * cols + j] = col_major[j * rows + i];
        }
    }
    out
}

fn mat_v5_array(file: &str, a: &matfile::Array) -> Result<NamedArray> {
    use matfile::NumericData as N;
    let name = a.name().to_string();
    let complex = || {
        Error::invalid(
            file,
            &name,
            "complex",
            "real data (complex records are not analysed: save real(x))",
        )
    };
    macro_rules! real {
        ($re:expr_2021, $im:expr_2021) => {{
            if $im.is_some() {
                return Err(complex());
            }
            $re.iter().map(|&v| v as f64).collect::<Vec<f64>>()
        }};
    }
    let data: Vec<f64> = match a.data() {
        N::Double { real, imag } => real!(real, imag),
        N::Single { real, imag } => real!(real, imag),
        N::Int8 { real, imag } => real!(real, imag),
        N::UInt8 { real, imag } => real!(real, imag),
        N::Int16 { real, imag } => real!(real, imag),
        N::UInt16 { real, imag } => real!(real, imag),
        N::Int32 { real, imag } => real!(real, imag),
        N::UInt32 { real, imag } => real!(real, imag),
        N::Int64 { real, imag } => real!(real, imag),
        N::UInt64 { real, imag } => real!(real, imag),
    };
    let size = a.size().clone();
    let shape = shape2(file, &name, &size)?;
    let data = if shape.len() == 2 {
        transpose(&data, shape[1], shape[0])
    } else {
        data
    };
    Ok(NamedArray { name, shape, data })
}

/// Datasets of an HDF5 file (or MAT v7.3, whose datasets hold MATLAB's column-major
/// arrays: HDF5 shape `[cols, rows]`, transposed back here).
fn read_hdf5(path: &Path, names: &[String], matlab: bool) -> Result<Vec<NamedArray>> {
    let shown = path.display().to_string();
    let f = hdf5_pure::File::open(path).map_err(|e| bad(&shown, "file", "an HDF5 file", e))?;
    let wanted: Vec<String> = if names.is_empty() {
        let mut found = Vec::new();
        walk(&f.root(), "", 0, &mut found)
            .map_err(|e| bad(&shown, "file", "an HDF5 file with readable groups", e))?;
        found
    } else {
        names.to_vec()
    };
    let mut out = Vec::new();
    for name in &wanted {
        let ds = f.dataset(name).map_err(|e| {
            bad(
                &shown,
                name,
                "the path of a dataset in the file (e.g. /records/echo)",
                e,
            )
        })?;
        let dtype = ds
            .dtype()
            .map_err(|e| bad(&shown, name, "a dataset with a readable type", e))?;
        use hdf5_pure::DType as D;
        match dtype {
            D::F32
            | D::F64
            | D::I8
            | D::I16
            | D::I32
            | D::I64
            | D::U8
            | D::U16
            | D::U32
            | D::U64 => {}
            D::Compound(fields) if fields.iter().any(|(n, _)| n == "real" || n == "imag") => {
                return Err(Error::invalid(
                    &shown,
                    name,
                    "complex",
                    "real data (complex records are not analysed: save real(x))",
                ));
            }
            other => {
                if names.is_empty() {
                    continue; // not a record: strings, references, MATLAB's #refs#
                }
                return Err(Error::invalid(
                    &shown,
                    name,
                    other.to_string(),
                    "a dataset of real numbers (floats or integers)",
                ));
            }
        }
        if matlab && let Ok(attrs) = ds.attrs() {
            let class = match attrs.get("MATLAB_class") {
                Some(hdf5_pure::AttrValue::String(c) | hdf5_pure::AttrValue::AsciiString(c)) => {
                    Some(c.trim_end_matches('\0').to_string())
                }
                _ => None,
            };
            if let Some(class) = class {
                let numeric = [
                    "double", "single", "int8", "uint8", "int16", "uint16", "int32", "uint32",
                    "int64", "uint64",
                ];
                if !numeric.contains(&class.as_str()) {
                    if names.is_empty() {
                        continue;
                    }
                    return Err(Error::invalid(
                        &shown,
                        name,
                        format!("MATLAB class {class}"),
                        "a numeric MATLAB array (double, single or integers)",
                    ));
                }
            }
        }
        let raw_shape: Vec<usize> = ds
            .shape()
            .map_err(|e| bad(&shown, name, "a dataset with a readable shape", e))?
            .iter()
            .map(|&s| s as usize)
            .collect();
        let count: f64 = raw_shape.iter().map(|&s| s as f64).product();
        budget::check_or(
            &shown,
            name,
            format!("{raw_shape:?}"),
            count * 8.0 * 4.0,
            "the dataset's values",
            "read a smaller dataset",
        )?;
        let data = ds
            .read_f64()
            .map_err(|e| bad(&shown, name, "readable dataset values", e))?;
        let shape = shape2(&shown, name, &raw_shape)?;
        let (shape, data) = if matlab && shape.len() == 2 {
            // HDF5 [cols, rows], C order: element (c, r) at c * rows + r, i.e. MATLAB's
            // column-major rows x cols
            let (cols, rows) = (shape[0], shape[1]);
            (vec![rows, cols], transpose(&data, cols, rows))
        } else {
            (shape, data)
        };
        out.push(NamedArray {
            name: name.trim_start_matches('/').to_string(),
            shape,
            data,
        });
    }
    Ok(out)
}

/// Most datasets and levels of groups [`walk`] lists.
const WALK_LIMIT: (usize, usize) = (4096, 16);

/// The paths of every dataset under `group` (at path `prefix`), depth first, skipping
/// MATLAB's `#refs#` and `#subsystem#` groups.
fn walk(
    group: &hdf5_pure::Group,
    prefix: &str,
    depth: usize,
    out: &mut Vec<String>,
) -> std::result::Result<(), hdf5_pure::Error> {
    if depth > WALK_LIMIT.1 || out.len() >= WALK_LIMIT.0 {
        return Ok(());
    }
    for d in group.datasets()? {
        out.push(format!("{prefix}/{d}"));
    }
    for g in group.groups()? {
        if g.starts_with('#') {
            continue;
        }
        let child = group.group(&g)?;
        walk(&child, &format!("{prefix}/{g}"), depth + 1, out)?;
    }
    Ok(())
}

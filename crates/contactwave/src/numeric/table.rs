//! The one reader of measured and tabulated data in CSV files: identification data
//! (`inverse`), the `fit` command's stiffness-pressure data and excitation waveforms
//! (`excitation::FileWaveform`). `#` starts a comment line, cells are trimmed, numbers
//! parse as `f64` (`NaN` and `inf` parse: finiteness is the caller's rule). Every error is
//! one [`CsvError`] naming the file, the line and the column (by header name, or
//! `column N` in a file without a header).
//!
//! [`CsvReader`] streams rows (a waveform longer than the simulated window is never read
//! to its end); [`read_table`] reads a whole table with a header.

use crate::error::Error;
use std::io::BufRead;
use std::path::Path;

/// An error reading a CSV table: where (file, line, column), the cell and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {}: {value}: {expected}", self.place())]
pub struct CsvError {
    /// The file (as shown to the user).
    pub file: String,
    /// Line of the file, from 1 (0: the file as a whole, e.g. it cannot be opened).
    pub line: u64,
    /// The column: its header name, or `column N` (from 1); `None` for a whole line.
    pub column: Option<String>,
    /// The offending cell or line, as written.
    pub value: String,
    /// What is allowed there.
    pub expected: String,
}

impl CsvError {
    /// `line L, column C` (or `line L`, or `file`): the field of the [`Error::Invalid`]
    /// this error becomes.
    pub fn place(&self) -> String {
        match (self.line, &self.column) {
            (0, _) => "file".to_string(),
            // (a file without a header names its columns `column N` already)
            (l, Some(c)) if c.starts_with("column ") => format!("line {l}, {c}"),
            (l, Some(c)) => format!("line {l}, column {c}"),
            (l, None) => format!("line {l}"),
        }
    }
}

impl From<CsvError> for Error {
    fn from(e: CsvError) -> Error {
        let field = e.place();
        Error::Invalid {
            file: e.file,
            field,
            value: e.value,
            allowed: e.expected,
        }
    }
}

/// Whether the first record of a file is a header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Header {
    /// The first record names the columns (identification data, `fit`).
    Required,
    /// The first record is a header when one of the cells a caller reads from it is not a
    /// number (a waveform: `time,stress` or none).
    Optional,
}

/// A streaming reader of numeric CSV rows (see the module doc). The lines are read here
/// (so that every error names its true line, comment and blank lines counted) and each
/// is split into cells by the `csv` crate's parser (`csv-core`: quoted cells, `\r\n`); a
/// quoted cell cannot span lines.
pub struct CsvReader<R: BufRead> {
    source: R,
    file: String,
    header: Option<Vec<String>>,
    mode: Header,
    core: csv_core::Reader,
    /// The current line, its cells' bytes and their ends (reused: no allocation per row).
    text: Vec<u8>,
    bytes: Vec<u8>,
    ends: Vec<usize>,
    cells: usize,
    line: u64,
    first: bool,
}

impl CsvReader<std::io::BufReader<std::fs::File>> {
    /// Open `path` (its display name names it in errors).
    pub fn open(path: &Path, header: Header) -> Result<Self, CsvError> {
        let file = path.display().to_string();
        let f = std::fs::File::open(path).map_err(|e| CsvError {
            file: file.clone(),
            line: 0,
            column: None,
            value: file.clone(),
            expected: format!("cannot read CSV: {e}"),
        })?;
        CsvReader::new(std::io::BufReader::new(f), file, header)
    }
}

impl<'a> CsvReader<&'a [u8]> {
    /// Read CSV `text` that came from `file`.
    pub fn from_text(text: &'a str, file: &str, header: Header) -> Result<Self, CsvError> {
        CsvReader::new(text.as_bytes(), file.to_string(), header)
    }
}

impl<R: BufRead> CsvReader<R> {
    fn new(source: R, file: String, mode: Header) -> Result<Self, CsvError> {
        let mut r = CsvReader {
            source,
            file,
            header: None,
            mode,
            core: csv_core::Reader::new(),
            text: Vec::new(),
            bytes: vec![0; 256],
            ends: vec![0; 16],
            cells: 0,
            line: 0,
            first: true,
        };
        if mode == Header::Required {
            if !r.advance()? {
                return Err(r.error(1, None, "(empty)", "a header line naming the columns"));
            }
            let names: Vec<String> = (0..r.cells).map(|c| r.cell(c).trim().to_string()).collect();
            r.check_header(&names)?;
            r.header = Some(names);
            r.first = false;
        }
        Ok(r)
    }

    /// A required header names every column once, and is not a row of numbers (a file
    /// without a header would lose its first row to it).
    fn check_header(&self, names: &[String]) -> Result<(), CsvError> {
        if names.iter().all(|n| n.parse::<f64>().is_ok()) {
            return Err(self.error(
                1,
                None,
                names.join(","),
                "a header line naming the columns (this line holds numbers only: add one, \
                 e.g. t,v)",
            ));
        }
        for (c, name) in names.iter().enumerate() {
            if name.is_empty() {
                return Err(self.error(
                    1,
                    Some(format!("column {}", c + 1)),
                    "(empty)",
                    "a name for every column of the header line",
                ));
            }
            if names[..c].contains(name) {
                return Err(self.error(
                    1,
                    Some(name.clone()),
                    format!("column {} named again", c + 1),
                    "each column named once",
                ));
            }
        }
        Ok(())
    }

    /// The column names (empty for a file without a header).
    pub fn header(&self) -> &[String] {
        self.header.as_deref().unwrap_or(&[])
    }

    /// The name of column `c` (from 0) in errors: its header name or `column c+1`.
    pub fn column_name(&self, c: usize) -> String {
        match self.header().get(c) {
            Some(h) => h.clone(),
            None => format!("column {}", c + 1),
        }
    }

    /// An error at `line` (and `column`) of this file: for the callers' own checks
    /// (finite, increasing, ...), so that every error of a table reads alike.
    pub fn error(
        &self,
        line: u64,
        column: Option<String>,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> CsvError {
        CsvError {
            file: self.file.clone(),
            line,
            column,
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// Cell `c` of the current line, trimmed.
    fn cell(&self, c: usize) -> &str {
        let start = if c == 0 { 0 } else { self.ends[c - 1] };
        // the cells were checked to be UTF-8 when the line was split
        std::str::from_utf8(&self.bytes[start..self.ends[c]])
            .unwrap_or("")
            .trim()
    }

    /// Read the next line that is not blank or a `#` comment and split it into cells;
    /// false at the end of the file.
    fn advance(&mut self) -> Result<bool, CsvError> {
        loop {
            self.text.clear();
            let n = self
                .source
                .read_until(b'\n', &mut self.text)
                .map_err(|e| self.error(self.line + 1, None, "?", format!("cannot read: {e}")))?;
            if n == 0 {
                return Ok(false);
            }
            self.line += 1;
            let Ok(text) = std::str::from_utf8(&self.text) else {
                return Err(self.error(self.line, None, "(not text)", "UTF-8 text"));
            };
            let t = text.trim();
            if !t.is_empty() && !t.starts_with('#') {
                break;
            }
        }
        self.split();
        Ok(true)
    }

    /// Split `self.text` (one line) into cells.
    fn split(&mut self) {
        use csv_core::ReadRecordResult as R;
        self.core.reset();
        let (mut input, mut out, mut end) = (0, 0, 0);
        loop {
            let (res, nin, nout, nend) = self.core.read_record(
                &self.text[input..],
                &mut self.bytes[out..],
                &mut self.ends[end..],
            );
            input += nin;
            out += nout;
            end += nend;
            match res {
                R::OutputFull => self.bytes.resize(2 * self.bytes.len(), 0),
                R::OutputEndsFull => self.ends.resize(2 * self.ends.len(), 0),
                // a line without its newline (the last one): the end of the input ends it
                R::InputEmpty => {}
                R::Record | R::End => break,
            }
        }
        self.cells = end;
    }

    /// Read the next row's cells `columns` (indices from 0) into `out` (cleared first);
    /// returns the row's line, or `None` at the end. With a header every row must have as
    /// many cells as the header; without one, at least the cells asked for.
    pub fn next_row(
        &mut self,
        columns: &[usize],
        out: &mut Vec<f64>,
    ) -> Result<Option<u64>, CsvError> {
        loop {
            if !self.advance()? {
                return Ok(None);
            }
            let line = self.line;
            let need = columns.iter().map(|c| c + 1).max().unwrap_or(0);
            match (self.mode, &self.header) {
                (Header::Required, Some(h)) if self.cells != h.len() => {
                    return Err(self.error(
                        line,
                        None,
                        format!("{} cells", self.cells),
                        format!("{} cells, as the header", h.len()),
                    ));
                }
                _ if self.cells < need => {
                    return Err(self.error(
                        line,
                        None,
                        format!("{} cells", self.cells),
                        format!("at least {need} cells"),
                    ));
                }
                _ => {}
            }
            out.clear();
            let mut bad = None;
            for &c in columns {
                match self.cell(c).parse::<f64>() {
                    Ok(x) => out.push(x),
                    Err(_) => {
                        bad = Some(c);
                        break;
                    }
                }
            }
            let first = std::mem::replace(&mut self.first, false);
            match bad {
                None => return Ok(Some(line)),
                Some(_) if first && self.mode == Header::Optional => {
                    self.header = Some((0..self.cells).map(|c| self.cell(c).to_string()).collect());
                }
                Some(c) => {
                    // a file separated by `;` or tabs reads as one column of text
                    let separator = [';', '\t'].into_iter().find(|s| self.cell(c).contains(*s));
                    let allowed = match separator {
                        Some(';') => "a number (cells separated by commas; this line uses `;`)",
                        Some(_) => "a number (cells separated by commas; this line uses tabs)",
                        None => "a number",
                    };
                    return Err(self.error(line, Some(self.column_name(c)), self.cell(c), allowed));
                }
            }
        }
    }
}

/// A whole numeric table with a header: `rows[i][c]` is column `header[c]` at the row on
/// line `lines[i]` of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvTable {
    /// Column names.
    pub header: Vec<String>,
    /// The rows, every one as long as the header.
    pub rows: Vec<Vec<f64>>,
    /// Line of each row in the file.
    pub lines: Vec<u64>,
}

/// Read every column of a table with a header; at least one data row.
pub fn read_table<R: BufRead>(mut reader: CsvReader<R>) -> Result<CsvTable, CsvError> {
    let header = reader.header().to_vec();
    let all: Vec<usize> = (0..header.len()).collect();
    let (mut rows, mut lines) = (Vec::new(), Vec::new());
    let mut row = Vec::with_capacity(all.len());
    while let Some(line) = reader.next_row(&all, &mut row)? {
        rows.push(row.clone());
        lines.push(line);
    }
    if rows.is_empty() {
        return Err(reader.error(0, None, "0 rows", "at least one data row"));
    }
    Ok(CsvTable {
        header,
        rows,
        lines,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> Result<CsvTable, CsvError> {
        read_table(CsvReader::from_text(text, "d.csv", Header::Required)?)
    }

    #[test]
    fn tables_read_with_comments_blanks_and_spaces() {
        let t = table("# measured\nxi, A\n0.1, 2\n\n# more\n 0.2 ,NaN\n").unwrap();
        assert_eq!(t.header, ["xi", "A"]);
        assert_eq!(t.rows[0], [0.1, 2.0]);
        assert!(t.rows[1][1].is_nan());
        assert_eq!(t.lines, [3, 6]);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let e = table("xi,A\n0.1,2\n0.2,abc\n").unwrap_err();
        assert_eq!((e.line, e.column.as_deref()), (3, Some("A")));
        assert_eq!(
            Error::from(e).to_string(),
            "d.csv: field `line 3, column A` = abc: a number"
        );
        // a file separated by semicolons says so
        let e = table("t;ch1\n0.0;0.3\n").unwrap_err();
        assert!(e.expected.contains("this line uses `;`"), "{e}");
        let e = table("xi,A\n0.1,2,3\n").unwrap_err();
        assert_eq!((e.line, e.value.as_str()), (2, "3 cells"));
        assert!(e.expected.contains("2 cells, as the header"), "{e}");
        let e = table("xi,A\n").unwrap_err();
        assert!(e.expected.contains("at least one data row"), "{e}");
        let e = table("# only a comment\n").unwrap_err();
        assert!(e.expected.contains("header"), "{e}");
        let e = CsvReader::open(Path::new("/nonexistent/w.csv"), Header::Optional)
            .err()
            .unwrap();
        assert_eq!(e.line, 0);
        assert!(
            e.to_string().starts_with("/nonexistent/w.csv: file: "),
            "{e}"
        );
    }

    #[test]
    fn an_optional_header_is_skipped_only_on_the_first_row() {
        let mut buf = Vec::new();
        for text in ["t,s\n0,1\n1e-6,2,extra\n", "0,1\n1e-6,2\n"] {
            let mut r = CsvReader::from_text(text, "w.csv", Header::Optional).unwrap();
            assert!(r.next_row(&[0, 1], &mut buf).unwrap().is_some());
            assert_eq!(buf, [0.0, 1.0]);
            r.next_row(&[0, 1], &mut buf).unwrap().unwrap();
            assert_eq!(buf, [1e-6, 2.0]);
            assert_eq!(r.next_row(&[0, 1], &mut buf).unwrap(), None);
        }
        let mut r = CsvReader::from_text("t,s\n0,x\n", "w.csv", Header::Optional).unwrap();
        let e = r.next_row(&[0, 1], &mut buf).unwrap_err();
        assert_eq!((e.line, e.column.as_deref()), (2, Some("s")));
        let mut r = CsvReader::from_text("0,1\n2\n", "w.csv", Header::Optional).unwrap();
        r.next_row(&[0, 1], &mut buf).unwrap();
        let e = r.next_row(&[0, 1], &mut buf).unwrap_err();
        assert_eq!((e.line, e.expected.as_str()), (2, "at least 2 cells"));
        let mut r = CsvReader::from_text("0,1\n2,y\n", "w.csv", Header::Optional).unwrap();
        r.next_row(&[0, 1], &mut buf).unwrap();
        let e = r.next_row(&[0, 1], &mut buf).unwrap_err();
        assert_eq!(e.column.as_deref(), Some("column 2"));
    }

    #[test]
    fn a_required_header_names_every_column_once() {
        let open = |text: &str| CsvReader::from_text(text, "h.csv", Header::Required).err();
        assert!(open("t,v\n0,1\n").is_none());
        let e = open("0,1\n1,2\n").unwrap().to_string();
        assert!(e.contains("h.csv") && e.contains("header line"), "{e}");
        let e = open("t,\n0,1\n").unwrap().to_string();
        assert!(e.contains("column 2") && e.contains("(empty)"), "{e}");
        let e = open("t,v,v\n0,1,2\n").unwrap().to_string();
        assert!(e.contains("column v") && e.contains("named once"), "{e}");
    }
}

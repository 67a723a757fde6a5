//! CSV tables with a header, appended and flushed row by row so that a killed run keeps what it
//! computed. A row with a non-finite number is refused: no NaN ever reaches a file.

use crate::error::{Error, Result};
use crate::format::format_number;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A CSV file being written.
pub struct CsvWriter {
    path: PathBuf,
    columns: usize,
    out: BufWriter<File>,
}

impl CsvWriter {
    /// Creates (truncates) `path` and writes the header.
    pub fn create(path: &Path, header: &[&str]) -> Result<Self> {
        let file = File::create(path).map_err(|e| Error::io(path, e))?;
        let mut writer = CsvWriter {
            path: path.to_path_buf(),
            columns: header.len(),
            out: BufWriter::new(file),
        };
        writer.write_line(&header.join(","))?;
        Ok(writer)
    }

    /// Appends one row of numbers and flushes it to disk.
    pub fn append(&mut self, row: &[f64]) -> Result<()> {
        self.append_labelled(None, row)
    }

    /// Appends one row whose first column is a text label.
    pub fn append_labelled(&mut self, label: Option<&str>, row: &[f64]) -> Result<()> {
        let width = row.len() + usize::from(label.is_some());
        assert_eq!(
            width,
            self.columns,
            "row width does not match the header of {}",
            self.path.display()
        );
        if let Some(bad) = row.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFinite(format!(
                "column {} of a row for {}",
                bad + 1,
                self.path.display()
            )));
        }
        let numbers = row.iter().map(|&x| format_number(x));
        let line: Vec<String> = label.map(str::to_string).into_iter().chain(numbers).collect();
        self.write_line(&line.join(","))
    }

    /// Appends one row of text, numbers and empty fields (numbers must be finite).
    pub fn append_cells(&mut self, cells: &[Cell<'_>]) -> Result<()> {
        assert_eq!(
            cells.len(),
            self.columns,
            "row width does not match the header of {}",
            self.path.display()
        );
        let mut fields = Vec::with_capacity(cells.len());
        for (i, cell) in cells.iter().enumerate() {
            fields.push(match *cell {
                Cell::Text(t) => t.to_string(),
                Cell::Empty => String::new(),
                Cell::Number(x) if x.is_finite() => format_number(x),
                Cell::Number(_) => {
                    return Err(Error::NonFinite(format!(
                        "column {} of a row for {}",
                        i + 1,
                        self.path.display()
                    )))
                }
            });
        }
        self.write_line(&fields.join(","))
    }

    fn write_line(&mut self, line: &str) -> Result<()> {
        writeln!(self.out, "{line}")
            .and_then(|_| self.out.flush())
            .map_err(|e| Error::io(&self.path, e))
    }
}

/// One named column of a table whose rows are `R`s: the header and every row of a table come
/// from one list of these, so that a column is one entry.
pub struct Column<R> {
    pub name: &'static str,
    /// The column's value in a row.
    pub value: fn(&R) -> f64,
}

/// The header of the columns `columns`.
pub fn header<R>(columns: &[Column<R>]) -> Vec<&'static str> {
    columns.iter().map(|c| c.name).collect()
}

/// The row of `record` in the columns `columns`.
pub fn row<R>(columns: &[Column<R>], record: &R) -> Vec<f64> {
    columns.iter().map(|c| (c.value)(record)).collect()
}

/// One field of a CSV row.
#[derive(Clone, Copy, Debug)]
pub enum Cell<'a> {
    Text(&'a str),
    Number(f64),
    /// A value that does not exist (e.g. `k0` of a long-wave limit).
    Empty,
}

/// The JSON name of a unit enum variant (`"long_wave"`), for a text cell.
pub fn variant_name<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_non_finite_rows_and_keeps_earlier_ones() {
        let dir = std::env::temp_dir().join(format!("fiberfold-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.csv");
        let mut w = CsvWriter::create(&path, &["a", "b"]).unwrap();
        w.append(&[1.0, 2.5]).unwrap();
        assert!(w.append(&[f64::NAN, 1.0]).is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a,b\n1,2.5\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_header_and_a_row_come_from_one_list_of_columns() {
        let columns: [Column<(f64, f64)>; 2] = [
            Column {
                name: "x",
                value: |r| r.0,
            },
            Column {
                name: "sum",
                value: |r| r.0 + r.1,
            },
        ];
        assert_eq!(header(&columns), ["x", "sum"]);
        assert_eq!(row(&columns, &(1.5, 2.0)), [1.5, 3.5]);
    }
}

//! `history.csv`: one row per converged step, appended and flushed as the run goes, so an
//! interrupted run keeps every converged step.

use crate::error::{CoreError, Result};
use crate::observables::Value;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub struct HistoryWriter {
    path: PathBuf,
    columns: Vec<String>,
    file: BufWriter<File>,
}

impl HistoryWriter {
    /// Creates the file with its header line.
    pub fn create(path: &Path, columns: Vec<String>) -> Result<Self> {
        let err = |source| CoreError::Write { path: path.to_path_buf(), source };
        let file = File::create(path).map_err(err)?;
        let mut file = BufWriter::new(file);
        writeln!(file, "{}", columns.join(",")).map_err(err)?;
        file.flush().map_err(err)?;
        Ok(Self { path: path.to_path_buf(), columns, file })
    }

    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// Appends one row of text fields (same length as the header) and flushes it to disk.
    pub fn append_fields(&mut self, row: &[String]) -> Result<()> {
        assert_eq!(row.len(), self.columns.len(), "row does not match its header");
        let err = |source| CoreError::Write { path: self.path.clone(), source };
        writeln!(self.file, "{}", row.join(",")).map_err(err)?;
        self.file.flush().map_err(err)?;
        self.file.get_ref().sync_data().map_err(err)
    }

    /// Appends one row of values (same length as the header) and flushes it to disk: reals
    /// as `{:.10e}`, counts as integers.
    pub fn append(&mut self, row: &[Value]) -> Result<()> {
        let fields: Vec<String> = row
            .iter()
            .map(|v| match v {
                Value::Real(x) => format!("{x:.10e}"),
                Value::Count(n) => n.to_string(),
            })
            .collect();
        self.append_fields(&fields)
    }
}

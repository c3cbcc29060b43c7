//! `history.csv`: one row per converged step, appended and flushed as the run goes, so an
//! interrupted run keeps every converged step.

use crate::error::{CoreError, Result};
use crate::observables::Value;
use crate::record::ObserverState;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub struct HistoryWriter {
    path: PathBuf,
    columns: Vec<String>,
    /// Open from [`Self::start`] or [`Self::reopen_at`] on.
    file: Option<BufWriter<File>>,
}

impl HistoryWriter {
    /// A writer of `path` with these columns; the file is not touched until [`Self::start`]
    /// (or [`Self::reopen_at`]).
    pub fn new(path: &Path, columns: Vec<String>) -> Self {
        Self { path: path.to_path_buf(), columns, file: None }
    }

    fn error(&self, source: std::io::Error) -> CoreError {
        CoreError::Write { path: self.path.clone(), source }
    }

    /// Creates the file with its header line.
    pub fn start(&mut self) -> Result<()> {
        let file = File::create(&self.path).map_err(|e| self.error(e))?;
        let mut file = BufWriter::new(file);
        writeln!(file, "{}", self.columns.join(",")).map_err(|e| self.error(e))?;
        file.flush().map_err(|e| self.error(e))?;
        self.file = Some(file);
        Ok(())
    }

    /// Goes on with the file an earlier run wrote: its header must be this writer's, and it is
    /// cut back to its first `length` bytes (what had been written at a checkpoint,
    /// [`Self::length`]) before rows are appended again.
    pub fn reopen_at(&mut self, length: u64) -> Result<()> {
        let text = std::fs::read(&self.path).map_err(|e| self.error(e))?;
        let header = text.split(|&b| b == b'\n').next().unwrap_or_default();
        if header != self.columns.join(",").as_bytes() {
            return Err(CoreError::Invalid(format!(
                "'{}' does not start with the header this run writes ({} columns): it was not written by the \
                 checkpointed run",
                self.path.display(),
                self.columns.len()
            )));
        }
        if (text.len() as u64) < length {
            return Err(CoreError::Invalid(format!(
                "'{}' has {} bytes, fewer than the {length} it had at the checkpoint",
                self.path.display(),
                text.len()
            )));
        }
        let file = std::fs::OpenOptions::new().append(true).open(&self.path).map_err(|e| self.error(e))?;
        file.set_len(length).map_err(|e| self.error(e))?;
        self.file = Some(BufWriter::new(file));
        Ok(())
    }

    /// The bytes written so far (all flushed: every row is).
    pub fn length(&self) -> Result<u64> {
        let file = self.file.as_ref().ok_or_else(|| self.not_open())?;
        Ok(file.get_ref().metadata().map_err(|e| self.error(e))?.len())
    }

    /// The file's record in a checkpoint: its length, under its file name.
    pub fn saved_state(&self) -> Result<ObserverState> {
        Ok(ObserverState::new(&self.record_name(), &self.length()?))
    }

    /// Goes on from the checkpoint that holds `saved` ([`Self::saved_state`]): the file is cut
    /// back to its length then ([`Self::reopen_at`]).
    pub fn resume(&mut self, saved: &[ObserverState]) -> Result<()> {
        self.reopen_at(ObserverState::find(saved, &self.record_name())?)
    }

    fn record_name(&self) -> String {
        self.path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    }

    fn not_open(&self) -> CoreError {
        CoreError::Invalid(format!("'{}' was written to before the run started", self.path.display()))
    }

    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// Appends one row of text fields (same length as the header) and flushes it to disk.
    pub fn append_fields(&mut self, row: &[String]) -> Result<()> {
        assert_eq!(row.len(), self.columns.len(), "row does not match its header");
        let err = |source| CoreError::Write { path: self.path.clone(), source };
        let Some(file) = self.file.as_mut() else { return Err(self.not_open()) };
        writeln!(file, "{}", row.join(",")).map_err(err)?;
        file.flush().map_err(err)?;
        file.get_ref().sync_data().map_err(err)
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

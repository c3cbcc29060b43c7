//! `messages.log`: what the run did, line by line as it happens, each line stamped with the
//! wall time since the run started: every committed increment (its one-line description),
//! every progress message (an increment cut and why, a snap and what it took, a crossing),
//! and how the run ended. It is the status file of a long run (ABAQUS writes its `.sta` and
//! `.msg` files for the same reason): `tail -f` shows where the time goes while the run is
//! still going, and an interrupted or failed run keeps the record up to its last line.

use super::{CommittedIncrement, Observer, RunSummary};
use crate::error::{CoreError, Result};
use crate::model::Model;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub struct MessageLog {
    path: PathBuf,
    file: File,
    started: Instant,
    /// A write that failed inside [`Observer::message`] (which cannot return it), reported by
    /// the next call that can.
    pending_error: Option<std::io::Error>,
}

impl MessageLog {
    /// Creates (truncates) the log at `path`.
    pub fn create(path: &Path) -> Result<Self> {
        let file = File::create(path).map_err(|source| CoreError::Write { path: path.to_path_buf(), source })?;
        Ok(Self { path: path.to_path_buf(), file, started: Instant::now(), pending_error: None })
    }

    /// Appends one stamped line in a single write (so a reader never sees half a line).
    fn line(&mut self, text: &str) -> std::io::Result<()> {
        let stamped = format!("[{:>10.1} s] {text}\n", self.started.elapsed().as_secs_f64());
        self.file.write_all(stamped.as_bytes())
    }

    /// Appends a line, or returns the write error (or one left by an earlier message).
    fn write(&mut self, text: &str) -> Result<()> {
        let written = match self.pending_error.take() {
            Some(e) => Err(e),
            None => self.line(text),
        };
        written.map_err(|source| CoreError::Write { path: self.path.clone(), source })
    }
}

impl Observer for MessageLog {
    fn started(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        self.started = Instant::now();
        let text = format!(
            "run '{}': {} free dofs, {} nonzeros, {} in the factor",
            summary.case, summary.n_free_dofs, summary.nnz, summary.factor_nnz
        );
        self.write(&text)
    }

    fn committed(&mut self, _model: &Model, increment: &CommittedIncrement) -> Result<()> {
        let text = format!("increment {}: {}", increment.increment, increment.description);
        self.write(&text)
    }

    fn message(&mut self, text: &str) {
        if self.pending_error.is_none()
            && let Err(e) = self.line(text)
        {
            self.pending_error = Some(e);
        }
    }

    fn finished(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        let mut text = format!(
            "{} at t = {}: {} increments, {} cut, {} snaps, {} Newton iterations, {} factorizations",
            summary.status,
            summary.final_time,
            summary.increments,
            summary.cut_increments,
            summary.snaps,
            summary.newton_iterations,
            summary.factorizations
        );
        if let Some(message) = &summary.message {
            text.push_str(&format!("; {message}"));
        }
        self.write(&text)
    }
}

//! `messages.log`: what the run did, line by line as it happens, each line stamped with the
//! wall time since the run started: every committed increment (its one-line description),
//! every progress message (an increment cut and why, a snap and what it took, a crossing),
//! and how the run ended. It is the status file of a long run (ABAQUS writes its `.sta` and
//! `.msg` files for the same reason): `tail -f` shows where the time goes while the run is
//! still going, and an interrupted or failed run keeps the record up to its last line.

use super::{CommittedIncrement, Observer, ObserverState, RunSummary};
use crate::error::{CoreError, Result};
use crate::model::Model;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub struct MessageLog {
    path: PathBuf,
    /// Open from the run's start (or resumption) on.
    file: Option<File>,
    started: Instant,
    /// Wall seconds of the run before it was resumed, added to the stamps.
    earlier_seconds: f64,
    pending_error: Option<std::io::Error>,
}

/// The name of messages.log's record in a checkpoint.
const NAME: &str = "messages.log";

/// What a checkpoint keeps of the log: its length, and the stamp it had reached.
#[derive(serde::Serialize, serde::Deserialize)]
struct Saved {
    length: u64,
    seconds: f64,
}

impl MessageLog {
    /// A log written to `path` from the run's start on.
    pub fn new(path: &Path) -> Self {
        Self {
            path: path.to_path_buf(),
            file: None,
            started: Instant::now(),
            earlier_seconds: 0.0,
            pending_error: None,
        }
    }

    fn seconds(&self) -> f64 {
        self.earlier_seconds + self.started.elapsed().as_secs_f64()
    }

    fn line(&mut self, text: &str) -> std::io::Result<()> {
        let stamped = format!("[{:>10.1} s] {text}\n", self.seconds());
        match self.file.as_mut() {
            Some(file) => file.write_all(stamped.as_bytes()),
            None => Err(std::io::Error::other("written to before the run started")),
        }
    }

    fn write(&mut self, text: &str) -> Result<()> {
        let written = match self.pending_error.take() {
            Some(e) => Err(e),
            None => self.line(text),
        };
        written.map_err(|source| CoreError::Write { path: self.path.clone(), source })
    }

    fn io(&self, source: std::io::Error) -> CoreError {
        CoreError::Write { path: self.path.clone(), source }
    }
}

impl Observer for MessageLog {
    fn started(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        self.file = Some(File::create(&self.path).map_err(|e| self.io(e))?);
        self.started = Instant::now();
        let text = format!(
            "run '{}': {} free dofs, {} nonzeros, {} in the factor",
            summary.case, summary.n_free_dofs, summary.nnz, summary.factor_nnz
        );
        self.write(&text)
    }

    fn saved_state(&mut self) -> Result<Option<ObserverState>> {
        let file = self.file.as_ref().ok_or_else(|| self.io(std::io::Error::other("not open")))?;
        let length = file.metadata().map_err(|e| self.io(e))?.len();
        Ok(Some(ObserverState::new(NAME, &Saved { length, seconds: self.seconds() })))
    }

    /// Cuts the log back to the checkpoint and goes on with its stamps from there.
    fn resumed(&mut self, _model: &Model, summary: &RunSummary, saved: &[ObserverState]) -> Result<()> {
        let Saved { length, seconds } = ObserverState::find(saved, NAME)?;
        let file = std::fs::OpenOptions::new().append(true).open(&self.path).map_err(|e| self.io(e))?;
        file.set_len(length).map_err(|e| self.io(e))?;
        self.file = Some(file);
        (self.started, self.earlier_seconds) = (Instant::now(), seconds);
        let text = format!(
            "run '{}' resumed from its checkpoint at t = {} ({} increments): {} free dofs, {} in the factor",
            summary.case, summary.final_time, summary.increments, summary.n_free_dofs, summary.factor_nnz
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

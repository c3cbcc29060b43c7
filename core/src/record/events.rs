//! `events.csv`: one row per interface event, flushed as it happens.

use super::{CommittedIncrement, InterfaceEvent, Observer, ObserverState, RunSummary};
use crate::error::Result;
use crate::model::Model;
use crate::output::HistoryWriter;
use std::path::Path;

pub struct EventsRecorder {
    writer: HistoryWriter,
}

impl EventsRecorder {
    pub fn new(path: &Path) -> Self {
        let columns = [
            "time",
            "approach",
            "interface",
            "event",
            "n_contact_before",
            "n_contact_after",
            "force_before",
            "force_after",
            "cuts_before",
        ];
        Self { writer: HistoryWriter::new(path, columns.iter().map(|s| s.to_string()).collect()) }
    }
}

impl Observer for EventsRecorder {
    fn started(&mut self, _model: &Model, _summary: &RunSummary) -> Result<()> {
        self.writer.start()
    }

    fn saved_state(&mut self) -> Result<Option<ObserverState>> {
        self.writer.saved_state().map(Some)
    }

    fn resumed(&mut self, _model: &Model, _summary: &RunSummary, saved: &[ObserverState]) -> Result<()> {
        self.writer.resume(saved)
    }

    fn committed(&mut self, _model: &Model, _increment: &CommittedIncrement) -> Result<()> {
        Ok(())
    }

    fn event(&mut self, e: &InterfaceEvent) -> Result<()> {
        self.writer.append_fields(&[
            format!("{:.10e}", e.time),
            format!("{:.10e}", e.approach),
            e.interface.clone(),
            e.kind.to_string(),
            format!("{}", e.n_contact_before),
            format!("{}", e.n_contact_after),
            format!("{:.10e}", e.force_before),
            format!("{:.10e}", e.force_after),
            format!("{}", e.cuts_before),
        ])
    }
}

//! `events.csv`: one row per interface event, flushed as it happens.

use super::{CommittedIncrement, InterfaceEvent, Observer};
use crate::error::Result;
use crate::model::Model;
use crate::output::HistoryWriter;
use std::path::Path;

pub struct EventsRecorder {
    writer: HistoryWriter,
}

impl EventsRecorder {
    pub fn create(path: &Path) -> Result<Self> {
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
        Ok(Self { writer: HistoryWriter::create(path, columns.iter().map(|s| s.to_string()).collect())? })
    }
}

impl Observer for EventsRecorder {
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

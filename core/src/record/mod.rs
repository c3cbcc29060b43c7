//! Recording as observers of committed increments. The step driver
//! ([`crate::path::driver`]) notifies every [`Observer`] of the initial state, of each
//! committed increment, of interface events, of progress messages and of the end of the run;
//! each output (history.csv, events.csv, messages.log, the VTK series, summary.json, a progress
//! bar, plots) is one small observer. A new output is a new observer, not an edit of the loop.

pub mod cycles;
mod events;
mod history;
pub mod interface_tracker;
mod message_log;
pub mod plastic_drawing;
pub mod summary;
mod vtk_series;

pub use cycles::CyclesWriter;
pub use events::EventsRecorder;
pub use history::HistoryRecorder;
pub use interface_tracker::{InterfaceEvent, InterfaceTracker};
pub use message_log::MessageLog;
pub use summary::{CycleSummary, InterfaceSummary, ResistanceAtForce, RunStatus, RunSummary, SnapSolve, SummaryWriter};
pub use vtk_series::VtkRecorder;

use crate::error::Result;
use crate::model::Model;

/// A committed increment, as observers see it (the model holds the committed state).
#[derive(Debug, Clone)]
pub struct CommittedIncrement {
    /// Step number (1-based; 0 for the initial state).
    pub step: usize,
    /// Increments committed so far in the run (0 for the initial state).
    pub increment: usize,
    /// Newton iterations this increment took.
    pub iterations: usize,
    /// Whether the step's output schedule asks for a field frame (VTK) now.
    pub frame_due: bool,
    /// Progress: the pseudo-time reached as a fraction of the run's end time.
    pub fraction_done: f64,
    /// A one-line description of the increment for progress displays.
    pub description: String,
    /// The continuum's plastic dissipation at this state ([`Model::dissipation`]), integrated
    /// once per commit for every observer.
    pub plastic_dissipation: f64,
    /// The energy the snaps so far dissipated besides plastic flow and the laws' own
    /// hysteresis: -int r.du along each snap's path at its fixed load (a damped flow's drag,
    /// int v.(M v) dtau; a descent's fall of potential energy). A quasi-static path has no
    /// other place for the energy a snap releases; an inertial snap would turn it into motion,
    /// waves and heat. ABAQUS reports the like for its stabilization as ALLSD.
    pub snap_dissipation: f64,
}

/// Something that records the run.
pub trait Observer {
    /// The run starts; `summary` has status "running" and the model's sizes.
    fn started(&mut self, _model: &Model, _summary: &RunSummary) -> Result<()> {
        Ok(())
    }
    /// A committed state: the initial one (step 0) and every converged increment.
    fn committed(&mut self, model: &Model, increment: &CommittedIncrement) -> Result<()>;
    /// An interface event (contact gained or lost, a jump, a limit point, a warning).
    fn event(&mut self, _event: &InterfaceEvent) -> Result<()> {
        Ok(())
    }
    /// A progress message (an increment cut, an arc-length cut).
    fn message(&mut self, _text: &str) {}
    /// The run ended (completed, failed or stopped); `summary` says how.
    fn finished(&mut self, _model: &Model, _summary: &RunSummary) -> Result<()> {
        Ok(())
    }
    /// What this observer needs to go on from the committed state it has recorded, for a
    /// checkpoint (None: nothing, it keeps no record between commits).
    fn saved_state(&mut self) -> Result<Option<ObserverState>> {
        Ok(None)
    }
    /// The run goes on from a checkpoint (instead of [`Self::started`]): `saved` holds what
    /// every observer of the checkpointed run saved ([`Self::saved_state`]), `summary` the run
    /// so far. An observer with a record picks its own by name and cuts its output back to the
    /// checkpoint, so what the interrupted run wrote after it is replaced; by default it starts
    /// afresh.
    fn resumed(&mut self, model: &Model, summary: &RunSummary, _saved: &[ObserverState]) -> Result<()> {
        self.started(model, summary)
    }
}

/// An observer's record in a checkpoint: its name and what it saved (JSON).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ObserverState {
    pub name: String,
    pub data: String,
}

impl ObserverState {
    /// The record named `name` in `saved`, decoded; Err when it is missing or does not decode
    /// (a checkpoint written with other output settings).
    pub fn find<T: serde::de::DeserializeOwned>(saved: &[ObserverState], name: &str) -> Result<T> {
        let missing = || {
            crate::error::CoreError::Invalid(format!(
                "the checkpoint has no record of the {name} output (was it written with other output settings?)"
            ))
        };
        let record = saved.iter().find(|s| s.name == name).ok_or_else(missing)?;
        serde_json::from_str(&record.data).map_err(|e| {
            crate::error::CoreError::Invalid(format!("the checkpoint's record of the {name} output is unreadable: {e}"))
        })
    }

    /// `data` as this observer's record named `name`.
    pub fn new<T: serde::Serialize>(name: &str, data: &T) -> Self {
        Self { name: name.into(), data: serde_json::to_string(data).expect("an observer's record serializes") }
    }
}

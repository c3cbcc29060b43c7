//! Checkpoints of a run ([`crate::checkpoint`] holds the file format): what the driver writes,
//! when, and how a run takes a checkpoint up again ([`super::resume_steps`]).
//!
//! When: at the first commit at least [`crate::checkpoint::CheckpointPlan::interval`] after the last checkpoint,
//! between increments (no crossing under way, no cut since the commit), and when the run fails
//! or is stopped, from its last committed increment. A damped-flow snap first writes one of
//! the commit it starts from (a failed flow leaves the model past that commit, and the
//! checkpoint written then stays the one to resume); inside it, at the first accepted flow
//! step at least the interval after the last checkpoint, and when the run is stopped there:
//! the checkpoint then also holds the snap under way ([`super::snapping`]). A completed run
//! removes its checkpoint.
//!
//! What: everything the rest of the run depends on: the model's committed state
//! ([`crate::model::ModelState`]); the driver's (time, step, the load control's increment and
//! predictor, the crawl and snap counters, the interfaces' records, the summary so far); and
//! each observer's record ([`crate::record::Observer::saved_state`]: how far its files had
//! got); and the solvers' ([`crate::linear_solver::LinearSolver::saved_factor`]: the matrix
//! of the factor held, which the resumed run factorizes again, and
//! [`crate::nonlinear::NonlinearSolver::saved_state`]: which factor the quasi-Newton solver
//! reuses, how its last increments went). Only what is rebuilt the same way is left out: the
//! pattern and the symbolic factorization, and the damped flow's drag matrix. Writing a
//! checkpoint changes nothing in the run, and with a solver whose decisions do not depend on
//! measured times (and the same number of threads) a run stopped at a checkpoint and resumed
//! writes the same history.csv as one that ran through without checkpoints, to the last digit.
//!
//! A run that fails or is stopped in the middle of a crossing resumes under load control from
//! the crossing's last commit; a failed run's checkpoint resumes with the increment size and the
//! snap counter of a fresh step, as a run resumed with other solver settings needs.

use super::{Driver, Ending, PathState, SnapInProgress};
use crate::checkpoint::{self, ModelState};
use crate::error::{CoreError, Result};
use crate::linear_solver::SavedFactor;
use crate::path::load_control::LoadControlState;
use crate::path::tangent_choice::TangentSwitch;
use crate::record::{InterfaceTracker, ObserverState, RunSummary};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;

/// A run's committed state as a checkpoint file holds it.
#[derive(Serialize, Deserialize)]
pub struct Checkpoint {
    /// What identifies the problem ([`crate::checkpoint::CheckpointPlan::fingerprint`]).
    pub fingerprint: String,
    model: ModelState,
    driver: DriverState,
    observers: Vec<ObserverState>,
}

impl Checkpoint {
    /// Reads the checkpoint at `path`.
    pub fn read(path: &Path) -> Result<Self> {
        checkpoint::read(path)
    }
}

/// The driver's part of a checkpoint: its state that carries from one increment to the next.
#[derive(Serialize, Deserialize)]
struct DriverState {
    path: PathState,
    load: LoadControlState,
    tangent: TangentSwitch,
    /// Whether the model's materials gave their stabilized tangent.
    stabilized: bool,
    tracker: InterfaceTracker,
    /// The summary so far, its totals (wall seconds, precision fallbacks) counted to the
    /// checkpoint.
    summary: RunSummary,
    /// The snap the checkpoint was taken in, with its damped flow's state (see
    /// [`super::snapping`]).
    snap: Option<SnapInProgress>,
    /// The linear solver's factor and the nonlinear solver's state, so that the resumed run's
    /// solvers decide as the saving run's went on to.
    linear: Option<SavedFactor>,
    nonlinear: Vec<u8>,
}

/// Totals of the parts of a run before it was resumed that the summary takes from counters
/// outside it (this process's wall clock, the linear solver's fallbacks).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct EarlierParts {
    wall_seconds: f64,
    precision_fallbacks: usize,
}

impl Driver<'_> {
    /// Sets the summary's totals that come from counters outside it: the final time, wall
    /// seconds, the threads of the current pool, precision fallbacks and tangent switches,
    /// with the earlier parts of the run.
    pub(super) fn count_totals(&mut self) {
        let s = &mut self.summary;
        s.final_time = self.path.t;
        s.wall_seconds = self.earlier.wall_seconds + self.wall.elapsed().as_secs_f64();
        s.threads = rayon::current_num_threads();
        s.double_precision_refactorizations = self.earlier.precision_fallbacks + self.linear.precision_fallbacks();
        s.tangent_switches = self.tangent.switches;
    }

    /// Writes a checkpoint if the plan asks for one now (see the module documentation).
    pub(super) fn checkpoint_if_due(&mut self) -> Result<()> {
        let Some(plan) = &self.plan.checkpoint else { return Ok(()) };
        let (when, increments) = self.last_checkpoint;
        let due = self.summary.increments > increments
            && self.crossing.is_none()
            && self.path.policy.cuts_since_commit() == 0
            && when.elapsed() >= plan.interval;
        if due { self.write_checkpoint(None) } else { Ok(()) }
    }

    /// Writes the checkpoint of the committed state (the run ends with `ending`, if given).
    /// Nothing is written before the first commit unless a snap is under way (else the run
    /// would start over from the same state), nor where a failed damped flow left the model
    /// past the last recorded increment (the checkpoint the flow wrote at its start stays the
    /// one to resume).
    pub(super) fn write_checkpoint(&mut self, ending: Option<&Ending>) -> Result<()> {
        let Some(plan) = &self.plan.checkpoint else { return Ok(()) };
        let snap_under_way = self.snap_in_progress.as_ref().is_some_and(|s| s.flow.is_some());
        if (self.summary.increments == 0 && !snap_under_way) || self.model_ahead_of_record {
            return Ok(());
        }
        let mut observers = Vec::new();
        for o in self.observers.iter_mut() {
            observers.extend(o.saved_state()?);
        }
        self.count_totals();
        let mut driver = self.driver_state();
        if matches!(ending, Some(Ending::Failed(_))) {
            // resumed with other settings: go on as from a step's start
            driver.load.restart_at(self.plan.steps[self.path.step].incrementation.initial);
            driver.path.policy = driver.path.policy.for_failed_run();
        }
        let record =
            Checkpoint { fingerprint: plan.fingerprint.clone(), model: self.model.saved_state(), driver, observers };
        checkpoint::write(&plan.path, &record)?;
        self.last_checkpoint = (Instant::now(), self.summary.increments);
        let inside = match &self.snap_in_progress {
            Some(SnapInProgress { target, flow: Some(flow), .. }) => {
                format!(", inside the snap to t = {target:.6} after {} damped flow steps", flow.report.steps)
            }
            _ => String::new(),
        };
        let text = format!(
            "checkpoint at t = {:.6} ({} increments{inside}) written to '{}'",
            self.path.t,
            self.summary.increments,
            plan.path.display()
        );
        self.observers.iter_mut().for_each(|o| o.message(&text));
        Ok(())
    }

    /// Removes the checkpoint of a run that completed (nothing is left to resume).
    pub(super) fn remove_checkpoint(&self) -> Result<()> {
        let Some(plan) = &self.plan.checkpoint else { return Ok(()) };
        match std::fs::remove_file(&plan.path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                Err(CoreError::Write { path: plan.path.clone(), source: e })
            }
            _ => Ok(()),
        }
    }

    fn driver_state(&self) -> DriverState {
        DriverState {
            path: self.path.clone(),
            load: self.load.saved(),
            tangent: self.tangent.clone(),
            stabilized: self.model.tangent_stabilized(),
            tracker: self.tracker.clone(),
            summary: self.summary.clone(),
            snap: self.snap_in_progress.clone(),
            linear: self.linear.saved_factor(),
            nonlinear: self.nonlinear.saved_state(),
        }
    }

    /// Takes up `checkpoint`: the model's state, the driver's, and the observers' (each told
    /// with [`crate::record::Observer::resumed`]). Returns the step to go on with and its start.
    pub(super) fn restore(&mut self, checkpoint: Checkpoint) -> Result<(usize, f64)> {
        let Checkpoint { model, driver: d, observers, .. } = checkpoint;
        let file = self.plan.checkpoint.as_ref().map(|p| p.path.clone()).unwrap_or_default();
        let (step, step_start) = (d.path.step, d.path.step_start);
        if step >= self.plan.steps.len() {
            let message = format!("is at step {}, the run has {}", step + 1, self.plan.steps.len());
            return Err(CoreError::Checkpoint { path: file, message });
        }
        self.model.restore_state(&model).map_err(|message| CoreError::Checkpoint { path: file.clone(), message })?;
        if let Some(factor) = &d.linear {
            self.linear.restore_factor(self.model.pattern(), factor).map_err(|e| CoreError::Checkpoint {
                path: file,
                message: format!("its linear solver's factor could not be remade: {e}"),
            })?;
        }
        self.nonlinear.restore_state(&d.nonlinear);
        self.load.start_step(&self.plan.steps[step].incrementation);
        self.load.restore(d.load);
        self.path = d.path;
        self.tangent = d.tangent.resumed(self.plan.tangent, self.model, d.stabilized);
        self.tracker = d.tracker;
        self.earlier = EarlierParts {
            wall_seconds: d.summary.wall_seconds,
            precision_fallbacks: d.summary.double_precision_refactorizations,
        };
        self.summary = resumed_summary(d.summary, &self.summary);
        self.path.policy.unbalanced_start(None);
        self.snap_in_progress = d.snap;
        self.last_checkpoint = (Instant::now(), self.summary.increments);
        for o in self.observers.iter_mut() {
            o.resumed(self.model, &self.summary, &observers)?;
        }
        Ok((step, step_start))
    }
}

/// The summary of a resumed run: the checkpointed one's counts, with what describes this
/// process's setup (sizes of the factor, the snap method, the output folder) from `fresh`.
fn resumed_summary(saved: RunSummary, fresh: &RunSummary) -> RunSummary {
    RunSummary {
        status: fresh.status,
        message: None,
        factor_nnz: fresh.factor_nnz,
        snap_method: fresh.snap_method,
        output_directory: fresh.output_directory.clone(),
        ..saved
    }
}

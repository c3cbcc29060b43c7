//! Snaps: where neither control can go on, the driver moves the model at a fixed load to the
//! stable state the displacement-controlled system snaps to (see the driver's module
//! documentation), by descent ([`settle`]) or along the damped flow ([`follow_damped_flow`]),
//! or by descent and, where the descent finds no stable state, along the flow.
//!
//! A damped flow may take thousands of steps (a 3D sphere jumping into contact under strong
//! adhesion: hours). It is paused between its steps when a checkpoint is due and when the run
//! is interrupted (Ctrl-C, [`super::RunPlan::interrupt`]) or asked to stop there
//! ([`super::RunPlan::stop_after_flow_steps`]): the checkpoint then holds the snap under way
//! (`SnapInProgress`: its target, its reason, and the flow's [`FlowState`]) beside the
//! model's committed state, which is the flow's last committed step. A run resumed from it
//! goes on with the same flow (`Driver::resume_snap`), as if it had not stopped. A flow commits
//! its steps into the model, past the run's last recorded increment, so a run that fails along
//! it cannot checkpoint that increment any more: a fresh flow first writes a checkpoint of the
//! commit it starts from (unless the last one is of it), and a run resumed from that redoes
//! the snap from its start.

use super::{Driver, Flow, SnapMethod, Via};
use crate::error::{CoreError, Result};
use crate::nonlinear::damped_flow::follow_damped_flow;
use crate::nonlinear::damped_flow::{
    FlowControl, FlowDamping, FlowEnd, FlowReport, FlowSettings, FlowStart, FlowState,
};
use crate::nonlinear::settle::{Settled, settle};
use crate::nonlinear::{IncrementFailure, IncrementReport};
use crate::path::StepWindow;
use crate::problem::NonlinearProblem;
use crate::record::summary::{SnapSolve, Units};
use serde::{Deserialize, Serialize};
use std::sync::atomic::Ordering;
use std::time::Instant;

/// A damped-flow snap tells the observers how far it is every this many steps.
const FLOW_PROGRESS_EVERY: usize = 20;

/// A snap under way: what it was asked for, and where its damped flow paused (None: it starts
/// afresh from the committed state).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct SnapInProgress {
    /// The step it belongs to.
    step: usize,
    /// Why the path snaps (said again if the snap fails).
    reason: String,
    /// The time it snaps at.
    pub(super) target: f64,
    /// The increment it was asked to go ahead by (a snap past the minimum increment counts as
    /// progress).
    dt: f64,
    /// A snap past a crawl: the path counts as still crawling after it.
    crawl: bool,
    /// Already retried on the other tangent after a failure.
    retried: bool,
    /// The damped flow where it paused.
    pub(super) flow: Option<FlowState>,
}

/// How solving a snap ended.
enum Snapped {
    /// On a stable state (the model's trial state): the costs, how it went, and the energy it
    /// dissipated on the way besides plastic flow (a flow's drag, a descent's fall of energy).
    Settled(IncrementReport, String, f64),
    /// No stable state found; `damped`: a damped flow committed some of its steps first.
    Failed { failure: IncrementFailure, damped: bool },
    /// The run was interrupted, or asked to stop, while a damped flow was under way: the snap
    /// stays in progress (with the flow's state) for the checkpoint.
    Interrupted,
}

impl Driver<'_> {
    /// Settles at the target `dt` past the committed time (clipped to the step and the next
    /// breakpoint) and commits it, or stops with `reason` and why settling failed (the policy
    /// decided the snap: [`crate::path::policy::PathPolicy`]). Errors are those of committing
    /// (writing the outputs and checkpoints).
    pub(super) fn snap_over(&mut self, si: usize, reason: &str, dt: f64, crawl: bool) -> Result<Flow> {
        let step = &self.plan.steps[si];
        self.crossing = None;
        self.model.rollback();
        self.load.set_increment(dt);
        let text = format!("{}: {reason}; snapping from t = {:.6}", step.name, self.path.t);
        self.observers.iter_mut().for_each(|o| o.message(&text));
        let window = StepWindow {
            t: self.path.t,
            step_start: self.path.t,
            step_end: step.end_time,
            t_end: self.t_end,
            breakpoints: &self.breakpoints,
        };
        let target = self.load.target(&window);
        self.model.set_time(target);
        self.snap_in_progress = Some(SnapInProgress {
            step: si,
            reason: reason.to_string(),
            target,
            dt,
            crawl,
            retried: false,
            flow: None,
        });
        self.settle_snap()
    }

    /// Goes on with the snap a resumed checkpoint holds, from its damped flow's state.
    pub(super) fn resume_snap(&mut self) -> Result<Flow> {
        let Some(snap) = &self.snap_in_progress else { return Ok(Flow::Continue) };
        let steps = snap.flow.as_ref().map_or(0, |f| f.report.steps);
        let text = format!(
            "{}: the snap at t = {:.6} goes on from damped flow step {steps}",
            self.plan.steps[snap.step].name, snap.target
        );
        self.model.set_time(snap.target);
        self.observers.iter_mut().for_each(|o| o.message(&text));
        self.settle_snap()
    }

    /// Solves the snap in progress (retried once on the other tangent if it fails, and along the
    /// damped flow where a descent found no stable state and the plan allows it,
    /// [`SnapMethod::SettleOrFlow`]) and commits the state it reaches, or stops with the snap's
    /// reason and why settling failed.
    fn settle_snap(&mut self) -> Result<Flow> {
        let Some(snap) = &self.snap_in_progress else { return Ok(Flow::Continue) };
        let (si, target, retried) = (snap.step, snap.target, snap.retried);
        let name = self.plan.steps[si].name.clone();
        let mut solved = self.solve_snap(&name, target)?;
        if let Snapped::Failed { failure, .. } = &solved
            && !retried
            && let Some(what) = {
                // a damped flow goes on from its last committed step
                self.model.rollback();
                self.tangent.after_failed_snap(self.model, failure)
            }
        {
            let text = format!("{name}: snapping at t = {target:.6}: {what} after: {failure}");
            self.observers.iter_mut().for_each(|o| o.message(&text));
            if let Some(snap) = self.snap_in_progress.as_mut() {
                (snap.retried, snap.flow) = (true, None);
            }
            // the rollback took the model back to its last commit's time (a flow that committed
            // steps: the target already)
            self.model.set_time(target);
            solved = self.solve_snap(&name, target)?;
        }
        if let (Snapped::Failed { failure, damped: false }, SnapMethod::SettleOrFlow(settings)) =
            (&solved, self.plan.snap)
        {
            let text = format!(
                "{name}: snapping at t = {target:.6}: the descent found no stable state ({failure}); following the damped flow instead"
            );
            self.observers.iter_mut().for_each(|o| o.message(&text));
            // the descent commits nothing: the rollback took the model back to its last
            // commit's time
            self.model.rollback();
            self.model.set_time(target);
            self.summary.snap_method = SnapSolve::SettleThenFlow;
            solved = self.solve_snap_by(&name, target, Some(settings))?;
        }
        if matches!(solved, Snapped::Interrupted) {
            return Ok(Flow::Interrupted);
        }
        let Some(snap) = self.snap_in_progress.take() else { return Ok(Flow::Continue) };
        let text = match &solved {
            Snapped::Settled(_, how, released) => {
                let energy = Units::of(&self.plan.units.0, &self.plan.units.1).energy;
                let energy = if energy.is_empty() { String::new() } else { format!(" {energy}") };
                format!("{name}: snapped at t = {target:.6} ({how}; dissipated {released:.6e}{energy})")
            }
            _ => format!("{name}: no stable state found at t = {target:.6}"),
        };
        self.observers.iter_mut().for_each(|o| o.message(&text));
        let flow = match solved {
            Snapped::Settled(report, _, released) => {
                self.path.snap_dissipation += released;
                self.path.policy.snapped(snap.dt, &self.plan.steps[si].incrementation);
                self.summary.snaps += 1;
                self.converged(si, report, Via::Settling)?
            }
            Snapped::Failed { failure, damped } => self.snap_failed(&snap.reason, target, &failure, damped),
            Snapped::Interrupted => Flow::Interrupted,
        };
        if snap.crawl {
            let at_breakpoint = self.at_breakpoint(self.path.t);
            self.path.policy.after_crawl_snap(matches!(flow, Flow::Continue), at_breakpoint);
        }
        Ok(flow)
    }

    /// A snap that found no stable state: the model goes back to its last committed state and
    /// the run stops with the snap's `reason` and the `failure`.
    fn snap_failed(&mut self, reason: &str, target: f64, failure: &IncrementFailure, damped: bool) -> Flow {
        self.model.rollback();
        // the flow's committed steps are the model's, not the record's
        self.model_ahead_of_record |= damped;
        // a law that fails the same way while settling is said once
        let same = matches!(failure, IncrementFailure::Error(CoreError::LawFailure { message, .. }) if reason.contains(message.as_str()));
        let why = match (same, damped) {
            (true, _) => "failed the same way".to_string(),
            (false, false) => format!("failed: {failure}"),
            (false, true) => format!(
                "failed along the damped flow ({failure}; the model is left at the flow's last committed step, which is not written)"
            ),
        };
        Flow::Stop(format!("{reason}; settling on a stable state at t = {target:.6} {why}"))
    }

    /// Solves the snap at `target` from the committed state (or from where its damped flow
    /// paused) by the plan's [`SnapMethod`]. The wall time of a failed snap, and of the solves a
    /// successful flow did not converge, is counted as discarded. Errors are those of writing
    /// the checkpoints a long flow pauses for.
    fn solve_snap(&mut self, step_name: &str, target: f64) -> Result<Snapped> {
        self.solve_snap_by(step_name, target, None)
    }

    /// [`Self::solve_snap`] along the damped flow with `flow` when given (a descent that
    /// failed), by the plan's method otherwise.
    fn solve_snap_by(&mut self, step_name: &str, target: f64, flow: Option<FlowSettings>) -> Result<Snapped> {
        let started = Instant::now();
        let (solved, failed_solve_seconds) = match flow {
            Some(settings) => self.snap_by_flow(step_name, target, &settings)?,
            None => self.snap_by_plan(step_name, target)?,
        };
        self.summary.discarded_attempt_seconds += match &solved {
            Snapped::Settled(..) => failed_solve_seconds,
            Snapped::Failed { .. } => started.elapsed().as_secs_f64(),
            Snapped::Interrupted => 0.0,
        };
        Ok(solved)
    }

    /// [`Self::solve_snap`] without the accounting: also the seconds of the flow's solves that
    /// did not converge.
    fn snap_by_plan(&mut self, step_name: &str, target: f64) -> Result<(Snapped, f64)> {
        // a damped flow that paused (for a checkpoint) goes on, also one a failed descent began
        let flow_under_way = self.snap_in_progress.as_ref().is_some_and(|snap| snap.flow.is_some());
        match self.plan.snap {
            SnapMethod::DampedFlow(settings) => self.snap_by_flow(step_name, target, &settings),
            SnapMethod::SettleOrFlow(settings) if flow_under_way => self.snap_by_flow(step_name, target, &settings),
            SnapMethod::Settle | SnapMethod::SettleOrFlow(_) => Ok((self.snap_by_descent(), 0.0)),
        }
    }

    /// The snap by descent ([`settle`]).
    fn snap_by_descent(&mut self) -> Snapped {
        let scales = self.scales();
        let settings = self.nonlinear.settings().clone();
        settled_by_descent(settle(self.model, &mut *self.linear, &settings, scales))
    }

    /// The snap along the damped flow with `settings` (by descent for a problem without a mass):
    /// how it ended, and the seconds of the flow's solves that did not converge.
    fn snap_by_flow(&mut self, step_name: &str, target: f64, settings: &FlowSettings) -> Result<(Snapped, f64)> {
        if self.mass.is_none() {
            self.mass = match settings.damping {
                FlowDamping::Mass => NonlinearProblem::mass(&*self.model),
                FlowDamping::Stiffness => match self.model.initial_stiffness_matrix() {
                    Ok(stiffness) => Some(stiffness),
                    Err(e) => return Ok((Snapped::Failed { failure: IncrementFailure::Error(e), damped: false }, 0.0)),
                },
            };
        }
        // a problem without a mass settles by descent
        let Some(mass) = self.mass.take() else { return Ok((self.snap_by_descent(), 0.0)) };
        let flowed = self.follow_flow(step_name, target, &mass, settings);
        self.mass = Some(mass);
        let f = match flowed? {
            Ok(Some(f)) => f,
            Ok(None) => return Ok((Snapped::Interrupted, 0.0)),
            Err(failure) => return Ok((Snapped::Failed { failure, damped: true }, 0.0)),
        };
        let mut text = format!("{} damped flow steps, {} redone", f.steps, f.rejected);
        let released = f.drag_dissipation;
        if f.kinks > 0 {
            text += &format!(", {} across kinks", f.kinks);
        }
        if let Some(ratio) = f.stalled_at_residual_ratio {
            text += &format!("; its steps stalled near rest, ended at {ratio:.1} times the residual test");
            self.path.stalled_snaps.0 += 1;
            self.path.stalled_snaps.1 = self.path.stalled_snaps.1.max(ratio);
        }
        let failed_seconds = f.failed_solve_seconds;
        Ok((Snapped::Settled(f.costs, text, released), failed_seconds))
    }

    /// Follows the snap's damped flow on the drag matrix `mass` (from where it paused, if it
    /// did), writing a checkpoint whenever one is due between its steps: Some(report) when it
    /// settled, None when the run is interrupted or asked to stop (the flow's state is then the
    /// snap's), or why it failed. Errors are those of writing checkpoints.
    fn follow_flow(
        &mut self,
        step_name: &str,
        target: f64,
        mass: &[f64],
        settings: &FlowSettings,
    ) -> Result<std::result::Result<Option<FlowReport>, IncrementFailure>> {
        let mut start = match self.snap_in_progress.as_mut().and_then(|s| s.flow.take()) {
            Some(state) => FlowStart::Resumed(Box::new(state)),
            None => {
                // the flow commits its steps into the model: a run that fails along it can
                // only resume from a checkpoint of the commit it starts from
                if self.plan.checkpoint.is_some() && self.summary.increments > self.last_checkpoint.1 {
                    self.write_checkpoint(None)?;
                }
                FlowStart::Fresh(self.scales())
            }
        };
        loop {
            let interrupt = self.plan.interrupt.clone();
            let checkpoint_due_at = self.plan.checkpoint.as_ref().map(|p| self.last_checkpoint.0 + p.interval);
            let stop_after = self.plan.stop_after_flow_steps;
            let steps_here = &mut self.flow_steps_here;
            let observers = &mut *self.observers;
            let mut stopping = false;
            let mut control = |f: &FlowReport| {
                *steps_here += 1;
                if f.steps.is_multiple_of(FLOW_PROGRESS_EVERY) {
                    let text = format!("{step_name}: snapping at t = {target:.6}, {} damped flow steps", f.steps);
                    observers.iter_mut().for_each(|o| o.message(&text));
                }
                stopping = interrupt.as_ref().is_some_and(|flag| flag.load(Ordering::Relaxed))
                    || stop_after.is_some_and(|n| *steps_here >= n);
                let due = checkpoint_due_at.is_some_and(|at| Instant::now() >= at);
                if stopping || due { FlowControl::Pause } else { FlowControl::Continue }
            };
            let flowed = follow_damped_flow(
                self.model,
                mass,
                &mut *self.linear,
                &mut *self.nonlinear,
                settings,
                start,
                &mut control,
            );
            let state = match flowed {
                Ok(FlowEnd::Settled(report)) => return Ok(Ok(Some(report))),
                Ok(FlowEnd::Paused(state)) => state,
                Err(failure) => return Ok(Err(failure)),
            };
            let Some(snap) = self.snap_in_progress.as_mut() else { return Ok(Ok(None)) };
            if stopping {
                snap.flow = Some(*state);
                return Ok(Ok(None));
            }
            // the checkpoint holds the flow's state; the flow goes on from it here too
            snap.flow = Some((*state).clone());
            self.write_checkpoint(None)?;
            if let Some(snap) = self.snap_in_progress.as_mut() {
                snap.flow = None;
            }
            start = FlowStart::Resumed(state);
        }
    }
}

/// A snap by descent as a [`Snapped`].
fn settled_by_descent(settled: std::result::Result<Settled, IncrementFailure>) -> Snapped {
    match settled {
        Ok(Settled { report, released_energy }) => {
            let text = format!("{} descent steps", report.iterations);
            Snapped::Settled(report, text, released_energy)
        }
        Err(failure) => Snapped::Failed { failure, damped: false },
    }
}

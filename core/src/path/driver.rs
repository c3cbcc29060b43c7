//! The step driver: runs the steps of an analysis with a [`LoadControl`] that hands over to a
//! [`Crossing`] at limit points (when continuation is on: an
//! [`super::arc_length_control::ArcLengthControl`] or a
//! [`super::dissipation_control::DissipationControl`]), commits each converged increment and notifies the observers. It
//! does no output of its own.
//!
//! What the driver does after each attempt (cut, hand over to a crossing, snap, stop) is the
//! [`PathPolicy`]'s decision: its rules, each named and documented in [`super::policy`], read
//! the facts the driver gathers. The driver carries the decisions out: it rolls back, cuts the
//! control, starts the crossing, or moves the model just past the committed time to the stable
//! state the displacement-controlled system snaps to ([`SnapMethod`]: by descent,
//! [`crate::nonlinear::settle`], or along the body's overdamped motion,
//! [`crate::nonlinear::damped_flow`], whose steps are committed so that plastic flow follows
//! the snap's path; or by descent, with the flow where the descent finds no stable state),
//! commits the snapped state as a jump, and load control goes on from it. The crossing hands
//! back once t moves forward past the target that failed, or when it cannot go on inside its
//! step window.
//!
//! Tangents: a failed attempt may switch the model between the materials' consistent and
//! stabilized tangents for the attempts after it, and a failed snap is retried on the other
//! tangent before the run stops ([`TangentSwitch`], `solver.tangent`).
//!
//! Checkpoints: the committed state is written between increments as the plan asks (and
//! between the steps of a damped-flow snap, with the snap under way: [`snapping`]), and when
//! the run fails or is stopped; [`resume_steps`] goes on from one in another process
//! ([`checkpointing`]).

use super::load_control::LoadControl;
use super::policy::{CRAWL_FRACTION, Decision, FailureFacts, JumpFacts, PathPolicy, jumped};
use super::tangent_choice::TangentSwitch;
use super::{Attempt, AttemptFailure, Crossing, PathControl, Solvers, StepWindow};
use crate::error::{CoreError, Result};
use crate::linear_solver::LinearSolver;
use crate::model::Model;
use crate::nonlinear::arc_length::PreviousIncrement;
use crate::nonlinear::{IncrementFailure, IncrementReport, NonlinearSolver, ReferenceScales};
use crate::problem::NonlinearProblem;
use crate::record::interface_tracker::CommitContext;
use crate::record::summary::{RunStatus, SnapSolve, Units};
use crate::record::{CommittedIncrement, InterfaceTracker, Observer, RunSummary};
use crate::vector::{dot, norm};
use std::collections::BTreeMap;
use std::sync::atomic::Ordering;
use std::time::Instant;

pub mod checkpointing;
mod plan;
pub mod snapping;
pub use checkpointing::Checkpoint;
use checkpointing::EarlierParts;
pub use plan::{Continuation, ContinuationMethod, RunPlan, SnapMethod};
use snapping::SnapInProgress;

/// How a converged increment was solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Via {
    LoadControl,
    Crossing,
    /// Pseudo-transient continuation: a snap to a stable state.
    Settling,
}

/// Why a run ended before its last step did.
enum Ending {
    Failed(String),
    Interrupted,
}

/// Runs every step of `plan` on `model` from its initial state. A run that cannot go on is not
/// an error: the summary says "failed" and why (errors are I/O and broken models).
pub fn run_steps(
    model: &mut Model,
    plan: &RunPlan,
    linear: &mut dyn LinearSolver,
    nonlinear: &mut dyn NonlinearSolver,
    observers: &mut [Box<dyn Observer>],
) -> Result<RunSummary> {
    let mut driver = Driver::new(model, plan, linear, nonlinear, observers);
    for o in driver.observers.iter_mut() {
        o.started(driver.model, &driver.summary)?;
    }
    driver.initial_state()?;
    driver.run_from(0, 0.0, false)
}

/// Goes on with a run from `checkpoint` (written by a run of the same model, see
/// [`Checkpoint`]): the model, the driver and the observers take up the checkpointed state,
/// and the steps run on from there. The plan's solver settings may differ from the
/// checkpointed run's; its model and steps may not (the caller compares fingerprints).
pub fn resume_steps(
    model: &mut Model,
    plan: &RunPlan,
    linear: &mut dyn LinearSolver,
    nonlinear: &mut dyn NonlinearSolver,
    observers: &mut [Box<dyn Observer>],
    checkpoint: Checkpoint,
) -> Result<RunSummary> {
    let mut driver = Driver::new(model, plan, linear, nonlinear, observers);
    let (step, step_start) = driver.restore(checkpoint)?;
    driver.run_from(step, step_start, true)
}

impl<'a> Driver<'a> {
    fn new(
        model: &'a mut Model,
        plan: &'a RunPlan,
        linear: &'a mut dyn LinearSolver,
        nonlinear: &'a mut dyn NonlinearSolver,
        observers: &'a mut [Box<dyn Observer>],
    ) -> Self {
        let first = plan.steps.first().expect("a run plan has at least one step");
        let tangent = TangentSwitch::start(plan.tangent, model);
        Driver {
            tangent,
            tracker: InterfaceTracker::new(model, &plan.interfaces),
            summary: initial_summary(model, plan, linear.factor_nnz()),
            breakpoints: breakpoints(model, plan),
            path: PathState::default(),
            t_end: plan.steps.last().map_or(0.0, |s| s.end_time),
            load: LoadControl::new(&first.incrementation, plan.start_predictor),
            crossing: None,
            mass: None,
            wall: Instant::now(),
            earlier: EarlierParts::default(),
            last_checkpoint: (Instant::now(), 0),
            model_ahead_of_record: false,
            snap_in_progress: None,
            flow_steps_here: 0,
            model,
            plan,
            linear,
            nonlinear,
            observers,
        }
    }

    /// Runs the steps from step `first` (starting at `step_start`; `resumed`: the step is
    /// under way, its increment size and output count carry on, and a snap the checkpoint was
    /// taken in goes on first) to the end, then finishes.
    fn run_from(mut self, mut first: usize, mut step_start: f64, mut resumed: bool) -> Result<RunSummary> {
        let mut ending = None;
        if resumed && self.snap_in_progress.is_some() {
            match self.resume_snap()? {
                Flow::Continue => {}
                Flow::StepDone => {
                    (first, step_start, resumed) = (first + 1, self.plan.steps[first].end_time, false);
                }
                Flow::Stop(message) => ending = Some(Ending::Failed(message)),
                Flow::Interrupted => ending = Some(Ending::Interrupted),
            }
        }
        if ending.is_none() {
            for si in first..self.plan.steps.len() {
                if let Some(end) = self.run_step(si, step_start, resumed && si == first)? {
                    ending = Some(end);
                    break;
                }
                step_start = self.plan.steps[si].end_time;
                self.crossing = None;
            }
        }
        if ending.is_some() {
            self.write_checkpoint(ending.as_ref())?;
        } else {
            self.remove_checkpoint()?;
        }
        self.finish(ending)
    }
}

fn initial_summary(model: &Model, plan: &RunPlan, factor_nnz: usize) -> RunSummary {
    RunSummary {
        case: plan.name.clone(),
        units: Units::of(&plan.units.0, &plan.units.1),
        status: RunStatus::Running,
        n_nodes: model.mesh.nodes.len(),
        n_cells: model.sets.iter().map(|s| s.n_cells()).sum(),
        n_free_dofs: model.n_free(),
        nnz: model.pattern().nnz(),
        factor_nnz,
        output_directory: plan.output_directory.clone(),
        snap_method: match plan.snap {
            SnapMethod::DampedFlow(_) => SnapSolve::DampedFlow,
            SnapMethod::Settle | SnapMethod::SettleOrFlow(_) => SnapSolve::Settle,
        },
        warnings: model.contributions.iter().flat_map(|c| c.warnings()).collect(),
        ..Default::default()
    }
}

/// Amplitude breakpoints and step ends: increments land on them exactly.
fn breakpoints(model: &Model, plan: &RunPlan) -> Vec<f64> {
    model
        .prescribed()
        .iter()
        .map(|p| p.amplitude.clone())
        .chain(model.loads.iter().map(|l| l.amplitude.clone()))
        .chain(model.contributions.iter().flat_map(|c| c.amplitudes()))
        .flat_map(|a| a.breakpoints_between(0.0, f64::INFINITY).collect::<Vec<_>>())
        .chain(plan.steps.iter().map(|s| s.end_time))
        .collect()
}

/// The driver's state that carries from one increment to the next, beside the load control,
/// the tangent switch, the interfaces' records and the summary: a checkpoint holds it whole.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
struct PathState {
    /// Pseudo-time of the committed state.
    t: f64,
    /// The last converged increment (free dofs, dt), kept through cuts to start arc length.
    last_converged: Option<PreviousIncrement>,
    /// The counts and flags the path policy's rules read.
    policy: PathPolicy,
    /// Interface-law failures that cut increments, each distinct one once: (law, interface,
    /// message) -> (times, first point).
    law_failures: BTreeMap<(String, String, String), (usize, usize)>,
    /// Sum and count of the force norms of the converged increments (the Newton reference
    /// force is their mean).
    force_sum: (f64, usize),
    /// Increments since the last field frame.
    since_output: usize,
    /// The largest displacement norm committed so far (the scale of round-off in increments).
    largest_displacement: f64,
    /// Damped-flow snaps that ended where their steps stalled near rest, and the largest
    /// residual over the test they ended at (see [`crate::nonlinear::damped_flow::STALLED_REST_FACTOR`]).
    stalled_snaps: (usize, f64),
    /// The energy the snaps dissipated so far besides plastic flow (see
    /// [`CommittedIncrement::snap_dissipation`]).
    snap_dissipation: f64,
    /// The step under way and the time it started at.
    step: usize,
    step_start: f64,
}

struct Driver<'a> {
    model: &'a mut Model,
    plan: &'a RunPlan,
    linear: &'a mut dyn LinearSolver,
    nonlinear: &'a mut dyn NonlinearSolver,
    observers: &'a mut [Box<dyn Observer>],
    /// Where the path is, and what it counts (checkpointed whole).
    path: PathState,
    tracker: InterfaceTracker,
    summary: RunSummary,
    breakpoints: Vec<f64>,
    /// Pseudo-time of the end of the run.
    t_end: f64,
    load: LoadControl,
    /// A crossing in progress.
    crossing: Option<Box<dyn Crossing>>,
    /// The damped flow's drag matrix on the pattern (made at the first damped snap): the
    /// unit-density mass, or the initial stiffness ([`FlowDamping`]).
    mass: Option<Vec<f64>>,
    /// Which material tangent the solvers see, switched after failures.
    tangent: TangentSwitch,
    /// When this process started on the run.
    wall: Instant,
    /// What the parts of the run before its resumption (if any) counted outside the summary.
    earlier: EarlierParts,
    /// When the last checkpoint was written, and the increments committed then.
    last_checkpoint: (Instant, usize),
    /// Set when a damped-flow snap failed after committing some of its steps to the model:
    /// the model's committed state is then not the one the record (history, summary) ends at.
    model_ahead_of_record: bool,
    /// The snap under way (checkpointed with it: a checkpoint taken inside a long damped flow
    /// goes on with that flow).
    snap_in_progress: Option<SnapInProgress>,
    /// Damped-flow steps this process took (see [`RunPlan::stop_after_flow_steps`]).
    flow_steps_here: usize,
}

/// What to do after handling an attempt.
enum Flow {
    Continue,
    /// The step ended early (its interface separated).
    StepDone,
    /// The run cannot go on.
    Stop(String),
    /// The run was interrupted, or asked to stop, inside a snap (which stays in progress).
    Interrupted,
}

impl Driver<'_> {
    fn initial_state(&mut self) -> Result<()> {
        self.model.apply_time(0.0);
        self.model.assemble(false)?;
        let imbalance = self.start_imbalance();
        self.path.policy.unbalanced_start(imbalance);
        self.model.commit();
        let initial = CommittedIncrement {
            step: 0,
            increment: 0,
            iterations: 0,
            frame_due: true,
            fraction_done: 0.0,
            description: "initial state".into(),
            plastic_dissipation: self.model.dissipation(),
            snap_dissipation: self.path.snap_dissipation,
        };
        // the interfaces' records start from the committed initial state
        self.tracker = InterfaceTracker::new(self.model, &self.plan.interfaces);
        for o in self.observers.iter_mut() {
            o.committed(self.model, &initial)?;
        }
        Ok(())
    }

    /// Whether the plan's `stop_after_increments` stops the run now: that many increments are
    /// committed and the path is between increments (no crossing under way, no cut since the
    /// commit), where a checkpoint resumes exactly.
    fn stop_due(&self) -> bool {
        let clean = self.crossing.is_none() && self.path.policy.cuts_since_commit() == 0;
        clean && self.plan.stop_after_increments.is_some_and(|n| self.summary.increments >= n)
    }

    /// The assembled initial state's residual norm ||r(u_0, 0)|| and the solver's residual test
    /// tol_residual F, where the residual fails it.
    fn start_imbalance(&self) -> Option<(f64, f64)> {
        let settings = self.nonlinear.settings();
        let residual = norm(NonlinearProblem::residual(&*self.model));
        let force_scale = settings.force_scale(NonlinearProblem::force_norm(&*self.model), self.scales());
        let test = settings.tol_residual * force_scale;
        (!settings.residual_converged(residual, force_scale)).then_some((residual, test))
    }

    fn scales(&self) -> ReferenceScales {
        let (sum, count) = self.path.force_sum;
        let mean = if count == 0 { 0.0 } else { sum / count as f64 };
        ReferenceScales { displacement: norm(&self.model.displacement), force: mean }
    }

    /// Runs step `si` from `step_start`; Some(ending) when the run cannot or must not go on.
    /// `resumed`: the step is under way (a run resumed from a checkpoint), so the increment
    /// size, the output count and the crawl state carry on.
    fn run_step(&mut self, si: usize, step_start: f64, resumed: bool) -> Result<Option<Ending>> {
        let step = &self.plan.steps[si];
        (self.path.step, self.path.step_start) = (si, step_start);
        if !resumed {
            self.load.start_step(&step.incrementation);
            self.path.since_output = 0;
            self.path.policy.step_started();
        }
        while self.path.t < step.end_time - 1e-12 * self.t_end {
            if self.plan.interrupt.as_ref().is_some_and(|flag| flag.load(Ordering::Relaxed)) || self.stop_due() {
                return Ok(Some(Ending::Interrupted));
            }
            self.checkpoint_if_due()?;
            let (t, dt, crossing) = (self.path.t, self.load.dt, self.crossing.is_some());
            let flow = match self.path.policy.before_attempt(crossing, t, dt, &step.incrementation) {
                Some(decision) => self.carry_out(si, decision)?,
                None => self.attempt(si, step_start)?,
            };
            match flow {
                Flow::Continue => {}
                Flow::StepDone => break,
                Flow::Stop(message) => return Ok(Some(Ending::Failed(message))),
                Flow::Interrupted => return Ok(Some(Ending::Interrupted)),
            }
        }
        if let Some(k) = step.until_separated {
            let units = Units::of(&self.plan.units.0, &self.plan.units.1);
            let warning = self.tracker.still_attached(self.model, k, &units);
            self.summary.warnings.extend(warning);
        }
        Ok(None)
    }

    /// One attempt of the active control (a crossing under way, else load control) from the
    /// committed state, and what follows from it.
    fn attempt(&mut self, si: usize, step_start: f64) -> Result<Flow> {
        let step = &self.plan.steps[si];
        let breakpoints = std::mem::take(&mut self.breakpoints);
        let window = StepWindow {
            t: self.path.t,
            step_start,
            step_end: step.end_time,
            t_end: self.t_end,
            breakpoints: &breakpoints,
        };
        let scales = self.scales();
        let solvers = Solvers { linear: &mut *self.linear, nonlinear: &mut *self.nonlinear };
        let via = if self.crossing.is_some() { Via::Crossing } else { Via::LoadControl };
        let started = Instant::now();
        // the load-controlled attempt's increment (for the fold rule)
        let attempted = self.load.target(&window) - self.path.t;
        let attempt = match self.crossing.as_mut() {
            Some(arc) => arc.attempt(self.model, solvers, &window, scales),
            None => self.load.attempt(self.model, solvers, &window, scales),
        };
        let attempt_seconds = started.elapsed().as_secs_f64();
        self.breakpoints = breakpoints;
        let committed_before = self.summary.increments;
        Ok(match attempt {
            Attempt::Converged(report) => {
                let flow = self.converged(si, report, via)?;
                if self.summary.increments == committed_before {
                    // rolled back as a jump
                    self.summary.discarded_attempt_seconds += attempt_seconds;
                }
                flow
            }
            Attempt::Failed(failure) => {
                self.summary.discarded_attempt_seconds += attempt_seconds;
                self.failed(si, &AttemptFailure::Solver(failure), attempted)?
            }
            Attempt::OutsideWindow => {
                self.crossing = None;
                self.path.policy.crossing_handed_back();
                self.load.after_detour(step.end_time - self.path.t);
                Flow::Continue
            }
        })
    }

    /// A failed attempt (over `attempted`, when load-controlled): roll back, then cut the active
    /// control (or start arc length, or snap).
    fn failed(&mut self, si: usize, failure: &AttemptFailure, attempted: f64) -> Result<Flow> {
        if let Some(IncrementFailure::Error(CoreError::LawFailure { law, interface, point, message, .. })) =
            failure.solver()
        {
            let entry =
                self.path.law_failures.entry((law.clone(), interface.clone(), message.clone())).or_insert((0, *point));
            entry.0 += 1;
        }
        self.model.rollback();
        if let Some(what) = failure.solver().and_then(|f| self.tangent.after_failure(self.model, f)) {
            let text = format!("{}: {what} at t = {:.6}", self.plan.steps[si].name, self.path.t);
            self.observers.iter_mut().for_each(|o| o.message(&text));
        }
        self.load.forget();
        self.summary.cut_increments += 1;
        self.path.policy.attempt_failed();
        let step = &self.plan.steps[si];
        let facts = FailureFacts {
            failure,
            t: self.path.t,
            attempted,
            crossing: self.crossing.is_some(),
            continuation: self.plan.continuation,
            crossing_can_start: self.path.last_converged.as_ref().is_some_and(PreviousIncrement::moved_forward),
            resume_after: self.load.first_failed_target.unwrap_or(self.path.t),
            incrementation: &step.incrementation,
            force_unit: &self.plan.units.1,
        };
        let decision = self.path.policy.after_failure(&facts);
        self.carry_out_after(si, decision, failure)
    }

    /// Carries out the policy's `decision` after the `failure` of an attempt.
    fn carry_out_after(&mut self, si: usize, decision: Decision, failure: &AttemptFailure) -> Result<Flow> {
        let cut = match decision {
            Decision::CutCrossing => match self.crossing.as_mut() {
                Some(arc) => arc.cut(failure),
                None => self.load.cut(failure),
            },
            Decision::CutLoad => self.load.cut(failure),
            Decision::StartCrossing { resume_after } => {
                let continuation = self.plan.continuation.expect("a crossing starts with continuation on");
                self.crossing =
                    self.path.last_converged.clone().and_then(|previous| continuation.start(previous, resume_after));
                return Ok(Flow::Continue);
            }
            other => return self.carry_out(si, other),
        };
        match cut {
            Ok(what) => {
                let text = format!("{}: {what} at t = {:.4} ({failure})", self.plan.steps[si].name, self.path.t);
                for o in self.observers.iter_mut() {
                    o.message(&text);
                }
                Ok(Flow::Continue)
            }
            Err(refused) => {
                let reason = refused.reason(failure);
                let decision = self.path.policy.snap(reason, self.path.t, &self.plan.steps[si].incrementation);
                self.carry_out(si, decision)
            }
        }
    }

    /// Carries out a snap or a stop the policy decided.
    fn carry_out(&mut self, si: usize, decision: Decision) -> Result<Flow> {
        match decision {
            Decision::Snap { dt, crawl, reason, .. } => self.snap_over(si, &reason, dt, crawl),
            Decision::Stop { reason } => Ok(Flow::Stop(reason)),
            Decision::CutCrossing | Decision::CutLoad | Decision::StartCrossing { .. } => {
                unreachable!("a cut or a crossing is carried out after a failure")
            }
        }
    }

    /// Whether a converged load-controlled increment to `target` jumped to another branch
    /// ([`jumped`]), and how.
    fn jump(&self, target: f64, du: &[f64]) -> Option<&'static str> {
        let previous = self.path.last_converged.as_ref()?;
        jumped(&JumpFacts {
            moved: norm(du),
            moved_before: norm(&previous.du),
            dt: target - self.path.t,
            dt_before: previous.dt,
            turned: dot(du, &previous.du) < 0.0,
            noise: self.nonlinear.settings().tol_displacement * self.path.largest_displacement,
            continuation: self.plan.continuation.is_some(),
            from_breakpoint: self.at_breakpoint(self.path.t),
            arc_blocked: self.path.policy.arc_blocked(),
        })
    }

    /// After a jump (see [`Self::jump`]) to `target`: the increment is rolled back, and the
    /// crossing (arc length or dissipation control) starts when continuation is on; without
    /// it the increment counts as failed and is cut, as load control does at a limit point it
    /// cannot converge past (down to the minimum increment, then a snap: the state the
    /// displacement-controlled body moves to on its own, where Newton's iterations chose one).
    fn after_jump(&mut self, si: usize, target: f64, why: &'static str) -> Result<Flow> {
        let Some(continuation) = self.plan.continuation else {
            return self.failed(si, &AttemptFailure::Jumped { why }, target - self.path.t);
        };
        self.model.rollback();
        self.summary.cut_increments += 1;
        self.path.policy.attempt_failed();
        self.crossing = self.path.last_converged.clone().and_then(|previous| continuation.start(previous, target));
        let next = if self.crossing.is_some() { "crossing the limit point" } else { "load control goes on" };
        let text = format!("the increment to t = {target:.6} jumped ({why}): rolled back, {next}");
        self.observers.iter_mut().for_each(|o| o.message(&text));
        Ok(Flow::Continue)
    }

    /// Whether time `t` is an amplitude breakpoint or a step end (where the load may reverse).
    fn at_breakpoint(&self, t: f64) -> bool {
        self.breakpoints.iter().any(|&b| (b - t).abs() <= 1e-12 * self.t_end.max(1.0))
    }

    /// A converged attempt: accept it (or detect a jump), commit, record, adapt the increment.
    fn converged(&mut self, si: usize, report: IncrementReport, via: Via) -> Result<Flow> {
        let by_arc_length = via == Via::Crossing;
        let step = &self.plan.steps[si];
        let target = self.model.time;
        let (mut limit_point, mut resume) = (false, false);
        if let Some(arc) = self.crossing.as_mut() {
            let outcome = arc.accept(target, report.iterations, &step.incrementation);
            (limit_point, resume) = (outcome.limit_point, outcome.resume);
            self.summary.arc_length_increments += 1;
            self.summary.limit_points += usize::from(limit_point);
        }
        let du = self.model.increment_since_commit();
        if via == Via::LoadControl
            && let Some(why) = self.jump(target, &du)
        {
            return self.after_jump(si, target, why);
        }
        self.path.force_sum.0 += NonlinearProblem::force_norm(&*self.model);
        self.path.force_sum.1 += 1;
        let reversal = self.at_breakpoint(target);
        if via == Via::Settling {
            // a snap's displacement is no rate to extrapolate or to start arc length from
            self.path.last_converged = None;
            self.load.remember(du, 0.0, true);
            self.load.set_increment(step.incrementation.initial);
        } else {
            self.path.last_converged = Some(PreviousIncrement { du: du.clone(), dt: target - self.path.t });
            self.load.remember(du, target - self.path.t, reversal);
        }
        if resume {
            // past the point where load control failed, moving forward again
            self.crossing = None;
            self.load.set_increment(target - self.path.t);
        }
        let small = target - self.path.t < CRAWL_FRACTION * step.incrementation.maximum;
        self.model.commit();
        self.tangent.committed();
        self.path.largest_displacement = self.path.largest_displacement.max(norm(&self.model.displacement));
        self.path.t = target;
        self.add_report(&report);
        let plastic_dissipation = self.model.dissipation();
        let context = CommitContext {
            cuts_since_commit: self.path.policy.cuts_since_commit(),
            limit_point,
            by_arc_length,
            plastic_dissipation,
            footprint_dissipation: self.model.subscale_dissipation(),
            snap_dissipation: self.path.snap_dissipation,
        };
        let (events, separated) = self.tracker.update(self.model, context, step.until_separated);
        self.path.policy.committed(self.path.t, via == Via::Settling, via == Via::LoadControl, small);
        self.path.since_output += 1;
        let at_end = self.path.t >= step.end_time - 1e-12 * self.t_end;
        let frame_due = (step.output_every > 0 && self.path.since_output >= step.output_every) || at_end || separated;
        if frame_due {
            self.path.since_output = 0;
        }
        self.notify(si, &report, frame_due, plastic_dissipation, &events)?;
        if report.iterations <= step.incrementation.easy_iterations && self.crossing.is_none() && !resume {
            self.load.grow();
        }
        Ok(if separated { Flow::StepDone } else { Flow::Continue })
    }

    fn add_report(&mut self, report: &IncrementReport) {
        let s = &mut self.summary;
        s.increments += 1;
        s.newton_iterations += report.iterations;
        s.factorizations += report.factorizations;
        s.assembly_seconds += report.assembly_seconds;
        s.factorization_seconds += report.factorization_seconds;
        s.solve_seconds += report.solve_seconds;
    }

    /// Tells every observer of the committed increment and its events.
    fn notify(
        &mut self,
        si: usize,
        report: &IncrementReport,
        frame_due: bool,
        plastic_dissipation: f64,
        events: &[crate::record::InterfaceEvent],
    ) -> Result<()> {
        let last = report.residual_norms.last().copied().unwrap_or(0.0);
        let committed = CommittedIncrement {
            step: si + 1,
            increment: self.summary.increments,
            iterations: report.iterations,
            frame_due,
            fraction_done: if self.t_end > 0.0 { self.path.t / self.t_end } else { 1.0 },
            description: format!(
                "{}: t = {:.4} dt = {:.2e}, {} iterations, |r| = {last:.2e}",
                self.plan.steps[si].name, self.path.t, self.load.dt, report.iterations
            ),
            plastic_dissipation,
            snap_dissipation: self.path.snap_dissipation,
        };
        for o in self.observers.iter_mut() {
            o.committed(self.model, &committed)?;
            for e in events {
                o.event(e)?;
            }
        }
        Ok(())
    }

    fn finish(mut self, ending: Option<Ending>) -> Result<RunSummary> {
        let (events, warnings) = self.tracker.finish(self.path.t, &Units::of(&self.plan.units.0, &self.plan.units.1));
        self.count_totals();
        let s = &mut self.summary;
        s.plastic_dissipation = self.model.dissipation();
        s.snap_dissipation = self.path.snap_dissipation;
        s.max_equivalent_plastic_strain = self.model.max_material_output("equivalent_plastic_strain");
        (s.status, s.message) = match ending {
            None => (RunStatus::Completed, None),
            Some(Ending::Failed(message)) => (RunStatus::Failed, Some(message)),
            Some(Ending::Interrupted) => {
                let inside = self.snap_in_progress.as_ref().map_or(String::new(), |snap| {
                    let steps = snap.flow.as_ref().map_or(0, |f| f.report.steps);
                    format!(", inside the snap to t = {} after {steps} damped flow steps", snap.target)
                });
                (
                    RunStatus::Interrupted,
                    Some(format!(
                        "interrupted at t = {}{inside}; every committed increment is in history.csv and the VTK series",
                        self.path.t
                    )),
                )
            }
        };
        s.warnings.extend(warnings);
        if self.path.stalled_snaps.0 > 0 {
            s.warnings.push(format!(
                "{} damped-flow snap(s) ended where their steps stalled near rest, at up to {:.1} times the residual test (messages.log: 'stalled near rest')",
                self.path.stalled_snaps.0, self.path.stalled_snaps.1
            ));
        }
        for ((law, interface, message), (times, point)) in &self.path.law_failures {
            s.warnings.push(format!(
                "law '{law}' on interface '{interface}' failed {times} time(s), first at point {point}: {message}"
            ));
        }
        s.interfaces = self.tracker.summaries().to_vec();
        for o in self.observers.iter_mut() {
            for e in &events {
                o.event(e)?;
            }
            o.finished(self.model, &self.summary)?;
        }
        Ok(self.summary)
    }
}

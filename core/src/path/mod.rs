//! Path control: how pseudo-time advances through the steps. [`LoadControl`] prescribes the
//! next value of the load parameter (cutting failed increments, growing easy ones, landing on
//! amplitude breakpoints); the [`Crossing`]s follow the path through limit points on a
//! constraint: [`ArcLengthControl`] on an arc length, [`DissipationControl`] on the energy
//! damage dissipates. All implement [`PathControl`], so a new constraint is a new
//! implementation. The [`driver`] runs the steps, switches between load control and a
//! crossing, and notifies the observers of [`crate::record`].

mod arc_length_control;
mod dissipation_control;
pub mod driver;
mod load_control;
pub mod policy;
pub mod step;
pub mod tangent_choice;

pub use arc_length_control::ArcLengthControl;
pub use dissipation_control::DissipationControl;
pub use driver::{Checkpoint, Continuation, ContinuationMethod, RunPlan, SnapMethod, resume_steps, run_steps};
pub use load_control::{LoadControl, StartPredictor};
pub use step::{Incrementation, StepPlan};
pub use tangent_choice::TangentChoice;

use crate::linear_solver::LinearSolver;
use crate::model::Model;
use crate::nonlinear::arc_length::PreviousIncrement;
use crate::nonlinear::{IncrementFailure, IncrementReport, NonlinearSolver, ReferenceScales};

/// Where an increment may go: inside its step, and not across an amplitude breakpoint.
#[derive(Debug, Clone, Copy)]
pub struct StepWindow<'a> {
    /// Pseudo-time of the committed state.
    pub t: f64,
    pub step_start: f64,
    pub step_end: f64,
    /// End of the last step (the scale of time tolerances).
    pub t_end: f64,
    pub breakpoints: &'a [f64],
}

impl StepWindow<'_> {
    /// Whether pseudo-time `t_new` lies outside the step or across a breakpoint from `t`.
    pub fn excludes(&self, t_new: f64) -> bool {
        let crosses = self.breakpoints.iter().any(|&b| (b - self.t) * (b - t_new) < 0.0);
        crosses || t_new > self.step_end || t_new < self.step_start
    }
}

/// The solvers an increment is solved with.
pub struct Solvers<'a> {
    pub linear: &'a mut dyn LinearSolver,
    pub nonlinear: &'a mut dyn NonlinearSolver,
}

/// What an attempt produced.
pub enum Attempt {
    /// The model holds the converged trial state at `model.time`.
    Converged(IncrementReport),
    /// The attempt failed; the caller rolls back and asks the control to cut.
    Failed(IncrementFailure),
    /// The control cannot go on inside this window (the model is rolled back): hand over.
    OutsideWindow,
}

/// Why an attempt failed: its solver's failure, or the path's verdict on an increment that
/// converged.
#[derive(Debug)]
pub enum AttemptFailure {
    Solver(IncrementFailure),
    /// A load-controlled increment converged on another branch than the path's (without
    /// continuation: it moved more than [`policy::JUMP_RATIO`] times what the last increment's
    /// rate predicts, "moved too far"; [`policy::jumped`]); it is cut like one that did not
    /// converge.
    Jumped {
        why: &'static str,
    },
}

impl AttemptFailure {
    /// The solver's failure, if the solver failed.
    pub fn solver(&self) -> Option<&IncrementFailure> {
        match self {
            AttemptFailure::Solver(f) => Some(f),
            AttemptFailure::Jumped { .. } => None,
        }
    }

    /// Whether the solver's iterations did not converge ([`IncrementFailure::is_no_convergence`]).
    pub fn is_no_convergence(&self) -> bool {
        self.solver().is_some_and(IncrementFailure::is_no_convergence)
    }
}

impl std::fmt::Display for AttemptFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AttemptFailure::Solver(failure) => failure.fmt(f),
            AttemptFailure::Jumped { why } => write!(f, "the increment jumped to another branch ({why})"),
        }
    }
}

/// A way to choose and solve the next increment from the committed state.
pub trait PathControl {
    /// Solves the next increment from the committed state at `window.t`.
    fn attempt(
        &mut self,
        model: &mut Model,
        solvers: Solvers<'_>,
        window: &StepWindow<'_>,
        scales: ReferenceScales,
    ) -> Attempt;
    /// After a failed attempt (`failure`): makes the next one smaller, or says why it cannot.
    fn cut(&mut self, failure: &AttemptFailure) -> Result<Cut, CutRefused>;
}

/// How a control shortened its next attempt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cut {
    /// Load control's pseudo-time increment.
    Increment(f64),
    /// Arc length's length.
    ArcLength(f64),
    /// Dissipation control's energy per increment; `emptied`: the last attempt found nothing
    /// left to damage.
    Energy { energy: f64, emptied: bool },
}

impl std::fmt::Display for Cut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cut::Increment(dt) => write!(f, "cut to dt = {dt:.2e}"),
            Cut::ArcLength(ds) => write!(f, "arc length cut to {ds:.2e}"),
            Cut::Energy { energy, emptied: false } => write!(f, "energy per increment cut to {energy:.2e}"),
            Cut::Energy { energy, emptied: true } => {
                write!(f, "energy per increment cut to {energy:.2e} (nothing left to damage at the last one)")
            }
        }
    }
}

/// Why a control cannot shorten its next attempt: the path snaps instead.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CutRefused {
    /// Load control's increment would fall below the step's minimum.
    BelowMinimum { minimum: f64 },
    /// Arc length would fall below 1e-4 of the crossing's first.
    ArcLengthStalled { arc_length: f64 },
    /// Dissipation control has no energy per increment yet (its first attempt failed).
    DissipationNotStarted,
    /// The energy per increment would fall below 1e-4 of the crossing's first.
    DissipationStalled { energy: f64 },
}

impl CutRefused {
    /// Why, after `failure`, in the run's words.
    pub fn reason(&self, failure: &AttemptFailure) -> String {
        match self {
            CutRefused::BelowMinimum { minimum } => {
                format!("increment below the minimum {minimum:.3e} after: {failure}")
            }
            CutRefused::ArcLengthStalled { arc_length } => {
                format!("arc-length continuation stalled (arc length {arc_length:.3e}) after: {failure}")
            }
            CutRefused::DissipationNotStarted => format!("dissipation control could not start: {failure}"),
            CutRefused::DissipationStalled { energy } => {
                format!("dissipation control stalled (energy per increment {energy:.3e}) after: {failure}")
            }
        }
    }
}

/// A control that takes over from load control to cross a limit point, and hands back.
pub trait Crossing: PathControl {
    /// The converged attempt was committed at pseudo-time `t_new` after `iterations`.
    fn accept(&mut self, t_new: f64, iterations: usize, incrementation: &Incrementation) -> CrossingOutcome;
}

/// What an accepted crossing increment means for the path.
#[derive(Debug, Clone, Copy)]
pub struct CrossingOutcome {
    /// The load parameter turned.
    pub limit_point: bool,
    /// Past the point where load control failed, moving forward: load control resumes.
    pub resume: bool,
}

impl CrossingOutcome {
    /// The outcome of `increment`, committed at `t_new`, after `previous`.
    pub fn of(previous: &PreviousIncrement, increment: &PreviousIncrement, t_new: f64, resume_after: f64) -> Self {
        Self {
            limit_point: increment.dt.signum() != previous.dt.signum(),
            resume: increment.dt > 0.0 && t_new > resume_after,
        }
    }
}

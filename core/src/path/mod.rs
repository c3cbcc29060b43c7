//! Path control: how pseudo-time advances through the steps. [`LoadControl`] prescribes the
//! next value of the load parameter (cutting failed increments, growing easy ones, landing on
//! amplitude breakpoints); [`ArcLengthControl`] follows the path through limit points on an
//! arc-length constraint. Both implement [`PathControl`], so a new constraint (e.g. a
//! dissipation-based one) is a new implementation. The [`driver`] runs the steps, switches
//! between the two, and notifies the observers of [`crate::record`].

mod arc_length_control;
pub mod driver;
mod load_control;
pub mod step;

pub use arc_length_control::ArcLengthControl;
pub use driver::{RunPlan, run_steps};
pub use load_control::LoadControl;
pub use step::{Incrementation, StepPlan};

use crate::linear_solver::LinearSolver;
use crate::model::Model;
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
    /// After a failed attempt: makes the next one smaller, or says why it cannot.
    fn cut(&mut self, failure: &IncrementFailure) -> Result<String, String>;
}

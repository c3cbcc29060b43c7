//! Nonlinear solvers: they drive a [`NonlinearProblem`] to equilibrium at a given pseudo-time
//! with a [`LinearSolver`], and know nothing of steps, outputs or the case. Full Newton is
//! [`NewtonSolver`]; [`arc_length`] solves one increment on a constraint in (u, t) for path
//! following, [`dissipation`] one on the energy its damage dissipates; where the path has no
//! nearby equilibrium (a snap), [`damped_flow`] follows the body's overdamped motion to the
//! stable state it reaches and [`settle`] descends to one. A quasi-Newton or Krylov-on-a-stale-factor strategy is a new [`NonlinearSolver`].

pub mod arc_length;
mod bordered;
pub mod convergence;
pub mod damped_flow;
pub mod dissipation;
pub mod newton;
pub mod quasi_newton;
mod refactorization_costs;
pub mod settle;
pub mod tangent_predictor;

pub use convergence::{NewtonSettings, ReferenceScales};
pub use newton::{NewtonSolver, solve_increment};
pub use quasi_newton::QuasiNewtonSolver;

use crate::error::CoreError;
use crate::linear_solver::LinearSolver;
use crate::problem::NonlinearProblem;
use convergence::STAGNATION_WINDOW;

/// What one converged increment took.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct IncrementReport {
    pub iterations: usize,
    /// ||r|| before each solve and at convergence.
    pub residual_norms: Vec<f64>,
    pub factorizations: usize,
    pub assembly_seconds: f64,
    pub factorization_seconds: f64,
    pub solve_seconds: f64,
}

/// Why an increment failed (the path control cuts the step).
#[derive(Debug)]
pub enum IncrementFailure {
    Diverged {
        iterations: usize,
        residual: f64,
    },
    /// The residual stopped falling (see [`convergence`]'s module documentation): after
    /// `iterations` it was `residual`, above 95% of what it was 3 iterations `earlier`.
    Stagnated {
        iterations: usize,
        residual: f64,
        earlier: f64,
    },
    /// A time integrator's step whose iterations diverged or stalled at iteration `iterations`
    /// (no line-search trial reduced ||r||, and the full step left it above the predictor's; or
    /// only a short trial did): the step is too long for its nonlinearity, and the integrator
    /// redoes it shorter at once (`newton::integrator_step_diverged`).
    NoDescent {
        iterations: usize,
        residual: f64,
    },
    /// An arc-length increment converged onto the path behind the committed state (the cosine
    /// of its angle with the previous increment, in the arc-length norm, is not positive).
    TurnedBack {
        cosine: f64,
    },
    /// A dissipation-controlled increment found nothing damaging within its reach (the
    /// constraint has no gradient).
    NoDissipation,
    /// A damped flow took its most steps without coming to rest.
    FlowUnsettled {
        steps: usize,
        residual: f64,
    },
    Error(CoreError),
}

impl IncrementFailure {
    /// Whether the iterations of a fixed-time increment did not converge (they ran to the limit,
    /// the residual stopped falling, or a time integrator's step diverged), as opposed to a law
    /// or solver error, a jump or a crossing's own failures.
    pub fn is_no_convergence(&self) -> bool {
        matches!(
            self,
            IncrementFailure::Diverged { .. } | IncrementFailure::Stagnated { .. } | IncrementFailure::NoDescent { .. }
        )
    }
}

impl std::fmt::Display for IncrementFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IncrementFailure::Diverged { iterations, residual } => {
                write!(f, "no convergence after {iterations} iterations (residual {residual:.3e})")
            }
            IncrementFailure::Stagnated { iterations, residual, earlier } => write!(
                f,
                "stagnated after {iterations} iterations (residual {residual:.3e}, {earlier:.3e} {STAGNATION_WINDOW} iterations before)"
            ),
            IncrementFailure::NoDescent { iterations, residual } => write!(
                f,
                "the step's iterations diverged or stalled at iteration {iterations} (residual {residual:.3e}): the step is too long"
            ),
            IncrementFailure::TurnedBack { cosine } => {
                write!(
                    f,
                    "the arc-length increment went back along the path (cosine {cosine:.2} with the previous one)"
                )
            }
            IncrementFailure::NoDissipation => {
                write!(f, "no damage within reach of the increment: the dissipation cannot set its length")
            }
            IncrementFailure::FlowUnsettled { steps, residual } => write!(
                f,
                "the damped flow had not come to rest after {steps} steps (residual {residual:.3e}; raise solver.snap_max_steps or solver.snap_tolerance)"
            ),
            IncrementFailure::Error(e) => write!(f, "{e}"),
        }
    }
}

impl From<CoreError> for IncrementFailure {
    fn from(e: CoreError) -> Self {
        IncrementFailure::Error(e)
    }
}

/// Solves equilibrium at a fixed pseudo-time.
pub trait NonlinearSolver {
    /// Solves r(u, t) = 0 from the problem's trial state; on success the problem holds the
    /// converged trial state (not committed).
    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> Result<IncrementReport, IncrementFailure>;
    /// The settings (convergence test, iteration limits) this solver applies.
    fn settings(&self) -> &NewtonSettings;
    /// What the solver carries from one increment to the next that its decisions depend on
    /// (which factor it reuses, how its last increments went), as bytes for a checkpoint
    /// (empty: nothing, as for Newton). The factor itself is the linear solver's
    /// ([`LinearSolver::saved_factor`]).
    fn saved_state(&self) -> Vec<u8> {
        Vec::new()
    }
    /// Takes up `saved` ([`Self::saved_state`] of a solver of the same kind, whose linear
    /// solver's factor has been remade); state of another kind (the method changed on resume)
    /// is not this solver's, and leaves it as made.
    fn restore_state(&mut self, saved: &[u8]) {
        let _ = saved;
    }
    /// Moves the problem's trial state (the committed state) along the tangent from `t0` to
    /// `t1` ([`tangent_predictor`]); `rate_step` is the step of the difference in t, the costs
    /// go to `report`. The default factorizes the committed tangent; a solver that keeps a
    /// factor across increments may reuse its own, or keep the new one.
    fn predict_along_tangent(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        times: (f64, f64),
        rate_step: f64,
        report: &mut IncrementReport,
    ) -> Result<(), CoreError> {
        let fresh = tangent_predictor::PredictorFactor::Fresh;
        tangent_predictor::predict_along_tangent(problem, linear, times, rate_step, fresh, report).map(|_| ())
    }
}

impl IncrementReport {
    /// Adds the costs (iterations, factorizations, seconds) of `other` to this report.
    pub fn add_costs(&mut self, other: &IncrementReport) {
        self.iterations += other.iterations;
        self.factorizations += other.factorizations;
        self.assembly_seconds += other.assembly_seconds;
        self.factorization_seconds += other.factorization_seconds;
        self.solve_seconds += other.solve_seconds;
    }
}

#[cfg(test)]
mod tests;

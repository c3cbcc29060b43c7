//! The tangent (Euler) predictor of an increment that has no earlier rate to extrapolate (a
//! run's first increment, the first after a load reversal): from the committed state (u0, t0)
//! the trial state moves to
//!   u = u0 + (t1 - t0) du/dt,   K(u0, t0) du/dt = -dR/dt(u0, t0),
//! the first-order change of the equilibrium as the load parameter moves to t1 (Code_Aster's
//! `PREDICTION = 'TANGENTE'`). dR/dt is a one-sided difference of the residual in t towards t1
//! (t0 may be an amplitude's breakpoint, where the rate turns).
//!
//! Without it, the solve starts from u0 with the prescribed motion applied at once: a bonded
//! ligament whose far side moves by more than its law's onset opening is damaged at the first
//! residual (the body has not followed yet), and Newton may converge on the broken state, a
//! true but wrong equilibrium of the softening law.

use super::IncrementReport;
use crate::error::{CoreError, Result};
use crate::linear_solver::{FactorKind, LinearSolver};
use crate::problem::NonlinearProblem;
use crate::vector::norm;
use std::time::Instant;

/// Where the predictor's K^-1 comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PredictorFactor {
    /// The linear solver's current factor (a recent tangent: cheaper, and good enough to start
    /// from).
    Reuse,
    /// A factorization of the tangent at the committed state.
    Fresh,
}

/// A factorization the predictor made: its kind, and what it cost as a refactorization does
/// in the iterations (the assembly with the tangent and the numeric factorization, seconds),
/// for a solver's cost model; the predictor's second residual assembly and its solve are not
/// part of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictorFactorization {
    pub kind: FactorKind,
    pub seconds: f64,
}

/// Moves the problem's trial state (the committed state, at `t0`) along the tangent to `t1`
/// (see the module documentation); `rate_step` is the step of the difference in t. Returns the
/// factorization it made (None when it reused one, or when the residual does not depend on t
/// there, so nothing moves). On error (a non-finite prediction among them) the trial
/// displacement has not moved; the costs go to `report` either way.
pub fn predict_along_tangent(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    (t0, t1): (f64, f64),
    rate_step: f64,
    factor: PredictorFactor,
    report: &mut IncrementReport,
) -> Result<Option<PredictorFactorization>> {
    let fresh = factor == PredictorFactor::Fresh;
    let (rate, tangent_assembly_seconds) = residual_rate_towards(problem, (t0, t1), rate_step, fresh, report)?;
    let mut velocity: Vec<f64> = rate.iter().map(|r| -r).collect();
    if !(norm(&velocity) > 0.0) {
        return Ok(None);
    }
    let mut made = None;
    if fresh {
        let timer = Instant::now();
        let kind = linear.factorize(problem.pattern(), problem.tangent())?;
        let seconds = timer.elapsed().as_secs_f64();
        report.factorization_seconds += seconds;
        report.factorizations += 1;
        made = Some(PredictorFactorization { kind, seconds: seconds + tangent_assembly_seconds });
    }
    let timer = Instant::now();
    linear.solve_approximately(&mut velocity)?;
    report.solve_seconds += timer.elapsed().as_secs_f64();
    if !velocity.iter().all(|v| v.is_finite()) {
        return Err(CoreError::NonFinite("the tangent predictor (a singular tangent at the committed state)".into()));
    }
    problem.add_to_free(&velocity, t1 - t0);
    Ok(made)
}

/// dR/dt at the committed state (the problem's trial state at `t0`), a one-sided difference of
/// step `h` towards `t1`; the first assembly also assembles the tangent when `with_tangent`.
/// Returns the rate and the seconds of that first assembly.
fn residual_rate_towards(
    problem: &mut dyn NonlinearProblem,
    (t0, t1): (f64, f64),
    h: f64,
    with_tangent: bool,
    report: &mut IncrementReport,
) -> Result<(Vec<f64>, f64)> {
    let timer = Instant::now();
    let h = h.copysign(t1 - t0);
    problem.set_time(t0);
    problem.assemble(with_tangent)?;
    let first_assembly_seconds = timer.elapsed().as_secs_f64();
    let at_start = problem.residual().to_vec();
    problem.set_time(t0 + h);
    problem.assemble(false)?;
    let rate = problem.residual().iter().zip(&at_start).map(|(r, r0)| (r - r0) / h).collect();
    problem.set_time(t0);
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    Ok((rate, first_assembly_seconds))
}

//! The two solves of a bordered Newton iteration in (u, t), shared by the path-following
//! constraints ([`super::arc_length`], [`super::dissipation`]): with the tangent K at the trial
//! state (u, t), a = -K^-1 R and b = -K^-1 dR/dt, the correction is a + dl b for whatever dl
//! the constraint asks.

use super::{IncrementFailure, IncrementReport};
use crate::error::CoreError;
use crate::linear_solver::LinearSolver;
use crate::problem::NonlinearProblem;
use std::time::Instant;

/// dR/dt at the problem's displacement by central differences of the residual in t (step h);
/// restores the problem's time.
pub(crate) fn residual_rate(
    problem: &mut dyn NonlinearProblem,
    t: f64,
    h: f64,
    rate: &mut [f64],
) -> Result<(), CoreError> {
    problem.set_time(t + h);
    problem.assemble(false)?;
    rate.copy_from_slice(problem.residual());
    problem.set_time(t - h);
    problem.assemble(false)?;
    for (r, m) in rate.iter_mut().zip(problem.residual()) {
        *r = (*r - m) / (2.0 * h);
    }
    problem.set_time(t);
    Ok(())
}

/// From the problem just assembled with its tangent at time `t`: a = -K^-1 R and
/// b = -K^-1 dR/dt (dR/dt by [`residual_rate`] with step `h`, whose assemblies leave the
/// tangent in place), one factorization; the costs go to `report`.
pub(crate) fn bordered_solves(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    t: f64,
    h: f64,
    (a, b): (&mut [f64], &mut [f64]),
    report: &mut IncrementReport,
) -> Result<(), IncrementFailure> {
    for (ai, r) in a.iter_mut().zip(problem.residual()) {
        *ai = -r;
    }
    let timer = Instant::now();
    residual_rate(problem, t, h, b)?;
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    let timer = Instant::now();
    linear.factorize(problem.pattern(), problem.tangent())?;
    report.factorization_seconds += timer.elapsed().as_secs_f64();
    report.factorizations += 1;
    let timer = Instant::now();
    for bi in b.iter_mut() {
        *bi = -*bi;
    }
    linear.solve_in_place(a)?;
    linear.solve_in_place(b)?;
    report.solve_seconds += timer.elapsed().as_secs_f64();
    Ok(())
}

//! Full Newton-Raphson with the consistent tangent and a backtracking line search: one
//! factorization per iteration. Convergence: [`NewtonSettings::converged`] (and a time
//! integrator step's own accuracy, [`crate::problem::IntegratorStep`]).

use super::convergence::{
    Correction, NEAR_MISS_ITERATIONS, NewtonSettings, ReferenceScales, check_iteration, iteration_limit,
};
use super::{IncrementFailure, IncrementReport, NonlinearSolver};
use crate::error::Result;
use crate::linear_solver::LinearSolver;
use crate::problem::NonlinearProblem;
use crate::vector::norm;
use std::time::Instant;

/// Full Newton (the default nonlinear solver).
#[derive(Debug, Clone, Default)]
pub struct NewtonSolver {
    pub settings: NewtonSettings,
}

impl NonlinearSolver for NewtonSolver {
    fn settings(&self) -> &NewtonSettings {
        &self.settings
    }

    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> std::result::Result<IncrementReport, IncrementFailure> {
        solve_increment(problem, linear, t, &self.settings, scales)
    }
}

/// Solves equilibrium at pseudo-time `t` starting from the problem's current trial state (the
/// committed state, possibly moved by a predictor). On success the problem holds the converged
/// trial state (not yet committed).
pub fn solve_increment(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    t: f64,
    settings: &NewtonSettings,
    scales: ReferenceScales,
) -> std::result::Result<IncrementReport, IncrementFailure> {
    let mut report = IncrementReport::default();
    let start_u: Vec<f64> = problem.solution().to_vec();
    problem.set_time(t);
    let timer = Instant::now();
    problem.assemble(true)?;
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    let mut du = vec![0.0; problem.n_free()];
    let mut full = true;
    let max_iterations = iteration_limit(settings, problem);
    for iteration in 0..=max_iterations + NEAR_MISS_ITERATIONS {
        let correction = Correction { step: &du, full };
        let check =
            check_iteration(settings, problem, scales, iteration, correction, &start_u, &mut report.residual_norms);
        if check.converged {
            report.iterations = iteration;
            return Ok(report);
        }
        let r_norm = check.residual;
        if let Some(stagnated) = check.stagnated {
            return Err(stagnated);
        }
        if check.out_of_iterations(iteration, max_iterations) {
            return Err(IncrementFailure::Diverged { iterations: iteration, residual: r_norm });
        }
        let timer = Instant::now();
        linear.factorize(problem.pattern(), problem.tangent())?;
        report.factorization_seconds += timer.elapsed().as_secs_f64();
        report.factorizations += 1;
        let timer = Instant::now();
        for (d, r) in du.iter_mut().zip(problem.residual()) {
            *d = -r;
        }
        linear.solve_in_place(&mut du)?;
        report.solve_seconds += timer.elapsed().as_secs_f64();
        let timer = Instant::now();
        let searched = line_search(problem, &du, r_norm, settings, true);
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        let searched = searched?;
        if let Some(diverged) = integrator_step_diverged(problem, iteration, searched, &du, report.residual_norms[0]) {
            return Err(diverged);
        }
        let alpha = searched.alpha;
        full = alpha == 1.0;
        for d in du.iter_mut() {
            *d *= alpha;
        }
    }
    // (not reached: the last iteration allowed is out of iterations, whatever its rate)
    Err(IncrementFailure::Diverged {
        iterations: max_iterations + NEAR_MISS_ITERATIONS,
        residual: norm(problem.residual()),
    })
}

/// What a line search took: the step length alpha, and whether it reduced ||r|| (false: no
/// trial did, and the full step was kept).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LineSearchStep {
    pub alpha: f64,
    pub reduced: bool,
}

/// The shortest line-search step a time integrator's step goes on with while its correction
/// is still above the step's tolerance (two cuts at least).
pub const INTEGRATOR_MIN_ALPHA: f64 = 0.1;

/// Whether a time integrator's step is given up after iteration `iteration`'s line search
/// `step` along `direction`, when the step started from the residual `initial` at its
/// predictor. It is when the iterations diverge: no trial reduced ||r||, and the full step kept
/// leaves it above `initial`; or when they stall: the direction is still longer than the
/// step's correction tolerance and only a step below [`INTEGRATOR_MIN_ALPHA`] of it reduced
/// ||r||. Either way the predictor lies outside the region where Newton's iteration converges,
/// and the remedy is a shorter step, which the integrator takes at once, not more iterations
/// (a stiff integrator's Newton iteration stops on divergence; Hairer and Wanner, Solving ODEs
/// II, IV.8). Such steps (a surface node thrown into the repulsive wall, ||r|| from 1 to 1e8;
/// or line-search steps of 0.02 to 0.0002 at a stalled ||r||) would otherwise run their 10
/// iterations with 6 line-search trials each and then be tried again by full Newton, at tens
/// of times the cost of an accepted step. Near
/// convergence a line search may fail in rounding: ||r|| is then far below `initial`, and the
/// direction below the tolerance (a step solved to equilibrium, tolerance 0, is judged by
/// divergence alone). An equilibrium solve goes on (it has no shorter step).
pub(crate) fn integrator_step_diverged(
    problem: &dyn NonlinearProblem,
    iteration: usize,
    step: LineSearchStep,
    direction: &[f64],
    initial: f64,
) -> Option<IncrementFailure> {
    let integrator = problem.integrator_step()?;
    let residual = norm(problem.residual());
    let diverged = !step.reduced && residual > initial;
    let tolerance = integrator.correction_tolerance;
    let stalled =
        step.alpha < INTEGRATOR_MIN_ALPHA && tolerance > 0.0 && crate::vector::norm_inf(direction) > tolerance;
    (diverged || stalled).then_some(IncrementFailure::NoDescent { iterations: iteration + 1, residual })
}

/// Moves the problem along `du` from the state with residual norm `r_norm` and returns the
/// step it took; the problem is left assembled at u + alpha du (with the tangent when
/// `tangent_after`).
///
/// The full step is taken when it reduces ||r||; otherwise (with line search on) alpha is
/// chosen by a quadratic model of ||r(u + alpha du)||^2, safeguarded to [0.1, 0.5] of the last
/// trial, until ||r|| < (1 - 1e-4 alpha) r_norm. If no trial succeeds the full step is kept:
/// quadratic convergence may still follow (and a material failure at the full step is
/// reported as such); the step says so (`reduced` false), and a time integrator's step may be
/// given up for it ([`integrator_step_diverged`]).
pub(crate) fn line_search(
    problem: &mut dyn NonlinearProblem,
    du: &[f64],
    r_norm: f64,
    settings: &NewtonSettings,
    tangent_after: bool,
) -> Result<LineSearchStep> {
    let mut alpha = 1.0;
    problem.add_to_free(du, alpha);
    let first = problem.assemble(tangent_after);
    let mut accepted = first.is_ok() && norm(problem.residual()) < r_norm * (1.0 - 1e-4);
    if !accepted && settings.line_search {
        let mut previous = alpha;
        let mut trial_norm = if first.is_ok() { norm(problem.residual()) } else { f64::INFINITY };
        for _ in 0..settings.max_line_search {
            let next = if trial_norm.is_finite() {
                let (g0, g1) = (r_norm * r_norm, trial_norm * trial_norm);
                let a = previous * previous * g0 / (g1 + g0 * (2.0 * previous - 1.0)).max(1e-300);
                a.clamp(0.1 * previous, 0.5 * previous)
            } else {
                0.25 * previous
            };
            problem.add_to_free(du, next - previous);
            previous = next;
            alpha = next;
            trial_norm = if problem.assemble(false).is_ok() { norm(problem.residual()) } else { f64::INFINITY };
            if trial_norm < r_norm * (1.0 - 1e-4 * alpha) {
                accepted = true;
                break;
            }
        }
        if accepted && tangent_after {
            // the trial left the residual assembled at this alpha; only the tangent is missing
            problem.assemble(true)?;
        }
    } else if let Err(e) = first {
        return Err(e);
    }
    if !accepted {
        // the full step is kept, so the correction the convergence test sees is the full du
        problem.add_to_free(du, 1.0 - alpha);
        problem.assemble(tangent_after)?;
        return Ok(LineSearchStep { alpha: 1.0, reduced: false });
    }
    Ok(LineSearchStep { alpha, reduced: true })
}

//! Quasi-Newton on a reused factorization (the default nonlinear solver): the factor of a
//! recent tangent K0 serves as the initial inverse Hessian H0 = K0^{-1} of a limited-memory
//! BFGS update (Matthies and Strang 1979; the two-loop recursion of Nocedal 1980), so an
//! iteration costs one residual assembly (no tangent) and one pair of triangular solves
//! instead of a tangent assembly and a numeric factorization.
//!
//! Direction: d = -H r with H the BFGS update of H0 by the pairs (s_i, y_i), s_i = u_{i+1} -
//! u_i, y_i = r_{i+1} - r_i, kept while s.y > 0. The step along d uses the same residual line
//! search as Newton. The tangent is reassembled and refactorized (and the pairs dropped):
//! - at the first increment, and after a failed one;
//! - when an iteration reduces ||r|| by less than `slow_ratio` (convergence has slowed);
//! - when the iterations left at the observed rate would cost more than a refactorization
//!   (on a factor made in the last increment, judged once the steps use two BFGS pairs; see
//!   [`super::refactorization_costs`]), counted to the solve's own test: the residual test of
//!   an equilibrium, the correction test of a time integrator's step;
//! - at every iteration while the tangent is indefinite (an LDL^T factor: softening);
//! - when the linear solver's factor is not the one this solver made (another method, a damped
//!   flow's mass or a settle's shifted tangent, factorized since), or was made for another
//!   matrix: a time integrator's step iterates on K + c M ([`IntegratorStep::mass_coefficient`]),
//!   and a factor made for a c more than [`MASS_COEFFICIENT_CHANGE`] away, or for K alone, is
//!   rebuilt (CVODE's rule for its Newton matrix, Hindmarsh et al. 2005, with a band derived
//!   below): on a factor of a far shorter step, whose drag c M dominates, the corrections come
//!   out too small by the ratio of the c's, and a step would count as converged on its
//!   correction test while far from solved.
//!
//! So a hard increment degrades to full Newton, never to a crawl; and an increment the
//! quasi-Newton iterations cannot converge is solved again by full Newton before it counts as
//! failed, and full Newton goes on for the next increments (a path hard enough to defeat the
//! quasi-Newton iterations, e.g. a cohesive crack growing, is Newton's ground): for
//! [`FIRST_NEWTON_STRETCH`] increments after the first such failure, twice as many after each
//! further one (so the failed attempts cost a bounded share however often the path is hard),
//! then quasi-Newton again (an adhesive jump-in is hard for a few increments, not for the rest
//! of the run). A damped flow's step that fails (it was too long) is tried once by full Newton
//! and starts no such stretch; nor is a flow's step solved in a stretch, or counted against it
//! (the stretch is for the hard equilibrium path: the flow's own matrix K + c M is better
//! conditioned, and solved in the stretch, the flow steps of a snap after a failed increment
//! would run it out at a factorization per iteration). Convergence is judged by the same test as Newton's
//! ([`NewtonSettings::converged`], or a time integrator step's own accuracy,
//! [`NonlinearProblem::integrator_step`]): the criteria are not loosened.

use super::convergence::{
    Correction, NEAR_MISS_ITERATIONS, NewtonSettings, ReferenceScales, check_iteration, iteration_limit,
};
use super::newton::{integrator_step_diverged, line_search};
use super::refactorization_costs::{Costs, ITERATIONS_AFTER_REFACTORIZATION, rate_is_trusted};
use super::tangent_predictor::{PredictorFactor, predict_along_tangent};
use super::{IncrementFailure, IncrementReport, NonlinearSolver};
use crate::error::Result;
use crate::linear_solver::{FactorKind, LinearSolver};
use crate::problem::{IntegratorStep, NonlinearProblem};
use crate::vector::{dot, norm, norm_inf};
use std::time::Instant;

/// Quasi-Newton (L-BFGS on a reused factor) with refactorization when convergence slows.
#[derive(Debug, Clone)]
pub struct QuasiNewtonSolver {
    pub settings: NewtonSettings,
    /// Refactorize when an iteration leaves more than this fraction of the residual.
    pub slow_ratio: f64,
    /// The factor this solver made last, while the linear solver holds it and it is usable.
    factor: Option<OwnFactor>,
    /// The last tangent was not positive definite (softening): BFGS's curvature condition
    /// fails there, so the iterations refactorize every time (full Newton) until it is again.
    indefinite: bool,
    /// The increments handed to full Newton after the quasi-Newton iterations failed one.
    newton: NewtonStretch,
    costs: Costs,
    /// Increments converged since the current factor was made.
    increments_on_factor: usize,
}

impl QuasiNewtonSolver {
    pub fn new(settings: NewtonSettings) -> Self {
        Self {
            settings,
            slow_ratio: 0.9,
            factor: None,
            indefinite: false,
            newton: NewtonStretch::default(),
            increments_on_factor: 0,
            costs: Costs::default(),
        }
    }

    /// Begins a full-Newton stretch as a failed equilibrium increment would (for tests).
    #[cfg(test)]
    pub(crate) fn start_newton_stretch(&mut self) {
        self.newton.quasi_newton_failed();
    }

    /// The same solver deciding with a fixed cost ratio of a refactorization (tangent assembly
    /// and numeric factorization) to a quasi-Newton iteration (residual assembly and solve)
    /// instead of measured times: reproducible to the last digit for a given thread count.
    pub fn with_cost_ratio(settings: NewtonSettings, ratio: f64) -> Self {
        Self { costs: Costs::with_fixed_ratio(ratio), ..Self::new(settings) }
    }
}

/// The first bytes of the quasi-Newton solver's saved state.
const SAVED_STATE_TAG: &[u8] = b"quasi-newton 1\n";

/// What the quasi-Newton solver carries between increments (see
/// [`NonlinearSolver::saved_state`]): the factor it reuses (named by the linear solver's count,
/// which a remade factor takes up), the tangent's definiteness, the full-Newton stretch, the
/// costs and the factor's age. BFGS pairs live within one increment.
#[derive(serde::Serialize, serde::Deserialize)]
struct SavedState {
    factor: Option<OwnFactor>,
    indefinite: bool,
    newton: NewtonStretch,
    costs: Costs,
    increments_on_factor: usize,
}

/// A factor's relative change of the mass coefficient c beyond which a time integrator's step
/// rebuilds its iteration matrix K + c M. On the factor of K + c_f M, the iteration for
/// K + c M (K positive semidefinite, M positive definite) propagates its error by
/// I - (K + c_f M)^{-1} (K + c M), whose eigenvalues 1 - lambda have lambda, a quotient
/// (x.K x + c x.M x) / (x.K x + c_f x.M x), between 1 and c / c_f: each iteration multiplies
/// the error by at most rho = |c / c_f - 1| (before the BFGS update and the line search improve
/// on it), and the error left after a correction du is at most rho / (1 - rho) |du|. With
/// |c / c_f - 1| <= 1/2 that is at most |du| itself, which the correction test
/// ([`IntegratorStep::correction_tolerance`]) takes as the error: the factor serves. (CVODE's
/// `dgmax` is 0.3, rho / (1 - rho) <= 0.43; the wider band spares about a third of the
/// damped flow's factorizations, whose steps' error estimates move c by 10 to 40% from one
/// step to the next: `docs/ru-rough-sphere.md`, "Factors the flow's steps share".)
pub const MASS_COEFFICIENT_CHANGE: f64 = 0.5;

/// Which factor the solver made: the linear solver's count of factorizations right after it
/// (so a later factorization by anyone else shows), and the mass coefficient c of the matrix
/// K + c M it factorized (None: K, the tangent of an equilibrium solve).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
struct OwnFactor {
    identity: u64,
    mass_coefficient: Option<f64>,
}

impl OwnFactor {
    fn made(linear: &dyn LinearSolver, step: Option<IntegratorStep>) -> Self {
        Self { identity: linear.factorizations(), mass_coefficient: step.map(|s| s.mass_coefficient) }
    }

    /// Whether the linear solver still holds this factor and it serves a solve of `step`'s
    /// matrix: the same kind (K, or K + c M), with c within [`MASS_COEFFICIENT_CHANGE`].
    fn serves(&self, linear: &dyn LinearSolver, step: Option<IntegratorStep>) -> bool {
        let same_matrix = match (self.mass_coefficient, step.map(|s| s.mass_coefficient)) {
            (None, None) => true,
            (Some(made), Some(wanted)) => (wanted / made - 1.0).abs() <= MASS_COEFFICIENT_CHANGE,
            _ => false,
        };
        same_matrix && self.identity == linear.factorizations()
    }
}

/// The BFGS pairs of one increment.
#[derive(Default)]
struct Pairs {
    s: Vec<Vec<f64>>,
    y: Vec<Vec<f64>>,
    rho: Vec<f64>,
}

impl Pairs {
    fn clear(&mut self) {
        self.s.clear();
        self.y.clear();
        self.rho.clear();
    }

    /// Keeps (s, y) when the curvature s.y is positive.
    fn push(&mut self, s: Vec<f64>, y: Vec<f64>) {
        let sy = dot(&s, &y);
        if sy > 1e-300 * norm(&s) * norm(&y) && sy > 0.0 {
            self.rho.push(1.0 / sy);
            self.s.push(s);
            self.y.push(y);
        }
    }

    /// z = H r by the two-loop recursion with H0 = the linear solver's factor.
    fn apply(&self, linear: &mut dyn LinearSolver, r: &[f64], z: &mut [f64]) -> Result<()> {
        z.copy_from_slice(r);
        let k = self.s.len();
        let mut alpha = vec![0.0; k];
        for i in (0..k).rev() {
            alpha[i] = self.rho[i] * dot(&self.s[i], z);
            for (q, y) in z.iter_mut().zip(&self.y[i]) {
                *q -= alpha[i] * y;
            }
        }
        linear.solve_approximately(z)?;
        for i in 0..k {
            let beta = self.rho[i] * dot(&self.y[i], z);
            for (q, s) in z.iter_mut().zip(&self.s[i]) {
                *q += (alpha[i] - beta) * s;
            }
        }
        Ok(())
    }
}

impl NonlinearSolver for QuasiNewtonSolver {
    fn settings(&self) -> &NewtonSettings {
        &self.settings
    }

    fn saved_state(&self) -> Vec<u8> {
        let state = SavedState {
            factor: self.factor,
            indefinite: self.indefinite,
            newton: self.newton,
            costs: self.costs,
            increments_on_factor: self.increments_on_factor,
        };
        let mut bytes = SAVED_STATE_TAG.to_vec();
        bytes.extend(postcard::to_allocvec(&state).expect("plain numbers serialize"));
        bytes
    }

    fn restore_state(&mut self, saved: &[u8]) {
        let state = saved.strip_prefix(SAVED_STATE_TAG).and_then(|body| postcard::from_bytes::<SavedState>(body).ok());
        if let Some(s) = state {
            (self.factor, self.indefinite, self.newton) = (s.factor, s.indefinite, s.newton);
            self.costs = self.costs.resumed(s.costs);
            self.increments_on_factor = s.increments_on_factor;
        }
    }

    /// The tangent predictor on the solver's own factor when it holds one; otherwise on a
    /// factor of the committed tangent, which the iterations then start from.
    fn predict_along_tangent(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        times: (f64, f64),
        rate_step: f64,
        report: &mut IncrementReport,
    ) -> Result<()> {
        let reuse = self.factor.is_some_and(|f| f.serves(linear, None)) && self.newton.left == 0;
        let factor = if reuse { PredictorFactor::Reuse } else { PredictorFactor::Fresh };
        if let Some(made) = predict_along_tangent(problem, linear, times, rate_step, factor, report)? {
            self.indefinite = made.kind == FactorKind::Ldlt;
            self.costs.refactorized(made.seconds);
            self.factor = Some(OwnFactor::made(linear, None));
            self.increments_on_factor = 0;
        }
        Ok(())
    }

    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> std::result::Result<IncrementReport, IncrementFailure> {
        // the full-Newton stretch is for the hard equilibrium path; a time integrator's step (a
        // damped flow's, on K + c M) is neither solved in it nor counted against it
        let integrating = problem.integrator_step().is_some();
        if self.newton.left > 0 && !integrating {
            let result = super::newton::solve_increment(problem, linear, t, &self.settings, scales);
            self.newton_solved(result.is_ok());
            return result;
        }
        let mut report = IncrementReport::default();
        let result = match self.iterate(problem, linear, t, scales, &mut report) {
            Ok(()) => Ok(report),
            Err(IncrementFailure::Diverged { iterations, .. } | IncrementFailure::Stagnated { iterations, .. }) => {
                // not a crawl, not a cut: the same increment by full Newton from the committed
                // state, and full Newton for the next increments (the path has become hard);
                // the report counts both attempts. A time integrator's step that failed was
                // too long, which says nothing of the next: it is tried once by Newton (one whose
                // iterations diverged or stalled, `NoDescent`, goes back to the integrator at once).
                if problem.integrator_step().is_none() {
                    self.newton.quasi_newton_failed();
                }
                problem.rollback();
                let newton = super::newton::solve_increment(problem, linear, t, &self.settings, scales);
                self.factor = None;
                if !integrating {
                    self.newton.newton_solved(newton.is_ok());
                }
                if newton.is_ok() {
                    // Newton's last factor, of a tangent next to the converged state, serves on
                    self.factor = Some(OwnFactor::made(linear, problem.integrator_step()));
                }
                newton.map(|mut newton| {
                    newton.add_costs(&IncrementReport { iterations, ..report });
                    newton
                })
            }
            Err(e) => Err(e),
        };
        // a failed increment may have left a factor of a state far from the next attempt's
        if result.is_err() {
            self.factor = None;
        }
        result
    }
}

/// Increments full Newton solves after the first increment the quasi-Newton iterations failed.
pub const FIRST_NEWTON_STRETCH: usize = 4;

/// The increments full Newton solves after the quasi-Newton iterations failed one: the failed
/// increment and 3 more after the first failure, twice as many after each further one.
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
struct NewtonStretch {
    /// Increments full Newton still solves.
    left: usize,
    /// How many the last failure handed to it.
    length: usize,
}

impl NewtonStretch {
    fn quasi_newton_failed(&mut self) {
        self.length = (2 * self.length).max(FIRST_NEWTON_STRETCH);
        self.left = self.length;
    }

    /// Full Newton solved an increment (`converged`) or failed it (cut: it tries again).
    fn newton_solved(&mut self, converged: bool) {
        if converged {
            self.left = self.left.saturating_sub(1);
        }
    }
}

impl QuasiNewtonSolver {
    /// After an increment solved by full Newton (`converged` or not): the quasi-Newton
    /// iterations, when they take over again, start from a factor of their own (whose kind,
    /// LL^T or LDL^T, they then know).
    fn newton_solved(&mut self, converged: bool) {
        self.factor = None;
        self.newton.newton_solved(converged);
    }

    fn refactorize(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        report: &mut IncrementReport,
        assemble_tangent: bool,
    ) -> Result<()> {
        let timer = Instant::now();
        if assemble_tangent {
            problem.assemble(true)?;
            report.assembly_seconds += timer.elapsed().as_secs_f64();
        }
        let factor_timer = Instant::now();
        self.indefinite = linear.factorize(problem.pattern(), problem.tangent())? == FactorKind::Ldlt;
        report.factorization_seconds += factor_timer.elapsed().as_secs_f64();
        report.factorizations += 1;
        self.costs.refactorized(timer.elapsed().as_secs_f64());
        self.factor = Some(OwnFactor::made(linear, problem.integrator_step()));
        self.increments_on_factor = 0;
        Ok(())
    }

    fn iterate(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
        report: &mut IncrementReport,
    ) -> std::result::Result<(), IncrementFailure> {
        let settings = self.settings.clone();
        let start_u: Vec<f64> = problem.solution().to_vec();
        problem.set_time(t);
        let timer = Instant::now();
        let with_tangent = !self.factor.is_some_and(|f| f.serves(linear, problem.integrator_step()));
        problem.assemble(with_tangent)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        if with_tangent {
            self.refactorize(problem, linear, report, false)?;
        }
        let n = problem.n_free();
        let mut pairs = Pairs::default();
        let (mut du, mut r_old) = (vec![0.0; n], vec![0.0; n]);
        // the BFGS pairs the last step was computed with
        let mut pairs_in_last_step = 0;
        let mut full = true;
        let max_iterations = iteration_limit(&settings, problem);
        for iteration in 0..=max_iterations + NEAR_MISS_ITERATIONS {
            let correction = Correction { step: &du, full };
            let check = check_iteration(
                &settings,
                problem,
                scales,
                iteration,
                correction,
                &start_u,
                &mut report.residual_norms,
            );
            if check.converged {
                report.iterations = iteration;
                self.increments_on_factor += 1;
                return Ok(());
            }
            let (r_norm, force_scale) = (check.residual, check.force_scale);
            if let Some(stagnated) = check.stagnated {
                return Err(stagnated);
            }
            if check.out_of_iterations(iteration, max_iterations) {
                return Err(IncrementFailure::Diverged { iterations: iteration, residual: r_norm });
            }
            if iteration > 0 {
                let rate = r_norm / report.residual_norms[iteration - 1];
                let (distance, target) = distance_to_convergence(problem, &settings, r_norm, force_scale, &du);
                let budget = max_iterations.saturating_sub(iteration + ITERATIONS_AFTER_REFACTORIZATION as usize);
                if self.indefinite
                    || rate > self.slow_ratio
                    || (rate_is_trusted(pairs_in_last_step, self.increments_on_factor)
                        && self.costs.refactorize_pays(rate, distance, target, budget))
                {
                    self.refactorize(problem, linear, report, true)?;
                    pairs.clear();
                }
            }
            let iteration_start = Instant::now();
            let timer = Instant::now();
            r_old.copy_from_slice(problem.residual());
            pairs_in_last_step = pairs.s.len();
            pairs.apply(linear, &r_old, &mut du)?;
            for d in du.iter_mut() {
                *d = -*d;
            }
            report.solve_seconds += timer.elapsed().as_secs_f64();
            let timer = Instant::now();
            let searched = line_search(problem, &du, r_norm, &settings, false);
            report.assembly_seconds += timer.elapsed().as_secs_f64();
            let searched = searched?;
            if let Some(diverged) =
                integrator_step_diverged(problem, iteration, searched, &du, report.residual_norms[0])
            {
                return Err(diverged);
            }
            let alpha = searched.alpha;
            full = alpha == 1.0;
            for d in du.iter_mut() {
                *d *= alpha;
            }
            let y: Vec<f64> = problem.residual().iter().zip(&r_old).map(|(a, b)| a - b).collect();
            pairs.push(du.clone(), y);
            self.costs.iterated(iteration_start.elapsed().as_secs_f64());
        }
        // (not reached: the last iteration allowed is out of iterations, whatever its rate)
        Err(IncrementFailure::Diverged {
            iterations: max_iterations + NEAR_MISS_ITERATIONS,
            residual: norm(problem.residual()),
        })
    }
}

/// How far the iterations are from their convergence test, as (now, test), for the cost model
/// ([`Costs::refactorize_pays`]), which assumes both shrink at the residual's rate per
/// iteration (linear convergence): an equilibrium solve converges on its residual,
/// (||r||, tol_residual x force scale); a time integrator's step on its correction
/// ([`IntegratorStep::correction_tolerance`]), so from the last correction `last_step`,
/// (||du||_inf, the step's correction tolerance), unless that tolerance is 0 (a step solved to
/// equilibrium). Judging a step by the equilibrium residual test, which it does not have to
/// pass, counts far more iterations left than it needs and refactorizes where the factor
/// would have converged: on the w = 6 plastic 3D quarter's jump-in (4 nm), 1,237
/// factorizations instead of 876.
fn distance_to_convergence(
    problem: &dyn NonlinearProblem,
    settings: &NewtonSettings,
    residual: f64,
    force_scale: f64,
    last_step: &[f64],
) -> (f64, f64) {
    match problem.integrator_step() {
        Some(step) if step.correction_tolerance > 0.0 => (norm_inf(last_step), step.correction_tolerance),
        _ => (residual, settings.tol_residual * force_scale),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 4 increments after the first failure (the failed one included), then 8, then 16; a
    /// failed (cut) Newton increment does not count.
    #[test]
    fn full_newton_takes_a_doubling_stretch_after_each_failure() {
        let mut stretch = NewtonStretch::default();
        let mut newton_increments = Vec::new();
        for _ in 0..3 {
            stretch.quasi_newton_failed();
            stretch.newton_solved(false);
            let mut count = 0;
            while stretch.left > 0 {
                stretch.newton_solved(true);
                count += 1;
            }
            newton_increments.push(count);
        }
        assert_eq!(newton_increments, [4, 8, 16]);
    }
}

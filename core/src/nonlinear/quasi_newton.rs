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
//! - after `refresh_after` iterations on one factor within an increment.
//! - at every iteration while the tangent is indefinite (an LDL^T factor: softening).
//! So a hard increment degrades to full Newton, never to a crawl; and an increment the
//! quasi-Newton iterations cannot converge is solved again by full Newton before it counts as
//! failed, and the rest of the run uses full Newton (a path hard enough to defeat the
//! quasi-Newton iterations, e.g. a cohesive crack growing, is Newton's ground). Convergence is judged by
//! the same test as Newton's ([`NewtonSettings::converged`]): the criteria are not loosened.

use super::convergence::{NewtonSettings, ReferenceScales, check_iteration};
use super::newton::line_search;
use super::{IncrementFailure, IncrementReport, NonlinearSolver};
use crate::error::Result;
use crate::linear_solver::{FactorKind, LinearSolver};
use crate::problem::NonlinearProblem;
use crate::vector::{dot, norm};
use std::time::Instant;

/// Quasi-Newton (L-BFGS on a reused factor) with refactorization when convergence slows.
#[derive(Debug, Clone)]
pub struct QuasiNewtonSolver {
    pub settings: NewtonSettings,
    /// Refactorize when an iteration leaves more than this fraction of the residual.
    pub slow_ratio: f64,
    /// Whether the linear solver holds a usable factor of a recent tangent.
    factor_ready: bool,
    /// The last tangent was not positive definite (softening): BFGS's curvature condition
    /// fails there, so the iterations refactorize every time (full Newton) until it is again.
    indefinite: bool,
    /// Set by the first increment the quasi-Newton iterations could not converge.
    newton_only: bool,
    costs: Costs,
}

/// The costs that decide when refactorizing pays: measured (seconds), or a fixed ratio.
#[derive(Debug, Clone, Copy, Default)]
struct Costs {
    /// A tangent assembly plus a numeric factorization.
    refactorization: f64,
    /// A quasi-Newton iteration: a solve with the factor and a residual assembly.
    iteration: f64,
    /// When set, refactorization / iteration is this ratio instead of the measured one, so the
    /// solver's choices depend on the residuals only and a run is reproducible to the last digit
    /// (for a given number of threads).
    fixed_ratio: Option<f64>,
}

/// Iterations a refactorized (Newton-like) increment is expected to need.
const ITERATIONS_AFTER_REFACTORIZATION: f64 = 4.0;

impl Costs {
    /// Whether to refactorize now: the iterations left at the observed rate `rate` (residual
    /// ratio per iteration) to bring `residual` to `target` cost more than a refactorization
    /// and the iterations after it, or would not fit in the `budget` of iterations left.
    fn refactorize_pays(&self, rate: f64, residual: f64, target: f64, budget: usize) -> bool {
        if residual <= target {
            return false;
        }
        if !(rate < 1.0) {
            return true;
        }
        let remaining = (target / residual).ln() / rate.ln();
        let (refactorization, iteration) = match self.fixed_ratio {
            Some(ratio) => (ratio, 1.0),
            None => (self.refactorization, self.iteration),
        };
        remaining > budget as f64
            || remaining * iteration > refactorization + ITERATIONS_AFTER_REFACTORIZATION * iteration
    }
}

impl QuasiNewtonSolver {
    pub fn new(settings: NewtonSettings) -> Self {
        Self {
            settings,
            slow_ratio: 0.9,
            factor_ready: false,
            indefinite: false,
            newton_only: false,
            costs: Costs::default(),
        }
    }

    /// The same solver deciding with a fixed cost ratio of a refactorization (tangent assembly
    /// and numeric factorization) to a quasi-Newton iteration (residual assembly and solve)
    /// instead of measured times: reproducible to the last digit for a given thread count.
    pub fn with_cost_ratio(settings: NewtonSettings, ratio: f64) -> Self {
        let mut solver = Self::new(settings);
        solver.costs.fixed_ratio = Some(ratio);
        solver
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

    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> std::result::Result<IncrementReport, IncrementFailure> {
        if self.newton_only {
            return super::newton::solve_increment(problem, linear, t, &self.settings, scales);
        }
        let mut report = IncrementReport::default();
        let result = match self.iterate(problem, linear, t, scales, &mut report) {
            Ok(()) => Ok(report),
            Err(IncrementFailure::Diverged { iterations, .. }) => {
                // not a crawl, not a cut: the same increment by full Newton from the committed
                // state, and full Newton for the rest of the run (the path has become hard);
                // the report counts both attempts
                self.newton_only = true;
                problem.rollback();
                super::newton::solve_increment(problem, linear, t, &self.settings, scales).map(|mut newton| {
                    newton.iterations += iterations;
                    newton.factorizations += report.factorizations;
                    newton.assembly_seconds += report.assembly_seconds;
                    newton.factorization_seconds += report.factorization_seconds;
                    newton.solve_seconds += report.solve_seconds;
                    newton
                })
            }
            Err(e) => Err(e),
        };
        // a failed increment may have left a factor of a state far from the next attempt's
        self.factor_ready = result.is_ok();
        result
    }
}

impl QuasiNewtonSolver {
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
        self.costs.refactorization = timer.elapsed().as_secs_f64();
        self.factor_ready = true;
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
        let with_tangent = !self.factor_ready;
        problem.assemble(with_tangent)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        if with_tangent {
            self.refactorize(problem, linear, report, false)?;
        }
        let n = problem.n_free();
        let mut pairs = Pairs::default();
        let (mut du, mut r_old) = (vec![0.0; n], vec![0.0; n]);
        for iteration in 0..=settings.max_iterations {
            let check =
                check_iteration(&settings, problem, scales, iteration, &du, &start_u, &mut report.residual_norms);
            if check.converged {
                report.iterations = iteration;
                return Ok(());
            }
            let (r_norm, force_scale) = (check.residual, check.force_scale);
            if iteration == settings.max_iterations {
                break;
            }
            if iteration > 0 {
                let rate = r_norm / report.residual_norms[iteration - 1];
                let target = settings.tol_residual * force_scale;
                let budget =
                    settings.max_iterations.saturating_sub(iteration + ITERATIONS_AFTER_REFACTORIZATION as usize);
                if self.indefinite
                    || rate > self.slow_ratio
                    || self.costs.refactorize_pays(rate, r_norm, target, budget)
                {
                    self.refactorize(problem, linear, report, true)?;
                    pairs.clear();
                }
            }
            let iteration_start = Instant::now();
            let timer = Instant::now();
            r_old.copy_from_slice(problem.residual());
            pairs.apply(linear, &r_old, &mut du)?;
            for d in du.iter_mut() {
                *d = -*d;
            }
            report.solve_seconds += timer.elapsed().as_secs_f64();
            let timer = Instant::now();
            let alpha = line_search(problem, &du, r_norm, &settings, false);
            report.assembly_seconds += timer.elapsed().as_secs_f64();
            let alpha = alpha?;
            for d in du.iter_mut() {
                *d *= alpha;
            }
            let y: Vec<f64> = problem.residual().iter().zip(&r_old).map(|(a, b)| a - b).collect();
            pairs.push(du.clone(), y);
            let elapsed = iteration_start.elapsed().as_secs_f64();
            self.costs.iteration =
                if self.costs.iteration > 0.0 { 0.8 * self.costs.iteration + 0.2 * elapsed } else { elapsed };
        }
        Err(IncrementFailure::Diverged { iterations: settings.max_iterations, residual: norm(problem.residual()) })
    }
}

//! Newton-Raphson with the consistent tangent, backtracking line search, and an incrementation
//! controller that cuts failed steps and grows easy ones.
//!
//! Convergence of an increment: ||r|| <= tol_residual * max(||f_int||, ||f_ext||, q_ref,
//! force_floor) and ||du|| <= tol_displacement * max(||u - u_committed||, 1e-3 ||u||,
//! displacement_floor); an increment whose residual is already below 1e-3 of that tolerance is
//! accepted without the second test. q_ref is the caller's time-averaged force norm over the
//! converged increments (ABAQUS's time-averaged force): without it a body whose load has
//! dropped to nearly zero (a cohesive interface near complete failure) would be held to a
//! residual below the round-off of its element forces.

use crate::error::{CoreError, Result};
use crate::linear_solver::SparseSolver;
use crate::model::Model;
use std::time::Instant;

/// Newton settings.
#[derive(Debug, Clone)]
pub struct NewtonSettings {
    pub max_iterations: usize,
    pub tol_residual: f64,
    pub tol_displacement: f64,
    /// Absolute force below which residuals count as zero (units of force).
    pub force_floor: f64,
    /// Absolute displacement below which corrections count as zero (units of length).
    pub displacement_floor: f64,
    pub line_search: bool,
    pub max_line_search: usize,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        Self {
            max_iterations: 25,
            tol_residual: 1e-8,
            tol_displacement: 1e-6,
            force_floor: 1e-12,
            displacement_floor: 1e-14,
            line_search: true,
            max_line_search: 6,
        }
    }
}

/// What one converged increment took.
#[derive(Debug, Clone, Default)]
pub struct IncrementReport {
    pub iterations: usize,
    /// ||r|| before each solve and at convergence.
    pub residual_norms: Vec<f64>,
    pub assembly_seconds: f64,
    pub factorization_seconds: f64,
    pub solve_seconds: f64,
}

/// The scales convergence is measured against (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct ReferenceScales {
    /// ||u|| at the last converged increment.
    pub displacement: f64,
    /// Time-averaged force norm over the converged increments so far (q_ref).
    pub force: f64,
}

/// Why an increment failed (the caller cuts the step).
#[derive(Debug)]
pub enum IncrementFailure {
    Diverged { iterations: usize, residual: f64 },
    Error(CoreError),
}

impl std::fmt::Display for IncrementFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IncrementFailure::Diverged { iterations, residual } => {
                write!(f, "no convergence after {iterations} iterations (residual {residual:.3e})")
            }
            IncrementFailure::Error(e) => write!(f, "{e}"),
        }
    }
}

impl From<CoreError> for IncrementFailure {
    fn from(e: CoreError) -> Self {
        IncrementFailure::Error(e)
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Solves equilibrium at pseudo-time `t` starting from the model's current (committed) state.
/// On success the model holds the converged trial state (not yet committed).
pub fn solve_increment(
    model: &mut Model,
    solver: &mut SparseSolver,
    t: f64,
    settings: &NewtonSettings,
    scales: ReferenceScales,
) -> std::result::Result<IncrementReport, IncrementFailure> {
    let mut report = IncrementReport::default();
    let start_u: Vec<f64> = model.displacement.clone();
    model.apply_time(t);
    let timer = Instant::now();
    model.assemble(true)?;
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    let mut du = vec![0.0; model.n_free()];
    for iteration in 0..=settings.max_iterations {
        let r_norm = norm(&model.residual);
        let force_scale =
            norm(&model.internal_force).max(norm(&model.external_force)).max(scales.force).max(settings.force_floor);
        report.residual_norms.push(r_norm);
        let residual_ok = r_norm <= settings.tol_residual * force_scale;
        if iteration > 0 || r_norm <= 1e-3 * settings.tol_residual * force_scale {
            let step_norm = model
                .displacement
                .iter()
                .zip(&start_u)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
                .max(scales.displacement * 1e-3)
                .max(settings.displacement_floor);
            let du_ok = norm(&du) <= settings.tol_displacement * step_norm;
            if residual_ok && (du_ok || r_norm <= 1e-3 * settings.tol_residual * force_scale) {
                report.iterations = iteration;
                return Ok(report);
            }
        }
        if iteration == settings.max_iterations {
            break;
        }
        let timer = Instant::now();
        solver.factorize(model.pattern(), &model.tangent_values)?;
        report.factorization_seconds += timer.elapsed().as_secs_f64();
        let timer = Instant::now();
        for (d, r) in du.iter_mut().zip(&model.residual) {
            *d = -r;
        }
        solver.solve_in_place(&mut du)?;
        report.solve_seconds += timer.elapsed().as_secs_f64();
        // Line search on ||r(u + alpha du)||.
        let timer = Instant::now();
        let mut alpha = 1.0;
        model.update_free(&du, alpha);
        let first = model.assemble(true);
        let mut accepted = matches!(first, Ok(_)) && norm(&model.residual) < r_norm * (1.0 - 1e-4);
        if !accepted && settings.line_search {
            let mut previous = alpha;
            let mut trial_norm = if first.is_ok() { norm(&model.residual) } else { f64::INFINITY };
            for _ in 0..settings.max_line_search {
                // Quadratic model of ||r||^2 along the search direction, safeguarded to [0.1, 0.5].
                let next = if trial_norm.is_finite() {
                    let (g0, g1) = (r_norm * r_norm, trial_norm * trial_norm);
                    let a = previous * previous * g0 / (g1 + g0 * (2.0 * previous - 1.0)).max(1e-300);
                    a.clamp(0.1 * previous, 0.5 * previous)
                } else {
                    0.25 * previous
                };
                model.update_free(&du, next - previous);
                previous = next;
                alpha = next;
                trial_norm = if model.assemble(false).is_ok() { norm(&model.residual) } else { f64::INFINITY };
                if trial_norm < r_norm * (1.0 - 1e-4 * alpha) {
                    accepted = true;
                    break;
                }
            }
            if accepted {
                model.assemble(true)?;
            }
        } else if let Err(e) = first {
            report.assembly_seconds += timer.elapsed().as_secs_f64();
            return Err(e.into());
        }
        if !accepted {
            // Keep the full Newton step: quadratic convergence may still follow (and a
            // material failure at the full step is reported as such).
            model.update_free(&du, 1.0 - alpha);
            model.assemble(true)?;
        }
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        for d in du.iter_mut() {
            *d *= alpha;
        }
    }
    Err(IncrementFailure::Diverged { iterations: settings.max_iterations, residual: norm(&model.residual) })
}

/// Incrementation: initial, minimum and maximum increments in pseudo-time, with cutting on
/// failure and growth after easy increments.
#[derive(Debug, Clone)]
pub struct Incrementation {
    pub initial: f64,
    pub minimum: f64,
    pub maximum: f64,
    /// Factor applied after a failed increment.
    pub cut_factor: f64,
    /// Factor applied after an increment that converged in at most `easy_iterations`.
    pub growth_factor: f64,
    pub easy_iterations: usize,
}

impl Incrementation {
    pub fn validate(&self) -> Result<()> {
        let ok = self.minimum > 0.0
            && self.initial >= self.minimum
            && self.maximum >= self.initial
            && self.cut_factor > 0.0
            && self.cut_factor < 1.0
            && self.growth_factor >= 1.0;
        if ok {
            Ok(())
        } else {
            Err(CoreError::Invalid(format!(
                "incrementation needs 0 < minimum <= initial <= maximum, 0 < cut < 1, growth >= 1 (got {self:?})"
            )))
        }
    }
}

//! Settings of the nonlinear solvers and the one convergence test they all use.
//!
//! An increment has converged when ||r|| <= tol_residual * F and
//! ||c|| <= tol_displacement * max(||du_increment||, 1e-3 ||u||, displacement_floor), with
//! F = max(||f_int||, ||f_ext||, q_ref, force_floor) and c the last correction; a residual
//! below 1e-3 of its tolerance is accepted without the second test. q_ref is the caller's
//! time-averaged force norm over the converged increments (ABAQUS's time-averaged force):
//! without it a body whose load has dropped to nearly zero (a cohesive interface near complete
//! failure) would be held to a residual below the round-off of its element forces.
//!
//! An increment whose residual has stopped falling is abandoned before its iteration limit:
//! from iteration [`NewtonSettings::stagnation_iterations`] (8) on, when ||r|| fell by less than
//! [`STAGNATION_FALL`] (5%) over the last [`STAGNATION_WINDOW`] (3) iterations (ABAQUS abandons
//! an increment on its residuals' trend from its 8th iteration, I_R, too). Such an increment
//! has no equilibrium near its start (a fold, a contact front that cannot settle): running it
//! to the iteration limit costs as much as the rest of a snap-heavy run, and cutting it lets the
//! path go on in shorter increments. The rule gives up a few increments that would have
//! converged late; they are cut and solved again.
//!
//! An increment still falling steadily at its iteration limit is a near miss, not a failure:
//! where its residuals' rate over the last [`STAGNATION_WINDOW`] iterations, rho, predicts
//! both tests passed within [`NEAR_MISS_ITERATIONS`] more (n = ln(test / now) / ln rho for the
//! residual and for the correction, each shrinking at rho), the iterations go on, as long as
//! the prediction holds and at most that many past the limit (ABAQUS's logarithmic rate check,
//! which lets an increment run past I_R while convergence is predicted within I_C, does the
//! same). Near a fold Newton converges only linearly, and such attempts end at residuals within
//! the range converged increments end at; cutting them would solve the same state again in
//! shorter increments.
//!
//! A step of a time integrator (a damped flow's) needs less: it also counts as converged at a
//! full correction within its own tolerance, and is given up at its own iteration limit
//! ([`crate::problem::IntegratorStep`]).

/// Nonlinear solver settings; `Default` is the single source of the defaults that case files
/// and the command-line help quote.
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
    /// Iterations after which an increment whose residual has stopped falling is abandoned
    /// (see the module documentation); 0: never, only `max_iterations` ends it.
    pub stagnation_iterations: usize,
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
            stagnation_iterations: 8,
        }
    }
}

/// The scales convergence is measured against (see the module documentation).
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
pub struct ReferenceScales {
    /// ||u|| at the last converged increment.
    pub displacement: f64,
    /// Time-averaged force norm over the converged increments so far (q_ref).
    pub force: f64,
}

impl NewtonSettings {
    /// F = max(force_norm, q_ref, force_floor).
    pub fn force_scale(&self, force_norm: f64, scales: ReferenceScales) -> f64 {
        force_norm.max(scales.force).max(self.force_floor)
    }

    /// ||r|| <= tol_residual F.
    pub fn residual_converged(&self, residual: f64, force_scale: f64) -> bool {
        residual <= self.tol_residual * force_scale
    }

    /// ||r|| <= 1e-3 tol_residual F: converged whatever the correction.
    pub fn residual_negligible(&self, residual: f64, force_scale: f64) -> bool {
        residual <= 1e-3 * self.tol_residual * force_scale
    }

    /// max(||du_increment||, 1e-3 ||u||, displacement_floor): what the correction is measured
    /// against.
    pub fn correction_scale(&self, increment_size: f64, scales: ReferenceScales) -> f64 {
        increment_size.max(scales.displacement * 1e-3).max(self.displacement_floor)
    }

    /// The whole test: residual, and correction against the size of the increment.
    pub fn converged(
        &self,
        residual: f64,
        force_scale: f64,
        correction: f64,
        increment_size: f64,
        scales: ReferenceScales,
    ) -> bool {
        let size = self.correction_scale(increment_size, scales);
        self.residual_converged(residual, force_scale)
            && (correction <= self.tol_displacement * size || self.residual_negligible(residual, force_scale))
    }
}

/// Iterations over which a stagnating residual is judged.
pub const STAGNATION_WINDOW: usize = 3;
/// The least relative fall of ||r|| over [`STAGNATION_WINDOW`] iterations: less is stagnation.
pub const STAGNATION_FALL: f64 = 0.05;

/// Iterations an equilibrium increment may run past its limit while its rate predicts
/// convergence within them (a near miss, see the module documentation).
pub const NEAR_MISS_ITERATIONS: usize = 5;

/// The state of one iteration as the convergence test sees it.
pub(crate) struct IterationCheck {
    pub residual: f64,
    pub force_scale: f64,
    pub converged: bool,
    /// Set when the iteration has not converged and stagnates (see the module documentation):
    /// the failure that abandons the increment.
    pub stagnated: Option<super::IncrementFailure>,
    /// Iterations left to pass both tests at the residual's rate over the last
    /// [`STAGNATION_WINDOW`] iterations (see [`iterations_left`]); None for a converged
    /// iteration, one too early to judge, one not falling, or a time integrator's step.
    pub iterations_left: Option<f64>,
}

impl IterationCheck {
    /// Whether an unconverged iteration `iteration` ends the increment: at `max_iterations`,
    /// unless the rate predicts convergence within the [`NEAR_MISS_ITERATIONS`] past it that
    /// are left.
    pub fn out_of_iterations(&self, iteration: usize, max_iterations: usize) -> bool {
        if iteration < max_iterations {
            return false;
        }
        let left = (max_iterations + NEAR_MISS_ITERATIONS).saturating_sub(iteration) as f64;
        !self.iterations_left.is_some_and(|n| n <= left)
    }
}

/// n = max(ln(tol_r F / ||r||), ln(tol_d size / ||c||)) / ln rho, at least 1, with
/// rho = (||r_i|| / ||r_{i-3}||)^(1/3) the residual's rate over the last [`STAGNATION_WINDOW`]
/// iterations: the iterations left to pass the residual and the correction test (see
/// [`NewtonSettings::converged`]) if both keep shrinking at that rate (linear convergence;
/// Newton converging quadratically does better). None before the window is full or where
/// ||r|| did not fall.
fn iterations_left(
    settings: &NewtonSettings,
    norms: &[f64],
    force_scale: f64,
    correction: f64,
    size: f64,
) -> Option<f64> {
    let i = norms.len().checked_sub(1)?;
    let earlier = norms[i.checked_sub(STAGNATION_WINDOW)?];
    let rate = (norms[i] / earlier).powf(1.0 / STAGNATION_WINDOW as f64);
    if !(rate > 0.0 && rate < 1.0) {
        return None;
    }
    let needed = |now: f64, test: f64| if now <= test { 0.0 } else { (test / now).ln() / rate.ln() };
    let residual = needed(norms[i], settings.tol_residual * force_scale);
    let correction = needed(correction, settings.tol_displacement * size);
    Some(residual.max(correction).ceil().max(1.0))
}

/// Stagnation at iteration `iteration` of a fixed-time increment with residual norms `norms`
/// (the initial one first): from `settings.stagnation_iterations` on, ||r_i|| >
/// (1 - [`STAGNATION_FALL`]) ||r_{i-3}||. A time integrator's step has its own, shorter limit
/// and is not judged.
fn stagnation(
    settings: &NewtonSettings,
    problem: &dyn crate::problem::NonlinearProblem,
    iteration: usize,
    norms: &[f64],
) -> Option<super::IncrementFailure> {
    let first = settings.stagnation_iterations.max(STAGNATION_WINDOW);
    if settings.stagnation_iterations == 0 || iteration < first || problem.integrator_step().is_some() {
        return None;
    }
    let (residual, earlier) = (norms[iteration], norms[iteration - STAGNATION_WINDOW]);
    (residual > (1.0 - STAGNATION_FALL) * earlier).then_some(super::IncrementFailure::Stagnated {
        iterations: iteration,
        residual,
        earlier,
    })
}

/// The last correction of a fixed-time iteration: the step taken, and whether it was the full
/// solver direction (no line-search cut).
pub(crate) struct Correction<'a> {
    pub step: &'a [f64],
    pub full: bool,
}

/// Applies the test at a fixed-time iteration: ||r|| is recorded in `residual_norms`; at
/// iteration 0 only a negligible residual counts (no correction has been made yet); the
/// increment size is ||u - u_start||. A step of a time integrator
/// ([`NonlinearProblem::integrator_step`](crate::problem::NonlinearProblem::integrator_step))
/// also accepts a full correction within its tolerance that reduced ||r||.
pub(crate) fn check_iteration(
    settings: &NewtonSettings,
    problem: &dyn crate::problem::NonlinearProblem,
    scales: ReferenceScales,
    iteration: usize,
    correction: Correction,
    start: &[f64],
    residual_norms: &mut Vec<f64>,
) -> IterationCheck {
    let residual = crate::vector::norm(problem.residual());
    let force_scale = settings.force_scale(problem.force_norm(), scales);
    residual_norms.push(residual);
    // a full correction that did not reduce ||r|| is no sign of being close
    let accurate_enough = iteration > 0
        && correction.full
        && residual_norms.len() >= 2
        && residual < residual_norms[residual_norms.len() - 2]
        && problem
            .integrator_step()
            .is_some_and(|step| crate::vector::norm_inf(correction.step) <= step.correction_tolerance);
    let step = crate::vector::distance(problem.solution(), start);
    let correction_norm = crate::vector::norm(correction.step);
    let converged = accurate_enough
        || (iteration > 0 || settings.residual_negligible(residual, force_scale))
            && settings.converged(residual, force_scale, correction_norm, step, scales);
    let stagnated = if converged { None } else { stagnation(settings, problem, iteration, residual_norms) };
    let iterations_left = (!converged && problem.integrator_step().is_none())
        .then(|| {
            let size = settings.correction_scale(step, scales);
            iterations_left(settings, residual_norms, force_scale, correction_norm, size)
        })
        .flatten();
    IterationCheck { residual, force_scale, converged, stagnated, iterations_left }
}

/// The iteration limit for `problem`: the settings', or a time integrator step's own when lower.
pub(crate) fn iteration_limit(settings: &NewtonSettings, problem: &dyn crate::problem::NonlinearProblem) -> usize {
    problem.integrator_step().map_or(settings.max_iterations, |step| step.max_iterations.min(settings.max_iterations))
}

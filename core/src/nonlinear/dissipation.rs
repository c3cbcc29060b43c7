//! Dissipation-based path following (Gutierrez 2004; Verhoosel, Remmers & Gutierrez 2009) for
//! damage: each increment from the committed state (u0, t0) dissipates a prescribed energy,
//!   R(u0 + du, t0 + dt) = 0   and   dD(u0 + du, t0 + dt) = tau,
//! where dD is the problem's damage dissipation ([`NonlinearProblem::damage_dissipation`]:
//! 1/2 sum_p w_p (v_p g_c,p - v_c,p g_p) over the interface points of secant-unloading laws).
//! Damage never heals, so the constraint orients itself: where a crack snaps back (the
//! prescribed displacement or load must decrease while the crack opens) dt turns negative
//! by itself, and no increment can go back along the path. Unlike an arc length in the
//! displacement norm, which the elastic bulk dominates, the constraint sees only the process
//! zone, so a localized failure is followed too.
//!
//! Each Newton iteration solves K a = -R and K b = -dR/dt with one factorization, sets the
//! correction to a + dl b and takes dl from the linearized constraint:
//!   dl = -(dD - tau + dD_u . a) / (dD_u . b + dD_t).
//! The predictor is the caller's (the previous increment, scaled).

use super::arc_length::PreviousIncrement;
use super::bordered::bordered_solves;
use super::convergence::{NewtonSettings, ReferenceScales};
use super::{IncrementFailure, IncrementReport};
use crate::error::CoreError;
use crate::linear_solver::LinearSolver;
use crate::problem::NonlinearProblem;
use crate::vector::{dot, norm};
use std::time::Instant;

/// The constraint's relative tolerance: |dD - tau| <= this * tau at convergence. The
/// constraint only sets the increment's length (every state that satisfies R = 0 is on the
/// path), so it is not held to the equilibrium tolerance.
pub const ENERGY_TOLERANCE: f64 = 1e-3;

/// One dissipation-controlled increment's request: dissipate `energy` from the committed state
/// at `t0`, starting from the `predictor` increment; `rate_step` is the step of the central
/// differences for dR/dt (as in [`super::arc_length::ArcLengthRequest`]).
#[derive(Debug, Clone, Copy)]
pub struct DissipationRequest<'a> {
    pub t0: f64,
    pub energy: f64,
    pub predictor: &'a PreviousIncrement,
    pub rate_step: f64,
}

/// A converged increment: the report, the increment and the energy it dissipated.
pub type DissipationIncrement = (IncrementReport, PreviousIncrement, f64);

/// The damage dissipation at the problem's trial state and its gradient, or `NoDissipation`
/// when the problem reports none.
fn dissipation(problem: &dyn NonlinearProblem, gradient: &mut [f64]) -> Result<(f64, f64), IncrementFailure> {
    gradient.fill(0.0);
    problem.damage_dissipation(gradient).ok_or(IncrementFailure::NoDissipation)
}

/// The damage dissipation of the increment `predictor` from the committed state at `t0`
/// (the problem is left at that trial state): how much a step like it would dissipate.
pub fn dissipation_of(
    problem: &mut dyn NonlinearProblem,
    t0: f64,
    predictor: &PreviousIncrement,
) -> Result<f64, IncrementFailure> {
    let u: Vec<f64> = problem.free_values().iter().zip(&predictor.du).map(|(a, b)| a + b).collect();
    problem.set_time(t0 + predictor.dt);
    problem.set_free_values(&u);
    problem.assemble(false)?;
    let mut gradient = vec![0.0; problem.n_free()];
    Ok(dissipation(problem, &mut gradient)?.0)
}

/// Solves one dissipation-controlled increment (see the module documentation). On success
/// the problem holds the converged trial state (not committed). `NoDissipation` when the
/// constraint has no gradient: nothing within reach of the increment is damaging (before the
/// first damage, or after the last point has failed).
pub fn solve_dissipation_increment(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    request: DissipationRequest<'_>,
    settings: &NewtonSettings,
    scales: ReferenceScales,
) -> Result<DissipationIncrement, IncrementFailure> {
    let DissipationRequest { t0, energy, predictor, rate_step } = request;
    let n = problem.n_free();
    let mut report = IncrementReport::default();
    problem.set_time(t0);
    let u0 = problem.free_values();
    let (mut du, mut dt) = (predictor.du.clone(), predictor.dt);
    let (mut a, mut b, mut gradient) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for iteration in 0..=settings.max_iterations {
        let timer = Instant::now();
        let u: Vec<f64> = u0.iter().zip(&du).map(|(x, y)| x + y).collect();
        problem.set_time(t0 + dt);
        problem.set_free_values(&u);
        problem.assemble(true)?;
        // the dissipation reads the trial state of this assembly: before the rate's assemblies
        let (dissipated, rate_in_time) = dissipation(problem, &mut gradient)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        let r_norm = norm(problem.residual());
        report.residual_norms.push(r_norm);
        let force_scale = settings.force_scale(problem.force_norm(), scales);
        let excess = dissipated - energy;
        if iteration > 0
            && settings.converged(r_norm, force_scale, norm(&a), norm(&du), scales)
            && excess.abs() <= ENERGY_TOLERANCE * energy
        {
            report.iterations = iteration;
            return Ok((report, PreviousIncrement { du, dt }, dissipated));
        }
        if iteration == settings.max_iterations {
            break;
        }
        bordered_solves(problem, linear, t0 + dt, rate_step, (&mut a, &mut b), &mut report)?;
        let slope = dot(&gradient, &b) + rate_in_time;
        let scale = norm(&gradient) * norm(&b) + rate_in_time.abs();
        if !(slope.abs() > 1e-12 * scale) {
            // no point is damaging: the constraint cannot set the increment
            return Err(IncrementFailure::NoDissipation);
        }
        let dl = -(excess + dot(&gradient, &a)) / slope;
        for ((d, ai), bi) in du.iter_mut().zip(a.iter_mut()).zip(&b) {
            *ai += dl * bi;
            *d += *ai;
        }
        dt += dl;
        if !dt.is_finite() || du.iter().any(|x| !x.is_finite()) {
            return Err(CoreError::NonFinite("dissipation-controlled increment".into()).into());
        }
    }
    Err(IncrementFailure::Diverged { iterations: settings.max_iterations, residual: norm(problem.residual()) })
}

//! Settling on a stable equilibrium at a fixed load where Newton, started from the last one,
//! cannot: the path has no nearby equilibrium left (an adhesive surface snapping into contact
//! or off it, a run started inside the jump-in range). The residual R(u) is the gradient of the
//! (incremental) potential energy, so a stable equilibrium is a local minimum, found by a
//! descent method that needs only R and K:
//! - direction: d = -(K + mu D)^{-1} R with D = |diag K| at the start and the shift mu >= 0
//!   the smallest of 0, mu0, 4 mu0, ... for which K + mu D factors as positive definite
//!   (Levenberg-Marquardt): d is then a descent direction, R.d < 0;
//! - K is the convex part of the tangent ([`NonlinearProblem::assemble_convex`]: the interface
//!   points of negative normal stiffness, an attractive tail or a softening branch, left out):
//!   those points' pull acts as a load the rest resists, instead of a negative curvature that
//!   only a large shift can mend. Where the shift has fallen to 0, the full tangent is tried
//!   (Newton near a stable state), and dropped for 2, 4, 8, 8, ... steps whenever it is not
//!   positive definite. On the smooth w = 6 Lennard-Jones sphere started inside the
//!   jump-in range, with the full tangent throughout this took 119 steps on the 2 nm contact
//!   mesh and did not converge within [`MAX_STEPS`] on the 1 nm one (53,032 dofs);
//! - step: alpha along d where the energy stops falling, g(alpha) = R(u + alpha d).d = 0 (a
//!   critical-point line search: PETSc's "cp"), found by expanding alpha while g < 0 (up to
//!   [`MAX_EXPANSION`]) and then by regula falsi (Illinois) on the bracket, accepting
//!   |g(alpha)| <= 0.5 |g(0)|;
//! - mu grows tenfold after a step the line search cut below 1/4 of d (the quadratic model is
//!   poor that far out) and shrinks tenfold after one beyond 3/4 (towards Newton), and grows
//!   while the factor is indefinite.
//! Near a stable solution K is positive definite, mu = 0 and alpha = 1: Newton's quadratic
//! convergence. Convergence is judged by the solver's usual test. The state found is the one a
//! displacement-controlled system snaps to; the energy released is what the snap dissipates.

use super::convergence::{NewtonSettings, ReferenceScales};
use super::{IncrementFailure, IncrementReport};
use crate::linear_solver::{FactorKind, LinearSolver};
use crate::problem::NonlinearProblem;
use crate::vector::{dot, norm};
use std::time::Instant;

/// Descent steps at most.
pub const MAX_STEPS: usize = 200;
/// The largest step along a direction, in units of the direction.
pub const MAX_EXPANSION: f64 = 16.0;
/// The first nonzero shift (relative to D).
const MU_FIRST: f64 = 1e-4;
/// The largest shift (the direction is then a scaled gradient).
const MU_MAX: f64 = 1e8;
/// Shifts tried per step before giving up on a positive definite factor.
const MAX_SHIFTS: usize = 24;
/// The longest wait before the full tangent is tried again (each try that fails costs a
/// factorization).
const MAX_FULL_TANGENT_WAIT: usize = 8;
/// Line-search evaluations per step.
const MAX_LINE_SEARCH: usize = 12;

/// Which tangent the next direction is computed with (see the module documentation).
#[derive(Debug, Default)]
struct TangentChoice {
    /// The full tangent (else its convex part).
    full: bool,
    /// Steps before the full tangent is tried again.
    wait: usize,
    /// How long the next failure of the full tangent makes it wait.
    backoff: usize,
}

impl TangentChoice {
    /// Chooses for the next step: the full tangent when the shift is 0 and it is not waiting.
    fn next_step(&mut self, unshifted: bool) {
        self.wait = self.wait.saturating_sub(1);
        self.full = unshifted && self.wait == 0;
    }

    /// The full tangent was not positive definite: the convex part, for a doubling wait.
    fn full_failed(&mut self) {
        self.full = false;
        self.backoff = (2 * self.backoff).clamp(2, MAX_FULL_TANGENT_WAIT);
        self.wait = self.backoff;
    }

    /// Assembles the residual and the chosen tangent.
    fn assemble(&self, problem: &mut dyn NonlinearProblem, report: &mut IncrementReport) -> crate::error::Result<()> {
        let timer = Instant::now();
        if self.full { problem.assemble(true) } else { problem.assemble_convex() }?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        Ok(())
    }
}

/// Indices of the diagonal entries in the pattern's values (None where a column has none).
fn diagonal_slots(problem: &dyn NonlinearProblem) -> Vec<Option<usize>> {
    let p = problem.pattern();
    (0..p.n).map(|j| (p.col_ptr[j]..p.col_ptr[j + 1]).find(|&k| p.row_idx[k] == j)).collect()
}

/// g(alpha) = R(u0 + alpha d).d, leaving the problem at u0 + alpha d.
fn slope(problem: &mut dyn NonlinearProblem, u0: &[f64], d: &[f64], alpha: f64) -> Result<f64, IncrementFailure> {
    let u: Vec<f64> = u0.iter().zip(d).map(|(a, b)| a + alpha * b).collect();
    problem.set_free_values(&u);
    problem.assemble(false)?;
    let g = dot(problem.residual(), d);
    Ok(if g.is_finite() { g } else { f64::INFINITY })
}

/// Relative accuracy of the energy a settle reports ([`released_between`]).
const ENERGY_TOLERANCE: f64 = 1e-5;
/// Intervals of Simpson's rule at most ([`released_between`]): residual assemblies + 1.
const ENERGY_MAX_INTERVALS: usize = 64;

/// The energy released from `u0` to `u1`: -int_0^1 g(s) ds with g(s) = R(u0 + s d).d,
/// d = u1 - u0, by Simpson's rule on 2, 4, 8, ... equal intervals (each doubling reuses the
/// slopes already evaluated) until two in a row agree within 15 x `ENERGY_TOLERANCE` of the
/// integral of |g| (their difference is then 15 times the finer one's error; at most
/// [`ENERGY_MAX_INTERVALS`], with Richardson's correction). The residual is the gradient of
/// the (incremental) potential energy, the history frozen at the committed state, so this is
/// the potential's fall whatever path the descent took; the straight segment integrates it
/// more accurately than the descent's own long steps would. Leaves the problem's free values
/// at `u1` (not assembled).
fn released_between(problem: &mut dyn NonlinearProblem, u0: &[f64], u1: &[f64]) -> Result<f64, IncrementFailure> {
    let d: Vec<f64> = u1.iter().zip(u0).map(|(a, b)| a - b).collect();
    let mut slopes = vec![slope(problem, u0, &d, 0.0)?, slope(problem, u0, &d, 0.5)?, slope(problem, u0, &d, 1.0)?];
    let simpson = |g: &[f64]| {
        let n = g.len() - 1;
        let inner: f64 = (1..n).map(|k| if k % 2 == 1 { 4.0 * g[k] } else { 2.0 * g[k] }).sum();
        (g[0] + inner + g[n]) / (3.0 * n as f64)
    };
    let mut coarse = simpson(&slopes);
    loop {
        let n = 2 * (slopes.len() - 1);
        let mut finer = Vec::with_capacity(n + 1);
        for (k, &g) in slopes.iter().enumerate() {
            if k > 0 {
                finer.push(slope(problem, u0, &d, (2 * k - 1) as f64 / n as f64)?);
            }
            finer.push(g);
        }
        slopes = finer;
        let fine = simpson(&slopes);
        let scale = slopes.iter().map(|g| g.abs()).sum::<f64>() / n as f64;
        let converged = (fine - coarse).abs() <= 15.0 * ENERGY_TOLERANCE * scale;
        if converged || n >= ENERGY_MAX_INTERVALS || !fine.is_finite() {
            problem.set_free_values(u1);
            return Ok(-(fine + (fine - coarse) / 15.0));
        }
        coarse = fine;
    }
}

/// The step along `d` from `u0` where the energy stops falling (see the module documentation);
/// `g0` = R(u0).d < 0. Leaves the problem at the accepted point.
fn critical_point(problem: &mut dyn NonlinearProblem, u0: &[f64], d: &[f64], g0: f64) -> Result<f64, IncrementFailure> {
    let (mut lo, mut g_lo) = (0.0, g0);
    let mut hi = 1.0;
    let mut g_hi = slope(problem, u0, d, hi)?;
    // still falling at the end: go further while it keeps falling
    while g_hi < 0.0 && hi < MAX_EXPANSION {
        (lo, g_lo) = (hi, g_hi);
        hi *= 2.0;
        g_hi = slope(problem, u0, d, hi)?;
    }
    if g_hi < 0.0 {
        return Ok(hi);
    }
    if g_hi.abs() <= 0.5 * g0.abs() {
        return Ok(hi);
    }
    // regula falsi (Illinois) on [lo, hi] with g(lo) < 0 < g(hi); an infinite g(hi) bisects
    let mut side = 0;
    let mut alpha = hi;
    for _ in 0..MAX_LINE_SEARCH {
        alpha = if g_hi.is_finite() { (lo * g_hi - hi * g_lo) / (g_hi - g_lo) } else { 0.5 * (lo + hi) };
        let g = slope(problem, u0, d, alpha)?;
        if g.abs() <= 0.5 * g0.abs() {
            return Ok(alpha);
        }
        if g < 0.0 {
            (lo, g_lo) = (alpha, g);
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            (hi, g_hi) = (alpha, g);
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
    }
    // the best point found that still lowers the energy (the problem is left at the returned
    // step: the last evaluation was at `alpha`)
    if lo > 0.0 {
        slope(problem, u0, d, lo)?;
        Ok(lo)
    } else {
        Ok(alpha)
    }
}

/// A settled state's costs and the energy the descent released on its way there.
#[derive(Debug, Clone, Default)]
pub struct Settled {
    pub report: IncrementReport,
    /// -int R.du from the start to the settled state, by Simpson's rule along the straight
    /// segment between them, refined to a relative 1e-5 (`released_between`): the fall of the
    /// (incremental) potential energy, what the snap dissipates besides the one-step plastic
    /// update.
    pub released_energy: f64,
}

/// Settles the problem at its current time from its current trial state (see the module
/// documentation). On success the problem holds the converged trial state (not committed).
pub fn settle(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    newton: &NewtonSettings,
    scales: ReferenceScales,
) -> Result<Settled, IncrementFailure> {
    let origin = problem.free_values();
    let mut report = IncrementReport::default();
    let mut tangent = TangentChoice::default();
    tangent.assemble(problem, &mut report)?;
    let slots = diagonal_slots(problem);
    let largest = slots.iter().flatten().map(|&k| problem.tangent()[k].abs()).fold(0.0, f64::max);
    let lumped: Vec<f64> =
        slots.iter().map(|s| s.map_or(largest, |k| problem.tangent()[k].abs()).max(1e-12 * largest)).collect();
    let mut mu = 0.0f64;
    let mut step_taken: Vec<f64> = Vec::new();
    let mut shifted: Vec<f64> = Vec::new();
    for step in 0..=MAX_STEPS {
        let r_norm = norm(problem.residual());
        report.residual_norms.push(r_norm);
        let force_scale = newton.force_scale(problem.force_norm(), scales);
        let converged = if step == 0 {
            newton.residual_negligible(r_norm, force_scale)
        } else {
            newton.converged(r_norm, force_scale, norm(&step_taken), norm(problem.solution()), scales)
        };
        if converged {
            report.iterations = step;
            if step == 0 {
                // at rest where it started: nothing released
                return Ok(Settled { report, released_energy: 0.0 });
            }
            let settled = problem.free_values();
            let timer = Instant::now();
            let released_energy = released_between(problem, &origin, &settled)?;
            report.assembly_seconds += timer.elapsed().as_secs_f64();
            // the settled state assembled again, as the convergence test saw it
            tangent.assemble(problem, &mut report)?;
            return Ok(Settled { report, released_energy });
        }
        if step == MAX_STEPS {
            break;
        }
        // the smallest shift giving a positive definite factor
        let mut positive = false;
        for _ in 0..MAX_SHIFTS {
            shifted.clear();
            shifted.extend_from_slice(problem.tangent());
            for (slot, d) in slots.iter().zip(&lumped) {
                if let Some(k) = slot {
                    shifted[*k] += mu * d;
                }
            }
            let timer = Instant::now();
            let kind = linear.factorize(problem.pattern(), &shifted)?;
            report.factorization_seconds += timer.elapsed().as_secs_f64();
            report.factorizations += 1;
            if kind == FactorKind::Llt {
                positive = true;
                break;
            }
            if tangent.full {
                // not near a stable state yet: back to the convex part, same shift
                tangent.full_failed();
                tangent.assemble(problem, &mut report)?;
                continue;
            }
            mu = if mu == 0.0 { MU_FIRST } else { 4.0 * mu };
        }
        if !positive {
            break;
        }
        let timer = Instant::now();
        let mut d: Vec<f64> = problem.residual().iter().map(|r| -r).collect();
        linear.solve_in_place(&mut d)?;
        report.solve_seconds += timer.elapsed().as_secs_f64();
        let g0 = dot(problem.residual(), &d);
        if !(g0 < 0.0) {
            break;
        }
        let u0 = problem.free_values();
        let alpha = critical_point(problem, &u0, &d, g0)?;
        step_taken = d.iter().map(|x| alpha * x).collect();
        // trust-region style: a step cut short by the line search means the quadratic model
        // is poor this far out (more shift, a shorter and more gradient-like step); a full
        // step means it is good (less shift, towards Newton)
        if alpha < 0.25 {
            mu = (mu.max(MU_FIRST) * 10.0).min(MU_MAX);
        } else if alpha > 0.75 {
            mu *= 0.1;
            if mu < MU_FIRST {
                mu = 0.0;
            }
        }
        tangent.next_step(mu == 0.0);
        tangent.assemble(problem, &mut report)?;
    }
    Err(IncrementFailure::Diverged { iterations: report.residual_norms.len(), residual: norm(problem.residual()) })
}

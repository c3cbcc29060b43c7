//! Arc-length continuation (Crisfield's spherical method) in the load parameter t, for
//! crossing limit points of displacement-driven problems: adhesive jump-in and pull-off, snap-back
//! of cohesive cracks.
//!
//! Unknowns: the free displacements u and the pseudo-time t (which drives prescribed
//! displacements, loads and interface motions through their amplitudes). From the committed
//! state (u0, t0) an increment (du, dt) satisfies
//!   R(u0 + du, t0 + dt) = 0   and   ||du||^2 + c^2 dt^2 = ds^2,
//! so the path may turn back in t (the approach of a rigid flat decreases while a surface snaps
//! off). c converts t into a displacement (the caller passes the displacement rate of the
//! stable path before the crossing); with c = 0 (the cylindrical method) a path on which the
//! displacements reach an extremum while t moves on (a force peak) could not be followed.
//! Each Newton iteration solves K a = -R and K b = -dR/dt with one factorization (dR/dt by
//! central differences of the residual in t), sets the correction to a + dl b and picks dl
//! from the constraint (the root keeping the increment closest to its previous direction). The
//! predictor follows the tangent (b, 1) in the direction of the last converged increment.
//! A converged increment must also point forward: where the path folds sharply within one arc
//! length, the sphere around the committed state meets the path behind it as well, and Newton
//! may converge there; such an increment (cosine with the previous one <= 0) is refused, so
//! the caller shortens the arc instead of walking back and forth across the fold.

use super::bordered::{bordered_solves, residual_rate};
use super::convergence::{NewtonSettings, ReferenceScales};
use super::{IncrementFailure, IncrementReport};
use crate::error::CoreError;
use crate::linear_solver::LinearSolver;
use crate::problem::NonlinearProblem;
use crate::vector::{dot, norm};
use std::time::Instant;

/// The last converged increment, which orients the next one.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct PreviousIncrement {
    /// Free-dof displacement increment.
    pub du: Vec<f64>,
    /// Pseudo-time increment (negative on a branch that turned back).
    pub dt: f64,
}

impl PreviousIncrement {
    /// Whether the increment moved forward in pseudo-time and in the displacements: a crossing
    /// can start from it.
    pub fn moved_forward(&self) -> bool {
        self.dt > 0.0 && self.du.iter().any(|&x| x != 0.0)
    }
}

/// One arc-length increment's request: length `ds` (free-dof displacement norm) from the
/// committed state at `t0`, oriented by `previous`; `time_weight` is c, and `rate_step` the
/// step of the central differences for dR/dt (a small fraction of the time scale of the
/// loading, not of the increment: the increment in t vanishes at a limit point).
#[derive(Debug, Clone, Copy)]
pub struct ArcLengthRequest<'a> {
    pub t0: f64,
    pub ds: f64,
    pub previous: &'a PreviousIncrement,
    pub time_weight: f64,
    pub rate_step: f64,
}

/// The root dl of ||w + dl b||^2 + c^2 (dt + dl)^2 = ds^2 (w = du + a) that keeps the increment
/// pointing the way it was going; the closest point when the constraint is not met.
fn constraint_root(du: &[f64], w: &[f64], b: &[f64], c2: f64, dt: f64, ds: f64) -> f64 {
    let (qa, qb, qc) = (dot(b, b) + c2, 2.0 * (dot(b, w) + c2 * dt), dot(w, w) + c2 * dt * dt - ds * ds);
    let disc = qb * qb - 4.0 * qa * qc;
    if qa <= 0.0 {
        0.0
    } else if disc < 0.0 {
        // no intersection with the constraint: the closest point (residual stays reduced)
        -qb / (2.0 * qa)
    } else {
        let root = disc.sqrt();
        let (l1, l2) = ((-qb + root) / (2.0 * qa), (-qb - root) / (2.0 * qa));
        let score = |l: f64| dot(du, w) + l * dot(du, b) + c2 * dt * (dt + l);
        if score(l1) >= score(l2) { l1 } else { l2 }
    }
}

/// The cosine of the angle between the increment (du, dt) and the previous one in the
/// arc-length inner product <(a, s), (b, t)> = a.b + c^2 s t.
fn forward_cosine(du: &[f64], dt: f64, previous: &PreviousIncrement, c2: f64) -> f64 {
    let inner = dot(du, &previous.du) + c2 * dt * previous.dt;
    let lengths =
        ((dot(du, du) + c2 * dt * dt) * (dot(&previous.du, &previous.du) + c2 * previous.dt * previous.dt)).sqrt();
    if lengths > 0.0 { inner / lengths } else { 1.0 }
}

/// Solves one arc-length increment (see the module documentation). On success the problem
/// holds the converged trial state at its new time (not yet committed) and the increment is
/// returned.
pub fn solve_arc_length_increment(
    problem: &mut dyn NonlinearProblem,
    linear: &mut dyn LinearSolver,
    request: ArcLengthRequest<'_>,
    settings: &NewtonSettings,
    scales: ReferenceScales,
) -> Result<(IncrementReport, PreviousIncrement), IncrementFailure> {
    let ArcLengthRequest { t0, ds, previous, time_weight, rate_step: h } = request;
    let n = problem.n_free();
    let mut report = IncrementReport::default();
    let u0 = problem.free_values();
    // u = u0 + du on the free dofs, prescribed values and loads at time t
    let set_state = |problem: &mut dyn NonlinearProblem, du: &[f64], t: f64| {
        problem.set_time(t);
        let u: Vec<f64> = u0.iter().zip(du).map(|(a, b)| a + b).collect();
        problem.set_free_values(&u);
    };
    let mut rate = vec![0.0; n];
    let mut b = vec![0.0; n];
    let mut a = vec![0.0; n];

    // Predictor along the tangent at the committed state.
    let timer = Instant::now();
    set_state(problem, &vec![0.0; n], t0);
    problem.assemble(true)?;
    residual_rate(problem, t0, h, &mut rate)?;
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    let timer = Instant::now();
    linear.factorize(problem.pattern(), problem.tangent())?;
    report.factorization_seconds += timer.elapsed().as_secs_f64();
    report.factorizations += 1;
    for (x, r) in b.iter_mut().zip(&rate) {
        *x = -r;
    }
    linear.solve_in_place(&mut b)?;
    let b_norm = norm(&b);
    if !(b_norm > 0.0) {
        return Err(
            CoreError::Invalid("arc length: the displacements do not respond to the load parameter".into()).into()
        );
    }
    // keep going the way the last increment went: the predictor (b, 1) dt must make a positive
    // weighted inner product with the previous increment (du_prev, dt_prev)
    let c2 = time_weight * time_weight;
    let along = dot(&b, &previous.du) + c2 * previous.dt;
    let mut dt = ds / (b_norm * b_norm + c2).sqrt() * if along >= 0.0 { 1.0 } else { -1.0 };
    let mut du: Vec<f64> = b.iter().map(|x| x * dt).collect();

    for iteration in 0..=settings.max_iterations {
        let timer = Instant::now();
        set_state(problem, &du, t0 + dt);
        problem.assemble(true)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        let r_norm = norm(problem.residual());
        report.residual_norms.push(r_norm);
        let force_scale = settings.force_scale(problem.force_norm(), scales);
        // `a` holds the last correction
        if iteration > 0 && settings.converged(r_norm, force_scale, norm(&a), ds, scales) {
            report.iterations = iteration;
            let cosine = forward_cosine(&du, dt, previous, c2);
            if cosine <= 0.0 {
                return Err(IncrementFailure::TurnedBack { cosine });
            }
            return Ok((report, PreviousIncrement { du, dt }));
        }
        if iteration == settings.max_iterations {
            break;
        }
        bordered_solves(problem, linear, t0 + dt, h, (&mut a, &mut b), &mut report)?;
        let w: Vec<f64> = du.iter().zip(&a).map(|(x, y)| x + y).collect();
        let dl = constraint_root(&du, &w, &b, c2, dt, ds);
        for ((d, ai), bi) in du.iter_mut().zip(a.iter_mut()).zip(&b) {
            *ai += dl * bi;
            *d += *ai;
        }
        dt += dl;
        if !dt.is_finite() || du.iter().any(|x| !x.is_finite()) {
            return Err(CoreError::NonFinite("arc-length increment".into()).into());
        }
    }
    Err(IncrementFailure::Diverged { iterations: settings.max_iterations, residual: norm(problem.residual()) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_forward_cosine_is_the_angle_in_the_weighted_norm() {
        let previous = PreviousIncrement { du: vec![1.0, 0.0], dt: 0.5 };
        // c = 2: the previous increment is (1, 0, 1) in the weighted coordinates
        assert!((forward_cosine(&[1.0, 0.0], 0.5, &previous, 4.0) - 1.0).abs() < 1e-15);
        assert!((forward_cosine(&[-1.0, 0.0], -0.5, &previous, 4.0) + 1.0).abs() < 1e-15);
        assert!(forward_cosine(&[0.0, 1.0], 0.0, &previous, 4.0).abs() < 1e-15);
        // the limit point: the load parameter turns, the displacement goes on
        assert!(forward_cosine(&[1.0, 0.0], -0.1, &previous, 4.0) > 0.0);
    }
}

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

use crate::error::CoreError;
use crate::linear_solver::SparseSolver;
use crate::model::Model;
use crate::newton::{IncrementFailure, IncrementReport, NewtonSettings, ReferenceScales};
use std::time::Instant;

/// The last converged increment, which orients the next one.
#[derive(Debug, Clone)]
pub struct PreviousIncrement {
    /// Free-dof displacement increment.
    pub du: Vec<f64>,
    /// Pseudo-time increment (negative on a branch that turned back).
    pub dt: f64,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// dR/dt at the model's displacement by central differences of the residual in t (step h);
/// restores the model's time.
fn residual_rate(model: &mut Model, t: f64, h: f64, rate: &mut [f64]) -> Result<(), CoreError> {
    model.apply_time(t + h);
    model.assemble(false)?;
    rate.copy_from_slice(&model.residual);
    model.apply_time(t - h);
    model.assemble(false)?;
    for (r, m) in rate.iter_mut().zip(&model.residual) {
        *r = (*r - m) / (2.0 * h);
    }
    model.apply_time(t);
    Ok(())
}

/// Solves one arc-length increment of length `ds` (free-dof displacement norm) from the
/// model's committed state at time `t0`; `rate_step` is the step of the central differences
/// for dR/dt (a small fraction of the time scale of the loading, not of the increment: the
/// increment in t vanishes at a limit point). On success the model holds the converged trial state
/// at its new time `model.time` (not yet committed) and the increment is returned.
pub fn solve_arc_length_increment(
    model: &mut Model,
    solver: &mut SparseSolver,
    t0: f64,
    ds: f64,
    previous: &PreviousIncrement,
    time_weight: f64,
    rate_step: f64,
    settings: &NewtonSettings,
    scales: ReferenceScales,
) -> Result<(IncrementReport, PreviousIncrement), IncrementFailure> {
    let n = model.n_free();
    let mut report = IncrementReport::default();
    let h = rate_step;
    let free = model.free_dofs().to_vec();
    let u0: Vec<f64> = free.iter().map(|&g| model.displacement[g]).collect();
    // u = u0 + du on the free dofs, prescribed values and loads at time t
    let set_state = |model: &mut Model, du: &[f64], t: f64| {
        model.apply_time(t);
        for (k, &g) in free.iter().enumerate() {
            model.displacement[g] = u0[k] + du[k];
        }
    };
    let mut rate = vec![0.0; n];
    let mut b = vec![0.0; n];
    let mut a = vec![0.0; n];

    // Predictor along the tangent at the committed state.
    let timer = Instant::now();
    set_state(model, &vec![0.0; n], t0);
    model.assemble(true)?;
    residual_rate(model, t0, h, &mut rate)?;
    report.assembly_seconds += timer.elapsed().as_secs_f64();
    let timer = Instant::now();
    solver.factorize(model.pattern(), &model.tangent_values)?;
    report.factorization_seconds += timer.elapsed().as_secs_f64();
    for (x, r) in b.iter_mut().zip(&rate) {
        *x = -r;
    }
    solver.solve_in_place(&mut b)?;
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
        set_state(model, &du, t0 + dt);
        model.assemble(true)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        let r_norm = norm(&model.residual);
        report.residual_norms.push(r_norm);
        let force_scale =
            norm(&model.internal_force).max(norm(&model.external_force)).max(scales.force).max(settings.force_floor);
        if iteration > 0 && r_norm <= settings.tol_residual * force_scale {
            // `a` holds the last correction
            let du_ok = norm(&a)
                <= settings.tol_displacement * ds.max(scales.displacement * 1e-3).max(settings.displacement_floor);
            if du_ok || r_norm <= 1e-3 * settings.tol_residual * force_scale {
                report.iterations = iteration;
                return Ok((report, PreviousIncrement { du, dt }));
            }
        }
        if iteration == settings.max_iterations {
            break;
        }
        for (ai, r) in a.iter_mut().zip(&model.residual) {
            *ai = -r;
        }
        // (the rate's assemblies leave the tangent of (u, t) in place)
        let timer = Instant::now();
        residual_rate(model, t0 + dt, h, &mut rate)?;
        report.assembly_seconds += timer.elapsed().as_secs_f64();
        let timer = Instant::now();
        solver.factorize(model.pattern(), &model.tangent_values)?;
        report.factorization_seconds += timer.elapsed().as_secs_f64();
        let timer = Instant::now();
        for (bi, q) in b.iter_mut().zip(&rate) {
            *bi = -q;
        }
        solver.solve_in_place(&mut a)?;
        solver.solve_in_place(&mut b)?;
        report.solve_seconds += timer.elapsed().as_secs_f64();
        // ||du + a + dl b||^2 + c^2 (dt + dl)^2 = ds^2
        let w: Vec<f64> = du.iter().zip(&a).map(|(x, y)| x + y).collect();
        let (qa, qb, qc) = (dot(&b, &b) + c2, 2.0 * (dot(&b, &w) + c2 * dt), dot(&w, &w) + c2 * dt * dt - ds * ds);
        let disc = qb * qb - 4.0 * qa * qc;
        let dl = if qa <= 0.0 {
            0.0
        } else if disc < 0.0 {
            // no intersection with the constraint: the closest point (residual stays reduced)
            -qb / (2.0 * qa)
        } else {
            let root = disc.sqrt();
            let (l1, l2) = ((-qb + root) / (2.0 * qa), (-qb - root) / (2.0 * qa));
            // keep the increment pointing the way it was going
            let score = |l: f64| dot(&du, &w) + l * dot(&du, &b) + c2 * dt * (dt + l);
            if score(l1) >= score(l2) { l1 } else { l2 }
        };
        for ((d, ai), bi) in du.iter_mut().zip(a.iter_mut()).zip(&b) {
            *ai += dl * bi;
            *d += *ai;
        }
        dt += dl;
        if !dt.is_finite() || du.iter().any(|x| !x.is_finite()) {
            return Err(CoreError::NonFinite("arc-length increment".into()).into());
        }
    }
    Err(IncrementFailure::Diverged { iterations: settings.max_iterations, residual: norm(&model.residual) })
}

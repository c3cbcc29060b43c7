//! A snap as a damped flow. Where the path has no nearby equilibrium (an adhesive surface
//! snapping into contact or off it, a run started inside the jump-in range), the body moves at
//! the fixed load as if against a uniform viscous drag, overdamped (no inertia):
//!
//!   M du/dtau = -r(u),
//!
//! with M the consistent mass of unit density ([`NonlinearProblem::mass`]: the L2 metric of
//! displacement fields) and tau a fictitious time. The drag coefficient only rescales tau, so
//! the path in u has no free parameter, and it converges with the mesh (M discretizes the L2
//! product): a 3D body and its axisymmetric section follow the same path. [`FlowDamping`]
//! chooses the drag: mass-proportional (M, the default) or stiffness-proportional (M replaced
//! by the body's initial elastic stiffness K_0, Rayleigh's beta damping; the energy metric,
//! which converges with the mesh too). Both are symmetric positive definite metrics, so either
//! flow only descends the energy and ends on a stable state; they differ in which parts of the
//! body move first. Against mass-proportional drag the small, stiff parts (a surface node
//! under a steep adhesive force) move fast and the large, soft ones (a plastic neck creeping
//! at its limit load) slowly; against stiffness-proportional drag every elastic mode relaxes
//! at the same rate (a linear elastic body moves straight to its equilibrium), so only the
//! nonlinear parts set the pace, and a flow needs far fewer steps. The steps are
//! committed (see Commits below), so plastic flow and hysteretic interface laws follow the
//! path (ABAQUS's `*STATIC, STABILIZE` damps with the same mass-proportional forces, with a
//! damping factor instead of an accuracy). The flow ends on the stable equilibrium the snap
//! reaches.
//!
//! Time stepping: the first step is backward Euler, the later ones variable-step BDF2 (both
//! L-stable: the stiff modes of an elastic body are damped out, not rung); a step of length h solves
//! M (u - s)/(beta h) + r(u) = 0 ([`Formula`]: s and beta from the last two states) with the
//! run's nonlinear solver ([`DampedStep`]: tangent K + M/(beta h); the quasi-Newton solver
//! reuses one factor over several steps) from an explicit predictor, only as accurately as the
//! step needs: to a full correction below [`FlowSettings::solve_share`] (0.1) of the local error
//! the step may make, and within [`MAX_ITERATIONS_PER_STEP`] iterations (a step that needs more
//! was too long and is redone shorter; [`NonlinearProblem::integrator_step`]); a step whose
//! iterations diverge from its predictor (no line-search trial reduces ||r||, and the full
//! step leaves it above the predictor's) or stall (only a short trial does) is redone shorter
//! at once ([`IncrementFailure::NoDescent`]). The velocity
//! (u - s)/(beta h) that a step ends with is the flow's, v = -M^{-1} r(u), up to that solve's
//! error; at the start it comes from a factor of M. Accuracy: the local error (for backward Euler (h/2) ||v_{n+1} -
//! v_n||_inf, for BDF2 Milne's estimate from the predictor) is kept below `tolerance` times
//! the step's move ||u_{n+1} - u_n||_inf; a step with more than twice that is redone shorter,
//! and the next h is h * 0.9 (tolerance move / error)^(1/(order + 1)), within [h/5, 2h] (BDF2
//! is zero-stable for step ratios below 1 + sqrt 2). The first h is the one the second
//! derivative at the start, a_0 = -M^{-1} K v_0, allows: h_0 = 2 tolerance ||v_0|| / ||a_0||.
//! Kinks: where the velocity itself jumps (an interface law whose force jumps, as a hysteretic
//! branch switch does, or a stiff component relaxing from the last step's inexact solve once a
//! short step resolves it), the error is h times the jump, proportional to the move, and no
//! step passes the test; a step redone at most half as long whose error ratio has not even
//! halved, or redone shorter by a fifth or more whose error ratio has not fallen at all
//! ([`Redone::is_kink`]; a smooth flow's falls as h^order) is accepted, and the flow
//! restarts from it by backward Euler at the same length.
//!
//! End: when a step's static residual r(u_{n+1}) = -M v_{n+1} passes the solver's residual test,
//! or when the move still to come, estimated from the velocity's decay ratio
//! q = ||v_{n+1}|| / ||v_n|| < 1 as ||u_{n+1} - u_n|| q / (1 - q), is below `tolerance` times the
//! snap's move so far, or below `tolerance` times the smallest increment the solver's correction
//! test measures against, 1e-3 ||u|| (a body creeping along a perfectly plastic mechanism near its
//! limit load moves so little that the snap's own move is no scale): the end is then solved for
//! directly (r(u) = 0 by the same solver) and accepted if it moved less than twice that (else the flow
//! goes on, and tries again when the estimate of the move to come has halved, or when the snap's
//! move so far has grown by half the distance to the end the missed solve found, whichever comes
//! first). A step that fails is cut fourfold, at most [`MAX_CUTS_IN_A_ROW`] times in a row; a
//! flow that cannot go on then ends at its last accepted state if that state's static residual
//! is within [`STALLED_REST_FACTOR`] of the residual test (the report says by how much), and
//! fails otherwise.
//!
//! Commits: an accepted step becomes the history the next steps start from (plastic strains,
//! interface states) once the body has moved, since the last commit, at least the move the flow
//! counts as negligible (the bar above: `tolerance` times the snap's move so far, or the
//! resolution); shorter steps are spanned by one update from the last committed state. A step
//! committed after a move below that bar leaves each point that yielded in it exactly on its
//! yield surface, at the kink of its response: near rest, where steps move the body 1e-12 to
//! 1e-10 nm (4 nm elements), Newton's iterations then switch such points between their elastic
//! and plastic branches and cycle with either tangent (the residual stalls a few times above
//! the test, the step is cut until it no longer moves u, and the snap fails). Spanning a move
//! below the flow's tolerance by one backward-Euler update changes the path by less than that
//! tolerance.
//!
//! Pauses: after an accepted step the caller may pause the flow ([`follow_damped_flow`],
//! [`FlowControl::Pause`]). The flow's own state ([`FlowState`]: the last accepted state and
//! velocity, the step before it, the next step's length, the commit and end bars) and the
//! problem's committed state are all its further steps depend on, so a flow taken up again
//! from them, in another process from a checkpoint too, takes the same steps (with a solver
//! that starts afresh at the pause either way).

use super::convergence::{NewtonSettings, ReferenceScales};
use super::{IncrementFailure, IncrementReport, NonlinearSolver};
use crate::error::{CoreError, Result};
use crate::linear_solver::{FactorKind, LinearSolver};
use crate::problem::{IntegratorStep, NonlinearProblem};
use crate::sparse::SparsityPattern;
use crate::vector::{distance_inf, norm, norm_inf};
use std::ops::ControlFlow;
use std::time::Instant;

/// Failed steps in a row (each cut fourfold) after which the flow gives up.
pub const MAX_CUTS_IN_A_ROW: usize = 12;

/// How accurately, and how long at most, the flow is followed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowSettings {
    /// The local error allowed per step, relative to the step's move (see the module
    /// documentation).
    pub tolerance: f64,
    /// Accepted steps at most.
    pub max_steps: usize,
    /// The share of a step's allowed local error its nonlinear solve may leave: the solve
    /// stops at a correction below `solve_share` x `tolerance` x the step's move (the Newton
    /// iteration of a stiff integrator stops once its error is a small fraction of the
    /// truncation error; Hairer and Wanner, Solving ODEs II, IV.8). 0: every step is solved to
    /// the solver's own equilibrium test.
    pub solve_share: f64,
    /// Which drag the body moves against (the metric the caller hands to [`damped_flow`]).
    pub damping: FlowDamping,
}

impl Default for FlowSettings {
    fn default() -> Self {
        Self { tolerance: 0.03, max_steps: 5000, solve_share: 0.1, damping: FlowDamping::Mass }
    }
}

/// The drag of the damped flow (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FlowDamping {
    /// M du/dtau = -r(u), M the consistent mass of unit density (ABAQUS's `*STATIC, STABILIZE`).
    #[default]
    Mass,
    /// K_0 du/dtau = -r(u), K_0 the initial elastic stiffness of the solid (interfaces left
    /// out): stiffness-proportional (Rayleigh beta) damping.
    Stiffness,
}

/// What a flow took.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct FlowReport {
    /// Newton iterations, factorizations and seconds of all its step solves that converged
    /// (accepted, or redone for accuracy) and of the direct end solves that converged.
    pub costs: IncrementReport,
    /// Accepted steps.
    pub steps: usize,
    /// Accepted steps committed (see the module documentation: a step that moved the body
    /// less than the flow's negligible move since the last commit is not).
    pub commits: usize,
    /// Steps redone shorter (too inaccurate, or not converged).
    pub rejected: usize,
    /// Steps accepted across a kink in the velocity (see [`Redone::is_kink`]): their error
    /// did not fall with their length; the flow restarted from each by backward Euler.
    pub kinks: usize,
    /// Wall seconds of the solves that did not converge (steps redone shorter, direct end
    /// solves that failed); none of their costs are in `costs`.
    pub failed_solve_seconds: f64,
    /// Set when the flow ended because its steps stalled near rest: the end state's static
    /// residual over the solver's residual test (at most [`STALLED_REST_FACTOR`]).
    pub stalled_at_residual_ratio: Option<f64>,
    /// The energy the drag took: D = int v.(M v) dtau = -int r(u).du along the flow, by the
    /// trapezoid rule over its accepted steps, -sum (r_n + r_(n+1)).(u_(n+1) - u_n) / 2, with
    /// the static residuals r at the accepted states (exact for a quadratic energy, whatever the
    /// steps). It is the energy the snap released and the body did not dissipate plastically
    /// (nor a law hysteretically) on the way: what an inertial snap turns into motion, waves
    /// and heat.
    pub drag_dissipation: f64,
    /// The flow's end solved for directly, hit or missed (see the module documentation).
    pub direct_end_tries: usize,
}

/// The trapezoid rule's -int r.du from `u_a` (residual `r_a`) to `u_b` (residual `r_b`) along
/// the straight segment between them.
fn released_along_segment(u_a: &[f64], r_a: &[f64], u_b: &[f64], r_b: &[f64]) -> f64 {
    -0.5 * u_a.iter().zip(u_b).zip(r_a.iter().zip(r_b)).map(|((a, b), (ra, rb))| (b - a) * (ra + rb)).sum::<f64>()
}

/// One step of the flow as a problem of its own: residual r(u) + M (u - start)/(beta h),
/// tangent K + M/(beta h); the state life cycle is the wrapped problem's. It is solved only as
/// accurately as the step's own error needs: to a correction below the share
/// ([`FlowSettings::solve_share`]) of the error the step may make, tolerance ||u - u_n||_inf.
struct DampedStep<'a> {
    inner: &'a mut dyn NonlinearProblem,
    mass: &'a [f64],
    /// `mass`'s nonzero entries, for the drag M (u - start) at every residual assembly.
    drag_matrix: &'a sprs::CsMat<f64>,
    start: &'a [f64],
    /// The state the step starts from.
    u_n: &'a [f64],
    inverse_h: f64,
    /// The flow's tolerance times the solve's share: the correction tolerance per unit of move.
    accuracy: f64,
    residual: Vec<f64>,
    tangent: Vec<f64>,
    moved: Vec<f64>,
    drag: Vec<f64>,
    /// The correction tolerance at the last assembled iterate.
    correction_tolerance: f64,
}

/// Iterations after which a flow step is given up and redone shorter (a step that needs
/// more was too long: its nonlinearity is not the predictor's).
pub const MAX_ITERATIONS_PER_STEP: usize = 10;

impl<'a> DampedStep<'a> {
    fn new(
        inner: &'a mut dyn NonlinearProblem,
        mass: &'a [f64],
        drag_matrix: &'a sprs::CsMat<f64>,
        formula: &'a Formula,
        u_n: &'a [f64],
        h: f64,
        settings: &FlowSettings,
    ) -> Self {
        Self {
            inner,
            mass,
            drag_matrix,
            start: &formula.start,
            u_n,
            inverse_h: 1.0 / (formula.beta * h),
            accuracy: settings.solve_share * settings.tolerance,
            residual: Vec::new(),
            tangent: Vec::new(),
            moved: Vec::new(),
            drag: Vec::new(),
            correction_tolerance: 0.0,
        }
    }
}

impl NonlinearProblem for DampedStep<'_> {
    fn n_free(&self) -> usize {
        self.inner.n_free()
    }
    fn pattern(&self) -> &SparsityPattern {
        self.inner.pattern()
    }
    fn set_time(&mut self, t: f64) {
        self.inner.set_time(t);
    }
    fn time(&self) -> f64 {
        self.inner.time()
    }
    fn assemble(&mut self, with_tangent: bool) -> Result<()> {
        self.inner.assemble(with_tangent)?;
        let u = self.inner.free_values();
        self.moved.clear();
        self.moved.extend(u.iter().zip(self.start).map(|(u, s)| u - s));
        self.drag.clear();
        self.drag.resize(u.len(), 0.0);
        sprs::prod::mul_acc_mat_vec_csc(self.drag_matrix.view(), &self.moved[..], &mut self.drag[..]);
        self.residual.clear();
        self.residual.extend(self.inner.residual().iter().zip(&self.drag).map(|(r, d)| r + self.inverse_h * d));
        if with_tangent {
            self.tangent.clear();
            self.tangent.extend(self.inner.tangent().iter().zip(self.mass).map(|(k, m)| k + self.inverse_h * m));
        }
        self.correction_tolerance = self.accuracy * distance_inf(&u, self.u_n);
        Ok(())
    }
    fn integrator_step(&self) -> Option<IntegratorStep> {
        Some(IntegratorStep {
            correction_tolerance: self.correction_tolerance,
            max_iterations: MAX_ITERATIONS_PER_STEP,
            mass_coefficient: self.inverse_h,
        })
    }
    fn residual(&self) -> &[f64] {
        &self.residual
    }
    fn tangent(&self) -> &[f64] {
        &self.tangent
    }
    fn force_norm(&self) -> f64 {
        self.inner.force_norm()
    }
    fn solution(&self) -> &[f64] {
        self.inner.solution()
    }
    fn add_to_free(&mut self, du: &[f64], alpha: f64) {
        self.inner.add_to_free(du, alpha);
    }
    fn free_values(&self) -> Vec<f64> {
        self.inner.free_values()
    }
    fn set_free_values(&mut self, values: &[f64]) {
        self.inner.set_free_values(values);
    }
    fn increment_since_commit(&self) -> Vec<f64> {
        self.inner.increment_since_commit()
    }
    fn commit(&mut self) {
        self.inner.commit();
    }
    fn rollback(&mut self) {
        self.inner.rollback();
    }
}

/// The flow's velocity at the problem's assembled state, v = -M^{-1} r, and the first step
/// h_0 = 2 tolerance ||v|| / ||M^{-1} K v|| (one factorization of M, the drag matrix, which
/// must be positive definite: a stiffness drag of a body its boundary conditions do not hold
/// is singular, and such a flow would not descend).
fn start_velocity(
    problem: &dyn NonlinearProblem,
    mass: &[f64],
    linear: &mut dyn LinearSolver,
    tolerance: f64,
    report: &mut IncrementReport,
) -> Result<(Vec<f64>, f64)> {
    let timer = Instant::now();
    if !matches!(linear.factorize(problem.pattern(), mass), Ok(FactorKind::Llt)) {
        return Err(CoreError::Invalid(
            "the damped flow's drag matrix is not positive definite (a stiffness-proportional drag \
             (solver.snap_damping = \"stiffness\") of a body that its boundary conditions do not hold \
             in place is singular): use solver.snap_damping = \"mass\""
                .into(),
        ));
    }
    report.factorization_seconds += timer.elapsed().as_secs_f64();
    report.factorizations += 1;
    let timer = Instant::now();
    let mut v: Vec<f64> = problem.residual().iter().map(|r| -r).collect();
    linear.solve_in_place(&mut v)?;
    let mut a = vec![0.0; v.len()];
    problem.pattern().multiply(problem.tangent(), &v, &mut a);
    linear.solve_in_place(&mut a)?;
    report.solve_seconds += timer.elapsed().as_secs_f64();
    let (speed, acceleration) = (norm_inf(&v), norm_inf(&a));
    let h = if acceleration > 0.0 { 2.0 * tolerance * speed / acceleration } else { 1.0 };
    Ok((v, h))
}

/// The step-size factor for a step of a formula of order `order` that moved `moved` with local
/// error `error` (which scales as h^(order + 1)).
fn step_factor(tolerance: f64, moved: f64, error: f64, order: i32, cap: f64) -> f64 {
    let exponent = 1.0 / f64::from(order + 1);
    if error > 0.0 { (0.9 * (tolerance * moved / error).powf(exponent)).clamp(0.2, cap) } else { cap }
}

/// A step redone at most this share as long whose error ratio did not fall shows a kink
/// ([`Redone::is_kink`]).
const KINK_SHORTER: f64 = 0.8;

/// A step redone shorter because its local error exceeded twice the tolerance: its length and
/// its error over the tolerance, error / (tolerance x move).
#[derive(Debug, Clone, Copy)]
struct Redone {
    h: f64,
    ratio: f64,
}

impl Redone {
    /// Whether the step of length `h` with error ratio `ratio` that follows this one shows a
    /// kink in the flow's velocity: at most half as long, and its error ratio has not even
    /// halved; or at most [`KINK_SHORTER`] as long, and its error ratio has not fallen at all.
    /// A smooth flow's ratio falls as h^order (for BDF2 at least fourfold when h halves, by
    /// 0.64 or less when h falls by a fifth); across a jump in the velocity (a force that jumps,
    /// or a stiff component relaxing from the last step's inexact solve) the error is the jump
    /// itself, h |v_after - v_before|, proportional to the move, and no shorter step passes the
    /// test. The second rule catches the smaller jumps: their ratios of 2 to 5 cut the step by
    /// the controller's factor of 0.55 to 0.7, never to half, and without it the flow crept
    /// toward the jump in ever shorter steps, each stopping short of it, until the steps' moves
    /// were below the resolution of the displacements and their solves failed.
    fn is_kink(&self, h: f64, ratio: f64) -> bool {
        (h <= 0.5 * self.h && ratio > 0.5 * self.ratio) || (h <= KINK_SHORTER * self.h && ratio >= self.ratio)
    }
}

/// The last accepted step: where it started, the velocity there, and its length.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
struct PreviousStep {
    u: Vec<f64>,
    v: Vec<f64>,
    h: f64,
}

/// One step's formula, M (u - start) / (beta h) + r(u) = 0, and its explicit predictor.
struct Formula {
    start: Vec<f64>,
    beta: f64,
    predicted: Vec<f64>,
    order: i32,
}

impl Formula {
    /// Backward Euler from (u_n, v_n) for the first step; after it variable-step BDF2 with
    /// w = h / h_prev: start = ((1 + w)^2 u_n - w^2 u_prev) / (1 + 2 w), beta = (1 + w) / (1 + 2 w),
    /// predicted by u_n + h v_n + h^2/2 (v_n - v_prev) / h_prev.
    fn new(u_n: &[f64], v_n: &[f64], previous: Option<&PreviousStep>, h: f64) -> Self {
        let Some(p) = previous else {
            let predicted = u_n.iter().zip(v_n).map(|(u, v)| u + h * v).collect();
            return Self { start: u_n.to_vec(), beta: 1.0, predicted, order: 1 };
        };
        let w = h / p.h;
        let d = 1.0 + 2.0 * w;
        let start = u_n.iter().zip(&p.u).map(|(u, up)| ((1.0 + w).powi(2) * u - w * w * up) / d).collect();
        let predicted = (0..u_n.len()).map(|i| u_n[i] + h * v_n[i] + 0.5 * h * h * (v_n[i] - p.v[i]) / p.h).collect();
        Self { start, beta: (1.0 + w) / d, predicted, order: 2 }
    }

    /// The local error of the step that ended at `u` with velocity `v_new` from velocity `v_n`:
    /// (h/2) ||v_new - v_n|| for backward Euler; for BDF2 Milne's estimate from the predictor,
    /// 2/9 / (2/9 + 5/12) ||u - predicted|| (the error constants of BDF2 and of the predictor).
    fn error(&self, u: &[f64], v_new: &[f64], v_n: &[f64], h: f64) -> f64 {
        if self.order == 1 { 0.5 * h * distance_inf(v_new, v_n) } else { 8.0 / 23.0 * distance_inf(u, &self.predicted) }
    }
}

/// A flow whose steps can no longer be solved (cut [`MAX_CUTS_IN_A_ROW`] times in a row) ends
/// at its last accepted state when that
/// state's static residual is within this factor of the solver's residual test: near rest, the
/// points that yielded sit at the kink of their response, where Newton's iterations may cycle a
/// few times above the test (see Commits in the module documentation).
pub const STALLED_REST_FACTOR: f64 = 100.0;

/// Ends a flow whose steps stalled at its last accepted state `u_n`: made the problem's
/// assembled trial state, it ends the flow when its static residual is within
/// [`STALLED_REST_FACTOR`] times the solver's residual test there; otherwise the problem is
/// rolled back to the last committed step and None says the flow fails.
fn end_stalled_near_rest(
    problem: &mut dyn NonlinearProblem,
    u_n: &[f64],
    newton: &NewtonSettings,
    scales: ReferenceScales,
    mut flow: FlowReport,
) -> Option<FlowReport> {
    problem.set_free_values(u_n);
    let test = |p: &dyn NonlinearProblem| newton.tol_residual * newton.force_scale(p.force_norm(), scales);
    let ratio = problem.assemble(true).ok().map(|()| norm(problem.residual()) / test(problem));
    match ratio {
        Some(ratio) if ratio <= STALLED_REST_FACTOR => {
            flow.stalled_at_residual_ratio = Some(ratio);
            Some(flow)
        }
        _ => {
            problem.rollback();
            None
        }
    }
}

/// Tries the flow's end directly from its accepted state `u_n`: solves r(u) = 0 at the
/// problem's time with the run's solver, and ends the flow when that end lies within twice the
/// `negligible` move of `u_n` (the problem then holds it as its trial state: Ok). A failed or
/// too long solve is a miss: the problem is rolled back to the last committed step, the flow
/// goes on, and the error holds how far from `u_n` the end the solve found lay (None: the
/// solve failed). The solve's costs go to `flow`.
fn end_directly(
    problem: &mut dyn NonlinearProblem,
    solver: &mut dyn NonlinearSolver,
    linear: &mut dyn LinearSolver,
    scales: ReferenceScales,
    u_n: &[f64],
    negligible: f64,
    flow: &mut FlowReport,
) -> std::result::Result<(), Option<f64>> {
    let (t, solving) = (problem.time(), Instant::now());
    let mut found = None;
    match solver.solve(problem, linear, t, scales) {
        Ok(report) => {
            flow.costs.add_costs(&report);
            let distance = distance_inf(&problem.free_values(), u_n);
            if distance <= 2.0 * negligible {
                return Ok(());
            }
            found = Some(distance);
        }
        Err(_) => flow.failed_solve_seconds += solving.elapsed().as_secs_f64(),
    }
    problem.rollback();
    Err(found)
}

/// Follows the flow at the problem's current time from its trial state (the committed one) to
/// a stable equilibrium (see the module documentation); `mass` is the drag matrix on the
/// problem's pattern: [`NonlinearProblem::mass`], or the initial stiffness for
/// [`FlowDamping::Stiffness`].
/// Accepted steps are committed (except those that moved too little, see the module
/// documentation); on success the problem holds the end state as its trial state (not
/// committed). On failure the problem is at the last committed step. `progress` is
/// told of every accepted step (long flows report how far they are). A flow that may be paused
/// between steps (and taken up again in another process) is [`follow_damped_flow`].
pub fn damped_flow(
    problem: &mut dyn NonlinearProblem,
    mass: &[f64],
    linear: &mut dyn LinearSolver,
    solver: &mut dyn NonlinearSolver,
    scales: ReferenceScales,
    settings: &FlowSettings,
    progress: &mut dyn FnMut(&FlowReport),
) -> std::result::Result<FlowReport, IncrementFailure> {
    let mut control = |report: &FlowReport| {
        progress(report);
        FlowControl::Continue
    };
    match follow_damped_flow(problem, mass, linear, solver, settings, FlowStart::Fresh(scales), &mut control)? {
        FlowEnd::Settled(report) => Ok(report),
        FlowEnd::Paused(_) => unreachable!("a flow whose control never pauses is not paused"),
    }
}

/// Where a damped flow starts: afresh from the problem's trial state (the committed one), with
/// the scales the solver measures convergence against, or where an earlier call paused.
#[derive(Debug)]
pub enum FlowStart {
    Fresh(ReferenceScales),
    Resumed(Box<FlowState>),
}

/// What the caller of [`follow_damped_flow`] tells it after each accepted step that did not
/// end the flow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlowControl {
    Continue,
    /// Return the flow's state now (e.g. to write a checkpoint, or to stop the run): the
    /// problem is rolled back to the last committed step, and [`FlowStart::Resumed`] with the
    /// state goes on exactly as the flow would have.
    Pause,
}

/// How a call of [`follow_damped_flow`] ended.
#[derive(Debug)]
pub enum FlowEnd {
    /// On a stable equilibrium, which the problem holds as its trial state.
    Settled(FlowReport),
    /// Paused between steps when the control asked.
    Paused(Box<FlowState>),
}

/// A damped flow between two steps: what its further steps depend on besides the problem's
/// committed state (the last committed step), so that a flow paused here (and written to a
/// checkpoint) goes on from it as if it had not stopped.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct FlowState {
    /// What the flow took so far.
    pub report: FlowReport,
    /// The time the flow moves at (a rolled-back problem's time is its last commit's).
    t: f64,
    scales: ReferenceScales,
    /// Where the flow started (the snap's move so far is measured from it).
    origin: Vec<f64>,
    /// The last accepted state and its velocity, and the length of the next step.
    u_n: Vec<f64>,
    v: Vec<f64>,
    h: f64,
    /// The step before it (None: the next step is backward Euler).
    previous: Option<PreviousStep>,
    /// The last committed state, and the move from it after which a step is committed.
    committed: Vec<f64>,
    commit_bar: f64,
    /// After a missed direct end, the end is tried again once the estimate of the move to
    /// come has fallen below `tail_bar` (half its value at the miss), or once the move so far
    /// has reached `tail_reach` (its value at the miss plus half the move to the end the
    /// missed solve found): whichever comes first. Both are infinite before a miss.
    tail_bar: f64,
    tail_reach: f64,
    /// The static residual of the last accepted state, which a failure reports.
    committed_residual: f64,
    /// The static residual vector at the last accepted state (for the drag's dissipation).
    residual_n: Vec<f64>,
}

impl FlowState {
    /// The flow's state at its start: as saved when resumed; fresh from the committed state,
    /// unless that is already at rest (then the flow ends at once, with the report of that
    /// check).
    fn begin(
        problem: &mut dyn NonlinearProblem,
        mass: &[f64],
        linear: &mut dyn LinearSolver,
        newton: &NewtonSettings,
        tol: f64,
        start: FlowStart,
    ) -> std::result::Result<ControlFlow<FlowReport, FlowState>, IncrementFailure> {
        let scales = match start {
            FlowStart::Resumed(state) => return Ok(ControlFlow::Continue(*state)),
            FlowStart::Fresh(scales) => scales,
        };
        let mut report = FlowReport::default();
        let timer = Instant::now();
        problem.assemble(true)?;
        report.costs.assembly_seconds += timer.elapsed().as_secs_f64();
        let force_scale = newton.force_scale(problem.force_norm(), scales);
        if newton.residual_negligible(norm(problem.residual()), force_scale) {
            return Ok(ControlFlow::Break(report));
        }
        Ok(ControlFlow::Continue(FlowState::start(problem, mass, linear, scales, tol, report)?))
    }

    /// Takes the accepted step of length `h` to `u` with velocity `v_new`: commits it once it
    /// moved past the commit bar, adds what the drag released along it, and sets the next
    /// step's history and length (`growth` times this one, BDF2 from this step; across a kink
    /// backward Euler again at the same length). Returns the velocity's decay over the step.
    fn accept(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        u: Vec<f64>,
        v_new: Vec<f64>,
        h: f64,
        kink: bool,
        growth: f64,
    ) -> f64 {
        if distance_inf(&u, &self.committed) >= self.commit_bar {
            problem.commit();
            self.committed.clone_from(&u);
            self.report.commits += 1;
        }
        self.report.steps += 1;
        self.report.drag_dissipation += released_along_segment(&self.u_n, &self.residual_n, &u, problem.residual());
        self.residual_n.copy_from_slice(problem.residual());
        let decay = norm(&v_new) / norm(&self.v);
        let (u_prev, v_prev) = (std::mem::replace(&mut self.u_n, u), std::mem::replace(&mut self.v, v_new));
        if kink {
            // across the kink the velocity is not smooth: BDF2's history would carry the jump
            // into the next steps; the flow restarts by backward Euler at the same length
            self.report.kinks += 1;
            self.previous = None;
        } else {
            self.previous = Some(PreviousStep { u: u_prev, v: v_prev, h });
            self.h *= growth;
        }
        // the wrapped problem's residual at the accepted state is the static one, r(u_n)
        self.committed_residual = norm(problem.residual());
        decay
    }
    /// Tries the flow's end directly ([`end_directly`]) from the last accepted state when the
    /// move `to_come` is below the `negligible` move and, after a miss, below the tail bar or
    /// with the move `so_far` past the tail reach (see [`FlowState`]'s fields); true when the
    /// flow ended there (the problem holds the end as its trial state, and the drag's
    /// dissipation up to it is counted).
    fn try_end_directly(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        solver: &mut dyn NonlinearSolver,
        linear: &mut dyn LinearSolver,
        to_come: f64,
        so_far: f64,
        negligible: f64,
    ) -> bool {
        if !(to_come < negligible && (to_come < self.tail_bar || so_far >= self.tail_reach)) {
            return false;
        }
        self.report.direct_end_tries += 1;
        match end_directly(problem, solver, linear, self.scales, &self.u_n, negligible, &mut self.report) {
            Ok(()) => {
                let end = problem.free_values();
                self.report.drag_dissipation +=
                    released_along_segment(&self.u_n, &self.residual_n, &end, problem.residual());
                true
            }
            // tried again once the estimate of the move to come has halved, or once the flow
            // has gone half the way to the end the solve found: while a fast, light part of the
            // body relaxes and a slow one has far to go, the estimate (from the velocity's
            // decay) is the light part's alone, and a bar from it alone held off the end to the
            // flow's last steps
            Err(found) => {
                self.tail_bar = 0.5 * to_come;
                self.tail_reach = found.map_or(f64::INFINITY, |d| so_far + 0.5 * d);
                false
            }
        }
    }

    /// The flow's start at the problem's assembled trial state: its velocity and first step
    /// ([`start_velocity`]).
    fn start(
        problem: &dyn NonlinearProblem,
        mass: &[f64],
        linear: &mut dyn LinearSolver,
        scales: ReferenceScales,
        tolerance: f64,
        mut report: FlowReport,
    ) -> Result<Self> {
        let residual_n = problem.residual().to_vec();
        let committed_residual = norm(&residual_n);
        let (v, h) = start_velocity(problem, mass, linear, tolerance, &mut report.costs)?;
        let origin = problem.free_values();
        Ok(Self {
            report,
            t: problem.time(),
            scales,
            u_n: origin.clone(),
            committed: origin.clone(),
            origin,
            v,
            h,
            previous: None,
            // moves below this are within the flow's tolerance of the smallest increment the
            // solver's correction test measures against, 1e-3 ||u||
            commit_bar: tolerance * 1e-3 * scales.displacement,
            tail_bar: f64::INFINITY,
            tail_reach: f64::INFINITY,
            committed_residual,
            residual_n,
        })
    }
}

/// [`damped_flow`] from `start`, asking `control` after each accepted step that did not end the
/// flow whether to go on or to pause (see [`FlowControl::Pause`]).
pub fn follow_damped_flow(
    problem: &mut dyn NonlinearProblem,
    mass: &[f64],
    linear: &mut dyn LinearSolver,
    solver: &mut dyn NonlinearSolver,
    settings: &FlowSettings,
    start: FlowStart,
    control: &mut dyn FnMut(&FlowReport) -> FlowControl,
) -> std::result::Result<FlowEnd, IncrementFailure> {
    let newton = solver.settings().clone();
    let tol = settings.tolerance;
    let mut s = match FlowState::begin(problem, mass, linear, &newton, tol, start)? {
        ControlFlow::Continue(state) => state,
        ControlFlow::Break(report) => return Ok(FlowEnd::Settled(report)),
    };
    let (t, scales) = (s.t, s.scales);
    let force_scale = |p: &dyn NonlinearProblem| newton.force_scale(p.force_norm(), scales);
    // the wrapped problem's residual at an accepted step is the static one, r(u_n) (= -M v_n
    // up to the step's solve): at rest when that passes the solver's residual test
    let at_rest = |p: &dyn NonlinearProblem| newton.residual_converged(norm(p.residual()), force_scale(p));
    // moves below this are within the flow's tolerance of the smallest increment the solver's
    // correction test measures against, 1e-3 ||u||
    let resolution = tol * 1e-3 * scales.displacement;
    let mut cuts_in_a_row = 0;
    // the step last redone shorter for its error
    let mut redone: Option<Redone> = None;
    let drag_matrix = problem.pattern().nonzeros(mass);
    while s.report.steps < settings.max_steps {
        let h = s.h;
        let formula = Formula::new(&s.u_n, &s.v, s.previous.as_ref(), h);
        problem.set_free_values(&formula.predicted);
        let mut step = DampedStep::new(&mut *problem, mass, &drag_matrix, &formula, &s.u_n, h, settings);
        let solving = Instant::now();
        if let Err(e) = solver.solve(&mut step, linear, t, scales).map(|report| s.report.costs.add_costs(&report)) {
            s.report.failed_solve_seconds += solving.elapsed().as_secs_f64();
            problem.rollback();
            s.report.rejected += 1;
            redone = None;
            cuts_in_a_row += 1;
            if cuts_in_a_row > MAX_CUTS_IN_A_ROW {
                return end_stalled_near_rest(problem, &s.u_n, &newton, scales, s.report)
                    .map(FlowEnd::Settled)
                    .ok_or(e);
            }
            s.h *= 0.25;
            continue;
        }
        let u = problem.free_values();
        let v_new: Vec<f64> = u.iter().zip(&formula.start).map(|(a, b)| (a - b) / (formula.beta * h)).collect();
        let moved = distance_inf(&u, &s.u_n);
        let error = formula.error(&u, &v_new, &s.v, h);
        let ratio = error / (tol * moved);
        let kink = redone.is_some_and(|r: Redone| r.is_kink(h, ratio));
        if error > 2.0 * tol * moved && !kink {
            problem.rollback();
            s.report.rejected += 1;
            redone = Some(Redone { h, ratio });
            s.h *= step_factor(tol, moved, error, formula.order, 0.9);
            continue;
        }
        redone = None;
        cuts_in_a_row = 0;
        // BDF2 stays zero-stable for step ratios below 1 + sqrt 2
        let growth = step_factor(tol, moved, error, formula.order, 2.0);
        let decay = s.accept(problem, u, v_new, h, kink, growth);
        if at_rest(problem) {
            return Ok(FlowEnd::Settled(s.report));
        }
        let to_come = if decay < 1.0 { moved * decay / (1.0 - decay) } else { f64::INFINITY };
        let so_far = distance_inf(&s.u_n, &s.origin);
        let negligible = (tol * so_far).max(resolution);
        s.commit_bar = negligible;
        if s.try_end_directly(problem, solver, linear, to_come, so_far, negligible) {
            return Ok(FlowEnd::Settled(s.report));
        }
        if control(&s.report) == FlowControl::Pause {
            problem.rollback();
            return Ok(FlowEnd::Paused(Box::new(s)));
        }
    }
    Err(IncrementFailure::FlowUnsettled { steps: s.report.steps, residual: s.committed_residual })
}

#[cfg(test)]
mod tests;

//! The damped flow against exact paths: M = I, r_i = k_i (u_i + c u_i^3) with k = (1, 10).
//! Linear (c = 0), from (1, 1) the flow is u(tau) = (exp(-tau), exp(-10 tau)), on the curve
//! y = x^10. Cubic (c = 1), u^2/(1 + u^2) decays as exp(-2 k tau), so with X = x^2/(1 + x^2),
//! Y = y^2/(1 + y^2) the path from (1, 1) is Y = (2X)^10 / 2. Every committed step must lie on
//! its curve to the stated accuracy, more closely as the tolerance shrinks, with steps that grow
//! as the second-order time stepping predicts, and each step solved in few iterations (to the
//! step's accuracy, not to equilibrium's).

use super::{FlowSettings, STALLED_REST_FACTOR, damped_flow};
use crate::error::Result;
use crate::linear_solver::{FaerCholesky, LinearSolver};
use crate::nonlinear::newton::NewtonSolver;
use crate::nonlinear::{
    IncrementFailure, IncrementReport, NewtonSettings, NonlinearSolver, QuasiNewtonSolver, ReferenceScales,
};
use crate::problem::NonlinearProblem;
use crate::sparse::SparsityPattern;

const STIFFNESS: [f64; 2] = [1.0, 10.0];

/// Two uncoupled unknowns with r_i = k_i (u_i + cubic u_i^3) that keep every committed state;
/// r_0 steps up by `step_size` (1 by default) where u_0 <= `step_down_at` (none by default).
struct Pair {
    cubic: f64,
    step_down_at: f64,
    step_size: f64,
    u: [f64; 2],
    committed: Vec<[f64; 2]>,
    residual: [f64; 2],
    tangent: [f64; 2],
    pattern: SparsityPattern,
    solution: [f64; 2],
}

impl Pair {
    fn new(start: [f64; 2], cubic: f64) -> Self {
        let cells = [vec![0usize], vec![1usize]];
        let pattern = SparsityPattern::from_cells(2, 2, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        let (residual, tangent) = ([0.0; 2], [0.0; 2]);
        let step_down_at = f64::NEG_INFINITY;
        let step_size = 1.0;
        Self {
            cubic,
            step_down_at,
            step_size,
            u: start,
            committed: vec![start],
            residual,
            tangent,
            pattern,
            solution: start,
        }
    }
}

impl NonlinearProblem for Pair {
    fn n_free(&self) -> usize {
        2
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn set_time(&mut self, _t: f64) {}
    fn time(&self) -> f64 {
        0.0
    }
    fn assemble(&mut self, _with_tangent: bool) -> Result<()> {
        for i in 0..2 {
            let u = self.u[i];
            self.residual[i] = STIFFNESS[i] * (u + self.cubic * u.powi(3));
            self.tangent[i] = STIFFNESS[i] * (1.0 + 3.0 * self.cubic * u * u);
        }
        if self.u[0] <= self.step_down_at {
            self.residual[0] += self.step_size;
        }
        Ok(())
    }
    fn residual(&self) -> &[f64] {
        &self.residual
    }
    fn tangent(&self) -> &[f64] {
        &self.tangent
    }
    fn force_norm(&self) -> f64 {
        1.0
    }
    fn solution(&self) -> &[f64] {
        &self.solution
    }
    fn add_to_free(&mut self, du: &[f64], alpha: f64) {
        self.set_free_values(&[self.u[0] + alpha * du[0], self.u[1] + alpha * du[1]]);
    }
    fn free_values(&self) -> Vec<f64> {
        self.u.to_vec()
    }
    fn set_free_values(&mut self, values: &[f64]) {
        self.u = [values[0], values[1]];
        self.solution = self.u;
    }
    fn increment_since_commit(&self) -> Vec<f64> {
        let last = self.committed.last().expect("the start is committed");
        vec![self.u[0] - last[0], self.u[1] - last[1]]
    }
    fn commit(&mut self) {
        self.committed.push(self.u);
    }
    fn rollback(&mut self) {
        let last = *self.committed.last().expect("the start is committed");
        self.set_free_values(&last);
    }
    fn mass(&self) -> Option<Vec<f64>> {
        Some(vec![1.0, 1.0])
    }
}

/// The exact path's y at x: y = x^10 (linear), or Y = (2X)^10 / 2 (cubic, see the module
/// documentation).
fn exact_y(x: f64, cubic: f64) -> f64 {
    if cubic == 0.0 {
        return x.powi(10);
    }
    let big_x = x * x / (1.0 + x * x);
    let big_y = 0.5 * (2.0 * big_x).powi(10);
    (big_y / (1.0 - big_y)).sqrt()
}

/// What a flow from (1, 1) did: the largest distance in y of the committed states from the
/// exact path, the steps, and the solver's iterations.
struct FlowOutcome {
    error: f64,
    steps: usize,
    iterations: usize,
    factorizations: usize,
}

fn flow_from_one_one(settings: FlowSettings, cubic: f64, solver: &mut dyn NonlinearSolver) -> FlowOutcome {
    let mut p = Pair::new([1.0, 1.0], cubic);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let flow =
        damped_flow(&mut p, &[1.0, 1.0], &mut linear, solver, ReferenceScales::default(), &settings, &mut |_| {})
            .unwrap();
    assert!(p.u[0].abs() < 1e-10 && p.u[1].abs() < 1e-10, "the flow ends at rest at the origin: {:?}", p.u);
    let error = p.committed.iter().map(|c| (c[1] - exact_y(c[0], cubic)).abs()).fold(0.0, f64::max);
    FlowOutcome {
        error,
        steps: flow.steps,
        iterations: flow.costs.iterations,
        factorizations: flow.costs.factorizations,
    }
}

fn tolerance(tolerance: f64) -> FlowSettings {
    FlowSettings { tolerance, max_steps: 10_000, ..FlowSettings::default() }
}

fn newton() -> NewtonSolver {
    NewtonSolver { settings: NewtonSettings { tol_residual: 1e-12, ..NewtonSettings::default() } }
}

#[test]
fn the_damped_flow_follows_the_exact_path_to_its_tolerance() {
    let coarse = flow_from_one_one(tolerance(0.03), 0.0, &mut newton());
    let fine = flow_from_one_one(tolerance(0.003), 0.0, &mut newton());
    println!(
        "largest distance from the path: {:.3e} in {} steps (tolerance 0.03), {:.3e} in {} (0.003)",
        coarse.error, coarse.steps, fine.error, fine.steps
    );
    assert!(coarse.error < 0.5 * 0.03, "tolerance 0.03: {}", coarse.error);
    // the error follows the tolerance (error per step ~ tolerance x move), and the steps grow
    // as tolerance^(-1/2) with second-order steps (h ~ tolerance^(1/2)), tolerance^(-1) with
    // backward Euler alone
    assert!(fine.error < coarse.error / 5.0, "{} vs {}", fine.error, coarse.error);
    assert!(fine.steps < 5 * coarse.steps, "{} vs {} steps", fine.steps, coarse.steps);
}

/// On a nonlinear flow each step is solved to its own accuracy (a correction within a tenth of
/// the error the step may make), not to equilibrium's 1e-12: the path is as close as when every
/// step is solved to equilibrium (`solve_share` 0), with fewer iterations by Newton, and with a
/// quarter less work at least by the quasi-Newton solver (iterations plus factorizations at
/// its price, 20 iterations each: it trades factorizations for iterations).
/// The quasi-Newton solver's price of a refactorization, in iterations, in the tests below.
const REFACTORIZATION_PRICE: f64 = 20.0;

#[test]
fn the_damped_flow_solves_each_step_only_as_accurately_as_the_step_needs() {
    for tol in [0.03, 0.003] {
        let to_equilibrium = FlowSettings { solve_share: 0.0, ..tolerance(tol) };
        for quasi in [false, true] {
            let solver = |quasi| -> Box<dyn NonlinearSolver> {
                if quasi {
                    Box::new(QuasiNewtonSolver::with_cost_ratio(newton().settings, REFACTORIZATION_PRICE))
                } else {
                    Box::new(newton())
                }
            };
            let inexact = flow_from_one_one(tolerance(tol), 1.0, &mut *solver(quasi));
            let exact = flow_from_one_one(to_equilibrium, 1.0, &mut *solver(quasi));
            println!(
                "cubic flow, quasi-Newton {quasi}, tolerance {tol}: {:.3e} from the path in {} steps, {} iterations, {} factorizations (solved to equilibrium: {:.3e}, {} steps, {} iterations, {} factorizations)",
                inexact.error,
                inexact.steps,
                inexact.iterations,
                inexact.factorizations,
                exact.error,
                exact.steps,
                exact.iterations,
                exact.factorizations
            );
            assert!(inexact.error < 0.5 * tol, "tolerance {tol}: {}", inexact.error);
            assert!(inexact.error < 1.1 * exact.error, "{} vs {}", inexact.error, exact.error);
            let (fewer, price) = if quasi { (0.75, REFACTORIZATION_PRICE) } else { (1.0, 0.0) };
            let work = |o: &FlowOutcome| o.iterations as f64 + price * o.factorizations as f64;
            assert!(work(&inexact) < fewer * work(&exact), "{} vs {} iterations' work", work(&inexact), work(&exact));
        }
    }
}

/// A move still to come below the flow's tolerance times the smallest increment the correction
/// test measures against (1e-3 ||u||) ends the flow by a direct solve, however small the
/// snap's own move: the same flow from (1, 1) (a move of 1) inside a body with ||u|| = 1e5
/// (increments of 100 count as small) ends at the origin after at most two steps, where with
/// ||u|| = 0 it follows the decay to the end.
#[test]
fn a_move_below_the_increment_scale_is_solved_for_directly() {
    let flow = |displacement: f64| {
        let mut p = Pair::new([1.0, 1.0], 1.0);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let scales = ReferenceScales { displacement, force: 0.0 };
        let report =
            damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut newton(), scales, &tolerance(0.03), &mut |_| {})
                .unwrap();
        assert!(p.u[0].abs() < 1e-10 && p.u[1].abs() < 1e-10, "the flow ends at the origin: {:?}", p.u);
        report.steps
    };
    let (alone, in_a_large_body) = (flow(0.0), flow(1e5));
    println!("steps: {alone} with ||u|| = 0, {in_a_large_body} with ||u|| = 1e5");
    assert!(in_a_large_body <= 2, "{in_a_large_body} steps");
    assert!(alone > 10, "{alone} steps");
}

/// A step is committed once the body has moved the flow's negligible move (tolerance times the
/// move so far) since the last commit: on the linear flow from (1, 1), whose tail moves less and
/// less, consecutive commits are at least that far apart, fewer steps are committed than
/// accepted, and every committed state still lies on the exact path.
#[test]
fn a_step_is_committed_only_after_a_move_the_flow_counts() {
    let tol = 0.03;
    let mut p = Pair::new([1.0, 1.0], 0.0);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let flow = damped_flow(
        &mut p,
        &[1.0, 1.0],
        &mut linear,
        &mut newton(),
        ReferenceScales::default(),
        &tolerance(tol),
        &mut |_| {},
    )
    .unwrap();
    let distance = |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
    let start = p.committed[0];
    for pair in p.committed.windows(2) {
        let (apart, so_far) = (distance(&pair[1], &pair[0]), distance(&pair[0], &start));
        assert!(apart >= tol * so_far, "commits {apart:.3e} apart after a move of {so_far:.3e}");
    }
    println!("{} of {} accepted steps committed", flow.commits, flow.steps);
    assert_eq!(flow.commits, p.committed.len() - 1);
    assert!(flow.commits < flow.steps, "{} of {} steps committed", flow.commits, flow.steps);
    let error = p.committed.iter().map(|c| (c[1] - exact_y(c[0], 0.0)).abs()).fold(0.0, f64::max);
    assert!(error < 0.5 * tol, "{error}");
}

/// Newton, except that it fails (as diverged) every solve `refuses` names from the problem it
/// is given.
struct Refusing<F: FnMut(&dyn NonlinearProblem) -> bool> {
    newton: NewtonSolver,
    refuses: F,
}

impl<F: FnMut(&dyn NonlinearProblem) -> bool> NonlinearSolver for Refusing<F> {
    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> std::result::Result<IncrementReport, IncrementFailure> {
        if (self.refuses)(&*problem) {
            return Err(IncrementFailure::Diverged { iterations: 3, residual: 1.0 });
        }
        self.newton.solve(problem, linear, t, scales)
    }

    fn settings(&self) -> &NewtonSettings {
        &self.newton.settings
    }
}

/// Step solves that do not converge are redone shorter; their wall time is reported apart
/// from the costs of the solves that converged (which the driver counts as committed).
#[test]
fn the_wall_time_of_step_solves_that_failed_is_reported() {
    // the first two solves fail, after a pause each
    let pause = std::time::Duration::from_millis(20);
    let mut failures = 2;
    let refuses = |_: &dyn NonlinearProblem| {
        let refuse = failures > 0;
        if refuse {
            failures -= 1;
            std::thread::sleep(pause);
        }
        refuse
    };
    let mut solver = Refusing { newton: newton(), refuses };
    let mut p = Pair::new([1.0, 1.0], 1.0);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let started = std::time::Instant::now();
    let report = damped_flow(
        &mut p,
        &[1.0, 1.0],
        &mut linear,
        &mut solver,
        ReferenceScales::default(),
        &tolerance(0.03),
        &mut |_| {},
    )
    .unwrap();
    let wall = started.elapsed().as_secs_f64();
    assert!(p.u[0].abs() < 1e-10 && p.u[1].abs() < 1e-10, "the flow still ends at the origin: {:?}", p.u);
    assert!(report.rejected >= 2, "{} redone", report.rejected);
    let failed = report.failed_solve_seconds;
    assert!(failed >= 2.0 * pause.as_secs_f64() && failed < wall, "{failed} s failed of {wall} s");
    let converged = report.costs.assembly_seconds + report.costs.factorization_seconds + report.costs.solve_seconds;
    assert!(converged + failed <= wall, "{converged} + {failed} s in {wall} s");
}

/// A flow whose steps stall where its static residual is within [`STALLED_REST_FACTOR`] of the
/// residual test (1e-12 here) ends at its last accepted state and says by how much; one that
/// stalls farther from rest fails.
#[test]
fn a_flow_that_stalls_near_rest_ends_there_and_one_that_stalls_farther_fails() {
    let flow = |stall_below: f64| {
        let mut p = Pair::new([1.0, 1.0], 0.0);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        // Newton for the flow's steps until the static residual at a step's predicted state
        // (|(u_0, 10 u_1)| on the linear pair) falls below `stall_below`; every step after
        // that fails, and every direct solve of the end: a flow whose steps stall near rest
        let refuses = |problem: &dyn NonlinearProblem| {
            let u = problem.free_values();
            problem.integrator_step().is_none() || (u[0] * u[0] + 100.0 * u[1] * u[1]).sqrt() < stall_below
        };
        let mut solver = Refusing { newton: newton(), refuses };
        let scales = ReferenceScales::default();
        let result = damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut solver, scales, &tolerance(0.03), &mut |_| {});
        (result, p)
    };
    let (near, p) = flow(3e-11);
    let report = near.expect("a stall near rest ends the flow");
    let ratio = report.stalled_at_residual_ratio.expect("the stall is reported");
    let residual = (p.residual[0].powi(2) + p.residual[1].powi(2)).sqrt();
    println!("stalled at {ratio:.1} times the test; the end state's residual {residual:.3e}");
    assert!(ratio <= STALLED_REST_FACTOR && (residual - ratio * 1e-12).abs() <= 1e-3 * residual);
    assert!(residual >= 1e-12, "the flow did not come to rest by itself: {residual:.3e}");
    let (far, _) = flow(1e-9);
    assert!(
        far.is_err(),
        "a stall at about 1000 times the test ends the flow: {:?}",
        far.map(|r| r.stalled_at_residual_ratio)
    );
}

/// A jump in the flow's velocity gives a step error proportional to the step (h times the
/// jump), which no shorter step passes: the flow accepts the step that crosses it once a step
/// half as long has not halved its error, restarts there by backward Euler, and reaches the
/// rest state with every committed state on the exact path to the tolerance. The linear pair
/// with r_0 stepping up by 1 where u_0 falls through 0.5: from (1, 1) the velocity in u_0
/// jumps from -0.5 to -1.5 there (tau = ln 2); the path is y = x^10 above and
/// y = ((x + 1) / 3)^10 below, and the rest state is (-1, 0).
#[test]
fn the_flow_crosses_a_jump_in_its_velocity() {
    let tol = 0.03;
    let mut p = Pair { step_down_at: 0.5, ..Pair::new([1.0, 1.0], 0.0) };
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let scales = ReferenceScales::default();
    let flow = damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut newton(), scales, &tolerance(tol), &mut |_| {})
        .expect("the flow crosses the jump");
    let u = p.u;
    assert!((u[0] + 1.0).abs() < 1e-10 && u[1].abs() < 1e-10, "the flow ends at rest at (-1, 0): {u:?}");
    let exact = |x: f64| if x > 0.5 { x.powi(10) } else { ((x + 1.0) / 3.0).powi(10) };
    let error = p.committed.iter().map(|c| (c[1] - exact(c[0])).abs()).fold(0.0, f64::max);
    println!(
        "{} steps, {} redone, {} across a kink; largest distance from the path {error:.3e}",
        flow.steps, flow.rejected, flow.kinks
    );
    assert!(flow.kinks >= 1, "the crossing is reported");
    assert!(error < 0.5 * tol, "{error}");
}

/// A smaller jump in the velocity gives error ratios of 2 to 4 that stay there as the step
/// shortens, where a step cut by the controller's usual factor (about 0.6) is never half as
/// long as the one before: the flow must still cross it, not creep toward it in ever shorter
/// steps. r_0 steps up by 0.25 where u_0 falls through 0.5 (the velocity in u_0 jumps from
/// -0.5 to -0.75); the path below is y = ((x + 0.25) / 1.25)^10, the rest state (-0.25, 0).
#[test]
fn the_flow_crosses_a_small_jump_in_its_velocity_without_creeping_toward_it() {
    let tol = 0.03;
    let mut p = Pair { step_down_at: 0.5, step_size: 0.25, ..Pair::new([1.0, 1.0], 0.0) };
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let scales = ReferenceScales::default();
    let flow = damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut newton(), scales, &tolerance(tol), &mut |_| {})
        .expect("the flow crosses the jump");
    let u = p.u;
    assert!((u[0] + 0.25).abs() < 1e-10 && u[1].abs() < 1e-10, "the flow ends at rest at (-0.25, 0): {u:?}");
    let exact = |x: f64| if x > 0.5 { x.powi(10) } else { ((x + 0.25) / 1.25).powi(10) };
    let error = p.committed.iter().map(|c| (c[1] - exact(c[0])).abs()).fold(0.0, f64::max);
    println!(
        "{} steps, {} redone, {} across a kink; largest distance from the path {error:.3e}",
        flow.steps, flow.rejected, flow.kinks
    );
    assert!(flow.kinks >= 1, "the crossing is reported");
    assert!(flow.rejected <= 10, "{} steps redone: the flow crept toward the jump", flow.rejected);
    assert!(error < 0.5 * tol, "{error}");
}

/// Against a stiffness-proportional drag (the metric K = diag(1, 10) of the linear pair,
/// [`super::FlowDamping::Stiffness`]) both modes relax at the same rate: the flow from (1, 1)
/// is u = (1, 1) exp(-tau), the straight line y = x, where the mass drag's is y = x^10. Every
/// committed state lies on that line, the flow ends at the origin, and in fewer steps than
/// against the mass (whose stiff mode first sets the step).
#[test]
fn against_a_stiffness_drag_a_linear_body_moves_straight_to_its_equilibrium() {
    let run = |drag: [f64; 2]| {
        let mut p = Pair::new([1.0, 1.0], 0.0);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let scales = ReferenceScales::default();
        let flow =
            damped_flow(&mut p, &drag, &mut linear, &mut newton(), scales, &tolerance(0.03), &mut |_| {}).unwrap();
        assert!(p.u[0].abs() < 1e-10 && p.u[1].abs() < 1e-10, "the flow ends at the origin: {:?}", p.u);
        (p.committed, flow.steps)
    };
    let (path, steps) = run(STIFFNESS);
    let off_the_line = path.iter().map(|c| (c[1] - c[0]).abs()).fold(0.0, f64::max);
    let (_, mass_steps) = run([1.0, 1.0]);
    println!("stiffness drag: {steps} steps, {off_the_line:.1e} off the line y = x; mass drag: {mass_steps} steps");
    assert!(off_the_line < 1e-12, "{off_the_line}");
    assert!(steps < mass_steps, "{steps} vs {mass_steps}");
}

/// A direct end that misses while a fast, light part of the body relaxes is tried again once
/// the flow has gone half the way to the end it found, not only once the estimate of the move
/// to come has halved. Here y of the linear pair, against the drag diag(1, 1e-6), relaxes 10^7
/// times faster than x; from (1, y_0) the flow first follows y (whose steps the max norm
/// sets) and then x, and the steps y takes grow as log y_0: from y_0 = 1e-6 and 3e-6 the end
/// is tried once, when x's flow ends. From y_0 = 1e-5, while y relaxes, the move to come
/// estimated from the velocity's decay is y's alone and below the flow's negligible move: the
/// end is tried, and misses (x's end is 1 away). That miss must cost no more than a retry: the
/// flow takes at most the steps the two runs without a miss extrapolate to (linearly in log
/// y_0), plus 2, and tries the end at most once more (a bar after a miss of half the short
/// estimate held off the end until x had all but come to rest: about twice the steps).
#[test]
fn a_direct_end_missed_while_a_light_part_relaxes_is_tried_again_once_the_flow_moved_on() {
    let run = |y_0: f64| {
        let mut p = Pair::new([1.0, y_0], 0.0);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let mut solver = NewtonSolver { settings: NewtonSettings::default() };
        let (scales, settings) = (ReferenceScales::default(), tolerance(0.03));
        let flow = damped_flow(&mut p, &[1.0, 1e-6], &mut linear, &mut solver, scales, &settings, &mut |_| {}).unwrap();
        assert!(p.u[0].abs() < 1e-6 && p.u[1].abs() < 1e-6, "the flow ends at the origin: {:?}", p.u);
        println!("from (1, {y_0:.0e}): {} steps, {} direct ends tried", flow.steps, flow.direct_end_tries);
        (flow.steps as f64, flow.direct_end_tries)
    };
    let (small, larger, missed) = (run(1e-6), run(3e-6), run(1e-5));
    assert!(small.1 == 1 && larger.1 == 1, "the two smaller starts try the end once each: {small:?} {larger:?}");
    assert!(missed.1 >= 2, "from y_0 = 1e-5 the first direct end misses: {missed:?}");
    let extrapolated = larger.0 + (larger.0 - small.0) * (1e-5_f64 / 3e-6).ln() / 3.0_f64.ln();
    assert!(missed.0 <= extrapolated + 2.0, "{} steps against {extrapolated:.1} extrapolated", missed.0);
    assert!(missed.1 <= 2, "{} direct ends tried", missed.1);
}

/// A drag that is not positive definite (a stiffness drag of a body nothing holds) is refused
/// with a message that names the setting to change, not followed.
#[test]
fn a_drag_that_is_not_positive_definite_is_refused_with_the_setting_to_change() {
    let mut p = Pair::new([1.0, 1.0], 0.0);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let scales = ReferenceScales::default();
    let result = damped_flow(&mut p, &[1.0, -1.0], &mut linear, &mut newton(), scales, &tolerance(0.03), &mut |_| {});
    let message = result.err().map(|e| e.to_string()).unwrap_or_default();
    assert!(message.contains("not positive definite") && message.contains("snap_damping"), "{message}");
}

/// A flow paused after every step, its state written out and read back (postcard, as a
/// checkpoint holds it), and taken up again by a fresh solver on a fresh linear solver (the
/// quasi-Newton solver's state and the factor it reuses remade from what they saved), on a
/// problem rolled back to its last commit, takes the same steps to the same end as the flow
/// that ran through without a pause, to the last bit: the cubic flow with the quasi-Newton
/// solver, whose factor reuse depends on what it carries from step to step.
#[test]
fn a_flow_paused_at_every_step_and_taken_up_again_ends_where_the_straight_flow_does() {
    use super::{FlowControl, FlowEnd, FlowStart, FlowState, follow_damped_flow};
    let settings = tolerance(0.03);
    let solver = || QuasiNewtonSolver::new(newton().settings);
    let mut straight = Pair::new([1.0, 1.0], 1.0);
    let mut linear = FaerCholesky::analyse(&straight.pattern).unwrap();
    let whole = damped_flow(
        &mut straight,
        &[1.0, 1.0],
        &mut linear,
        &mut solver(),
        ReferenceScales::default(),
        &settings,
        &mut |_| {},
    )
    .unwrap();
    let mut paused = Pair::new([1.0, 1.0], 1.0);
    let mut linear = FaerCholesky::analyse(&paused.pattern).unwrap();
    let mut nonlinear = solver();
    let mut start = FlowStart::Fresh(ReferenceScales::default());
    let mut pauses = 0;
    let report = loop {
        let control = &mut |_: &super::FlowReport| FlowControl::Pause;
        match follow_damped_flow(&mut paused, &[1.0, 1.0], &mut linear, &mut nonlinear, &settings, start, control)
            .unwrap()
        {
            FlowEnd::Settled(report) => break report,
            FlowEnd::Paused(state) => {
                pauses += 1;
                // a new process: the flow's state, the factor and the solver's state from bytes
                let bytes = postcard::to_stdvec(&(&*state, linear.saved_factor(), nonlinear.saved_state())).unwrap();
                let (read, factor, solver_state): (FlowState, Option<crate::linear_solver::SavedFactor>, Vec<u8>) =
                    postcard::from_bytes(&bytes).unwrap();
                linear = FaerCholesky::analyse(&paused.pattern).unwrap();
                if let Some(factor) = &factor {
                    linear.restore_factor(&paused.pattern, factor).unwrap();
                }
                nonlinear = solver();
                nonlinear.restore_state(&solver_state);
                paused.rollback();
                start = FlowStart::Resumed(Box::new(read));
            }
        }
    };
    println!(
        "{pauses} pauses; {} steps, {} committed, {} factorizations",
        report.steps, report.commits, report.costs.factorizations
    );
    assert!(pauses > 10, "the flow was paused along its way: {pauses}");
    assert_eq!((report.steps, report.commits, report.rejected), (whole.steps, whole.commits, whole.rejected));
    assert_eq!(
        (report.costs.iterations, report.costs.factorizations),
        (whole.costs.iterations, whole.costs.factorizations)
    );
    assert_eq!(paused.committed, straight.committed, "the same committed states, bit for bit");
    assert_eq!(paused.u, straight.u, "the same end");
}

/// The drag's dissipation is the energy the flow released: from (1, 1) to rest at the origin,
/// the fall of the pair's energy sum_i k_i (u_i^2 / 2 + c u_i^4 / 4), 5.5 (linear) and 8.25
/// (cubic). The trapezoid rule on the accepted states is exact for the linear pair whatever the
/// steps, and second order in them for the cubic one.
#[test]
fn the_drag_dissipates_the_energy_the_flow_releases() {
    let dissipated = |settings: FlowSettings, cubic: f64| {
        let mut p = Pair::new([1.0, 1.0], cubic);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let scales = ReferenceScales::default();
        damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut newton(), scales, &settings, &mut |_| {})
            .unwrap()
            .drag_dissipation
    };
    let linear = dissipated(tolerance(0.03), 0.0);
    assert!((linear / 5.5 - 1.0).abs() < 1e-9, "linear: {linear} against 5.5");
    let coarse = (dissipated(tolerance(0.03), 1.0) / 8.25 - 1.0).abs();
    let fine = (dissipated(tolerance(0.003), 1.0) / 8.25 - 1.0).abs();
    println!("cubic: relative error {coarse:.3e} (tolerance 0.03), {fine:.3e} (0.003)");
    assert!(coarse < 1e-2 && fine < coarse / 3.0, "cubic: {coarse} (0.03), {fine} (0.003)");
}

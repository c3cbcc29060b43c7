//! The nonlinear solvers on one-unknown problems with closed-form equilibrium paths: a cubic
//! snap-through under load control, a two-spring chain (linear spring k in series with a
//! softening spring F = g exp(-g)) whose end displacement t is prescribed, which snaps back,
//! and a damaging bond pulled through a spring (dissipation control through its snap-back).

use super::arc_length::{ArcLengthRequest, PreviousIncrement, solve_arc_length_increment};
use super::{NewtonSettings, ReferenceScales, solve_increment};
use crate::error::Result;
use crate::linear_solver::{FaerCholesky, LinearSolver};
use crate::problem::{IntegratorStep, NonlinearProblem};
use crate::sparse::SparsityPattern;

/// One free unknown u; `internal(u, t)` is (f_int - f_ext, d/du).
struct OneDof {
    residual_of: fn(f64, f64) -> (f64, f64),
    /// What it says it needs as a time integrator's step (None: an equilibrium problem).
    integrator_step: Option<IntegratorStep>,
    u: f64,
    t: f64,
    committed: (f64, f64),
    residual: [f64; 1],
    tangent: [f64; 1],
    pattern: SparsityPattern,
    solution: [f64; 2],
    /// Assemblies so far.
    assemblies: usize,
}

impl OneDof {
    fn new(residual_of: fn(f64, f64) -> (f64, f64)) -> Self {
        let cells = [vec![0usize]];
        let pattern = SparsityPattern::from_cells(1, 1, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        Self {
            residual_of,
            integrator_step: None,
            u: 0.0,
            t: 0.0,
            committed: (0.0, 0.0),
            residual: [0.0],
            tangent: [0.0],
            pattern,
            solution: [0.0; 2],
            assemblies: 0,
        }
    }
}

impl NonlinearProblem for OneDof {
    fn n_free(&self) -> usize {
        1
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn set_time(&mut self, t: f64) {
        self.t = t;
        self.solution = [self.u, t];
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn assemble(&mut self, _with_tangent: bool) -> Result<()> {
        self.assemblies += 1;
        let (r, k) = (self.residual_of)(self.u, self.t);
        self.residual = [r];
        self.tangent = [k];
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
        self.u += alpha * du[0];
        self.solution[0] = self.u;
    }
    fn free_values(&self) -> Vec<f64> {
        vec![self.u]
    }
    fn set_free_values(&mut self, values: &[f64]) {
        self.u = values[0];
        self.solution[0] = self.u;
    }
    fn increment_since_commit(&self) -> Vec<f64> {
        vec![self.u - self.committed.0]
    }
    fn commit(&mut self) {
        self.committed = (self.u, self.t);
    }
    fn rollback(&mut self) {
        (self.u, self.t) = self.committed;
        self.solution = [self.u, self.t];
    }
    fn mass(&self) -> Option<Vec<f64>> {
        Some(vec![1.0])
    }
    fn integrator_step(&self) -> Option<IntegratorStep> {
        self.integrator_step
    }
}

/// r = u^3 - 3 u^2 + 2.5 u - t: limit points at u = 1 -+ sqrt(6)/6.
fn snap_through(u: f64, t: f64) -> (f64, f64) {
    (u * u * u - 3.0 * u * u + 2.5 * u - t, 3.0 * u * u - 6.0 * u + 2.5)
}

/// Chain with k = 0.1, end displacement t: r = k u - g exp(-g), g = t - u (force balance at
/// the middle node). Closed-form path: t = g + g exp(-g) / k, u = g exp(-g) / k.
fn softening_chain(u: f64, t: f64) -> (f64, f64) {
    let g = t - u;
    let k = 0.1;
    (k * u - g * (-g).exp(), k + (1.0 - g) * (-g).exp())
}

fn settings() -> NewtonSettings {
    NewtonSettings { tol_residual: 1e-12, tol_displacement: 1e-10, ..NewtonSettings::default() }
}

#[test]
fn newton_converges_quadratically_on_the_stable_branch() {
    let mut p = OneDof::new(snap_through);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let report = solve_increment(&mut p, &mut linear, 0.3, &settings(), ReferenceScales::default()).unwrap();
    let (r, _) = snap_through(p.u, 0.3);
    assert!(r.abs() < 1e-12, "residual {r}");
    // order from the last three residuals before convergence: log(r3/r2) / log(r2/r1)
    let n = &report.residual_norms;
    assert!(n.len() >= 4, "{n:?}");
    let k = n.len() - 1;
    let order = (n[k - 1] / n[k - 2]).ln() / (n[k - 2] / n[k - 3]).ln();
    assert!(order > 1.8, "observed order {order} from {n:?}");
    assert_eq!(report.factorizations, report.iterations);
}

/// Traces `path` by arc length from t = 0 and returns the converged (u, t).
fn trace(residual_of: fn(f64, f64) -> (f64, f64), start_dt: f64, ds: f64, steps: usize) -> Vec<(f64, f64)> {
    let mut p = OneDof::new(residual_of);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    // one load-controlled increment to orient the path
    solve_increment(&mut p, &mut linear, start_dt, &settings(), ReferenceScales::default()).unwrap();
    let mut previous = PreviousIncrement { du: p.increment_since_commit(), dt: start_dt };
    p.commit();
    let weight = previous.du[0].abs() / start_dt;
    let mut states = vec![(p.u, p.t)];
    for _ in 0..steps {
        let request = ArcLengthRequest { t0: p.t, ds, previous: &previous, time_weight: weight, rate_step: 1e-7 };
        let (_, increment) =
            solve_arc_length_increment(&mut p, &mut linear, request, &settings(), ReferenceScales::default())
                .unwrap_or_else(|e| panic!("at u = {}: {e}", p.u));
        p.commit();
        previous = increment;
        states.push((p.u, p.t));
    }
    states
}

/// Turns of the load parameter along a traced path.
fn turns(states: &[(f64, f64)]) -> usize {
    states.windows(3).filter(|w| (w[1].1 - w[0].1) * (w[2].1 - w[1].1) < 0.0).count()
}

#[test]
fn arc_length_passes_both_limit_points_of_a_snap_through() {
    let states = trace(snap_through, 0.1, 0.05, 60);
    for &(u, t) in &states {
        assert!(snap_through(u, t).0.abs() < 1e-10, "off the path at u = {u}, t = {t}");
    }
    assert!(states.last().unwrap().0 > 1.6, "did not get past the second limit point: {:?}", states.last());
    assert_eq!(turns(&states), 2, "the load parameter turns at both limit points");
    // the largest load reached is the first limit point's, f(1 - sqrt(6)/6), to the path resolution
    let u1 = 1.0 - 6f64.sqrt() / 6.0;
    let turn = states.windows(3).position(|w| (w[1].1 - w[0].1) * (w[2].1 - w[1].1) < 0.0).unwrap();
    let peak = states[..turn + 3].iter().map(|s| s.1).fold(f64::MIN, f64::max);
    assert!((peak - snap_through(u1, 0.0).0).abs() < 5e-3, "peak load {peak}");
}

#[test]
fn arc_length_follows_the_snap_back_of_a_softening_chain_under_end_displacement() {
    let states = trace(softening_chain, 0.05, 0.1, 200);
    for &(u, t) in &states {
        let g = t - u;
        assert!((u - g * (-g).exp() / 0.1).abs() < 1e-8, "off the closed-form path at u = {u}, t = {t}");
    }
    // the end displacement turns back (snap-back) and forward again
    assert_eq!(turns(&states), 2, "turns {} along {states:?}", turns(&states));
    assert!(states.last().unwrap().1 - states.last().unwrap().0 > 4.0, "softening spring not opened past its tail");
}

/// Double well: energy u^4/4 - u^2/2 - t u, r = u^3 - u - t, k = 3 u^2 - 1 (unstable for
/// |u| < 1/sqrt 3).
fn double_well(u: f64, t: f64) -> (f64, f64) {
    (u * u * u - u - t, 3.0 * u * u - 1.0)
}

/// The root of r(., t) in [a, b] (r(a) r(b) < 0) by bisection: an independent reference.
fn root(a: f64, b: f64, t: f64) -> f64 {
    let (mut lo, mut hi) = (a, b);
    let f = |u: f64| double_well(u, t).0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) < 0.0) == (f(lo) < 0.0) { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// From inside the unstable region, settling finds the stable equilibrium downhill of the
/// start (never the unstable one Newton can land on), converging quadratically at the end, and
/// reports the fall of the energy on the way.
#[test]
fn settling_finds_the_stable_equilibrium_downhill_and_never_the_unstable_one() {
    use super::settle::settle;
    // t = 0.2: stable roots near -0.88 and 1.09, an unstable one near -0.20
    let t = 0.2;
    for (start, lo, hi) in [(-0.3, -1.5, -0.6), (-0.1, 0.6, 1.5), (0.0, 0.6, 1.5)] {
        let mut p = OneDof::new(double_well);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        p.set_time(t);
        p.set_free_values(&[start]);
        let settled = settle(&mut p, &mut linear, &settings(), ReferenceScales::default())
            .unwrap_or_else(|e| panic!("from {start}: {e}"));
        let report = settled.report;
        let expected = root(lo, hi, t);
        // the energy released is the fall of u^4/4 - u^2/2 - t u from the start to the root
        let energy = |u: f64| u.powi(4) / 4.0 - u * u / 2.0 - t * u;
        let fall = energy(start) - energy(expected);
        // (Simpson's rule along the straight segment is exact for this quartic energy)
        let released = settled.released_energy;
        assert!((released / fall - 1.0).abs() < 1e-12, "from {start}: released {released} against {fall}");
        assert!((p.u - expected).abs() < 1e-10, "from {start}: {} vs the stable root {expected}", p.u);
        assert!(double_well(p.u, t).1 > 0.0, "from {start}: an unstable equilibrium {}", p.u);
        // the last steps are Newton's: order from the last three residuals before convergence
        let n = &report.residual_norms;
        assert!(n.len() >= 4, "{n:?}");
        let k = n.len() - 1;
        let order = (n[k - 1] / n[k - 2]).ln() / (n[k - 2] / n[k - 3]).ln();
        assert!(order > 1.8, "from {start}: observed order {order} from {n:?}");
    }
    // t = 0.5: one equilibrium only, u = 1.19...; from the far side of the barrier
    let mut p = OneDof::new(double_well);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    p.set_time(0.5);
    p.set_free_values(&[-0.4]);
    settle(&mut p, &mut linear, &settings(), ReferenceScales::default()).unwrap();
    assert!((p.u - root(0.6, 1.5, 0.5)).abs() < 1e-10, "{}", p.u);
}

/// r = u^3 + u - 2: one root, u = 1.
fn cubic_with_root_one(u: f64, _t: f64) -> (f64, f64) {
    (u * u * u + u - 2.0, 3.0 * u * u + 1.0)
}

/// The quasi-Newton solver (`quasi`) or full Newton with `settings`.
fn solver(settings: NewtonSettings, quasi: bool) -> Box<dyn super::NonlinearSolver> {
    if quasi {
        Box::new(super::QuasiNewtonSolver::new(settings))
    } else {
        Box::new(super::newton::NewtonSolver { settings })
    }
}

/// A full-Newton stretch (begun after the quasi-Newton iterations failed an equilibrium
/// increment; 4 increments) solves its equilibrium increments by Newton, a factorization at
/// every iteration; a time integrator's step between them is solved by the quasi-Newton
/// iterations (fewer factorizations than iterations) and does not count against the stretch, so
/// the fourth equilibrium increment, after three flow steps, is still Newton's and the fifth
/// the quasi-Newton solver's. Each solve reaches the root.
#[test]
fn a_time_integrator_step_in_a_full_newton_stretch_is_solved_by_the_quasi_newton_iterations() {
    use super::{NonlinearSolver, QuasiNewtonSolver};
    let mut p = OneDof::new(cubic_with_root_one);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let mut solver = QuasiNewtonSolver::new(settings());
    let flow_step = Some(IntegratorStep { correction_tolerance: 1e-9, max_iterations: 25, mass_coefficient: 1.0 });
    let solve = |p: &mut OneDof, linear: &mut FaerCholesky, solver: &mut QuasiNewtonSolver, step| {
        p.integrator_step = step;
        p.set_free_values(&[3.0]);
        p.commit();
        let report = solver.solve(p, linear, 0.0, ReferenceScales::default()).unwrap();
        assert!((p.u - 1.0).abs() < 1e-8, "{}", p.u);
        (report.factorizations, report.iterations)
    };
    let quasi = solve(&mut p, &mut linear, &mut QuasiNewtonSolver::new(settings()), None);
    assert!(quasi.0 < quasi.1, "quasi-Newton's iterations outnumber its factorizations: {quasi:?}");
    solver.start_newton_stretch();
    for increment in 0..4 {
        let (factorizations, iterations) = solve(&mut p, &mut linear, &mut solver, None);
        assert_eq!(factorizations, iterations, "equilibrium increment {increment} is Newton's");
        assert!(iterations > 2);
        let (factorizations, iterations) = solve(&mut p, &mut linear, &mut solver, flow_step);
        assert!(factorizations < iterations, "flow step {increment}: {factorizations}, {iterations}");
    }
    let (factorizations, iterations) = solve(&mut p, &mut linear, &mut solver, None);
    assert!(factorizations < iterations, "the stretch is over: {factorizations}, {iterations}");
}

/// A time integrator's step is solved to its own correction tolerance (fewer iterations than
/// equilibrium's 1e-12 test, and within the tolerance of the root) and given up at its own
/// iteration limit, by Newton and by the quasi-Newton solver.
#[test]
fn an_integrator_step_is_solved_to_its_own_tolerance_and_given_up_at_its_own_limit() {
    use super::IncrementFailure;
    let solve = |step: Option<IntegratorStep>, quasi: bool| {
        let mut p = OneDof::new(cubic_with_root_one);
        p.integrator_step = step;
        p.set_free_values(&[3.0]);
        p.commit();
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let report = solver(settings(), quasi).solve(&mut p, &mut linear, 0.0, ReferenceScales::default());
        (report, p.u)
    };
    for quasi in [false, true] {
        let (exact, u) = solve(None, quasi);
        let exact = exact.unwrap();
        assert!((u - 1.0).abs() < 1e-12, "{u}");
        let loose = IntegratorStep { correction_tolerance: 1e-3, max_iterations: 25, mass_coefficient: 0.0 };
        let (inexact, u) = solve(Some(loose), quasi);
        let inexact = inexact.unwrap();
        assert!((u - 1.0).abs() < 1e-3, "quasi-Newton {quasi}: {u}");
        assert!(inexact.iterations < exact.iterations, "{} vs {}", inexact.iterations, exact.iterations);
        let short = IntegratorStep { correction_tolerance: 0.0, max_iterations: 2, mass_coefficient: 0.0 };
        match solve(Some(short), quasi).0 {
            // the quasi-Newton solver tries the step once more by Newton, within the same limit
            Err(IncrementFailure::Diverged { iterations, .. }) => assert_eq!(iterations, 2),
            other => panic!("quasi-Newton {quasi}: {other:?}"),
        }
    }
}

/// r = 2 (u - 1): one Newton step from anywhere, on the right factor.
fn linear_with_root_one(u: f64, _t: f64) -> (f64, f64) {
    (2.0 * (u - 1.0), 2.0)
}

/// The quasi-Newton solver reuses its factor only for the matrix it factorized, while the
/// linear solver still holds it: a time integrator's step with a mass coefficient within 50% of
/// the factor's, either way, is solved on it (no factorization); one 60% or 150% away, an
/// equilibrium solve after the integrator's, and any solve after someone else factorized are
/// solved on a new factor.
#[test]
fn the_quasi_newton_solver_rebuilds_a_factor_made_for_another_matrix_or_replaced() {
    use super::{NonlinearSolver, QuasiNewtonSolver};
    let mut p = OneDof::new(linear_with_root_one);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let mut solver = QuasiNewtonSolver::new(settings());
    let step = |c: f64| Some(IntegratorStep { correction_tolerance: 1e-3, max_iterations: 10, mass_coefficient: c });
    let mut factorizations = |p: &mut OneDof, linear: &mut FaerCholesky, integrator_step| {
        p.integrator_step = integrator_step;
        p.set_free_values(&[3.0]);
        p.commit();
        let report = solver.solve(p, linear, 0.0, ReferenceScales::default()).unwrap();
        assert!((p.u - 1.0).abs() < 1e-12, "{}", p.u);
        report.factorizations
    };
    assert_eq!(factorizations(&mut p, &mut linear, step(1.0)), 1, "the first solve factorizes");
    assert_eq!(factorizations(&mut p, &mut linear, step(1.25)), 0, "c moved 25%: the factor serves");
    assert_eq!(factorizations(&mut p, &mut linear, step(1.45)), 0, "c moved 45% up: the factor serves");
    assert_eq!(factorizations(&mut p, &mut linear, step(0.55)), 0, "c moved 45% down: the factor serves");
    assert_eq!(factorizations(&mut p, &mut linear, step(0.4)), 1, "c moved 60% down");
    assert_eq!(factorizations(&mut p, &mut linear, step(1.0)), 1, "c moved 150% up");
    linear.factorize(&p.pattern, &[7.0]).unwrap();
    assert_eq!(factorizations(&mut p, &mut linear, step(1.0)), 1, "the factor was replaced");
    assert_eq!(factorizations(&mut p, &mut linear, None), 1, "K alone after K + c M");
    assert_eq!(factorizations(&mut p, &mut linear, None), 0, "K again");
}

/// r = (2 + 0.4 t)(u - 1): linear, its slope 2.4 at t = 1 and 2 at t = 0.
fn linear_with_slope_in_time(u: f64, t: f64) -> (f64, f64) {
    let k = 2.0 + 0.4 * t;
    (k * (u - 1.0), k)
}

/// A time integrator's step on a stale factor is judged by its own correction test, not by
/// equilibrium's: on a factor of slope 2.4 (made at t = 1 and aged two solves) the step at t = 0,
/// slope 2, converges at the plain factor's rate 1/6. Its correction tolerance 1e-3 is about 4
/// iterations away at that rate, within the 10 it may take and cheaper than a refactorization
/// (priced at 20 iterations): no refactorization. Judged by the equilibrium test, 1e-12, it
/// would be 15 iterations away, beyond the step's limit, and refactorized.
#[test]
fn a_time_integrator_step_on_a_stale_factor_is_priced_by_its_own_test() {
    use super::{NonlinearSolver, QuasiNewtonSolver};
    let mut p = OneDof::new(linear_with_slope_in_time);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let mut solver = QuasiNewtonSolver::with_cost_ratio(settings(), 20.0);
    let step = Some(IntegratorStep { correction_tolerance: 1e-3, max_iterations: 10, mass_coefficient: 1.0 });
    let mut solve = |p: &mut OneDof, linear: &mut FaerCholesky, t: f64, integrator_step| {
        p.integrator_step = integrator_step;
        p.set_free_values(&[3.0]);
        p.commit();
        let report = solver.solve(p, linear, t, ReferenceScales::default()).unwrap();
        assert!((p.u - 1.0).abs() < 1e-3, "{}", p.u);
        report.factorizations
    };
    assert_eq!(solve(&mut p, &mut linear, 1.0, step), 1, "the first solve factorizes");
    assert_eq!(solve(&mut p, &mut linear, 1.0, step), 0, "the same matrix");
    assert_eq!(solve(&mut p, &mut linear, 0.0, step), 0, "the step's own test is near");
}

/// A one-unknown problem's (r, dr/du) at (u, t).
type ResidualOf = fn(f64, f64) -> (f64, f64);

/// r = u seen through a tangent of the wrong sign, -1: Newton's direction runs uphill, every
/// line-search trial raises ||r||, and the full step doubles it.
fn uphill(u: f64, _t: f64) -> (f64, f64) {
    (u, -1.0)
}

/// r = u seen through a tangent 25 times too soft: the full step overshoots to -24 u, the line
/// search's first trial (0.1) to -1.5 u, and its second (0.01) reduces ||r|| to 0.75 u.
fn far_too_soft(u: f64, _t: f64) -> (f64, f64) {
    (u, 0.04)
}

/// A time integrator's step whose iterations diverge from its predictor (no line-search trial
/// reduces ||r||, and the full step leaves it above the predictor's) or stall (only a trial
/// below 0.1 of a correction above the step's tolerance reduces it) is given up at its first
/// iteration, by Newton and by the quasi-Newton solver, which does not try it again by full
/// Newton: its remedy is a shorter step. The assemblies are the predictor's, the line search's
/// (the full step, its trials and the step kept) and no more: a trial that is kept is assembled
/// again only for Newton's tangent there, while the quasi-Newton iterations, which need none,
/// keep the trial's residual. An equilibrium solve of the same problem goes on (it has no
/// shorter step).
#[test]
fn a_time_integrator_step_that_diverges_or_stalls_is_given_up_at_once() {
    use super::IncrementFailure;
    let step = Some(IntegratorStep { correction_tolerance: 1e-3, max_iterations: 10, mass_coefficient: 1.0 });
    let trials = settings().max_line_search;
    // (problem, ||r|| after the first iteration, assemblies up to it by Newton and by the
    // quasi-Newton iterations): uphill keeps the full step after its trials (assembled again),
    // far_too_soft its second trial
    let cases = [(uphill as ResidualOf, 2.0, [3 + trials; 2]), (far_too_soft, 0.75, [5, 4])];
    for (residual_of, residual_after, assemblies_by) in cases {
        for (quasi, assemblies) in [false, true].into_iter().zip(assemblies_by) {
            for integrator_step in [step, None] {
                let mut p = OneDof::new(residual_of);
                p.integrator_step = integrator_step;
                p.set_free_values(&[1.0]);
                p.commit();
                let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
                let result = solver(settings(), quasi).solve(&mut p, &mut linear, 0.0, ReferenceScales::default());
                match (integrator_step, result) {
                    (Some(_), Err(IncrementFailure::NoDescent { iterations, residual })) => {
                        assert_eq!(iterations, 1, "quasi-Newton {quasi}");
                        assert!((residual - residual_after).abs() < 1e-12, "{residual} against {residual_after}");
                        assert_eq!(p.assemblies, assemblies, "quasi-Newton {quasi}");
                    }
                    (None, Err(IncrementFailure::NoDescent { .. })) => panic!("an equilibrium solve gave up"),
                    (None, _) => assert!(p.assemblies > assemblies, "quasi-Newton {quasi}: {}", p.assemblies),
                    (Some(_), other) => panic!("quasi-Newton {quasi}: {other:?}"),
                }
            }
        }
    }
}

/// r = sin u + 1/2: stable equilibria at -pi/6 + 2 pi n, unstable ones at 7 pi/6 + 2 pi n.
fn periodic(u: f64, _t: f64) -> (f64, f64) {
    (u.sin() + 0.5, u.cos())
}

/// The damped flow du/dtau = -r(u) runs downhill to the first stable equilibrium on its way,
/// however far: from either side of an unstable one it ends on the stable neighbour on that
/// side (closed form), and it ends there with the solver's tolerance.
#[test]
fn the_damped_flow_ends_on_the_stable_equilibrium_its_path_reaches() {
    use super::damped_flow::{FlowSettings, damped_flow};
    use super::newton::NewtonSolver;
    let below = -std::f64::consts::PI / 6.0;
    let above = below + 2.0 * std::f64::consts::PI;
    // 3.6 and 3.7 lie either side of the unstable root 7 pi / 6 = 3.665
    for (start, expected) in [(2.0, below), (3.6, below), (3.7, above), (4.0, above), (-2.0, below)] {
        let mut p = OneDof::new(periodic);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        p.set_free_values(&[start]);
        p.commit();
        let mass = p.mass().unwrap();
        let mut solver = NewtonSolver { settings: settings() };
        let settings = FlowSettings::default();
        let scales = ReferenceScales::default();
        let flow = damped_flow(&mut p, &mass, &mut linear, &mut solver, scales, &settings, &mut |_| {})
            .unwrap_or_else(|e| panic!("from {start}: {e}"));
        assert!((p.u - expected).abs() < 1e-9, "from {start}: ended at {} instead of {expected}", p.u);
        assert!(flow.steps > 3 && flow.steps < 200, "from {start}: {} steps", flow.steps);
    }
}

/// A bond that damages (bilinear: stiffness K_BOND up to the opening G0, linear softening to
/// zero at GF, secant unloading) at node u, pulled through a spring K_PULL whose end is at t:
/// r = s(u, kappa) - K_PULL (t - u). On the softening branch t = u + s(u) / K_PULL decreases
/// with u when K_PULL < s_max / (GF - G0): a snap-back.
struct DamageChain {
    u: f64,
    t: f64,
    /// Largest opening so far (committed), and the committed (u, t).
    kappa: f64,
    committed: (f64, f64),
    /// Trial bond traction (pulling the node back) and its slope.
    bond: (f64, f64),
    residual: [f64; 1],
    tangent: [f64; 1],
    pattern: SparsityPattern,
    solution: [f64; 2],
}

const K_BOND: f64 = 100.0;
const G0: f64 = 0.01;
const GF: f64 = 0.04;
const K_PULL: f64 = 10.0;

impl DamageChain {
    fn new() -> Self {
        let cells = [vec![0usize]];
        let pattern = SparsityPattern::from_cells(1, 1, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        let (residual, tangent, solution) = ([0.0], [0.0], [0.0; 2]);
        Self {
            u: 0.0,
            t: 0.0,
            kappa: 0.0,
            committed: (0.0, 0.0),
            bond: (0.0, 0.0),
            residual,
            tangent,
            pattern,
            solution,
        }
    }

    /// The bond's traction and slope at opening g from the largest opening kappa.
    fn bond_at(g: f64, kappa: f64) -> (f64, f64) {
        let envelope = |x: f64| if x <= G0 { K_BOND * x } else { (K_BOND * G0 * (GF - x) / (GF - G0)).max(0.0) };
        if g > kappa && g > G0 {
            let slope = if g < GF { -K_BOND * G0 / (GF - G0) } else { 0.0 };
            (envelope(g), slope)
        } else {
            let k = kappa.max(G0);
            let secant = envelope(k) / k;
            (secant * g, secant)
        }
    }

    /// The energy dissipated at largest opening kappa (closed form).
    fn dissipated(kappa: f64) -> f64 {
        if kappa <= G0 {
            return 0.0;
        }
        let k = kappa.min(GF);
        let s = K_BOND * G0 * (GF - k) / (GF - G0);
        0.5 * K_BOND * G0 * G0 + 0.5 * (K_BOND * G0 + s) * (k - G0) - 0.5 * s * k
    }
}

impl NonlinearProblem for DamageChain {
    fn n_free(&self) -> usize {
        1
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn set_time(&mut self, t: f64) {
        self.t = t;
        self.solution = [self.u, t];
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn assemble(&mut self, _with_tangent: bool) -> Result<()> {
        self.bond = Self::bond_at(self.u, self.kappa);
        self.residual = [self.bond.0 - K_PULL * (self.t - self.u)];
        self.tangent = [self.bond.1 + K_PULL];
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
        self.u += alpha * du[0];
        self.solution[0] = self.u;
    }
    fn free_values(&self) -> Vec<f64> {
        vec![self.u]
    }
    fn set_free_values(&mut self, values: &[f64]) {
        self.u = values[0];
        self.solution[0] = self.u;
    }
    fn increment_since_commit(&self) -> Vec<f64> {
        vec![self.u - self.committed.0]
    }
    fn commit(&mut self) {
        self.committed = (self.u, self.t);
        self.kappa = self.kappa.max(self.u);
    }
    fn rollback(&mut self) {
        (self.u, self.t) = self.committed;
        self.solution = [self.u, self.t];
    }
    /// The interface formula with v = -bond traction (v pushes apart), g = u.
    fn damage_dissipation(&self, gradient: &mut [f64]) -> Option<(f64, f64)> {
        let (uc, _) = self.committed;
        let vc = -Self::bond_at(uc, self.kappa).0;
        let (v, k) = (-self.bond.0, -self.bond.1);
        let (g, gc) = (self.u, uc);
        // a bond that fails within the increment is charged up to its final opening
        let failed = v == 0.0 && k == 0.0 && vc != 0.0;
        if failed {
            gradient[0] = 0.0;
            return Some((-0.5 * vc * GF, 0.0));
        }
        gradient[0] = 0.5 * (k * gc - vc);
        Some((0.5 * (v * gc - vc * g), 0.0))
    }
}

#[test]
fn dissipation_control_follows_a_snap_back_and_each_increment_dissipates_what_it_was_asked() {
    use super::dissipation::{DissipationRequest, solve_dissipation_increment};
    let mut p = DamageChain::new();
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    // load control to just before the peak (t = G0 (1 + K_BOND / K_PULL) = 0.11)
    solve_increment(&mut p, &mut linear, 0.1, &settings(), ReferenceScales::default()).unwrap();
    p.commit();
    let mut previous = PreviousIncrement { du: vec![p.u], dt: 0.1 };
    let energy = 2e-4;
    let mut states = Vec::new();
    while p.kappa < GF - 1e-3 {
        let request = DissipationRequest { t0: p.t, energy, predictor: &previous, rate_step: 1e-7 };
        let before = DamageChain::dissipated(p.kappa);
        let (report, increment, dissipated) =
            solve_dissipation_increment(&mut p, &mut linear, request, &settings(), ReferenceScales::default())
                .unwrap_or_else(|e| panic!("at u = {}: {e}", p.u));
        p.commit();
        // on the path, and the bond's energy grew by what was asked (the envelope is linear)
        let (s, _) = DamageChain::bond_at(p.u, p.kappa);
        assert!((p.t - (p.u + s / K_PULL)).abs() < 1e-10, "off the path at u = {}", p.u);
        let exact = DamageChain::dissipated(p.kappa) - before;
        // (the trapezoid is exact once the committed state is on the softening line)
        let on_envelope = !states.is_empty();
        assert!((dissipated - energy).abs() <= 1e-3 * energy, "{dissipated} for {energy}");
        assert!(!on_envelope || (exact - dissipated).abs() < 1e-9 * energy, "{dissipated} vs exact {exact}");
        assert!(report.iterations <= 6, "{report:?}");
        states.push((p.u, p.t));
        previous =
            PreviousIncrement { du: increment.du.iter().map(|x| x * energy / dissipated).collect(), dt: increment.dt };
    }
    // past the peak the end of the spring moves back while the bond opens
    assert!(states.len() >= 5 && states.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1), "{states:?}");
}

/// r = atan u + 2: no root; Newton's steps run off to u -> -inf, where ||r|| creeps down
/// to 2 - pi/2 and never below.
fn no_root(u: f64, _t: f64) -> (f64, f64) {
    (u.atan() + 2.0, 1.0 / (1.0 + u * u))
}

/// r = u - 1 seen through a tangent twice too stiff: Newton converges linearly, ||r|| halving
/// at each iteration.
fn stiff_tangent(u: f64, _t: f64) -> (f64, f64) {
    (u - 1.0, 2.0)
}

/// An increment whose residual has stopped falling is abandoned at the first iteration the
/// stagnation test looks at (the 8th: ||r|| fell by less than 5% over the 3 before) by Newton
/// and by the quasi-Newton solver, instead of at the iteration limit (as with the test switched
/// off); one that converges slowly but steadily (||r|| halving each iteration, 40 iterations to
/// 1e-12) is not.
#[test]
fn a_stagnating_increment_is_abandoned_and_a_slow_steady_one_is_not() {
    use super::IncrementFailure;
    let solve = |residual_of: fn(f64, f64) -> (f64, f64), settings: NewtonSettings, quasi: bool| {
        let mut p = OneDof::new(residual_of);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        solver(settings, quasi).solve(&mut p, &mut linear, 0.0, ReferenceScales::default())
    };
    for quasi in [false, true] {
        match solve(no_root, settings(), quasi) {
            Err(IncrementFailure::Stagnated { iterations, residual, earlier }) => {
                assert_eq!(iterations, 8, "quasi-Newton {quasi}");
                assert!(
                    residual > 0.95 * earlier && residual >= 2.0 - std::f64::consts::FRAC_PI_2 - 1e-12,
                    "{residual}"
                );
            }
            other => panic!("quasi-Newton {quasi}: {other:?}"),
        }
        // switched off, the same iterations end only at the limit (here 8 too: a few
        // iterations later the tangent, 1/(1 + u^2), underflows to zero)
        let without = NewtonSettings { stagnation_iterations: 0, max_iterations: 8, ..settings() };
        match solve(no_root, without, quasi) {
            Err(IncrementFailure::Diverged { iterations, .. }) => assert_eq!(iterations, 8),
            other => panic!("quasi-Newton {quasi}: {other:?}"),
        }
    }
    let patient = NewtonSettings { max_iterations: 60, ..settings() };
    let report = solve(stiff_tangent, patient, false).unwrap();
    assert!((38..=42).contains(&report.iterations), "{} iterations", report.iterations);
}

/// A near miss goes on (`convergence`'s module documentation): Newton through a tangent twice
/// too stiff halves ||r|| and the correction at each iteration, so from ||r|| = 1 it passes the
/// residual test (1e-12) at iteration 40, with no limit in the way. With the limit at 35 the
/// rate predicts ceil(log2(1e12) - 35) = 5 iterations more, within the 5 allowed past the
/// limit: the increment converges at iteration 40 as before. With the limit at 34 the
/// prediction is 6: the increment fails at its limit, as it did before the rule.
#[test]
fn an_increment_converging_steadily_at_its_limit_goes_on_only_while_its_rate_predicts_convergence_within_reach() {
    use super::IncrementFailure;
    use super::convergence::NEAR_MISS_ITERATIONS;
    let solve = |max_iterations: usize| {
        let mut p = OneDof::new(stiff_tangent);
        let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
        let settings = NewtonSettings { max_iterations, ..settings() };
        solver(settings, false).solve(&mut p, &mut linear, 0.0, ReferenceScales::default())
    };
    assert_eq!(NEAR_MISS_ITERATIONS, 5);
    let patient = solve(60).unwrap();
    assert_eq!(patient.iterations, 40, "2^-40 <= 1e-12 < 2^-39");
    let near_miss = solve(35).unwrap();
    assert_eq!(near_miss.iterations, 40);
    match solve(34) {
        Err(IncrementFailure::Diverged { iterations, residual }) => {
            assert_eq!(iterations, 34);
            assert!((residual / 0.5f64.powi(34) - 1.0).abs() < 1e-9, "{residual}");
        }
        other => panic!("{other:?}"),
    }
}

//! The damped flow against an exact path: M = I, r = K u with K = diag(1, 10), so from (1, 1)
//! the flow is u(tau) = (exp(-tau), exp(-10 tau)), on the curve y = x^10. Every committed step
//! must lie on that curve to the stated accuracy, more closely as the tolerance shrinks, with
//! steps that grow as the second-order time stepping predicts.

use super::{FlowSettings, damped_flow};
use crate::error::Result;
use crate::linear_solver::{FaerCholesky, LinearSolver};
use crate::nonlinear::newton::NewtonSolver;
use crate::nonlinear::{NewtonSettings, ReferenceScales};
use crate::problem::NonlinearProblem;
use crate::sparse::SparsityPattern;

const STIFFNESS: [f64; 2] = [1.0, 10.0];

/// Two uncoupled unknowns with r = K u that keep every committed state.
struct LinearPair {
    u: [f64; 2],
    committed: Vec<[f64; 2]>,
    residual: [f64; 2],
    pattern: SparsityPattern,
    solution: [f64; 2],
}

impl LinearPair {
    fn new(start: [f64; 2]) -> Self {
        let cells = [vec![0usize], vec![1usize]];
        let pattern = SparsityPattern::from_cells(2, 2, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        Self { u: start, committed: vec![start], residual: [0.0; 2], pattern, solution: start }
    }
}

impl NonlinearProblem for LinearPair {
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
        self.residual = [STIFFNESS[0] * self.u[0], STIFFNESS[1] * self.u[1]];
        Ok(())
    }
    fn residual(&self) -> &[f64] {
        &self.residual
    }
    fn tangent(&self) -> &[f64] {
        &STIFFNESS
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

/// The largest distance in y of the committed states from the exact path y = x^10, and the
/// number of steps.
fn path_error(tolerance: f64) -> (f64, usize) {
    let mut p = LinearPair::new([1.0, 1.0]);
    let mut linear = FaerCholesky::analyse(&p.pattern).unwrap();
    let mut solver = NewtonSolver { settings: NewtonSettings { tol_residual: 1e-12, ..NewtonSettings::default() } };
    let settings = FlowSettings { tolerance, max_steps: 10_000 };
    let flow =
        damped_flow(&mut p, &[1.0, 1.0], &mut linear, &mut solver, ReferenceScales::default(), &settings, &mut |_| {})
            .unwrap();
    assert!(p.u[0].abs() < 1e-10 && p.u[1].abs() < 1e-10, "the flow ends at rest at the origin: {:?}", p.u);
    let error = p.committed.iter().map(|c| (c[1] - c[0].powi(10)).abs()).fold(0.0, f64::max);
    (error, flow.steps)
}

#[test]
fn the_damped_flow_follows_the_exact_path_to_its_tolerance() {
    let (coarse, coarse_steps) = path_error(0.03);
    let (fine, fine_steps) = path_error(0.003);
    println!(
        "largest distance from the path: {coarse:.3e} in {coarse_steps} steps (tolerance 0.03), {fine:.3e} in {fine_steps} (0.003)"
    );
    assert!(coarse < 0.5 * 0.03, "tolerance 0.03: {coarse}");
    // the error follows the tolerance (error per step ~ tolerance x move), and the steps grow
    // as tolerance^(-1/2) with second-order steps (h ~ tolerance^(1/2)), tolerance^(-1) with
    // backward Euler alone
    assert!(fine < coarse / 5.0, "{fine} vs {coarse}");
    assert!(fine_steps < 5 * coarse_steps, "{fine_steps} vs {coarse_steps} steps");
}

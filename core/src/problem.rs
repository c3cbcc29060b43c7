//! The nonlinear problem a solver drives: residual and tangent at a trial state, and the state
//! life cycle (trial, commit, roll back), as in MFEM's `NonlinearForm` or dolfinx's
//! `NonlinearProblem`. The problem knows nothing of how it is solved: Newton, arc length or a
//! quasi-Newton method are separate objects that call these functions.
//!
//! The unknowns are the free degrees of freedom; the prescribed ones follow the pseudo-time.
//! Solved: r(u, t) = f_int(u) - f_ext(t) = 0 on the free dofs.

use crate::error::Result;
use crate::sparse::SparsityPattern;

pub trait NonlinearProblem {
    /// Number of free unknowns (the length of the residual).
    fn n_free(&self) -> usize;
    /// Sparsity pattern of the tangent on the free dofs (fixed per topology).
    fn pattern(&self) -> &SparsityPattern;
    /// Sets pseudo-time `t`: prescribed values and external loads follow it.
    fn set_time(&mut self, t: f64);
    /// The pseudo-time of the trial state.
    fn time(&self) -> f64;
    /// Assembles the residual (and the tangent if asked) at the trial state; history-dependent
    /// state goes to the trial copies.
    fn assemble(&mut self, with_tangent: bool) -> Result<()>;
    /// [`NonlinearProblem::assemble`] with a tangent that keeps only the convex part of the
    /// interface laws (their points of negative normal stiffness left out), for descent
    /// methods; the residual is the same. The default is the full tangent.
    fn assemble_convex(&mut self) -> Result<()> {
        self.assemble(true)
    }
    /// r on the free dofs from the last assembly.
    fn residual(&self) -> &[f64];
    /// Tangent values on [`NonlinearProblem::pattern`] from the last assembly with tangent.
    fn tangent(&self) -> &[f64];
    /// max(||f_int||, ||f_ext||) of the last assembly: the force scale of convergence tests.
    fn force_norm(&self) -> f64;
    /// The whole solution vector (free and prescribed values) of the trial state.
    fn solution(&self) -> &[f64];
    /// u_free += alpha du.
    fn add_to_free(&mut self, du: &[f64], alpha: f64);
    /// The free values of the trial state.
    fn free_values(&self) -> Vec<f64>;
    /// Overwrites the free values of the trial state.
    fn set_free_values(&mut self, values: &[f64]);
    /// u_free - u_free(committed).
    fn increment_since_commit(&self) -> Vec<f64>;
    /// Accepts the trial state as converged.
    fn commit(&mut self);
    /// Returns to the last committed state.
    fn rollback(&mut self);
    /// The energy dissipated by damage from the committed to the trial state of the last
    /// assembly, its gradient on the free dofs (written to `gradient`) and its rate in
    /// pseudo-time: what a dissipation-based path constraint controls. None when the problem
    /// has no damaging part.
    fn damage_dissipation(&self, _gradient: &mut [f64]) -> Option<(f64, f64)> {
        None
    }
    /// A mass of unit density on [`NonlinearProblem::pattern`] (symmetric positive definite on
    /// the free dofs): the metric a damped flow moves in, M du/dtau = -r(u). None when the
    /// problem has none (snaps then settle without a path).
    fn mass(&self) -> Option<Vec<f64>> {
        None
    }
    /// What the problem needs of a solve when it is one step of a time integrator (a damped
    /// flow's step): less accuracy than equilibrium (its own truncation error is much larger)
    /// and an early end (a shorter step is cheaper than a long iteration). None (the default):
    /// the solver's own test and iteration limit.
    fn integrator_step(&self) -> Option<IntegratorStep> {
        None
    }
}

/// How a solver treats a problem that is one step of a time integrator
/// ([`NonlinearProblem::integrator_step`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegratorStep {
    /// An iterate reached by a full correction c (no line-search cut) that reduced ||r|| and
    /// has ||c||_inf <= this counts as converged, whatever the solver's own test says.
    pub correction_tolerance: f64,
    /// Iterations after which the solve is given up (the integrator then shortens the step).
    pub max_iterations: usize,
    /// c in the step's iteration matrix K + c M (a damped flow's 1 / (beta h)): it changes
    /// with the step's length, so a factor made for another c is a different matrix.
    pub mass_coefficient: f64,
}

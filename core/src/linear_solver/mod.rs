//! Linear solvers for the Newton systems K du = -r on a sparsity pattern fixed per topology.
//!
//! The life cycle follows faer's own split: [`LinearSolver::analyse`] once per pattern
//! (ordering, elimination tree, storage), [`LinearSolver::factorize`] for each new matrix, then
//! any number of [`LinearSolver::solve_in_place`] with that factor. A nonlinear solver may keep
//! a factor across iterations (modified Newton) and solve with it again: that is why factoring
//! and solving are separate calls. Implementations: [`FaerCholesky`] (LL^T with an LDL^T
//! fallback). A different ordering, a reused or single-precision factor, or an iterative solver
//! is a new implementation of this trait.

mod faer_cholesky;
pub mod ordering;

pub use faer_cholesky::{FaerCholesky, PARALLEL_FACTOR_ENTRIES, Precision};
pub use ordering::Ordering;

use crate::error::Result;
use crate::sparse::SparsityPattern;

/// What remakes a linear solver's factor in another process ([`LinearSolver::saved_factor`]):
/// a checkpoint holds it, so that a resumed run solves with the factor the saving run held.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SavedFactor {
    /// The values of the matrix factored, on the solver's pattern.
    pub values: Vec<f64>,
    /// The solver's count of factorizations begun when it was made
    /// ([`LinearSolver::factorizations`], which names the factor held).
    pub factorizations: u64,
    /// A reduced-precision solver had refactored it in double precision (its refinement did
    /// not converge on this matrix).
    pub in_double: bool,
}

/// Which numeric factorization the last call used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FactorKind {
    Llt,
    Ldlt,
}

/// A sparse solver for one symmetric sparsity pattern (the lower triangle is read).
pub trait LinearSolver {
    /// Symbolic analysis of `pattern`, done once per topology.
    fn analyse(pattern: &SparsityPattern) -> Result<Self>
    where
        Self: Sized;
    /// Numeric factorization of the matrix with `values` on `pattern`.
    fn factorize(&mut self, pattern: &SparsityPattern, values: &[f64]) -> Result<FactorKind>;
    /// Solves A x = b in place (b becomes x) with the last factorization, to double precision.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()>;
    /// x ~ A^-1 b with the factor alone (no refinement of a reduced-precision factor): for
    /// methods that use the factor as a preconditioner. The default is the exact solve.
    fn solve_approximately(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_in_place(rhs)
    }
    /// Stored entries of the factor (memory and cost measure).
    fn factor_nnz(&self) -> usize;
    /// Numeric factorizations begun so far: it names the factor held, so a caller that reuses
    /// a factor of its own can tell whether someone else has replaced it since.
    fn factorizations(&self) -> u64;
    /// Matrices a reduced-precision solver had to refactor in double precision because its
    /// refinement did not converge on them (0 for a solver without reduced precision).
    fn precision_fallbacks(&self) -> usize {
        0
    }
    /// The factor held, as what remakes it (None: none held, or a solver that cannot say).
    fn saved_factor(&self) -> Option<SavedFactor> {
        None
    }
    /// Remakes the factor `saved` describes (from a solver analysed on the same `pattern`), and
    /// takes up its count of factorizations, so that the solves after it are those the saving
    /// solver's would have been. The default cannot: an error says so.
    fn restore_factor(&mut self, pattern: &SparsityPattern, saved: &SavedFactor) -> Result<()> {
        let _ = (pattern, saved);
        Err(crate::error::CoreError::Factorization("this linear solver cannot remake a saved factor".into()))
    }
}

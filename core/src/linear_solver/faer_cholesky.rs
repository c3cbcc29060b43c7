//! Sparse direct solution with faer (the default [`LinearSolver`]): the symbolic Cholesky analysis (AMD ordering, elimination
//! tree, supernodes) runs once per sparsity pattern; each Newton iteration refactorizes
//! numerically into buffers owned here, and the workspace is reused.
//!
//! LL^T is tried first (the usual case: a stable elastic or elastic-plastic tangent). When the
//! tangent is not positive definite (a softening interface law, an unstable adhesive branch)
//! the same symbolic structure is used for an LDL^T factorization.

use super::{FactorKind, LinearSolver};
use crate::error::{CoreError, Result};
use crate::sparse::SparsityPattern;
use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// A reusable sparse symmetric direct solver for one sparsity pattern.
pub struct FaerCholesky {
    symbolic: SymbolicCholesky<usize>,
    factor_values: Vec<f64>,
    workspace: MemBuffer,
    kind: Option<FactorKind>,
    par: Par,
}

impl FaerCholesky {
    /// The kind of the last successful factorization.
    pub fn last_kind(&self) -> Option<FactorKind> {
        self.kind
    }
}

impl LinearSolver for FaerCholesky {
    fn analyse(pattern: &SparsityPattern) -> Result<Self> {
        let par = Par::rayon(0);
        let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &pattern.col_ptr, None, &pattern.row_idx);
        let symbolic =
            factorize_symbolic_cholesky(sym, Side::Lower, SymmetricOrdering::Amd, CholeskySymbolicParams::default())
                .map_err(|e| CoreError::Factorization(format!("symbolic analysis failed: {e:?}")))?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, par),
        ]);
        let workspace = MemBuffer::try_new(req)
            .map_err(|_| CoreError::Factorization("out of memory for the factorization workspace".into()))?;
        let factor_values = vec![0.0; symbolic.len_val()];
        Ok(Self { symbolic, factor_values, workspace, kind: None, par })
    }

    fn factor_nnz(&self) -> usize {
        self.factor_values.len()
    }

    fn factorize(&mut self, pattern: &SparsityPattern, values: &[f64]) -> Result<FactorKind> {
        if values.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::NonFinite("tangent matrix".into()));
        }
        let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &pattern.col_ptr, None, &pattern.row_idx);
        let a = SparseColMatRef::new(sym, values);
        let stack = MemStack::new(&mut self.workspace);
        let llt = self.symbolic.factorize_numeric_llt(
            &mut self.factor_values,
            a,
            Side::Lower,
            LltRegularization::default(),
            self.par,
            stack,
            Default::default(),
        );
        if llt.is_ok() {
            self.kind = Some(FactorKind::Llt);
            return Ok(FactorKind::Llt);
        }
        let stack = MemStack::new(&mut self.workspace);
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.factor_values,
                a,
                Side::Lower,
                LdltRegularization::default(),
                self.par,
                stack,
                Default::default(),
            )
            .map_err(|e| {
                self.kind = None;
                CoreError::Factorization(format!("LDL^T failed after LL^T failed: {e:?}"))
            })?;
        self.kind = Some(FactorKind::Ldlt);
        Ok(FactorKind::Ldlt)
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let n = rhs.len();
        let kind = self.kind.ok_or_else(|| CoreError::Factorization("solve before factorization".into()))?;
        let stack = MemStack::new(&mut self.workspace);
        let rhs_mat = MatMut::from_column_major_slice_mut(rhs, n, 1);
        match kind {
            FactorKind::Llt => faer::sparse::linalg::cholesky::LltRef::new(&self.symbolic, &self.factor_values)
                .solve_in_place_with_conj(Conj::No, rhs_mat, self.par, stack),
            FactorKind::Ldlt => faer::sparse::linalg::cholesky::LdltRef::new(&self.symbolic, &self.factor_values)
                .solve_in_place_with_conj(Conj::No, rhs_mat, self.par, stack),
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::NonFinite("solution of the linear system (singular tangent?)".into()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 1D Laplacian (SPD) and a shifted, indefinite version: x = A^{-1} b checked by A x = b.
    #[test]
    fn solves_spd_and_indefinite_tridiagonal_systems() {
        let n = 50;
        let cells: Vec<Vec<usize>> = (0..n - 1).map(|i| vec![i, i + 1]).collect();
        let p = SparsityPattern::from_cells(n, n, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        for shift in [0.1, -1.5] {
            let mut values = vec![0.0; p.nnz()];
            for i in 0..n {
                values[p.slot(i, i).unwrap()] = 2.0 + shift;
                if i + 1 < n {
                    values[p.slot(i, i + 1).unwrap()] = -1.0;
                    values[p.slot(i + 1, i).unwrap()] = -1.0;
                }
            }
            let mut solver = FaerCholesky::analyse(&p).unwrap();
            let kind = solver.factorize(&p, &values).unwrap();
            assert_eq!(kind, if shift > 0.0 { FactorKind::Llt } else { FactorKind::Ldlt });
            let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
            let mut x = b.clone();
            solver.solve_in_place(&mut x).unwrap();
            let mut ax = vec![0.0; n];
            p.multiply(&values, &x, &mut ax);
            let err = ax.iter().zip(&b).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(err < 1e-10, "shift {shift}: residual {err}");
        }
    }
}

//! Sparse direct solution with faer (the default [`LinearSolver`]): the symbolic Cholesky analysis (ordering, elimination
//! tree, supernodes) runs once per sparsity pattern; each Newton iteration refactorizes
//! numerically into buffers owned here, and the workspace is reused.
//!
//! LL^T is tried first (the usual case: a stable elastic or elastic-plastic tangent). When the
//! tangent is not positive definite (a softening interface law, an unstable adhesive branch)
//! the same symbolic structure is used for an LDL^T factorization.

use super::ordering::{Ordering, nested_dissection};
use super::{FactorKind, LinearSolver, SavedFactor};
use crate::error::{CoreError, Result};
use crate::sparse::SparsityPattern;
use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Precision of the numeric factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// f64 factor: exact solves.
    #[default]
    Double,
    /// f32 factor (half the memory and about half the time); exact solves by iterative
    /// refinement in double precision, x += L^-T L^-1 (b - A x), until ||b - A x|| <= 1e-12 ||b||.
    /// Refinement contracts only while cond(A) eps_f32 < 1: when it stalls or diverges (a nearly
    /// singular or indefinite tangent), the matrix is refactored in f64 and that factor solves
    /// until the next factorization.
    Single,
}

/// A numeric factor in precision T on the shared symbolic structure.
struct Numeric<T> {
    values: Vec<T>,
    kind: Option<FactorKind>,
}

impl<T: faer::traits::ComplexField + Copy + Default> Numeric<T> {
    fn factorize(
        &mut self,
        symbolic: &SymbolicCholesky<usize>,
        a: SparseColMatRef<'_, usize, T>,
        par: Par,
        workspace: &mut MemBuffer,
    ) -> Result<FactorKind> {
        // allocated at the first factorization, so that the symbolic analysis tells the
        // factor's size before any of its memory is taken
        if self.values.len() != symbolic.len_val() {
            self.values = zeroed(symbolic.len_val())?;
        }
        let stack = MemStack::new(workspace);
        let llt = symbolic.factorize_numeric_llt(
            &mut self.values,
            a,
            Side::Lower,
            LltRegularization::default(),
            par,
            stack,
            Default::default(),
        );
        if llt.is_ok() {
            self.kind = Some(FactorKind::Llt);
            return Ok(FactorKind::Llt);
        }
        let stack = MemStack::new(workspace);
        symbolic
            .factorize_numeric_ldlt(
                &mut self.values,
                a,
                Side::Lower,
                LdltRegularization::default(),
                par,
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

    /// Solves in place for the `n_rhs` columns of `rhs` (column major).
    fn solve(
        &self,
        symbolic: &SymbolicCholesky<usize>,
        (rhs, n_rhs): (&mut [T], usize),
        par: Par,
        workspace: &mut MemBuffer,
    ) -> Result<()> {
        let n = rhs.len() / n_rhs;
        let kind = self.kind.ok_or_else(|| CoreError::Factorization("solve before factorization".into()))?;
        let stack = MemStack::new(workspace);
        let rhs_mat = MatMut::from_column_major_slice_mut(rhs, n, n_rhs);
        match kind {
            FactorKind::Llt => faer::sparse::linalg::cholesky::LltRef::new(symbolic, &self.values)
                .solve_in_place_with_conj(Conj::No, rhs_mat, par, stack),
            FactorKind::Ldlt => faer::sparse::linalg::cholesky::LdltRef::new(symbolic, &self.values)
                .solve_in_place_with_conj(Conj::No, rhs_mat, par, stack),
        }
        Ok(())
    }
}

/// The factor and, for a single-precision one, what refinement needs.
enum Factor {
    Double {
        numeric: Numeric<f64>,
        /// The matrix factored (what remakes the factor from a checkpoint).
        matrix: Vec<f64>,
    },
    Single {
        numeric: Numeric<f32>,
        /// The matrix factored (f64, for the refinement residual) and its f32 copy.
        matrix: Vec<f64>,
        matrix_f32: Vec<f32>,
        pattern: SparsityPattern,
        /// The f64 factor of the same matrix, made when refinement fails (storage kept once
        /// allocated; `kind` is None until this matrix has been factored in f64).
        fallback: Numeric<f64>,
        /// Matrices refactored in f64 because refinement failed.
        fallbacks: usize,
    },
}

/// `len` zeros, or an error saying how much memory the factor needed where the allocation
/// fails (an abort otherwise). Where the system overcommits, the allocation may succeed and the
/// process be stopped when the memory is touched: the callers' size checks come first.
fn zeroed<T: Clone + Default>(len: usize) -> Result<Vec<T>> {
    let mut values = Vec::new();
    values.try_reserve_exact(len).map_err(|_| {
        CoreError::Factorization(format!(
            "out of memory for the sparse factor: {len} entries ({:.1} GiB)",
            (len * std::mem::size_of::<T>()) as f64 / f64::from(1u32 << 30)
        ))
    })?;
    values.resize(len, T::default());
    Ok(values)
}

/// A reusable sparse symmetric direct solver for one sparsity pattern.
pub struct FaerCholesky {
    symbolic: SymbolicCholesky<usize>,
    factor: Factor,
    workspace: MemBuffer,
    /// The numeric factorization's (and a many-column solve's) parallelism: see
    /// [`PARALLEL_FACTOR_ENTRIES`].
    par: Par,
    factorizations: u64,
}

/// A factor with at least this many stored entries is factored on the current rayon pool's
/// threads; a smaller one on one thread, and a solve for one right-hand side always on one
/// thread ([`SOLVE_PAR`]). faer parallelizes the dense work inside each supernode, and a small
/// factor's supernodes are too small to pay for the threads' synchronization. Measured on 2
/// cores (`benches/linear-solvers`, single-precision factor): 3.2M entries (the quick main job)
/// 41 ms on one thread against 70 ms on two; 70M (the CalculiX benchmark) 1.35 s against 1.39 s;
/// 386M 12.0 s against 9.4 s. One-column solves were faster on one thread at all three sizes.
/// With more cores the crossing comes at a smaller factor: the bound is the middle of what 2
/// cores showed, not a tuned value.
pub const PARALLEL_FACTOR_ENTRIES: usize = 50_000_000;

/// Solves for one right-hand side: forward and back substitution are bound by memory traffic.
const SOLVE_PAR: Par = Par::Seq;

/// Refinement stops at this relative residual, or after this many corrections.
const REFINEMENT_TOLERANCE: f64 = 1e-12;
const MAX_REFINEMENTS: usize = 10;

impl FaerCholesky {
    /// Symbolic analysis of `pattern` with the given fill-reducing ordering (double precision).
    pub fn analyse_with(pattern: &SparsityPattern, ordering: Ordering) -> Result<Self> {
        Self::analyse_with_precision(pattern, ordering, Precision::Double)
    }

    /// Symbolic analysis of `pattern` with the given ordering and factor precision.
    pub fn analyse_with_precision(pattern: &SparsityPattern, ordering: Ordering, precision: Precision) -> Result<Self> {
        let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &pattern.col_ptr, None, &pattern.row_idx);
        let permutation = match ordering {
            Ordering::Amd => None,
            Ordering::NestedDissection => Some(nested_dissection(pattern)?),
        };
        let faer_ordering = match &permutation {
            None => SymmetricOrdering::Amd,
            Some((forward, inverse)) => SymmetricOrdering::Custom(PermRef::new_checked(forward, inverse, pattern.n)),
        };
        let symbolic = factorize_symbolic_cholesky(sym, Side::Lower, faer_ordering, CholeskySymbolicParams::default())
            .map_err(|e| CoreError::Factorization(format!("symbolic analysis failed: {e:?}")))?;
        let par = if symbolic.len_val() >= PARALLEL_FACTOR_ENTRIES { Par::rayon(0) } else { Par::Seq };
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, SOLVE_PAR),
        ]);
        let workspace = MemBuffer::try_new(req)
            .map_err(|_| CoreError::Factorization("out of memory for the factorization workspace".into()))?;
        let factor = match precision {
            Precision::Double => {
                Factor::Double { numeric: Numeric { values: Vec::new(), kind: None }, matrix: Vec::new() }
            }
            Precision::Single => Factor::Single {
                numeric: Numeric { values: Vec::new(), kind: None },
                matrix: Vec::new(),
                matrix_f32: Vec::new(),
                pattern: pattern.clone(),
                fallback: Numeric { values: Vec::new(), kind: None },
                fallbacks: 0,
            },
        };
        Ok(Self { symbolic, factor, workspace, par, factorizations: 0 })
    }

    /// Solves A X = B in place for the `n_rhs` columns of `rhs` (column major, one after the
    /// other) with the last factorization, in one pass over the factor: for many right-hand
    /// sides at once. Needs a double-precision factor.
    pub fn solve_columns_in_place(&mut self, rhs: &mut [f64], n_rhs: usize) -> Result<()> {
        let Factor::Double { numeric, .. } = &self.factor else {
            return Err(CoreError::Factorization("solving many columns needs a double-precision factor".into()));
        };
        if n_rhs == 0 || !rhs.len().is_multiple_of(n_rhs) {
            return Err(CoreError::Invalid(format!("{} values are not {n_rhs} columns", rhs.len())));
        }
        let req = self.symbolic.solve_in_place_scratch::<f64>(n_rhs, self.par);
        let mut workspace = MemBuffer::try_new(req)
            .map_err(|_| CoreError::Factorization("out of memory for the solve workspace".into()))?;
        numeric.solve(&self.symbolic, (rhs, n_rhs), self.par, &mut workspace)?;
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::NonFinite("solution of the linear system (singular tangent?)".into()));
        }
        Ok(())
    }

    /// The kind of the last successful factorization.
    pub fn last_kind(&self) -> Option<FactorKind> {
        match &self.factor {
            Factor::Double { numeric, .. } => numeric.kind,
            Factor::Single { numeric, .. } => numeric.kind,
        }
    }
}

/// Iterative refinement with the f32 factor of A: x_0 = 0, x_{k+1} = x_k + F^-1 (b - A x_k),
/// stopped at ||b - A x|| <= REFINEMENT_TOLERANCE ||b||. On success `rhs` holds x and the result
/// is true; it is false (and `rhs` untouched) when the residual grows or is still above the
/// tolerance after MAX_REFINEMENTS corrections.
fn refine(
    numeric: &Numeric<f32>,
    (symbolic, matrix, pattern): (&SymbolicCholesky<usize>, &[f64], &SparsityPattern),
    rhs: &mut [f64],
    workspace: &mut MemBuffer,
) -> Result<bool> {
    let b = rhs.to_vec();
    let tolerance = REFINEMENT_TOLERANCE * crate::vector::norm(&b);
    let mut x = vec![0.0; b.len()];
    let mut r = b.clone();
    let mut r_norm = f64::INFINITY;
    let mut r32 = vec![0.0f32; b.len()];
    let mut ax = vec![0.0; b.len()];
    for _ in 0..=MAX_REFINEMENTS {
        for (s, d) in r32.iter_mut().zip(&r) {
            *s = *d as f32;
        }
        numeric.solve(symbolic, (&mut r32, 1), SOLVE_PAR, workspace)?;
        for (xi, c) in x.iter_mut().zip(&r32) {
            *xi += *c as f64;
        }
        pattern.multiply(matrix, &x, &mut ax);
        for ((ri, bi), ai) in r.iter_mut().zip(&b).zip(&ax) {
            *ri = bi - ai;
        }
        let previous = r_norm;
        r_norm = crate::vector::norm(&r);
        if r_norm <= tolerance {
            rhs.copy_from_slice(&x);
            return Ok(true);
        }
        if r_norm.is_nan() || r_norm >= previous {
            return Ok(false);
        }
    }
    Ok(false)
}

/// The f64 factor of a single-precision solver's `matrix` (made when refinement fails).
fn factorize_in_double(
    fallback: &mut Numeric<f64>,
    (symbolic, matrix, pattern): (&SymbolicCholesky<usize>, &[f64], &SparsityPattern),
    par: Par,
    workspace: &mut MemBuffer,
) -> Result<FactorKind> {
    let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &pattern.col_ptr, None, &pattern.row_idx);
    fallback.factorize(symbolic, SparseColMatRef::new(sym, matrix), par, workspace)
}

impl LinearSolver for FaerCholesky {
    fn analyse(pattern: &SparsityPattern) -> Result<Self> {
        Self::analyse_with(pattern, Ordering::default())
    }

    fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    fn precision_fallbacks(&self) -> usize {
        match &self.factor {
            Factor::Double { .. } => 0,
            Factor::Single { fallbacks, .. } => *fallbacks,
        }
    }

    fn factorizations(&self) -> u64 {
        self.factorizations
    }

    fn saved_factor(&self) -> Option<SavedFactor> {
        let (kind, matrix, in_double) = match &self.factor {
            Factor::Double { numeric, matrix } => (numeric.kind, matrix, false),
            Factor::Single { numeric, matrix, fallback, .. } => (numeric.kind, matrix, fallback.kind.is_some()),
        };
        kind?;
        Some(SavedFactor { values: matrix.clone(), factorizations: self.factorizations, in_double })
    }

    fn restore_factor(&mut self, pattern: &SparsityPattern, saved: &SavedFactor) -> Result<()> {
        if saved.values.len() != pattern.nnz() {
            return Err(CoreError::Invalid(format!(
                "a saved factor of {} matrix values for a pattern of {}",
                saved.values.len(),
                pattern.nnz()
            )));
        }
        self.factorize(pattern, &saved.values)?;
        if let Factor::Single { matrix, pattern, fallback, .. } = &mut self.factor
            && saved.in_double
        {
            // the saving solver had fallen back to double precision on this matrix: so does
            // this one (not counted again as a fallback)
            factorize_in_double(fallback, (&self.symbolic, matrix, pattern), self.par, &mut self.workspace)?;
        }
        self.factorizations = saved.factorizations;
        Ok(())
    }

    fn factorize(&mut self, pattern: &SparsityPattern, values: &[f64]) -> Result<FactorKind> {
        if values.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::NonFinite("tangent matrix".into()));
        }
        self.factorizations += 1;
        let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &pattern.col_ptr, None, &pattern.row_idx);
        match &mut self.factor {
            Factor::Double { numeric, matrix } => {
                matrix.clear();
                matrix.extend_from_slice(values);
                numeric.factorize(&self.symbolic, SparseColMatRef::new(sym, values), self.par, &mut self.workspace)
            }
            Factor::Single { numeric, matrix, matrix_f32, fallback, .. } => {
                fallback.kind = None;
                matrix.clear();
                matrix.extend_from_slice(values);
                matrix_f32.clear();
                matrix_f32.extend(values.iter().map(|&v| v as f32));
                let a = SparseColMatRef::new(sym, &matrix_f32[..]);
                numeric.factorize(&self.symbolic, a, self.par, &mut self.workspace)
            }
        }
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        match &mut self.factor {
            Factor::Double { numeric, .. } => {
                numeric.solve(&self.symbolic, (rhs, 1), SOLVE_PAR, &mut self.workspace)?
            }
            Factor::Single { numeric, matrix, pattern, fallback, fallbacks, .. } => {
                let refined = fallback.kind.is_none()
                    && refine(numeric, (&self.symbolic, matrix, pattern), rhs, &mut self.workspace)?;
                if !refined {
                    if fallback.kind.is_none() {
                        *fallbacks += 1;
                        factorize_in_double(
                            fallback,
                            (&self.symbolic, matrix, pattern),
                            self.par,
                            &mut self.workspace,
                        )?;
                    }
                    fallback.solve(&self.symbolic, (rhs, 1), SOLVE_PAR, &mut self.workspace)?;
                }
            }
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::NonFinite("solution of the linear system (singular tangent?)".into()));
        }
        Ok(())
    }

    fn solve_approximately(&mut self, rhs: &mut [f64]) -> Result<()> {
        let Factor::Single { numeric, .. } = &self.factor else {
            return self.solve_in_place(rhs);
        };
        let mut r32: Vec<f32> = rhs.iter().map(|&v| v as f32).collect();
        numeric.solve(&self.symbolic, (&mut r32, 1), SOLVE_PAR, &mut self.workspace)?;
        for (d, s) in rhs.iter_mut().zip(&r32) {
            *d = *s as f64;
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
            for precision in [Precision::Double, Precision::Single] {
                let mut solver =
                    FaerCholesky::analyse_with_precision(&p, Ordering::NestedDissection, precision).unwrap();
                let kind = solver.factorize(&p, &values).unwrap();
                assert_eq!(kind, if shift > 0.0 { FactorKind::Llt } else { FactorKind::Ldlt });
                let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
                let mut x = b.clone();
                solver.solve_in_place(&mut x).unwrap();
                let mut ax = vec![0.0; n];
                p.multiply(&values, &x, &mut ax);
                let err = ax.iter().zip(&b).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
                assert!(err < 1e-10, "shift {shift}, {precision:?}: residual {err}");
                if precision == Precision::Double {
                    // three columns at once give the three single solves
                    let columns: Vec<f64> = (0..3 * n).map(|i| ((i * 7 % 11) as f64).cos()).collect();
                    let mut many = columns.clone();
                    solver.solve_columns_in_place(&mut many, 3).unwrap();
                    for (c, column) in columns.chunks(n).enumerate() {
                        let mut one = column.to_vec();
                        solver.solve_in_place(&mut one).unwrap();
                        let diff =
                            one.iter().zip(&many[c * n..(c + 1) * n]).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
                        assert!(diff < 1e-12, "column {c}: {diff}");
                    }
                }
            }
        }
    }

    /// A nearly singular indefinite matrix (shifted Laplacian, one eigenvalue 1e-8, cond ~ 4e8):
    /// f32 refinement cannot converge (cond eps_f32 ~ 24 > 1), so the single-precision solver
    /// must refactor in f64 and agree with the double-precision solve, once per matrix.
    #[test]
    fn single_precision_falls_back_to_double_when_refinement_fails() {
        let n = 50;
        let cells: Vec<Vec<usize>> = (0..n - 1).map(|i| vec![i, i + 1]).collect();
        let p = SparsityPattern::from_cells(n, n, 1, cells.iter().map(|c| c.as_slice()), |a, _| Some(a));
        // eigenvalues of the Laplacian: 2 - 2 cos(k pi / (n + 1)); put the 10th at 1e-8
        let lambda_10 = 2.0 - 2.0 * (10.0 * std::f64::consts::PI / (n as f64 + 1.0)).cos();
        let mut values = vec![0.0; p.nnz()];
        for i in 0..n {
            values[p.slot(i, i).unwrap()] = 2.0 - lambda_10 + 1e-8;
            if i + 1 < n {
                values[p.slot(i, i + 1).unwrap()] = -1.0;
                values[p.slot(i + 1, i).unwrap()] = -1.0;
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).sin()).collect();
        let solve = |precision: Precision, solver: &mut Option<FaerCholesky>| {
            let s = solver.insert(FaerCholesky::analyse_with_precision(&p, Ordering::Amd, precision).unwrap());
            s.factorize(&p, &values).unwrap();
            let mut x = b.clone();
            s.solve_in_place(&mut x).unwrap();
            x
        };
        let (mut double, mut single) = (None, None);
        let x_double = solve(Precision::Double, &mut double);
        let x_single = solve(Precision::Single, &mut single);
        let single = single.unwrap();
        let scale = crate::vector::norm(&x_double);
        let diff = x_single.iter().zip(&x_double).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
        assert!(diff < 1e-6 * scale, "single vs double: {diff} against |x| = {scale}");
        assert_eq!(single.precision_fallbacks(), 1);
        // a second solve with the same matrix reuses the f64 factor
        let mut single = single;
        let mut again = b.clone();
        single.solve_in_place(&mut again).unwrap();
        assert_eq!(single.precision_fallbacks(), 1);
        assert_eq!(again, x_single);
    }
}

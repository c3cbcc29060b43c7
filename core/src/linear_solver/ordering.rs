//! Fill-reducing orderings for the sparse factorization: faer's approximate minimum degree, or
//! METIS's nested dissection (`METIS_NodeND`, through the `metis-sys` crate, which builds the
//! vendored METIS 5 with the C compiler; the `metis` wrapper crate does not expose NodeND).
//!
//! Nested dissection runs on the compressed graph: consecutive dofs with identical columns
//! (the components of one node) form one vertex, so METIS sees the node graph (a third of the
//! size in 3D) and the dofs of a node stay together, which suits supernodes.

use crate::error::{CoreError, Result};
use crate::sparse::SparsityPattern;

/// Which fill-reducing ordering the symbolic analysis uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ordering {
    /// faer's approximate minimum degree.
    Amd,
    /// METIS nested dissection on the compressed (node) graph: less fill on 3D meshes.
    #[default]
    NestedDissection,
}

/// Groups of consecutive columns with identical row patterns: `starts[g]..starts[g + 1]`.
fn supervariables(pattern: &SparsityPattern) -> Vec<usize> {
    let column = |j: usize| &pattern.row_idx[pattern.col_ptr[j]..pattern.col_ptr[j + 1]];
    let mut starts = vec![0];
    for j in 1..pattern.n {
        if column(j) != column(j - 1) {
            starts.push(j);
        }
    }
    starts.push(pattern.n);
    starts
}

/// A nested-dissection permutation of `pattern`: `perm[new] = old` and its inverse.
pub fn nested_dissection(pattern: &SparsityPattern) -> Result<(Vec<usize>, Vec<usize>)> {
    let starts = supervariables(pattern);
    let n_groups = starts.len() - 1;
    let mut group_of = vec![0usize; pattern.n];
    for g in 0..n_groups {
        group_of[starts[g]..starts[g + 1]].fill(g);
    }
    // the quotient graph without self loops, in METIS's CSR form
    let mut xadj: Vec<i32> = Vec::with_capacity(n_groups + 1);
    let mut adjncy: Vec<i32> = Vec::new();
    let mut weights: Vec<i32> = Vec::with_capacity(n_groups);
    xadj.push(0);
    for g in 0..n_groups {
        let j = starts[g];
        let mut last = usize::MAX;
        for &r in &pattern.row_idx[pattern.col_ptr[j]..pattern.col_ptr[j + 1]] {
            let h = group_of[r];
            if h != g && h != last {
                adjncy.push(h as i32);
                last = h;
            }
        }
        xadj.push(adjncy.len() as i32);
        weights.push((starts[g + 1] - starts[g]) as i32);
    }
    let too_large = || CoreError::Factorization("the matrix is too large for METIS's 32-bit indices".into());
    let mut nvtxs = i32::try_from(n_groups).map_err(|_| too_large())?;
    i32::try_from(adjncy.len()).map_err(|_| too_large())?;
    let mut perm = vec![0i32; n_groups];
    let mut iperm = vec![0i32; n_groups];
    // METIS keeps its random number generator in global state (GKlib), so two calls at once (an
    // ensemble's members in one process) would race on it and order differently: one at a time.
    let _one_at_a_time = METIS_LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    // SAFETY: METIS reads nvtxs, xadj (nvtxs + 1 entries), adjncy (xadj[nvtxs] entries) and
    // vwgt (nvtxs entries), all owned here and alive for the call, and writes nvtxs entries
    // to perm and iperm; a null options pointer selects METIS's defaults. The lock above keeps
    // calls from running concurrently.
    let status = unsafe {
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            weights.as_mut_ptr(),
            std::ptr::null_mut(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(CoreError::Factorization(format!("METIS_NodeND failed (status {status})")));
    }
    // expand: the groups in METIS's order, each group's dofs in their own order
    let mut forward = Vec::with_capacity(pattern.n);
    for &g in &perm {
        forward.extend(starts[g as usize]..starts[g as usize + 1]);
    }
    let mut inverse = vec![0usize; pattern.n];
    for (new, &old) in forward.iter().enumerate() {
        inverse[old] = new;
    }
    Ok((forward, inverse))
}

/// Serializes the calls into METIS (see [`nested_dissection`]).
static METIS_LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nested_dissection_is_a_permutation_that_keeps_node_dofs_together() {
        // a 20 x 20 grid of nodes with 3 dofs each, 5-point coupling
        let n = 20;
        let cells: Vec<Vec<usize>> = (0..n * n)
            .flat_map(|i| {
                let (x, y) = (i % n, i / n);
                let mut c = Vec::new();
                if x + 1 < n {
                    c.push(vec![i, i + 1]);
                }
                if y + 1 < n {
                    c.push(vec![i, i + n]);
                }
                c
            })
            .collect();
        let p = SparsityPattern::from_cells(3 * n * n, n * n, 3, cells.iter().map(|c| c.as_slice()), |a, c| {
            Some(3 * a + c)
        });
        let (forward, inverse) = nested_dissection(&p).unwrap();
        let mut seen = forward.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..3 * n * n).collect::<Vec<_>>());
        for (new, &old) in forward.iter().enumerate() {
            assert_eq!(inverse[old], new);
        }
        for chunk in forward.chunks(3) {
            assert_eq!(chunk[0] % 3, 0);
            assert_eq!((chunk[1], chunk[2]), (chunk[0] + 1, chunk[0] + 2));
        }
    }
}

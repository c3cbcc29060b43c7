//! Sparsity pattern built once per topology, and element-to-slot maps so that assembly writes
//! straight into the value array of the compressed-column matrix (no triplets per iteration).

use std::sync::Arc;

/// Marks a local (row, column) pair that has no slot because one of the dofs is constrained.
pub const NO_SLOT: u32 = u32::MAX;

/// A square compressed-sparse-column pattern over the free degrees of freedom, holding both
/// triangles (so symmetric and unsymmetric factorizations can use it). The index arrays are
/// shared: a clone (e.g. the one a single-precision factor keeps for its refinement) costs no
/// memory.
#[derive(Debug, Clone)]
pub struct SparsityPattern {
    pub n: usize,
    pub col_ptr: Arc<[usize]>,
    pub row_idx: Arc<[usize]>,
}

impl SparsityPattern {
    /// Builds the pattern from node connectivity: every pair of nodes that share a cell (any
    /// list in `cells`) couples all their free dofs. `dof_of(node, component)` gives the free dof
    /// number or `None` when the dof is constrained.
    pub fn from_cells<'a>(
        n_free: usize,
        n_nodes: usize,
        dofs_per_node: usize,
        cells: impl Iterator<Item = &'a [usize]> + Clone,
        dof_of: impl Fn(usize, usize) -> Option<usize>,
    ) -> Self {
        // Node-to-node adjacency first (small), then expand to dofs.
        let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); n_nodes];
        for cell in cells {
            for &a in cell {
                adjacency[a].extend_from_slice(cell);
            }
        }
        let mut columns: Vec<Vec<usize>> = vec![Vec::new(); n_free];
        for (node, neighbours) in adjacency.iter_mut().enumerate() {
            neighbours.sort_unstable();
            neighbours.dedup();
            for c in 0..dofs_per_node {
                let Some(col) = dof_of(node, c) else { continue };
                let column = &mut columns[col];
                for &other in neighbours.iter() {
                    for r in 0..dofs_per_node {
                        if let Some(row) = dof_of(other, r) {
                            column.push(row);
                        }
                    }
                }
            }
        }
        let mut col_ptr = Vec::with_capacity(n_free + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        for (col, mut column) in columns.into_iter().enumerate() {
            column.push(col); // every dof keeps its diagonal
            column.sort_unstable();
            column.dedup();
            row_idx.extend_from_slice(&column);
            col_ptr.push(row_idx.len());
        }
        Self { n: n_free, col_ptr: col_ptr.into(), row_idx: row_idx.into() }
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry (row, col) in the value array.
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    /// Slot map for one element: `slots[i * n + j]` is the value index of local entry (i, j)
    /// (row i, column j), or [`NO_SLOT`] when either dof is constrained.
    pub fn element_slots(&self, dofs: &[Option<usize>], slots: &mut Vec<u32>) {
        let n = dofs.len();
        slots.clear();
        slots.resize(n * n, NO_SLOT);
        for (i, ri) in dofs.iter().enumerate() {
            let Some(r) = ri else { continue };
            for (j, cj) in dofs.iter().enumerate() {
                let Some(c) = cj else { continue };
                let s = self.slot(*r, *c).expect("element dofs are in the pattern by construction");
                slots[i * n + j] = s as u32;
            }
        }
    }

    /// The matrix with `values` on this pattern, as a sprs compressed-column view (no copy).
    pub fn as_sprs<'a>(&'a self, values: &'a [f64]) -> sprs::CsMatViewI<'a, f64, usize> {
        sprs::CsMatViewI::try_new_csc((self.n, self.n), &self.col_ptr[..], &self.row_idx[..], values)
            .map_err(|(_, _, _, e)| e)
            .expect("the pattern is a valid compressed-column structure by construction")
    }

    /// y = A x for the values `values` on this pattern: y_i = sum_k A_ik x_k, column by
    /// column. Written out rather than through sprs's product because a sprs view checks the
    /// whole structure (sorted, in range) each time one is made, as costly as the product
    /// itself; this pattern is valid by construction ([`SparsityPattern::from_cells`]), and
    /// the single-precision factor's refinement multiplies by its matrix at every refined
    /// solve. (The damped flow's drag, mostly zeros, is multiplied through
    /// [`SparsityPattern::nonzeros`] instead.)
    pub fn multiply(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        assert!(
            values.len() == self.nnz() && x.len() == self.n && y.len() == self.n,
            "multiply: {} values, {} x and {} y entries for a pattern of {} entries and {} dofs",
            values.len(),
            x.len(),
            y.len(),
            self.nnz(),
            self.n
        );
        y.fill(0.0);
        for (&x_k, bounds) in x.iter().zip(self.col_ptr.windows(2)) {
            let range = bounds[0]..bounds[1];
            for (&row, &a) in self.row_idx[range.clone()].iter().zip(&values[range]) {
                y[row] += a * x_k;
            }
        }
    }

    /// The matrix with `values` on this pattern, its exact zeros left out, as an owned sprs
    /// matrix (its structure checked once, here): for a matrix multiplied many times whose
    /// pattern holds many zeros. The consistent mass M_(ai)(bj) = delta_ij int N_a N_b dV
    /// couples no two components, so on a 3D pattern two thirds of its entries are zeros; the
    /// damped flow multiplies by its drag at every residual assembly
    /// ([`sprs::prod::mul_acc_mat_vec_csc`] gives y += A x over the entries kept: the same sums
    /// as [`SparsityPattern::multiply`] but for the zero terms).
    pub fn nonzeros(&self, values: &[f64]) -> sprs::CsMat<f64> {
        assert_eq!(
            values.len(),
            self.nnz(),
            "nonzeros: {} values for a pattern of {} entries",
            values.len(),
            self.nnz()
        );
        let mut col_ptr = Vec::with_capacity(self.n + 1);
        col_ptr.push(0);
        let (mut rows, mut kept) = (Vec::new(), Vec::new());
        for bounds in self.col_ptr.windows(2) {
            let range = bounds[0]..bounds[1];
            for (&row, &value) in self.row_idx[range.clone()].iter().zip(&values[range]) {
                if value != 0.0 {
                    rows.push(row);
                    kept.push(value);
                }
            }
            col_ptr.push(rows.len());
        }
        sprs::CsMat::new_csc((self.n, self.n), col_ptr, rows, kept)
    }

    /// Writes the matrix in Matrix Market format (for inspection, or to compare with another
    /// code's tangent).
    pub fn write_matrix_market(&self, values: &[f64], path: &std::path::Path) -> std::io::Result<()> {
        sprs::io::write_matrix_market(path, self.as_sprs(values))
    }

    /// Writes a symmetric matrix's lower triangle as a `symmetric` Matrix Market file, the form
    /// other sparse solvers (CHOLMOD, MUMPS) read; atomically (a `.part` file renamed into
    /// place). The upper triangle's values are not written: the linear solvers read the lower.
    /// (Written here because sprs's symmetric writer stores the upper triangle, where the
    /// format's specification has the lower.)
    pub fn write_matrix_market_symmetric(&self, values: &[f64], path: &std::path::Path) -> std::io::Result<()> {
        use std::io::Write;
        assert_eq!(values.len(), self.nnz(), "{} values for a pattern of {} entries", values.len(), self.nnz());
        let mut part = path.as_os_str().to_owned();
        part.push(".part");
        let part = std::path::PathBuf::from(part);
        let lower = |j: usize| (self.col_ptr[j]..self.col_ptr[j + 1]).filter(move |&k| self.row_idx[k] >= j);
        let entries: usize = (0..self.n).map(|j| lower(j).count()).sum();
        let write = || -> std::io::Result<()> {
            let mut out = std::io::BufWriter::new(std::fs::File::create(&part)?);
            writeln!(out, "%%MatrixMarket matrix coordinate real symmetric")?;
            writeln!(out, "{} {} {entries}", self.n, self.n)?;
            for j in 0..self.n {
                for k in lower(j) {
                    // Rust's shortest representation that reads back to the same f64
                    writeln!(out, "{} {} {:e}", self.row_idx[k] + 1, j + 1, values[k])?;
                }
            }
            out.into_inner().map_err(|e| e.into_error())?.sync_all()
        };
        write().and_then(|()| std::fs::rename(&part, path)).inspect_err(|_| {
            let _ = std::fs::remove_file(&part);
        })
    }

    /// Reads a square Matrix Market file (a `symmetric` one gives both triangles) as a pattern
    /// holding both triangles and its values, as a model assembles them.
    pub fn read_matrix_market(path: &std::path::Path) -> Result<(Self, Vec<f64>), sprs::io::IoError> {
        let triplets: sprs::TriMat<f64> = sprs::io::read_matrix_market(path)?;
        if triplets.rows() != triplets.cols() {
            return Err(sprs::io::IoError::BadMatrixMarketFile);
        }
        // the compressed-column conversion sorts the rows of each column and sums duplicates
        let (col_ptr, row_idx, values) = triplets.to_csc::<usize>().into_raw_storage();
        Ok((Self { n: col_ptr.len() - 1, col_ptr: col_ptr.into(), row_idx: row_idx.into() }, values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    /// The nonzero entries' product is the full pattern's: y = A x for a 2x2 block pattern
    /// whose off-diagonal block is zero, by hand.
    #[test]
    fn the_nonzeros_multiply_as_the_whole_pattern() {
        let cells: Vec<Vec<usize>> = vec![vec![0, 1]];
        let p = SparsityPattern::from_cells(2, 2, 1, cells.iter().map(|c| c.as_slice()), |n, _| Some(n));
        // columns [a00 a10 | a01 a11] = [2 0 | 0 3]
        let values = [2.0, 0.0, 0.0, 3.0];
        let kept = p.nonzeros(&values);
        assert_eq!(kept.nnz(), 2);
        let x = [5.0, 7.0];
        let mut y = [1.0, 1.0];
        sprs::prod::mul_acc_mat_vec_csc(kept.view(), &x[..], &mut y[..]);
        assert_eq!(y, [11.0, 22.0]);
    }

    #[test]
    fn pattern_of_two_bars_with_a_constrained_end() {
        // nodes 0-1-2 in two 2-node cells, 1 dof per node, node 0 constrained.
        let cells: Vec<Vec<usize>> = vec![vec![0, 1], vec![1, 2]];
        let dof = |n: usize, _c: usize| if n == 0 { None } else { Some(n - 1) };
        let p = SparsityPattern::from_cells(2, 3, 1, cells.iter().map(|c| c.as_slice()), dof);
        assert_eq!(p.col_ptr[..], [0, 2, 4]);
        assert_eq!(p.row_idx[..], [0, 1, 0, 1]);
        let mut slots = vec![];
        p.element_slots(&[None, Some(0)], &mut slots);
        assert_eq!(slots, vec![NO_SLOT, NO_SLOT, NO_SLOT, 0]);
    }

    #[test]
    fn matrix_market_round_trip_and_product() {
        let cells: Vec<Vec<usize>> = vec![vec![0, 1], vec![1, 2]];
        let p = SparsityPattern::from_cells(3, 3, 1, cells.iter().map(|c| c.as_slice()), |n, _| Some(n));
        let values: Vec<f64> = (0..p.nnz()).map(|k| 1.0 + k as f64).collect();
        let path = std::env::temp_dir().join(format!("stiction-pattern-{}.mtx", std::process::id()));
        p.write_matrix_market(&values, &path).unwrap();
        let back: sprs::TriMat<f64> = sprs::io::read_matrix_market(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        let back = back.to_csc::<usize>();
        assert_eq!(back.indptr().raw_storage(), &p.col_ptr[..]);
        assert_eq!(back.indices(), &p.row_idx[..]);
        assert_eq!(back.data(), &values[..]);
        // y = A x by hand for the tridiagonal pattern [[1,3,.],[2,4,6],[.,5,7]]
        let mut y = vec![0.0; 3];
        p.multiply(&values, &[1.0, 10.0, 100.0], &mut y);
        assert_eq!(y, vec![1.0 + 30.0, 2.0 + 40.0 + 600.0, 50.0 + 700.0]);
    }

    #[test]
    fn symmetric_matrix_market_holds_the_lower_triangle_and_reads_back_whole() {
        let cells: Vec<Vec<usize>> = vec![vec![0, 1], vec![1, 2]];
        let p = SparsityPattern::from_cells(3, 3, 1, cells.iter().map(|c| c.as_slice()), |n, _| Some(n));
        // [[4, 1, .], [1, 5, 2], [., 2, 6]] column by column
        let values = vec![4.0, 1.0, 1.0, 5.0, 2.0, 2.0, 6.0];
        let path = std::env::temp_dir().join(format!("stiction-symmetric-{}.mtx", std::process::id()));
        p.write_matrix_market_symmetric(&values, &path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let (back, back_values) = SparsityPattern::read_matrix_market(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        assert!(text.starts_with("%%MatrixMarket matrix coordinate real symmetric"), "{text}");
        let entries: Vec<(usize, usize)> = text
            .lines()
            .filter(|l| !l.starts_with('%'))
            .skip(1)
            .map(|l| {
                let w: Vec<usize> = l.split_whitespace().take(2).map(|w| w.parse().unwrap()).collect();
                (w[0], w[1])
            })
            .collect();
        // 1-based (row, column) of the lower triangle, each once
        assert_eq!(entries, vec![(1, 1), (2, 1), (2, 2), (3, 2), (3, 3)]);
        assert_eq!(back.n, 3);
        assert_eq!(back.col_ptr[..], p.col_ptr[..]);
        assert_eq!(back.row_idx[..], p.row_idx[..]);
        assert_eq!(back_values, values);
    }
}

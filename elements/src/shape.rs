//! Lagrange shape functions and their reference derivatives, in gmsh's local node order.
//!
//! Barycentric coordinates: tetrahedron L = (1 - x - y - z, x, y, z), triangle
//! L = (1 - x - y, x, y). Quadratic corner functions L_i (2 L_i - 1), edge functions 4 L_i L_j.

use stiction_core::mesh::CellType;

/// Evaluates shape functions `n[a]` and reference derivatives `dn[a][k]` (k < cell dim) at `xi`.
pub fn evaluate(cell: CellType, xi: &[f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    match cell {
        CellType::Line2 => {
            let s = xi[0];
            n[0] = 0.5 * (1.0 - s);
            n[1] = 0.5 * (1.0 + s);
            dn[0] = [-0.5, 0.0, 0.0];
            dn[1] = [0.5, 0.0, 0.0];
        }
        CellType::Line3 => {
            let s = xi[0];
            n[0] = 0.5 * s * (s - 1.0);
            n[1] = 0.5 * s * (s + 1.0);
            n[2] = 1.0 - s * s;
            dn[0] = [s - 0.5, 0.0, 0.0];
            dn[1] = [s + 0.5, 0.0, 0.0];
            dn[2] = [-2.0 * s, 0.0, 0.0];
        }
        CellType::Tri3 => {
            n[0] = 1.0 - xi[0] - xi[1];
            n[1] = xi[0];
            n[2] = xi[1];
            dn[0] = [-1.0, -1.0, 0.0];
            dn[1] = [1.0, 0.0, 0.0];
            dn[2] = [0.0, 1.0, 0.0];
        }
        CellType::Tri6 => {
            let l = [1.0 - xi[0] - xi[1], xi[0], xi[1]];
            let dl = [[-1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
            quadratic_simplex(&l, &dl, &[(0, 1), (1, 2), (2, 0)], n, dn);
        }
        CellType::Tet4 => {
            n[0] = 1.0 - xi[0] - xi[1] - xi[2];
            n[1] = xi[0];
            n[2] = xi[1];
            n[3] = xi[2];
            dn[0] = [-1.0, -1.0, -1.0];
            dn[1] = [1.0, 0.0, 0.0];
            dn[2] = [0.0, 1.0, 0.0];
            dn[3] = [0.0, 0.0, 1.0];
        }
        CellType::Tet10 => {
            let l = [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]];
            let dl = [[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            quadratic_simplex(&l, &dl, &[(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)], n, dn);
        }
    }
}

fn quadratic_simplex(l: &[f64], dl: &[[f64; 3]], edges: &[(usize, usize)], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let nc = l.len();
    for i in 0..nc {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        for k in 0..3 {
            dn[i][k] = (4.0 * l[i] - 1.0) * dl[i][k];
        }
    }
    for (e, &(i, j)) in edges.iter().enumerate() {
        n[nc + e] = 4.0 * l[i] * l[j];
        for k in 0..3 {
            dn[nc + e][k] = 4.0 * (dl[i][k] * l[j] + l[i] * dl[j][k]);
        }
    }
}

/// Reference coordinates of the nodes (for tests and extrapolation).
pub fn reference_nodes(cell: CellType) -> Vec<[f64; 3]> {
    match cell {
        CellType::Line2 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        CellType::Line3 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        CellType::Tri3 => vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        CellType::Tri6 => {
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 0.5, 0.0]]
        }
        CellType::Tet4 => vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        CellType::Tet10 => vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
            [0.0, 0.0, 0.5],
            [0.0, 0.5, 0.5],
            [0.5, 0.0, 0.5],
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [CellType; 6] =
        [CellType::Line2, CellType::Line3, CellType::Tri3, CellType::Tri6, CellType::Tet4, CellType::Tet10];

    #[test]
    fn kronecker_property_and_partition_of_unity() {
        for cell in ALL {
            let nodes = reference_nodes(cell);
            let nn = cell.n_nodes();
            let mut n = vec![0.0; nn];
            let mut dn = vec![[0.0; 3]; nn];
            for (b, xb) in nodes.iter().enumerate() {
                evaluate(cell, xb, &mut n, &mut dn);
                for a in 0..nn {
                    let expected = if a == b { 1.0 } else { 0.0 };
                    assert!((n[a] - expected).abs() < 1e-14, "{cell:?} N{a} at node {b}");
                }
                for k in 0..3 {
                    let s: f64 = dn.iter().map(|d| d[k]).sum();
                    assert!(s.abs() < 1e-13, "{cell:?} derivatives sum to {s}");
                }
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        for cell in ALL {
            let nn = cell.n_nodes();
            let xi = [0.21, 0.17, 0.13];
            let (mut n0, mut n1) = (vec![0.0; nn], vec![0.0; nn]);
            let mut dn = vec![[0.0; 3]; nn];
            let mut scratch = vec![[0.0; 3]; nn];
            evaluate(cell, &xi, &mut n0, &mut dn);
            for k in 0..cell.dim() {
                let h = 1e-6;
                let (mut xp, mut xm) = (xi, xi);
                xp[k] += h;
                xm[k] -= h;
                evaluate(cell, &xp, &mut n1, &mut scratch);
                evaluate(cell, &xm, &mut n0, &mut scratch);
                for a in 0..nn {
                    let fd = (n1[a] - n0[a]) / (2.0 * h);
                    assert!((fd - dn[a][k]).abs() < 1e-8, "{cell:?} dN{a}/dxi{k}: {fd} vs {}", dn[a][k]);
                }
            }
        }
    }
}

#[cfg(test)]
mod vtk_order_tests {
    use super::reference_nodes;
    use stiction_core::mesh::CellType;
    use stiction_core::output::vtk::vtk_cell;

    /// VTK's quadratic cells place mid-edge node k >= corners on edge VTK_EDGES[k - corners];
    /// the permutation must pick the gmsh node at that edge's midpoint.
    #[test]
    fn gmsh_to_vtk_permutation_puts_midside_nodes_on_vtk_edges() {
        let vtk_edges: [(CellType, &[(usize, usize)]); 3] = [
            (CellType::Tet10, &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]),
            (CellType::Tri6, &[(0, 1), (1, 2), (2, 0)]),
            (CellType::Line3, &[(0, 1)]),
        ];
        for (cell, edges) in vtk_edges {
            let x = reference_nodes(cell);
            let (_, perm) = vtk_cell(cell);
            let nc = cell.n_corners();
            for (k, &(a, b)) in edges.iter().enumerate() {
                let mid: Vec<f64> = (0..3).map(|d| 0.5 * (x[perm[a]][d] + x[perm[b]][d])).collect();
                let node = x[perm[nc + k]];
                assert!((0..3).all(|d| (node[d] - mid[d]).abs() < 1e-15), "{cell:?} VTK edge {k}");
            }
        }
    }
}

//! Structured meshes generated without gmsh: quick models, tests and benchmarks.

use stiction_core::mesh::{CellBlock, CellType, Mesh, PhysicalGroup};

/// A small deterministic pseudo-random perturbation in [-1, 1].
fn wobble(i: usize, k: usize) -> f64 {
    let x = ((i * 7919 + k * 104_729) % 10_007) as f64 / 10_007.0;
    2.0 * x - 1.0
}

pub fn add_midside_nodes(
    nodes: &mut Vec<[f64; 3]>,
    conn: &mut Vec<usize>,
    corners: usize,
    edges: &[(usize, usize)],
) -> Vec<usize> {
    // conn holds corner lists; returns quadratic connectivity
    use std::collections::HashMap;
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut out = Vec::new();
    for cell in conn.chunks_exact(corners) {
        out.extend_from_slice(cell);
        for &(a, b) in edges {
            let (p, q) = (cell[a].min(cell[b]), cell[a].max(cell[b]));
            let idx = *mid.entry((p, q)).or_insert_with(|| {
                let x = nodes[p];
                let y = nodes[q];
                nodes.push([(x[0] + y[0]) / 2.0, (x[1] + y[1]) / 2.0, (x[2] + y[2]) / 2.0]);
                nodes.len() - 1
            });
            out.push(idx);
        }
    }
    conn.clear();
    out
}

/// Unit cube [0, 1]^3 in n^3 sub-cubes of 6 tetrahedra each (tet4, or tet10 with straight
/// edges). Interior nodes are moved by up to `distortion * h` in each direction.
/// Groups: "body" (dim 3).
pub fn structured_cube(n: usize, quadratic: bool, distortion: f64) -> Mesh {
    let h = 1.0 / n as f64;
    let id = |i: usize, j: usize, k: usize| (i * (n + 1) + j) * (n + 1) + k;
    let mut nodes = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            for k in 0..=n {
                let mut x = [i as f64 * h, j as f64 * h, k as f64 * h];
                let interior = [i, j, k].iter().all(|&c| c > 0 && c < n);
                if interior {
                    for (d, xd) in x.iter_mut().enumerate() {
                        *xd += distortion * h * wobble(id(i, j, k), d);
                    }
                }
                nodes.push(x);
            }
        }
    }
    let mut conn = Vec::new();
    let perms = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                for p in perms {
                    let mut c = [i, j, k];
                    let mut tet = vec![id(c[0], c[1], c[2])];
                    for axis in p {
                        c[axis] += 1;
                        tet.push(id(c[0], c[1], c[2]));
                    }
                    // orient positively
                    let v = |a: usize| nodes[tet[a]];
                    let (x0, x1, x2, x3) = (v(0), v(1), v(2), v(3));
                    let d = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                    let (e1, e2, e3) = (d(x1, x0), d(x2, x0), d(x3, x0));
                    let det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
                        + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
                    if det < 0.0 {
                        tet.swap(1, 2);
                    }
                    conn.extend(tet);
                }
            }
        }
    }
    let (cell_type, connectivity) = if quadratic {
        let q = add_midside_nodes(&mut nodes, &mut conn, 4, &[(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)]);
        (CellType::Tet10, q)
    } else {
        (CellType::Tet4, conn)
    };
    Mesh {
        nodes,
        blocks: vec![CellBlock { cell_type, physical_tag: 1, connectivity }],
        groups: vec![PhysicalGroup { name: "body".into(), dim: 3, tag: 1 }],
        source: "structured cube".into(),
    }
}

/// Rectangle [r0, r0 + w] x [0, hgt] in the x-y plane, n x n squares of 2 triangles each (tri3
/// or tri6), interior nodes moved by up to `distortion * h`. Groups: "body" (dim 2).
pub fn structured_rectangle(n: usize, r0: f64, w: f64, hgt: f64, quadratic: bool, distortion: f64) -> Mesh {
    let id = |i: usize, j: usize| i * (n + 1) + j;
    let mut nodes = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let mut x = [r0 + w * i as f64 / n as f64, hgt * j as f64 / n as f64, 0.0];
            if i > 0 && i < n && j > 0 && j < n {
                x[0] += distortion * w / n as f64 * wobble(id(i, j), 0);
                x[1] += distortion * hgt / n as f64 * wobble(id(i, j), 1);
            }
            nodes.push(x);
        }
    }
    let mut conn = Vec::new();
    for i in 0..n {
        for j in 0..n {
            conn.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            conn.extend([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let (cell_type, connectivity) = if quadratic {
        (CellType::Tri6, add_midside_nodes(&mut nodes, &mut conn, 3, &[(0, 1), (1, 2), (2, 0)]))
    } else {
        (CellType::Tri3, conn)
    };
    Mesh {
        nodes,
        blocks: vec![CellBlock { cell_type, physical_tag: 1, connectivity }],
        groups: vec![PhysicalGroup { name: "body".into(), dim: 2, tag: 1 }],
        source: "structured rectangle".into(),
    }
}

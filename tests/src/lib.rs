//! Helpers for Stiction's integration and validation tests: structured meshes with controlled
//! distortion, direct linear/Newton solves of a model, L2 error norms, and running shipped case
//! files into a scratch output directory.

use std::path::PathBuf;
use std::sync::Arc;
use stiction::build::BuiltModel;
use stiction::case;
use stiction::run::{RunOptions, RunSummary, run_model};
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::linear_solver::SparseSolver;
use stiction_core::mesh::{CellBlock, CellType, Mesh, PhysicalGroup};
use stiction_core::model::{Model, Prescribed};
use stiction_core::newton::{IncrementReport, NewtonSettings, solve_increment};
use stiction_core::quadrature::QuadratureRule;
use stiction_elements::shape;

/// The workspace root (where `cases/` lives).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

/// Loads a shipped case (path relative to the workspace root), applies `--set` overrides, runs
/// it into `target/test-out/<label>` and returns the model in its final state.
pub fn run_case(relative: &str, sets: &[&str], label: &str) -> (BuiltModel, RunSummary) {
    let path = workspace_root().join(relative);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = case::load(&path, &sets).unwrap_or_else(|e| panic!("{e}"));
    let mut built = stiction::build::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let out = workspace_root().join("target").join("test-out").join(label);
    let options = RunOptions { out: Some(out), progress: false };
    let summary = run_model(&loaded, &mut built, &options).unwrap_or_else(|e| panic!("{e}"));
    (built, summary)
}

/// A small deterministic pseudo-random perturbation in [-1, 1].
fn wobble(i: usize, k: usize) -> f64 {
    let x = ((i * 7919 + k * 104_729) % 10_007) as f64 / 10_007.0;
    2.0 * x - 1.0
}

fn add_midside_nodes(
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

/// Prescribes `exact(x)` on every node for which `on_boundary(x)` holds.
pub fn prescribe_where(
    model: &mut Model,
    on_boundary: impl Fn([f64; 3]) -> bool,
    exact: impl Fn([f64; 3]) -> [f64; 3],
) {
    let dpn = model.dofs_per_node();
    let ramp = Arc::new(Amplitude::ramp());
    let nodes = model.mesh.nodes.clone();
    for (n, x) in nodes.iter().enumerate() {
        if on_boundary(*x) {
            let u = exact(*x);
            for c in 0..dpn {
                model
                    .prescribe(Prescribed {
                        dof: n * dpn + c,
                        scale: u[c],
                        amplitude: ramp.clone(),
                        source: "test".into(),
                    })
                    .unwrap();
            }
        }
    }
}

/// Finalizes the model and solves equilibrium at t = 1 (amplitude "ramp" at full value).
pub fn solve_at_full_load(model: &mut Model) -> IncrementReport {
    model.finalize().unwrap();
    let mut solver = SparseSolver::new(model.pattern()).unwrap();
    let settings = NewtonSettings { tol_residual: 1e-10, ..NewtonSettings::default() };
    let report = solve_increment(model, &mut solver, 1.0, &settings, 0.0).unwrap_or_else(|e| panic!("{e}"));
    model.commit();
    report
}

/// L2 norm of (u_h - u_exact) and of u_exact over the solid cells, with `rule` on each cell
/// (axisymmetric: weighted by 2 pi r).
pub fn l2_error(model: &Model, rule: &QuadratureRule, exact: impl Fn([f64; 3]) -> [f64; 3]) -> (f64, f64) {
    let dpn = model.dofs_per_node();
    let (mut err, mut norm) = (0.0, 0.0);
    for set in &model.sets {
        let ct = set.kernel.cell_type();
        let nn = ct.n_nodes();
        let d = ct.dim();
        let mut n = vec![0.0; nn];
        let mut dn = vec![[0.0; 3]; nn];
        for c in 0..set.n_cells() {
            let cell = set.cell(c);
            for (xi, w) in rule.points.iter().zip(&rule.weights) {
                shape::evaluate(ct, xi, &mut n, &mut dn);
                let mut x = [0.0; 3];
                let mut uh = [0.0; 3];
                let mut j = [[0.0; 3]; 3];
                for (a, &node) in cell.iter().enumerate() {
                    let xa = model.mesh.nodes[node];
                    for i in 0..3 {
                        x[i] += n[a] * xa[i];
                    }
                    for i in 0..dpn {
                        uh[i] += n[a] * model.displacement[node * dpn + i];
                    }
                    for i in 0..d {
                        for k in 0..d {
                            j[i][k] += xa[i] * dn[a][k];
                        }
                    }
                }
                let det = if d == 3 {
                    j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
                } else {
                    (j[0][0] * j[1][1] - j[0][1] * j[1][0]) * 2.0 * std::f64::consts::PI * x[0]
                };
                let ue = exact(x);
                for i in 0..dpn {
                    err += w * det * (uh[i] - ue[i]).powi(2);
                    norm += w * det * ue[i].powi(2);
                }
            }
        }
    }
    (err.sqrt(), norm.sqrt())
}

/// Builds a single-set model.
pub fn model_with(mesh: Mesh, kin: Kinematics, material: Arc<dyn stiction_core::material::Material>) -> Model {
    let mesh = Arc::new(mesh);
    let mut model = Model::new(mesh.clone(), kin);
    for b in &mesh.blocks {
        let kernel =
            stiction_elements::SolidKernel::new(b.cell_type, kin, stiction_elements::QuadratureChoice::Standard)
                .unwrap();
        model.sets.push(stiction_core::model::ElementSet::new(
            "body",
            Box::new(kernel),
            material.clone(),
            b.connectivity.clone(),
        ));
    }
    model
}

//! Helpers for Stiction's integration and validation tests: structured meshes with controlled
//! distortion, direct linear/Newton solves of a model, L2 error norms, and running shipped case
//! files into a scratch output directory.

pub mod greenwood_tripp;
pub mod gw_surface;
pub mod half_space_lj;
pub mod validation_record;

pub use validation_record::{Tolerance, validate};

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use stiction::build::BuiltModel;
use stiction::case;
use stiction::run::{RunOptions, RunSummary, run_model};
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver};
use stiction_core::mesh::Mesh;
use stiction_core::model::{Model, Prescribed};
use stiction_core::nonlinear::{IncrementReport, NewtonSettings, ReferenceScales, solve_increment};
use stiction_core::quadrature::QuadratureRule;
use stiction_elements::shape;

/// The workspace root (where `cases/` lives).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

/// Loads a shipped case (path relative to the workspace root) with `--set` overrides and builds
/// its model without running it.
pub fn build_case(relative: &str, sets: &[&str]) -> (case::LoadedCase, BuiltModel) {
    let path = workspace_root().join(relative);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = case::load(&path, &sets).unwrap_or_else(|e| panic!("{e}"));
    let built = stiction::build::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    (loaded, built)
}

/// Claims the scratch folder `target/test-out/<label>` for one test and returns its path; panics
/// if another test of this process claimed it already. The tests share one binary and run two
/// at a time, so two tests writing one folder would corrupt each other's files at random: a
/// label used twice fails at once, whichever test comes second.
pub fn claim_output_dir(label: &str) -> PathBuf {
    static CLAIMED: Mutex<BTreeSet<String>> = Mutex::new(BTreeSet::new());
    let fresh = CLAIMED.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).insert(label.to_string());
    assert!(fresh, "two tests write into target/test-out/{label}: give one of them another label");
    workspace_root().join("target").join("test-out").join(label)
}

/// Runs the case file at `path` (a test's own, e.g. written into its claimed folder) into `out`,
/// with no overrides.
pub fn run_case_file(path: &std::path::Path, out: PathBuf) -> RunSummary {
    let loaded = case::load(path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let mut built = stiction::build::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let options = RunOptions { out: Some(out), overwrite: true, ..Default::default() };
    run_model(&loaded, &mut built, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// Loads a shipped case (path relative to the workspace root), applies `--set` overrides, runs
/// it into `target/test-out/<label>` (claimed, [`claim_output_dir`]) and returns the model in
/// its final state.
pub fn run_case(relative: &str, sets: &[&str], label: &str) -> (BuiltModel, RunSummary) {
    let (loaded, mut built) = build_case(relative, sets);
    let out = claim_output_dir(label);
    let options = RunOptions { out: Some(out), overwrite: true, ..Default::default() };
    let summary = run_model(&loaded, &mut built, &options).unwrap_or_else(|e| panic!("{e}"));
    (built, summary)
}

/// A points file with one asperity at the pole (x, y = 0, height 2.786 nm, the Ru cases'),
/// written under `target/test-out/<dir>/` through a temporary file and a rename, so that tests
/// sharing it never read it half written.
pub fn one_asperity_at_the_pole(dir: &str) -> PathBuf {
    let dir = workspace_root().join("target").join("test-out").join(dir);
    std::fs::create_dir_all(&dir).unwrap();
    let points = dir.join("one-asperity.csv");
    let partial = dir.join(format!("one-asperity.csv.{:?}", std::thread::current().id()));
    std::fs::write(&partial, "x,y,height\n0.0,0.0,2.786\n").unwrap();
    std::fs::rename(&partial, &points).unwrap();
    points
}

/// The named columns of a run's history.csv, one vector per row (the initial state included).
pub fn history_columns(dir: &std::path::Path, names: &[&str]) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let index: Vec<usize> = names
        .iter()
        .map(|n| header.iter().position(|h| h == n).unwrap_or_else(|| panic!("no column {n} in {header:?}")))
        .collect();
    text.lines()
        .skip(1)
        .map(|line| {
            let v: Vec<&str> = line.split(',').collect();
            index.iter().map(|&i| v[i].parse().unwrap()).collect()
        })
        .collect()
}

pub use stiction_meshes::generate::{structured_cube, structured_rectangle};

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
    let mut solver = FaerCholesky::analyse(model.pattern()).unwrap();
    let settings = NewtonSettings { tol_residual: 1e-10, ..NewtonSettings::default() };
    let report = solve_increment(model, &mut solver, 1.0, &settings, ReferenceScales::default())
        .unwrap_or_else(|e| panic!("{e}"));
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

/// Every integration point of the model's solid: (set index, cell, point, position, stress),
/// with the stresses of the last assembly.
pub fn integration_points(model: &Model) -> Vec<(usize, usize, usize, [f64; 3], [f64; 6])> {
    use stiction_core::element::ElementKernel;
    let mut out = Vec::new();
    for (si, set) in model.sets.iter().enumerate() {
        let kernel = stiction_elements::SolidKernel::new(
            set.kernel.cell_type(),
            model.kinematics,
            stiction_elements::QuadratureChoice::Standard,
        )
        .unwrap();
        let nq = kernel.n_points();
        for c in 0..set.n_cells() {
            let coords: Vec<[f64; 3]> = set.cell(c).iter().map(|&n| model.mesh.nodes[n]).collect();
            for (q, x) in kernel.point_positions(&coords).into_iter().enumerate() {
                out.push((si, c, q, x, set.stresses()[c * nq + q]));
            }
        }
    }
    out
}

/// Relative difference max |K - K_fd| / max |K| between the assembled tangent and central
/// differences (step h) of the assembled residual, over all free-dof pairs, at the model's
/// current displacement and committed state (elements and interface contributions alike).
pub fn assembled_tangent_error(model: &mut Model, h: f64) -> f64 {
    model.assemble(true).unwrap();
    let k = model.tangent_values.clone();
    let n = model.n_free();
    let pattern = model.pattern().clone();
    let free = model.free_dofs().to_vec();
    let mut worst: f64 = 0.0;
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for (j, &g) in free.iter().enumerate() {
        model.displacement[g] += h;
        model.assemble(false).unwrap();
        let rp = model.residual.clone();
        model.displacement[g] -= 2.0 * h;
        model.assemble(false).unwrap();
        let rm = model.residual.clone();
        model.displacement[g] += h;
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            let kij = pattern.slot(i, j).map(|s| k[s]).unwrap_or(0.0);
            worst = worst.max((fd - kij).abs());
        }
    }
    worst / kmax
}

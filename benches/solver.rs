//! Benchmark (not a test): assembly, symbolic and numeric factorization, and solve times for a
//! tet10 model of about 100k degrees of freedom (unit cube, 16^3 x 6 tets, J2 material, bottom
//! clamped, top displaced), with the round-1 factorization (AMD ordering, f64) and the default
//! (METIS nested dissection, f32 factor with refinement). Run with `cargo bench --bench solver` (add `-- N` for another
//! cube subdivision).

use std::sync::Arc;
use std::time::Instant;
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver, Ordering, Precision};
use stiction_core::model::{ElementSet, Model, Prescribed};
use stiction_elements::{QuadratureChoice, SolidKernel};
use stiction_materials::J2Plasticity;
use stiction_meshes::generate::structured_cube;

fn main() {
    let n: usize = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(16);
    let t = Instant::now();
    let mesh = Arc::new(structured_cube(n, true, 0.1));
    let t_mesh = t.elapsed().as_secs_f64();
    let material = Arc::new(J2Plasticity::new("ru", 410.0, 0.3, 3.42, 0.0, 0.0).unwrap());
    let mut model = Model::new(mesh.clone(), Kinematics::Solid3D);
    let kernel = SolidKernel::new(mesh.blocks[0].cell_type, Kinematics::Solid3D, QuadratureChoice::Standard).unwrap();
    model.sets.push(ElementSet::new("body", Box::new(kernel), material, mesh.blocks[0].connectivity.clone()));
    let ramp = Arc::new(Amplitude::ramp());
    for (i, x) in mesh.nodes.iter().enumerate() {
        if x[2] < 1e-12 || x[2] > 1.0 - 1e-12 {
            for c in 0..3 {
                let scale = if x[2] > 0.5 && c == 0 { 0.02 } else { 0.0 };
                model
                    .prescribe(Prescribed { dof: i * 3 + c, scale, amplitude: ramp.clone(), source: "bench".into() })
                    .unwrap();
            }
        }
    }
    let t = Instant::now();
    model.finalize().unwrap();
    let t_pattern = t.elapsed().as_secs_f64();
    model.apply_time(1.0);
    let reps = 3;
    let mut t_assembly = f64::INFINITY;
    for _ in 0..reps {
        let t = Instant::now();
        model.assemble(true).unwrap();
        t_assembly = t_assembly.min(t.elapsed().as_secs_f64());
    }
    let mut t_force = f64::INFINITY;
    for _ in 0..reps {
        let t = Instant::now();
        model.assemble(false).unwrap();
        t_force = t_force.min(t.elapsed().as_secs_f64());
    }
    model.assemble(true).unwrap();
    println!(
        "tet10 cube n = {n}: {} cells, {} nodes, {} free dofs, {} matrix entries",
        model.sets[0].n_cells(),
        mesh.nodes.len(),
        model.n_free(),
        model.pattern().nnz(),
    );
    println!("threads (rayon): {}", rayon_threads());
    println!("mesh generation          {t_mesh:8.3} s");
    println!("pattern + slot maps      {t_pattern:8.3} s  (once per topology)");
    println!("assembly, force+tangent  {t_assembly:8.3} s  (best of {reps})");
    println!("assembly, force only     {t_force:8.3} s  (best of {reps})");
    // the round-1 factorization (AMD, f64) and the default (nested dissection, f32 + refinement)
    for (ordering, precision) in [(Ordering::Amd, Precision::Double), (Ordering::NestedDissection, Precision::Single)] {
        let t = Instant::now();
        let mut solver = FaerCholesky::analyse_with_precision(model.pattern(), ordering, precision).unwrap();
        let t_symbolic = t.elapsed().as_secs_f64();
        let mut t_numeric = f64::INFINITY;
        let mut kind = None;
        for _ in 0..reps {
            let t = Instant::now();
            kind = Some(solver.factorize(model.pattern(), &model.tangent_values).unwrap());
            t_numeric = t_numeric.min(t.elapsed().as_secs_f64());
        }
        let b: Vec<f64> = model.residual.iter().map(|r| -r).collect();
        let mut x = b.clone();
        let t = Instant::now();
        solver.solve_in_place(&mut x).unwrap();
        let t_solve = t.elapsed().as_secs_f64();
        let mut x_approx = b.clone();
        let t = Instant::now();
        solver.solve_approximately(&mut x_approx).unwrap();
        let t_approx = t.elapsed().as_secs_f64();
        let mut ax = vec![0.0; b.len()];
        model.pattern().multiply(&model.tangent_values, &x, &mut ax);
        let residual = ax.iter().zip(&b).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt()
            / b.iter().map(|v| v * v).sum::<f64>().sqrt();
        println!("{ordering:?}, {precision:?}: {} factor entries ({kind:?})", solver.factor_nnz());
        println!("  symbolic factorization {t_symbolic:8.3} s  (once per topology)");
        println!("  numeric factorization  {t_numeric:8.3} s  (best of {reps})");
        println!("  solve (exact)          {t_solve:8.3} s  (relative residual {residual:.1e})");
        println!("  solve (factor only)    {t_approx:8.3} s");
    }
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)
}

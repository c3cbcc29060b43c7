//! The assembled tangent against central finite differences of the assembled residual, for
//! every element with an elastic-plastic state, and quadratic Newton convergence on a plastic
//! problem with the consistent tangent.

use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver};
use stiction_core::model::Model;
use stiction_core::nonlinear::{NewtonSettings, ReferenceScales, solve_increment};
use stiction_materials::J2Plasticity;
use stiction_tests::*;

fn tangent_error(model: &mut Model) -> f64 {
    assembled_tangent_error(model, 1e-7)
}

fn plastic() -> Arc<J2Plasticity> {
    Arc::new(J2Plasticity::new("ru", 410.0, 0.3, 3.42, 5.0, 3.0).unwrap())
}

fn plastic_state(model: &mut Model, field: impl Fn([f64; 3]) -> [f64; 3]) {
    // Impose a displacement field well beyond yield everywhere, commit it as history, then
    // move on to a second, different field (the state at which tangents are checked).
    let dpn = model.dofs_per_node();
    model.finalize().unwrap();
    for (n, x) in model.mesh.nodes.clone().iter().enumerate() {
        let u = field(*x);
        for c in 0..dpn {
            model.displacement[n * dpn + c] = u[c];
        }
    }
    model.assemble(false).unwrap();
    model.commit();
    for (n, x) in model.mesh.nodes.clone().iter().enumerate() {
        let u = field([x[1], x[2], x[0]]);
        for c in 0..dpn {
            model.displacement[n * dpn + c] += 0.5 * u[c];
        }
    }
}

fn shear_field(x: [f64; 3]) -> [f64; 3] {
    [0.03 * x[1] + 0.01 * x[0] * x[2], 0.02 * x[2] - 0.01 * x[0] * x[1], -0.015 * x[0] + 0.01 * x[1] * x[1]]
}

#[test]
fn assembled_tangent_matches_finite_differences_for_all_elements() {
    let cases: Vec<(&str, Model)> = vec![
        ("tet4", model_with(structured_cube(2, false, 0.2), Kinematics::Solid3D, plastic())),
        ("tet10", model_with(structured_cube(1, true, 0.0), Kinematics::Solid3D, plastic())),
        (
            "tri3 axisymmetric",
            model_with(structured_rectangle(2, 0.5, 1.0, 1.0, false, 0.2), Kinematics::Axisymmetric, plastic()),
        ),
        (
            "tri6 axisymmetric",
            model_with(structured_rectangle(2, 0.5, 1.0, 1.0, true, 0.2), Kinematics::Axisymmetric, plastic()),
        ),
    ];
    for (name, mut model) in cases {
        // Fix one node's components so the residual has both free and prescribed dofs.
        prescribe_where(&mut model, |x| x[0] < 1e-12 && x[1] < 1e-12, |_| [0.0; 3]);
        plastic_state(&mut model, shear_field);
        let plastic_points = model.sets[0].committed_state().chunks(15).filter(|s| s[12] > 0.0).count();
        assert!(plastic_points > 0, "{name}: the committed state must be plastic");
        let err = tangent_error(&mut model);
        println!("{name}: tangent vs finite differences, max error / max entry = {err:.2e}");
        assert!(err < 1e-6, "{name}: {err}");
    }
}

#[test]
fn newton_converges_quadratically_on_a_plastic_problem() {
    // A tet10 cube pulled in shear on its top face well past yield, bottom clamped.
    let mut model = model_with(structured_cube(3, true, 0.1), Kinematics::Solid3D, plastic());
    prescribe_where(&mut model, |x| x[2] < 1e-12, |_| [0.0; 3]);
    prescribe_where(&mut model, |x| (x[2] - 1.0).abs() < 1e-12, |_| [0.02, 0.01, -0.004]);
    model.finalize().unwrap();
    let mut solver = FaerCholesky::analyse(model.pattern()).unwrap();
    let settings = NewtonSettings { tol_residual: 1e-12, tol_displacement: 1e-12, ..NewtonSettings::default() };
    let mut sequences = Vec::new();
    for t in [0.25, 0.5, 0.75, 1.0] {
        let report = solve_increment(&mut model, &mut solver, t, &settings, ReferenceScales::default()).unwrap();
        model.commit();
        sequences.push(report.residual_norms.clone());
    }
    let plastic_points: usize = model.sets[0].committed_state().chunks(15).filter(|s| s[12] > 0.0).count();
    assert!(plastic_points > 50, "the problem must be plastic (got {plastic_points} plastic points)");
    println!("residual norms per increment: {sequences:?}");
    // Quadratic convergence: once in the asymptotic range, r_{k+1} <= C r_k^2, i.e. the
    // ratio log(r_{k+1}/r0)/log(r_k/r0) approaches 2. Check the last increment.
    let r = sequences.last().unwrap();
    let r0 = r[0];
    let e: Vec<f64> = r.iter().map(|x| x / r0).collect();
    let mut best: f64 = 0.0;
    for k in 1..e.len() - 1 {
        if e[k] < 1e-2 && e[k + 1] > 1e-15 {
            best = best.max(e[k + 1].ln() / e[k].ln());
        }
    }
    println!("observed convergence order {best:.2}");
    assert!(best > 1.8, "order {best}: {r:?}");
}

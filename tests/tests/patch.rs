//! Patch tests: a linear displacement field imposed on the boundary of a distorted mesh must be
//! reproduced exactly inside, with the exact constant stress (tet4, tet10, axisymmetric tri3
//! and tri6). Reference: the linear field itself (closed form).

use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_materials::LinearElastic;
use stiction_tests::*;

const E: f64 = 210.0;
const NU: f64 = 0.3;

fn field_3d(x: [f64; 3]) -> [f64; 3] {
    [
        1e-3 * (1.0 + 2.0 * x[0] - 1.0 * x[1] + 0.5 * x[2]),
        1e-3 * (-0.5 + 0.3 * x[0] + 1.5 * x[1] - 0.7 * x[2]),
        1e-3 * (0.2 - 0.4 * x[0] + 0.6 * x[1] + 1.1 * x[2]),
    ]
}

/// Axisymmetric linear field that is admissible: u_r = a r, u_z = b z + c (plus rigid z shift).
fn field_axi(x: [f64; 3]) -> [f64; 3] {
    [2e-3 * x[0], -1e-3 * x[1] + 5e-4, 0.0]
}

fn check(
    kin: Kinematics,
    mesh: stiction_core::mesh::Mesh,
    exact: fn([f64; 3]) -> [f64; 3],
    boundary: impl Fn([f64; 3]) -> bool,
    strain: [f64; 6],
) {
    let mat = Arc::new(LinearElastic::new("m", E, NU).unwrap());
    let mut model = model_with(mesh, kin, mat);
    prescribe_where(&mut model, &boundary, exact);
    let interior = model.mesh.nodes.iter().filter(|x| !boundary(**x)).count();
    assert!(interior > 5, "the patch needs free interior nodes");
    solve_at_full_load(&mut model);
    let dpn = model.dofs_per_node();
    let mut worst: f64 = 0.0;
    for (n, x) in model.mesh.nodes.iter().enumerate() {
        let u = exact(*x);
        for c in 0..dpn {
            worst = worst.max((model.displacement[n * dpn + c] - u[c]).abs());
        }
    }
    assert!(worst < 1e-12, "{kin:?}: displacement error {worst:e}");
    let c = stiction_core::voigt::isotropic_elasticity(E, NU);
    let sigma: Vec<f64> = (0..6).map(|i| (0..6).map(|j| c[i][j] * strain[j]).sum()).collect();
    for set in &model.sets {
        for s in set.stresses() {
            for i in 0..6 {
                assert!((s[i] - sigma[i]).abs() < 1e-9 * E * 1e-3, "{kin:?}: stress {i} {} vs {}", s[i], sigma[i]);
            }
        }
    }
}

fn on_cube_boundary(x: [f64; 3]) -> bool {
    x.iter().any(|&c| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12)
}

const STRAIN_3D: [f64; 6] = [2e-3, 1.5e-3, 1.1e-3, -1e-3 + 0.3e-3, -0.7e-3 + 0.6e-3, 0.5e-3 - 0.4e-3];

#[test]
fn tet4_patch_test() {
    check(Kinematics::Solid3D, structured_cube(3, false, 0.25), field_3d, on_cube_boundary, STRAIN_3D);
}

#[test]
fn tet10_patch_test() {
    check(Kinematics::Solid3D, structured_cube(2, true, 0.25), field_3d, on_cube_boundary, STRAIN_3D);
}

fn on_rect_boundary(x: [f64; 3]) -> bool {
    (x[0] - 0.5).abs() < 1e-12 || (x[0] - 1.5).abs() < 1e-12 || x[1].abs() < 1e-12 || (x[1] - 1.0).abs() < 1e-12
}

#[test]
fn axisymmetric_tri3_patch_test() {
    check(
        Kinematics::Axisymmetric,
        structured_rectangle(4, 0.5, 1.0, 1.0, false, 0.25),
        field_axi,
        on_rect_boundary,
        [2e-3, -1e-3, 2e-3, 0.0, 0.0, 0.0],
    );
}

#[test]
fn axisymmetric_tri6_patch_test() {
    check(
        Kinematics::Axisymmetric,
        structured_rectangle(3, 0.5, 1.0, 1.0, true, 0.25),
        field_axi,
        on_rect_boundary,
        [2e-3, -1e-3, 2e-3, 0.0, 0.0, 0.0],
    );
}

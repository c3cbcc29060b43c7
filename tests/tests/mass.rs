//! The consistent unit-density mass (the metric of the damped flow that solves snaps) against
//! closed forms: on one distorted 10-node tet, the row sums are integral N_a dV (-V/20 at a
//! corner, V/5 at a midside node) and u^T M u = integral x^2 dV for u = x (the second moment
//! V/20 (sum x_a^2 + (sum x_a)^2) over the corners a); assembled over a cube and an
//! axisymmetric ring, the entries of one component add up to the volume. The initial
//! stiffness (the drag of a stiffness-proportional flow) against the closed-form strain energy
//! of a uniform strain, whatever plastic state the body is in.

use std::sync::Arc;
use stiction_core::element::{ElementKernel, Kinematics};
use stiction_core::mesh::CellType;
use stiction_core::problem::NonlinearProblem;
use stiction_elements::{QuadratureChoice, SolidKernel};
use stiction_materials::{J2Plasticity, LinearElastic};
use stiction_meshes::generate::{structured_cube, structured_rectangle};
use stiction_tests::model_with;

fn tet_volume(c: &[[f64; 3]]) -> f64 {
    let d = |i: usize| [c[i][0] - c[0][0], c[i][1] - c[0][1], c[i][2] - c[0][2]];
    let (a, b, e) = (d(1), d(2), d(3));
    (a[0] * (b[1] * e[2] - b[2] * e[1]) - a[1] * (b[0] * e[2] - b[2] * e[0]) + a[2] * (b[0] * e[1] - b[1] * e[0])) / 6.0
}

#[test]
fn tet10_mass_has_the_closed_form_row_sums_and_second_moment() {
    let corners = [[0.1, -0.2, 0.05], [1.3, 0.1, -0.1], [0.2, 0.9, 0.2], [0.3, 0.25, 1.1]];
    // gmsh order: corners, then the midsides of edges 01, 12, 20, 03, 23, 13
    let edges = [(0, 1), (1, 2), (2, 0), (0, 3), (2, 3), (1, 3)];
    let mut coords: Vec<[f64; 3]> = corners.to_vec();
    for (a, b) in edges {
        coords.push([0, 1, 2].map(|k| 0.5 * (corners[a][k] + corners[b][k])));
    }
    let kernel = SolidKernel::new(CellType::Tet10, Kinematics::Solid3D, QuadratureChoice::Standard).unwrap();
    let nd = kernel.n_dofs();
    let mut m = vec![0.0; nd * nd];
    kernel.mass(&coords, &mut m);
    let v = tet_volume(&corners);
    for i in 0..nd {
        let row: f64 = (0..nd).map(|j| m[i * nd + j]).sum();
        let expected = if i / 3 < 4 { -v / 20.0 } else { v / 5.0 };
        assert!((row - expected).abs() < 1e-13, "row {i}: {row} vs {expected}");
        for j in 0..nd {
            assert!((m[i * nd + j] - m[j * nd + i]).abs() < 1e-15, "not symmetric at ({i}, {j})");
        }
    }
    // u = x in the first component: u^T M u = integral x^2 dV
    let u: Vec<f64> = (0..nd).map(|i| if i % 3 == 0 { coords[i / 3][0] } else { 0.0 }).collect();
    let energy: f64 = (0..nd).map(|i| u[i] * (0..nd).map(|j| m[i * nd + j] * u[j]).sum::<f64>()).sum();
    let (sum_sq, sum): (f64, f64) = corners.iter().fold((0.0, 0.0), |(q, s), c| (q + c[0] * c[0], s + c[0]));
    let expected = v / 20.0 * (sum_sq + sum * sum);
    assert!((energy - expected).abs() < 1e-13, "{energy} vs {expected}");
}

#[test]
fn assembled_mass_adds_up_to_the_volume_in_3d_and_axisymmetric() {
    let material = Arc::new(LinearElastic::new("m", 100.0, 0.3).unwrap());
    // a distorted unit cube of 10-node tets: 3 components x volume 1
    let mut cube = model_with(structured_cube(2, true, 0.25), Kinematics::Solid3D, material.clone());
    cube.finalize().unwrap();
    let total: f64 = cube.mass_matrix().iter().sum();
    assert!((total - 3.0).abs() < 1e-12, "cube: {total}");
    // the ring 0.5 <= r <= 1.5, 0 <= z <= 1 of 6-node triangles: 2 components x pi (1.5^2 - 0.5^2)
    let mut ring = model_with(structured_rectangle(3, 0.5, 1.0, 1.0, true, 0.2), Kinematics::Axisymmetric, material);
    ring.finalize().unwrap();
    let total: f64 = ring.mass_matrix().iter().sum();
    let expected = 2.0 * std::f64::consts::PI * (1.5f64.powi(2) - 0.5f64.powi(2));
    assert!((total - expected).abs() < 1e-12 * expected, "ring: {total} vs {expected}");
}

/// K_0 of an elastic-perfectly plastic unit cube is its elastic stiffness, before and after the
/// cube has yielded: for the uniform strain u = (x, 0, 0), u^T K_0 u = (lambda + 2 mu) V (V = 1),
/// while the tangent of the yielded state gives less; and K_0 is unchanged by the state.
#[test]
fn the_initial_stiffness_is_the_elastic_one_whatever_the_plastic_state() {
    let (e, nu) = (100.0, 0.3);
    let material = Arc::new(J2Plasticity::new("m", e, nu, 0.1, 0.0, 0.0).unwrap());
    let mut cube = model_with(structured_cube(2, true, 0.25), Kinematics::Solid3D, material);
    cube.finalize().unwrap();
    let x: Vec<f64> = cube.mesh.nodes.iter().flat_map(|p| [p[0], 0.0, 0.0]).collect();
    let pattern = cube.pattern().clone();
    let energy = |values: &[f64]| {
        let mut kx = vec![0.0; x.len()];
        pattern.multiply(values, &x, &mut kx);
        x.iter().zip(&kx).map(|(a, b)| a * b).sum::<f64>()
    };
    let (lambda, mu) = (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)));
    let before = cube.initial_stiffness_matrix().unwrap();
    assert!((energy(&before) - (lambda + 2.0 * mu)).abs() < 1e-9 * (lambda + 2.0 * mu), "{}", energy(&before));
    // stretched to a strain of 0.05 (50 times the yield strain) and committed
    let stretched: Vec<f64> = x.iter().map(|u| 0.05 * u).collect();
    cube.set_free_values(&stretched);
    NonlinearProblem::assemble(&mut cube, true).unwrap();
    cube.commit();
    let yielded = energy(NonlinearProblem::tangent(&cube));
    assert!(yielded < 0.9 * (lambda + 2.0 * mu), "the yielded tangent: {yielded}");
    let after = cube.initial_stiffness_matrix().unwrap();
    assert_eq!(before, after, "K_0 does not depend on the state");
}

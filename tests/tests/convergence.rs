//! Convergence rates of the L2 displacement error against exact elasticity solutions with zero
//! body force, Dirichlet data from the exact solution on the whole boundary:
//! * 3D: Kelvin's point-force solution with the source outside the unit cube,
//!   u_i = [(3 - 4 nu) P_i / R + (r . P) r_i / R^3] / (16 pi mu (1 - nu)).
//! * axisymmetric: the Lame thick-sphere field u = u_rho(rho) e_rho on an r-z rectangle,
//!   u_rho = A rho + B / rho^2.
//! Expected rates: h^2 for linear, h^3 for quadratic elements.

use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::quadrature;
use stiction_materials::LinearElastic;
use stiction_tests::*;

const E: f64 = 100.0;
const NU: f64 = 0.3;

fn kelvin(x: [f64; 3]) -> [f64; 3] {
    let s = [-0.6, -0.4, -0.5];
    let p = [1.0, -0.5, 0.8];
    let mu = E / (2.0 * (1.0 + NU));
    let r = [x[0] - s[0], x[1] - s[1], x[2] - s[2]];
    let rr = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    let rp = r[0] * p[0] + r[1] * p[1] + r[2] * p[2];
    let c = 1.0 / (16.0 * std::f64::consts::PI * mu * (1.0 - NU));
    std::array::from_fn(|i| c * ((3.0 - 4.0 * NU) * p[i] / rr + rp * r[i] / rr.powi(3)))
}

fn lame_axi(x: [f64; 3]) -> [f64; 3] {
    let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
    let u = 1e-3 * (rho + 0.4 / (rho * rho));
    [u * x[0] / rho, u * x[1] / rho, 0.0]
}

fn rates(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

fn study_3d(quadratic: bool, levels: &[usize]) -> Vec<f64> {
    let rule = quadrature::tetrahedron_collapsed(5);
    levels
        .iter()
        .map(|&n| {
            let mat = Arc::new(LinearElastic::new("m", E, NU).unwrap());
            let mut model = model_with(structured_cube(n, quadratic, 0.1), Kinematics::Solid3D, mat);
            prescribe_where(&mut model, |x| x.iter().any(|&c| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12), kelvin);
            solve_at_full_load(&mut model);
            let (e, norm) = l2_error(&model, &rule, kelvin);
            e / norm
        })
        .collect()
}

fn study_axi(quadratic: bool, levels: &[usize]) -> Vec<f64> {
    let rule = quadrature::triangle_collapsed(6);
    levels
        .iter()
        .map(|&n| {
            let mat = Arc::new(LinearElastic::new("m", E, NU).unwrap());
            let mut model =
                model_with(structured_rectangle(n, 0.5, 1.0, 1.0, quadratic, 0.1), Kinematics::Axisymmetric, mat);
            let on_boundary = |x: [f64; 3]| {
                (x[0] - 0.5).abs() < 1e-12
                    || (x[0] - 1.5).abs() < 1e-12
                    || x[1].abs() < 1e-12
                    || (x[1] - 1.0).abs() < 1e-12
            };
            prescribe_where(&mut model, on_boundary, lame_axi);
            solve_at_full_load(&mut model);
            let (e, norm) = l2_error(&model, &rule, lame_axi);
            e / norm
        })
        .collect()
}

#[test]
fn tet4_converges_at_rate_two() {
    let e = study_3d(false, &[3, 6, 12]);
    let r = rates(&e);
    println!("tet4 relative L2 errors {e:?}, rates {r:?}");
    validate(
        "tet4: L2 convergence rate of the displacement",
        "-",
        r[1],
        2.0,
        "the element's order + 1",
        Tolerance::Absolute(0.15),
    );
}

#[test]
fn tet10_converges_at_rate_three() {
    let e = study_3d(true, &[2, 4, 8]);
    let r = rates(&e);
    println!("tet10 relative L2 errors {e:?}, rates {r:?}");
    validate(
        "tet10: L2 convergence rate of the displacement",
        "-",
        r[1],
        3.0,
        "the element's order + 1",
        Tolerance::Absolute(0.2),
    );
}

#[test]
fn axisymmetric_tri3_converges_at_rate_two() {
    let e = study_axi(false, &[4, 8, 16]);
    let r = rates(&e);
    println!("tri3 axisymmetric relative L2 errors {e:?}, rates {r:?}");
    validate(
        "axisymmetric tri3: L2 convergence rate of the displacement",
        "-",
        r[1],
        2.0,
        "the element's order + 1",
        Tolerance::Absolute(0.15),
    );
}

#[test]
fn axisymmetric_tri6_converges_at_rate_three() {
    let e = study_axi(true, &[2, 4, 8]);
    let r = rates(&e);
    println!("tri6 axisymmetric relative L2 errors {e:?}, rates {r:?}");
    validate(
        "axisymmetric tri6: L2 convergence rate of the displacement",
        "-",
        r[1],
        3.0,
        "the element's order + 1",
        Tolerance::Absolute(0.2),
    );
}

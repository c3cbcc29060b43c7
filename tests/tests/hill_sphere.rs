//! Hill's elastic-plastic thick sphere under internal pressure (cases/validation/
//! hill-sphere-axisym.toml): the elastic-plastic boundary radius c and the outer radial
//! displacement u_b = Y (1 - nu) c^3 / (E b^2), for p = Y [2 ln(c/a) + (2/3)(1 - c^3/b^3)].

use stiction_tests::{Tolerance, run_case, validate};

#[test]
fn elastic_plastic_boundary_and_outer_displacement_match_hill() {
    let (built, summary) = run_case("cases/validation/hill-sphere-axisym.toml", &[], "hill-sphere");
    assert_eq!(summary.status, "completed");
    let (a, b, c, e, nu, y, h) = (1.0f64, 2.0f64, 1.5f64, 200.0f64, 0.3f64, 0.1f64, 0.05f64);
    let p = y * (2.0 * (c / a).ln() + 2.0 / 3.0 * (1.0 - (c / b).powi(3)));
    assert!((p - 0.1196346883).abs() < 1e-9, "case pressure {p}");
    let m = &built.model;
    // outer radial displacement: mean over the outer surface nodes
    let outer = m.mesh.group_nodes(m.mesh.group("outer").unwrap());
    let ub: f64 = outer
        .iter()
        .map(|&n| {
            let x = m.mesh.nodes[n];
            let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
            (m.displacement[2 * n] * x[0] + m.displacement[2 * n + 1] * x[1]) / rho
        })
        .sum::<f64>()
        / outer.len() as f64;
    let exact = y * (1.0 - nu) * c.powi(3) / (e * b * b);
    println!("u_b = {ub:.6e}, Hill {exact:.6e} ({:+.2}%)", 100.0 * (ub / exact - 1.0));
    validate(
        "Hill elastic-plastic thick sphere: outer radial displacement",
        "-",
        ub,
        exact,
        "Hill's closed form",
        Tolerance::Relative(0.01),
    );
    // plastic front: largest radius of an integration point with plastic strain
    let nq = m.sets[0].kernel.n_points();
    let (mut front, mut inner_elastic) = (0.0f64, f64::INFINITY);
    for (si, cell, q, x, _) in stiction_tests::integration_points(m) {
        let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
        let eqps = m.sets[si].committed_state()[(cell * nq + q) * 15 + 12];
        if eqps > 0.0 {
            front = front.max(rho);
        } else {
            inner_elastic = inner_elastic.min(rho);
        }
    }
    println!("plastic points reach rho = {front:.4}, elastic points start at rho = {inner_elastic:.4}; Hill c = {c}");
    assert!((front - c).abs() < h && (inner_elastic - c).abs() < h, "front {front}, elastic from {inner_elastic}");
}

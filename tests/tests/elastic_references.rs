//! Shipped validation cases against closed forms: the Lame thick sphere (3D octant and
//! axisymmetric) and a cantilever against Timoshenko beam theory.

use stiction_tests::{Tolerance, run_case, validate};

/// Lame: u_rho(rho) for internal pressure p, radii a < b.
fn lame_u(rho: f64, p: f64, a: f64, b: f64, e: f64, nu: f64) -> f64 {
    p * a.powi(3) / (e * (b.powi(3) - a.powi(3)))
        * ((1.0 - 2.0 * nu) * rho + (1.0 + nu) * b.powi(3) / (2.0 * rho * rho))
}

/// Lame: hoop stress p a^3 / (b^3 - a^3) (1 + b^3 / (2 rho^3)).
fn lame_hoop(rho: f64, p: f64, a: f64, b: f64) -> f64 {
    p * a.powi(3) / (b.powi(3) - a.powi(3)) * (1.0 + b.powi(3) / (2.0 * rho.powi(3)))
}

fn check_lame(case: &str, label: &str, tol_u: f64) {
    let (built, summary) = run_case(case, &[], label);
    assert_eq!(summary.status, "completed");
    let m = &built.model;
    let dpn = m.dofs_per_node();
    let (p, a, b, e, nu) = (0.1, 1.0, 2.0, 200.0, 0.3);
    let mut worst: f64 = 0.0;
    for (n, x) in m.mesh.nodes.iter().enumerate() {
        let rho = (x[0] * x[0] + x[1] * x[1] + if dpn == 3 { x[2] * x[2] } else { 0.0 }).sqrt();
        if rho < a - 1e-9 {
            continue; // an unused geometry node
        }
        let exact = lame_u(rho, p, a, b, e, nu);
        let u_rad: f64 = (0..dpn).map(|k| m.displacement[n * dpn + k] * x[k] / rho).sum();
        worst = worst.max((u_rad - exact).abs() / exact);
    }
    println!("{case}: max relative error of u_rho over all nodes {worst:.3e}");
    validate(
        &format!("Lame thick sphere ({case}): max relative error of the radial displacement"),
        "-",
        worst,
        0.0,
        "Lame's closed form",
        Tolerance::Absolute(tol_u),
    );
    // Hoop stress at the integration points, where stresses are most accurate: mean error.
    let mut sum = 0.0;
    let mut count = 0.0;
    for (_, _, _, x, s) in stiction_tests::integration_points(m) {
        // hoop direction: in 3D use the z-axis-free direction e_phi = (-y, x, 0)/|.|
        let hoop = if dpn == 2 {
            s[2]
        } else {
            let rxy = (x[0] * x[0] + x[1] * x[1]).sqrt();
            let (c1, s1) = (-x[1] / rxy, x[0] / rxy);
            s[0] * c1 * c1 + s[1] * s1 * s1 + 2.0 * s[3] * c1 * s1
        };
        let rho = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        sum += ((hoop - lame_hoop(rho, p, a, b)) / lame_hoop(rho, p, a, b)).abs();
        count += 1.0;
    }
    println!("{case}: mean relative error of the hoop stress at integration points {:.3e}", sum / count);
    assert!(sum / count < 0.01, "{case}: hoop stress error {}", sum / count);
}

#[test]
fn lame_sphere_3d_octant() {
    check_lame("cases/validation/lame-sphere-3d.toml", "lame-3d", 0.004);
}

#[test]
fn lame_sphere_axisymmetric() {
    check_lame("cases/validation/lame-sphere-axisym.toml", "lame-axi", 0.002);
}

#[test]
fn cantilever_tip_deflection_matches_timoshenko() {
    let (built, _) = run_case("cases/validation/cantilever.toml", &[], "cantilever");
    let m = &built.model;
    let tip = m.mesh.group("tip").unwrap();
    let nodes = m.mesh.group_nodes(tip);
    let uz: f64 = nodes.iter().map(|&n| m.displacement[n * 3 + 2]).sum::<f64>() / nodes.len() as f64;
    let (l, b, h, e, nu, t): (f64, f64, f64, f64, f64, f64) = (10.0, 1.0, 1.0, 200.0, 0.3, 0.001);
    let p = t * b * h;
    let i = b * h.powi(3) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    let exact = p * l.powi(3) / (3.0 * e * i) + p * l / (5.0 / 6.0 * g * b * h);
    let rel = (-uz - exact) / exact;
    println!("cantilever tip deflection {:.6e}, Timoshenko {exact:.6e}, relative difference {rel:.3e}", -uz);
    validate("cantilever: tip deflection", "-", -uz, exact, "Timoshenko beam", Tolerance::Relative(0.02));
    // Equilibrium: the clamp reaction balances the applied load.
    let clamp = m.mesh.group_nodes(m.mesh.group("clamp").unwrap());
    let r = m.reaction(&clamp);
    assert!((r[2] - p).abs() < 1e-9 * p.max(1.0) + 1e-9, "clamp reaction {r:?} vs load {p}");
}

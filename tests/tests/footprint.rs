//! Footprints of discrete points: one asperity at the pole of the Ru hemisphere, its force
//! spread over a disc of radius a. The mean surface displacement under a uniform pressure on a
//! disc of an elastic half-space is u_bar = (16 / (3 pi)) (1 - nu^2) p a / E (Johnson, Contact
//! Mechanics, 1985, section 3.4), so the footprint's compliance is
//!   u_bar / F = 16 (1 - nu^2) / (3 pi^2 a E).
//! A point force has no finite compliance (u ~ 1/r under it): with footprint 0 the compliance
//! grows as the mesh is refined, with a footprint it converges to the closed form.

use stiction_tests::{Tolerance, build_case, one_asperity_at_the_pole, run_case, validate};

const E: f64 = 410.0;
const NU: f64 = 0.3;

/// The compliance u_bar / F of one asperity at the pole after a short loading, on the quick
/// hemisphere mesh with `h_contact`, for a footprint of `area` (0: a point force).
fn compliance(h_contact: f64, area: f64, label: &str) -> f64 {
    let points = one_asperity_at_the_pole("footprint-input");
    let (built, summary) = run_case(
        "cases/ru-rough-sphere/rough-w6-quick.toml",
        &[
            &format!("interfaces.0.points={{ file = \"{}\", footprint_area = {area} }}", points.display()),
            "steps=[{ name = \"load\", end_time = 0.4, initial_increment = 0.1, max_increment = 0.1 }]",
            &format!("mesh.parameters.h_contact={h_contact}"),
            "mesh.parameters.r_fine=80.0",
            "mesh.parameters.growth=0.3",
        ],
        label,
    );
    assert_eq!(summary.status, "completed");
    let flat = &built.model.contributions[0];
    let observed = flat.observables().unwrap();
    let (_, fields) = flat.point_output().unwrap();
    let gap = fields.iter().find(|f| f.name == "gap").unwrap().values[0];
    // one point at the pole with the mean height: its gap is u_bar - approach
    let u_bar = gap + observed.approach.unwrap();
    println!(
        "h_contact {h_contact}, footprint {area}: F = {:.2} nN, u_bar = {u_bar:.5e} nm, compliance {:.4e} nm/nN",
        observed.force,
        u_bar / observed.force
    );
    assert!(observed.force > 0.0);
    u_bar / observed.force
}

#[test]
fn a_resolved_footprint_has_the_half_space_compliance_and_a_point_force_does_not_converge() {
    let a: f64 = 40.0;
    let area = std::f64::consts::PI * a * a;
    let exact = 16.0 * (1.0 - NU * NU) / (3.0 * std::f64::consts::PI.powi(2) * a * E);
    let coarse = compliance(20.0, area, "footprint-coarse");
    let fine = compliance(10.0, area, "footprint-fine");
    let point_coarse = compliance(20.0, 0.0, "point-coarse");
    let point_fine = compliance(10.0, 0.0, "point-fine");
    println!(
        "footprint a = {a} nm: {coarse:.4e} (h 20), {fine:.4e} (h 10), half-space {exact:.4e}; point force: {point_coarse:.4e} (h 20), {point_fine:.4e} (h 10)"
    );
    // the footprint: within 6% of the half-space value and nearly mesh-independent (measured
    // -3.7% at h 20 and -2.4% at h 10: the discretisation is stiffer and converges from below;
    // the finite, clamped hemisphere would add compliance of order a / R)
    validate(
        &format!("footprint of radius {a} nm: compliance on the 10 nm mesh"),
        "nm/nN",
        fine,
        exact,
        "uniform pressure on a half-space disc",
        Tolerance::Relative(0.06),
    );
    assert!((coarse / fine - 1.0).abs() < 0.03, "{coarse} vs {fine}");
    // the point force: stiffer-looking on the coarse mesh, and growing with refinement
    assert!(point_fine > 1.2 * point_coarse, "{point_fine} vs {point_coarse}");
}

/// The interface's tangent with a footprint (a force law at one asperity whose footprint spans
/// several faces) against central differences of its own forces, over every coupled dof.
#[test]
fn the_footprint_tangent_matches_finite_differences() {
    let points = one_asperity_at_the_pole("footprint-input");
    let area = 150.0; // radius 6.9 nm: several faces of the h 5 mesh at the pole
    let (_, mut built) = build_case(
        "cases/ru-rough-sphere/rough-w6-quick.toml",
        &[
            &format!("interfaces.0.points={{ file = \"{}\", footprint_area = {area} }}", points.display()),
            "mesh.parameters.h_contact=5.0",
            "mesh.parameters.r_fine=10.0",
        ],
    );
    let n = built.model.displacement.len();
    let flat = &mut built.model.contributions[0];
    let nodes: Vec<usize> = flat.coupled_nodes().concat();
    assert!(nodes.len() > 10, "the footprint should span several faces: {} nodes", nodes.len());
    // a loaded state with a non-uniform displacement under the footprint (t = 0.3: approach 0.25)
    let mut u = vec![0.0; n];
    for (k, &node) in nodes.iter().enumerate() {
        u[3 * node + 2] = 0.01 * (k as f64 * 0.7).sin();
        u[3 * node] = 0.005 * (k as f64 * 1.3).cos();
    }
    let t = 0.3;
    let mut force = vec![0.0; n];
    let mut tangent = std::collections::HashMap::new();
    let mut add = |i: usize, j: usize, v: f64| *tangent.entry((i, j)).or_insert(0.0) += v;
    flat.assemble(t, &u, &mut force, Some(&mut add)).unwrap();
    assert!(force.iter().any(|f| *f != 0.0), "the asperity must be in contact");
    let dofs: Vec<usize> = nodes.iter().flat_map(|&a| (0..3).map(move |k| 3 * a + k)).collect();
    let (h, mut worst, mut largest) = (1e-7, 0.0f64, 0.0f64);
    for &j in &dofs {
        let mut plus = vec![0.0; n];
        let mut minus = vec![0.0; n];
        u[j] += h;
        flat.assemble(t, &u, &mut plus, None).unwrap();
        u[j] -= 2.0 * h;
        flat.assemble(t, &u, &mut minus, None).unwrap();
        u[j] += h;
        for &i in &dofs {
            let fd = (plus[i] - minus[i]) / (2.0 * h);
            let k = tangent.get(&(i, j)).copied().unwrap_or(0.0);
            worst = worst.max((fd - k).abs());
            largest = largest.max(k.abs());
        }
    }
    println!(
        "footprint over {} nodes: tangent vs finite differences {:.2e} of the largest entry",
        nodes.len(),
        worst / largest
    );
    assert!(worst / largest < 1e-6, "{worst} of {largest}");
}

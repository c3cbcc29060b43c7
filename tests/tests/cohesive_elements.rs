//! Zero-thickness cohesive elements (mesh split + two-sided interface) against a closed form:
//! two elastic blocks in series in uniaxial stress joined by an elastic interface of stiffness k
//! (cases/validation/two-blocks-cohesive.toml): g = E U / (2 L k + E), sigma = k g. The stress
//! state is uniform, so the discrete solution is exact up to round-off.

use stiction_tests::run_case;

#[test]
fn blocks_in_series_with_an_elastic_interface_match_the_closed_form() {
    let (built, summary) = run_case("cases/validation/two-blocks-cohesive.toml", &[], "two-blocks-cohesive");
    assert_eq!(summary.status, "completed");
    let (e, u, l, k) = (100.0f64, 0.01f64, 1.0f64, 50.0f64);
    let g = e * u / (2.0 * l * k + e);
    let sigma = k * g;
    let m = &built.model;
    // the top's reaction is the stress times the unit area
    let top = m.mesh.group_nodes(m.mesh.group("top").unwrap());
    let r = m.reaction(&top);
    println!("reaction {:.12}, closed form {sigma:.12}", r[2]);
    assert!((r[2] - sigma).abs() < 1e-9, "{} vs {sigma}", r[2]);
    let stresses: Vec<f64> = stiction_tests::integration_points(m).iter().map(|p| p.4[2]).collect();
    assert!(stresses.iter().all(|s| (s - sigma).abs() < 1e-9), "uniform stress expected");
    let text = std::fs::read_to_string(summary.output_directory.join("history.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let f = header.iter().position(|h| *h == "force").unwrap();
    let last: Vec<f64> = text.lines().last().unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    // interface force = integral of the (tensile, negative) traction over the unit face
    assert!((last[f] + sigma).abs() < 1e-9, "interface force {} vs {}", last[f], -sigma);
    // every interface point opens by g
    let (_, fields) = m.contributions[0].point_output().unwrap();
    assert!(fields[0].values.iter().all(|gap| (gap - g).abs() < 1e-12), "openings {:?} vs {g}", &fields[0].values[..4]);
}

/// The assembled tangent of the cohesive elements against central differences of the residual,
/// in the softening range of the bilinear law (opening between onset 0.004 and failure 0.01).
#[test]
fn cohesive_element_tangent_matches_finite_differences_while_softening() {
    let (_, mut built) = stiction_tests::build_case(
        "cases/validation/two-blocks-cohesive.toml",
        &[
            "mesh.parameters.h=1.0",
            "interfaces.0.parameters={ G_c = 0.001, sigma_max = 0.2, penalty = 50.0, initially_bonded = 1 }",
        ],
    );
    let m = &mut built.model;
    m.apply_time(0.0);
    m.assemble(false).unwrap();
    m.commit();
    // open the interface by 0.006 (softening) with some slip and a smooth field on top
    let upper_nodes: std::collections::HashSet<usize> =
        m.mesh.group_nodes(m.mesh.group("upper").unwrap()).into_iter().collect();
    for (n, x) in m.mesh.nodes.clone().iter().enumerate() {
        let jump = if upper_nodes.contains(&n) { [0.0005, -0.0003, 0.006] } else { [0.0; 3] };
        for c in 0..3 {
            m.displacement[n * 3 + c] = 1e-3 * (x[0] - 0.3 * x[1] + 0.2 * x[2] * (c as f64 + 1.0)) + jump[c];
        }
    }
    let err = stiction_tests::assembled_tangent_error(m, 1e-8);
    println!("cohesive elements (softening): tangent vs finite differences {err:.2e}");
    assert!(err < 1e-5, "{err}");
}

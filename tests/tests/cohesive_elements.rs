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

//! Zero-thickness cohesive elements (mesh split + two-sided interface) against a closed form:
//! two elastic blocks in series in uniaxial stress joined by an elastic interface of stiffness k
//! (cases/validation/two-blocks-cohesive.toml): g = E U / (2 L k + E), sigma = k g. The stress
//! state is uniform, so the discrete solution is exact up to round-off.

use stiction_tests::{Tolerance, run_case, validate};

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
    validate(
        "cohesive elements: two blocks in series, reaction",
        "-",
        r[2],
        sigma,
        "closed form sigma = E k U / (2 L k + E)",
        Tolerance::Absolute(1e-9),
    );
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

/// Assembled tangent error (vs central differences) of a cohesive case whose interface softens:
/// the committed state is the undeformed one; then the nodes get a smooth field 1e-3 f(x) plus
/// `jump(x)` on the cells of 'upper' (the opening of the interface).
fn softening_tangent_error(
    case: &str,
    field: impl Fn(&[f64; 3], usize) -> f64,
    jump: impl Fn(&[f64; 3]) -> Vec<f64>,
) -> f64 {
    let (_, mut built) = stiction_tests::build_case(
        case,
        &[
            "mesh.parameters.h=1.0",
            "interfaces.0.parameters={ G_c = 0.001, sigma_max = 0.2, penalty = 50.0, initially_bonded = 1 }",
        ],
    );
    let m = &mut built.model;
    m.apply_time(0.0);
    m.assemble(false).unwrap();
    m.commit();
    let dpn = m.dofs_per_node();
    let upper: std::collections::HashSet<usize> =
        m.mesh.group_nodes(m.mesh.group("upper").unwrap()).into_iter().collect();
    for (n, x) in m.mesh.nodes.clone().iter().enumerate() {
        let j = if upper.contains(&n) { jump(x) } else { vec![0.0; dpn] };
        for c in 0..dpn {
            m.displacement[n * dpn + c] = 1e-3 * field(x, c) + j[c];
        }
    }
    stiction_tests::assembled_tangent_error(m, 1e-8)
}

/// The assembled tangent of the cohesive elements against central differences of the residual,
/// in the softening range of the mixed-mode bilinear law (normal opening 0.006 between onset
/// 0.004 and failure 0.01, plus slip: the damage couples normal and shear).
#[test]
fn cohesive_element_tangent_matches_finite_differences_while_softening() {
    let err = softening_tangent_error(
        "cases/validation/two-blocks-cohesive.toml",
        |x, c| x[0] - 0.3 * x[1] + 0.2 * x[2] * (c as f64 + 1.0),
        |_| vec![0.0005, -0.0003, 0.006],
    );
    println!("cohesive elements (softening): tangent vs finite differences {err:.2e}");
    validate(
        "cohesive elements (3D, mixed-mode softening): assembled tangent, max error / max entry",
        "-",
        err,
        0.0,
        "central differences of the residual",
        Tolerance::Absolute(1e-5),
    );
}

/// Work of the top face over a run: sum over increments of the trapezoid of the reaction times
/// the prescribed displacement increment (top displacement = (u_x, 0, u_z) * t).
fn work_of_top(history: &std::path::Path, u: [f64; 2]) -> f64 {
    let text = std::fs::read_to_string(history).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (t, rx, rz) = (col("time"), col("reaction_top_x"), col("reaction_top_z"));
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    rows.windows(2)
        .map(|w| {
            let dt = w[1][t] - w[0][t];
            0.5 * ((w[0][rx] + w[1][rx]) * u[0] + (w[0][rz] + w[1][rz]) * u[1]) * dt
        })
        .sum()
}

/// Mixed-mode separation of two stiff blocks (cases/validation/mixed-mode-blocks.toml): the
/// work of the top face over the whole separation equals the unit interface area times the
/// Benzeggagh-Kenane energy G_Ic + (G_IIc - G_Ic) B^eta for the applied mode mixity
/// B = sin^2(theta): pure mode I (0.5), 45 degrees (0.75) and pure mode II (1.5). The blocks'
/// compliance (1e-3 of the interface's) makes the opening slightly non-uniform; tolerance 0.5%.
#[test]
fn mixed_mode_separation_dissipates_the_benzeggagh_kenane_energy() {
    let (g1, g2, eta) = (0.5f64, 1.5f64, 2.0f64);
    for (theta_deg, ux, uz) in [(0.0f64, 0.0, 0.7), (45.0, 0.5, 0.5), (90.0, 1.1, 0.0)] {
        let b = theta_deg.to_radians().sin().powi(2);
        let expected = g1 + (g2 - g1) * b.powf(eta);
        let label = format!("mixed-mode-{theta_deg}");
        let x = format!("boundary.1.value={ux}");
        let z = format!("boundary.3.value={uz}");
        let (_, summary) = run_case("cases/validation/mixed-mode-blocks.toml", &[&x, &z], &label);
        assert_eq!(summary.status, "completed");
        let w = work_of_top(&summary.output_directory.join("history.csv"), [ux, uz]);
        println!(
            "theta {theta_deg}: work {w:.6}, Benzeggagh-Kenane {expected:.6} ({:+.3}%)",
            100.0 * (w / expected - 1.0)
        );
        validate(
            &format!("mixed-mode cohesive separation at {theta_deg} degrees: work of separation"),
            "-",
            w,
            expected,
            "Benzeggagh-Kenane",
            Tolerance::Relative(5e-3),
        );
    }
}

/// Axisymmetric cohesive elements (cases/validation/two-discs-axisym-cohesive.toml): two
/// cylinders in series in uniaxial stress, g = E U / (2 L k + E), sigma = k g; the top reaction
/// is sigma times the face area pi R^2 (reactions are totals over the circumference).
#[test]
fn axisymmetric_cylinders_with_an_elastic_interface_match_the_closed_form() {
    let (built, summary) =
        run_case("cases/validation/two-discs-axisym-cohesive.toml", &[], "two-discs-axisym-cohesive");
    assert_eq!(summary.status, "completed");
    let (e, u, l, k) = (100.0f64, 0.01f64, 1.0f64, 50.0f64);
    let g = e * u / (2.0 * l * k + e);
    let sigma = k * g;
    let m = &built.model;
    let top = m.mesh.group_nodes(m.mesh.group("top").unwrap());
    let r = m.reaction(&top);
    let expected = sigma * std::f64::consts::PI;
    println!("axisymmetric: top reaction {:.12}, closed form {expected:.12}", r[1]);
    validate(
        "cohesive elements: two cylinders in series (axisymmetric), reaction",
        "-",
        r[1],
        expected,
        "closed form",
        Tolerance::Absolute(1e-9),
    );
    let (_, fields) = m.contributions[0].point_output().unwrap();
    let gap = fields.iter().find(|f| f.name == "gap").unwrap();
    let slip = fields.iter().find(|f| f.name == "slip").unwrap();
    assert!(gap.values.iter().all(|v| (v - g).abs() < 1e-12), "openings {:?} vs {g}", &gap.values[..4]);
    assert!(slip.values.iter().all(|v| v.abs() < 1e-12), "no slip expected");
}

/// The assembled tangent of axisymmetric cohesive elements vs central differences, softening
/// under mixed opening (normal 0.006, radial slip 0.002 r).
#[test]
fn axisymmetric_cohesive_tangent_matches_finite_differences_while_softening() {
    let err = softening_tangent_error(
        "cases/validation/two-discs-axisym-cohesive.toml",
        |x, c| x[0] + 0.4 * x[1] * (c as f64 + 1.0),
        |x| vec![0.002 * x[0], 0.006],
    );
    println!("axisymmetric cohesive elements (softening): tangent vs finite differences {err:.2e}");
    validate(
        "cohesive elements (axisymmetric, softening): assembled tangent, max error / max entry",
        "-",
        err,
        0.0,
        "central differences of the residual",
        Tolerance::Absolute(1e-5),
    );
}

/// A second cohesive interface on a surface another one already split (here frictionless
/// contact on the pre-crack of the full DCB next to the cohesive ligament) shares that split
/// instead of splitting again. Under mode-I opening the crack faces separate, so the contact
/// carries nothing and the load-line reaction equals the run without it.
#[test]
fn contact_on_a_pre_crack_shares_the_ligament_split() {
    let contact = [
        "interfaces.1={ name = \"crack-contact\", type = \"cohesive\", surface = \"crack\", side = \"upper\", law = \"frictionless-contact\", shear_stiffness = 0.0 }",
        "steps.0.end_time=0.08",
        "mesh.parameters.h_fine=2.5",
        "mesh.parameters.h_coarse=5.0",
    ];
    let (with_contact, s1) = run_case("cases/validation/dcb-full.toml", &contact, "dcb-crack-contact");
    let (without, s2) = run_case("cases/validation/dcb-full.toml", &contact[1..], "dcb-no-crack-contact");
    assert_eq!((s1.status.as_str(), s2.status.as_str()), ("completed", "completed"));
    let load = |m: &stiction::build::BuiltModel| {
        let nodes = m.model.mesh.group_nodes(m.model.mesh.group("load_top").unwrap());
        m.model.reaction(&nodes)[2]
    };
    let (a, b) = (load(&with_contact), load(&without));
    let crack_points = with_contact.model.contributions[1].point_output().unwrap().0.len();
    println!("load-line reaction with crack contact {a:.10e}, without {b:.10e}; {crack_points} crack-face points");
    assert!(crack_points > 0);
    assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} vs {b}");
    let gaps = &with_contact.model.contributions[1].point_output().unwrap().1[0].values;
    assert!(gaps.iter().all(|g| *g >= 0.0), "the crack faces open");

    // closing the arms instead: without the crack interface they pass through each other; with
    // it (no separation: the faces slide but stay together normally) they stop at the penalty's
    // small penetration and the load line meets a stiff support
    let closing = ["boundary.1.value=-1.0", "boundary.2.value=1.0"];
    let tie = "interfaces.1.parameters={ no_separation = 1 }";
    let with_sets: Vec<&str> = contact.iter().chain(&closing).chain(std::iter::once(&tie)).copied().collect();
    let without_sets: Vec<&str> = contact[1..].iter().chain(&closing).copied().collect();
    let (closed, s3) = run_case("cases/validation/dcb-full.toml", &with_sets, "dcb-crack-closing");
    let (through, s4) = run_case("cases/validation/dcb-full.toml", &without_sets, "dcb-crack-closing-free");
    assert_eq!((s3.status.as_str(), s4.status.as_str()), ("completed", "completed"));
    let min_gap = |m: &stiction::build::BuiltModel| {
        // opening of the pre-crack at the load line: top arm's bottom face minus bottom arm's top face
        let (_, fields) = m.model.contributions[1].point_output().unwrap_or_default();
        fields.first().map_or(f64::NAN, |f| f.values.iter().fold(f64::INFINITY, |a, &b| a.min(b)))
    };
    let closed_gap = min_gap(&closed);
    let (rc, rt) = (load(&closed), load(&through));
    println!(
        "closing: with contact min crack gap {closed_gap:.3e}, load-line reaction {rc:.4e}; without contact {rt:.4e}"
    );
    assert!(closed_gap > -2e-3 && closed_gap < 0.0, "penalty penetration only: {closed_gap}");
    assert!(rc.abs() > 10.0 * rt.abs(), "contact stiffens the load line: {rc} vs {rt}");
}

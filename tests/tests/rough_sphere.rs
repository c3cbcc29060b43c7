//! The rough-sphere model (discrete asperities with the ru-asperity law on a hemisphere):
//! * against a closed form: with a nearly rigid continuum (E x 1000), asperity i at in-plane
//!   radius r_i sits z_i = R - sqrt(R^2 - r_i^2) above the pole, so its distance is
//!   d_i = approach - z_i and the total force is sum_i F_L(d_i) on loading (F_L: the law's
//!   loading branch from the same calibration, evaluated independently here);
//! * equilibrium: the base reaction balances the flat's force at every increment;
//! * the generated layout has density x pi r^2 asperities.

use stiction_law_ru_asperity::calibration::Calibration;
use stiction_law_ru_asperity::law::{AsperityModel, N_STATE};
use stiction_tests::{Tolerance, history_columns, run_case, validate, workspace_root};

fn history(dir: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let header: Vec<String> = text.lines().next().unwrap().split(',').map(str::to_string).collect();
    let rows = text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    (header, rows)
}

#[test]
fn rigid_continuum_force_equals_the_sum_of_asperity_laws_and_equilibrium_holds() {
    let (_, summary) = run_case(
        "cases/ru-rough-sphere/rough-w6-quick.toml",
        &[
            "materials.ru.model=\"linear-elastic\"",
            "materials.ru.youngs_modulus=410000.0",
            "amplitudes.cycle.value=[-0.5, 1.5, -2.5]",
            "steps.0.initial_increment=0.05",
            "steps.0.max_increment=0.05",
            "steps=[{ end_time = 1.0, initial_increment = 0.05, max_increment = 0.05 }]",
        ],
        "rough-rigid",
    );
    let out = summary.output_directory.clone();
    let (header, rows) = history(&out);
    let col = |n: &str| header.iter().position(|h| h == n).unwrap();
    let (ia, i_f, irz) = (col("approach"), col("force"), col("reaction_base_z"));
    // layout written by the run
    let text = std::fs::read_to_string(out.join("asperities_points.csv")).unwrap();
    let points: Vec<(f64, f64)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0].hypot(v[1]), v[2])
        })
        .collect();
    let expected_count = (0.0079 * std::f64::consts::PI * 117.6f64.powi(2)).round() as usize;
    assert_eq!(points.len(), expected_count);
    let cal = std::fs::read_to_string(workspace_root().join("cases/ru-rough-sphere/calibrations/ru-surrogate-w6.toml"))
        .unwrap();
    let law = AsperityModel { calibration: Calibration::parse(&cal).unwrap(), ramp: 0.05 };
    let r_sphere: f64 = 1000.0;
    let mut checked = 0;
    for row in &rows[1..] {
        let a = row[ia];
        let expected: f64 = points
            .iter()
            .map(|&(r, h)| {
                let z = r_sphere - (r_sphere * r_sphere - r * r).sqrt();
                let d = a - z - (h - 2.786); // identical heights: the last term is 0
                let mut s = [0.0; N_STATE];
                law.evaluate(d, &[0.0; N_STATE], &mut s).force
            })
            .sum();
        let f = row[i_f];
        // equilibrium of the body: base reaction + flat force = 0
        assert!(
            (row[irz] + f).abs() <= 1e-6 * f.abs().max(1.0),
            "approach {a}: base reaction {} vs flat force {f}",
            row[irz]
        );
        if expected.abs() > 100.0 {
            let rel = f / expected - 1.0;
            println!("approach {a:.2} nm: FE {f:.1} nN, sum of asperity laws {expected:.1} nN ({:+.3}%)", 100.0 * rel);
            validate(
                &format!("rough sphere, asperities on a rigid body: force at approach {a:.2} nm"),
                "nN",
                f,
                expected,
                "the sum of the asperity laws at their gaps",
                Tolerance::Relative(0.01),
            );
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked}");
}

/// The shipped default (asperity laws over their footprints, in series with the footprint's
/// compliance, no footprint limit) against the paper's global statements
/// (`shared/spec/ru-rough-sphere.md`, "What the paper reports"), on the quick mesh at the
/// quick case's 2.0 nm maximum. The asperity law is the surrogate, so each statement tests
/// the two-scale model with that surrogate; the thresholds are the paper's:
/// - (4) the w = 6 pull-off more than 3 times the w = 3 one;
/// - (7) at w = 6 the contact area vanishes at a negative approach, and the sphere separates;
/// - (8) at the maximum load the most compressed asperity takes 55 to 75% of the approach
///   (the paper: about 65%);
/// - (1) the loading curves of w = 1, 3 and 6 are virtually the same: within 2% wherever the
///   force exceeds a tenth of its maximum;
/// - (11) the smooth elastic-plastic Lennard-Jones sphere at w = 1 has a larger pull-off and a
///   larger contact area than the rough one (its own axisymmetric case, contact mesh 4 nm
///   instead of the shipped 2 nm, for time: its pull-off is 4 times the rough one's).
#[test]
fn the_shipped_default_meets_the_papers_global_statements_on_the_quick_mesh() {
    let rough = |w: u32| {
        let config = format!("interfaces.0.config_file=\"calibrations/ru-surrogate-w{w}.toml\"");
        let expected = format!("interfaces.0.parameters.expected_work_of_adhesion={w}.0");
        let sets = [config.as_str(), expected.as_str(), "output.vtk=false"];
        let (_, summary) = run_case("cases/ru-rough-sphere/rough-w6-quick.toml", &sets, &format!("paper-rough-w{w}"));
        assert_eq!(summary.status, "completed", "w = {w}: {:?}", summary.message);
        let rows = history_columns(&summary.output_directory, &["time", "approach", "force", "contact_area"]);
        (summary, rows)
    };
    let runs: Vec<_> = [1, 3, 6].into_iter().map(rough).collect();
    let pull_off = |k: usize| runs[k].0.interfaces[0].pull_off_force.expect("the rough sphere separated");
    let (p1, p3, p6) = (pull_off(0), pull_off(1), pull_off(2));
    println!("pull-off (nN): w = 1 {p1:.1}, w = 3 {p3:.1}, w = 6 {p6:.1}; w3/w1 {:.2}, w6/w3 {:.2}", p3 / p1, p6 / p3);
    assert!(p6 / p3 > 3.0, "(4) w6/w3 pull-off {}", p6 / p3);
    // (7): the last state with contact area lies at a negative approach, and the sphere let go
    let (s6, rows6) = &runs[2];
    let last_contact = rows6.iter().rposition(|r| r[3] > 0.0).unwrap();
    let approach = rows6[last_contact][1];
    println!("w = 6: area vanishes after approach {approach:.4} nm");
    assert!(approach < 0.0 && last_contact + 1 < rows6.len(), "(7) last contact at approach {approach} nm");
    assert!(s6.interfaces[0].separated && s6.interfaces[0].final_n_contact == 0);
    // this w = 6 run is the main job: README quotes its closing line
    let readme = std::fs::read_to_string(workspace_root().join("README.md")).unwrap();
    let quoted = format!(
        "max force {:.2} uN at approach 2.000 nm; pull-off {:.2} uN",
        s6.interfaces[0].max_force / 1000.0,
        p6 / 1000.0
    );
    assert!(readme.contains(&quoted), "README.md should quote the main job's '{quoted}'");
    for (w, (s, _)) in [1, 3, 6].iter().zip(&runs) {
        let share = s.interfaces[0].point_share_of_approach_at_max_force;
        println!("w = {w}: most compressed asperity's share of the approach {share:.3}");
        assert!((0.55..=0.75).contains(&share), "(8) w = {w}: share {share}");
    }
    // (1): the same loading increments (no cuts on loading), force against force
    let loading = |rows: &Vec<Vec<f64>>| rows.iter().filter(|r| r[0] <= 1.0).map(|r| (r[0], r[2])).collect::<Vec<_>>();
    let reference = loading(&runs[2].1);
    let max = reference.iter().map(|r| r.1).fold(0.0, f64::max);
    for (w, (_, rows)) in [1, 3].iter().zip(&runs) {
        let other = loading(rows);
        assert_eq!(other.len(), reference.len(), "w = {w}: loading increments");
        let worst = reference
            .iter()
            .zip(&other)
            .filter(|(a, _)| a.1 > 0.1 * max)
            .map(|(a, b)| {
                assert_eq!(a.0, b.0);
                (b.1 / a.1 - 1.0).abs()
            })
            .fold(0.0, f64::max);
        println!("(1) loading force of w = {w} against w = 6: within {:.2}%", 100.0 * worst);
        assert!(worst <= 0.02, "(1) w = {w}: loading differs by {worst}");
    }
    // (11): the smooth sphere at w = 1
    let (_, smooth) = run_case(
        "cases/ru-sphere/smooth-lj-w1.toml",
        &["mesh.parameters.h_contact=4.0", "output.vtk=false"],
        "paper-smooth-lj-w1",
    );
    assert_eq!(smooth.status, "completed", "{:?}", smooth.message);
    let (i_smooth, i_rough) = (&smooth.interfaces[0], &runs[0].0.interfaces[0]);
    let smooth_pull_off = i_smooth.pull_off_force.expect("the smooth sphere separated");
    println!(
        "(11) w = 1: pull-off smooth {smooth_pull_off:.1} nN, rough {p1:.1} nN; max area smooth {:.1} nm^2, rough {:.1} nm^2",
        i_smooth.max_contact_area, i_rough.max_contact_area
    );
    assert!(smooth_pull_off < p1 && i_smooth.max_contact_area > i_rough.max_contact_area);
}

/// The shipped height-map case: each summit of its map (found here by the library, the
/// 8-neighbour rule above the mean plane, the higher of two closer than 3.5 nm) within 117.6 nm
/// of the map's middle is one point, at its offset from the middle, its height and its radius;
/// and the run lets go of the flat (every asperity separated).
#[test]
fn the_afm_hemisphere_places_every_summit_of_its_map_and_separates() {
    use stiction_interfaces::height_map::{gsf, summits};
    let map = gsf::read(&workspace_root().join("cases/rough-surface/ru-film-256nm.gsf")).unwrap();
    let middle = [(map.nx - 1) as f64 * map.dx / 2.0, (map.ny - 1) as f64 * map.dy / 2.0];
    let mut expected: Vec<[f64; 4]> = summits::find(&map, summits::SummitRule { threshold: 0.0, min_spacing: 3.5 })
        .iter()
        .map(|s| [s.x - middle[0], s.y - middle[1], s.height, s.radius])
        .filter(|p| p[0].hypot(p[1]) <= 117.6)
        .collect();
    let (_, summary) = run_case("cases/rough-surface/afm-hemisphere.toml", &["output.vtk=false"], "afm-hemisphere");
    assert_eq!(summary.status, "completed", "{:?}", summary.message);
    let text = std::fs::read_to_string(summary.output_directory.join("asperities_points.csv")).unwrap();
    assert_eq!(text.lines().next(), Some("x,y,height,radius"));
    let mut placed: Vec<[f64; 4]> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect();
    let order = |v: &mut Vec<[f64; 4]>| v.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    order(&mut expected);
    order(&mut placed);
    assert!(expected.len() > 150, "{} summits in the region", expected.len());
    assert_eq!(placed.len(), expected.len());
    for (p, e) in placed.iter().zip(&expected) {
        for k in 0..4 {
            assert!((p[k] - e[k]).abs() <= 1e-8 * (1.0 + e[k].abs()), "placed {p:?}, summit {e:?}");
        }
    }
    let asperities = &summary.interfaces[0];
    assert!(asperities.separated && asperities.final_n_contact == 0, "{asperities:?}");
    println!(
        "afm-hemisphere: {} summits; max force {:.1} nN, pull-off {:.1} nN",
        placed.len(),
        asperities.max_force,
        asperities.pull_off_force.unwrap()
    );
}

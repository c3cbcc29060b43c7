//! The rough-sphere model (discrete asperities with the ru-asperity law on a hemisphere):
//! * against a closed form: with a nearly rigid continuum (E x 1000), asperity i at in-plane
//!   radius r_i sits z_i = R - sqrt(R^2 - r_i^2) above the pole, so its distance is
//!   d_i = approach - z_i and the total force is sum_i F_L(d_i) on loading (F_L: the law's
//!   loading branch from the same calibration, evaluated independently here);
//! * equilibrium: the base reaction balances the flat's force at every increment;
//! * the generated layout has density x pi r^2 asperities.

use stiction_law_ru_asperity::calibration::Calibration;
use stiction_law_ru_asperity::law::{AsperityModel, N_STATE};
use stiction_tests::{run_case, workspace_root};

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
            assert!(rel.abs() < 0.01, "approach {a}: {f} vs {expected}");
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked}");
}

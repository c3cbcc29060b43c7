//! Elastic-perfectly plastic Ru hemisphere on a rigid flat (cases/validation/jackson-green.toml)
//! against the Jackson & Green (2005) and Kogut & Etsion (2002) fits, loading to w/w_c = 10 and
//! unloading. Formulas in shared/spec/validation.md section 4. Their FE data scatter a few
//! percent around the fits; tolerances: JG 3%, KE 4% (KE's fit is piecewise in w/w_c).

use stiction_tests::{Tolerance, run_case, validate};

const E: f64 = 410.0;
const NU: f64 = 0.3;
const Y: f64 = 3.42;
const R: f64 = 1000.0;

fn e_star() -> f64 {
    E / (1.0 - NU * NU)
}

/// Jackson-Green load for interference w (valid for w / w_c > 1.9).
fn jackson_green(w: f64) -> f64 {
    let c = 1.295 * (0.736 * NU).exp();
    let wc = (std::f64::consts::PI * c * Y / (2.0 * e_star())).powi(2) * R;
    let pc = 4.0 / 3.0 * (R / e_star()).powi(2) * (c * std::f64::consts::PI * Y / 2.0).powi(3);
    let b = 0.14 * (23.0 * Y / e_star()).exp();
    let r = w / wc;
    let a = (R * w).sqrt() * (r / 1.9).powf(b / 2.0);
    let hg = 2.84 * Y * (1.0 - (-0.82 * (a / R).powf(-0.7)).exp());
    pc * ((-0.25 * r.powf(5.0 / 12.0)).exp() * r.powf(1.5)
        + 4.0 * hg / (c * Y) * (1.0 - (-(1.0 / 25.0) * r.powf(5.0 / 9.0)).exp()) * r)
}

/// Kogut-Etsion load for interference w (1 <= w / w_c <= 110, their own w_c).
fn kogut_etsion(w: f64) -> f64 {
    let k = 0.454 + 0.41 * NU;
    let h = 2.8 * Y;
    let wc = (std::f64::consts::PI * k * h / (2.0 * e_star())).powi(2) * R;
    let pc = 4.0 / 3.0 * e_star() * R.sqrt() * wc.powf(1.5);
    let r = w / wc;
    if r <= 6.0 { pc * 1.03 * r.powf(1.425) } else { pc * 1.40 * r.powf(1.263) }
}

#[test]
fn elastic_plastic_sphere_matches_jackson_green_and_kogut_etsion() {
    let (_, summary) = run_case(
        "cases/validation/jackson-green.toml",
        &["mesh.parameters.h_contact=6.0", "steps.0.max_increment=0.1", "steps.0.initial_increment=0.1"],
        "jackson-green",
    );
    assert_eq!(summary.status, "completed");
    let c = 1.295 * (0.736 * NU).exp();
    let wc = (std::f64::consts::PI * c * Y / (2.0 * e_star())).powi(2) * R;
    let text = std::fs::read_to_string(summary.output_directory.join("history.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    let (it, ia, i_f, id) = (col("time"), col("approach"), col("force"), col("plastic_dissipation"));
    let mut checked = 0;
    for row in rows.iter().filter(|r| r[it] <= 1.0 + 1e-9) {
        let w = row[ia];
        if w / wc < 2.0 {
            continue;
        }
        let jg = jackson_green(w);
        let ke = kogut_etsion(w);
        println!(
            "w/w_c = {:5.2}: F = {:9.1} nN, JG {jg:9.1} ({:+.2}%), KE {ke:9.1} ({:+.2}%)",
            w / wc,
            row[i_f],
            100.0 * (row[i_f] / jg - 1.0),
            100.0 * (row[i_f] / ke - 1.0)
        );
        validate(
            &format!("Jackson-Green: elastic-plastic Ru hemisphere force at w/w_c = {:.2}", w / wc),
            "nN",
            row[i_f],
            jg,
            "Jackson and Green (2005)",
            Tolerance::Relative(0.03),
        );
        assert!((row[i_f] / ke - 1.0).abs() < 0.04, "KE at w/w_c = {}", w / wc);
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} loading points beyond w/w_c = 2");
    // Plastic dissipation: zero while elastic (w < w_c), then non-decreasing.
    let mut previous: f64 = 0.0;
    for row in &rows {
        if row[ia] < 0.9 * wc && row[it] <= 1.0 {
            assert!(row[id].abs() < 1e-9, "dissipation before yield: {}", row[id]);
        }
        assert!(row[id] >= previous - 1e-9 * previous.abs(), "dissipation decreased");
        previous = row[id];
    }
    // After unloading the flat has left the sphere: zero force, and the contact ends at a
    // positive approach (the permanent flattening of the pole).
    let last = rows.last().unwrap();
    assert!(last[i_f].abs() < 1e-9, "force after unloading {}", last[i_f]);
    let release = rows.iter().filter(|r| r[it] > 1.0 && r[i_f] == 0.0).map(|r| r[ia]).fold(f64::NEG_INFINITY, f64::max);
    println!("contact lost at approach {release:.3} nm; plastic dissipation {:.1} nN nm", last[id]);
    assert!(release > 0.1 * wc, "no residual flattening: contact lost at {release}");
}

/// `tangent_hardening` stiffens only the tangent of flowing points: the same loading and
/// unloading gives the same forces and plastic dissipation at every increment (to the Newton
/// tolerance, 1e-8 of the force scale), with the increments the perfectly plastic tangent takes.
#[test]
fn tangent_hardening_changes_neither_forces_nor_dissipation() {
    let sets = ["mesh.parameters.h_contact=6.0", "steps.0.max_increment=0.1", "steps.0.initial_increment=0.1"];
    let history = |extra: &[&'static str], name: &str| {
        let all: Vec<&str> = sets.iter().chain(extra).copied().collect();
        let (_, summary) = run_case("cases/validation/jackson-green.toml", &all, name);
        assert_eq!(summary.status, "completed", "{name}");
        let text = std::fs::read_to_string(summary.output_directory.join("history.csv")).unwrap();
        let header: Vec<String> = text.lines().next().unwrap().split(',').map(String::from).collect();
        let col = |name: &str| header.iter().position(|h| h == name).unwrap();
        let (it, i_f, id) = (col("time"), col("force"), col("plastic_dissipation"));
        let rows: Vec<[f64; 3]> = text
            .lines()
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                [v[it], v[i_f], v[id]]
            })
            .collect();
        (rows, summary.newton_iterations)
    };
    let (perfect, its_perfect) = history(&[], "jackson-green-perfect");
    let (stiffened, its_stiffened) =
        history(&["materials.ru.tangent_hardening=41.0"], "jackson-green-tangent-hardening");
    println!("Newton iterations: {its_perfect} with the exact tangent, {its_stiffened} with H_t = 41 GPa");
    assert_eq!(perfect.len(), stiffened.len(), "different increments");
    let max_force = perfect.iter().map(|r| r[1].abs()).fold(0.0, f64::max);
    let max_dissipation = perfect.iter().map(|r| r[2]).fold(0.0, f64::max);
    assert!(max_dissipation > 0.0, "the run must yield");
    for (a, b) in perfect.iter().zip(&stiffened) {
        assert_eq!(a[0], b[0], "increment times differ");
        assert!((a[1] - b[1]).abs() <= 1e-6 * max_force, "t = {}: force {} vs {}", a[0], a[1], b[1]);
        assert!((a[2] - b[2]).abs() <= 1e-6 * max_dissipation, "t = {}: dissipation {} vs {}", a[0], a[2], b[2]);
    }
}

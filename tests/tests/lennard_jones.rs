//! Smooth elastic Ru sphere with Lennard-Jones adhesion (cases/validation/lj-sphere.toml,
//! w = 1 J/m^2, z0 = 0.169 nm, Tabor parameter 1.01) loaded and unloaded through pull-off.
//! References: the pull-off force lies between JKR (1.5 pi w R) and DMT/Bradley (2 pi w R);
//! Maugis-Dugdale with lambda = 1.157 mu (the usual match of the Dugdale stress to the LJ law)
//! gives the transition value, solved here from Maugis' equations (J. Colloid Interface Sci.
//! 150, 1992). MD only approximates the LJ law and the model's hemisphere is clamped at its base
//! (+2.9% stiffer than a half-space in the Hertz case), so the tolerance is 8%; measured +5.5%
//! at h_contact = 1 and 2 nm.

use stiction_tests::run_case;

/// Maugis-Dugdale pull-off (most tensile load) in units of pi w R for transition parameter lambda:
/// for m = c/a > 1, a solves (lambda/2)[s + (m^2 - 2) t] a^2 + (4 lambda^2/3)[s t - m + 1] a = 1
/// with s = sqrt(m^2 - 1), t = atan s, and P = a^3 - lambda a^2 (s + m^2 t).
fn maugis_pull_off(lambda: f64) -> f64 {
    let mut best = f64::INFINITY;
    for i in 1..200_000 {
        let m = 1.0 + i as f64 * 1e-4;
        let s = (m * m - 1.0).sqrt();
        let t = s.atan();
        let a2 = lambda / 2.0 * (s + (m * m - 2.0) * t);
        let a1 = 4.0 * lambda * lambda / 3.0 * (s * t - m + 1.0);
        let disc = a1 * a1 + 4.0 * a2;
        if a2.abs() < 1e-15 || disc < 0.0 {
            continue;
        }
        let a = (-a1 + disc.sqrt()) / (2.0 * a2);
        if a > 0.0 {
            best = best.min(a.powi(3) - lambda * a * a * (s + m * m * t));
        }
    }
    -best
}

/// The quick resolution of cases/validation/lj-sphere.toml used here.
const QUICK: [&str; 5] = [
    "mesh.parameters.h_contact=2.0",
    "mesh.parameters.r_fine=40.0",
    "steps.0.max_increment=0.02",
    "steps.1.max_increment=0.01",
    "steps.1.initial_increment=0.01",
];

#[test]
fn lennard_jones_pull_off_lies_in_the_jkr_dmt_transition_and_near_maugis() {
    let (_, summary) = run_case("cases/validation/lj-sphere.toml", &QUICK, "lj-sphere");
    assert_eq!(summary.status, "completed");
    let (e, nu, r, w, z0) = (410.0f64, 0.3f64, 1000.0f64, 1.0f64, 0.169f64);
    let e_star = e / (1.0 - nu * nu);
    let mu = (r * w * w / (e_star * e_star * z0.powi(3))).powf(1.0 / 3.0);
    let md = maugis_pull_off(1.157 * mu);
    let i = &summary.interfaces[0];
    let fe = -i.pull_off_force / (std::f64::consts::PI * w * r);
    println!(
        "Tabor {mu:.3}: pull-off {:.1} nN = {fe:.4} pi w R; Maugis-Dugdale {md:.4} ({:+.2}%); viscous dissipation {:.2} ({:.1}% of the cycle's work)",
        -i.pull_off_force,
        100.0 * (fe / md - 1.0),
        i.viscous_dissipation,
        100.0 * i.viscous_share_of_work
    );
    assert!(fe > 1.5 && fe < 2.0, "outside JKR-DMT: {fe}");
    assert!((fe / md - 1.0).abs() < 0.08, "vs Maugis-Dugdale {md}: {fe}");
    // arc length passed the limit points of jump-in and pull-off, with no viscous dissipation
    let events = std::fs::read_to_string(summary.output_directory.join("events.csv")).unwrap();
    let limit_points = events.lines().filter(|l| l.contains(",limit_point,")).count();
    assert!(summary.limit_points >= 2 && limit_points == summary.limit_points, "{events}");
    assert_eq!(i.viscous_dissipation, 0.0);
    // the same run crossing the jumps by viscous regularisation instead gives the same pull-off
    let viscous_sets: Vec<&str> =
        QUICK.iter().copied().chain(["solver.continuation=\"none\"", "interfaces.0.viscosity=1e-4"]).collect();
    let (_, viscous) = run_case("cases/validation/lj-sphere.toml", &viscous_sets, "lj-sphere-viscous");
    assert_eq!(viscous.status, "completed");
    let v = &viscous.interfaces[0];
    println!(
        "arc length: pull-off {:.2} nN, {} limit points, {} arc-length increments; viscous (zeta 1e-4): pull-off {:.2} nN, viscous dissipation {:.1} aJ",
        -i.pull_off_force,
        summary.limit_points,
        summary.arc_length_increments,
        -v.pull_off_force,
        v.viscous_dissipation
    );
    assert!((v.pull_off_force / i.pull_off_force - 1.0).abs() < 1e-3, "{} vs {}", v.pull_off_force, i.pull_off_force);
    assert!(v.viscous_dissipation > 0.0);
}

//! Smooth elastic Ru sphere with Lennard-Jones adhesion (cases/validation/lj-sphere.toml,
//! z0 = 0.169 nm) loaded and unloaded through pull-off at the paper's three works of adhesion,
//! w = 1, 3 and 6 J/m^2 (Tabor parameter 1.01, 2.09, 3.32).
//!
//! The reference is Greenwood's axisymmetric half-space model with the same Lennard-Jones law
//! (Proc. R. Soc. A 453, 1997), solved independently of the finite-element code in
//! `stiction_tests::half_space_lj` (Boussinesq rings, central-gap control; converged to 1e-5).
//! The pull-off force (the most tensile force on the curve) must agree within 3%. The limit
//! points are the folds the run reports (summary.json `folds`: the vertex of the parabola
//! approach(force) through the increments around each turn, so the approach is located to
//! second order in the increment, the force to first order); the hemisphere's base is clamped
//! at 1000 nm, which shifts the approach by up to F (1 + nu)(3 - 2 nu) / (2 pi E R) (0.01 nm at
//! 8 uN) but not the force.
//! Bounds as well: JKR 1.5 pi w R < pull-off < DMT/Bradley 2 pi w R; Maugis-Dugdale with
//! lambda = 1.157 mu (Maugis, J. Colloid Interface Sci. 150, 1992) only approximates the LJ law
//! (it is 5.5% below the finite-element and Greenwood values at w = 1), so it is printed.

use std::f64::consts::PI;
use stiction::run::RunSummary;
use stiction_tests::half_space_lj::{CurveSummary, HalfSpaceLj, RingGrid, SphereLj};
use stiction_tests::{Tolerance, run_case, validate};

/// The case's sphere: R = 1000 nm, E = 410 GPa, nu = 0.3, z0 = 0.169 nm.
fn sphere(w: f64) -> SphereLj {
    SphereLj { radius: 1000.0, e_star: 410.0 / (1.0 - 0.3 * 0.3), w, z0: 0.169 }
}

/// Greenwood's half-space curve from the case's start (the pole 3 z0 from the flat) into contact.
fn greenwood(w: f64) -> CurveSummary {
    let sphere = sphere(w);
    let grid = RingGrid { spacing: 0.25, fine_radius: 1.3 * sphere.jkr_radius(), growth: 1.05, outer_radius: 300.0 };
    let scale = PI * w * sphere.radius;
    HalfSpaceLj::new(sphere, grid).trace(3.0 * sphere.z0, 0.02 * sphere.z0, 0.01 * scale, 0.3 * scale)
}

/// Runs the case at work of adhesion `w` and compares it with Greenwood's half-space model.
/// - Pull-off within 3%.
/// - The folds of unloading, jump-out (the first) and jump-in (the last, where the unstable
///   branch meets the outer one; at w = 6 the 1 nm mesh adds two small folds right after the
///   jump-out, as the contact edge passes nodes). The approach is stationary at a fold, so its
///   sampling error is small: the FE approach minus Greenwood's must lie in [-0.003, c |F| + 0.003] nm, where
///   c |F| = |F| (1 + nu)(3 - 2 nu) / (2 pi E R) bounds how much less a hemisphere clamped at
///   depth R stretches than a half-space (measured: 57-66% of it, 105% at the coarsely sampled w = 1 jump-in). The force at the jump-out
///   within 5% (the force is sampled to first order; the jump-in's is printed only).
/// - When Greenwood's jump-in lies before the start, the run must begin with a snap.
fn compare_with_greenwood(w: f64, sets: &[&str], label: &str) -> RunSummary {
    let w_set = format!("interfaces.0.parameters.w={w:.1}");
    let all: Vec<&str> = sets.iter().copied().chain([w_set.as_str()]).collect();
    let (_, summary) = run_case("cases/validation/lj-sphere.toml", &all, label);
    assert_eq!(summary.status, "completed", "{:?}", summary.message);
    assert!(!summary.warnings.iter().any(|m| m.contains("had not separated")), "{:?}", summary.warnings);
    let reference = greenwood(w);
    let scale = PI * w * 1000.0;
    let fe = summary.interfaces[0].pull_off_force.expect("the sphere separated");
    let (jump_in, jump_out) = (reference.jump_in.unwrap(), reference.jump_out.unwrap());
    // the folds the run reports (summary.json `folds`), those of unloading (step 2)
    let folds: Vec<(f64, f64)> =
        summary.interfaces[0].folds.iter().filter(|f| f.time > 1.0).map(|f| (f.approach, f.force)).collect();
    println!(
        "w = {w}: pull-off FE {:.4} pi w R, Greenwood {:.4} ({:+.2}%); (approach, force) of jump-out: Greenwood {jump_out:.4?}, FE {:.4?}; of jump-in: Greenwood {jump_in:.4?}, FE {:.4?}; {} snaps",
        -fe / scale,
        -reference.pull_off_force / scale,
        100.0 * (fe / reference.pull_off_force - 1.0),
        folds.first(),
        folds.last(),
        summary.snaps
    );
    validate(
        &format!("Lennard-Jones sphere, w = {w} J/m^2: pull-off force"),
        "nN",
        fe,
        reference.pull_off_force,
        "Greenwood's half-space model with the same law (tests/src/half_space_lj.rs)",
        Tolerance::Relative(0.03),
    );
    assert!(folds.len() >= 2, "unloading crossed {} folds", folds.len());
    let stretch_per_force = (1.0 + 0.3) * (3.0 - 2.0 * 0.3) / (2.0 * PI * 410.0 * 1000.0);
    let (first, last) = (folds[0], folds[folds.len() - 1]);
    for (fold, (name, expected)) in [(first, ("jump-out", jump_out)), (last, ("jump-in", jump_in))] {
        let shift = fold.0 - expected.0;
        let bound = stretch_per_force * expected.1.abs() + 0.003;
        assert!(
            (-0.003..=bound).contains(&shift),
            "{name} approach {} vs Greenwood {} (bound {bound})",
            fold.0,
            expected.0
        );
    }
    assert!((folds[0].1 / jump_out.1 - 1.0).abs() < 0.05, "jump-out force {} vs {}", folds[0].1, jump_out.1);
    let events = std::fs::read_to_string(summary.output_directory.join("events.csv")).unwrap();
    let first = events.lines().nth(1).unwrap_or_default();
    let time: f64 = first.split(',').next().unwrap_or_default().parse().unwrap_or(f64::NAN);
    let starts_with_a_snap = first.contains(",jump,") && time < 1e-3;
    assert_eq!(starts_with_a_snap, jump_in.0 < 0.0, "Greenwood's jump-in at approach {}; {events}", jump_in.0);
    summary
}

#[test]
fn strong_adhesion_pull_off_matches_greenwood_at_w_3() {
    compare_with_greenwood(3.0, &QUICK, "lj-sphere-w3");
}

/// w = 6 needs the shipped 1 nm contact mesh: the cohesive zone is ~1 nm wide, and on a 2 nm
/// mesh each surface node zips into contact with a jump of its own. Loaded to 0.2 nm only and
/// unloaded to -0.8 nm (past the jump-out at -0.59). A long run (30,658 dofs, 205 arc-length
/// increments; about 8 minutes on 2 cores), which would add a sixth to the default test run's
/// time, so it is run by hand whenever the solver or the elements change (CHANGELOG.md
/// records the last run):
/// `cargo test -p stiction-tests --test validation lennard_jones:: -- --ignored`.
#[test]
#[ignore = "long run (6 to 10 minutes on 2 cores); run by hand with --ignored after solver or element changes"]
fn strong_adhesion_pull_off_matches_greenwood_at_w_6() {
    let sets = [
        "steps.0.max_increment=0.05",
        "steps.0.initial_increment=0.05",
        "steps.1.max_increment=0.01",
        "steps.1.initial_increment=0.01",
        "interfaces.0.approach=0.2",
        "amplitudes.cycle.value=[0.0, 1.0, -4.0]",
    ];
    compare_with_greenwood(6.0, &sets, "lj-sphere-w6");
}

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
fn lennard_jones_pull_off_matches_greenwood_at_w_1_and_lies_in_the_jkr_dmt_transition() {
    let summary = compare_with_greenwood(1.0, &QUICK, "lj-sphere");
    let (e, nu, r, w, z0) = (410.0f64, 0.3f64, 1000.0f64, 1.0f64, 0.169f64);
    let e_star = e / (1.0 - nu * nu);
    let mu = (r * w * w / (e_star * e_star * z0.powi(3))).powf(1.0 / 3.0);
    let md = maugis_pull_off(1.157 * mu);
    let i = &summary.interfaces[0];
    let pull_off = i.pull_off_force.expect("the sphere separated");
    let fe = -pull_off / (std::f64::consts::PI * w * r);
    println!(
        "Tabor {mu:.3}: pull-off {:.1} nN = {fe:.4} pi w R; Maugis-Dugdale {md:.4} ({:+.2}%); viscous dissipation {:.2} ({:.1}% of the cycle's work)",
        -pull_off,
        100.0 * (fe / md - 1.0),
        i.viscous_dissipation,
        100.0 * i.viscous_share_of_work
    );
    assert!(fe > 1.5 && fe < 2.0, "outside JKR-DMT: {fe}");
    validate(
        "Lennard-Jones sphere, w = 1 J/m^2: pull-off / (pi w R)",
        "-",
        fe,
        md,
        "Maugis-Dugdale at lambda = 1.157 mu",
        Tolerance::Relative(0.08),
    );
    // arc length passed the limit points of jump-in and pull-off, with no viscous dissipation
    let events = std::fs::read_to_string(summary.output_directory.join("events.csv")).unwrap();
    let limit_points = events.lines().filter(|l| l.contains(",limit_point,")).count();
    // exactly the four physical folds (jump-in and jump-out, crossed on loading and again on
    // unloading): no walking back and forth across a fold (before increments that turned back
    // were refused, the shipped mesh counted 7)
    assert!(summary.limit_points == 4 && limit_points == summary.limit_points, "{events}");
    assert_eq!(i.viscous_dissipation, 0.0);
    // the same run crossing the jumps by viscous regularisation instead gives the same pull-off
    let viscous_sets: Vec<&str> =
        QUICK.iter().copied().chain(["solver.continuation=\"none\"", "interfaces.0.viscosity=1e-4"]).collect();
    let (_, viscous) = run_case("cases/validation/lj-sphere.toml", &viscous_sets, "lj-sphere-viscous");
    assert_eq!(viscous.status, "completed");
    let v = &viscous.interfaces[0];
    let viscous_pull_off = v.pull_off_force.expect("the viscous run separated");
    println!(
        "arc length: pull-off {:.2} nN, {} limit points, {} arc-length increments; viscous (zeta 1e-4): pull-off {:.2} nN, viscous dissipation {:.1} aJ",
        -pull_off, summary.limit_points, summary.arc_length_increments, -viscous_pull_off, v.viscous_dissipation
    );
    validate(
        "Lennard-Jones sphere, w = 1 J/m^2: pull-off with viscous regularisation",
        "nN",
        viscous_pull_off,
        pull_off,
        "the same run by arc length",
        Tolerance::Relative(1e-3),
    );
    assert!(v.viscous_dissipation > 0.0);
}

/// A step that was to unload until separated but ends first says so: its most tensile force is
/// not a pull-off. Loaded to 0.3 nm and unloaded only to 0.15 nm, the w = 1 sphere is still in
/// contact (its pull-off fold is at 0.044 nm). Unloaded back to the start instead (approach 0,
/// past the jump-out, where the flat still pulls with -1.1 uN, 21% of the pull-off, from 3 z0),
/// it has let go: no warning.
#[test]
fn an_unloading_that_ends_before_separation_warns() {
    let run = |end: &str, label: &str| {
        let amplitude = format!("amplitudes.cycle.value=[0.0, 0.3, {end}]");
        let sets: Vec<&str> = QUICK.iter().copied().chain([amplitude.as_str()]).collect();
        let (_, summary) = run_case("cases/validation/lj-sphere.toml", &sets, label);
        assert_eq!(summary.status, "completed");
        summary.warnings.into_iter().find(|w| w.contains("had not separated"))
    };
    let attached = run("0.15", "lj-sphere-attached");
    assert!(attached.as_ref().is_some_and(|w| w.contains("'flat'") && w.contains("not a pull-off")), "{attached:?}");
    assert_eq!(run("0.0", "lj-sphere-let-go"), None);
    // the shipped schedule separates without the warning: checked in `compare_with_greenwood`
}

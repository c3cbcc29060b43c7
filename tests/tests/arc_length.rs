//! Arc-length continuation through limit points, against a closed-form equilibrium path
//! (cases/validation/lj-block-arc-length.toml): an elastic block (E = 10 GPa, nu = 0, L = 1 nm,
//! unit area, uniaxial strain) on a rigid flat through the Lennard-Jones law. The state is
//! uniform, so with F = sigma(h) the gap is h = h0 - a + F L / E and every equilibrium satisfies
//!   F = sigma(h),  sigma(h) = -(8 w / 3 z0) [(z0/h)^3 - (z0/h)^9]   (w = 1, z0 = 0.169).
//! The path folds in the approach a where d sigma / dh = E / L; between the folds it is
//! unstable under load control. A conservative system traced along its equilibrium path does
//! no net work over a closed cycle; a load-controlled run jumps and loses energy at each jump.

use stiction_tests::{Tolerance, run_case, validate};

const Z0: f64 = 0.169;
const STIFFNESS: f64 = 10.0; // E / L

fn sigma(h: f64) -> f64 {
    let s = Z0 / h;
    -(8.0 / (3.0 * Z0)) * (s.powi(3) - s.powi(9))
}

fn sigma_slope(h: f64) -> f64 {
    let s = Z0 / h;
    (8.0 / (3.0 * Z0)) * (3.0 * s.powi(3) - 9.0 * s.powi(9)) / h
}

/// (approach, force) per converged increment (the first row, the undeformed state written
/// before the first solve, is not an equilibrium and is left out).
fn path(dir: &std::path::Path) -> Vec<(f64, f64)> {
    let text = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let (a, f) = (col("approach"), col("force"));
    text.lines()
        .skip(2)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[a], v[f])
        })
        .collect()
}

/// Work of the flat over the path (trapezoids in the approach).
fn cycle_work(p: &[(f64, f64)]) -> f64 {
    p.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum()
}

#[test]
fn arc_length_follows_the_closed_form_path_through_both_folds_without_dissipation() {
    let peak = 16.0 / (9.0 * 3f64.sqrt() * Z0);
    let (_, arc) = run_case("cases/validation/lj-block-arc-length.toml", &[], "lj-block-arc-length");
    assert_eq!(arc.status, "completed");
    let arc_path = path(&arc.output_directory);
    let (_, load) = run_case(
        "cases/validation/lj-block-arc-length.toml",
        &["solver.continuation=\"none\""],
        "lj-block-load-control",
    );
    assert_eq!(load.status, "completed");
    let load_path = path(&load.output_directory);

    let on_curve_error = |p: &[(f64, f64)]| {
        p.iter().map(|&(a, f)| (f - sigma(1.0 - a + f / STIFFNESS)).abs()).fold(0.0f64, f64::max) / peak
    };
    let unstable =
        |p: &[(f64, f64)]| p.iter().filter(|&&(a, f)| sigma_slope(1.0 - a + f / STIFFNESS) > STIFFNESS).count();
    let (arc_error, load_error) = (on_curve_error(&arc_path), on_curve_error(&load_path));
    let (arc_unstable, load_unstable) = (unstable(&arc_path), unstable(&load_path));
    let (arc_work, load_work) = (cycle_work(&arc_path), cycle_work(&load_path));
    let min_force = arc_path.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    println!(
        "arc length: {} increments ({} by arc length), {} limit points, largest distance from the closed-form path {arc_error:.1e} of the peak, {arc_unstable} states on the unstable branch, cycle work {arc_work:.4}",
        arc.increments, arc.arc_length_increments, arc.limit_points
    );
    println!(
        "load control: {} increments, largest distance {load_error:.1e}, {load_unstable} unstable states, cycle work {load_work:.4} (jump losses)",
        load.increments
    );
    println!("most adhesive force {min_force:.5} vs peak traction x area {:.5}", -peak);
    // every converged state is an equilibrium of the closed form
    validate(
        "arc length, block on a Lennard-Jones flat: largest distance of a state from the path / peak",
        "-",
        arc_error,
        0.0,
        "the closed-form equilibrium path",
        Tolerance::Absolute(1e-6),
    );
    assert!(load_error < 1e-6, "{load_error}");
    // arc length passes the two folds of the approach and the two of the retraction
    assert!(arc.limit_points >= 4, "{} limit points", arc.limit_points);
    assert!(arc_unstable >= 20 && load_unstable == 0, "{arc_unstable} / {load_unstable}");
    // no artificial dissipation: the cycle's work vanishes up to the trapezoid error, while the
    // load-controlled run loses its jumps' energy
    assert!(load_work > 0.5, "load-control losses {load_work}");
    assert!(arc_work.abs() < 0.01 * load_work, "arc-length cycle work {arc_work} vs {load_work}");
    // the stable branch reaches the peak adhesive traction
    validate(
        "arc length, block on a Lennard-Jones flat: most adhesive force",
        "-",
        min_force,
        -peak,
        "peak traction x area (closed form)",
        Tolerance::Relative(1e-3),
    );
}

/// The viscous regularisation, the other way across jumps, reports its dissipation and warns
/// when it exceeds the stated share (`max_viscous_share`, default 5%) of the gross work of the
/// flat: zeta = 1e-4 stays below it on the LJ block, zeta = 1e-2 (a regularisation that
/// absorbs the jumps' energy) does not.
#[test]
fn a_viscous_share_above_its_limit_is_reported() {
    let mut shares = Vec::new();
    for (zeta, label) in [("1e-4", "lj-block-viscous-small"), ("1e-2", "lj-block-viscous-large")] {
        let (_, s) = run_case(
            "cases/validation/lj-block-arc-length.toml",
            &["solver.continuation=\"none\"", &format!("interfaces.0.viscosity={zeta}")],
            label,
        );
        assert_eq!(s.status, "completed");
        let i = &s.interfaces[0];
        println!(
            "zeta {zeta}: viscous dissipation {:.4} = {:.2}% of the gross work {:.4}; warnings {:?}",
            i.viscous_dissipation,
            100.0 * i.viscous_share_of_work,
            i.gross_work_of_flat,
            s.warnings
        );
        assert!(i.viscous_dissipation > 0.0);
        shares.push((i.viscous_share_of_work, s.warnings.clone(), s.output_directory.clone()));
    }
    assert!(shares[0].0 < 0.05 && shares[0].1.is_empty(), "{:?}", shares[0]);
    assert!(shares[1].0 > 0.05, "{:?}", shares[1]);
    assert!(shares[1].1.iter().any(|w| w.contains("max_viscous_share") && w.contains("'flat'")), "{:?}", shares[1].1);
    let events = std::fs::read_to_string(shares[1].2.join("events.csv")).unwrap();
    assert!(events.contains("viscous_share_exceeded"), "{events}");
}

/// Arc length and viscous regularisation exclude each other (the viscous term needs time to
/// move forward); the error names the key.
#[test]
fn arc_length_with_a_viscous_interface_is_refused() {
    let path = stiction_tests::workspace_root().join("cases/validation/lj-block-arc-length.toml");
    let loaded = stiction::case::load(&path, &["interfaces.0.viscosity=1e-4".to_string()]).unwrap();
    let e = stiction::build::build(&loaded).err().unwrap().to_string();
    assert!(e.contains("interfaces[0].viscosity") && e.contains("arc-length"), "{e}");
}

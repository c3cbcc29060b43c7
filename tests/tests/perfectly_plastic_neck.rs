//! A small smooth elastic-perfectly plastic Lennard-Jones sphere at w = 6 J/m^2 (R = 100 nm,
//! `smooth-lj-w6.toml` scaled down), pressed to 0.5 nm and held: its adhesive neck yields at
//! its limit load, where the consistent tangent loses rank, and with it Newton stalls (this run
//! stops at t = 0.237 with the exact tangent, on some builds and thread counts and not others).
//! A tangent-only hardening (`tangent_hardening`) keeps the stresses and states perfectly
//! plastic and gives Newton a direction: the cycle completes, and two moduli a decade apart
//! (4.1 and 41 GPa) give the same answer up to the snaps' paths: most tensile force within 1%,
//! plastic dissipation within 1%, where a real hardening of 4.1 GPa raises the dissipation by
//! 7% (976.1 against 913.1 aJ, measured 2026-11-27).

use stiction::run::RunSummary;
use stiction_tests::run_case;

fn small_sphere(extra: &[&str], label: &str) -> RunSummary {
    let mut sets = vec![
        "mesh.parameters.R=100.0",
        "mesh.parameters.r_fine=20.0",
        "mesh.parameters.h_far=10.0",
        "amplitudes.cycle.value=[0.0, 0.5, 0.5]",
        "output.vtk=false",
    ];
    sets.extend_from_slice(extra);
    let (_, summary) = run_case("cases/ru-sphere/smooth-lj-w6.toml", &sets, label);
    summary
}

#[test]
fn a_perfectly_plastic_adhesive_neck_completes_its_cycle_whatever_the_tangent_hardening() {
    let exact = small_sphere(&["materials.ru.tangent_hardening=4.1"], "neck-tangent-hardening-4.1");
    let stiffened = small_sphere(&["materials.ru.tangent_hardening=41.0"], "neck-tangent-hardening-41");
    for s in [&exact, &stiffened] {
        assert_eq!(s.status, "completed", "{:?}", s.message);
        assert_eq!(s.final_time, 2.0);
    }
    let (fa, fb) = (exact.interfaces[0].pull_off_force, stiffened.interfaces[0].pull_off_force);
    let (da, db) = (exact.plastic_dissipation, stiffened.plastic_dissipation);
    println!(
        "most tensile force {fa:.1} vs {fb:.1} nN ({:+.2}%), plastic dissipation {da:.2} vs {db:.2} aJ ({:+.2}%); {} and {} snaps, {} double-precision refactorizations",
        100.0 * (fa / fb - 1.0),
        100.0 * (da / db - 1.0),
        exact.snaps,
        stiffened.snaps,
        exact.double_precision_refactorizations
    );
    assert!(fa < -1000.0 && da > 500.0, "the neck must be adhesive and yield: {fa} nN, {da} aJ");
    assert!((fa / fb - 1.0).abs() < 0.01, "most tensile force {fa} vs {fb}");
    assert!((da / db - 1.0).abs() < 0.01, "plastic dissipation {da} vs {db}");
}

//! The tangent predictor of a run's first increment (`solver.start_predictor`), against the
//! closed form of the cohesive bar of `cases/validation/cohesive-bar-snap-back.toml` (E = 10,
//! L = 1, uniaxial strain, bonded to the flat by the bilinear law k = 100, onset opening 0.01,
//! final opening 0.04; see `tests/tests/dissipation_control.rs`).
//!
//! Before its peak (flat travel d < 0.11) the bar has one equilibrium on its path, the bonded
//! one: opening delta = d / (1 + k L / E), tension s = k delta. A first increment that moves
//! the flat by d = 0.06 (six onset openings) while the bar stays where it is opens the
//! ligament past its final opening at the first residual; with the law there at zero traction
//! the unstressed bar is in equilibrium as well (s = 0 and delta = d > 0.04 satisfy the law),
//! and Newton stops there at once. The tangent predictor moves the bar with the flat first.
//!
//! Measured: tension 0.545454545 with the predictor (closed form 0.545454545), 0 without.

use stiction_tests::{history_columns, run_case};

const CASE: &str = "cases/validation/cohesive-bar-snap-back.toml";
const L_OVER_E: f64 = 0.1;
const K: f64 = 100.0;

/// Flat travel and bar tension after the run's one increment of `d = 0.06`.
fn first_increment(start_predictor: &str, label: &str) -> (f64, f64) {
    let predictor = format!("solver.start_predictor=\"{start_predictor}\"");
    let sets = ["steps.0.end_time=0.3", "steps.0.initial_increment=0.3", "steps.0.max_increment=0.3", &predictor];
    let (_, run) = run_case(CASE, &sets, label);
    assert_eq!(run.status, "completed", "{:?}", run.message);
    assert_eq!((run.increments, run.cut_increments), (1, 0), "one increment, not cut");
    let rows = history_columns(&run.output_directory, &["approach", "force"]);
    (-rows[1][0], -rows[1][1])
}

#[test]
fn a_first_increment_past_the_onset_opening_leaves_the_ligament_bonded() {
    let (d, s) = first_increment("tangent", "tangent-predictor-bar");
    let closed_form = K * d / (1.0 + K * L_OVER_E);
    println!("tangent predictor: travel {d:.6}, tension {s:.9} (closed form {closed_form:.9})");
    assert!((d - 0.06).abs() < 1e-12, "{d}");
    assert!((s - closed_form).abs() < 1e-8 * closed_form, "{s} vs {closed_form}");

    // from the committed state the ligament is torn at the first residual
    let (_, torn) = first_increment("none", "no-predictor-bar");
    println!("no predictor: tension {torn:.3e}");
    assert!(torn.abs() < 1e-9, "expected the broken equilibrium without the predictor: {torn}");
}

//! Restart: a run stopped at checkpoints and resumed in new processes (`stiction run --resume`)
//! against the same run done in one go. The reference is the run itself: with a solver whose
//! decisions do not depend on measured times (`solver.refactorization_cost_ratio` fixed), the
//! resumed run must write the same history.csv, events.csv and cycles.csv to the last byte,
//! and the same summary counts (increments, cuts, snaps, Newton iterations, factorizations).
//! Resuming another problem, or a folder with nothing to resume, is refused with the reason.

use std::path::{Path, PathBuf};
use stiction::run::{RunOptions, RunSummary, run};
use stiction_tests::workspace_root;

fn scratch(name: &str) -> PathBuf {
    let d = workspace_root().join("target").join("test-out").join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Runs `case` with `sets` into `out`: afresh, or resumed; stopping after `stop_after`
/// increments when given.
fn part(
    case: &str,
    sets: &[&str],
    out: &Path,
    resume: bool,
    stop_after: Option<usize>,
) -> stiction::error::Result<RunSummary> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = stiction::case::load(&workspace_root().join(case), &sets)?;
    let options =
        RunOptions { out: Some(out.to_path_buf()), resume, stop_after_increments: stop_after, ..Default::default() };
    run(&loaded, &options)
}

/// Runs `case` in one go and in parts stopped after each of `stops` increments (each part a
/// resumption of the one before), and checks that both write the same record: the same files
/// (VTK frames included), with the same history.csv, events.csv, cycles.csv and `.pvd`
/// collections. `rewind`: the last part goes on from the first part's checkpoint instead of its
/// own, as after a run killed long after its last checkpoint, so that what the killed run wrote
/// past the checkpoint must be cut back.
fn resumed_equals_straight(case: &str, sets: &[&str], stops: &[usize], rewind: bool, label: &str) -> RunSummary {
    let straight_out = scratch(&format!("restart-{label}-straight"));
    let straight = part(case, sets, &straight_out, false, None).unwrap_or_else(|e| panic!("{e}"));
    let parts_out = scratch(&format!("restart-{label}-parts"));
    for (k, &n) in stops.iter().enumerate() {
        let error = part(case, sets, &parts_out, k > 0, Some(n)).expect_err("a part stops before the end");
        assert!(error.to_string().contains("--resume"), "the stop says how to go on: {error}");
        let summary = std::fs::read_to_string(parts_out.join("summary.json")).unwrap();
        assert!(summary.contains("\"status\": \"interrupted\""), "{summary}");
        assert!(summary.contains(&format!("\"increments\": {n},")), "part {k} stopped after {n} increments: {summary}");
        assert!(parts_out.join("restart.bin").exists(), "a stopped run leaves its checkpoint");
        if rewind && k == 0 {
            std::fs::copy(parts_out.join("restart.bin"), parts_out.with_extension("first-checkpoint")).unwrap();
        }
    }
    if rewind {
        std::fs::rename(parts_out.with_extension("first-checkpoint"), parts_out.join("restart.bin")).unwrap();
    }
    let resumed = part(case, sets, &parts_out, true, None).unwrap_or_else(|e| panic!("{e}"));
    let names = |dir: &Path| {
        let mut names: Vec<String> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    };
    assert_eq!(names(&parts_out), names(&straight_out), "the resumed run's folder holds the same files");
    for file in names(&straight_out).iter().filter(|f| f.ends_with(".csv") || f.ends_with(".pvd")) {
        let (a, b) = (std::fs::read(straight_out.join(file)).unwrap(), std::fs::read(parts_out.join(file)).unwrap());
        assert!(
            a == b,
            "{file} of the resumed run differs from the straight run's ({} against {} bytes)",
            b.len(),
            a.len()
        );
    }
    let counts = |s: &RunSummary| {
        (s.increments, s.cut_increments, s.snaps, s.arc_length_increments, s.newton_iterations, s.factorizations)
    };
    assert_eq!(
        counts(&resumed),
        counts(&straight),
        "(increments, cuts, snaps, path-following, iterations, factorizations)"
    );
    assert_eq!(resumed.plastic_dissipation.to_bits(), straight.plastic_dissipation.to_bits());
    assert!(!parts_out.join("restart.bin").exists(), "a completed run removes its checkpoint");
    println!(
        "{label}: {} increments, {} snaps, {} cut; resumed from {stops:?} and identical",
        straight.increments, straight.snaps, straight.cut_increments
    );
    straight
}

/// The elastic-perfectly plastic Lennard-Jones sphere (axisymmetric, w = 3, coarse): J2 states,
/// the flat's law, damped-flow snaps at jump-in and pull-off, stopped before and after the
/// first snap and during unloading.
#[test]
fn a_plastic_adhesive_sphere_stopped_twice_and_resumed_writes_the_same_history_as_one_run() {
    let sets = [
        "mesh.parameters.h_contact=8.0",
        "mesh.parameters.r_fine=40.0",
        "amplitudes.cycle.value=[0.0, 1.0, -1.0]",
        "output.vtk=false",
        "output.checkpoint_minutes=0",
        "solver.threads=1",
    ];
    let summary =
        resumed_equals_straight("cases/ru-sphere/smooth-lj-w3.toml", &sets, &[3, 150, 260], false, "lj-plastic");
    assert!(summary.snaps >= 2 && summary.plastic_dissipation > 0.0, "the path has snaps and yields");
}

/// The main job at its quick default: the rough Ru sphere, whose ~300 asperities are the Ru
/// plugin law (hysteretic, its states in the host's buffers) with the footprint correction, on
/// the yielding body, with VTK output: stopped during loading and unloading.
#[test]
fn the_rough_sphere_stopped_twice_and_resumed_writes_the_same_history_as_one_run() {
    let sets = ["output.checkpoint_minutes=0", "solver.threads=1", "solver.refactorization_cost_ratio=20"];
    let summary =
        resumed_equals_straight("cases/ru-rough-sphere/rough-w6-quick.toml", &sets, &[7, 60], false, "rough-quick");
    assert!(summary.interfaces[0].pull_off_force < 0.0, "the asperities adhere");
}

/// Cohesive elements (the Camanho-Davila law, which damages), with VTK output: stopped at
/// onset and in softening, then resumed from the first stop's checkpoint (the rows and frames
/// written after it are cut back and written again).
#[test]
fn cohesive_elements_stopped_in_softening_and_resumed_write_the_same_history_as_one_run() {
    let sets = ["output.checkpoint_minutes=0", "solver.threads=1", "solver.refactorization_cost_ratio=20"];
    resumed_equals_straight("cases/validation/mixed-mode-blocks.toml", &sets, &[10, 55], true, "mixed-mode");
}

/// Resuming with another problem names the first key that differs; with other solver settings
/// it goes on; a folder whose run completed has nothing to resume.
#[test]
fn resuming_another_problem_or_a_completed_run_is_refused_with_the_reason() {
    let case = "cases/validation/mixed-mode-blocks.toml";
    let sets = ["output.checkpoint_minutes=0", "solver.threads=1"];
    let out = scratch("restart-refusals");
    part(case, &sets, &out, false, Some(20)).expect_err("stopped");
    let other: Vec<&str> = sets.iter().copied().chain(["materials.block.youngs_modulus=2.0e5"]).collect();
    let error = part(case, &other, &out, true, None).unwrap_err().to_string();
    assert!(
        error.contains("materials.block.youngs_modulus") && error.contains("100000") && error.contains("200000"),
        "{error}"
    );
    let solver: Vec<&str> = sets.iter().copied().chain(["solver.max_iterations=30"]).collect();
    let summary = part(case, &solver, &out, true, None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(summary.status, "completed");
    let error = part(case, &sets, &out, true, None).unwrap_err().to_string();
    assert!(error.contains("has no checkpoint") && error.contains("completed"), "{error}");
    let error = part(case, &sets, &scratch("restart-nothing-there"), true, None).unwrap_err().to_string();
    assert!(error.contains("has no checkpoint") && error.contains("--out"), "{error}");
}

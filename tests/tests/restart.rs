//! Restart: a run stopped at checkpoints and resumed in new processes (`stiction run --resume`)
//! against the same run done in one go without checkpoints. The reference is the run itself:
//! with a solver whose decisions do not depend on measured times
//! (`solver.refactorization_cost_ratio` fixed), the run checkpointed at every commit and
//! resumed must write the same history.csv, events.csv and cycles.csv to the last byte, and
//! the same summary counts (increments, cuts, snaps, Newton iterations, factorizations):
//! writing a checkpoint changes nothing, and a resumed run takes up all its state, the
//! solvers' included.
//! Resuming another problem, or a folder with nothing to resume, is refused with the reason.

use std::path::{Path, PathBuf};
use stiction::run::{RunOptions, RunSummary, run};
use stiction_tests::{claim_output_dir, workspace_root};

fn scratch(name: &str) -> PathBuf {
    let d = claim_output_dir(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Where a part of a run stops.
#[derive(Debug, Clone, Copy)]
enum Stop {
    /// After this many increments in all.
    Increments(usize),
    /// Inside a damped-flow snap, after this many flow steps of the part.
    FlowSteps(usize),
}

/// Runs `case` with `sets` into `out`: afresh, or resumed; stopping where `stop` says when
/// given.
fn part(
    case: &str,
    sets: &[&str],
    out: &Path,
    resume: bool,
    stop: Option<Stop>,
) -> stiction::error::Result<RunSummary> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = stiction::case::load(&workspace_root().join(case), &sets)?;
    let mut options = RunOptions { out: Some(out.to_path_buf()), resume, ..Default::default() };
    match stop {
        Some(Stop::Increments(n)) => options.stop_after_increments = Some(n),
        Some(Stop::FlowSteps(n)) => options.stop_after_flow_steps = Some(n),
        None => {}
    }
    run(&loaded, &options)
}

/// Runs `case` in one go (writing no checkpoint) and in parts stopped at each of `stops` (each
/// part a resumption of the one before, checkpointing at every commit and every damped-flow
/// step), and checks that both write the same record: the same files
/// (VTK frames included), with the same history.csv, events.csv, cycles.csv and `.pvd`
/// collections. `rewind`: the last part goes on from the first part's checkpoint instead of its
/// own, as after a run killed long after its last checkpoint, so that what the killed run wrote
/// past the checkpoint must be cut back.
fn resumed_equals_straight(case: &str, sets: &[&str], stops: &[Stop], rewind: bool, label: &str) -> RunSummary {
    let straight_out = scratch(&format!("restart-{label}-straight"));
    let straight = part(case, sets, &straight_out, false, None).unwrap_or_else(|e| panic!("{e}"));
    assert!(!straight_out.join("restart.bin").exists(), "the straight run writes no checkpoint in its 10 minutes");
    // the parts write a checkpoint at every commit and every damped-flow step
    let sets: &Vec<&str> = &sets.iter().copied().chain(["output.checkpoint_minutes=0"]).collect();
    let parts_out = scratch(&format!("restart-{label}-parts"));
    for (k, &stop) in stops.iter().enumerate() {
        let error = part(case, sets, &parts_out, k > 0, Some(stop)).expect_err("a part stops before the end");
        assert!(error.to_string().contains("--resume"), "the stop says how to go on: {error}");
        let summary = std::fs::read_to_string(parts_out.join("summary.json")).unwrap();
        assert!(summary.contains("\"status\": \"interrupted\""), "{summary}");
        match stop {
            Stop::Increments(n) => {
                assert!(
                    summary.contains(&format!("\"increments\": {n},")),
                    "part {k} stopped after {n} increments: {summary}"
                )
            }
            Stop::FlowSteps(n) => assert!(
                summary.contains("inside the snap") && summary.contains("damped flow steps"),
                "part {k} stopped inside a snap, after {n} flow steps: {summary}"
            ),
        }
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
/// the flat's law, damped-flow snaps at jump-in and pull-off, stopped inside the first snap
/// (the jump-in from the unbalanced start, before any increment is committed), inside a later
/// one, and during unloading.
#[test]
fn a_plastic_adhesive_sphere_stopped_inside_snaps_and_resumed_writes_the_same_history_as_one_run() {
    let sets = [
        "mesh.parameters.h_contact=8.0",
        "mesh.parameters.r_fine=40.0",
        "amplitudes.cycle.value=[0.0, 1.0, -1.0]",
        "output.vtk=false",
        "solver.threads=1",
    ];
    let summary = resumed_equals_straight(
        "cases/ru-sphere/smooth-lj-w3.toml",
        &sets,
        &[Stop::FlowSteps(100), Stop::FlowSteps(210), Stop::Increments(260)],
        false,
        "lj-plastic",
    );
    assert!(summary.snaps >= 2 && summary.plastic_dissipation > 0.0, "the path has snaps and yields");
}

/// The main job at its quick default: the rough Ru sphere, whose ~300 asperities are the Ru
/// plugin law (hysteretic, its states in the host's buffers) with the footprint correction, on
/// the yielding body, with VTK output: stopped during loading and unloading.
#[test]
fn the_rough_sphere_stopped_twice_and_resumed_writes_the_same_history_as_one_run() {
    let sets = ["solver.threads=1", "solver.refactorization_cost_ratio=20"];
    let summary = resumed_equals_straight(
        "cases/ru-rough-sphere/rough-w6-quick.toml",
        &sets,
        &[Stop::Increments(7), Stop::Increments(60)],
        false,
        "rough-quick",
    );
    assert!(summary.interfaces[0].most_tensile_force < 0.0, "the asperities adhere");
}

/// Cohesive elements (the Camanho-Davila law, which damages), with VTK output: stopped at
/// onset and in softening, then resumed from the first stop's checkpoint (the rows and frames
/// written after it are cut back and written again).
#[test]
fn cohesive_elements_stopped_in_softening_and_resumed_write_the_same_history_as_one_run() {
    let sets = ["solver.threads=1", "solver.refactorization_cost_ratio=20"];
    resumed_equals_straight(
        "cases/validation/mixed-mode-blocks.toml",
        &sets,
        &[Stop::Increments(10), Stop::Increments(55)],
        true,
        "mixed-mode",
    );
}

/// A run that fails along a damped flow (its steps at most `solver.snap_max_steps`, too few
/// for the snap) leaves the model past its last recorded increment: it keeps the checkpoint
/// the flow wrote of the commit it started from, and resumed with the default limit it redoes
/// the snap and writes the same history as a run with that limit throughout. The Lennard-Jones
/// sphere of the first test, loaded from 1 nm apart: its second snap takes 416 flow steps.
#[test]
fn a_run_that_fails_along_a_damped_flow_resumes_from_the_commit_the_flow_started_from() {
    let case = "cases/ru-sphere/smooth-lj-w3.toml";
    let sets = [
        "mesh.parameters.h_contact=8.0",
        "mesh.parameters.r_fine=40.0",
        "amplitudes.cycle.value=[-1.0, 1.0, -1.0]",
        "output.vtk=false",
        "solver.threads=1",
        "solver.refactorization_cost_ratio=20",
    ];
    let straight_out = scratch("restart-flow-failed-straight");
    let straight = part(case, &sets, &straight_out, false, None).unwrap_or_else(|e| panic!("{e}"));
    let out = scratch("restart-flow-failed");
    let few: Vec<&str> = sets.iter().copied().chain(["solver.snap_max_steps=100"]).collect();
    let error = part(case, &few, &out, false, None).expect_err("the snap needs more flow steps").to_string();
    assert!(error.contains("failed along the damped flow") && error.contains("--resume"), "{error}");
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
    assert!(out.join("restart.bin").exists(), "the failed run keeps the checkpoint of the flow's start");
    let resumed = part(case, &sets, &out, true, None).unwrap_or_else(|e| panic!("{e}"));
    for file in ["history.csv", "events.csv", "cycles.csv"] {
        let (a, b) = (std::fs::read(straight_out.join(file)).unwrap(), std::fs::read(out.join(file)).unwrap());
        assert!(
            a == b,
            "{file} of the resumed run differs from the straight run's ({} against {} bytes)",
            b.len(),
            a.len()
        );
    }
    assert_eq!((resumed.increments, resumed.snaps), (straight.increments, straight.snaps), "(increments, snaps)");
    assert!(straight.snaps >= 2, "the path snaps");
}

/// Resuming with another problem names the first key that differs; with other solver settings
/// it goes on; a folder whose run completed has nothing to resume.
#[test]
fn resuming_another_problem_or_a_completed_run_is_refused_with_the_reason() {
    let case = "cases/validation/mixed-mode-blocks.toml";
    let sets = ["output.checkpoint_minutes=0", "solver.threads=1"];
    let out = scratch("restart-refusals");
    part(case, &sets, &out, false, Some(Stop::Increments(20))).expect_err("stopped");
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

/// A sweep stopped in its first run and resumed: the first run goes on from its checkpoint, the
/// second runs afresh, and each writes the history of the sweep done in one go; resumed again,
/// the completed runs are kept (the same summaries); resumed with other sweep values it is
/// refused with the key that differs.
#[test]
fn a_sweep_stopped_in_its_first_run_and_resumed_writes_the_same_runs_as_one_sweep() {
    let case = workspace_root().join("cases/validation/hertz-axisym.toml");
    let sets = |values: &str| -> Vec<String> {
        [
            "mesh.parameters.h_contact=10.0",
            &format!("sweep={{ key = \"interfaces.0.approach\", values = {values}, label = \"approach\" }}"),
            "steps.0.initial_increment=0.25",
            "steps.0.max_increment=0.25",
            "output.vtk=false",
            "output.checkpoint_minutes=0",
            "solver.threads=1",
            "solver.refactorization_cost_ratio=20",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect()
    };
    let sweep = |out: &Path, values: &str, resume: bool, stop: Option<usize>| {
        let options =
            RunOptions { out: Some(out.to_path_buf()), resume, stop_after_increments: stop, ..Default::default() };
        stiction::sweep::run_sweep(&case, &sets(values), &options)
    };
    let straight_out = scratch("restart-sweep-straight");
    let straight = sweep(&straight_out, "[0.5, 1.0]", false, None).unwrap_or_else(|e| panic!("{e}"));
    let parts_out = scratch("restart-sweep-parts");
    let error = sweep(&parts_out, "[0.5, 1.0]", false, Some(2)).expect_err("the first run stops");
    assert!(error.to_string().contains("--resume"), "{error}");
    assert!(parts_out.join("approach=0.5").join("restart.bin").exists());
    assert!(!parts_out.join("approach=1").exists(), "the second run had not started");
    let resumed = sweep(&parts_out, "[0.5, 1.0]", true, None).unwrap_or_else(|e| panic!("{e}"));
    for folder in ["approach=0.5", "approach=1"] {
        for file in ["history.csv", "events.csv", "cycles.csv"] {
            let read = |root: &Path| std::fs::read(root.join(folder).join(file)).unwrap();
            assert!(read(&parts_out) == read(&straight_out), "{folder}/{file} differs from the one-go sweep's");
        }
    }
    let forces = |s: &[RunSummary]| s.iter().map(|s| s.interfaces[0].max_force.to_bits()).collect::<Vec<_>>();
    assert_eq!(forces(&resumed), forces(&straight));
    let again = sweep(&parts_out, "[0.5, 1.0]", true, None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(forces(&again), forces(&straight), "completed runs are kept");
    let error = sweep(&parts_out, "[0.5, 2.0]", true, None).unwrap_err().to_string();
    assert!(error.contains("sweep.values") && error.contains("1.0") && error.contains("2.0"), "{error}");
    let error = sweep(&scratch("restart-sweep-nothing"), "[0.5, 1.0]", true, None).unwrap_err().to_string();
    assert!(error.contains("sweep-plan.json"), "{error}");
}

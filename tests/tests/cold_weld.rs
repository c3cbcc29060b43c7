//! A cold weld: one w = 6 asperity (point force) at the pole of the Ru hemisphere, quick mesh,
//! pressed to 2 nm and pulled back to -6 nm.
//! - With the shipped Ru (Y = 3.42 GPa) it pulls off (about -388 nN) and the unloading step
//!   ends as soon as it has separated.
//! - With Y = 1 GPa the body under the asperity yields in tension and follows the flat: the
//!   force holds near -370 nN to the end, and the run must say that the body is being drawn out
//!   plastically rather than ask to unload further. The energy check: over the trailing
//!   retraction the continuum's plastic dissipation dD is most of the flat's work W (the
//!   drawing) and cannot exceed it (W = dD + the growth of the elastic and interface energies,
//!   both non-negative while the force holds).

use stiction::run::RunSummary;
use stiction_tests::{history_columns, one_asperity_at_the_pole, run_case};

/// Runs the asperity at the pole with yield stress `yield_stress` (GPa).
fn pull_one_asperity(yield_stress: f64, label: &str) -> RunSummary {
    let points = one_asperity_at_the_pole("cold-weld-input");
    let (_, summary) = run_case(
        "cases/ru-rough-sphere/rough-w6-quick.toml",
        &[
            &format!("interfaces.0.points={{ file = \"{}\" }}", points.display()),
            &format!("materials.ru.yield_stress={yield_stress}"),
            "amplitudes.cycle.value=[-0.5, 2.0, -6.0]",
            "output.vtk=false",
        ],
        label,
    );
    summary
}

#[test]
fn an_asperity_on_a_yielding_body_is_reported_as_drawn_out_and_the_flats_work_is_dissipated() {
    let summary = pull_one_asperity(1.0, "cold-weld-yielding");
    assert_eq!(summary.status, "completed");
    let warning = summary
        .warnings
        .iter()
        .find(|w| w.contains("had not separated"))
        .unwrap_or_else(|| panic!("no warning that the asperity is still attached: {:?}", summary.warnings));
    assert!(warning.contains("drawn out plastically"), "{warning}");
    // a point force: the work goes into the mesh's continuum, none into footprint sliders; the
    // most tensile force is not called a pull-off
    assert!(warning.contains("0.0000 aJ (0%) went into the footprint sliders"), "{warning}");
    assert!(warning.contains("into plastic flow of the mesh's continuum"), "{warning}");
    let i = &summary.interfaces[0];
    assert!(!i.separated && i.pull_off_force.is_none() && i.most_tensile_force < -300.0, "{i:?}");
    assert!(i.final_n_contact == 1, "{i:?}");
    // the last 1 nm of retraction, from history.csv
    let rows = history_columns(&summary.output_directory, &["approach", "force", "plastic_dissipation"]);
    let end = rows.len() - 1;
    let start = rows.iter().rposition(|r| r[0] >= rows[end][0] + 1.0).unwrap();
    let work: f64 =
        rows[start..].windows(2).map(|w| 0.5 * (w[0][1].abs() + w[1][1].abs()) * (w[0][0] - w[1][0]).abs()).sum();
    let dissipated = rows[end][2] - rows[start][2];
    let share = dissipated / work;
    println!(
        "last {:.3} nm: flat's work {work:.2}, plastic dissipation {dissipated:.2} aJ ({:.1}%)",
        rows[start][0] - rows[end][0],
        100.0 * share
    );
    assert!(rows[start..].iter().all(|r| r[1] < -300.0), "the asperity holds above 300 nN");
    assert!(share > 0.5 && share <= 1.0 + 1e-6, "plastic share of the flat's work {share}");
}

#[test]
fn the_same_asperity_on_shipped_ru_pulls_off_and_ends_the_step() {
    let summary = pull_one_asperity(3.42, "cold-weld-shipped");
    assert_eq!(summary.status, "completed");
    assert!(!summary.warnings.iter().any(|w| w.contains("had not separated")), "{:?}", summary.warnings);
    // the unloading step ended at separation, well before the schedule's -6 nm (t = 2)
    assert!(summary.final_time < 1.6, "final time {}", summary.final_time);
    let pull_off = summary.interfaces[0].pull_off_force.expect("the asperity separated");
    assert!((-400.0..-370.0).contains(&pull_off), "pull-off {pull_off} nN (single-asperity law: about -388)");
}

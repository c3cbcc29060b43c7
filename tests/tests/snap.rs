//! Snaps: a run that starts inside the jump-in range, or whose path has no nearby equilibrium
//! left, settles on the stable state the displacement-controlled system snaps to and goes on
//! (core `nonlinear::settle`, driver "snaps"). The reference is path independence: the smooth
//! elastic Lennard-Jones sphere at w = 3 J/m^2 (Tabor 2.1) started inside the jump-in range
//! (3 z0 from the pole, where Newton cannot find an equilibrium at t = 0) and started far away
//! (1.2 nm, jumping in on the way) must reach the same state at the same position of the flat,
//! and the same most tensile force on the contact branch. The two ways to solve a snap, by
//! descent (what "auto", the default, takes for this body) and along the damped flow, must
//! land on the same state of this elastic body (one stable state in reach: its path does not
//! matter), and report the same energy dissipated by the snaps (the potential energy's fall).
//! A start out of equilibrium snaps at its first failed attempt, without cuts.

use stiction_tests::run_case;

/// (approach, force) at the end of the loading step (t = 1).
fn at_end_of_loading(dir: &std::path::Path) -> (f64, f64) {
    let text = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let row = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect::<Vec<f64>>())
        .find(|v| (v[col("time")] - 1.0).abs() < 1e-12)
        .expect("a state at t = 1");
    (row[col("approach")], row[col("force")])
}

#[test]
fn a_start_inside_the_jump_in_range_snaps_to_the_state_a_far_start_reaches() {
    // both end the loading with the flat 0.3 nm from the undeformed pole
    let run = |gap: &str, approach: &str, snap: &str, label: &str| {
        let gap_set = format!("interfaces.0.initial_gap={gap}");
        let approach_set = format!("interfaces.0.approach={approach}");
        let snap_set = format!("solver.snap=\"{snap}\"");
        let sets = [
            "interfaces.0.parameters.w=3.0",
            "mesh.parameters.h_contact=3.0",
            "solver.continuation=\"none\"",
            "steps.1.end_time=1.02",
            gap_set.as_str(),
            approach_set.as_str(),
            snap_set.as_str(),
        ];
        run_case("cases/validation/lj-sphere.toml", &sets, label).1
    };
    let near = run("0.507", "0.207", "settle", "snap-near-start");
    // "auto", the default, settles: this elastic body with a reversible law has no path memory
    let far = run("1.2", "0.9", "auto", "snap-far-start");
    let flowed = run("0.507", "0.207", "damped-flow", "snap-near-start-flow");
    for s in [&near, &far, &flowed] {
        assert_eq!(s.status, "completed", "{:?}", s.message);
        assert!(s.snaps >= 1, "no snap in {}", s.output_directory.display());
    }
    assert_eq!((far.snap_method.as_str(), flowed.snap_method.as_str()), ("settle", "damped-flow"));
    let (a_near, f_near) = at_end_of_loading(&near.output_directory);
    let (a_far, f_far) = at_end_of_loading(&far.output_directory);
    assert!((0.507 - a_near - (1.2 - a_far)).abs() < 1e-9, "the flat is not at the same place");
    println!("force at the common position: near start {f_near}, far start {f_far}");
    assert!((f_near - f_far).abs() < 1e-6 * f_far.abs(), "{f_near} vs {f_far}");
    let (a_flow, f_flow) = at_end_of_loading(&flowed.output_directory);
    println!("force at the end of loading after the damped-flow snap: {f_flow} (descent: {f_near})");
    assert!((a_flow - a_near).abs() < 1e-12 && (f_flow - f_near).abs() < 1e-6 * f_near.abs(), "{f_flow} vs {f_near}");
    let (p_near, p_far) = (near.interfaces[0].most_tensile_force, far.interfaces[0].most_tensile_force);
    println!("most tensile force: near start {p_near}, far start {p_far}");
    // sampled at different positions along the same branch (increments of 0.0021 / 0.009 nm)
    assert!((p_near - p_far).abs() < 1e-3 * p_far.abs(), "{p_near} vs {p_far}");
    // the snap is a jump of the force, recorded as an event
    let events = std::fs::read_to_string(near.output_directory.join("events.csv")).unwrap();
    assert!(events.lines().nth(1).is_some_and(|l| l.contains(",jump,")), "{events}");
    // the near start is out of equilibrium: its first failed attempt snaps at once, with the
    // reason, instead of being cut down to the minimum increment (which no shorter increment
    // passes); the far start's first increments converge and are not affected
    for s in [&near, &flowed] {
        let log = std::fs::read_to_string(s.output_directory.join("messages.log")).unwrap();
        let before_snap = log.split("snapping from t = 0.000000").next().unwrap();
        assert!(before_snap.contains("the initial state is out of equilibrium"), "{log}");
        assert!(!before_snap.contains("cut to dt"), "cut before the snap:\n{before_snap}");
    }
    let far_log = std::fs::read_to_string(far.output_directory.join("messages.log")).unwrap();
    assert!(!far_log.contains("out of equilibrium"), "{far_log}");
    // the energy the snaps dissipated is the fall of the potential energy from where each snap
    // starts to where it lands, whatever the path: the descent's (by Simpson's rule along the
    // straight segment) and the damped flow's (the drag's work, by the trapezoid rule along
    // its steps) must agree to the flow's accuracy; the history's last row holds the total
    let (by_descent, by_flow) = (near.snap_dissipation, flowed.snap_dissipation);
    println!("energy dissipated by the snaps: descent {by_descent}, damped flow {by_flow}");
    assert!(by_descent > 0.0 && (by_flow / by_descent - 1.0).abs() < 2e-3, "{by_flow} vs {by_descent}");
    for s in [&near, &flowed] {
        let text = std::fs::read_to_string(s.output_directory.join("history.csv")).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        let col = header.iter().position(|h| *h == "snap_dissipation").expect("a snap_dissipation column");
        let last: f64 = text.lines().last().unwrap().split(',').nth(col).unwrap().parse().unwrap();
        // (history.csv holds 11 significant digits)
        assert!(
            (last / s.snap_dissipation - 1.0).abs() < 1e-9,
            "history.csv's {last} against summary.json's {}",
            s.snap_dissipation
        );
    }
}

/// Where the descent finds no stable state, the snap follows the damped flow instead of
/// stopping the run (`SnapMethod::SettleOrFlow`, what "auto" takes for an elastic body). The
/// elastic w = 6 sphere on a 4 nm contact mesh started 0.25 nm from the pole (the start-gap
/// scan's first start, `scripts/start-gap-scan.sh`) meets such a snap while unloading past
/// pull-off (t = 1.5702: 201 descent steps stalled at a residual of 4.6e-2 nN, and the run
/// stopped there before). The reference is path independence again: this elastic body with a
/// reversible law has one pull-off branch, so the run must pull off at the force of the same
/// sphere started 0.507 nm away (the shipped start), which needs no such snap.
#[test]
fn a_snap_whose_descent_stalls_follows_the_damped_flow_and_pulls_off_as_another_start_does() {
    let run = |gap: &str, label: &str| {
        let gap_set = format!("interfaces.0.initial_gap={gap}");
        let sets = [
            "output.vtk=false",
            "solver.threads=1",
            "mesh.parameters.h_contact=4.0",
            "mesh.parameters.r_fine=40.0",
            "materials.ru.model=\"linear-elastic\"",
            gap_set.as_str(),
        ];
        run_case("cases/ru-sphere/smooth-lj-w6.toml", &sets, label).1
    };
    let near = run("0.25", "snap-descent-stalls");
    let shipped = run("0.507", "snap-descent-stalls-shipped-start");
    for s in [&near, &shipped] {
        assert_eq!(s.status, "completed", "{:?}", s.message);
    }
    let log = std::fs::read_to_string(near.output_directory.join("messages.log")).unwrap();
    let fallback = log.lines().find(|l| l.contains("the descent found no stable state")).unwrap_or_else(|| {
        panic!(
            "no descent failed in {}: the path no longer meets the stalled snap this test is \
             about; find a start that does (the start-gap scan's table) and test that",
            near.output_directory.display()
        )
    });
    println!("{fallback}");
    assert!(fallback.contains("following the damped flow instead"), "{fallback}");
    assert_eq!(near.snap_method, "settle, the damped flow where a descent failed");
    let pull_off = |s: &stiction::run::RunSummary| s.interfaces[0].pull_off_force.expect("the sphere separated");
    let (p_near, p_shipped) = (pull_off(&near), pull_off(&shipped));
    println!("pull-off: started at 0.25 nm {p_near}, at 0.507 nm {p_shipped}");
    // the same branch, sampled by increments that land at different places near its fold
    assert!((p_near - p_shipped).abs() < 1e-4 * p_shipped.abs(), "{p_near} vs {p_shipped}");
}

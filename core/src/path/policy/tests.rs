//! Each rule of the path policy on the facts that make it fire, and on those that must not.

use super::*;
use crate::path::ContinuationMethod;

fn incrementation() -> Incrementation {
    Incrementation::for_tests()
}

const DIVERGED: AttemptFailure = AttemptFailure::Solver(IncrementFailure::Diverged { iterations: 25, residual: 1.0 });

fn facts<'a>(failure: &'a AttemptFailure, incrementation: &'a Incrementation) -> FailureFacts<'a> {
    FailureFacts {
        failure,
        t: 0.5,
        attempted: 0.1,
        crossing: false,
        continuation: None,
        crossing_can_start: true,
        resume_after: 0.6,
        incrementation,
        force_unit: "nN",
    }
}

fn rule_of(decision: &Decision) -> Option<Rule> {
    match decision {
        Decision::Snap { rule, .. } => Some(*rule),
        _ => None,
    }
}

/// A failure the policy sees: counted first, as the driver does.
fn fail(policy: &mut PathPolicy, facts: &FailureFacts<'_>) -> Decision {
    policy.attempt_failed();
    policy.after_failure(facts)
}

#[test]
fn a_crossing_under_way_cuts_its_own_increment_before_any_other_rule() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    policy.unbalanced_start(Some((2.0, 1.0)));
    let decision = fail(&mut policy, &FailureFacts { crossing: true, ..facts(&DIVERGED, &inc) });
    assert_eq!(decision, Decision::CutCrossing);
    // the unbalanced start is still there for load control's first failure
    assert_eq!(rule_of(&fail(&mut policy, &facts(&DIVERGED, &inc))), Some(Rule::UnbalancedStart));
}

#[test]
fn an_unbalanced_start_snaps_at_the_minimum_once_and_only_on_a_convergence_failure() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    policy.unbalanced_start(Some((2.0, 1.0)));
    let law = AttemptFailure::Jumped { why: "moved too far" };
    assert_eq!(fail(&mut policy, &facts(&law, &inc)), Decision::CutLoad, "not a failure to converge");
    let Decision::Snap { dt, crawl, reason, rule } = fail(&mut policy, &facts(&DIVERGED, &inc)) else {
        panic!("the unbalanced start snaps")
    };
    assert_eq!((dt, crawl, rule), (inc.minimum, false, Rule::UnbalancedStart));
    assert!(reason.contains("out of equilibrium (residual 2.000e0 nN against the test's 1.000e0"), "{reason}");
    assert_eq!(fail(&mut policy, &facts(&DIVERGED, &inc)), Decision::CutLoad, "said once");
    // a commit ends the start's rule too
    let mut policy = PathPolicy::default();
    policy.unbalanced_start(Some((2.0, 1.0)));
    policy.committed(0.6, false, true, false);
    assert_eq!(fail(&mut policy, &facts(&DIVERGED, &inc)), Decision::CutLoad);
}

#[test]
fn continuation_takes_over_after_its_cuts_unless_it_just_handed_back_or_has_nothing_to_start_from() {
    let inc = &incrementation();
    let continuation = Some(Continuation { method: ContinuationMethod::ArcLength, after_cuts: 2 });
    let mut policy = PathPolicy::default();
    assert_eq!(
        fail(&mut policy, &FailureFacts { continuation, ..facts(&DIVERGED, inc) }),
        Decision::CutLoad,
        "one cut"
    );
    assert_eq!(
        fail(&mut policy, &FailureFacts { continuation, ..facts(&DIVERGED, inc) }),
        Decision::StartCrossing { resume_after: 0.6 }
    );
    let nothing = FailureFacts { crossing_can_start: false, continuation, ..facts(&DIVERGED, inc) };
    assert_eq!(fail(&mut policy, &nothing), Decision::CutLoad, "no converged increment to start from");
    policy.crossing_handed_back();
    assert_eq!(
        fail(&mut policy, &FailureFacts { continuation, ..facts(&DIVERGED, inc) }),
        Decision::CutLoad,
        "the crossing just handed back"
    );
    policy.committed(0.55, false, true, false);
    assert_eq!(
        fail(&mut policy, &FailureFacts { continuation, ..facts(&DIVERGED, inc) }),
        Decision::CutLoad,
        "cuts count from the commit"
    );
    assert!(matches!(
        fail(&mut policy, &FailureFacts { continuation, ..facts(&DIVERGED, inc) }),
        Decision::StartCrossing { .. }
    ));
}

#[test]
fn a_crawl_of_six_small_load_controlled_commits_snaps_one_initial_increment_ahead() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    for k in 0..CRAWL_COMMITS {
        assert_eq!(policy.before_attempt(false, 0.5, 1e-4, &inc), None, "after {k} small commits");
        policy.committed(0.5 + k as f64 * 1e-4, false, true, true);
    }
    assert_eq!(policy.before_attempt(true, 0.5, 1e-4, &inc), None, "not while a crossing is under way");
    let Some(Decision::Snap { dt, crawl, reason, rule }) = policy.before_attempt(false, 0.5006, 1e-4, &inc) else {
        panic!("the crawl snaps")
    };
    assert_eq!((dt, crawl, rule), (inc.initial, true, Rule::Crawl));
    assert_eq!(reason, "crawling at t = 0.500600 (dt = 1.00e-4)");
    assert_eq!(policy.before_attempt(false, 0.5006, 1e-4, &inc), None, "the count starts again");
    // a commit that is not small, or not by load control, breaks the row
    for small_by_load_control in [(false, true), (true, false)] {
        let mut policy = PathPolicy::default();
        for _ in 0..CRAWL_COMMITS - 1 {
            policy.committed(0.5, false, true, true);
        }
        policy.committed(0.5, false, small_by_load_control.1, small_by_load_control.0);
        assert_eq!(policy.before_attempt(false, 0.5, 1e-4, &inc), None, "{small_by_load_control:?}");
    }
}

#[test]
fn after_a_crawl_snap_a_failure_snaps_again_until_load_control_converges_or_a_breakpoint_is_reached() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    policy.snapped(inc.initial, &inc);
    policy.committed(0.6, true, false, false);
    policy.after_crawl_snap(true, false);
    let decision = fail(&mut policy, &facts(&DIVERGED, &inc));
    assert_eq!(rule_of(&decision), Some(Rule::StillCrawling));
    assert!(matches!(decision, Decision::Snap { dt, crawl: true, .. } if dt == inc.initial));
    policy.committed(0.61, false, true, false);
    assert_eq!(fail(&mut policy, &facts(&DIVERGED, &inc)), Decision::CutLoad, "load control converged");
    policy.after_crawl_snap(true, true);
    assert_eq!(fail(&mut policy, &facts(&DIVERGED, &inc)), Decision::CutLoad, "the snap reached a breakpoint");
}

/// Floors r = c (T - t_f) of attempts past a fold at t_f: the secant places it exactly.
#[test]
fn two_stalled_attempts_place_a_fold_by_the_secant_of_their_floors() {
    let (t_f, c) = (0.503, 100.0);
    let floor = |target: f64| c * (target - t_f);
    let d = fold_ahead(0.5, (0.6, floor(0.6)), (0.525, floor(0.525))).unwrap();
    assert!((d - 0.003).abs() < 1e-12, "{d}");
    assert_eq!(fold_ahead(0.5, (0.525, floor(0.525)), (0.6, floor(0.6))), None, "the later attempt must be nearer");
    assert_eq!(fold_ahead(0.5, (0.6, 1.0), (0.525, 2.0)), None, "its floor must be lower");
}

#[test]
fn a_fold_within_the_next_cuts_reach_is_snapped_over_at_once_without_continuation_only() {
    let inc = incrementation();
    let floor = |target: f64| 100.0 * (target - 0.503);
    let stalled = |target: f64| {
        AttemptFailure::Solver(IncrementFailure::Stagnated { iterations: 8, residual: floor(target), earlier: 1e9 })
    };
    let (first, second) = (stalled(0.6), stalled(0.525));
    let mut policy = PathPolicy::default();
    assert_eq!(fail(&mut policy, &facts(&first, &inc)), Decision::CutLoad, "one stall places nothing");
    let Decision::Snap { dt, crawl, reason, rule } =
        fail(&mut policy, &FailureFacts { attempted: 0.025, ..facts(&second, &inc) })
    else {
        panic!("the fold is within reach")
    };
    assert_eq!((crawl, rule), (false, Rule::FoldAhead));
    assert!((dt - 0.025 * inc.cut_factor).abs() < 1e-15, "the next cut's increment: {dt}");
    assert!(reason.starts_with("a fold 3.00e-3 from t = 0.500000"), "{reason}");
    // a fold farther ahead than the next cut: load control cuts on
    let far = |target: f64| {
        AttemptFailure::Solver(IncrementFailure::Stagnated {
            iterations: 8,
            residual: 100.0 * (target - 0.52),
            earlier: 1e9,
        })
    };
    let mut policy = PathPolicy::default();
    fail(&mut policy, &facts(&far(0.6), &inc));
    assert_eq!(fail(&mut policy, &FailureFacts { attempted: 0.025, ..facts(&far(0.525), &inc) }), Decision::CutLoad);
    // with continuation the crossing takes the fold over
    let continuation = Some(Continuation { method: ContinuationMethod::ArcLength, after_cuts: 10 });
    let mut policy = PathPolicy::default();
    fail(&mut policy, &FailureFacts { continuation, ..facts(&first, &inc) });
    let with = FailureFacts { continuation, attempted: 0.025, ..facts(&second, &inc) };
    assert_eq!(fail(&mut policy, &with), Decision::CutLoad);
    // a commit past the remembered target forgets it: it was no fold
    let mut policy = PathPolicy::default();
    fail(&mut policy, &facts(&first, &inc));
    policy.committed(0.61, false, true, false);
    assert_eq!(fail(&mut policy, &FailureFacts { attempted: 0.025, ..facts(&second, &inc) }), Decision::CutLoad);
}

#[test]
fn snaps_in_a_row_at_the_minimum_go_one_initial_increment_ahead_then_stop() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    for k in 0..MAX_SNAPS_WITHOUT_PROGRESS {
        let decision = policy.snap("cut below the minimum".into(), 0.5, &inc);
        assert!(matches!(decision, Decision::Snap { dt, rule: Rule::Cut, .. } if dt == inc.minimum), "snap {k}");
        policy.snapped(inc.minimum, &inc);
        policy.committed(0.5 + (k + 1) as f64 * inc.minimum, true, false, false);
    }
    let decision = policy.snap("cut below the minimum".into(), 0.503, &inc);
    assert!(matches!(decision, Decision::Snap { dt, rule: Rule::Stuck, .. } if dt == inc.initial), "{decision:?}");
    // where the initial increment is no further than the minimum, the run stops
    let short = Incrementation { initial: inc.minimum, ..inc };
    let Decision::Stop { reason } = policy.snap("cut below the minimum".into(), 0.503, &short) else {
        panic!("no progress")
    };
    assert_eq!(reason, "cut below the minimum; 3 snaps in a row found no path onward from t = 0.503000");
    // a snap past the minimum, or an ordinary increment, is progress
    policy.snapped(inc.initial, &inc);
    assert!(matches!(policy.snap("again".into(), 0.6, &inc), Decision::Snap { rule: Rule::Cut, .. }));
    let mut policy = PathPolicy::default();
    for _ in 0..MAX_SNAPS_WITHOUT_PROGRESS {
        policy.snapped(inc.minimum, &inc);
    }
    policy.committed(0.6, false, true, false);
    assert!(matches!(policy.snap("again".into(), 0.6, &inc), Decision::Snap { rule: Rule::Cut, .. }));
}

#[test]
fn a_failed_run_is_saved_to_go_on_as_from_a_steps_start() {
    let inc = incrementation();
    let mut policy = PathPolicy::default();
    let stalled = AttemptFailure::Solver(IncrementFailure::Stagnated { iterations: 8, residual: 10.0, earlier: 1e9 });
    fail(&mut policy, &facts(&stalled, &inc));
    for _ in 0..MAX_SNAPS_WITHOUT_PROGRESS {
        policy.snapped(inc.minimum, &inc);
    }
    let saved = policy.for_failed_run();
    assert_eq!(saved.cuts_since_commit(), 0);
    assert_eq!((saved.snaps_in_a_row, saved.stagnated_attempt), (0, None));
}

fn jump_facts() -> JumpFacts {
    JumpFacts {
        moved: 1.0,
        moved_before: 1.0,
        dt: 0.1,
        dt_before: 0.1,
        turned: false,
        noise: 1e-12,
        continuation: false,
        from_breakpoint: false,
        arc_blocked: false,
    }
}

#[test]
fn an_increment_that_moved_five_times_its_rate_or_turned_back_with_continuation_jumped() {
    let base = jump_facts();
    assert_eq!(jumped(&base), None, "on its rate");
    assert_eq!(jumped(&JumpFacts { moved: 4.9, ..base }), None);
    assert_eq!(jumped(&JumpFacts { moved: 5.1, ..base }), Some("moved too far"));
    assert_eq!(jumped(&JumpFacts { moved: 2.6, dt: 0.05, ..base }), Some("moved too far"), "rate times dt");
    assert_eq!(jumped(&JumpFacts { moved: 5.1, from_breakpoint: true, ..base }), None, "the rate may change there");
    let cont = JumpFacts { continuation: true, ..base };
    assert_eq!(jumped(&JumpFacts { moved: 5.1, from_breakpoint: true, ..cont }), Some("moved too far"));
    assert_eq!(jumped(&JumpFacts { turned: true, ..base }), None, "turning back counts with continuation only");
    assert_eq!(jumped(&JumpFacts { turned: true, ..cont }), Some("turned back"));
    assert_eq!(jumped(&JumpFacts { turned: true, from_breakpoint: true, ..cont }), None, "the load reversed");
    assert_eq!(jumped(&JumpFacts { turned: true, arc_blocked: true, ..cont }), None, "load control goes on");
    assert_eq!(jumped(&JumpFacts { moved: 1e-13, moved_before: 1e-15, ..base }), None, "round-off");
    assert_eq!(jumped(&JumpFacts { dt_before: 0.0, moved: 100.0, ..base }), None, "after a snap: no rate");
}

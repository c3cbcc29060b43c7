//! The driver's rules for paths that load control cannot follow: the crawl rule
//! ([`CRAWL_COMMITS`] small commits in a row are passed by a snap one initial increment ahead,
//! and a failure while still crawling snaps again at once) and the stuck rule
//! ([`MAX_SNAPS_WITHOUT_PROGRESS`] snaps in a row at the minimum increment are followed by one
//! an initial increment ahead, or the run stops where that is no further), the jump rule
//! without continuation (an increment that converged far off the path is cut like a failed one),
//! and the fold rule (two stalled attempts whose residual floors place a fold short of the next
//! attempt are followed by a snap over that attempt's increment, not by more cuts).
//!
//! The folds are made on purpose: a linear cantilever solved by Newton, except that the
//! nonlinear solver refuses every increment a given rule calls impassable (from the committed
//! time to the target), or lands it off the path ([`Twist`]). Snaps settle by descent, which
//! the twist does not reach, so the driver's choices are the only thing under test, and each
//! count below follows from the incrementation by hand.

use std::cell::{Cell, RefCell};
use std::rc::Rc;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver, Ordering};
use stiction_core::model::Model;
use stiction_core::nonlinear::{
    IncrementFailure, IncrementReport, NewtonSettings, NewtonSolver, NonlinearSolver, ReferenceScales,
};
use stiction_core::path::policy::{CRAWL_COMMITS, CRAWL_FRACTION, MAX_SNAPS_WITHOUT_PROGRESS};
use stiction_core::path::{Incrementation, RunPlan, SnapMethod, StartPredictor, StepPlan, TangentChoice, run_steps};
use stiction_core::problem::NonlinearProblem;
use stiction_core::record::{CommittedIncrement, Observer, RunSummary};
use stiction_tests::build_case;

/// Which increments (committed time, target) load control cannot take.
type Impassable = fn(f64, f64) -> bool;

/// What the mock Newton does to an increment (committed time, target) besides solving it.
#[derive(Clone, Copy)]
enum Twist {
    /// Refuses the increments the rule calls impassable, as diverged.
    Refuse(Impassable),
    /// An increment from before [`FOLD`] to past it lands ten times as far as the path goes:
    /// Newton's iterations carried the body onto another branch.
    LandPastFold,
    /// An increment from before the fold at this time to past it stagnates, at a residual
    /// floor that grows with the overshoot, ||r|| = target - fold (a fold of the path).
    StallPast(f64),
}

const FOLD: f64 = 0.45;

/// Newton with a [`Twist`].
struct TwistedNewton {
    newton: NewtonSolver,
    committed: Rc<Cell<f64>>,
    twist: Twist,
}

impl NonlinearSolver for TwistedNewton {
    fn solve(
        &mut self,
        problem: &mut dyn NonlinearProblem,
        linear: &mut dyn LinearSolver,
        t: f64,
        scales: ReferenceScales,
    ) -> Result<IncrementReport, IncrementFailure> {
        let from = self.committed.get();
        if let Twist::Refuse(impassable) = self.twist
            && impassable(from, t)
        {
            return Err(IncrementFailure::Diverged { iterations: 1, residual: 1.0 });
        }
        if let Twist::StallPast(fold) = self.twist
            && from < fold
            && t > fold
        {
            let floor = t - fold;
            return Err(IncrementFailure::Stagnated { iterations: 8, residual: floor, earlier: floor });
        }
        let report = self.newton.solve(problem, linear, t, scales)?;
        if matches!(self.twist, Twist::LandPastFold) && from < FOLD && t > FOLD {
            let du = problem.increment_since_commit();
            problem.add_to_free(&du, 9.0);
            problem.assemble(true)?;
        }
        Ok(report)
    }

    fn settings(&self) -> &NewtonSettings {
        &self.newton.settings
    }
}

/// Records the committed times (shared with the solver) and displacement norms, and the
/// driver's messages.
struct Recorder {
    committed: Rc<Cell<f64>>,
    times: Rc<RefCell<Vec<f64>>>,
    norms: Rc<RefCell<Vec<f64>>>,
    messages: Rc<RefCell<Vec<String>>>,
}

impl Observer for Recorder {
    fn committed(&mut self, model: &Model, _increment: &CommittedIncrement) -> stiction_core::error::Result<()> {
        self.committed.set(model.time);
        self.times.borrow_mut().push(model.time);
        self.norms.borrow_mut().push(model.displacement.iter().map(|u| u * u).sum::<f64>().sqrt());
        Ok(())
    }

    fn message(&mut self, text: &str) {
        self.messages.borrow_mut().push(text.to_string());
    }
}

/// What a run on the folded path did.
struct Run {
    summary: RunSummary,
    /// Committed times, the initial state's 0 first, and the displacement norms there.
    times: Vec<f64>,
    norms: Vec<f64>,
    messages: Vec<String>,
}

impl Run {
    fn count(&self, text: &str) -> usize {
        self.messages.iter().filter(|m| m.contains(text)).count()
    }
}

/// Runs the cantilever (coarse, linear elastic) from t = 0 to 1 with `incrementation`, load
/// control refusing what `impassable` names.
fn run_on_folded_path(incrementation: Incrementation, impassable: Impassable) -> Run {
    run_on_path(incrementation, Twist::Refuse(impassable))
}

/// Runs the cantilever (coarse, linear elastic) from t = 0 to 1 with `incrementation`, solved
/// by Newton with `twist`.
fn run_on_path(incrementation: Incrementation, twist: Twist) -> Run {
    let (_, mut built) = build_case("cases/validation/cantilever.toml", &["mesh.parameters.h=1.0"]);
    let committed = Rc::new(Cell::new(0.0));
    let times = Rc::new(RefCell::new(Vec::new()));
    let norms = Rc::new(RefCell::new(Vec::new()));
    let messages = Rc::new(RefCell::new(Vec::new()));
    let recorder = Recorder {
        committed: committed.clone(),
        times: times.clone(),
        norms: norms.clone(),
        messages: messages.clone(),
    };
    let mut observers: Vec<Box<dyn Observer>> = vec![Box::new(recorder)];
    let plan = RunPlan {
        name: "folded path".into(),
        units: Default::default(),
        output_directory: Default::default(),
        steps: vec![StepPlan {
            name: "load".into(),
            end_time: 1.0,
            incrementation,
            output_every: 0,
            until_separated: None,
        }],
        continuation: None,
        interfaces: built.interfaces.clone(),
        interrupt: None,
        start_predictor: StartPredictor::Tangent,
        snap: SnapMethod::Settle,
        tangent: TangentChoice::Consistent,
        checkpoint: None,
        stop_after_increments: None,
        stop_after_flow_steps: None,
    };
    let model = &mut built.model;
    let mut linear = FaerCholesky::analyse_with(model.pattern(), Ordering::Amd).unwrap();
    let mut nonlinear = TwistedNewton { newton: NewtonSolver { settings: built.newton.clone() }, committed, twist };
    let summary = run_steps(model, &plan, &mut linear, &mut nonlinear, &mut observers).unwrap();
    let (times, norms, messages) = (times.borrow().clone(), norms.borrow().clone(), messages.borrow().clone());
    Run { summary, times, norms, messages }
}

/// Steps of 1/8 exactly (binary fractions: the committed times are exact).
fn eighths(minimum: f64) -> Incrementation {
    Incrementation { initial: 0.125, minimum, maximum: 0.125, cut_factor: 0.25, growth_factor: 1.5, easy_iterations: 5 }
}

/// Stuck between t = 0.5 and 0.55: no increment that starts there, or that starts before 0.55
/// and ends past 0.5, converges.
fn stuck_after_one_half(committed: f64, target: f64) -> bool {
    committed < 0.55 && target > 0.5
}

#[test]
fn snaps_that_find_no_path_onward_are_followed_by_one_an_initial_increment_ahead() {
    let minimum = 1e-3;
    let run = run_on_folded_path(eighths(minimum), stuck_after_one_half);
    assert_eq!(run.summary.status, "completed", "{:?}", run.summary.message);
    // 0.125, 0.25, 0.375, 0.5 by load control; then snaps at the minimum increment, each after
    // the cuts 0.125 -> 0.03125 -> 0.0078125 -> 0.001953125 -> below 1e-3 (4 cuts)
    assert_eq!(run.summary.snaps, MAX_SNAPS_WITHOUT_PROGRESS + 1);
    assert_eq!(run.summary.cut_increments, 4 * (MAX_SNAPS_WITHOUT_PROGRESS + 1));
    let snapped = &run.times[5..5 + MAX_SNAPS_WITHOUT_PROGRESS + 1];
    for (k, &t) in snapped.iter().take(MAX_SNAPS_WITHOUT_PROGRESS).enumerate() {
        assert!((t - (0.5 + (k + 1) as f64 * minimum)).abs() < 1e-12, "snap {k} at the minimum increment: {t}");
    }
    let ahead = 0.5 + MAX_SNAPS_WITHOUT_PROGRESS as f64 * minimum + 0.125;
    assert!((snapped[MAX_SNAPS_WITHOUT_PROGRESS] - ahead).abs() < 1e-12, "{snapped:?}");
    assert_eq!(run.times.last(), Some(&1.0));
    assert_eq!(run.count("snapping from"), MAX_SNAPS_WITHOUT_PROGRESS + 1);
}

#[test]
fn a_run_stops_with_the_reason_where_a_snap_ahead_is_no_further_than_the_minimum_increment() {
    // the minimum is the initial increment: each snap moves 1/8 on, and the fourth may not
    let run = run_on_folded_path(eighths(0.125), |_, target| target > 0.5);
    assert_eq!(run.summary.status, "failed");
    assert_eq!(run.summary.snaps, MAX_SNAPS_WITHOUT_PROGRESS);
    assert_eq!(run.summary.final_time, 0.5 + MAX_SNAPS_WITHOUT_PROGRESS as f64 * 0.125);
    let message = run.summary.message.unwrap_or_default();
    assert!(message.contains("snaps in a row found no path onward from t = 0.875"), "{message}");
    assert!(message.contains("increment below the minimum"), "{message}");
}

/// Folds at t = 0.3 and 0.55 that load control cannot step over: a snap one initial increment
/// (0.2) past the first lands before the second, and the next initial increment steps over it.
fn two_folds(committed: f64, target: f64) -> bool {
    [0.3, 0.55].iter().any(|&fold| committed < fold && target > fold)
}

#[test]
fn a_crawl_towards_a_fold_is_passed_by_snaps_one_initial_increment_ahead() {
    let incrementation = Incrementation { initial: 0.2, minimum: 1e-9, maximum: 0.2, ..eighths(1e-9) };
    let run = run_on_folded_path(incrementation, two_folds);
    assert_eq!(run.summary.status, "completed", "{:?}", run.summary.message);
    // load control creeps towards 0.3 in shrinking increments; the crawl rule snaps past it
    let crawl = run.times.windows(2).position(|w| w[1] > 0.3).expect("the first fold is passed");
    let (before, after) = (run.times[crawl], run.times[crawl + 1]);
    assert!((after - (before + 0.2)).abs() < 1e-12, "one initial increment ahead: {before} -> {after}");
    let small: Vec<f64> = run.times[..=crawl].windows(2).map(|w| w[1] - w[0]).rev().take(CRAWL_COMMITS).collect();
    assert!(small.iter().all(|&dt| dt < CRAWL_FRACTION * 0.2), "the commits before the crawl snap: {small:?}");
    assert_eq!(run.count(": crawling at t ="), 1);
    // from there (past 0.3, before 0.55) the first attempt steps over 0.55 and fails: still
    // crawling, the driver snaps again at once instead of cutting
    assert!(after < 0.55 && after + 0.2 > 0.55);
    assert_eq!(run.count("still crawling at t ="), 1);
    assert!((run.times[crawl + 2] - (after + 0.2)).abs() < 1e-12, "{:?}", &run.times[crawl..]);
    assert_eq!(run.summary.snaps, 2);
    assert_eq!(run.times.last(), Some(&1.0));
}

/// Without continuation, a load-controlled increment that converges far off the path (ten
/// times what the last increment's rate predicts: Newton's iterations carried the body onto
/// another branch past a fold) is not committed: it is cut like one that failed, and the fold
/// is crossed by a snap. On the linear cantilever every committed state then lies on the path,
/// |u| proportional to t, where the jumped increment would be ten times off it.
#[test]
fn an_increment_that_lands_on_another_branch_is_cut_and_the_fold_crossed_by_a_snap() {
    let run = run_on_path(eighths(1e-3), Twist::LandPastFold);
    assert_eq!(run.summary.status, "completed", "{:?}", run.summary.message);
    assert!(run.count("jumped to another branch (moved too far)") >= 1, "{:?}", run.messages);
    assert!(run.summary.snaps >= 1 && run.times.iter().any(|&t| t > FOLD));
    let per_unit_time = run.norms.last().unwrap() / run.times.last().unwrap();
    for (t, norm) in run.times.iter().zip(&run.norms) {
        assert!((norm - t * per_unit_time).abs() <= 1e-9 * per_unit_time, "|u| = {norm} at t = {t}");
    }
    assert_eq!(run.times.last(), Some(&1.0));
}

/// A fold 1e-3 past the committed t = 0.5: the attempt over 1/8 stalls at 0.124, the one over
/// 1/32 at 0.03025; their secant places the fold 1e-3 ahead, short of the next attempt's 1/128,
/// so the driver snaps over 1/128 at once: two cuts there, where cutting on would take two more
/// failed attempts (1/128 and 1/512 overshoot the fold too) and then crawl towards it.
#[test]
fn two_stalled_attempts_that_place_a_fold_short_of_the_next_one_are_followed_by_a_snap_over_it() {
    let run = run_on_path(eighths(1e-9), Twist::StallPast(0.501));
    assert_eq!(run.summary.status, "completed", "{:?}", run.summary.message);
    assert_eq!(run.summary.snaps, 1, "{:?}", run.messages);
    assert_eq!(run.summary.cut_increments, 2, "{:?}", run.messages);
    assert_eq!(run.count("a fold 1.00e-3 from t = 0.500000"), 1, "{:?}", run.messages);
    let snap = run.times.iter().position(|&t| t > 0.5).expect("the fold is passed");
    assert_eq!(run.times[snap - 1], 0.5);
    assert_eq!(run.times[snap], 0.5 + 0.125 / 16.0, "the snap goes over the increment load control would try next");
    assert_eq!(run.times.last(), Some(&1.0));
}

/// A fold 0.02 past the committed t = 0.5: the secant of the attempts over 1/8 and 1/32 (floors
/// 0.105 and 0.01125) places it 0.02 ahead, beyond the next attempt's 1/128, so load control
/// cuts as before and that attempt converges short of the fold. Two commits on (t = 0.519531),
/// the attempts to 0.537109 and 0.523926 stall and place the fold 4.69e-4 ahead, now within
/// the next attempt's reach, and one snap passes it.
#[test]
fn a_fold_the_secant_places_beyond_the_next_attempt_leaves_load_control_cutting() {
    let run = run_on_path(eighths(1e-9), Twist::StallPast(0.52));
    assert_eq!(run.summary.status, "completed", "{:?}", run.summary.message);
    let after_half = run.times.iter().position(|&t| t > 0.5).expect("the run passes t = 0.5");
    assert_eq!(run.times[after_half], 0.5 + 0.125 / 16.0, "committed by load control: {:?}", run.times);
    assert_eq!(run.count("a fold 2.00e-2 from t = 0.500000"), 0, "{:?}", run.messages);
    assert!(run.times.iter().any(|&t| t > 0.52));
    assert_eq!(run.summary.snaps, 1, "{:?}", run.messages);
    assert_eq!(run.count("a fold 4.69e-4 from t = 0.519531"), 1, "{:?}", run.messages);
    assert_eq!(run.times.last(), Some(&1.0));
}

//! The path policy: what the driver does next after an attempt, as named rules over the facts
//! the driver gathers. The policy decides; the driver carries out (rolls back, cuts, starts a
//! crossing, snaps, commits) and reports. The policy knows nothing of the model, the solvers, the
//! output or the checkpoints: it reads [`FailureFacts`] and [`JumpFacts`], keeps the few counts
//! and flags its rules need ([`PathPolicy`], checkpointed with the driver), and returns a
//! [`Decision`].
//!
//! After a failed attempt the rules are asked in this order, and the first that fires decides
//! ([`PathPolicy::after_failure`]):
//! 1. [`Rule::CrossingCuts`]: a crossing (arc length, dissipation control) is under way: it
//!    cuts its own increment, and the path snaps where it cannot.
//! 2. [`Rule::UnbalancedStart`]: the initial state failed the residual test (an adhesive surface
//!    started inside its jump-in range) and the first attempt did not converge: the nearest
//!    equilibrium may lie across a snap no shorter increment reaches, so the path snaps at once.
//! 3. [`Rule::HandOver`]: with continuation, after `after_cuts` failed attempts in a row (and
//!    unless the crossing just handed back): the crossing takes over from the last converged
//!    increment.
//! 4. [`Rule::StillCrawling`]: after a crawl snap, until a load-controlled increment converges
//!    again: a failure snaps one initial increment ahead at once (a contact front crossing a
//!    3D mesh node by node folds at every node; cutting down to each fold costs more).
//! 5. [`Rule::FoldAhead`]: without continuation, two stalled attempts whose floors fall with
//!    their overshoot place a fold within the next cut's reach ([`fold_ahead`]): the path snaps
//!    over that next increment instead of cutting down to it.
//! 6. [`Rule::Cut`]: load control cuts its increment; below its minimum the path snaps.
//!
//! Snaps at the minimum increment (a control that cannot cut, [`PathPolicy::snap`]; an
//! unbalanced start): [`Rule::Stuck`]: after [`MAX_SNAPS_WITHOUT_PROGRESS`] snaps in a row at
//! the minimum increment, the next goes one initial increment ahead. Any snap: where it would
//! go no further than the minimum after that many, [`Rule::NoProgress`] stops the run with the
//! reason.
//!
//! Before an attempt ([`PathPolicy::before_attempt`]): [`Rule::Crawl`]: after [`CRAWL_COMMITS`]
//! committed load-controlled increments in a row each below [`CRAWL_FRACTION`] of the step's
//! maximum (sizes only cuts produce), the path creeps towards a fold it cannot pass: it snaps one
//! initial increment ahead.
//!
//! After a converged load-controlled attempt ([`jumped`]): [`Rule::Jump`]: an increment that
//! moved far more than the last one's rate predicts (or, with continuation, turned back) went
//! over a limit point onto another branch: it is rolled back and handled as a failure (or the
//! crossing starts).

use super::step::Incrementation;
use super::{AttemptFailure, Continuation};
use crate::nonlinear::IncrementFailure;
use serde::{Deserialize, Serialize};

/// A load-controlled increment whose displacement increment exceeds this multiple of the one
/// the previous increment's rate predicts counts as a jump over a limit point.
pub const JUMP_RATIO: f64 = 5.0;

/// Snaps in a row (no ordinary increment converging in between, none moving the load on by more
/// than the minimum increment) after which the next snap goes one initial increment ahead (or
/// the run stops, where that is no further than the minimum increment).
pub const MAX_SNAPS_WITHOUT_PROGRESS: usize = 3;

/// A crawl: this many committed load-controlled increments in a row, each below
/// [`CRAWL_FRACTION`] of the step's maximum increment (see [`Rule::Crawl`]).
pub const CRAWL_COMMITS: usize = 6;
pub const CRAWL_FRACTION: f64 = 1e-2;

/// The rules, by name (for the driver's messages and the tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    CrossingCuts,
    UnbalancedStart,
    HandOver,
    StillCrawling,
    FoldAhead,
    Cut,
    Crawl,
    Stuck,
    NoProgress,
    Jump,
}

/// What the driver does next.
#[derive(Debug, Clone, PartialEq)]
pub enum Decision {
    /// The crossing under way cuts its increment (or, where it cannot, the path snaps: ask
    /// [`PathPolicy::snap`] with its reason).
    CutCrossing,
    /// The crossing starts from the last converged increment and hands back past `resume_after`.
    StartCrossing { resume_after: f64 },
    /// Load control cuts its increment (or, where it cannot, the path snaps: ask
    /// [`PathPolicy::snap`] with its reason).
    CutLoad,
    /// Snap to the stable state `dt` past the committed time; `crawl`: a snap past a crawl,
    /// after which the path counts as still crawling.
    Snap { dt: f64, crawl: bool, reason: String, rule: Rule },
    /// The run cannot go on.
    Stop { reason: String },
}

/// What the rules after a failed attempt read.
#[derive(Debug, Clone, Copy)]
pub struct FailureFacts<'a> {
    pub failure: &'a AttemptFailure,
    /// Pseudo-time of the committed state.
    pub t: f64,
    /// The failed load-controlled attempt's increment (target - t).
    pub attempted: f64,
    /// A crossing was under way.
    pub crossing: bool,
    pub continuation: Option<Continuation>,
    /// A crossing could start: the last converged increment moved forward.
    pub crossing_can_start: bool,
    /// Where a crossing started now hands back (the first target load control failed at).
    pub resume_after: f64,
    pub incrementation: &'a Incrementation,
    /// The case's force unit, for the reasons ("" when not stated).
    pub force_unit: &'a str,
}

/// The policy's own state: the counts and flags its rules read, kept between attempts.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct PathPolicy {
    /// Set when a crossing had to hand back to load control; cleared by the next commit.
    arc_blocked: bool,
    /// Failed attempts since the last commit.
    cuts_since_commit: usize,
    /// Snaps since the last ordinary increment.
    snaps_in_a_row: usize,
    /// Committed load-controlled increments in a row below the crawl size ([`Rule::Crawl`]).
    small_commits_in_a_row: usize,
    /// Set by a crawl snap; cleared when a load-controlled (or crossing) increment converges,
    /// when the load reaches a breakpoint and at a step's start ([`Rule::StillCrawling`]).
    crawling: bool,
    /// The last load-controlled attempt that stagnated, while the committed state is short of
    /// its target: that target and the lowest residual it reached ([`Rule::FoldAhead`]).
    stagnated_attempt: Option<(f64, f64)>,
    /// Until the first commit: the initial state's residual norm and the solver's residual
    /// test, when that fails ([`Rule::UnbalancedStart`]). Not checkpointed: a checkpoint
    /// follows a commit.
    #[serde(skip)]
    unbalanced_start: Option<(f64, f64)>,
}

impl PathPolicy {
    /// Failed attempts since the last commit.
    pub fn cuts_since_commit(&self) -> usize {
        self.cuts_since_commit
    }

    /// Whether a crossing had to hand back since the last commit.
    pub fn arc_blocked(&self) -> bool {
        self.arc_blocked
    }

    /// The initial state's residual norm and the solver's residual test, where the residual
    /// fails the test (None: the start is balanced, or the run resumed past it).
    pub fn unbalanced_start(&mut self, imbalance: Option<(f64, f64)>) {
        self.unbalanced_start = imbalance;
    }

    /// A step starts (not a resumed one).
    pub fn step_started(&mut self) {
        self.crawling = false;
        self.stagnated_attempt = None;
    }

    /// The crossing could not go on inside its window and handed back.
    pub fn crossing_handed_back(&mut self) {
        self.arc_blocked = true;
    }

    /// A failed attempt was rolled back (a failure, or a jump handed to a crossing).
    pub fn attempt_failed(&mut self) {
        self.cuts_since_commit += 1;
    }

    /// The state saved for a run that failed: resumed with other settings, it goes on as from a
    /// step's start.
    pub fn for_failed_run(&self) -> Self {
        Self { cuts_since_commit: 0, snaps_in_a_row: 0, stagnated_attempt: None, ..self.clone() }
    }

    /// [`Rule::Crawl`], before an attempt by load control: the snap past the crawl, if due.
    pub fn before_attempt(
        &mut self,
        crossing: bool,
        t: f64,
        dt: f64,
        incrementation: &Incrementation,
    ) -> Option<Decision> {
        if crossing || self.small_commits_in_a_row < CRAWL_COMMITS {
            return None;
        }
        self.small_commits_in_a_row = 0;
        let reason = format!("crawling at t = {t:.6} (dt = {dt:.2e})");
        Some(self.snap_by(incrementation.initial, true, reason, Rule::Crawl, t, incrementation))
    }

    /// After a failed attempt (rolled back, counted by [`Self::attempt_failed`]): the first rule
    /// that fires, in the order of the module documentation.
    pub fn after_failure(&mut self, facts: &FailureFacts<'_>) -> Decision {
        let FailureFacts { failure, t, incrementation, .. } = *facts;
        if facts.crossing {
            return Decision::CutCrossing;
        }
        if failure.is_no_convergence()
            && let Some((residual, test)) = self.unbalanced_start.take()
        {
            let force = if facts.force_unit.is_empty() { String::new() } else { format!(" {}", facts.force_unit) };
            let reason = format!(
                "the initial state is out of equilibrium (residual {residual:.3e}{force} against the test's \
                 {test:.3e}: e.g. an adhesive surface started inside its jump-in range), and the first increment \
                 found no equilibrium near it ({failure})"
            );
            return self.snap_with(reason, Rule::UnbalancedStart, t, incrementation);
        }
        if let Some(continuation) = facts.continuation
            && self.cuts_since_commit >= continuation.after_cuts
            && !self.arc_blocked
            && facts.crossing_can_start
        {
            return Decision::StartCrossing { resume_after: facts.resume_after };
        }
        if self.crawling {
            let reason = format!("still crawling at t = {t:.6} ({failure})");
            return self.snap_by(incrementation.initial, true, reason, Rule::StillCrawling, t, incrementation);
        }
        if let Some((dt, reason)) = self.fold_within_reach(facts) {
            return self.snap_by(dt, false, reason, Rule::FoldAhead, t, incrementation);
        }
        Decision::CutLoad
    }

    /// [`Rule::FoldAhead`]: whether the stalled attempt over `facts.attempted` and the last one
    /// that stalled place a fold within the next attempt's reach (see [`fold_ahead`]): then that
    /// next increment, to snap over, and the reason. Remembers a stalled attempt.
    fn fold_within_reach(&mut self, facts: &FailureFacts<'_>) -> Option<(f64, String)> {
        let Some(IncrementFailure::Stagnated { residual, earlier, .. }) = facts.failure.solver() else { return None };
        if facts.continuation.is_some() {
            // the crossing takes the folds over (and locates them)
            return None;
        }
        let (t, attempted) = (facts.t, facts.attempted);
        let later = (t + attempted, residual.min(*earlier));
        let before = self.stagnated_attempt.replace(later)?;
        let next = attempted * facts.incrementation.cut_factor;
        let fold = fold_ahead(t, before, later).filter(|d| d.abs() < next && next >= facts.incrementation.minimum)?;
        let reason = format!(
            "a fold {fold:.2e} from t = {t:.6}: two attempts stalled at residuals falling with their \
             overshoot ({:.3e} at t = {:.6}, {:.3e} at {:.6})",
            before.1, before.0, later.1, later.0
        );
        Some((next, reason))
    }

    /// A control could not cut any further (`reason`), or another rule asks for a snap at the
    /// minimum increment: [`Rule::Stuck`] moves it one initial increment ahead after
    /// [`MAX_SNAPS_WITHOUT_PROGRESS`] snaps in a row.
    pub fn snap(&mut self, reason: String, t: f64, incrementation: &Incrementation) -> Decision {
        self.snap_with(reason, Rule::Cut, t, incrementation)
    }

    fn snap_with(&mut self, reason: String, rule: Rule, t: f64, incrementation: &Incrementation) -> Decision {
        let stuck = self.snaps_in_a_row >= MAX_SNAPS_WITHOUT_PROGRESS;
        let (dt, rule) = if stuck { (incrementation.initial, Rule::Stuck) } else { (incrementation.minimum, rule) };
        self.snap_by(dt, false, reason, rule, t, incrementation)
    }

    /// A snap `dt` ahead, or [`Rule::NoProgress`]: the stop where snaps in a row found no path
    /// onward and this one would not move the load on either.
    fn snap_by(&mut self, dt: f64, crawl: bool, reason: String, rule: Rule, t: f64, inc: &Incrementation) -> Decision {
        if self.snaps_in_a_row >= MAX_SNAPS_WITHOUT_PROGRESS && dt <= inc.minimum {
            self.crawling &= !crawl;
            return Decision::Stop {
                reason: format!(
                    "{reason}; {MAX_SNAPS_WITHOUT_PROGRESS} snaps in a row found no path onward from t = {t:.6}"
                ),
            };
        }
        Decision::Snap { dt, crawl, reason, rule }
    }

    /// A snap `dt` ahead settled (before its state is committed by [`Self::committed`]): one
    /// past the minimum increment moved the load on.
    pub fn snapped(&mut self, dt: f64, incrementation: &Incrementation) {
        self.snaps_in_a_row = if dt > incrementation.minimum { 0 } else { self.snaps_in_a_row + 1 };
    }

    /// After a crawl snap was committed (`went_on`: the run goes on in the step) at a state
    /// that is (`at_breakpoint`) or is not on a breakpoint.
    pub fn after_crawl_snap(&mut self, went_on: bool, at_breakpoint: bool) {
        self.crawling = went_on && !at_breakpoint;
    }

    /// An increment was committed at `t`: a snap's (`settled`) or an ordinary one, whose size
    /// (`small`) counts towards a crawl when load control (`by_load_control`) solved it.
    pub fn committed(&mut self, t: f64, settled: bool, by_load_control: bool, small: bool) {
        if !settled {
            self.snaps_in_a_row = 0;
            self.crawling = false;
            self.small_commits_in_a_row = if by_load_control && small { self.small_commits_in_a_row + 1 } else { 0 };
        }
        self.arc_blocked = false;
        self.unbalanced_start = None;
        self.cuts_since_commit = 0;
        if settled || self.stagnated_attempt.is_some_and(|(target, _)| target <= t) {
            self.stagnated_attempt = None;
        }
    }
}

/// A fold located from two stalled attempts: past a fold at load t_f no equilibrium is near,
/// and the lowest residual an attempt to the target T stalls at grows with its overshoot,
/// r ~ c (T - t_f). Two load-controlled attempts that stagnate, to T_1 and a nearer T_2 with
/// floors r_1 > r_2 (from the same committed state, or from two on the way there: a crawl's
/// converged increments creep towards the fold between its failures), place the fold by the
/// secant t_f = (r_1 T_2 - r_2 T_1) / (r_1 - r_2). Where it lies within the next attempt's
/// reach of the committed state t, |t_f - t| < cut (T_2 - t), that attempt overshoots the fold
/// too, and so would every shorter one down to it: the driver then snaps at once over that next
/// increment instead of cutting on towards its minimum (six to nine failed solves per fold in
/// the w = 6 plastic 3D quarter, where the contact front folds at each ring of surface nodes).
/// A fold placed farther ahead leaves load control to cut as before, and so does one placed
/// farther behind (a floor that fell no faster than the overshoot: not yet the linear regime).
/// The attempt remembered is forgotten when the committed state passes its target (it was no
/// fold), at a snap and at a step's start. Only without continuation: with it, the crossing
/// follows the path round the fold (and locates it) once load control has failed
/// `after_cuts` times. Returns t_f - t.
pub fn fold_ahead(t: f64, earlier: (f64, f64), later: (f64, f64)) -> Option<f64> {
    let ((target_1, r_1), (target_2, r_2)) = (earlier, later);
    (target_2 < target_1 && r_2 < r_1).then(|| (r_1 * target_2 - r_2 * target_1) / (r_1 - r_2) - t)
}

/// What [`jumped`] reads of a converged load-controlled increment.
#[derive(Debug, Clone, Copy)]
pub struct JumpFacts {
    /// ||du|| of this increment and of the last converged one.
    pub moved: f64,
    pub moved_before: f64,
    /// The increment's and the last one's pseudo-time increments (this one positive).
    pub dt: f64,
    pub dt_before: f64,
    /// du . du_before < 0.
    pub turned: bool,
    /// Round-off in a state that no longer moves: the solver's displacement test times the
    /// largest displacement committed.
    pub noise: f64,
    pub continuation: bool,
    /// The increment started on a breakpoint (where the load's rate may change).
    pub from_breakpoint: bool,
    /// A crossing handed back since the last commit.
    pub arc_blocked: bool,
}

/// [`Rule::Jump`]: whether a converged load-controlled increment jumped to another branch, and
/// how: its displacements moved more than [`JUMP_RATIO`] times what the last increment's rate
/// predicts ("moved too far"), or they turned back against it although the load did not
/// reverse ("turned back"): a limit point passed inside one increment, after which Newton's
/// iterations carried the body onto another branch. Without continuation only the first counts,
/// and not for an increment that starts on a breakpoint: a body's motion also turns back on a
/// smooth path (where an adhesive pull gives way to contact pressure), and a snap is costlier
/// than the crossing's step. After a crossing handed back, load control goes on: nothing counts.
pub fn jumped(f: &JumpFacts) -> Option<&'static str> {
    if (f.continuation && f.arc_blocked) || !(f.dt_before > 0.0 && f.dt > 0.0) {
        return None;
    }
    let predicted = f.moved_before * f.dt / f.dt_before;
    let too_far = (f.continuation || !f.from_breakpoint) && predicted > 0.0 && f.moved > JUMP_RATIO * predicted;
    let turned_back = f.continuation && f.moved_before > f.noise && f.turned && !f.from_breakpoint;
    if !(f.moved > f.noise && (too_far || turned_back)) {
        return None;
    }
    Some(if too_far { "moved too far" } else { "turned back" })
}

#[cfg(test)]
mod tests;

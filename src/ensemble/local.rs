//! Members on one machine: `concurrent` at a time, each with a rayon pool of `threads`, taken in
//! member order from a shared counter (so a slow member does not hold up the others).

use super::member::{MemberContext, MemberOutcome, run_member};
use super::plan::Member;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How the cores of one machine (or one MPI rank) are shared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ThreadBudget {
    /// Members run at once.
    pub concurrent: usize,
    /// Threads of each member.
    pub threads: usize,
}

impl ThreadBudget {
    /// `concurrent` x `threads` <= `cores`, chosen automatically where 0 is given: as many
    /// members at once as there are cores (at most `members`), and the cores shared among them.
    pub fn choose(cores: usize, members: usize, concurrent: usize, threads: usize) -> Self {
        let cores = cores.max(1);
        let concurrent = match (concurrent, threads) {
            (0, 0) => cores.min(members.max(1)),
            (0, t) => (cores / t).clamp(1, members.max(1)),
            (c, _) => c,
        };
        let threads = if threads == 0 { (cores / concurrent).max(1) } else { threads };
        Self { concurrent, threads }
    }
}

/// The cores this process may use.
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs `members` with `budget`; `report` is called as each finishes (from its worker thread).
/// After a Ctrl-C no further member starts; the members in flight stop after their increment.
pub fn run_members(
    members: &[Member],
    context: &MemberContext,
    budget: ThreadBudget,
    report: &(dyn Fn(&MemberOutcome) + Sync),
) -> Vec<MemberOutcome> {
    let jobs: Vec<(&MemberContext, &Member)> = members.iter().map(|m| (context, m)).collect();
    let mut outcomes: Vec<MemberOutcome> = run_jobs(&jobs, budget, report).into_iter().flatten().collect();
    outcomes.sort_by_key(|o| o.index);
    outcomes
}

/// Runs `jobs` (each a member of its own context: runs of different cases, as a fit makes) with
/// `budget`; the outcomes come back in the order of `jobs`, None for a job that never started:
/// after a Ctrl-C (any job's context's flag) no further job starts.
pub fn run_jobs(
    jobs: &[(&MemberContext, &Member)],
    budget: ThreadBudget,
    report: &(dyn Fn(&MemberOutcome) + Sync),
) -> Vec<Option<MemberOutcome>> {
    let next = AtomicUsize::new(0);
    let outcomes = Mutex::new(Vec::new());
    let interrupted = || jobs.iter().any(|(c, _)| c.interrupt.as_ref().is_some_and(|f| f.load(Ordering::SeqCst)));
    std::thread::scope(|scope| {
        for _ in 0..budget.concurrent.min(jobs.len()) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    if i >= jobs.len() || interrupted() {
                        break;
                    }
                    let (context, member) = jobs[i];
                    let outcome = run_member(context, member, budget.threads);
                    report(&outcome);
                    outcomes.lock().expect("outcome list").push((i, outcome));
                }
            });
        }
    });
    let mut ordered: Vec<Option<MemberOutcome>> = vec![None; jobs.len()];
    for (i, o) in outcomes.into_inner().expect("outcome list") {
        ordered[i] = Some(o);
    }
    ordered
}

#[cfg(test)]
mod tests {
    use super::ThreadBudget;

    #[test]
    fn the_budget_never_exceeds_the_cores_when_chosen() {
        for cores in 1..=16 {
            for pending in 1..=20 {
                let b = ThreadBudget::choose(cores, pending, 0, 0);
                assert!(b.concurrent * b.threads <= cores, "{cores} cores, {pending} pending: {b:?}");
                assert!(b.concurrent <= pending && b.concurrent >= 1);
            }
        }
        assert_eq!(ThreadBudget::choose(8, 2, 0, 0), ThreadBudget { concurrent: 2, threads: 4 });
        assert_eq!(ThreadBudget::choose(8, 10, 0, 2), ThreadBudget { concurrent: 4, threads: 2 });
        assert_eq!(ThreadBudget::choose(2, 10, 1, 0), ThreadBudget { concurrent: 1, threads: 2 });
    }
}

//! A fit's runs over MPI ranks (`mpirun -n P stiction fit FIT.toml`, cargo feature `mpi`).
//!
//! Rank 0 runs the optimizer. Its batches of runs (a trial point, a Jacobian's steps) go into a
//! queue that every rank takes jobs from: the other ranks ask rank 0 for a job (tag
//! [`REQUEST`], carrying the outcome of their previous job, if any) and get one, "wait" (no
//! batch is pending) or "stop" (the fit is over) back (tag [`ASSIGN`]). Rank 0 answers from a
//! dispatcher thread, the only thread that calls MPI there, and computes jobs from the same
//! queue on its main thread. A job names the case file, its `--set` assignments and the run's
//! folder, which all ranks share; its outcome comes back as `member.json` does. Every run gets
//! the same number of threads, so the fit is the one a single machine makes with that many
//! threads per run.

use super::evaluate::Runs;
use super::{FitOptions, FitReport};
use crate::ensemble::local::available_cores;
use crate::ensemble::member::{MemberContext, MemberOutcome, run_member};
use crate::ensemble::plan::Member;
use crate::error::{Result, StictionError};
use mpi::Threading;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// Tag of a rank's request for a job (payload: its previous job's id and outcome as JSON, or
/// empty).
pub const REQUEST: i32 = 11;
/// Tag of rank 0's answer (payload: a [`Reply`] as JSON).
pub const ASSIGN: i32 = 12;

/// How long a waiting rank sleeps between polls (MPI's blocking calls would spin a core).
const POLL: std::time::Duration = std::time::Duration::from_millis(20);

/// One run, as it crosses the network.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Job {
    id: u64,
    case_path: PathBuf,
    sets: Vec<String>,
    root: PathBuf,
    member: Member,
    threads: usize,
}

#[derive(Debug, Serialize, Deserialize)]
enum Reply {
    Run(Job),
    Wait,
    Stop,
}

impl Job {
    fn run(&self, interrupt: Option<Arc<AtomicBool>>) -> MemberOutcome {
        let context = MemberContext {
            case_path: self.case_path.clone(),
            sets: self.sets.clone(),
            root: self.root.clone(),
            interrupt,
        };
        run_member(&context, &self.member, self.threads)
    }
}

/// The fit's runs on every rank (rank 0's side).
struct MpiRuns {
    queue: Mutex<VecDeque<Job>>,
    results: Mutex<HashMap<u64, MemberOutcome>>,
    next_id: AtomicU64,
    /// Set when the fit is over: the dispatcher then stops every rank.
    finished: AtomicBool,
    threads: usize,
    interrupt: Option<Arc<AtomicBool>>,
}

impl MpiRuns {
    fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|f| f.load(Ordering::SeqCst))
    }

    fn take(&self) -> Option<Job> {
        if self.interrupted() {
            return None;
        }
        self.queue.lock().expect("job queue").pop_front()
    }
}

impl Runs for MpiRuns {
    fn run(
        &self,
        jobs: &[(&MemberContext, &Member)],
        report: &(dyn Fn(&MemberOutcome) + Sync),
    ) -> Vec<Option<MemberOutcome>> {
        let ids: Vec<u64> = jobs
            .iter()
            .map(|(context, member)| {
                let id = self.next_id.fetch_add(1, Ordering::SeqCst);
                let job = Job {
                    id,
                    case_path: context.case_path.clone(),
                    sets: context.sets.clone(),
                    root: context.root.clone(),
                    member: (*member).clone(),
                    threads: self.threads,
                };
                self.queue.lock().expect("job queue").push_back(job);
                id
            })
            .collect();
        // rank 0 computes from the same queue
        while let Some(job) = self.take() {
            let outcome = job.run(self.interrupt.clone());
            self.results.lock().expect("results").insert(job.id, outcome);
        }
        // wait for the jobs other ranks took; after Ctrl-C, those no rank took never start
        let mut never_started: Vec<u64> = Vec::new();
        loop {
            let mut queue = self.queue.lock().expect("job queue");
            if self.interrupted() {
                queue.retain(|j| {
                    let mine = ids.contains(&j.id);
                    if mine {
                        never_started.push(j.id);
                    }
                    !mine
                });
            }
            let queued = queue.iter().any(|j| ids.contains(&j.id));
            drop(queue);
            let results = self.results.lock().expect("results");
            if !queued && ids.iter().all(|id| results.contains_key(id) || never_started.contains(id)) {
                break;
            }
            drop(results);
            std::thread::sleep(POLL);
        }
        let mut results = self.results.lock().expect("results");
        ids.iter()
            .map(|id| {
                let outcome = results.remove(id);
                if let Some(o) = &outcome {
                    report(o);
                }
                outcome
            })
            .collect()
    }
}

/// Rank 0's dispatcher: answers the other ranks' requests until the fit is over and every rank
/// has been told to stop.
fn dispatch(runs: &MpiRuns, size: i32) {
    let world = SimpleCommunicator::world();
    let mut active = size - 1;
    while active > 0 {
        let Some(probed) = world.any_process().immediate_matched_probe_with_tag(REQUEST) else {
            std::thread::sleep(POLL);
            continue;
        };
        let (bytes, status) = probed.matched_receive_vec::<u8>();
        if let Ok((id, outcome)) = serde_json::from_slice::<(u64, MemberOutcome)>(&bytes) {
            runs.results.lock().expect("results").insert(id, outcome);
        }
        let reply = match runs.take() {
            Some(job) => Reply::Run(job),
            None if runs.finished.load(Ordering::SeqCst) => {
                active -= 1;
                Reply::Stop
            }
            None => Reply::Wait,
        };
        let bytes = serde_json::to_vec(&reply).expect("reply serializes");
        world.process_at_rank(status.source_rank()).send_with_tag(&bytes[..], ASSIGN);
    }
}

/// Another rank: runs the jobs rank 0 gives it until told to stop.
fn serve(world: &SimpleCommunicator, interrupt: Option<Arc<AtomicBool>>) {
    let root = world.process_at_rank(0);
    let mut last: Vec<u8> = Vec::new();
    loop {
        root.send_with_tag(&last[..], REQUEST);
        let (bytes, _) = root.receive_vec_with_tag::<u8>(ASSIGN);
        match serde_json::from_slice::<Reply>(&bytes) {
            Ok(Reply::Run(job)) => {
                let outcome = job.run(interrupt.clone());
                last = serde_json::to_vec(&(job.id, outcome)).expect("outcome serializes");
            }
            Ok(Reply::Wait) => {
                last.clear();
                std::thread::sleep(POLL);
            }
            Ok(Reply::Stop) | Err(_) => return,
        }
    }
}

/// Runs the fit over the ranks of MPI_COMM_WORLD. Rank 0 returns the report; the other ranks
/// return None once the fit is over.
pub fn run_fit_mpi(path: &Path, options: &FitOptions) -> Result<Option<FitReport>> {
    let (universe, threading) = mpi::initialize_with_threading(Threading::Serialized).ok_or_else(|| {
        StictionError::Fit { path: path.to_path_buf(), message: "MPI was already initialized".into() }
    })?;
    let world = universe.world();
    let (rank, size) = (world.rank(), world.size());
    // collective: every rank takes part
    let on_node = world.split_shared(rank).size().max(1) as usize;
    if rank != 0 {
        serve(&world, options.interrupt.clone());
        return Ok(None);
    }
    if !matches!(threading, Threading::Serialized | Threading::Multiple) {
        return Err(StictionError::Fit {
            path: path.to_path_buf(),
            message: "the MPI library does not allow a dispatcher thread (MPI_THREAD_SERIALIZED)".into(),
        });
    }
    // every rank's runs get the threads of a rank on this node (or threads_per_run)
    let spec = super::spec::load(path);
    let threads = match &spec {
        Ok(s) if s.optimizer.threads_per_run > 0 => s.optimizer.threads_per_run,
        _ => (available_cores() / on_node).max(1),
    };
    let runs = MpiRuns {
        queue: Mutex::new(VecDeque::new()),
        results: Mutex::new(HashMap::new()),
        next_id: AtomicU64::new(0),
        finished: AtomicBool::new(false),
        threads,
        interrupt: options.interrupt.clone(),
    };
    if !options.quiet {
        eprintln!("fit over {size} MPI ranks, {threads} thread{} per run", if threads == 1 { "" } else { "s" });
    }
    let report = std::thread::scope(|scope| {
        scope.spawn(|| dispatch(&runs, size));
        let report = spec.and_then(|spec| super::fit_with(spec, options, &runs));
        runs.finished.store(true, Ordering::SeqCst);
        report
    });
    report.map(Some)
}

//! Members over MPI ranks (`mpirun -n P stiction ensemble CASE.toml`, cargo feature `mpi`).
//!
//! Dynamic load balancing by a work queue on rank 0: each other rank asks rank 0 for a member
//! (a message tagged [`REQUEST`] that carries the outcome of its previous member, if any), and
//! rank 0 answers with the next member's index or -1 when none is left (tag [`ASSIGN`]). Rank 0
//! answers from a dispatcher thread and runs members from the same queue on its main thread, so
//! every rank computes. Every rank plans the members itself from the same case and overrides
//! (the plan is deterministic), so only indices cross the network; the members' files go to the
//! shared output folder, and rank 0 aggregates them from there once every rank is done.

use super::member::{MemberOutcome, run_member};
use super::{EnsembleOptions, Prepared, announce, describe, estimate, finish, local, prepare};
use crate::ensemble::aggregate::EnsembleAggregate;
use crate::error::{Result, StictionError};
use mpi::Threading;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::collections::VecDeque;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::Ordering;

/// Tag of a worker's request for work (payload: its previous outcome as JSON, or empty).
pub const REQUEST: i32 = 1;
/// Tag of rank 0's answer (payload: a member index, or -1 for "stop").
pub const ASSIGN: i32 = 2;

/// Whether an MPI launcher (mpirun/mpiexec of OpenMPI or MPICH, Slurm's srun) started this
/// process.
pub fn launched_under_mpi() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"].iter().any(|v| std::env::var_os(v).is_some())
}

/// Runs the ensemble over the ranks of MPI_COMM_WORLD. Rank 0 returns the aggregate; the other
/// ranks return None once rank 0 has no more work for them.
pub fn run_ensemble_mpi(path: &Path, sets: &[String], options: &EnsembleOptions) -> Result<Option<EnsembleAggregate>> {
    let (universe, threading) = mpi::initialize_with_threading(Threading::Serialized).ok_or_else(|| {
        StictionError::Output { path: path.to_path_buf(), message: "MPI was already initialized".into() }
    })?;
    let world = universe.world();
    let (rank, size) = (world.rank(), world.size());
    // every rank plans; only rank 0 checks and writes the folder
    let prepared = prepare(path, sets, options, rank == 0);
    let ok_here = i32::from(prepared.is_ok());
    let mut ok_everywhere = 0i32;
    world.all_reduce_into(&ok_here, &mut ok_everywhere, SystemOperation::min());
    let prepared = match (prepared, ok_everywhere == 1) {
        (Ok(p), true) => p,
        (Err(e), _) => return if rank == 0 { Err(e) } else { Ok(None) },
        (Ok(_), false) => return Ok(None), // rank 0 reports the error
    };
    let threads = threads_per_rank(&world, &prepared);
    if rank != 0 {
        work(&world, &prepared, threads);
        idle_barrier(&world);
        return Ok(None);
    }
    let rank0_computes = matches!(threading, Threading::Serialized | Threading::Multiple);
    let how = format!("{size} MPI ranks, {threads} threads per member");
    announce(&prepared, &how);
    let outcomes = dispatch(&prepared, size, threads, rank0_computes, options.quiet);
    idle_barrier(&world);
    finish(&prepared, outcomes).map(Some)
}

/// How long a rank waiting for messages sleeps between polls. MPI's blocking calls spin, which
/// would take a core from the members computing on the same node.
const POLL: std::time::Duration = std::time::Duration::from_millis(20);

/// A barrier that sleeps while it waits (so ranks done early do not spin until MPI_Finalize).
fn idle_barrier(world: &SimpleCommunicator) {
    let mut request = world.immediate_barrier();
    loop {
        match request.test() {
            Ok(_) => return,
            Err(pending) => request = pending,
        }
        std::thread::sleep(POLL);
    }
}

/// Threads per member on this rank: the option or the case's `threads_per_member`, else the
/// node's cores shared among the ranks on the node.
fn threads_per_rank(world: &SimpleCommunicator, prepared: &Prepared) -> usize {
    if prepared.threads_per_member > 0 {
        return prepared.threads_per_member;
    }
    let on_node = world.split_shared(world.rank()).size().max(1) as usize;
    (local::available_cores() / on_node).max(1)
}

/// A worker rank: asks for members until told to stop, reporting each outcome with the next
/// request.
fn work(world: &SimpleCommunicator, prepared: &Prepared, threads: usize) {
    let root = world.process_at_rank(0);
    let mut last: Vec<u8> = Vec::new();
    loop {
        root.send_with_tag(&last[..], REQUEST);
        let (index, _) = root.receive_with_tag::<i64>(ASSIGN);
        let Some(member) = usize::try_from(index).ok().and_then(|i| prepared.members.get(i)) else {
            break;
        };
        let outcome = run_member(&prepared.context, member, threads);
        last = serde_json::to_vec(&outcome).expect("outcome serializes");
    }
}

/// Rank 0: serves the other ranks from a dispatcher thread (the only thread that calls MPI
/// meanwhile) and, when MPI allows threads, runs members itself from the same queue.
fn dispatch(prepared: &Prepared, size: i32, threads: usize, rank0_computes: bool, quiet: bool) -> Vec<MemberOutcome> {
    let queue = Mutex::new(prepared.todo.iter().cloned().collect::<VecDeque<_>>());
    let outcomes = Mutex::new(Vec::new());
    let interrupted = || prepared.context.interrupt.as_ref().is_some_and(|f| f.load(Ordering::SeqCst));
    let next = || if interrupted() { None } else { queue.lock().expect("queue").pop_front() };
    // the ranks running members at once (rank 0 among them when it computes)
    let concurrent = (size as usize - 1 + usize::from(rank0_computes)).max(1);
    let record = |o: MemberOutcome| {
        let mut outcomes = outcomes.lock().expect("outcomes");
        let (done, total) = (outcomes.len() + 1, prepared.todo.len());
        if !quiet || !o.completed() {
            eprintln!("{}", describe(&prepared.root, &o, done, total));
        }
        // printed even when quiet, as the local runner does, after the first member to complete
        if o.completed() && done < total && !outcomes.iter().any(MemberOutcome::completed) {
            if let Some(line) = estimate(&prepared.root, &o, total - done, concurrent) {
                eprintln!("{line}");
            }
        }
        outcomes.push(o);
    };
    std::thread::scope(|scope| {
        scope.spawn(|| {
            let world = SimpleCommunicator::world();
            let mut active = size - 1;
            while active > 0 {
                let Some(probed) = world.any_process().immediate_matched_probe_with_tag(REQUEST) else {
                    std::thread::sleep(POLL);
                    continue;
                };
                let (bytes, status) = probed.matched_receive_vec::<u8>();
                if let Ok(o) = serde_json::from_slice::<MemberOutcome>(&bytes) {
                    record(o);
                }
                let index = next().map_or(-1i64, |m| m.index as i64);
                world.process_at_rank(status.source_rank()).send_with_tag(&index, ASSIGN);
                if index < 0 {
                    active -= 1;
                }
            }
        });
        if rank0_computes {
            while let Some(member) = next() {
                record(run_member(&prepared.context, &member, threads));
            }
        }
    });
    let mut outcomes = outcomes.into_inner().expect("outcomes");
    outcomes.sort_by_key(|o| o.index);
    outcomes
}

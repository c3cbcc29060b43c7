//! `solver.threads` sets the threads of a run's assembly and factorization, whatever ran
//! before it in the process. The rough cases' build factorizes the body's elastic stiffness
//! for the footprint correction on rayon's global pool, which that first use sizes to all
//! cores; a run used to size the global pool itself at its start, which rayon allows only
//! once, so on these cases `solver.threads = 1` was silently ignored (the quick case's
//! history.csv was byte for byte the same with 1 thread as with all). A run now
//! gets a pool of its own, and summary.json says how many threads it had.

use stiction_tests::run_case;

const QUICK: &str = "cases/ru-rough-sphere/rough-w6-quick.toml";

/// The loading step's first five increments and one of unloading.
const SHORT: [&str; 3] = ["output.vtk=false", "steps.0.end_time=0.1", "steps.1.end_time=0.11"];

#[test]
fn solver_threads_sizes_the_run_even_after_its_build_used_every_core() {
    let available = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut sets = SHORT.to_vec();
    sets.push("solver.threads=1");
    let (_, one) = run_case(QUICK, &sets, "solver-threads-1");
    assert_eq!(one.status, "completed", "{:?}", one.message);
    assert_eq!(one.threads, 1, "solver.threads = 1 was not applied");
    let (_, all) = run_case(QUICK, &SHORT, "solver-threads-0");
    assert_eq!(all.threads, available, "solver.threads = 0 must use every core");
    let (f1, f0) = (one.interfaces[0].max_force, all.interfaces[0].max_force);
    assert!((f1 - f0).abs() <= 1e-9 * f0.abs(), "the thread count changed the answer: {f1} vs {f0}");
}

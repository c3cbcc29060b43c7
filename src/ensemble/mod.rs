//! Ensembles (`stiction ensemble`): N realizations of a case, each a whole run in
//! `<out>/member-NNN/`, and their aggregate (`ensemble.json`, `ensemble.csv`, the mean curves
//! with confidence bands and the convergence figure).
//!
//! - [`plan`]: the members and their varied values;
//! - [`member`]: one member's run, and whether an earlier invocation completed it (resume);
//! - [`local`]: members run concurrently on one machine under a thread budget;
//! - [`mpi`] (cargo feature `mpi`): members spread over MPI ranks with dynamic load balancing;
//! - [`statistics`], [`curves`], [`aggregate`], [`plots`]: the aggregate.
//!
//! Every member is validated before any runs, so a bad varied value is an input error (exit 2)
//! rather than a failed member. A member that fails later is reported and excluded; running the
//! same command again resumes, skipping the members whose summary.json says "completed" and
//! going on with a member that was stopped (Ctrl-C) from its checkpoint (`--resume`).

pub mod aggregate;
pub mod curves;
pub mod local;
pub mod member;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod plan;
pub mod plots;
pub mod statistics;

use crate::error::{Result, StictionError};
use aggregate::EnsembleAggregate;
use member::{MemberContext, MemberOutcome};
use plan::Member;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use stiction_core::output::write_atomically;

/// The file that marks a folder as an ensemble's (written before any member runs).
pub const PLAN_FILE: &str = "ensemble-plan.json";

/// Options of `stiction ensemble` beyond the case file.
#[derive(Debug, Clone, Default)]
pub struct EnsembleOptions {
    /// Output folder (default: the case's output.directory, else out/<name>).
    pub out: Option<PathBuf>,
    /// Threads per member and members at once (override the case's `[ensemble]`; 0 = auto).
    pub threads_per_member: Option<usize>,
    pub concurrent_members: Option<usize>,
    /// Set by Ctrl-C: no member starts after it, those in flight stop after their increment.
    pub interrupt: Option<Arc<AtomicBool>>,
    /// No line per finished member.
    pub quiet: bool,
}

/// An ensemble ready to run: its members, those an earlier invocation completed, and the rest.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub name: String,
    /// The case's (length, force) units, empty when it states none.
    pub units: (String, String),
    pub root: PathBuf,
    pub members: Vec<Member>,
    pub varied: Vec<String>,
    /// Members completed by an earlier invocation (skipped).
    pub earlier: Vec<MemberOutcome>,
    /// Members to run now.
    pub todo: Vec<Member>,
    pub context: MemberContext,
    /// The case's `[ensemble]` thread settings (0 = auto).
    pub threads_per_member: usize,
    pub concurrent_members: usize,
    /// The lock on the output folder while this process runs the ensemble (rank 0's).
    pub lock: Option<std::sync::Arc<crate::output_folder::FolderLock>>,
}

/// Loads the case, plans its members and validates every member's case. With `write`, checks
/// the output folder (new, empty, or an earlier run of an ensemble, which is resumed) and writes
/// the plan; MPI ranks other than 0 plan without touching the folder.
pub fn prepare(path: &Path, sets: &[String], options: &EnsembleOptions, write: bool) -> Result<Prepared> {
    let base = crate::case::load(path, sets)?;
    let Some(spec) = base.case.ensemble.clone() else {
        return Err(base.error(
            "ensemble",
            "is missing: `stiction ensemble` needs an [ensemble] table (members and [[ensemble.vary]] keys)",
        ));
    };
    let members = plan::members(&spec);
    for m in &members {
        let mut member_sets = sets.to_vec();
        member_sets.extend(m.sets.iter().cloned());
        crate::case::load(path, &member_sets).map_err(|e| StictionError::Case {
            path: path.to_path_buf(),
            message: format!("ensemble member {} ({}): {e}", m.index, m.sets.join(", ")),
        })?;
    }
    let root =
        crate::run::output_directory(&base, &crate::run::RunOptions { out: options.out.clone(), ..Default::default() });
    let mut lock = None;
    if write {
        check_folder(&root)?;
        lock = Some(std::sync::Arc::new(crate::output_folder::lock(&root)?));
        let json = serde_json::to_string_pretty(&members).expect("plan serializes");
        let io = |source| StictionError::Core(stiction_core::CoreError::Write { path: root.clone(), source });
        std::fs::create_dir_all(&root).map_err(io)?;
        write_atomically(&root.join(PLAN_FILE), json.as_bytes())?;
    }
    let earlier: Vec<MemberOutcome> = members.iter().filter_map(|m| member::earlier_completion(&root, m)).collect();
    let todo = members.iter().filter(|m| !earlier.iter().any(|e| e.index == m.index)).cloned().collect();
    Ok(Prepared {
        name: base.name.clone(),
        units: base.case.units.as_ref().map_or_else(Default::default, |u| (u.length.clone(), u.force.clone())),
        root: root.clone(),
        varied: spec.vary.iter().map(|v| v.key.clone()).collect(),
        members,
        earlier,
        todo,
        context: MemberContext {
            case_path: path.to_path_buf(),
            sets: sets.to_vec(),
            root,
            interrupt: options.interrupt.clone(),
        },
        threads_per_member: options.threads_per_member.unwrap_or(spec.threads_per_member),
        concurrent_members: options.concurrent_members.unwrap_or(spec.concurrent_members),
        lock,
    })
}

/// An ensemble's folder is new, empty, or holds an earlier invocation of an ensemble.
fn check_folder(root: &Path) -> Result<()> {
    let refuse = |message: String| Err(StictionError::Output { path: root.to_path_buf(), message });
    if root.exists() && !root.is_dir() {
        return refuse("is a file, not a folder; give another --out".into());
    }
    let entries = std::fs::read_dir(root)
        .map(|d| d.flatten().filter(|e| e.file_name() != crate::output_folder::LOCK_FILE).count())
        .unwrap_or(0);
    if entries > 0 && !root.join(PLAN_FILE).exists() {
        return refuse(format!(
            "is not empty ({entries} entries) and holds no earlier ensemble ({PLAN_FILE}); give a new or empty folder \
             with --out"
        ));
    }
    Ok(())
}

/// A line for a finished member: `done` of `total` members to run in this invocation have ended with this one.
pub fn describe(root: &Path, o: &MemberOutcome, done: usize, total: usize) -> String {
    let summary: Option<serde_json::Value> = std::fs::read_to_string(root.join(&o.folder).join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok());
    let wall =
        summary.as_ref().and_then(|s| s["wall_seconds"].as_f64()).map_or(String::new(), |w| format!(" in {w:.1} s"));
    let error = o.error.as_ref().map_or(String::new(), |e| format!(": {e}"));
    format!("{} of {total}: {} [{}]: {}{wall}{error}", done, o.folder, o.sets.join(", "), o.status)
}

/// After the first member that completes: what the members still to run will take, from its
/// wall time and the size of its folder (a warning when that is more than the disk has free).
pub fn estimate(root: &Path, first: &MemberOutcome, left: usize, concurrent: usize) -> Option<String> {
    let folder = root.join(&first.folder);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(folder.join("summary.json")).ok()?).ok()?;
    let wall = summary["wall_seconds"].as_f64()?;
    let bytes = crate::resources::folder_bytes(&folder);
    let hours = wall * left as f64 / concurrent.max(1) as f64 / 3600.0;
    let need = bytes.saturating_mul(left as u64);
    let free = crate::resources::free_disk(root);
    let disk = free.map_or(String::new(), |f| format!(" ({} free)", crate::resources::gib(f)));
    let line = format!(
        "estimate from {}: {wall:.1} s and {} each; the {left} members left need about {hours:.2} h at {concurrent} \
         at once and {} on disk{disk}",
        first.folder,
        crate::resources::gib(bytes),
        crate::resources::gib(need)
    );
    Some(match free {
        Some(f) if need > f => format!(
            "warning: {line}: more than the disk has free; stop with Ctrl-C and give fewer members, or output.vtk = false"
        ),
        _ => line,
    })
}

/// The ensemble's end: the earlier and new outcomes in member order, then the aggregate written
/// and plotted, unless the run was interrupted (then only the completed members stay, to be
/// resumed).
pub fn finish(prepared: &Prepared, new: Vec<MemberOutcome>) -> Result<EnsembleAggregate> {
    let interrupted = prepared.context.interrupt.as_ref().is_some_and(|f| f.load(Ordering::SeqCst))
        || new.iter().any(|o| o.status == "interrupted");
    let mut outcomes: Vec<MemberOutcome> = prepared.earlier.iter().cloned().chain(new).collect();
    outcomes.sort_by_key(|o| o.index);
    let completed = outcomes.iter().filter(|o| o.completed()).count();
    if interrupted {
        return Err(StictionError::EnsembleInterrupted {
            completed,
            members: prepared.members.len(),
            out: prepared.root.clone(),
        });
    }
    let aggregate = aggregate::aggregate(
        (&prepared.name, prepared.units.clone()),
        prepared.varied.clone(),
        outcomes,
        &prepared.root,
    );
    aggregate::write(&prepared.root, &aggregate)?;
    if let Err(e) = plots::plot(&prepared.root, &aggregate) {
        eprintln!("warning: ensemble plots not written: {e}");
    }
    if completed == 0 {
        return Err(StictionError::EnsembleFailed { members: prepared.members.len(), out: prepared.root.clone() });
    }
    Ok(aggregate)
}

/// Runs an ensemble on this machine: the members not completed earlier, concurrently under the
/// thread budget, then the aggregate.
pub fn run_ensemble(path: &Path, sets: &[String], options: &EnsembleOptions) -> Result<EnsembleAggregate> {
    let prepared = prepare(path, sets, options, true)?;
    // chosen from the whole ensemble, not the members left, so a resumed member runs with the
    // threads its siblings had (the assembly's sums, hence the last digits, depend on them)
    let budget = local::ThreadBudget::choose(
        local::available_cores(),
        prepared.members.len(),
        prepared.concurrent_members,
        prepared.threads_per_member,
    );
    announce(&prepared, &format!("{} at once, {} threads each", budget.concurrent, budget.threads));
    let root = prepared.root.clone();
    let quiet = options.quiet;
    let (done, total) = (std::sync::atomic::AtomicUsize::new(0), prepared.todo.len());
    let estimated = std::sync::atomic::AtomicBool::new(false);
    let report = move |o: &MemberOutcome| {
        let done = done.fetch_add(1, Ordering::SeqCst) + 1;
        if !quiet || !o.completed() {
            eprintln!("{}", describe(&root, o, done, total));
        }
        // printed even when quiet: an ensemble's cost is known only once a member has run
        if o.completed() && done < total && !estimated.swap(true, Ordering::SeqCst) {
            if let Some(line) = estimate(&root, o, total - done, budget.concurrent) {
                eprintln!("{line}");
            }
        }
    };
    let new = local::run_members(&prepared.todo, &prepared.context, budget, &report);
    finish(&prepared, new)
}

/// The opening line (printed even when quiet): members, resumed ones, and how they run.
pub fn announce(prepared: &Prepared, how: &str) {
    let resumed = if prepared.earlier.is_empty() {
        String::new()
    } else {
        format!(" ({} complete from an earlier invocation, skipped)", prepared.earlier.len())
    };
    eprintln!(
        "ensemble {}: {} members{resumed}; running {} ({how}) into {}",
        prepared.name,
        prepared.members.len(),
        prepared.todo.len(),
        prepared.root.display()
    );
}

/// The lines `stiction ensemble` prints: members, failures, and each quantity's mean +- the 95%
/// confidence half width (and the standard deviation), 4 significant figures.
pub fn lines(a: &EnsembleAggregate) -> Vec<String> {
    let mut lines = vec![format!(
        "ensemble {}: {} of {} members completed (varied: {})",
        a.case,
        a.completed,
        a.members,
        a.varied.join(", ")
    )];
    for o in a.outcomes.iter().filter(|o| !o.completed()) {
        lines.push(format!("  excluded {}: {}", o.folder, o.error.as_deref().unwrap_or(&o.status)));
    }
    let unit = &a.force_unit;
    for s in &a.statistics {
        // forces with the case's force unit rescaled (e.g. nN -> uN), anything else as it is
        let is_force =
            matches!(s.quantity.rsplit('.').next(), Some("max_force" | "pull_off_force" | "most_tensile_force"));
        let show = |v: f64| if is_force { crate::report::force(v, unit) } else { crate::report::significant(v) };
        let ci = s.ci95_half_width.map_or(String::new(), |h| format!(" +- {} (95%)", show(h)));
        let std = s.std.map_or(String::new(), |d| format!(", std {}", show(d)));
        lines.push(format!("  {}: {}{ci}{std}, n {}", s.quantity, show(s.mean), s.n));
    }
    lines
        .push("  aggregate: ensemble.json, ensemble.csv, ensemble_{loading,unloading}.csv, ensemble_*.png/.svg".into());
    lines
}

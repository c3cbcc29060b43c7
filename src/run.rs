//! `stiction run` for one case: builds the model, sets up the output folder and the observers
//! (history.csv, events.csv, the VTK series, summary.json, plots, progress) and hands the run
//! to the core's step driver.

use crate::build::{BuiltModel, build};
use crate::case::{
    ContinuationSpec, LoadedCase, MethodSpec, OrderingSpec, PrecisionSpec, SnapDampingSpec, SnapSpec, SolverSpec,
    StartPredictorSpec, TangentSpec,
};
use crate::error::{Result, StictionError};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;
use stiction_core::checkpoint::CheckpointPlan;
use stiction_core::linear_solver::{FaerCholesky, Ordering, Precision};
use stiction_core::model::Model;
use stiction_core::nonlinear::damped_flow::{FlowDamping, FlowSettings};
use stiction_core::nonlinear::{NewtonSolver, NonlinearSolver, QuasiNewtonSolver};
use stiction_core::path::{
    Checkpoint, Continuation, ContinuationMethod, RunPlan, SnapMethod, StartPredictor, TangentChoice, resume_steps,
    run_steps,
};
use stiction_core::record::{
    CyclesWriter, EventsRecorder, HistoryRecorder, MessageLog, Observer, SummaryWriter, VtkRecorder,
};

pub use stiction_core::record::{InterfaceSummary, RunStatus, RunSummary};

/// Options of `stiction run` beyond the case file.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output directory (overrides the case's `output.directory`).
    pub out: Option<PathBuf>,
    /// Show progress (normally: stderr is a terminal).
    pub progress: bool,
    /// What the progress line starts with (a sweep's "run 2 of 3: ...").
    pub progress_label: Option<String>,
    /// Replace an earlier run in the output folder (otherwise a non-empty folder is refused).
    pub overwrite: bool,
    /// Set to stop the run after the increment in progress (Ctrl-C).
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Go on from the checkpoint of an earlier run of the case in the output folder
    /// ([`crate::resume`]) instead of starting afresh.
    pub resume: bool,
    /// Stop (as if interrupted, with a checkpoint) once this many increments are committed.
    pub stop_after_increments: Option<usize>,
    /// Stop (as if interrupted, with a checkpoint) inside a damped-flow snap, after this many
    /// flow steps of this process (a test that resuming inside a snap changes nothing).
    pub stop_after_flow_steps: Option<usize>,
}

/// Output directory of a case: `--out`, else `output.directory`, else `out/<name>`.
pub fn output_directory(case: &LoadedCase, options: &RunOptions) -> PathBuf {
    options
        .out
        .clone()
        .or_else(|| case.case.output.directory.clone())
        .unwrap_or_else(|| PathBuf::from("out").join(&case.name))
}

/// Builds and runs a case, or goes on with it from its checkpoint (`options.resume`).
pub fn run(case: &LoadedCase, options: &RunOptions) -> Result<RunSummary> {
    let out = output_directory(case, options);
    if options.resume {
        // refuse a checkpoint of another problem before the (possibly long) build
        let path = crate::resume::checkpoint_path(case, &out)?;
        let checkpoint = Checkpoint::read(&path)?;
        crate::resume::check_same_problem(case, &path, &checkpoint.fingerprint, &crate::resume::fingerprint(case))?;
        let mut built = build(case)?;
        return run_built(case, &mut built, options, Some(checkpoint));
    }
    // refuse an occupied output folder before the (possibly long) build; replace it only after
    crate::output_folder::check(&out, options.overwrite)?;
    let mut built = build(case)?;
    run_model(case, &mut built, options)
}

/// The observers of a run into `out`: the files every run writes, plots, and progress.
fn observers(
    case: &LoadedCase,
    built: &BuiltModel,
    out: &std::path::Path,
    progress: Option<Option<&str>>,
) -> Vec<Box<dyn Observer>> {
    let model = &built.model;
    let mut list: Vec<Box<dyn Observer>> = vec![
        Box::new(HistoryRecorder::new(
            &out.join("history.csv"),
            model,
            built.reaction_groups.clone(),
            built.load_groups.clone(),
        )),
        Box::new(EventsRecorder::new(&out.join("events.csv"))),
        Box::new(MessageLog::new(&out.join("messages.log"))),
    ];
    if case.case.output.vtk {
        list.push(Box::new(VtkRecorder::new(out, &case.name, model)));
    }
    list.push(Box::new(SummaryWriter::new(out)));
    list.push(Box::new(CyclesWriter::new(out)));
    list.push(Box::new(crate::plots::RunPlots::new(out, &case.name)));
    if let Some(label) = progress {
        list.push(Box::new(crate::progress::ProgressDisplay::new(label)));
    }
    list
}

/// The case's `solver.continuation` as the driver's crossing plan.
fn continuation(solver: &SolverSpec) -> Option<Continuation> {
    let method = match solver.continuation {
        ContinuationSpec::None => return None,
        ContinuationSpec::ArcLength => ContinuationMethod::ArcLength,
        ContinuationSpec::Dissipation => ContinuationMethod::Dissipation,
    };
    Some(Continuation { method, after_cuts: solver.arc_length_after_cuts })
}

/// The case's `solver.snap` as the driver's method; "auto" follows the damped flow where the
/// state a snap lands on depends on its path (a material or an interface law with state), and
/// elsewhere settles by descent, with the damped flow where a descent finds no stable state.
fn snap_method(solver: &SolverSpec, model: &Model) -> SnapMethod {
    let settings = FlowSettings {
        tolerance: solver.snap_tolerance,
        max_steps: solver.snap_max_steps,
        damping: match solver.snap_damping {
            SnapDampingSpec::Mass => FlowDamping::Mass,
            SnapDampingSpec::Stiffness => FlowDamping::Stiffness,
        },
        ..FlowSettings::default()
    };
    match solver.snap {
        SnapSpec::DampedFlow => SnapMethod::DampedFlow(settings),
        SnapSpec::Settle => SnapMethod::Settle,
        SnapSpec::Auto if model.path_dependent() => SnapMethod::DampedFlow(settings),
        SnapSpec::Auto => SnapMethod::SettleOrFlow(settings),
    }
}

/// Runs an already built model from its initial state; the model keeps the final converged
/// state for inspection.
pub fn run_model(case: &LoadedCase, built: &mut BuiltModel, options: &RunOptions) -> Result<RunSummary> {
    run_built(case, built, options, None)
}

/// Runs an already built model from its initial state, or from `checkpoint` (the output folder
/// then holds the checkpointed run, which goes on).
///
/// With `solver.threads` > 0 the run gets a thread pool of that size for itself (not rayon's
/// global one, which a process sets once: several runs in one process, as in the tests, each
/// keep their own count); a run already on a pool's thread (an ensemble member, whose pool the
/// ensemble sized) stays on it.
fn run_built(
    case: &LoadedCase,
    built: &mut BuiltModel,
    options: &RunOptions,
    checkpoint: Option<Checkpoint>,
) -> Result<RunSummary> {
    let threads = case.case.solver.threads;
    if threads == 0 || rayon::current_thread_index().is_some() {
        return solve_built(case, built, options, checkpoint);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        // the main thread's stack (the run would have used it), not a worker's 2 MiB default
        .stack_size(RUN_THREAD_STACK_BYTES)
        .build()
        .map_err(|e| StictionError::CaseKey {
            path: case.path.clone(),
            key: "solver.threads".into(),
            message: format!("cannot start {threads} threads for the run: {e} (0 uses all cores)"),
        })?;
    pool.install(|| solve_built(case, built, options, checkpoint))
}

/// Where a run stopped with an error after its summary was first written (status "running"),
/// e.g. a degenerate element found at the first assembly: the summary says "failed" with the
/// reason, so it never describes a run that is not running as running.
fn mark_failed(out: &std::path::Path, reason: &str) {
    let path = out.join("summary.json");
    let Some(mut summary) =
        std::fs::read_to_string(&path).ok().and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
    else {
        return;
    };
    if summary["status"] != "running" {
        return;
    }
    summary["status"] = "failed".into();
    summary["message"] = reason.into();
    let text = serde_json::to_string_pretty(&summary).expect("a summary serializes");
    if let Err(e) = stiction_core::output::write_atomically(&path, text.as_bytes()) {
        eprintln!("warning: {} not marked failed: {e}", path.display());
    }
}

/// The stack of each thread of a run's own pool: 8 MiB, Linux's default for a main thread.
const RUN_THREAD_STACK_BYTES: usize = 8 << 20;

/// [`run_built`] on the current thread pool.
fn solve_built(
    case: &LoadedCase,
    built: &mut BuiltModel,
    options: &RunOptions,
    checkpoint: Option<Checkpoint>,
) -> Result<RunSummary> {
    // the factor's size is known from the symbolic analysis: refuse one that cannot fit before
    // the output folder is made
    let ordering = match case.case.solver.ordering {
        OrderingSpec::NestedDissection => Ordering::NestedDissection,
        OrderingSpec::Amd => Ordering::Amd,
    };
    let precision = match case.case.solver.factor_precision {
        PrecisionSpec::Single => Precision::Single,
        PrecisionSpec::Double => Precision::Double,
    };
    let mut linear = FaerCholesky::analyse_with_precision(built.model.pattern(), ordering, precision)?;
    let bytes_per_entry = if precision == Precision::Single { 4 } else { 8 };
    crate::build::size::check_factor_fits(case, &linear, built.model.free_dofs().len(), bytes_per_entry)?;
    let out = output_directory(case, options);
    let _lock = crate::output_folder::lock(&out)?;
    if checkpoint.is_none() {
        crate::output_folder::prepare(&out, options.overwrite)?;
    } else {
        crate::output_folder::remove_temporaries(&out)?;
    }
    for (name, points) in &built.layouts {
        let path = out.join(format!("{name}_points.csv"));
        crate::build::write_points_csv(&path, points)?;
    }
    let mut observers = observers(case, built, &out, options.progress.then_some(options.progress_label.as_deref()));
    let plan = RunPlan {
        name: case.name.clone(),
        units: case.case.units.as_ref().map_or_else(Default::default, |u| (u.length.clone(), u.force.clone())),
        output_directory: out.clone(),
        steps: built.steps.clone(),
        continuation: continuation(&case.case.solver),
        interfaces: built.interfaces.clone(),
        interrupt: options.interrupt.clone(),
        start_predictor: match case.case.solver.start_predictor {
            StartPredictorSpec::Tangent => StartPredictor::Tangent,
            StartPredictorSpec::None => StartPredictor::None,
        },
        snap: snap_method(&case.case.solver, &built.model),
        tangent: match case.case.solver.tangent {
            TangentSpec::SwitchOnFailure => TangentChoice::SwitchOnFailure,
            TangentSpec::Consistent => TangentChoice::Consistent,
            TangentSpec::Stabilized => TangentChoice::Stabilized,
        },
        checkpoint: Some(CheckpointPlan {
            path: out.join(crate::resume::CHECKPOINT_FILE),
            interval: Duration::from_secs_f64(60.0 * case.case.output.checkpoint_minutes),
            fingerprint: crate::resume::fingerprint(case),
        }),
        stop_after_increments: options.stop_after_increments,
        stop_after_flow_steps: options.stop_after_flow_steps,
    };
    let mut nonlinear: Box<dyn NonlinearSolver> = match case.case.solver.method {
        MethodSpec::QuasiNewton => match case.case.solver.refactorization_cost_ratio {
            r if r > 0.0 => Box::new(QuasiNewtonSolver::with_cost_ratio(built.newton.clone(), r)),
            _ => Box::new(QuasiNewtonSolver::new(built.newton.clone())),
        },
        MethodSpec::Newton => Box::new(NewtonSolver { settings: built.newton.clone() }),
    };
    let result = match checkpoint {
        None => run_steps(&mut built.model, &plan, &mut linear, nonlinear.as_mut(), &mut observers),
        Some(checkpoint) => {
            resume_steps(&mut built.model, &plan, &mut linear, nonlinear.as_mut(), &mut observers, checkpoint)
        }
    };
    let summary = result.inspect_err(|e| mark_failed(&out, &e.to_string()))?;
    let resumable = out.join(crate::resume::CHECKPOINT_FILE).exists();
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    if summary.status == RunStatus::Interrupted {
        return Err(StictionError::Interrupted { time: summary.final_time, out, resumable });
    }
    if summary.status == RunStatus::Failed {
        let message = summary.message.clone().unwrap_or_default();
        return Err(StictionError::RunFailed { time: summary.final_time, message, out, resumable });
    }
    Ok(summary)
}

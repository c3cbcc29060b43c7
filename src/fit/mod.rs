//! Inverse calibration (`stiction fit FIT.toml`): the numeric case keys that minimise the
//! weighted squared differences between the FE model's results and measured ones, with the FE
//! model in the loop.
//!
//! - [`spec`]: the fit file, read and checked before any run;
//! - [`targets`]: measured curves and summary numbers against a run's outputs;
//! - [`evaluate`]: the runs at parameter vectors (concurrent, each in its own folder, reused
//!   when a fit is resumed) and the weighted residuals;
//! - [`problem`]: the least-squares problem for the Levenberg-Marquardt solver, with bounds by
//!   a change of variable and a finite-difference Jacobian;
//! - [`report`]: intervals, undetermined parameters and residuals per target;
//! - [`output`]: the fitted case files and the plots;
//! - `mpi` (cargo feature `mpi`): the runs spread over MPI ranks.
//!
//! The folder of a fit holds `fit-plan.json` (the fingerprint of the fit file, its target
//! files and its cases), `runs/` (every run), `fit_history.csv` (every parameter vector evaluated), and at the
//! end `fit.json`, `fitted-<case>.toml` and `fit_<k>.png/.svg`. A fit stopped by Ctrl-C, or
//! killed, goes on with `--resume`: the optimizer starts again from the start values and finds
//! the runs it asks for already in `runs/` (the path is deterministic), so it replays to where
//! it stopped and then runs what is new.

pub mod evaluate;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod output;
pub mod problem;
pub mod report;
pub mod spec;
pub mod targets;

use crate::error::{Result, StictionError};
use evaluate::{Evaluator, Outcome, Purpose};
use levenberg_marquardt::LevenbergMarquardt;
use problem::{FitProblem, Stop};
use serde::Serialize;
use sha2::Digest;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use stiction_core::output::write_atomically;
use stiction_core::record::summary::Units;

/// The file that marks a folder as a fit's.
pub const PLAN_FILE: &str = "fit-plan.json";

/// Options of `stiction fit` beyond the fit file.
#[derive(Debug, Clone, Default)]
pub struct FitOptions {
    /// The fit's folder (default: `out/fit-<name>`).
    pub out: Option<PathBuf>,
    /// Go on with the fit in the folder (its runs are reused).
    pub resume: bool,
    /// Replace an earlier fit in the folder.
    pub overwrite: bool,
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Do not report each run.
    pub quiet: bool,
}

/// What fit.json holds.
#[derive(Debug, Clone, Serialize)]
pub struct FitReport {
    pub name: String,
    /// "converged", or "not converged: <why>".
    pub status: String,
    /// The optimizer's reason to stop.
    pub termination: String,
    /// Residual evaluations (the start, and every trial point), Jacobians, runs made by this
    /// invocation and runs read back from the folder.
    pub evaluations: usize,
    pub iterations: usize,
    pub runs: usize,
    pub runs_reused: usize,
    /// Sum of the squared weighted residuals, at the start and at the fit.
    pub cost_at_start: f64,
    pub cost: f64,
    pub parameters: Vec<report::FittedParameter>,
    pub uncertainty: report::Uncertainty,
    pub targets: Vec<report::TargetResidual>,
    pub fitted_cases: Vec<PathBuf>,
}

/// Runs the fit described by the file at `path` on this machine's cores.
pub fn run_fit(path: &Path, options: &FitOptions) -> Result<FitReport> {
    let spec = spec::load(path)?;
    let runs = evaluate::LocalRuns::for_fit(&spec);
    fit_with(spec, options, &runs)
}

/// Runs the fit of `spec`, its runs going to `runs`.
pub fn fit_with(spec: spec::FitSpec, options: &FitOptions, runs: &dyn evaluate::Runs) -> Result<FitReport> {
    // every case must load with the parameters at their start: unknown keys are named now
    let mut units = Vec::new();
    let mut measured_costs = Vec::new();
    let mut fingerprint = sha2::Sha256::new();
    fingerprint.update(spec.fingerprint.as_bytes());
    for (c, case) in spec.cases.iter().enumerate() {
        let bad = |key: String, e: StictionError| StictionError::FitKey {
            path: spec.path.clone(),
            key,
            message: format!("the case '{}' does not take it: {e}", case.name),
        };
        crate::case::load(&case.file, &case.set).map_err(|e| bad(format!("cases.{c}"), e))?;
        let mut sets = case.set.clone();
        for (j, p) in spec.parameters.iter().enumerate().filter(|(_, p)| p.cases.contains(&c)) {
            sets.push(format!("{}={:e}", p.key, p.start));
            crate::case::load(&case.file, &sets).map_err(|e| bad(format!("parameters.{j}.key"), e))?;
        }
        let loaded = crate::case::load(&case.file, &sets)?;
        measured_costs.push(loaded.case.solver.refactorization_cost_ratio == 0.0);
        // a resumed fit must run the same cases (their files and bases as merged)
        fingerprint.update(toml::to_string(&loaded.value).unwrap_or_default().as_bytes());
        let u = loaded.case.units.as_ref();
        units.push(Units::of(u.map_or("", |u| u.length.as_str()), u.map_or("", |u| u.force.as_str())));
    }
    let out = options.out.clone().unwrap_or_else(|| PathBuf::from("out").join(format!("fit-{}", spec.name)));
    let fingerprint = format!("{:x}", fingerprint.finalize());
    let _lock = crate::output_folder::lock(&out)?;
    prepare_folder(&spec, &fingerprint, &out, options)?;

    let evaluator = Evaluator::new(&spec, &out, runs, &measured_costs, options.interrupt.clone(), options.quiet);
    let x0: Vec<f64> = spec.parameters.iter().map(|p| p.start).collect();
    let start = match evaluator.evaluate(std::slice::from_ref(&x0), Purpose::Start).remove(0) {
        Outcome::Done(p) => p,
        Outcome::Failed(message) => {
            return Err(StictionError::Fit {
                path: spec.path.clone(),
                message: format!("the cases cannot be compared with the targets at the start values: {message}"),
            });
        }
        Outcome::Interrupted => return Err(StictionError::FitInterrupted { out }),
    };
    let m = start.residuals.len();
    let n = spec.parameters.len();
    let o = &spec.optimizer;
    let problem = FitProblem::new(&evaluator, &spec.parameters, o.fd_step, o.jacobian, m);
    let solver = LevenbergMarquardt::new()
        .with_ftol(o.tolerance)
        .with_xtol(o.tolerance)
        .with_gtol(1e-10)
        .with_stepbound(1.0)
        .with_patience(o.max_evaluations.div_ceil(n + 1));
    let (problem, outcome) = solver.minimize(problem);
    match problem.stop.borrow().clone() {
        Some(Stop::Interrupted) => return Err(StictionError::FitInterrupted { out }),
        Some(Stop::Failed(message)) => return Err(StictionError::FitFailed { message, out }),
        None => {}
    }
    let x = problem.x();
    let end = match evaluator.evaluate(std::slice::from_ref(&x), Purpose::Trial).remove(0) {
        Outcome::Done(p) => p,
        Outcome::Failed(message) => return Err(StictionError::FitFailed { message, out }),
        Outcome::Interrupted => return Err(StictionError::FitInterrupted { out }),
    };
    // the Jacobian at the solution (its runs are mostly those of the last iteration)
    let jacobian = match problem.jacobian_in_v(&x, &end.residuals) {
        Ok(j) => j,
        Err(Stop::Interrupted) => return Err(StictionError::FitInterrupted { out }),
        Err(Stop::Failed(message)) => return Err(StictionError::FitFailed { message, out }),
    };
    let uncertainty = report::uncertainty(&spec, &jacobian, end.cost());
    let parameters = report::fitted_parameters(&spec, &x, &uncertainty);
    let status = if outcome.termination.was_successful() {
        "converged".to_string()
    } else {
        format!("not converged: {:?}", outcome.termination)
    };
    let header = fitted_header(&spec, &parameters);
    let fitted_cases = output::write_fitted_cases(&spec, &out, &x, &header)?;
    if let Err(e) = output::plot_curves(&spec, &out, &units, &start, &end) {
        eprintln!("warning: fit plots not written: {e}");
    }
    let report = FitReport {
        name: spec.name.clone(),
        status,
        termination: format!("{:?}", outcome.termination),
        evaluations: problem.evaluations.get(),
        iterations: problem.iterations.get(),
        runs: evaluator.runs.load(std::sync::atomic::Ordering::SeqCst),
        runs_reused: evaluator.runs_reused.load(std::sync::atomic::Ordering::SeqCst),
        cost_at_start: start.cost(),
        cost: end.cost(),
        parameters,
        uncertainty,
        targets: report::target_residuals(&spec, &start, &end),
        fitted_cases,
    };
    let json = serde_json::to_string_pretty(&report).expect("fit report serializes");
    write_atomically(&out.join("fit.json"), json.as_bytes())?;
    Ok(report)
}

/// A new fit's folder is prepared (an earlier fit replaced only with `overwrite`); a resumed
/// fit's must hold a fit with the same `fingerprint` (of the fit file, its targets and cases).
fn prepare_folder(spec: &spec::FitSpec, fingerprint: &str, out: &Path, options: &FitOptions) -> Result<()> {
    let plan = out.join(PLAN_FILE);
    if options.resume {
        let saved = std::fs::read_to_string(&plan)
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .and_then(|v| v["fingerprint"].as_str().map(String::from));
        return match saved {
            None => Err(StictionError::Output {
                path: out.to_path_buf(),
                message: format!("holds no fit to resume ({PLAN_FILE} is missing or unreadable)"),
            }),
            Some(s) if s != fingerprint => Err(StictionError::Output {
                path: out.to_path_buf(),
                message: format!(
                    "holds a fit of another fit file, other targets or other cases than '{}' has now; run it \
                     afresh with --overwrite or give another --out",
                    spec.path.display()
                ),
            }),
            Some(_) => crate::output_folder::remove_temporaries(out),
        };
    }
    crate::output_folder::prepare(out, options.overwrite)?;
    let text = serde_json::json!({ "fingerprint": fingerprint, "fit_file": spec.path }).to_string();
    write_atomically(&plan, text.as_bytes())?;
    Ok(())
}

/// The comment block at the top of a fitted case file.
fn fitted_header(spec: &spec::FitSpec, parameters: &[report::FittedParameter]) -> String {
    let mut h = format!(
        "# Fitted by `stiction fit {}`: the case as the fit ran it, with these values fitted to\n# its targets ({}):\n",
        spec.path.display(),
        spec.targets.iter().map(|t| t.name.as_str()).collect::<Vec<_>>().join("; ")
    );
    for p in parameters {
        let interval = p
            .interval_95
            .map_or("not determined by the targets".to_string(), |[a, b]| format!("95% interval {a:.6e} to {b:.6e}"));
        h.push_str(&format!("#   {} = {:.6e} ({interval})\n", p.key, p.value));
    }
    h.push('\n');
    h
}

/// The lines `stiction fit` prints: the status, each parameter with its interval, each
/// target's residual.
pub fn lines(report: &FitReport) -> Vec<String> {
    let mut lines = vec![format!(
        "{}: {} after {} evaluations and {} Jacobians ({} runs, {} reused); cost {} -> {}",
        report.name,
        report.status,
        report.evaluations,
        report.iterations,
        report.runs,
        report.runs_reused,
        crate::report::significant(report.cost_at_start),
        crate::report::significant(report.cost)
    )];
    for p in &report.parameters {
        let interval = match p.interval_95 {
            Some([a, b]) => {
                format!("95% interval {} to {}", crate::report::significant(a), crate::report::significant(b))
            }
            None => "not determined by the targets".into(),
        };
        let truth = p.true_value.map_or(String::new(), |t| format!("; true value {}", crate::report::significant(t)));
        let bound = if p.near_bound { " (at a bound)" } else { "" };
        lines.push(format!(
            "  {} = {}{bound}, {interval} (start {}{truth})",
            p.key,
            crate::report::significant(p.value),
            crate::report::significant(p.start)
        ));
    }
    for u in &report.uncertainty.undetermined {
        lines.push(format!("  warning: {u}"));
    }
    for t in &report.targets {
        lines.push(format!(
            "  target {}: rms difference {} over {} point{}; cost {} -> {}",
            t.name,
            crate::report::significant(t.rms_difference),
            t.points,
            if t.points == 1 { "" } else { "s" },
            crate::report::significant(t.cost_at_start),
            crate::report::significant(t.cost)
        ));
    }
    lines
}

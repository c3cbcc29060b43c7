//! Sweeps: whole runs driven from outside the single-run driver, one per value of a case key,
//! with combined plots and `sweep.json`.
//!
//! Resuming (`stiction run SWEEP.toml --resume`): a sweep records its problem at its start
//! ([`SWEEP_PLAN`]: the fingerprint of the case as given, its `[sweep]` included, see
//! [`crate::resume`]). Resumed, the case must describe the same sweep (the first key that
//! differs is named); then each value's run is kept where it completed, goes on from its
//! checkpoint where it has one (stopped, or failed), and runs afresh otherwise (not started,
//! or killed before its first checkpoint).

use crate::case::LoadedCase;
use crate::error::{Result, StictionError};
use crate::resume::CHECKPOINT_FILE;
use crate::run::{RunOptions, output_directory, run};
use std::path::Path;
use stiction_core::output::write_atomically;
use stiction_core::record::{RunStatus, RunSummary};

/// The record a sweep writes into its folder at its start: the fingerprint of its problem.
pub const SWEEP_PLAN: &str = "sweep-plan.json";

/// Runs a case once per value of its `[sweep]` (or once if it has none). Each run writes to
/// `<out>/<label>=<value>/`; the combined plots and `sweep.json` go to `<out>/`.
pub fn run_sweep(path: &Path, sets: &[String], options: &RunOptions) -> Result<Vec<RunSummary>> {
    let base = crate::case::load(path, sets)?;
    if let Some(e) = &base.case.ensemble {
        eprintln!(
            "note: `stiction run` runs the case as written, once; `stiction ensemble` runs its {} members",
            e.members
        );
    }
    let Some(sweep) = base.case.sweep.clone() else {
        return Ok(vec![run(&base, options)?]);
    };
    if sweep.values.is_empty() {
        return Err(base.error("sweep.values", "needs at least one value"));
    }
    let out = output_directory(&base, options);
    let _lock = crate::output_folder::lock(&out)?;
    let fingerprint = crate::resume::fingerprint(&base);
    if options.resume {
        check_same_sweep(&base, &out, &fingerprint)?;
    } else {
        crate::output_folder::prepare(&out, options.overwrite)?;
        let plan = serde_json::json!({ "fingerprint": fingerprint }).to_string();
        write_atomically(&out.join(SWEEP_PLAN), plan.as_bytes())?;
    }
    let label = sweep.label.clone().unwrap_or_else(|| sweep.key.clone());
    let mut summaries = Vec::new();
    let mut curves = Vec::new();
    for (k, v) in sweep.values.iter().enumerate() {
        let mut run_sets = sets.to_vec();
        run_sets.push(format!("{}={v}", sweep.key));
        let case = crate::case::load(path, &run_sets)?;
        let folder = out.join(format!("{}={v}", label.replace(['/', ' '], "_")));
        let progress_label = Some(format!("run {} of {}: {label} = {v}", k + 1, sweep.values.len()));
        let run_options = RunOptions { out: Some(folder.clone()), progress_label, ..options.clone() };
        let summary = if options.resume {
            resume_member(&case, &folder, &format!("{label} = {v}"), run_options)?
        } else {
            run(&case, &run_options)?
        };
        if let Some(c) = crate::plots::read_history(&folder.join("history.csv"), &format!("{label} = {v}")) {
            curves.push(c);
        }
        summaries.push(summary);
    }
    if !curves.is_empty() {
        if let Err(e) = crate::plots::plot_curves(&out, "combined_", &base.name, &curves) {
            eprintln!("warning: combined plots not written: {e}");
        }
    }
    let json = serde_json::to_string_pretty(&summaries).expect("summaries serialize");
    write_atomically(&out.join("sweep.json"), json.as_bytes())?;
    Ok(summaries)
}

/// Ok when the sweep recorded in `out` ([`SWEEP_PLAN`]) has the fingerprint `now` (the case
/// given); Err says why it cannot be resumed (none recorded, or the first key that differs).
fn check_same_sweep(base: &LoadedCase, out: &Path, now: &str) -> Result<()> {
    let path = out.join(SWEEP_PLAN);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Err(StictionError::Output {
            path: out.to_path_buf(),
            message: format!(
                "holds no sweep of case '{}' to resume ({SWEEP_PLAN} is missing): give the folder of the sweep \
                 with --out, or run the sweep afresh",
                base.name
            ),
        });
    };
    let saved =
        serde_json::from_str::<serde_json::Value>(&text).ok().and_then(|v| v["fingerprint"].as_str().map(String::from));
    let Some(saved) = saved else {
        return Err(StictionError::Output {
            path,
            message: "is not a sweep record (expected JSON with a \"fingerprint\" string)".into(),
        });
    };
    crate::resume::check_same_problem(base, &path, &saved, now)
}

/// One value's run of a resumed sweep, in `folder`: kept where it completed (its summary read
/// back), resumed from its checkpoint where it has one, run afresh otherwise. Says which on
/// stderr, as `name` (the sweep's label and value).
fn resume_member(case: &LoadedCase, folder: &Path, name: &str, options: RunOptions) -> Result<RunSummary> {
    if folder.join(CHECKPOINT_FILE).exists() {
        eprintln!("{name}: going on from its checkpoint");
        return run(case, &RunOptions { resume: true, ..options });
    }
    let completed = std::fs::read_to_string(folder.join("summary.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<RunSummary>(&text).ok())
        .filter(|summary| summary.status == RunStatus::Completed);
    if let Some(summary) = completed {
        eprintln!("{name}: completed earlier, kept");
        return Ok(summary);
    }
    eprintln!("{name}: run afresh (no checkpoint to go on from)");
    run(case, &RunOptions { resume: false, overwrite: true, ..options })
}

//! Sweeps: whole runs driven from outside the single-run driver, one per value of a case key,
//! with combined plots and `sweep.json`.

use crate::error::Result;
use crate::run::{RunOptions, RunSummary, output_directory, run};
use std::path::Path;
use stiction_core::output::write_atomically;

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
    if options.resume {
        return Err(base.error(
            "sweep",
            "is set: --resume goes on with a single run, not a sweep (run the sweep again to repeat it)",
        ));
    }
    let out = output_directory(&base, options);
    crate::output_folder::prepare(&out, options.overwrite)?;
    let label = sweep.label.clone().unwrap_or_else(|| sweep.key.clone());
    let mut summaries = Vec::new();
    let mut curves = Vec::new();
    for v in &sweep.values {
        let mut run_sets = sets.to_vec();
        run_sets.push(format!("{}={v}", sweep.key));
        let case = crate::case::load(path, &run_sets)?;
        let folder = out.join(format!("{}={v}", label.replace(['/', ' '], "_")));
        let run_options = RunOptions { out: Some(folder.clone()), ..options.clone() };
        let summary = run(&case, &run_options)?;
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

//! The output folder of a run: never overwritten silently. A run goes into a new or empty
//! folder; with `--overwrite` it may replace an earlier Stiction run (a folder holding
//! `summary.json`, `history.csv`, a sweep's `sweep-plan.json` or `sweep.json`, or an ensemble
//! member's `member.json`),
//! never a folder of other files.

use crate::error::{Result, StictionError};
use std::path::Path;

/// Files whose presence marks a folder as written by an earlier run of Stiction.
const RUN_MARKERS: [&str; 5] = ["summary.json", "history.csv", "sweep-plan.json", "sweep.json", "member.json"];

/// Whether a run may write into `out` (see the module documentation), without touching it:
/// Ok(true) when `out` holds an earlier run that `overwrite` allows to replace.
pub fn check(out: &Path, overwrite: bool) -> Result<bool> {
    let refuse = |message: String| Err(StictionError::Output { path: out.to_path_buf(), message });
    if out.exists() && !out.is_dir() {
        return refuse("is a file, not a folder; give another --out".into());
    }
    let entries = match std::fs::read_dir(out) {
        Ok(entries) => entries.filter_map(|e| e.ok()).count(),
        Err(_) => 0,
    };
    if entries == 0 {
        return Ok(false);
    }
    let earlier_run = RUN_MARKERS.iter().any(|m| out.join(m).exists());
    match (overwrite, earlier_run) {
        (false, true) => refuse("holds an earlier run; give --overwrite to replace it, or another --out".into()),
        (false, false) => refuse(format!("is not empty ({entries} entries); give an empty or new folder with --out")),
        (true, false) => refuse(format!(
            "is not empty and holds no earlier run ({}); --overwrite replaces only an earlier run's folder",
            RUN_MARKERS.join(", ")
        )),
        (true, true) => Ok(true),
    }
}

/// Makes `out` ready for a new run: creates it, or empties it when `overwrite` is given and it
/// holds an earlier run; refuses a non-empty folder otherwise.
pub fn prepare(out: &Path, overwrite: bool) -> Result<()> {
    let io = |source| StictionError::Core(stiction_core::CoreError::Write { path: out.to_path_buf(), source });
    if check(out, overwrite)? {
        std::fs::remove_dir_all(out).map_err(io)?;
    }
    std::fs::create_dir_all(out).map_err(io)
}

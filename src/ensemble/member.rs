//! Running one member of an ensemble into its own folder, and telling whether an earlier
//! invocation already completed it (resuming).

use super::plan::Member;
use crate::error::StictionError;

/// What a stopped member's message advises (instead of `stiction run`'s --resume).
const AGAIN: &str = "; running the same `stiction ensemble` command again goes on with this member from its checkpoint";
use crate::run::{RunOptions, run};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use stiction_core::output::write_atomically;

/// The record a member leaves in its folder (`member.json`) and the ensemble reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MemberOutcome {
    pub index: usize,
    pub folder: String,
    pub sets: Vec<String>,
    /// "completed", "failed" or "interrupted".
    pub status: String,
    /// Why a member failed or stopped.
    pub error: Option<String>,
}

impl MemberOutcome {
    pub fn completed(&self) -> bool {
        self.status == "completed"
    }
}

/// What every member shares: the case file, the command's own --set overrides, the ensemble's
/// folder and the Ctrl-C flag.
#[derive(Debug, Clone)]
pub struct MemberContext {
    pub case_path: PathBuf,
    pub sets: Vec<String>,
    pub root: PathBuf,
    pub interrupt: Option<Arc<AtomicBool>>,
}

/// The outcome an earlier invocation recorded for `member`, when it completed with the same
/// varied values (its member.json matches and its summary.json says "completed").
pub fn earlier_completion(root: &Path, member: &Member) -> Option<MemberOutcome> {
    let folder = root.join(&member.folder);
    let outcome: MemberOutcome =
        serde_json::from_str(&std::fs::read_to_string(folder.join("member.json")).ok()?).ok()?;
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(folder.join("summary.json")).ok()?).ok()?;
    let same = outcome.sets == member.sets && outcome.completed();
    (same && summary["status"] == "completed").then_some(outcome)
}

/// Whether an earlier invocation stopped `member` (Ctrl-C; the same varied values) and left the
/// checkpoint of its run in `folder`, to go on from.
fn stopped_with_checkpoint(folder: &Path, member: &Member) -> bool {
    let outcome = std::fs::read_to_string(folder.join("member.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<MemberOutcome>(&text).ok());
    outcome.is_some_and(|o| o.sets == member.sets && o.status == "interrupted")
        && folder.join(crate::resume::CHECKPOINT_FILE).exists()
}

/// Runs `member` with `threads` threads (a pool of its own) into `<root>/<folder>`: from the
/// checkpoint an earlier invocation that was stopped left there, or afresh, replacing whatever
/// an unfinished earlier attempt left; records the outcome in member.json.
pub fn run_member(context: &MemberContext, member: &Member, threads: usize) -> MemberOutcome {
    let folder = context.root.join(&member.folder);
    let mut sets = context.sets.clone();
    sets.extend(member.sets.iter().cloned());
    let resume = stopped_with_checkpoint(&folder, member);
    let result = (|| -> crate::error::Result<()> {
        let case = crate::case::load(&context.case_path, &sets)?;
        let options = RunOptions {
            out: Some(folder.clone()),
            progress: false,
            overwrite: !resume,
            resume,
            interrupt: context.interrupt.clone(),
            ..Default::default()
        };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.max(1)).build().map_err(|e| {
            StictionError::Output { path: folder.clone(), message: format!("cannot start {threads} threads: {e}") }
        })?;
        pool.install(|| run(&case, &options)).map(|_| ())
    })();
    let (status, error) = match result {
        Ok(()) => ("completed", None),
        // `stiction ensemble` has no --resume: running it again goes on with a stopped member
        Err(StictionError::Interrupted { time, out, resumable }) => {
            let e = StictionError::Interrupted { time, out, resumable: false };
            ("interrupted", Some(format!("{e}{}", if resumable { AGAIN } else { "" })))
        }
        Err(StictionError::RunFailed { time, message, out, resumable }) => {
            let e = StictionError::RunFailed { time, message, out, resumable: false };
            ("failed", Some(format!("{e}{}", if resumable { AGAIN } else { "" })))
        }
        Err(e) => ("failed", Some(e.to_string())),
    };
    let outcome = MemberOutcome {
        index: member.index,
        folder: member.folder.clone(),
        sets: member.sets.clone(),
        status: status.into(),
        error,
    };
    let json = serde_json::to_string_pretty(&outcome).expect("outcome serializes");
    let written = std::fs::create_dir_all(&folder)
        .map_err(|source| stiction_core::CoreError::Write { path: folder.clone(), source })
        .and_then(|_| write_atomically(&folder.join("member.json"), json.as_bytes()));
    if let Err(e) = written {
        eprintln!("warning: {}: member.json not written: {e}", member.folder);
    }
    outcome
}

//! The output folder of a run: never overwritten silently, never shared by two runs at once.
//!
//! A run goes into a new or empty folder. With `--overwrite` it may replace an earlier
//! Stiction run (a folder holding a run's `summary.json`, a sweep's `sweep-plan.json` or
//! `sweep.json`, or an ensemble member's `member.json`, each read and found to be what a
//! Stiction run writes; a file of the name alone does not make a run): it then removes only the files a
//! Stiction run writes (by name: [`written_by_stiction`]; folders only when everything in them
//! is), and refuses, naming them, when the folder holds anything else (a user's notes, data).
//!
//! A run holds a lock on its folder while it runs: [`LOCK_FILE`], holding the process id and
//! start time of its holder, removed when the run ends. A second run into a folder in use (or
//! into a folder above one in use, with `--overwrite`) is refused with the holder named; a lock
//! whose process has ended (a killed run) is stale and taken over.

use crate::error::{Result, StictionError};
use std::path::{Path, PathBuf};

/// Files that mark a folder as written by an earlier run of Stiction, each with a key its JSON
/// object holds (`sweep.json`: a list of run summaries, each with a status).
const RUN_MARKERS: [(&str, &str); 5] = [
    ("summary.json", "status"),
    ("fit-plan.json", "fingerprint"),
    ("sweep-plan.json", "fingerprint"),
    ("sweep.json", "status"),
    ("member.json", "status"),
];

/// The lock file of a folder in use.
pub const LOCK_FILE: &str = ".stiction-lock";

/// Files a run, a sweep or an ensemble writes, by exact name.
const WRITTEN_FILES: [&str; 19] = [
    "history.csv",
    "events.csv",
    "cycles.csv",
    "summary.json",
    "messages.log",
    "restart.bin",
    "sweep-plan.json",
    "sweep.json",
    "member.json",
    "ensemble-plan.json",
    "ensemble.json",
    "ensemble.csv",
    "ensemble_loading.csv",
    "ensemble_unloading.csv",
    "contact_views.pvsm",
    "fit-plan.json",
    "fit.json",
    "fit_history.csv",
    LOCK_FILE,
];

/// Stems of the plots (`.png`, `.svg`) a run writes; `combined_`, `ensemble_` and `view_`
/// (ParaView's standard views) begin families of them.
const PLOT_STEMS: [&str; 5] = ["force_approach", "area_approach", "resistance_approach", "resistance_force", "cycles"];
const PLOT_PREFIXES: [&str; 4] = ["combined_", "ensemble_", "view_", "fit_"];

/// Whether a file of this name is one a Stiction run writes: its CSV, JSON and log files, the
/// checkpoint, the VTK series (`.pvd`, `.vtu`), the points layout (`*_points.csv`), the plots,
/// and the temporary files of atomic writes (`*.tmp`).
pub fn written_by_stiction(name: &str) -> bool {
    if WRITTEN_FILES.contains(&name) {
        return true;
    }
    let ext = |e: &str| name.strip_suffix(e);
    if [".pvd", ".vtu", ".tmp"].iter().any(|e| name.ends_with(e)) || ext("_points.csv").is_some() {
        return true;
    }
    // a fit's fitted case files
    if name.starts_with("fitted-") && name.ends_with(".toml") {
        return true;
    }
    match ext(".png").or_else(|| ext(".svg")) {
        Some(stem) => PLOT_STEMS.contains(&stem) || PLOT_PREFIXES.iter().any(|p| stem.starts_with(p)),
        None => false,
    }
}

/// What in `dir` a Stiction run did not write: files by name, and folders (sweep runs,
/// ensemble members) that hold any such file; relative paths, folders with a trailing `/`.
fn foreign_entries(dir: &Path, prefix: &str) -> Vec<String> {
    let mut foreign = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().to_string();
        let path = entry.path();
        if path.is_dir() {
            // a folder is a run's (a sweep's run, an ensemble member) when all in it is
            foreign.extend(foreign_entries(&path, &format!("{prefix}{name}/")));
        } else if !written_by_stiction(&name) {
            foreign.push(format!("{prefix}{name}"));
        }
    }
    foreign.sort();
    foreign
}

/// Whether `dir` holds a run's marker file: one of [`RUN_MARKERS`], a JSON object with its key.
fn is_run_folder(dir: &Path) -> bool {
    RUN_MARKERS.iter().any(|(file, key)| {
        std::fs::read_to_string(dir.join(file))
            .ok()
            .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
            .is_some_and(|value| match value.as_array() {
                Some(runs) => runs.first().is_some_and(|run| run.get(key).is_some()),
                None => value.get(key).is_some(),
            })
    })
}

/// The process holding the lock file `path`, if it is still running (None: no lock, or a
/// stale one).
fn live_holder(path: &Path) -> Option<u32> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut words = text.split_whitespace();
    let pid: u32 = words.next()?.parse().ok()?;
    let started = words.next().map(str::to_string);
    match (process_start(pid), started) {
        // the process exists; with both start times known they must agree (a reused id)
        (Some(now), Some(then)) if now == then => Some(pid),
        (Some(_), Some(_)) => None,
        (Some(_), None) => Some(pid),
        (None, _) if cfg!(target_os = "linux") => None,
        // where processes cannot be looked up, a lock is taken as live
        (None, _) => Some(pid),
    }
}

/// A process's start time (Linux: field 22 of /proc/PID/stat), or None when it is not running.
fn process_start(pid: u32) -> Option<String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // the command name (field 2) may hold spaces: count fields after its closing parenthesis
    let after = &stat[stat.rfind(')')? + 1..];
    after.split_whitespace().nth(19).map(str::to_string)
}

/// Every live lock under `dir` (itself and the folders in it), with its holder.
fn locks_in_use(dir: &Path) -> Vec<(PathBuf, u32)> {
    let mut found = Vec::new();
    if let Some(pid) = live_holder(&dir.join(LOCK_FILE)) {
        found.push((dir.to_path_buf(), pid));
    }
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if entry.path().is_dir() {
            found.extend(locks_in_use(&entry.path()));
        }
    }
    found
}

/// Whether a run may write into `out` (see the module documentation), without touching it:
/// Ok(true) when `out` holds an earlier run that `overwrite` allows to replace.
pub fn check(out: &Path, overwrite: bool) -> Result<bool> {
    let refuse = |message: String| Err(StictionError::Output { path: out.to_path_buf(), message });
    if out.exists() && !out.is_dir() {
        return refuse("is a file, not a folder; give another --out".into());
    }
    let entries: Vec<String> = std::fs::read_dir(out)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        // a stale lock, or this process's own, does not make the folder occupied
        .filter(|n| n != LOCK_FILE || live_holder(&out.join(LOCK_FILE)).is_some_and(|p| p != std::process::id()))
        .collect();
    if entries.is_empty() {
        return Ok(false);
    }
    if let Some((folder, pid)) = locks_in_use(out).into_iter().find(|(_, pid)| *pid != std::process::id()) {
        return refuse(format!(
            "is in use by a running Stiction (process {pid}, lock file {}); wait for it to end or give another --out",
            folder.join(LOCK_FILE).display()
        ));
    }
    let earlier_run = is_run_folder(out);
    match (overwrite, earlier_run) {
        (false, true) => refuse("holds an earlier run; give --overwrite to replace it, or another --out".into()),
        (false, false) => {
            refuse(format!("is not empty ({} entries); give an empty or new folder with --out", entries.len()))
        }
        (true, false) => refuse(format!(
            "is not empty and holds no earlier run (a Stiction {}); --overwrite replaces only an earlier run's folder",
            RUN_MARKERS.map(|(file, _)| file).join(", ")
        )),
        (true, true) => {
            let foreign = foreign_entries(out, "");
            if foreign.is_empty() {
                Ok(true)
            } else {
                refuse(format!(
                    "holds files a Stiction run did not write ({}); --overwrite removes only a run's own files: \
                     move these away, or give another --out",
                    foreign.join(", ")
                ))
            }
        }
    }
}

/// Makes `out` ready for a new run: creates it, or, when `overwrite` is given and it holds an
/// earlier run and nothing else, removes that run's files (not a live lock of this process);
/// refuses a non-empty folder otherwise.
pub fn prepare(out: &Path, overwrite: bool) -> Result<()> {
    let io = |source| StictionError::Core(stiction_core::CoreError::Write { path: out.to_path_buf(), source });
    if check(out, overwrite)? {
        for entry in std::fs::read_dir(out).map_err(io)?.flatten() {
            let path = entry.path();
            if entry.file_name() == LOCK_FILE && live_holder(&path) == Some(std::process::id()) {
                continue;
            }
            if path.is_dir() { std::fs::remove_dir_all(&path) } else { std::fs::remove_file(&path) }.map_err(io)?;
        }
    }
    std::fs::create_dir_all(out).map_err(io)
}

/// Removes the temporary files of atomic writes (`<file>.tmp`, where `<file>` is one a run
/// writes) that a killed run left in `out`: called on resume, under the folder's lock.
pub fn remove_temporaries(out: &Path) -> Result<()> {
    for entry in std::fs::read_dir(out).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().to_string();
        if name.strip_suffix(".tmp").is_some_and(written_by_stiction) && entry.path().is_file() {
            std::fs::remove_file(entry.path()).map_err(|source| {
                StictionError::Core(stiction_core::CoreError::Write { path: entry.path(), source })
            })?;
        }
    }
    Ok(())
}

/// A held lock on an output folder; removed when dropped.
#[derive(Debug)]
pub struct FolderLock {
    /// The lock file this guard removes (None: the folder was already locked by this process).
    path: Option<PathBuf>,
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        if let Some(p) = &self.path {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Locks `out` for this process (creating the folder): Err names the running holder of a live
/// lock; a stale lock is taken over; a lock this process already holds is kept as it is.
pub fn lock(out: &Path) -> Result<FolderLock> {
    let io = |source| StictionError::Core(stiction_core::CoreError::Write { path: out.to_path_buf(), source });
    if out.exists() && !out.is_dir() {
        return Err(StictionError::Output { path: out.to_path_buf(), message: "is a file, not a folder".into() });
    }
    std::fs::create_dir_all(out).map_err(io)?;
    let path = out.join(LOCK_FILE);
    let me = std::process::id();
    let record = format!("{me} {}\n", process_start(me).unwrap_or_default());
    loop {
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(mut file) => {
                use std::io::Write;
                file.write_all(record.as_bytes()).map_err(io)?;
                return Ok(FolderLock { path: Some(path) });
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => match live_holder(&path) {
                Some(pid) if pid == me => return Ok(FolderLock { path: None }),
                Some(pid) => {
                    return Err(StictionError::Output {
                        path: out.to_path_buf(),
                        message: format!(
                            "is in use by a running Stiction (process {pid}, lock file {}); wait for it to end or \
                             give another --out",
                            path.display()
                        ),
                    });
                }
                // stale (its process has ended): take it over
                None => std::fs::remove_file(&path)
                    .or_else(|e| match e.kind() {
                        std::io::ErrorKind::NotFound => Ok(()),
                        _ => Err(e),
                    })
                    .map_err(io)?,
            },
            Err(e) => return Err(io(e)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("stiction-folder-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_runs_files_are_known_by_name_and_a_users_are_not() {
        for name in [
            "history.csv",
            "rough_00012.vtu",
            "rough_asperities.pvd",
            "asperities_points.csv",
            "force_approach.png",
            "combined_area_approach.svg",
            "summary.json.tmp",
            "view_contact.png",
        ] {
            assert!(written_by_stiction(name), "{name}");
        }
        for name in ["notes.txt", "my_force_approach.png", "data.csv", "report.pdf", "paper.svg"] {
            assert!(!written_by_stiction(name), "{name}");
        }
    }

    #[test]
    fn overwrite_removes_a_runs_files_only_and_refuses_a_folder_with_others() {
        let out = scratch("overwrite");
        // files of a run's names alone do not make a run
        for f in ["history.csv", "summary.json", "case_00001.vtu"] {
            std::fs::write(out.join(f), "x").unwrap();
        }
        let error = check(&out, true).unwrap_err().to_string();
        assert!(error.contains("holds no earlier run"), "{error}");
        std::fs::write(out.join("summary.json"), r#"{"status": "completed"}"#).unwrap();
        std::fs::create_dir_all(out.join("max=2")).unwrap();
        std::fs::write(out.join("max=2").join("summary.json"), "x").unwrap();
        assert!(check(&out, true).unwrap());
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        std::fs::create_dir_all(out.join("data")).unwrap();
        std::fs::write(out.join("data").join("measured.csv"), "mine").unwrap();
        let error = prepare(&out, true).unwrap_err().to_string();
        assert!(error.contains("notes.txt") && error.contains("data/measured.csv"), "{error}");
        assert!(out.join("notes.txt").exists() && out.join("history.csv").exists(), "nothing removed");
        std::fs::remove_file(out.join("notes.txt")).unwrap();
        std::fs::remove_dir_all(out.join("data")).unwrap();
        prepare(&out, true).unwrap();
        assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0);
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn a_live_lock_is_named_a_stale_one_taken_over_and_a_held_one_removed_at_the_end() {
        let out = scratch("lock");
        {
            let _held = lock(&out).unwrap();
            let text = std::fs::read_to_string(out.join(LOCK_FILE)).unwrap();
            assert!(text.starts_with(&format!("{} ", std::process::id())), "{text}");
            // this process again: kept, not removed by the inner guard
            drop(lock(&out).unwrap());
            assert!(out.join(LOCK_FILE).exists());
        }
        assert!(!out.join(LOCK_FILE).exists(), "removed when the run ends");
        // a lock of a process that has ended is stale
        let ended = std::process::Command::new("true").spawn().unwrap();
        let pid = ended.id();
        let mut ended = ended;
        ended.wait().unwrap();
        std::fs::write(out.join(LOCK_FILE), format!("{pid} 1\n")).unwrap();
        drop(lock(&out).unwrap());
        // a live process other than this one (pid 1, with its real start time) holds the folder
        if let Some(start) = process_start(1) {
            std::fs::write(out.join(LOCK_FILE), format!("1 {start}\n")).unwrap();
            let error = lock(&out).unwrap_err().to_string();
            assert!(error.contains("in use by a running Stiction (process 1"), "{error}");
            std::fs::write(out.join("summary.json"), r#"{"status": "running"}"#).unwrap();
            let error = check(&out, true).unwrap_err().to_string();
            assert!(error.contains("process 1"), "{error}");
        }
        std::fs::remove_dir_all(&out).unwrap();
    }
}

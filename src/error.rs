//! The error type of the `stiction` crate and program. Input errors exit with status 2,
//! failed runs (no convergence after cutting) with status 1, interrupted ones (Ctrl-C) with 130.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum StictionError {
    #[error("case file '{path}': {message}")]
    Case { path: PathBuf, message: String },
    #[error("case file '{path}', key '{key}': {message}")]
    CaseKey { path: PathBuf, key: String, message: String },
    #[error(transparent)]
    Mesh(#[from] stiction_meshes::MeshError),
    #[error(transparent)]
    Materials(#[from] stiction_materials::MaterialsError),
    #[error(transparent)]
    Core(#[from] stiction_core::CoreError),
    #[error(
        "the run stopped at t = {time:.6}: {message} (every converged step so far is in '{out}'{})",
        if *resumable { "; to go on from its last checkpoint, e.g. with other solver settings: the same command with --resume" } else { "" }
    )]
    RunFailed { time: f64, message: String, out: PathBuf, resumable: bool },
    #[error("output folder '{path}' {message}")]
    Output { path: PathBuf, message: String },
    #[error(
        "interrupted at t = {time:.6}; every converged step so far is in '{out}' (summary.json says \"interrupted\"){}",
        if *resumable { "; to go on from there: the same command with --resume" } else { "" }
    )]
    Interrupted { time: f64, out: PathBuf, resumable: bool },
    #[error(
        "ensemble interrupted with {completed} of {members} members complete in '{out}'; run the same command again \
         to resume (completed members are skipped)"
    )]
    EnsembleInterrupted { completed: usize, members: usize, out: PathBuf },
    #[error("fit file '{path}': {message}")]
    Fit { path: PathBuf, message: String },
    #[error("fit file '{path}', key '{key}': {message}")]
    FitKey { path: PathBuf, key: String, message: String },
    #[error("target file '{path}'{}: {message}", if *line > 0 { format!(", line {line}") } else { String::new() })]
    TargetFile { path: PathBuf, line: usize, message: String },
    #[error(
        "the fit stopped: {message} (every run so far and fit_history.csv are in '{out}'; the same command with --resume goes on)"
    )]
    FitFailed { message: String, out: PathBuf },
    #[error("fit interrupted; every completed run is in '{out}': the same command with --resume goes on from there")]
    FitInterrupted { out: PathBuf },
    #[error("no member of the ensemble completed ({members} members; see the errors in '{out}/ensemble.json')")]
    EnsembleFailed { members: usize, out: PathBuf },
}

impl StictionError {
    /// Exit status: 2 for bad input, 1 for a run that failed after starting.
    pub fn exit_code(&self) -> i32 {
        match self {
            StictionError::RunFailed { .. } => 1,
            StictionError::Interrupted { .. } | StictionError::EnsembleInterrupted { .. } => 130,
            StictionError::Mesh(stiction_meshes::MeshError::GmshInterrupted { .. }) => 130,
            StictionError::EnsembleFailed { .. } | StictionError::FitFailed { .. } => 1,
            StictionError::FitInterrupted { .. } => 130,
            StictionError::Core(stiction_core::CoreError::Write { .. }) => 1,
            _ => 2,
        }
    }
}

pub type Result<T> = std::result::Result<T, StictionError>;

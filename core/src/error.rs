//! The core crate's error type.

use std::path::PathBuf;

/// Every failure the core can report. Messages name what failed and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum CoreError {
    #[error("physical group '{name}' does not exist in the mesh (known groups: {known})")]
    UnknownGroup { name: String, known: String },
    #[error("physical group '{name}' has no {what}")]
    EmptyGroup { name: String, what: String },
    #[error("{0}")]
    Invalid(String),
    #[error("material '{material}' failed at element {element}, integration point {point}: {message}")]
    MaterialFailure { material: String, element: usize, point: usize, message: String },
    #[error("law '{law}' failed at point {point} of interface '{interface}' ({at}): {message}")]
    LawFailure { law: String, interface: String, point: usize, at: String, message: String },
    #[error("the tangent matrix could not be factorized ({0})")]
    Factorization(String),
    #[error("non-finite value in the {0}")]
    NonFinite(String),
    #[error("checkpoint '{path}': {message}")]
    Checkpoint { path: PathBuf, message: String },
    #[error("could not write '{path}': {source}")]
    Write { path: PathBuf, source: std::io::Error },
}

pub type Result<T> = std::result::Result<T, CoreError>;

//! Checkpoint files: a run's committed state written so that a later process can go on from it
//! (ABAQUS's restart, MOOSE's recover). The file is one record in postcard's compact binary
//! serde format behind a magic line, a format version and the SHA-256 of the record, written
//! atomically, so a checkpoint on disk is always a whole one: the state at one committed
//! increment. A file whose record does not match its checksum (a disk or copy error, an edit)
//! is refused, never resumed.
//!
//! What a run checkpoints and when is the step driver's business
//! ([`crate::path::driver`]: its `Checkpoint`); this module holds the file format, the
//! [`ModelState`] and the plan a run is given.

use crate::error::{CoreError, Result};
use crate::output::write_atomically;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The first bytes of every checkpoint file.
const MAGIC: &[u8] = b"stiction checkpoint\n";

/// The version of the checkpoint layout; a file of another version is refused by name (9: the
/// record's checksum).
pub const FORMAT_VERSION: u32 = 10;

/// The committed state of a model ([`crate::model::Model::saved_state`]).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ModelState {
    pub time: f64,
    /// All dofs, free and prescribed.
    pub displacement: Vec<f64>,
    /// Per element set: its material state, `n_points * n_state` numbers.
    pub sets: Vec<Vec<f64>>,
    /// Per contribution: [`crate::model::Contribution::saved_state`].
    pub contributions: Vec<Vec<f64>>,
}

/// A contribution's saved numbers ([`crate::model::Contribution::saved_state`]) read back in
/// the order they were written.
pub struct SavedNumbers<'a> {
    rest: &'a [f64],
}

impl<'a> SavedNumbers<'a> {
    /// `saved`, which must hold `expected` numbers; Err says how many it holds.
    pub fn new(saved: &'a [f64], expected: usize) -> std::result::Result<Self, String> {
        if saved.len() == expected {
            Ok(Self { rest: saved })
        } else {
            Err(format!("the checkpoint holds {} numbers of its state, this model {expected}", saved.len()))
        }
    }

    /// The next `n` numbers.
    pub fn take(&mut self, n: usize) -> &'a [f64] {
        let (head, rest) = self.rest.split_at(n);
        self.rest = rest;
        head
    }

    /// The next number.
    pub fn scalar(&mut self) -> f64 {
        self.take(1)[0]
    }
}

/// How a run writes checkpoints.
#[derive(Debug, Clone)]
pub struct CheckpointPlan {
    /// The checkpoint file (replaced by each new checkpoint).
    pub path: PathBuf,
    /// Wall time between checkpoints: one is written at the first commit at least this long
    /// after the last one (zero: at every commit), and one when the run fails or is stopped.
    pub interval: Duration,
    /// What identifies the problem (the case without its solver and output settings): a
    /// checkpoint is resumed only by a run whose fingerprint is the same.
    pub fingerprint: String,
}

/// The SHA-256 of a record.
fn checksum(body: &[u8]) -> [u8; 32] {
    use sha2::Digest;
    sha2::Sha256::digest(body).into()
}

/// Writes `record` to `path` atomically: the magic line, the format version, the record's
/// SHA-256, then the record (postcard).
pub fn write<T: Serialize>(path: &Path, record: &T) -> Result<()> {
    let body = postcard::to_allocvec(record)
        .map_err(|e| CoreError::Checkpoint { path: path.to_path_buf(), message: format!("could not encode: {e}") })?;
    let mut bytes = Vec::with_capacity(MAGIC.len() + 4 + 32 + body.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    bytes.extend_from_slice(&checksum(&body));
    bytes.extend_from_slice(&body);
    write_atomically(path, &bytes)
}

/// Reads a record written by [`write()`]; Err names the file and what is wrong with it (missing,
/// not a checkpoint, another format version, corrupted, truncated or of another layout).
pub fn read<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let fail = |message: String| CoreError::Checkpoint { path: path.to_path_buf(), message };
    let bytes = std::fs::read(path).map_err(|e| fail(format!("could not read it ({e})")))?;
    let body = bytes.strip_prefix(MAGIC).ok_or_else(|| fail("is not a Stiction checkpoint".into()))?;
    let (version, body) = body.split_first_chunk::<4>().ok_or_else(|| fail("is truncated".into()))?;
    let version = u32::from_le_bytes(*version);
    if version != FORMAT_VERSION {
        return Err(fail(format!(
            "has format version {version}, this build reads version {FORMAT_VERSION}; resume it with the \
             Stiction that wrote it"
        )));
    }
    let (sum, body) = body.split_first_chunk::<32>().ok_or_else(|| fail("is truncated".into()))?;
    if *sum != checksum(body) {
        return Err(fail(
            "is corrupted: its contents do not match the checksum written with them (a truncated copy, a disk \
             error or an edit); it cannot be resumed: start the run afresh with --overwrite"
                .into(),
        ));
    }
    postcard::from_bytes(body).map_err(|e| fail(format!("could not be decoded ({e}): of another layout")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> ModelState {
        ModelState {
            time: 0.25,
            displacement: vec![1.0, -2.5e-300, f64::MAX],
            sets: vec![vec![0.1; 7], Vec::new()],
            contributions: vec![vec![f64::INFINITY, 3.0]],
        }
    }

    #[test]
    fn a_model_state_reads_back_bit_for_bit() {
        let path = std::env::temp_dir().join(format!("stiction-checkpoint-{}.bin", std::process::id()));
        write(&path, &state()).unwrap();
        let back: ModelState = read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(back, state());
    }

    #[test]
    fn a_file_that_is_not_a_checkpoint_or_of_another_version_is_refused_by_name() {
        let path = std::env::temp_dir().join(format!("stiction-not-a-checkpoint-{}.bin", std::process::id()));
        std::fs::write(&path, b"time,force\n0,0\n").unwrap();
        let error = read::<ModelState>(&path).unwrap_err().to_string();
        assert!(
            error.contains("is not a Stiction checkpoint") && error.contains("stiction-not-a-checkpoint"),
            "{error}"
        );
        let mut other = MAGIC.to_vec();
        other.extend_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
        std::fs::write(&path, &other).unwrap();
        let error = read::<ModelState>(&path).unwrap_err().to_string();
        assert!(error.contains(&format!("format version {}", FORMAT_VERSION + 1)), "{error}");
        write(&path, &state()).unwrap();
        let whole = std::fs::read(&path).unwrap();
        std::fs::write(&path, &whole[..whole.len() - 20]).unwrap();
        let error = read::<ModelState>(&path).unwrap_err().to_string();
        assert!(error.contains("is corrupted"), "{error}");
        std::fs::write(&path, &whole[..MAGIC.len() + 10]).unwrap();
        let error = read::<ModelState>(&path).unwrap_err().to_string();
        std::fs::remove_file(&path).unwrap();
        assert!(error.contains("is truncated"), "{error}");
    }

    /// A single flipped bit anywhere in the record (a displacement, a state, the time) is
    /// found, and the file is refused rather than resumed with other numbers.
    #[test]
    fn a_checkpoint_with_any_changed_byte_is_refused_as_corrupted() {
        let path = std::env::temp_dir().join(format!("stiction-corrupted-{}.bin", std::process::id()));
        write(&path, &state()).unwrap();
        let whole = std::fs::read(&path).unwrap();
        let record_start = MAGIC.len() + 4 + 32;
        for at in [record_start, record_start + 9, whole.len() / 2, whole.len() - 1] {
            let mut changed = whole.clone();
            changed[at] ^= 0x10;
            std::fs::write(&path, &changed).unwrap();
            let error = read::<ModelState>(&path).unwrap_err().to_string();
            assert!(error.contains("is corrupted"), "byte {at}: {error}");
        }
        std::fs::remove_file(&path).unwrap();
    }
}

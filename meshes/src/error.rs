//! Errors of the mesh crate: each names the file and what was expected.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    #[error("cannot read mesh file '{path}': {source}")]
    Io { path: PathBuf, source: std::io::Error },
    #[error(
        "'{path}' is gmsh MSH version {version}; Stiction reads MSH 4.1 (ASCII or binary). Convert it with: gmsh '{path}' -save -format msh41 -o converted.msh"
    )]
    UnsupportedVersion { path: PathBuf, version: String },
    #[error("'{path}' is not a valid gmsh MSH 4.1 file: {message}")]
    Parse { path: PathBuf, message: String },
    #[error("'{path}' line {line}: {message}")]
    ParseLine { path: PathBuf, line: usize, message: String },
    #[error(
        "'{path}' contains {what} (gmsh element type {code}); supported are 2-/3-node lines, 3-/6-node triangles, 4-/10-node tetrahedra (and points, which are ignored). Re-mesh with triangles/tetrahedra, e.g. without 'Recombine', and 'Mesh.ElementOrder' 1 or 2"
    )]
    UnsupportedElement { path: PathBuf, what: String, code: i32 },
    #[error(
        "the 'gmsh' program is needed to mesh '{path}' but was not found on PATH; install it with 'apt-get install gmsh' (Debian/Ubuntu) or give a .msh file instead"
    )]
    GmshMissing { path: PathBuf },
    #[error("gmsh failed to mesh '{path}' ({status}):\n{output}")]
    GmshFailed { path: PathBuf, status: String, output: String },
    #[error(
        "gmsh did not finish meshing '{path}' within {seconds} s ({settings}); a mesh size far too small for the geometry is the usual cause. Raise the limit with mesh.time_limit if the mesh is meant to be this fine"
    )]
    GmshTimeLimit { path: PathBuf, seconds: f64, settings: String },
    #[error(
        "gmsh used {} of memory after {seconds:.0} s meshing '{path}' ({settings}), more than its limit of {}. A mesh size far too small for the geometry is the usual cause",
        gib(*used_bytes), gib(*limit_bytes)
    )]
    GmshMemoryLimit { path: PathBuf, seconds: f64, used_bytes: u64, limit_bytes: u64, settings: String },
    #[error("meshing '{path}' interrupted after {seconds:.0} s; gmsh was stopped and nothing was cached")]
    GmshInterrupted { path: PathBuf, seconds: f64 },
    #[error(
        "mesh file '{path}' is {}; reading it needs about {}, more than the {} the run may count on",
        gib(*file_bytes), gib(*needed_bytes), gib(*limit_bytes)
    )]
    TooLargeToRead { path: PathBuf, file_bytes: u64, needed_bytes: u64, limit_bytes: u64 },
}

/// Bytes as GiB (or MiB below one GiB, KiB below one MiB), for messages.
pub fn gib(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{:.1} GiB", bytes as f64 / f64::from(1u32 << 30))
    } else if bytes < 1 << 20 {
        format!("{:.0} KiB", bytes as f64 / 1024.0)
    } else {
        format!("{:.0} MiB", bytes as f64 / f64::from(1u32 << 20))
    }
}

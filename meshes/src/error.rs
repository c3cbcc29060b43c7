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
}

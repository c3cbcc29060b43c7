//! Meshing `.geo` files with the `gmsh` program, with a cache keyed by a SHA-256 of the `.geo`
//! text, the options and the gmsh version, so an unchanged input is never meshed twice.

use crate::error::MeshError;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::process::Command;

/// How to mesh a `.geo` file.
#[derive(Debug, Clone, PartialEq)]
pub struct GeoOptions {
    /// Mesh dimension (2 for axisymmetric r-z models, 3 for solids).
    pub dimension: usize,
    /// Element order, 1 or 2.
    pub order: usize,
    /// gmsh's `-clscale` factor on all mesh sizes.
    pub size_factor: f64,
    /// `-setnumber NAME VALUE` parameters passed to the `.geo` script.
    pub parameters: Vec<(String, f64)>,
}

fn gmsh_version() -> Option<String> {
    let out = Command::new("gmsh").arg("--version").output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    Some(text.trim().to_string())
}

/// Meshes `geo` into `cache_dir` (created if needed) and returns the `.msh` path.
pub fn mesh_geo(geo: &Path, options: &GeoOptions, cache_dir: &Path) -> Result<PathBuf, MeshError> {
    let text = std::fs::read(geo).map_err(|source| MeshError::Io { path: geo.to_path_buf(), source })?;
    let version = gmsh_version().ok_or_else(|| MeshError::GmshMissing { path: geo.to_path_buf() })?;
    let mut hasher = Sha256::new();
    hasher.update(&text);
    hasher.update(format!("{options:?}|{version}").as_bytes());
    let hash: String = hasher.finalize().iter().take(8).map(|b| format!("{b:02x}")).collect();
    let stem = geo.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    let out = cache_dir.join(format!("{stem}-{hash}.msh"));
    if out.exists() {
        return Ok(out);
    }
    std::fs::create_dir_all(cache_dir).map_err(|source| MeshError::Io { path: cache_dir.to_path_buf(), source })?;
    // A temporary name unique to this process and call, so concurrent runs never share it;
    // the rename into place is atomic.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = out.with_extension(format!("partial-{}-{call}.msh", std::process::id()));
    let mut cmd = Command::new("gmsh");
    cmd.arg(geo)
        .arg(format!("-{}", options.dimension))
        .arg("-order")
        .arg(options.order.to_string())
        .arg("-clscale")
        .arg(options.size_factor.to_string())
        .arg("-format")
        .arg("msh41")
        .arg("-nt")
        .arg("1");
    for (name, value) in &options.parameters {
        cmd.arg("-setnumber").arg(name).arg(value.to_string());
    }
    cmd.arg("-o").arg(&tmp);
    let result = cmd.output().map_err(|_| MeshError::GmshMissing { path: geo.to_path_buf() })?;
    if !result.status.success() || !tmp.exists() {
        let output = String::from_utf8_lossy(&result.stdout).to_string() + &String::from_utf8_lossy(&result.stderr);
        let tail: Vec<&str> = output.lines().rev().take(15).collect();
        return Err(MeshError::GmshFailed {
            path: geo.to_path_buf(),
            status: result.status.to_string(),
            output: tail.into_iter().rev().collect::<Vec<_>>().join("\n"),
        });
    }
    std::fs::rename(&tmp, &out).map_err(|source| MeshError::Io { path: out.clone(), source })?;
    Ok(out)
}

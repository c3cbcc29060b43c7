//! Meshing `.geo` files with the `gmsh` program, with a cache keyed by a SHA-256 of the `.geo`
//! text, the options and the gmsh version, so an unchanged input is never meshed twice.

use crate::error::MeshError;
use crate::msh::read_msh_within;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use stiction_core::mesh::Mesh;

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

/// What a gmsh run may use, and whom it tells how it goes.
pub struct GmshLimits<'a> {
    /// gmsh is stopped after this many seconds.
    pub time_limit_seconds: f64,
    /// gmsh is stopped once its resident memory passes this many bytes (None: no limit).
    pub memory_limit_bytes: Option<u64>,
    /// Told every [`PROGRESS_INTERVAL`] of a meshing that takes longer than that.
    pub progress: Option<&'a mut dyn FnMut(&GmshProgress)>,
    /// Asked between polls: gmsh is stopped once it says true (an interrupted program).
    pub interrupted: Option<&'a dyn Fn() -> bool>,
}

impl GmshLimits<'_> {
    /// A time limit alone: no memory limit, no progress.
    pub fn time(time_limit_seconds: f64) -> Self {
        GmshLimits { time_limit_seconds, memory_limit_bytes: None, progress: None, interrupted: None }
    }
}

/// How a gmsh run is going.
#[derive(Debug, Clone)]
pub struct GmshProgress {
    pub geo: PathBuf,
    pub elapsed_seconds: f64,
    /// gmsh's resident memory (None where it cannot be read).
    pub memory_bytes: Option<u64>,
    /// The last line gmsh wrote (e.g. "Info    : Meshing surface 1 (Plane, Frontal-Delaunay)").
    pub last_line: String,
}

/// How often a long meshing is reported, and gmsh's memory read.
pub const PROGRESS_INTERVAL: Duration = Duration::from_secs(5);
const MEMORY_INTERVAL: Duration = Duration::from_millis(250);

fn gmsh_version() -> Option<String> {
    let out = Command::new("gmsh").arg("--version").output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    Some(text.trim().to_string())
}

/// The most a gmsh run may take unless the caller says otherwise.
pub const DEFAULT_TIME_LIMIT_SECONDS: f64 = 600.0;

/// The cache file for `geo` meshed with `options` by gmsh `version`: a hash of the `.geo` text,
/// the options that shape the mesh and the gmsh version.
fn cache_path(geo: &Path, text: &[u8], options: &GeoOptions, version: &str, cache_dir: &Path) -> PathBuf {
    let mut hasher = Sha256::new();
    hasher.update(text);
    let shape = (options.dimension, options.order, options.size_factor, &options.parameters);
    hasher.update(format!("{shape:?}|{version}").as_bytes());
    let hash: String = hasher.finalize().iter().take(8).map(|b| format!("{b:02x}")).collect();
    let stem = geo.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    cache_dir.join(format!("{stem}-{hash}.msh"))
}

/// Reads a mesh gmsh made from `geo` and checks it has cells of the model's dimension (an
/// empty or truncated `.geo` gives gmsh nothing to mesh, and gmsh still exits 0).
fn read_meshed(
    msh: &Path,
    geo: &Path,
    options: &GeoOptions,
    gmsh_output: &str,
    memory_limit_bytes: Option<u64>,
) -> Result<Mesh, MeshError> {
    let gmsh_said = gmsh_flagged(gmsh_output);
    let mut mesh = read_msh_within(msh, memory_limit_bytes).map_err(|e| match e {
        e @ MeshError::TooLargeToRead { .. } => e,
        e => MeshError::GmshFailed {
            path: geo.to_path_buf(),
            status: "exit status: 0, but its mesh does not load: is the .geo empty or truncated?".into(),
            output: gmsh_said.clone().unwrap_or_else(|| e.to_string()),
        },
    })?;
    if !mesh.blocks.iter().any(|b| b.cell_type.dim() == options.dimension) {
        return Err(MeshError::GmshFailed {
            path: geo.to_path_buf(),
            status: format!(
                "exit status: 0, but it made no {}D cells: is the .geo empty or truncated?",
                options.dimension
            ),
            output: gmsh_said.unwrap_or_default(),
        });
    }
    mesh.source = format!("{} (meshed by gmsh as {})", geo.display(), msh.display());
    Ok(mesh)
}

/// Meshes `geo` with gmsh, or takes the mesh from `cache_dir` (created if needed) when the same
/// inputs were meshed before, and reads it. A mesh enters the cache only once it has loaded.
/// gmsh runs within `limits`.
pub fn mesh_geo(
    geo: &Path,
    options: &GeoOptions,
    cache_dir: &Path,
    limits: &mut GmshLimits,
) -> Result<(Mesh, PathBuf), MeshError> {
    let text = std::fs::read(geo).map_err(|source| MeshError::Io { path: geo.to_path_buf(), source })?;
    let version = gmsh_version().ok_or_else(|| MeshError::GmshMissing { path: geo.to_path_buf() })?;
    let out = cache_path(geo, &text, options, &version, cache_dir);
    if out.exists() {
        match read_meshed(&out, geo, options, "", limits.memory_limit_bytes) {
            Ok(mesh) => return Ok((mesh, out)),
            Err(e @ MeshError::TooLargeToRead { .. }) => return Err(e),
            // a cache entry that does not load (written by an older version) is meshed again
            Err(_) => {
                let _ = std::fs::remove_file(&out);
            }
        }
    }
    std::fs::create_dir_all(cache_dir).map_err(|source| MeshError::Io { path: cache_dir.to_path_buf(), source })?;
    // A temporary name unique to this process and call, so concurrent runs never share it;
    // the rename into place is atomic.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = out.with_extension(format!("partial-{}-{call}.msh", std::process::id()));
    let log = tmp.with_extension("log");
    let result = run_gmsh(geo, options, &tmp, &log, limits);
    let output = std::fs::read_to_string(&log).unwrap_or_default();
    let _ = std::fs::remove_file(&log);
    let loaded = match result {
        Err(MeshError::GmshFailed { path, status, .. }) => {
            Err(MeshError::GmshFailed { path, status, output: gmsh_messages(&output) })
        }
        Err(e) => Err(e),
        Ok(()) => {
            let errors: Vec<&str> = output.lines().filter(|l| l.starts_with("Error")).collect();
            if errors.is_empty() {
                read_meshed(&tmp, geo, options, &output, limits.memory_limit_bytes)
            } else {
                Err(MeshError::GmshFailed {
                    path: geo.to_path_buf(),
                    status: "exit status: 0, but it reported errors".into(),
                    output: errors.join("\n"),
                })
            }
        }
    };
    let mut mesh = match loaded {
        Ok(mesh) => mesh,
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            return Err(e);
        }
    };
    std::fs::rename(&tmp, &out).map_err(|source| MeshError::Io { path: out.clone(), source })?;
    mesh.source = format!("{} (meshed by gmsh as {})", geo.display(), out.display());
    Ok((mesh, out))
}

/// gmsh's errors and warnings in its output, if it gave any.
fn gmsh_flagged(output: &str) -> Option<String> {
    let flagged: Vec<&str> = output.lines().filter(|l| l.starts_with("Error") || l.starts_with("Warning")).collect();
    (!flagged.is_empty()).then(|| flagged.join("\n"))
}

/// gmsh's errors and warnings in its output, or its last 15 lines if it gave none.
fn gmsh_messages(output: &str) -> String {
    gmsh_flagged(output).unwrap_or_else(|| {
        let lines: Vec<&str> = output.lines().collect();
        lines[lines.len().saturating_sub(15)..].join("\n")
    })
}

/// Runs gmsh on `geo` into `msh`, its output into `log`, stopping it when it passes `limits`.
fn run_gmsh(
    geo: &Path,
    options: &GeoOptions,
    msh: &Path,
    log: &Path,
    limits: &mut GmshLimits,
) -> Result<(), MeshError> {
    let io = |source| MeshError::Io { path: log.to_path_buf(), source };
    let log_file = std::fs::File::create(log).map_err(io)?;
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
    cmd.arg("-o").arg(msh).stdin(Stdio::null()).stdout(log_file.try_clone().map_err(io)?).stderr(log_file);
    let mut child = cmd.spawn().map_err(|_| MeshError::GmshMissing { path: geo.to_path_buf() })?;
    let pid = sysinfo::Pid::from_u32(child.id());
    let mut system = sysinfo::System::new();
    let start = Instant::now();
    let (mut memory_read, mut reported) = (start, start);
    let mut peak_memory: Option<u64> = None;
    let stop = |child: &mut std::process::Child| {
        let _ = child.kill();
        let _ = child.wait();
        let _ = std::fs::remove_file(msh);
    };
    let settings = || {
        let mut keys = vec![format!("size_factor = {}", options.size_factor)];
        keys.extend(options.parameters.iter().map(|(k, v)| format!("{k} = {v}")));
        keys.join(", ")
    };
    let status = loop {
        if let Some(status) = child.try_wait().map_err(io)? {
            break status;
        }
        let elapsed = start.elapsed();
        if limits.interrupted.is_some_and(|interrupted| interrupted()) {
            stop(&mut child);
            return Err(MeshError::GmshInterrupted { path: geo.to_path_buf(), seconds: elapsed.as_secs_f64() });
        }
        if elapsed.as_secs_f64() > limits.time_limit_seconds {
            stop(&mut child);
            return Err(MeshError::GmshTimeLimit {
                path: geo.to_path_buf(),
                seconds: limits.time_limit_seconds,
                settings: settings(),
            });
        }
        if memory_read.elapsed() >= MEMORY_INTERVAL {
            memory_read = Instant::now();
            system.refresh_processes_specifics(
                sysinfo::ProcessesToUpdate::Some(&[pid]),
                true,
                sysinfo::ProcessRefreshKind::nothing().with_memory(),
            );
            peak_memory = system.process(pid).map(|p| p.memory()).or(peak_memory);
            if let (Some(used), Some(limit)) = (peak_memory, limits.memory_limit_bytes)
                && used > limit
            {
                stop(&mut child);
                return Err(MeshError::GmshMemoryLimit {
                    path: geo.to_path_buf(),
                    seconds: elapsed.as_secs_f64(),
                    used_bytes: used,
                    limit_bytes: limit,
                    settings: settings(),
                });
            }
        }
        if let Some(progress) = limits.progress.as_mut()
            && reported.elapsed() >= PROGRESS_INTERVAL
        {
            reported = Instant::now();
            progress(&GmshProgress {
                geo: geo.to_path_buf(),
                elapsed_seconds: elapsed.as_secs_f64(),
                memory_bytes: peak_memory,
                last_line: last_line(log),
            });
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    if !status.success() || !msh.exists() {
        let _ = std::fs::remove_file(msh);
        return Err(MeshError::GmshFailed {
            path: geo.to_path_buf(),
            status: status.to_string(),
            output: String::new(),
        });
    }
    Ok(())
}

/// The last non-empty line of a (growing) log file: read from its last few kilobytes.
fn last_line(log: &Path) -> String {
    use std::io::{Read, Seek, SeekFrom};
    let Ok(mut file) = std::fs::File::open(log) else { return String::new() };
    let len = file.metadata().map(|m| m.len()).unwrap_or(0);
    let _ = file.seek(SeekFrom::Start(len.saturating_sub(4096)));
    let mut tail = Vec::new();
    let _ = file.read_to_end(&mut tail);
    let text = String::from_utf8_lossy(&tail);
    text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("").trim().to_string()
}

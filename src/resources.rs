//! What this machine can give a run: the memory available now (the operating system's
//! "available" figure, or a container's limit where that is smaller). The size checks before
//! meshing, reading and factoring a mesh ([`crate::build::mesh`], [`crate::run`]) compare
//! against it, so that a model too large for the machine is refused with the key that made it
//! so instead of ending in an allocation failure. Also: the free disk and a folder's size (an
//! ensemble's estimate), and the process's interrupt flag (for work outside a run's increment
//! loop, such as meshing).

/// Bytes of memory available to this process now (None where the system does not say).
pub fn available_memory() -> Option<u64> {
    let mut system = sysinfo::System::new();
    system.refresh_memory();
    let available = system.available_memory();
    let limited = system.cgroup_limits().map_or(available, |c| available.min(c.free_memory));
    (limited > 0).then_some(limited)
}

pub use stiction_meshes::error::gib;

/// The program's interrupt flag: set by the Ctrl-C / SIGTERM handler the `stiction` program
/// installs, read by work that is not a run's increment loop (meshing). One per process, as the
/// signal handler is.
pub fn interrupt_flag() -> std::sync::Arc<std::sync::atomic::AtomicBool> {
    static FLAG: std::sync::OnceLock<std::sync::Arc<std::sync::atomic::AtomicBool>> = std::sync::OnceLock::new();
    FLAG.get_or_init(Default::default).clone()
}

/// Whether the program was interrupted ([`interrupt_flag`]).
pub fn interrupted() -> bool {
    interrupt_flag().load(std::sync::atomic::Ordering::SeqCst)
}

/// Bytes free on the disk that holds `path` (the mounted file system with the longest mount
/// point above it; None where none is found).
pub fn free_disk(path: &std::path::Path) -> Option<u64> {
    let path = std::fs::canonicalize(path).ok()?;
    let disks = sysinfo::Disks::new_with_refreshed_list();
    disks
        .list()
        .iter()
        .filter(|d| path.starts_with(d.mount_point()))
        .max_by_key(|d| d.mount_point().as_os_str().len())
        .map(|d| d.available_space())
}

/// Bytes of the files under `dir`.
pub fn folder_bytes(dir: &std::path::Path) -> u64 {
    std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| match e.file_type() {
            Ok(t) if t.is_dir() => folder_bytes(&e.path()),
            Ok(_) => e.metadata().map_or(0, |m| m.len()),
            Err(_) => 0,
        })
        .sum()
}

/// Bytes this process holds in memory now (its resident set; None where it cannot be read).
pub fn own_memory() -> Option<u64> {
    let pid = sysinfo::get_current_pid().ok()?;
    let mut system = sysinfo::System::new();
    system.refresh_processes_specifics(
        sysinfo::ProcessesToUpdate::Some(&[pid]),
        true,
        sysinfo::ProcessRefreshKind::nothing().with_memory(),
    );
    system.process(pid).map(|p| p.memory())
}

//! `stiction md MD.toml`: the nano-asperity experiment of the two-scale model run with LAMMPS,
//! its force against distance as the table an asperity law is calibrated from.
//!
//! - [`spec`]: the MD file (lattice, asperity, substrate, counter-body, potential, run), read
//!   and checked before anything runs;
//! - [`geometry`]: the atoms: an fcc substrate with a spherical-cap asperity grown on its
//!   lattice, and a flat counter-body above the tip;
//! - [`lammps`]: the LAMMPS data file and input it writes, the run, and the table read back;
//! - [`neck`]: the contact area, the neck's smallest cross-section.
//!
//! This part runs one approach to `run.max_approach` and back, with a rigid counter-body and the
//! potential's own adhesion; `stiction calibrate` reads its table. It does not yet scale the
//! work of adhesion or measure it, or take several maxima.

pub mod geometry;
pub mod lammps;
pub mod neck;
pub mod spec;

/// Why an MD command stopped: bad input or no LAMMPS to run (exit 2), or a LAMMPS run that
/// failed, or an output that could not be written (exit 1).
#[derive(Debug, thiserror::Error)]
pub enum MdError {
    #[error("MD file '{}', key '{key}': {message}", path.display())]
    Key { path: std::path::PathBuf, key: String, message: String },
    #[error("MD file '{}': {message}", path.display())]
    File { path: std::path::PathBuf, message: String },
    #[error("{0}")]
    LammpsMissing(String),
    #[error("{0}")]
    Lammps(String),
    #[error("cannot write '{}': {message}", path.display())]
    Output { path: std::path::PathBuf, message: String },
}

impl MdError {
    pub fn exit_code(&self) -> u8 {
        match self {
            MdError::Key { .. } | MdError::File { .. } | MdError::LammpsMissing(_) => 2,
            MdError::Lammps(_) | MdError::Output { .. } => 1,
        }
    }
}

/// What a run of the experiment gave.
#[derive(Debug, Clone)]
pub struct MdReport {
    pub atoms: usize,
    pub asperity_atoms: usize,
    pub base_atoms: usize,
    /// The table's rows (nm, nN).
    pub rows: Vec<lammps::Row>,
    /// The largest compressive and the most tensile force on the asperity (nN).
    pub max_force: f64,
    pub min_force: f64,
}

/// Runs the experiment of the MD file at `path` into `out`: `atoms.data`, `in.stiction`,
/// `log.lammps`, `loading.dat`, `unloading.dat` and `force-distance.csv`.
pub fn run(path: &std::path::Path, out: &std::path::Path) -> Result<MdReport, MdError> {
    let (spec, funcfl) = spec::load(path)?;
    let assembly = geometry::build(
        spec.lattice.constant,
        spec.substrate.width_cells,
        spec.substrate.thickness,
        spec.asperity.base_radius,
        spec.asperity.height,
        (spec.counter.thickness, spec.counter.gap),
    );
    if assembly.asperity_atoms == 0 {
        return Err(MdError::Key {
            path: path.into(),
            key: "asperity.height".into(),
            message: format!(
                "the cap holds no lattice site: make it at least a plane spacing, {} Angstrom",
                spec.lattice.constant / 2.0
            ),
        });
    }
    let rows = lammps::run(&spec, &funcfl, &assembly, out)?;
    let notes = [
        ("description", format!("nano-asperity experiment of {}", path.display())),
        (
            "provenance",
            format!(
                "stiction md with LAMMPS, EAM '{}' ({}), {} K, {} m/s, {} ps steps; not fitted to the paper's MD",
                spec.potential.file.display(),
                spec.potential.element,
                spec.run.temperature,
                spec.run.speed,
                spec.run.timestep
            ),
        ),
    ];
    lammps::write_table(&out.join("force-distance.csv"), &rows, spec.run.max_approach / 10.0, &notes)?;
    let max_force = rows.iter().map(|r| r.force).fold(f64::NEG_INFINITY, f64::max);
    let min_force = rows.iter().map(|r| r.force).fold(f64::INFINITY, f64::min);
    Ok(MdReport {
        atoms: assembly.atoms.len(),
        asperity_atoms: assembly.asperity_atoms,
        base_atoms: assembly.base_atoms,
        rows,
        max_force,
        min_force,
    })
}

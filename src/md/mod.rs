//! `stiction md MD.toml`: the nano-asperity experiment of the two-scale model run with LAMMPS,
//! its force against distance as the table an asperity law is calibrated from.
//!
//! - [`spec`]: the MD file (lattice, asperity, substrate, counter-body, potential, run), read
//!   and checked before anything runs;
//! - [`geometry`]: the atoms: an fcc substrate with a spherical-cap asperity grown on its
//!   lattice, and a flat counter-body above the tip;
//! - [`eam`]: the potential, rewritten with the interaction across the interface scaled;
//! - [`adhesion`]: the work of adhesion that interaction gives, measured on flat slabs, and the
//!   scale that gives a target;
//! - [`lammps`]: the LAMMPS data file and input it writes, the run, and the table read back;
//! - [`neck`]: the contact area, the neck's smallest cross-section.
//!
//! The counter-body is rigid and the lattice fcc; `stiction calibrate` reads the table, whose
//! `# work_of_adhesion` line is the measured one.

pub mod adhesion;
pub mod eam;
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
    /// A work of adhesion the cross scale cannot reach (the caller names the key).
    #[error("{0}")]
    Target(String),
    #[error("{0}")]
    Lammps(String),
    #[error("cannot write '{}': {message}", path.display())]
    Output { path: std::path::PathBuf, message: String },
}

impl MdError {
    pub fn exit_code(&self) -> u8 {
        match self {
            MdError::Key { .. } | MdError::File { .. } | MdError::LammpsMissing(_) | MdError::Target(_) => 2,
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
    /// How each unloading branch ended, in the order of the maxima.
    pub branches: Vec<lammps::BranchEnd>,
    /// The cross scale of the interaction across the interface, and the work of adhesion
    /// measured with it (J/m^2).
    pub cross_scale: f64,
    pub work_of_adhesion: f64,
    /// The largest compressive and the most tensile force on the asperity (nN).
    pub max_force: f64,
    pub min_force: f64,
}

/// Runs the experiment of the MD file at `path` into `out`: `atoms.data`, `in.stiction`,
/// `log.lammps`, `loading.dat`, `unloading.dat` and `force-distance.csv`.
pub fn run(path: &std::path::Path, out: &std::path::Path) -> Result<MdReport, MdError> {
    let (spec, tables) = spec::load(path)?;
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
    lammps::prepare_folder(out)?;
    let a = spec.lattice.constant;
    let element = &spec.potential.element;
    let dir = out.join("adhesion");
    let (cross_scale, work_of_adhesion) = match spec.adhesion.work_of_adhesion {
        Some(target) => {
            adhesion::scale_for(&tables, element, a, target, spec.adhesion.tolerance, &dir).map_err(|e| match e {
                MdError::Target(message) => {
                    MdError::Key { path: path.into(), key: "adhesion.work_of_adhesion".into(), message }
                }
                e => e,
            })?
        }
        None => {
            let s = spec.adhesion.cross_scale.unwrap_or(1.0);
            (s, adhesion::measure(&tables, element, a, s, &dir)?)
        }
    };
    let names = eam::element_names(element);
    let potential = eam::fs_file(&tables, [&names[0], &names[1]], cross_scale);
    let (rows, branches) = lammps::run(&spec, &tables, &potential, &assembly, out)?;
    let notes = [
        ("description", format!("nano-asperity experiment of {}", path.display())),
        (
            "provenance",
            format!(
                "stiction md with LAMMPS, EAM '{}' ({}), cross scale {cross_scale:.4}, {} K, {} m/s, {} ps steps; not fitted to the paper's MD",
                spec.potential.file.display(),
                spec.potential.element,
                spec.run.temperature,
                spec.run.speed,
                spec.run.timestep
            ),
        ),
        ("work_of_adhesion", format!("{work_of_adhesion:.6}")),
    ];
    lammps::write_table(&out.join("force-distance.csv"), &rows, &notes)?;
    let max_force = rows.iter().map(|r| r.force).fold(f64::NEG_INFINITY, f64::max);
    let min_force = rows.iter().map(|r| r.force).fold(f64::INFINITY, f64::min);
    Ok(MdReport {
        atoms: assembly.atoms.len(),
        asperity_atoms: assembly.asperity_atoms,
        base_atoms: assembly.base_atoms,
        rows,
        branches,
        cross_scale,
        work_of_adhesion,
        max_force,
        min_force,
    })
}

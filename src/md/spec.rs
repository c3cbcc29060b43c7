//! The MD file (TOML; LAMMPS `metal` units: lengths in Angstrom, time in ps, speeds in m/s as the
//! paper gives them, temperature in K).
//!
//! ```toml
//! [lattice]
//! constant = 4.08            # the fcc lattice constant a (Au), matching the potential's
//! [substrate]
//! width_cells = 8            # the periodic box's side, in cubic cells
//! thickness = 12.0           # (001) planes below this height; the lowest two are held fixed
//! [asperity]
//! base_radius = 10.0         # a spherical cap grown on the substrate's lattice
//! height = 8.0
//! [counter]
//! thickness = 6.0            # a flat, rigid (001) slab over the tip
//! gap = 4.0                  # between the tip atom and the counter's lowest plane, at the start
//! [potential]
//! file = "/usr/share/lammps/potentials/Au_u3.eam"
//! element = "Au"             # DYNAMO funcfl EAM: one element
//! [adhesion]                 # optional: the interaction across the interface
//! work_of_adhesion = 1.0     # J/m^2, reached by a cross scale; or cross_scale = 0.45
//! tolerance = 0.01           # relative, on work_of_adhesion
//! [run]
//! temperature = 300.0
//! timestep = 0.002           # ps
//! speed = 7.0                # m/s, the counter's
//! max_approach = [1.0, 2.0]  # Angstrom: an unloading branch from each
//! pull_back = -12.0          # Angstrom, where each unloading ends (default: the start)
//! average_steps = 50         # steps per row of the table, and per dump frame
//! processes = 1              # MPI processes for LAMMPS
//! seed = 1
//! ```

use super::MdError;
use super::eam::{FuncflTables, read_funcfl_tables};
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MdSpec {
    pub lattice: LatticeSpec,
    pub substrate: SubstrateSpec,
    pub asperity: AsperitySpec,
    pub counter: CounterSpec,
    pub potential: PotentialSpec,
    pub run: RunSpec,
    #[serde(default)]
    pub adhesion: AdhesionSpec,
}

/// The interaction across the interface (asperity and counter-body): the potential's own
/// (neither key), scaled by `cross_scale`, or scaled to give `work_of_adhesion`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdhesionSpec {
    /// The factor on the cross terms of the potential (pair energy and density).
    pub cross_scale: Option<f64>,
    /// The (001) flat-on-flat work of adhesion to reach (J/m^2), by the cross scale.
    pub work_of_adhesion: Option<f64>,
    /// The relative tolerance on `work_of_adhesion`.
    #[serde(default = "one_percent")]
    pub tolerance: f64,
}

fn one_percent() -> f64 {
    0.01
}

impl Default for AdhesionSpec {
    fn default() -> Self {
        AdhesionSpec { cross_scale: None, work_of_adhesion: None, tolerance: one_percent() }
    }
}

/// One number or a list of them.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum OneOrMany {
    One(f64),
    Many(Vec<f64>),
}

impl OneOrMany {
    pub fn values(&self) -> Vec<f64> {
        match self {
            OneOrMany::One(v) => vec![*v],
            OneOrMany::Many(v) => v.clone(),
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeSpec {
    /// The cubic fcc lattice constant (Angstrom).
    pub constant: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubstrateSpec {
    /// The periodic box's side in cubic cells.
    pub width_cells: usize,
    /// The substrate holds the (001) planes below this height (Angstrom).
    pub thickness: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AsperitySpec {
    /// The cap's base radius on the substrate (Angstrom).
    pub base_radius: f64,
    /// The cap's height above the substrate (Angstrom).
    pub height: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterSpec {
    /// The counter-body's thickness (Angstrom).
    pub thickness: f64,
    /// The gap between the tip atom and the counter's lowest plane at the start (Angstrom).
    pub gap: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PotentialSpec {
    /// A DYNAMO funcfl EAM file (`pair_style eam`), relative to the MD file.
    pub file: PathBuf,
    /// The element's symbol; the file's atomic number must be its.
    pub element: String,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    /// Thermostat temperature (K).
    pub temperature: f64,
    /// Time step (ps).
    pub timestep: f64,
    /// The counter-body's speed (m/s).
    pub speed: f64,
    /// The approaches at which unloading branches are taken (Angstrom): one, or a list in
    /// increasing order. The loading runs on to the largest; each unloading starts from a state
    /// saved on the way.
    pub max_approach: OneOrMany,
    /// The approach each unloading runs back to (Angstrom); the start's, a / 2 - gap, when
    /// not given.
    pub pull_back: Option<f64>,
    /// The time steps averaged into one row of the table; the atoms are dumped as often.
    #[serde(default = "fifty")]
    pub average_steps: usize,
    /// The MPI processes LAMMPS runs on (`mpirun -np`); 1 runs `lmp` alone.
    #[serde(default = "one_process")]
    pub processes: usize,
    /// The seed of the initial velocities and the thermostat's noise.
    #[serde(default = "one")]
    pub seed: u64,
}

fn one() -> u64 {
    1
}

fn fifty() -> usize {
    50
}

fn one_process() -> usize {
    1
}

/// The largest distance the counter may move in one time step, in lattice constants: a step
/// that moves it farther jolts the atoms it touches.
pub const MAX_STEP_MOTION: f64 = 1e-3;

/// The atomic numbers of the elements a funcfl file may hold (the common EAM metals).
pub fn atomic_number(symbol: &str) -> Option<u32> {
    let table = [
        ("Al", 13),
        ("Ni", 28),
        ("Cu", 29),
        ("Ru", 44),
        ("Rh", 45),
        ("Pd", 46),
        ("Ag", 47),
        ("Ir", 77),
        ("Pt", 78),
        ("Au", 79),
        ("Pb", 82),
    ];
    table.iter().find(|(s, _)| *s == symbol).map(|&(_, z)| z)
}

/// Reads and checks the MD file: every number in range, the potential's element and lattice
/// the file's, a time step the speed allows.
pub fn load(path: &Path) -> Result<(MdSpec, FuncflTables), MdError> {
    let file = |message: String| MdError::File { path: path.into(), message };
    let text = std::fs::read_to_string(path).map_err(|e| file(format!("cannot read it: {e}")))?;
    let mut spec: MdSpec = toml::from_str(&text).map_err(|e| file(e.to_string()))?;
    let key = |k: &str, message: String| MdError::Key { path: path.into(), key: k.into(), message };
    let positive = [
        ("lattice.constant", spec.lattice.constant),
        ("substrate.thickness", spec.substrate.thickness),
        ("asperity.base_radius", spec.asperity.base_radius),
        ("asperity.height", spec.asperity.height),
        ("counter.thickness", spec.counter.thickness),
        ("counter.gap", spec.counter.gap),
        ("run.temperature", spec.run.temperature),
        ("run.timestep", spec.run.timestep),
        ("run.speed", spec.run.speed),
    ];
    for (k, v) in positive {
        if !(v.is_finite() && v > 0.0) {
            return Err(key(k, format!("must be a finite number > 0, got {v}")));
        }
    }
    check_path(&spec, &key)?;
    check_adhesion(&spec.adhesion, &key)?;
    if spec.substrate.width_cells < 2 {
        return Err(key("substrate.width_cells", format!("must be at least 2, got {}", spec.substrate.width_cells)));
    }
    let a = spec.lattice.constant;
    if 2.0 * spec.asperity.base_radius > (spec.substrate.width_cells as f64 - 1.0) * a {
        return Err(key(
            "asperity.base_radius",
            format!(
                "a base of diameter {} does not fit a box of {} cells ({} Angstrom) with a cell to spare: the asperity would touch its periodic image",
                2.0 * spec.asperity.base_radius,
                spec.substrate.width_cells,
                spec.substrate.width_cells as f64 * a
            ),
        ));
    }
    let per_step = spec.run.speed * 0.01 * spec.run.timestep;
    if per_step > MAX_STEP_MOTION * a {
        return Err(key(
            "run.timestep",
            format!(
                "at {} m/s the counter moves {per_step:.3e} Angstrom per step of {} ps; at most {:.3e} (a thousandth of the lattice constant): take a time step of at most {:.3e} ps",
                spec.run.speed,
                spec.run.timestep,
                MAX_STEP_MOTION * a,
                MAX_STEP_MOTION * a / (spec.run.speed * 0.01)
            ),
        ));
    }
    let base = path.parent().unwrap_or(Path::new("."));
    // absolute: LAMMPS runs in the output folder
    spec.potential.file = std::path::absolute(base.join(&spec.potential.file))
        .map_err(|e| key("potential.file", format!("'{}': {e}", spec.potential.file.display())))?;
    let funcfl = read_funcfl_tables(&spec.potential.file).map_err(|m| key("potential.file", m))?;
    let z = atomic_number(&spec.potential.element).ok_or_else(|| {
        key("potential.element", format!("'{}' is not an element this reader knows", spec.potential.element))
    })?;
    if z != funcfl.atomic_number {
        return Err(key(
            "potential.element",
            format!(
                "'{}' (Z = {z}) is not the element of '{}' (Z = {})",
                spec.potential.element,
                spec.potential.file.display(),
                funcfl.atomic_number
            ),
        ));
    }
    if !funcfl.structure.eq_ignore_ascii_case("fcc") {
        return Err(key(
            "potential.file",
            format!("its element is {}, not fcc: only fcc lattices are built", funcfl.structure),
        ));
    }
    if (a / funcfl.lattice_constant - 1.0).abs() > 0.02 {
        return Err(key(
            "lattice.constant",
            format!("{a} Angstrom does not match the potential's {} (2%)", funcfl.lattice_constant),
        ));
    }
    Ok((spec, funcfl))
}

/// The run's path: maxima in increasing order past the start, a pull-back below them, at
/// least one step per row and one process.
fn check_path(spec: &MdSpec, key: &dyn Fn(&str, String) -> MdError) -> Result<(), MdError> {
    let maxima = spec.run.max_approach.values();
    if maxima.is_empty() || maxima.iter().any(|m| !m.is_finite()) || maxima.windows(2).any(|w| w[1] <= w[0]) {
        return Err(key(
            "run.max_approach",
            format!("expected a finite number or a list of them in increasing order, got {maxima:?}"),
        ));
    }
    let start = spec.lattice.constant / 2.0 - spec.counter.gap;
    if maxima[0] <= start {
        return Err(key(
            "run.max_approach",
            format!("{} Angstrom is not past the start's approach, a / 2 - counter.gap = {start} Angstrom", maxima[0]),
        ));
    }
    if let Some(p) = spec.run.pull_back
        && !(p.is_finite() && p < maxima[0])
    {
        return Err(key(
            "run.pull_back",
            format!("must be a finite approach below the smallest max_approach ({} Angstrom), got {p}", maxima[0]),
        ));
    }
    if spec.run.average_steps == 0 {
        return Err(key("run.average_steps", "must be at least 1".into()));
    }
    if spec.run.processes == 0 {
        return Err(key("run.processes", "must be at least 1".into()));
    }
    Ok(())
}

/// The interaction across the interface: one of the scale and the target, each in range.
fn check_adhesion(adhesion: &AdhesionSpec, key: &dyn Fn(&str, String) -> MdError) -> Result<(), MdError> {
    match (adhesion.cross_scale, adhesion.work_of_adhesion) {
        (Some(_), Some(_)) => {
            return Err(key(
                "adhesion.work_of_adhesion",
                "give cross_scale or work_of_adhesion, not both (the scale is found from the work)".into(),
            ));
        }
        (Some(s), None) if !(s.is_finite() && s >= 0.0) => {
            return Err(key("adhesion.cross_scale", format!("must be a finite number >= 0, got {s}")));
        }
        (None, Some(w)) if !(w.is_finite() && w > 0.0) => {
            return Err(key("adhesion.work_of_adhesion", format!("must be a finite number > 0 (J/m^2), got {w}")));
        }
        _ => {}
    }
    let t = adhesion.tolerance;
    if !(t.is_finite() && t > 0.0 && t < 0.5) {
        return Err(key("adhesion.tolerance", format!("must lie in (0, 0.5), got {t}")));
    }
    Ok(())
}

//! The LAMMPS side: the data file (`atoms.data`: types 1 fixed base, 2 mobile, 3 counter-body)
//! and the input (`in.stiction`) this writes, the run (`lmp`, or `mpirun -np N lmp`, its log
//! kept in `log.lammps`), and the force-distance table read back from the averaged outputs.
//!
//! The input, in `metal` units: periodic in x and y; `eam/fs` with the cross-scaled potential
//! ([`super::eam`]); the base held (zero force and velocity); the mobile atoms integrated
//! (`nve`) with a Langevin bath on the substrate's mobile planes (damping 0.1 ps); the counter
//! moved rigidly (`fix move`) down at the speed through each maximum to the largest, the state
//! saved at each (`branch-K.restart`), then up to the pull-back from the largest and from each
//! saved state in turn. The force on the counter along z (`fcm`, positive when the asperity
//! pushes it away) and its height are averaged over every `run.average_steps` steps (`fix
//! ave/time`) into `loading.dat` and `unloading-K.dat`; the atoms are dumped at the same steps
//! (`loading.lammpstrj`, `unloading-K.lammpstrj`, which OVITO and ParaView open) for the neck's
//! area ([`super::neck`]).
//!
//! It does not know what the table is fitted to, or how the work of adhesion was chosen.

use super::MdError;
use super::eam::FuncflTables;
use super::geometry::{Assembly, Part};
use super::spec::MdSpec;
use std::path::{Path, PathBuf};

/// eV / Angstrom in nN.
pub const EV_PER_ANGSTROM_IN_NN: f64 = 1.602_176_634;

/// The data file's text; the box reaches 10 Angstrom over the counter's top once it has been
/// lifted by `lift` above its start (the farthest an unloading takes it).
pub fn data_file(assembly: &Assembly, funcfl: &FuncflTables, lift: f64) -> String {
    let top = assembly.atoms.iter().map(|(x, _)| x[2]).fold(f64::NEG_INFINITY, f64::max) + lift.max(0.0);
    let mut text = format!(
        "stiction md: {} atoms\n\n{} atoms\n3 atom types\n\n0 {w} xlo xhi\n0 {w} ylo yhi\n-10 {} zlo zhi\n\nMasses\n\n1 {m}\n2 {m}\n3 {m}\n\nAtoms # atomic\n\n",
        assembly.atoms.len(),
        assembly.atoms.len(),
        top + 10.0,
        w = assembly.width,
        m = funcfl.mass
    );
    for (k, (x, part)) in assembly.atoms.iter().enumerate() {
        let t = match part {
            Part::Base => 1,
            Part::Mobile => 2,
            Part::Counter => 3,
        };
        text.push_str(&format!("{} {t} {:.8} {:.8} {:.8}\n", k + 1, x[0], x[1], x[2]));
    }
    text
}

/// The time steps that move the counter `distance` Angstrom at the run's speed (at least one).
pub fn leg_steps(spec: &MdSpec, distance: f64) -> usize {
    let per_step = spec.run.speed * 0.01 * spec.run.timestep; // m/s = 0.01 Angstrom/ps
    ((distance / per_step).round() as usize).max(1)
}

/// The commands that set the potential, the fixes that hold, integrate and thermostat, the
/// measured variables and the time step: the input's start, and again after a restart (which
/// keeps atoms, velocities and groups but none of these).
fn setup(spec: &MdSpec, names: &[String; 2]) -> String {
    format!(
        "pair_style eam/fs\n\
         pair_coeff * * cross.eam.fs {a} {a} {b}\n\
         neighbor 2.0 bin\n\
         neigh_modify every 1 delay 0 check yes\n\
         fix hold base setforce 0.0 0.0 0.0\n\
         fix integrate mobile nve\n\
         fix thermostat bath langevin {t} {t} 0.1 {seed}\n\
         variable fz equal fcm(counter,z)\n\
         variable zc equal xcm(counter,z)\n\
         timestep {dt}\n\
         thermo {avg}\n",
        a = names[0],
        b = names[1],
        t = spec.run.temperature,
        seed = spec.run.seed,
        dt = spec.run.timestep,
        avg = spec.run.average_steps,
    )
}

/// One leg: the counter moved at `velocity` (Angstrom/ps) for `steps`, averaged into
/// `{name}.dat` and dumped into `{name}.lammpstrj`, then the leg's fixes and dump removed.
fn leg(name: &str, velocity: f64, average: usize, runs: &[(usize, Option<String>)]) -> String {
    // an ID of its own: a fix move of the loading's ID defined after a restart would take up
    // the loading's saved origin and jump the counter
    let id = name.replace('-', "_");
    let mut text = format!(
        "fix move_{id} counter move linear 0.0 0.0 {velocity}\n\
         fix table all ave/time 1 {avg} {avg} v_zc v_fz file {name}.dat\n\
         dump frames all custom {avg} {name}.lammpstrj id type x y z\n\
         dump_modify frames sort id\n",
        avg = average
    );
    for (steps, then) in runs {
        text.push_str(&format!("run {steps}\n"));
        if let Some(command) = then {
            text.push_str(command);
            text.push('\n');
        }
    }
    text.push_str(&format!("undump frames\nunfix table\nunfix move_{id}\n"));
    text
}

/// The input script's text: load to each maximum in turn, saving the state there
/// (`branch-K.restart`), unload from the largest, then from each saved state in turn.
pub fn input_file(spec: &MdSpec, assembly: &Assembly, names: &[String; 2]) -> String {
    let a = spec.lattice.constant;
    let speed = spec.run.speed * 0.01;
    let start = assembly.start_approach(a);
    let maxima = spec.run.max_approach.values();
    let back = spec.run.pull_back.unwrap_or(start);
    let bath_top = 2.0 * a; // the substrate's planes from a to 2 a: above the fixed ones
    let mut text = format!(
        "# written by stiction md\n\
         units metal\n\
         atom_style atomic\n\
         boundary p p f\n\
         read_data atoms.data\n\
         group base type 1\n\
         group mobile type 2\n\
         group counter type 3\n\
         region bath block INF INF INF INF INF {bath_top}\n\
         group inbath region bath\n\
         group bath intersect inbath mobile\n\
         velocity mobile create {t} {seed} dist gaussian\n\
         velocity base set 0.0 0.0 0.0\n\
         velocity counter set 0.0 0.0 0.0\n{setup}",
        t = spec.run.temperature,
        seed = spec.run.seed,
        setup = setup(spec, names),
    );
    let n = maxima.len();
    let mut runs = Vec::new();
    let mut previous = start;
    for (k, m) in maxima.iter().enumerate() {
        let save = (k + 1 < n).then(|| format!("write_restart branch-{}.restart", k + 1));
        runs.push((leg_steps(spec, m - previous), save));
        previous = *m;
    }
    text.push_str("# loading, through each maximum\n");
    text.push_str(&leg("loading", -speed, spec.run.average_steps, &runs));
    for k in (1..=n).rev() {
        text.push_str(&format!("# unloading from maximum {k}, {} Angstrom\n", maxima[k - 1]));
        if k < n {
            text.push_str(&format!("clear\nread_restart branch-{k}.restart\n{}", setup(spec, names)));
        }
        let steps = leg_steps(spec, maxima[k - 1] - back);
        text.push_str(&leg(&format!("unloading-{k}"), speed, spec.run.average_steps, &[(steps, None)]));
    }
    text
}

/// One row of the table: approach (nm), force on the asperity (nN, positive compressive), the
/// neck's area (nm^2), branch and the branch's maximum approach (nm; the largest on loading).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub step: u64,
    pub distance: f64,
    pub force: f64,
    pub area: f64,
    pub loading: bool,
    pub max_distance: f64,
}

/// How an unloading branch ended.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchEnd {
    /// The branch's maximum approach (nm).
    pub max_distance: f64,
    /// Whether the branch had a neck at all.
    pub touched: bool,
    /// The approach at which the neck broke, the first row from which its area stays zero
    /// (nm); None when it still held at the pull-back.
    pub separated_at: Option<f64>,
    /// The last row's approach, area and force (nm, nm^2, nN).
    pub last: (f64, f64, f64),
    /// The asperity's atoms detached from the substrate at the pull-back: carried off by the
    /// counter-body when the neck broke inside the metal, none when it broke at the interface.
    pub detached: usize,
}

/// Where the neck broke on an unloading branch: the first row from which the area stays zero,
/// after some contact. None when the last row still has area (or the branch never touched).
pub fn separation_row(rows: &[Row]) -> Option<usize> {
    let last_contact = rows.iter().rposition(|r| r.area > 0.0)?;
    (last_contact + 1 < rows.len()).then_some(last_contact + 1)
}

/// The frames of a `dump custom id type x y z` file: per time step, each atom's type and
/// position.
pub fn read_frames(text: &str) -> Result<std::collections::HashMap<u64, Vec<(u32, [f64; 3])>>, String> {
    let mut frames = std::collections::HashMap::new();
    let mut lines = text.lines().enumerate();
    while let Some((k, line)) = lines.next() {
        if line.trim() != "ITEM: TIMESTEP" {
            return Err(format!("line {}: expected 'ITEM: TIMESTEP', found '{line}'", k + 1));
        }
        let mut next = |what: &str| {
            lines.next().map(|(k, l)| (k, l.trim().to_string())).ok_or_else(|| format!("ends before {what}"))
        };
        let (k, step) = next("the time step")?;
        let step: u64 = step.parse().map_err(|_| format!("line {}: a time step, found '{step}'", k + 1))?;
        next("ITEM: NUMBER OF ATOMS")?;
        let (k, count) = next("the number of atoms")?;
        let count: usize = count.parse().map_err(|_| format!("line {}: a number of atoms, found '{count}'", k + 1))?;
        for _ in 0..4 {
            next("the box bounds")?;
        }
        let (k, header) = next("ITEM: ATOMS")?;
        if header != "ITEM: ATOMS id type x y z" {
            return Err(format!("line {}: expected 'ITEM: ATOMS id type x y z', found '{header}'", k + 1));
        }
        let mut atoms = Vec::with_capacity(count);
        for _ in 0..count {
            let (k, l) = next("an atom")?;
            let v: Vec<f64> = l
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|_| format!("line {}: '{l}'", k + 1))?;
            if v.len() != 5 {
                return Err(format!("line {}: expected 'id type x y z', found '{l}'", k + 1));
            }
            atoms.push((v[1] as u32, [v[2], v[3], v[4]]));
        }
        frames.insert(step, atoms);
    }
    Ok(frames)
}

/// The rows of an `ave/time` file of `v_zc v_fz`: the approach from the counter's height
/// (its start `zc0` where the approach is `start`), in nm and nN; the area is filled in later.
pub fn read_leg(text: &str, zc0: f64, start: f64, loading: bool) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate().filter(|(_, l)| !l.trim_start().starts_with('#') && !l.trim().is_empty())
    {
        let v: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| format!("line {}: '{line}'", k + 1))?;
        if v.len() != 3 {
            return Err(format!("line {}: expected 'step zc fz', found '{line}'", k + 1));
        }
        rows.push(Row {
            step: v[0] as u64,
            distance: (start + zc0 - v[1]) / 10.0,
            force: v[2] * EV_PER_ANGSTROM_IN_NN,
            area: 0.0,
            loading,
            max_distance: 0.0,
        });
    }
    Ok(rows)
}

/// The LAMMPS executable: `STICTION_LAMMPS`, else `lmp` on the PATH.
pub fn executable() -> PathBuf {
    std::env::var_os("STICTION_LAMMPS").map(PathBuf::from).unwrap_or_else(|| PathBuf::from("lmp"))
}

/// Runs LAMMPS on the input `input` in the folder `dir`, its log into `log`, on `processes`
/// MPI processes (`mpirun -np`, or `STICTION_MPIRUN`, when more than one). A LAMMPS that is
/// missing or fails is an error naming the log and its last error line.
pub fn run_lammps(dir: &Path, input: &str, log: &str, processes: usize) -> Result<(), MdError> {
    let lmp = executable();
    let mpirun = std::env::var_os("STICTION_MPIRUN").map(PathBuf::from).unwrap_or_else(|| PathBuf::from("mpirun"));
    let mut command = if processes > 1 {
        let mut c = std::process::Command::new(&mpirun);
        c.arg("-np").arg(processes.to_string()).arg(&lmp);
        // Open MPI refuses to start as root unless told: CI containers run as root
        c.env("OMPI_ALLOW_RUN_AS_ROOT", "1").env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
        c
    } else {
        std::process::Command::new(&lmp)
    };
    let status = command
        .args(["-in", input, "-log", log, "-screen", "none"])
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null()) // MPI's abort notice; the log holds LAMMPS's error
        .status()
        .map_err(|e| {
            MdError::LammpsMissing(if processes > 1 {
                format!(
                    "cannot run '{}' for run.processes = {processes} ({e}); install Open MPI (Debian: apt-get install openmpi-bin), set STICTION_MPIRUN, or take run.processes = 1",
                    mpirun.display()
                )
            } else {
                format!(
                    "cannot run LAMMPS ('{}': {e}); install it (Debian: apt-get install lammps lammps-data) or set STICTION_LAMMPS",
                    lmp.display()
                )
            })
        })?;
    if !status.success() {
        let log = dir.join(log);
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        let last = text.lines().rev().find(|l| l.contains("ERROR")).unwrap_or("no ERROR line");
        return Err(MdError::Lammps(format!("LAMMPS failed ({status}); its log is '{}': {last}", log.display())));
    }
    Ok(())
}

/// Writes the files into `out` (which [`prepare_folder`] made), the potential `potential`
/// among them, runs LAMMPS there and returns the table (loading, then each unloading branch up
/// to where its neck broke) and how each branch ended. A LAMMPS that is missing or fails is an
/// error naming its log and last error line.
pub fn run(
    spec: &MdSpec,
    funcfl: &FuncflTables,
    potential: &str,
    assembly: &Assembly,
    out: &Path,
) -> Result<(Vec<Row>, Vec<BranchEnd>), MdError> {
    let write = |name: &str, text: &str| {
        let path = out.join(name);
        stiction_core::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| MdError::Output { path: path.clone(), message: e.to_string() })
    };
    let start = assembly.start_approach(spec.lattice.constant);
    write("atoms.data", &data_file(assembly, funcfl, start - spec.run.pull_back.unwrap_or(start)))?;
    write("cross.eam.fs", potential)?;
    let names = super::eam::element_names(&spec.potential.element);
    write("in.stiction", &input_file(spec, assembly, &names))?;
    run_lammps(out, "in.stiction", "log.lammps", spec.run.processes)?;
    let zc0 = counter_height(assembly);
    let a = spec.lattice.constant;
    let maxima = spec.run.max_approach.values();
    let read = |name: String| {
        let path = out.join(name);
        std::fs::read_to_string(&path)
            .map(|t| (path.clone(), t))
            .map_err(|e| MdError::Lammps(format!("'{}': {e}", path.display())))
    };
    // the rows of a leg, and the atoms detached from the substrate at its end
    let leg_rows = |leg: &str, loading: bool, max_distance: f64| -> Result<(Vec<Row>, usize), MdError> {
        let (path, text) = read(format!("{leg}.dat"))?;
        let mut rows =
            read_leg(&text, zc0, start, loading).map_err(|m| MdError::Lammps(format!("'{}' {m}", path.display())))?;
        let (path, text) = read(format!("{leg}.lammpstrj"))?;
        let frames = read_frames(&text).map_err(|m| MdError::Lammps(format!("'{}' {m}", path.display())))?;
        for row in &mut rows {
            let atoms = frames
                .get(&row.step)
                .ok_or_else(|| MdError::Lammps(format!("'{}' has no frame at step {}", path.display(), row.step)))?;
            let mobile: Vec<[f64; 3]> = atoms.iter().filter(|(t, _)| *t == 2).map(|(_, x)| *x).collect();
            let bottom = atoms.iter().filter(|(t, _)| *t == 3).map(|(_, x)| x[2]).fold(f64::INFINITY, f64::min);
            row.area = super::neck::neck_area(&mobile, assembly.substrate_top, bottom, assembly.width, a) / 100.0;
            row.max_distance = max_distance;
        }
        let detached = frames.keys().max().map_or(0, |last| {
            let mobile: Vec<[f64; 3]> = frames[last].iter().filter(|(t, _)| *t == 2).map(|(_, x)| *x).collect();
            super::neck::detached(&mobile, assembly.substrate_top, assembly.width, a)
        });
        Ok((rows, detached))
    };
    let (mut rows, _) = leg_rows("loading", true, maxima[maxima.len() - 1] / 10.0)?;
    // the loading branch starts at the jump-in: the row before the first with a neck (before
    // it, the potential's long-range tail, which the asperity law takes as no force)
    if let Some(first) = rows.iter().position(|r| r.area > 0.0) {
        rows.drain(..first.saturating_sub(1));
    }
    let mut ends = Vec::new();
    for (k, m) in maxima.iter().enumerate() {
        let (mut branch, detached) = leg_rows(&format!("unloading-{}", k + 1), false, m / 10.0)?;
        let cut = separation_row(&branch);
        if let Some(i) = cut {
            branch.truncate(i + 1);
        }
        let last = branch.last().map_or((f64::NAN, 0.0, 0.0), |r| (r.distance, r.area, r.force));
        let touched = branch.iter().any(|r| r.area > 0.0);
        ends.push(BranchEnd {
            max_distance: m / 10.0,
            touched,
            separated_at: cut.map(|i| branch[i].distance),
            last,
            detached,
        });
        rows.extend(branch);
    }
    Ok((rows, ends))
}

/// Makes the output folder, refusing one that holds files `stiction md` did not write.
pub fn prepare_folder(out: &Path) -> Result<(), MdError> {
    let foreign = std::fs::read_dir(out).ok().is_some_and(|mut d| d.next().is_some())
        && !out.join("in.stiction").exists()
        && !out.join("adhesion").join("in.adhesion").exists();
    if foreign {
        return Err(MdError::Output {
            path: out.into(),
            message: "the folder holds files that stiction md did not write: give another --out".into(),
        });
    }
    std::fs::create_dir_all(out).map_err(|e| MdError::Output { path: out.into(), message: e.to_string() })
}

/// The counter-body's centre of mass height at the start.
pub fn counter_height(assembly: &Assembly) -> f64 {
    let z: Vec<f64> = assembly.atoms.iter().filter(|(_, p)| *p == Part::Counter).map(|(x, _)| x[2]).collect();
    z.iter().sum::<f64>() / z.len() as f64
}

/// Writes the table as CSV: `distance,force,area,branch,max_distance` (nm, nN, nm^2; the force
/// on the asperity, positive compressive), the columns `stiction calibrate` reads, after the
/// `# key: value` lines `notes` (its description and provenance).
pub fn write_table(path: &Path, rows: &[Row], notes: &[(&str, String)]) -> Result<(), MdError> {
    let mut text: String = notes.iter().map(|(k, v)| format!("# {k}: {v}\n")).collect();
    text.push_str("distance,force,area,branch,max_distance\n");
    for r in rows {
        let branch = if r.loading { "loading" } else { "unloading" };
        text.push_str(&format!("{:.6},{:.6},{:.6},{branch},{:.6}\n", r.distance, r.force, r.area, r.max_distance));
    }
    stiction_core::output::write_atomically(path, text.as_bytes())
        .map_err(|e| MdError::Output { path: path.into(), message: e.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(areas: &[f64]) -> Vec<Row> {
        areas
            .iter()
            .enumerate()
            .map(|(k, &area)| Row {
                step: k as u64,
                distance: -(k as f64),
                force: 0.0,
                area,
                loading: false,
                max_distance: 0.0,
            })
            .collect()
    }

    /// The neck breaks at the first row from which the area stays zero: a zero between rows
    /// with area does not count, a neck that holds to the end has no break, and neither has a
    /// branch that never touched.
    #[test]
    fn the_neck_breaks_where_its_area_stays_zero() {
        assert_eq!(separation_row(&rows(&[2.0, 1.0, 0.0, 0.5, 0.0, 0.0])), Some(4));
        assert_eq!(separation_row(&rows(&[2.0, 1.0, 0.5])), None);
        assert_eq!(separation_row(&rows(&[0.0, 0.0])), None);
    }
}

//! The LAMMPS side: the data file (`atoms.data`: types 1 fixed base, 2 mobile, 3 counter-body)
//! and the input (`in.stiction`) this writes, the run (`lmp`, its log kept in `log.lammps`),
//! and the force-distance table read back from the averaged outputs.
//!
//! The input, in `metal` units: periodic in x and y; EAM for all three types from the one
//! potential file; the base held (zero force and velocity); the mobile atoms integrated
//! (`nve`) with a Langevin bath on the substrate's mobile planes (damping 0.1 ps); the counter
//! moved rigidly (`fix move`) down at the speed to `max_approach`, then up as far. The force on
//! the counter along z (`fcm`, positive when the asperity pushes it away) and its height are
//! averaged over every `AVERAGE_STEPS` steps (`fix ave/time`) into `loading.dat` and
//! `unloading.dat`; the atoms are dumped at the same steps (`loading.lammpstrj`,
//! `unloading.lammpstrj`, which OVITO and ParaView open) for the neck's area
//! ([`super::neck`]).

use super::MdError;
use super::geometry::{Assembly, Part};
use super::spec::{Funcfl, MdSpec};
use std::path::{Path, PathBuf};

/// Steps averaged into one row of the table.
pub const AVERAGE_STEPS: usize = 50;

/// eV / Angstrom in nN.
pub const EV_PER_ANGSTROM_IN_NN: f64 = 1.602_176_634;

/// The data file's text.
pub fn data_file(assembly: &Assembly, funcfl: &Funcfl) -> String {
    let top = assembly.atoms.iter().map(|(x, _)| x[2]).fold(f64::NEG_INFINITY, f64::max);
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

/// The steps of one leg of `distance` Angstrom at the run's speed.
pub fn leg_steps(spec: &MdSpec, distance: f64) -> usize {
    let per_step = spec.run.speed * 0.01 * spec.run.timestep; // m/s = 0.01 Angstrom/ps
    ((distance / per_step / AVERAGE_STEPS as f64).ceil() as usize).max(1) * AVERAGE_STEPS
}

/// The input script's text.
pub fn input_file(spec: &MdSpec, assembly: &Assembly) -> String {
    let a = spec.lattice.constant;
    let speed = spec.run.speed * 0.01;
    let leg = leg_steps(spec, spec.run.max_approach - assembly.start_approach(a));
    let bath_top = 2.0 * a; // the substrate's planes from a to 2 a: above the fixed ones
    let potential = spec.potential.file.display();
    format!(
        "# written by stiction md\n\
         units metal\n\
         atom_style atomic\n\
         boundary p p f\n\
         read_data atoms.data\n\
         pair_style eam\n\
         pair_coeff 1 1 \"{potential}\"\n\
         pair_coeff 2 2 \"{potential}\"\n\
         pair_coeff 3 3 \"{potential}\"\n\
         neighbor 2.0 bin\n\
         neigh_modify every 1 delay 0 check yes\n\
         group base type 1\n\
         group mobile type 2\n\
         group counter type 3\n\
         region bath block INF INF INF INF INF {bath_top}\n\
         group inbath region bath\n\
         group bath intersect inbath mobile\n\
         velocity mobile create {t} {seed} dist gaussian\n\
         velocity base set 0.0 0.0 0.0\n\
         velocity counter set 0.0 0.0 0.0\n\
         fix hold base setforce 0.0 0.0 0.0\n\
         fix integrate mobile nve\n\
         fix thermostat bath langevin {t} {t} 0.1 {seed}\n\
         variable fz equal fcm(counter,z)\n\
         variable zc equal xcm(counter,z)\n\
         timestep {dt}\n\
         thermo {avg}\n\
         fix move counter move linear 0.0 0.0 {down}\n\
         fix table all ave/time 1 {avg} {avg} v_zc v_fz file loading.dat\n\
         dump frames all custom {avg} loading.lammpstrj id type x y z\n\
         dump_modify frames sort id\n\
         run {leg}\n\
         undump frames\n\
         unfix table\n\
         unfix move\n\
         fix move counter move linear 0.0 0.0 {speed}\n\
         fix table all ave/time 1 {avg} {avg} v_zc v_fz file unloading.dat\n\
         dump frames all custom {avg} unloading.lammpstrj id type x y z\n\
         dump_modify frames sort id\n\
         run {leg}\n",
        t = spec.run.temperature,
        seed = spec.run.seed,
        dt = spec.run.timestep,
        avg = AVERAGE_STEPS,
        down = -speed,
    )
}

/// One row of the table: approach (nm), force on the asperity (nN, positive compressive), the
/// neck's area (nm^2), branch.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub step: u64,
    pub distance: f64,
    pub force: f64,
    pub area: f64,
    pub loading: bool,
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
        });
    }
    Ok(rows)
}

/// The LAMMPS executable: `STICTION_LAMMPS`, else `lmp` on the PATH.
pub fn executable() -> PathBuf {
    std::env::var_os("STICTION_LAMMPS").map(PathBuf::from).unwrap_or_else(|| PathBuf::from("lmp"))
}

/// Writes the files into `out`, runs LAMMPS there and returns the table (loading then unloading
/// rows). A LAMMPS that is missing or fails is an error naming its log and last error line.
pub fn run(spec: &MdSpec, funcfl: &Funcfl, assembly: &Assembly, out: &Path) -> Result<Vec<Row>, MdError> {
    let write = |name: &str, text: &str| {
        let path = out.join(name);
        stiction_core::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| MdError::Output { path: path.clone(), message: e.to_string() })
    };
    let foreign =
        std::fs::read_dir(out).ok().is_some_and(|mut d| d.next().is_some()) && !out.join("in.stiction").exists();
    if foreign {
        return Err(MdError::Output {
            path: out.into(),
            message: "the folder holds files that stiction md did not write: give another --out".into(),
        });
    }
    std::fs::create_dir_all(out).map_err(|e| MdError::Output { path: out.into(), message: e.to_string() })?;
    write("atoms.data", &data_file(assembly, funcfl))?;
    write("in.stiction", &input_file(spec, assembly))?;
    let lmp = executable();
    let status = std::process::Command::new(&lmp)
        .args(["-in", "in.stiction", "-log", "log.lammps", "-screen", "none"])
        .current_dir(out)
        .stderr(std::process::Stdio::null()) // MPI's abort notice; the log holds LAMMPS's error
        .status()
        .map_err(|e| {
            MdError::LammpsMissing(format!(
                "cannot run LAMMPS ('{}': {e}); install it (Debian: apt-get install lammps lammps-data) or set STICTION_LAMMPS",
                lmp.display()
            ))
        })?;
    let log = out.join("log.lammps");
    if !status.success() {
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        let last = text.lines().rev().find(|l| l.contains("ERROR")).unwrap_or("no ERROR line");
        return Err(MdError::Lammps(format!("LAMMPS failed ({status}); its log is '{}': {last}", log.display())));
    }
    let start = assembly.start_approach(spec.lattice.constant);
    let zc0 = counter_height(assembly);
    let mut rows = Vec::new();
    let a = spec.lattice.constant;
    for (leg, loading) in [("loading", true), ("unloading", false)] {
        let read = |name: String| {
            let path = out.join(name);
            std::fs::read_to_string(&path)
                .map(|t| (path.clone(), t))
                .map_err(|e| MdError::Lammps(format!("'{}': {e}", path.display())))
        };
        let (path, text) = read(format!("{leg}.dat"))?;
        let mut leg_rows =
            read_leg(&text, zc0, start, loading).map_err(|m| MdError::Lammps(format!("'{}' {m}", path.display())))?;
        let (path, text) = read(format!("{leg}.lammpstrj"))?;
        let frames = read_frames(&text).map_err(|m| MdError::Lammps(format!("'{}' {m}", path.display())))?;
        for row in &mut leg_rows {
            let atoms = frames
                .get(&row.step)
                .ok_or_else(|| MdError::Lammps(format!("'{}' has no frame at step {}", path.display(), row.step)))?;
            let mobile: Vec<[f64; 3]> = atoms.iter().filter(|(t, _)| *t == 2).map(|(_, x)| *x).collect();
            let bottom = atoms.iter().filter(|(t, _)| *t == 3).map(|(_, x)| x[2]).fold(f64::INFINITY, f64::min);
            row.area = super::neck::neck_area(&mobile, assembly.substrate_top, bottom, assembly.width, a) / 100.0;
        }
        rows.extend(leg_rows);
    }
    Ok(rows)
}

/// The counter-body's centre of mass height at the start.
pub fn counter_height(assembly: &Assembly) -> f64 {
    let z: Vec<f64> = assembly.atoms.iter().filter(|(_, p)| *p == Part::Counter).map(|(x, _)| x[2]).collect();
    z.iter().sum::<f64>() / z.len() as f64
}

/// Writes the table as CSV: `distance,force,area,branch,max_distance` (nm, nN, nm^2; the force
/// on the asperity, positive compressive), the columns `stiction calibrate` reads, after the
/// `# key: value` lines `notes` (its description and provenance).
pub fn write_table(path: &Path, rows: &[Row], max_distance: f64, notes: &[(&str, String)]) -> Result<(), MdError> {
    let mut text: String = notes.iter().map(|(k, v)| format!("# {k}: {v}\n")).collect();
    text.push_str("distance,force,area,branch,max_distance\n");
    for r in rows {
        let branch = if r.loading { "loading" } else { "unloading" };
        text.push_str(&format!("{:.6},{:.6},{:.6},{branch},{:.6}\n", r.distance, r.force, r.area, max_distance));
    }
    stiction_core::output::write_atomically(path, text.as_bytes())
        .map_err(|e| MdError::Output { path: path.into(), message: e.to_string() })
}

//! The work of adhesion across the interface, measured: two flat (001) slabs of the metal, the
//! lower of the bodies' element A and the upper of the counter's B (with the cross scale of
//! [`super::eam`]), relaxed at 0 K in contact and again apart:
//!
//! w = (E_apart - E_contact) / A,
//!
//! A the periodic cell's area. At cross scale 1 the two slabs are one crystal cut in two and w
//! is twice the (001) surface energy. Each slab is `SLAB_CELLS` cells (2 x `SLAB_CELLS` planes)
//! thick, more than twice the potential's cutoff, over `CELLS` x `CELLS` cells; both relax
//! freely (conjugate gradients to forces below `FORCE_TOLERANCE`), so the interface finds its
//! own spacing. Apart, the upper slab is lifted by `LIFT`, beyond the cutoff.
//!
//! A target work of adhesion is met by the cross scale found with Brent's method (argmin's
//! `BrentRoot`) on [0, `LARGEST_SCALE`], w growing with the scale from w(0) = 0.
//!
//! This measures the ideal (relaxed, 0 K, commensurate (001)) work of adhesion; the
//! asperity's own contact, thermal and plastic, does not enter it.

use super::MdError;
use super::eam::{FuncflTables, element_names, fs_file};
use super::lammps::run_lammps;
use std::path::Path;

/// The cell's side, in cubic cells.
pub const CELLS: usize = 3;
/// Each slab's thickness, in cubic cells.
pub const SLAB_CELLS: usize = 5;
/// The upper slab's lift apart (Angstrom).
pub const LIFT: f64 = 20.0;
/// The relaxation's force tolerance (eV / Angstrom).
pub const FORCE_TOLERANCE: f64 = 1e-6;
/// The largest cross scale tried for a target.
pub const LARGEST_SCALE: f64 = 8.0;
/// eV / Angstrom^2 in J / m^2.
pub const EV_PER_SQUARE_ANGSTROM_IN_J_PER_SQUARE_METRE: f64 = 16.021_766_34;

/// The data file of the two slabs in contact (types 1 lower, 2 upper; the upper's lowest plane
/// a / 2 above the lower's top).
fn slabs_data(a: f64, mass: f64) -> String {
    let planes = 2 * SLAB_CELLS;
    let lower: Vec<[f64; 3]> = super::geometry::sites(a, CELLS, SLAB_CELLS).collect();
    let mut atoms: Vec<(u8, [f64; 3])> = lower.iter().map(|x| (1, *x)).collect();
    let shift = planes as f64 * a / 2.0;
    atoms.extend(lower.iter().map(|x| (2, [x[0], x[1], x[2] + shift])));
    let width = CELLS as f64 * a;
    let mut text = format!(
        "stiction md: two (001) slabs\n\n{} atoms\n2 atom types\n\n0 {width} xlo xhi\n0 {width} ylo yhi\n-1 {} zlo zhi\n\nMasses\n\n1 {mass}\n2 {mass}\n\nAtoms # atomic\n\n",
        atoms.len(),
        2.0 * shift + LIFT + 1.0
    );
    for (k, (t, x)) in atoms.iter().enumerate() {
        text.push_str(&format!("{} {t} {:.8} {:.8} {:.8}\n", k + 1, x[0], x[1], x[2]));
    }
    text
}

fn input(names: &[String; 2]) -> String {
    format!(
        "# written by stiction md: the work of adhesion of two (001) slabs\n\
         units metal\n\
         atom_style atomic\n\
         boundary p p s\n\
         read_data slabs.data\n\
         pair_style eam/fs\n\
         pair_coeff * * cross.eam.fs {a} {b}\n\
         group upper type 2\n\
         thermo_style custom step pe fnorm\n\
         min_style cg\n\
         minimize 0.0 {tol} 100000 1000000\n\
         variable contact equal $(pe:%.12f)\n\
         displace_atoms upper move 0.0 0.0 {LIFT}\n\
         minimize 0.0 {tol} 100000 1000000\n\
         variable apart equal $(pe:%.12f)\n\
         print \"${{contact}} ${{apart}}\" file energies.txt screen no\n",
        a = names[0],
        b = names[1],
        tol = FORCE_TOLERANCE,
    )
}

/// The work of adhesion (J/m^2) at cross scale `scale`, measured in `dir` (its files kept).
pub fn measure(tables: &FuncflTables, element: &str, a: f64, scale: f64, dir: &Path) -> Result<f64, MdError> {
    std::fs::create_dir_all(dir).map_err(|e| MdError::Output { path: dir.into(), message: e.to_string() })?;
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        stiction_core::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| MdError::Output { path: path.clone(), message: e.to_string() })
    };
    let names = element_names(element);
    write("cross.eam.fs", &fs_file(tables, [&names[0], &names[1]], scale))?;
    write("slabs.data", &slabs_data(a, tables.mass))?;
    write("in.adhesion", &input(&names))?;
    run_lammps(dir, "in.adhesion", "log.adhesion", 1)?;
    let path = dir.join("energies.txt");
    let text = std::fs::read_to_string(&path).map_err(|e| MdError::Lammps(format!("'{}': {e}", path.display())))?;
    let e: Vec<f64> = text.split_whitespace().filter_map(|v| v.parse().ok()).collect();
    if e.len() != 2 {
        return Err(MdError::Lammps(format!("'{}': expected two energies, found '{}'", path.display(), text.trim())));
    }
    let area = (CELLS as f64 * a).powi(2);
    Ok((e[1] - e[0]) / area * EV_PER_SQUARE_ANGSTROM_IN_J_PER_SQUARE_METRE)
}

/// The cross scale whose work of adhesion is `target` (J/m^2) within a relative `tolerance`,
/// and that work. A target beyond the reach of `LARGEST_SCALE` is an error naming what it gives.
pub fn scale_for(
    tables: &FuncflTables,
    element: &str,
    a: f64,
    target: f64,
    tolerance: f64,
    dir: &Path,
) -> Result<(f64, f64), MdError> {
    use argmin::core::{CostFunction, Executor};
    use argmin::solver::brent::BrentRoot;
    use std::cell::RefCell;
    struct Gap<'a> {
        tables: &'a FuncflTables,
        element: &'a str,
        a: f64,
        target: f64,
        dir: &'a Path,
        failure: RefCell<Option<MdError>>,
    }
    impl CostFunction for Gap<'_> {
        type Param = f64;
        type Output = f64;
        fn cost(&self, s: &f64) -> Result<f64, argmin::core::Error> {
            match measure(self.tables, self.element, self.a, *s, self.dir) {
                Ok(w) => Ok(w - self.target),
                Err(e) => {
                    let message = e.to_string();
                    *self.failure.borrow_mut() = Some(e);
                    Err(argmin::core::Error::msg(message))
                }
            }
        }
    }
    // the executor takes its problem by value; this hands it a borrow, the failure kept here
    struct Borrowed<'a>(&'a Gap<'a>);
    impl CostFunction for Borrowed<'_> {
        type Param = f64;
        type Output = f64;
        fn cost(&self, s: &f64) -> Result<f64, argmin::core::Error> {
            self.0.cost(s)
        }
    }
    let gap = Gap { tables, element, a, target, dir, failure: RefCell::new(None) };
    let failure = |gap: &Gap| gap.failure.borrow_mut().take();
    let at_largest = match gap.cost(&LARGEST_SCALE) {
        Ok(v) => v + target,
        Err(e) => return Err(failure(&gap).unwrap_or_else(|| MdError::Lammps(e.to_string()))),
    };
    if at_largest < target {
        return Err(MdError::Target(format!(
            "a work of adhesion of {target} J/m^2 is beyond this potential's reach: the cross scale {LARGEST_SCALE} gives {at_largest:.3} J/m^2"
        )));
    }
    // tolerance on the scale: w is about linear in it, so a relative tolerance carries over
    let solver = BrentRoot::new(0.0, LARGEST_SCALE, 0.25 * tolerance);
    let result = Executor::new(Borrowed(&gap), solver).configure(|state| state.param(1.0).max_iters(40)).run();
    if let Some(e) = failure(&gap) {
        return Err(e);
    }
    let result = result.map_err(|e| MdError::Lammps(format!("the cross scale's search failed: {e}")))?;
    let s = result.state.best_param.unwrap_or(1.0);
    // the work at the scale returned, measured last so the folder holds that run's files
    let w = measure(tables, element, a, s, dir)?;
    if (w / target - 1.0).abs() > tolerance {
        return Err(MdError::Target(format!(
            "the cross scale {s:.4} gives {w:.4} J/m^2, not {target} J/m^2 within {:.1}%",
            100.0 * tolerance
        )));
    }
    Ok((s, w))
}

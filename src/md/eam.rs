//! The interatomic potential with the asperity-counter interaction scaled: a DYNAMO funcfl EAM
//! file (one element) rewritten as a two-element Finnis-Sinclair file (`pair_style eam/fs`)
//! whose second element is the counter-body's.
//!
//! A funcfl file tabulates, for its element, the embedding energy F(rho) on `Nrho` points
//! `drho` apart, and the effective charge Z(r) and the electron density rho(r) on `Nr` points
//! `dr` apart; LAMMPS takes the pair energy as phi(r) = 27.2 x 0.529 Z(r)^2 / r (Hartree and Bohr
//! in eV and Angstrom). An eam/fs file tabulates, on the same grids, F(rho) per element, the
//! density rho_ij(r) that an atom of element j gives one of element i, and r phi_ij(r) per pair.
//!
//! The two elements here are the one element twice, A (substrate and asperity) and B (the
//! counter-body), with
//!
//! - F_A = F_B = F, rho_AA = rho_BB = rho, phi_AA = phi_BB = phi: each body is the potential's
//!   metal;
//! - rho_AB = rho_BA = s rho and phi_AB = s phi: the interaction across the interface scaled by
//!   the cross scale s.
//!
//! At s = 1 the file is the funcfl potential itself (the tables are copied, not interpolated,
//! so the energies agree to round-off); s < 1 weakens the bond across the interface and s > 1
//! strengthens it. The work of adhesion this gives is measured, not assumed
//! ([`super::adhesion`]).

use std::path::Path;

/// A funcfl file's tables.
#[derive(Debug, Clone)]
pub struct FuncflTables {
    pub comment: String,
    pub atomic_number: u32,
    pub mass: f64,
    pub lattice_constant: f64,
    pub structure: String,
    pub nrho: usize,
    pub drho: f64,
    pub nr: usize,
    pub dr: f64,
    pub cutoff: f64,
    pub embedding: Vec<f64>,
    pub charge: Vec<f64>,
    pub density: Vec<f64>,
}

/// The element names in the generated potential: the bodies', the counter's.
pub fn element_names(element: &str) -> [String; 2] {
    [element.to_string(), format!("{element}_counter")]
}

/// Hartree x Bohr in eV x Angstrom, as LAMMPS converts a funcfl charge to a pair energy.
pub const HARTREE_BOHR: f64 = 27.2 * 0.529;

/// Reads a funcfl file: a comment line, `Z mass a lattice`, `Nrho drho Nr dr cutoff`, then the
/// Nrho + 2 Nr values. Errors name the file and what was expected.
pub fn read_funcfl_tables(path: &Path) -> Result<FuncflTables, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
    let mut lines = text.lines();
    let comment = lines.next().unwrap_or("").trim().to_string();
    let shape = |n: usize, what: &str| format!("'{}' line {n}: expected {what}", path.display());
    let element: Vec<&str> = lines.next().unwrap_or("").split_whitespace().collect();
    let grid: Vec<&str> = lines.next().unwrap_or("").split_whitespace().collect();
    if element.len() < 4 {
        return Err(shape(2, "'atomic-number mass lattice-constant structure'"));
    }
    if grid.len() < 5 {
        return Err(shape(3, "'Nrho drho Nr dr cutoff'"));
    }
    let int = |s: &str, n: usize, what: &str| s.parse::<usize>().map_err(|_| shape(n, what));
    let num =
        |s: &str, n: usize, what: &str| s.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| shape(n, what));
    let (nrho, nr) = (int(grid[0], 3, "an integer Nrho")?, int(grid[2], 3, "an integer Nr")?);
    let values: Vec<f64> = lines
        .flat_map(str::split_whitespace)
        .map(|s| s.parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("'{}': a table value is not a finite number", path.display()))?;
    if values.len() < nrho + 2 * nr || nrho < 5 || nr < 5 {
        return Err(format!(
            "'{}': expected Nrho + 2 Nr = {} table values (Nrho, Nr at least 5), found {}",
            path.display(),
            nrho + 2 * nr,
            values.len()
        ));
    }
    Ok(FuncflTables {
        comment,
        atomic_number: int(element[0], 2, "an integer atomic number")? as u32,
        mass: num(element[1], 2, "a mass")?,
        lattice_constant: num(element[2], 2, "a lattice constant")?,
        structure: element[3].to_string(),
        nrho,
        drho: num(grid[1], 3, "a number drho")?,
        nr,
        dr: num(grid[3], 3, "a number dr")?,
        cutoff: num(grid[4], 3, "a cutoff")?,
        embedding: values[..nrho].to_vec(),
        charge: values[nrho..nrho + nr].to_vec(),
        density: values[nrho + nr..nrho + 2 * nr].to_vec(),
    })
}

/// Appends values five to a line.
fn push_column(text: &mut String, values: impl Iterator<Item = f64>) {
    for (k, v) in values.enumerate() {
        text.push_str(&format!("{v:.16e}"));
        text.push(if k % 5 == 4 { '\n' } else { ' ' });
    }
    if !text.ends_with('\n') {
        text.push('\n');
    }
}

/// The two-element eam/fs file's text: elements `names` (the bodies' A, then the counter's B),
/// the cross terms scaled by `scale`.
pub fn fs_file(t: &FuncflTables, names: [&str; 2], scale: f64) -> String {
    let mut text = String::with_capacity(26 * (t.nrho + 6 * t.nr));
    text.push_str(&format!(
        "stiction md: {} as two elements, the cross terms scaled by {scale}\nfrom: {}\nphi = 27.2 x 0.529 Z^2 / r\n",
        names[0], t.comment
    ));
    text.push_str(&format!("2 {} {}\n", names[0], names[1]));
    text.push_str(&format!("{} {:.16e} {} {:.16e} {:.16e}\n", t.nrho, t.drho, t.nr, t.dr, t.cutoff));
    let cross = |i: usize, j: usize| if i == j { 1.0 } else { scale };
    for i in 0..2 {
        text.push_str(&format!("{} {} {} {}\n", t.atomic_number, t.mass, t.lattice_constant, t.structure));
        push_column(&mut text, t.embedding.iter().copied());
        for j in 0..2 {
            push_column(&mut text, t.density.iter().map(|r| cross(i, j) * r));
        }
    }
    for (i, j) in [(0, 0), (1, 0), (1, 1)] {
        push_column(&mut text, t.charge.iter().map(|z| cross(i, j) * HARTREE_BOHR * z * z));
    }
    text
}

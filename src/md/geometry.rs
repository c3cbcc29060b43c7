//! The atoms of the experiment, on one fcc lattice of constant a with its cube edges along x, y
//! and z: (001) planes a / 2 apart, each holding 2 atoms per a^2.
//!
//! - the substrate: the planes at z = 0, a/2, ... below `thickness`, over the periodic square of
//!   `width_cells` cells; its lowest two planes are held fixed;
//! - the asperity: the lattice sites above the substrate inside the spherical cap of base radius
//!   r_b and height h on the box's middle (the sphere's radius (r_b^2 + h^2) / (2 h)), so it grows
//!   epitaxially from the substrate;
//! - the counter-body: a flat slab of (001) planes whose lowest lies `gap` above the tip atom.
//!
//! The approach is zero when the undeformed surfaces barely touch, the counter's lowest plane
//! one plane spacing a / 2 above the tip atom: approach = a / 2 - (z_counter - z_tip), growing
//! as the counter comes down.

/// Which body an atom belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The substrate's lowest two planes, held fixed.
    Base,
    /// The substrate's other planes and the asperity.
    Mobile,
    /// The counter-body.
    Counter,
}

/// The built assembly.
#[derive(Debug, Clone)]
pub struct Assembly {
    pub atoms: Vec<([f64; 3], Part)>,
    /// The periodic box's side.
    pub width: f64,
    /// The substrate's top plane.
    pub substrate_top: f64,
    /// The tip atom's height.
    pub tip: f64,
    /// The counter's lowest plane at the start.
    pub counter_bottom: f64,
    /// The atoms of the asperity's lowest plane (its base).
    pub base_atoms: usize,
    /// The asperity's atoms.
    pub asperity_atoms: usize,
}

impl Assembly {
    /// The approach at the start: a / 2 - (counter_bottom - tip).
    pub fn start_approach(&self, a: f64) -> f64 {
        a / 2.0 - (self.counter_bottom - self.tip)
    }
}

/// The fcc sites of the cells (i, j, k), i and j in 0..n, k in 0..layers: cell corner plus
/// the basis (0,0,0), (1/2,1/2,0), (1/2,0,1/2), (0,1/2,1/2).
pub(crate) fn sites(a: f64, n: usize, layers: usize) -> impl Iterator<Item = [f64; 3]> {
    const BASIS: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]];
    (0..layers).flat_map(move |k| {
        (0..n).flat_map(move |j| {
            (0..n).flat_map(move |i| {
                BASIS.iter().map(move |b| [(i as f64 + b[0]) * a, (j as f64 + b[1]) * a, (k as f64 + b[2]) * a])
            })
        })
    })
}

/// Builds the assembly; `a` the lattice constant, `n` the box's cells, lengths in Angstrom.
pub fn build(a: f64, n: usize, thickness: f64, base_radius: f64, height: f64, counter: (f64, f64)) -> Assembly {
    let (counter_thickness, gap) = counter;
    let eps = 1e-6 * a;
    let width = n as f64 * a;
    let plane = a / 2.0;
    let top_layers = ((thickness + height) / a).ceil() as usize + 1;
    let mut atoms = Vec::new();
    let substrate_top = ((thickness - eps) / plane).floor() * plane;
    let middle = width / 2.0; // a column of sites, a apart: the tip is one atom
    let sphere = (base_radius * base_radius + height * height) / (2.0 * height);
    let centre_z = substrate_top + height - sphere;
    let (mut tip, mut base_atoms, mut asperity_atoms) = (f64::NEG_INFINITY, 0, 0);
    for x in sites(a, n, top_layers) {
        if x[2] <= substrate_top + eps {
            let part = if x[2] < 2.0 * plane - eps { Part::Base } else { Part::Mobile };
            atoms.push((x, part));
            continue;
        }
        let (dx, dy, dz) = (x[0] - middle, x[1] - middle, x[2] - centre_z);
        if x[2] <= substrate_top + height + eps && dx * dx + dy * dy + dz * dz <= sphere * sphere + eps {
            atoms.push((x, Part::Mobile));
            asperity_atoms += 1;
            tip = tip.max(x[2]);
            if (x[2] - substrate_top - plane).abs() < eps {
                base_atoms += 1;
            }
        }
    }
    if asperity_atoms == 0 {
        tip = substrate_top;
    }
    let counter_bottom = tip + gap;
    let counter_layers = (counter_thickness / a).ceil() as usize + 1;
    for x in sites(a, n, counter_layers) {
        if x[2] < counter_thickness - eps {
            atoms.push(([x[0], x[1], x[2] + counter_bottom], Part::Counter));
        }
    }
    Assembly { atoms, width, substrate_top, tip, counter_bottom, base_atoms, asperity_atoms }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: f64 = 4.08;

    fn count(assembly: &Assembly, part: Part) -> usize {
        assembly.atoms.iter().filter(|(_, p)| *p == part).count()
    }

    /// Every (001) plane holds 2 atoms per a^2: a substrate of p planes over n x n cells holds
    /// 2 p n^2, the counter likewise; neighbours are a / sqrt 2 apart.
    #[test]
    fn slabs_hold_two_atoms_per_cell_face_per_plane() {
        let s = build(A, 5, 3.0 * A, 6.0, 4.0, (2.0 * A, 5.0));
        // planes at 0, a/2, ..., 2.5 a: 6 planes below 3 a
        assert_eq!(count(&s, Part::Base) + count(&s, Part::Mobile) - s.asperity_atoms, 2 * 6 * 25);
        assert_eq!(count(&s, Part::Base), 2 * 2 * 25);
        assert_eq!(count(&s, Part::Counter), 2 * 4 * 25);
        assert!((s.substrate_top - 2.5 * A).abs() < 1e-9);
        let atoms: Vec<[f64; 3]> = s.atoms.iter().filter(|(_, p)| *p != Part::Counter).map(|a| a.0).collect();
        let nearest = atoms[1..].iter().map(|x| (0..3).map(|k| (x[k] - atoms[0][k]).powi(2)).sum::<f64>().sqrt());
        let nearest = nearest.fold(f64::INFINITY, f64::min);
        assert!((nearest - A / 2f64.sqrt()).abs() < 1e-9, "{nearest}");
    }

    /// The cap's base plane holds about 2 / a^2 x pi r_b^2 atoms, its tip lies at most the
    /// height above the substrate and within a plane of it, and the counter starts `gap` above.
    #[test]
    fn the_asperity_has_its_base_area_and_height_and_the_approach_starts_at_plane_contact() {
        let (r, h) = (5.0 * A, 4.0 * A);
        let s = build(A, 14, 2.0 * A, r, h, (A, 6.0));
        let expected = 2.0 / (A * A) * std::f64::consts::PI * r * r;
        assert!(
            (s.base_atoms as f64 / expected - 1.0).abs() < 0.1,
            "{} base atoms, {expected:.1} expected",
            s.base_atoms
        );
        assert!(s.tip <= s.substrate_top + h + 1e-9 && s.tip >= s.substrate_top + h - A / 2.0 - 1e-9, "tip {}", s.tip);
        assert!((s.counter_bottom - s.tip - 6.0).abs() < 1e-12);
        assert!((s.start_approach(A) - (A / 2.0 - 6.0)).abs() < 1e-12);
        // a plane spacing apart, the approach is zero
        let touching = build(A, 14, 2.0 * A, r, h, (A, A / 2.0));
        assert!(touching.start_approach(A).abs() < 1e-12);
    }
}

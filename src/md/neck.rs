//! The contact area of the asperity: the smallest cross-section of the neck between the
//! substrate and the counter-body.
//!
//! The neck is the mobile atoms joined to the substrate through bonds (closer than 1.2 a /
//! sqrt 2, the nearest-neighbour distance with room for thermal motion and stretch, well
//! short of the second neighbours' a; periodic in x and y). There is contact while one of them
//! lies within 0.6 a of the counter's lowest plane; atoms that broke off with the counter, or
//! sit on it away from the neck, are not joined to the substrate and do not count.
//!
//! The neck's atoms between the substrate's top plane and the counter's lowest are cut into
//! slabs a plane spacing (a / 2) thick, one about each (001) plane of the undeformed lattice
//! that lies at least half a spacing under the counter. In each slab they fall into clusters
//! of in-plane neighbours (the same bond); the slab's cross-section is its largest cluster,
//! each atom carrying the a^2 / 2 of area a (001) plane gives it, and at least one atom: a
//! chain stretched along z may cross a slab between two of its atoms. The neck's area is the
//! smallest slab's; zero without contact (apart, or the neck broke).

/// The neck's area of the mobile atoms `mobile` at the counter's lowest plane `counter_bottom`,
/// over the substrate's top plane `substrate_top`, in a periodic box of side `width`, lattice
/// constant `a` (lengths in one unit, the area in its square).
pub fn neck_area(mobile: &[[f64; 3]], substrate_top: f64, counter_bottom: f64, width: f64, a: f64) -> f64 {
    let bond = 1.2 * a / 2f64.sqrt();
    let spacing = a / 2.0;
    let neck = joined_to_substrate(mobile, substrate_top + spacing / 2.0, width, bond);
    let top = neck.iter().map(|x| x[2]).fold(f64::NEG_INFINITY, f64::max);
    if top < counter_bottom - 0.6 * a {
        return 0.0;
    }
    // a slab a spacing thick about each plane of the undeformed lattice over the substrate,
    // k = 1, 2, ..., while the plane lies at least half a spacing under the counter's lowest
    // (one slab where the counter has crushed the asperity to less)
    let slabs = ((counter_bottom - spacing / 2.0 - substrate_top) / spacing + 1e-9).floor().max(1.0) as usize;
    let mut smallest = usize::MAX;
    for k in 1..=slabs {
        let centre = substrate_top + k as f64 * spacing;
        let (lo, hi) = (centre - spacing / 2.0, centre + spacing / 2.0);
        let slab: Vec<[f64; 2]> = neck.iter().filter(|x| x[2] >= lo && x[2] < hi).map(|x| [x[0], x[1]]).collect();
        smallest = smallest.min(largest_cluster(&slab, width, bond).max(1));
    }
    smallest as f64 * a * a / 2.0
}

/// The mobile atoms not joined to the substrate (the bond of [`neck_area`]): after the neck
/// broke, those the counter-body carried off.
pub fn detached(mobile: &[[f64; 3]], substrate_top: f64, width: f64, a: f64) -> usize {
    mobile.len() - joined_to_substrate(mobile, substrate_top + a / 4.0, width, 1.2 * a / 2f64.sqrt()).len()
}

/// The atoms of `atoms` joined through bonds shorter than `bond` (periodic in x and y, side
/// `width`) to one lying below `floor`, found over a grid of cells a bond wide.
fn joined_to_substrate(atoms: &[[f64; 3]], floor: f64, width: f64, bond: f64) -> Vec<[f64; 3]> {
    use std::collections::HashMap;
    let per_side = ((width / bond).floor() as i64).max(1);
    let cell_size = width / per_side as f64;
    let cell = |x: &[f64; 3]| {
        let c = |u: f64| ((u / cell_size).floor() as i64).rem_euclid(per_side);
        (c(x[0]), c(x[1]), (x[2] / cell_size).floor() as i64)
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, x) in atoms.iter().enumerate() {
        grid.entry(cell(x)).or_default().push(i);
    }
    let near = |p: &[f64; 3], q: &[f64; 3]| {
        let d = |u: f64| u - width * (u / width).round();
        let (dx, dy, dz) = (d(p[0] - q[0]), d(p[1] - q[1]), p[2] - q[2]);
        dx * dx + dy * dy + dz * dz < bond * bond
    };
    // neighbouring cells, each once (a narrow box has fewer than three per side)
    let offsets: Vec<i64> = if per_side >= 3 { vec![-1, 0, 1] } else { (0..per_side).collect() };
    let mut joined = vec![false; atoms.len()];
    let mut stack: Vec<usize> = (0..atoms.len()).filter(|&i| atoms[i][2] < floor).collect();
    for &i in &stack {
        joined[i] = true;
    }
    while let Some(i) = stack.pop() {
        let (cx, cy, cz) = cell(&atoms[i]);
        for &ox in &offsets {
            for &oy in &offsets {
                for oz in -1..=1 {
                    let key = ((cx + ox).rem_euclid(per_side), (cy + oy).rem_euclid(per_side), cz + oz);
                    for &j in grid.get(&key).map_or(&[][..], |v| v.as_slice()) {
                        if !joined[j] && near(&atoms[i], &atoms[j]) {
                            joined[j] = true;
                            stack.push(j);
                        }
                    }
                }
            }
        }
    }
    atoms.iter().zip(&joined).filter(|(_, j)| **j).map(|(x, _)| *x).collect()
}

/// The size of the largest cluster of `points` linked by distances below `cutoff` (periodic in
/// a square of side `width`).
fn largest_cluster(points: &[[f64; 2]], width: f64, cutoff: f64) -> usize {
    let n = points.len();
    let mut cluster = vec![usize::MAX; n];
    let mut largest = 0;
    let near = |p: [f64; 2], q: [f64; 2]| {
        let d = |u: f64| u - width * (u / width).round();
        d(p[0] - q[0]).hypot(d(p[1] - q[1])) < cutoff
    };
    for seed in 0..n {
        if cluster[seed] != usize::MAX {
            continue;
        }
        cluster[seed] = seed;
        let (mut stack, mut size) = (vec![seed], 0);
        while let Some(i) = stack.pop() {
            size += 1;
            for j in 0..n {
                if cluster[j] == usize::MAX && near(points[i], points[j]) {
                    cluster[j] = seed;
                    stack.push(j);
                }
            }
        }
        largest = largest.max(size);
    }
    largest
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: f64 = 4.08;

    /// fcc sites of an n x n cell box, planes z = k a / 2 for k in planes.
    fn sites(n: usize, planes: std::ops::Range<usize>) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        for k in planes {
            for j in 0..2 * n {
                for i in 0..2 * n {
                    if (i + j + k) % 2 == 0 {
                        out.push([i as f64 * A / 2.0, j as f64 * A / 2.0, k as f64 * A / 2.0]);
                    }
                }
            }
        }
        out
    }

    /// A cylinder of radius r through 4 planes between a substrate (planes 0..3) and a counter
    /// whose lowest plane is plane 7, with adatoms spread on the counter's side away from it:
    /// its area is its fewest atoms in a plane times a^2 / 2, about pi r^2; the adatoms do not count; a
    /// plane removed (the neck broke) gives 0, and so does a counter out of reach.
    #[test]
    fn a_cylindrical_neck_has_its_cross_section_and_adatoms_do_not_count() {
        let (n, r) = (10, 2.2 * A);
        let middle = n as f64 * A / 2.0;
        let inside = |x: &[f64; 3]| (x[0] - middle).hypot(x[1] - middle) <= r;
        let mut atoms: Vec<[f64; 3]> = sites(n, 0..3);
        let neck: Vec<[f64; 3]> = sites(n, 3..7).into_iter().filter(inside).collect();
        let per_plane =
            (3..7).map(|k| neck.iter().filter(|x| (x[2] - k as f64 * A / 2.0).abs() < 1e-9).count()).min().unwrap();
        atoms.extend(&neck);
        // adatoms: isolated sites of plane 6 far from the neck (and one at the box's edge, whose
        // periodic neighbours are not atoms either)
        atoms.extend([[0.0, 0.0, 3.0 * A], [2.0 * A, 2.0 * A, 3.0 * A], [4.0 * A, 0.0, 3.0 * A]]);
        let (top, counter) = (2.0 * A / 2.0, 7.0 * A / 2.0);
        let area = neck_area(&atoms, top, counter, n as f64 * A, A);
        assert_eq!(area, per_plane as f64 * A * A / 2.0);
        assert!(
            (area / (std::f64::consts::PI * r * r) - 1.0).abs() < 0.15,
            "{area} against {}",
            std::f64::consts::PI * r * r
        );
        // the neck broken at plane 5
        let broken: Vec<[f64; 3]> = atoms.iter().copied().filter(|x| (x[2] - 5.0 * A / 2.0).abs() > 1e-9).collect();
        assert_eq!(neck_area(&broken, top, counter, n as f64 * A, A), 0.0);
        // the counter two planes above the tip: no contact
        assert_eq!(neck_area(&atoms, top, counter + A, n as f64 * A, A), 0.0);
        // a chain of single atoms stretched to 1.1 nearest-neighbour distances along z, from
        // the substrate to the counter: one atom's area, though slabs lie between its atoms
        let nn = A / 2f64.sqrt();
        let mut chain: Vec<[f64; 3]> = sites(n, 0..3);
        let links = 5;
        chain.extend((1..=links).map(|k| [middle, middle, top + k as f64 * 1.1 * nn]));
        let chain_counter = top + links as f64 * 1.1 * nn + A / 2.0;
        assert_eq!(neck_area(&chain, top, chain_counter, n as f64 * A, A), A * A / 2.0);
        // one link stretched past the bond: broken, though the atoms above it touch the counter
        let mut broken_chain = chain.clone();
        for x in broken_chain.iter_mut().filter(|x| x[2] > top + 2.5 * 1.1 * nn) {
            x[2] += 0.5 * nn;
        }
        assert_eq!(neck_area(&broken_chain, top, chain_counter + 0.5 * nn, n as f64 * A, A), 0.0);
        // the atoms above the broken link, carried off; none while the chain holds
        assert_eq!(detached(&broken_chain, top, n as f64 * A, A), 3);
        assert_eq!(detached(&chain, top, n as f64 * A, A), 0);
    }
}

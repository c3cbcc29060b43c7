//! The contact area of the asperity: the smallest cross-section of the neck between the
//! substrate and the counter-body.
//!
//! The mobile atoms between the substrate's top plane and the counter's lowest plane are cut
//! into slabs a plane spacing (a / 2) thick, one about each (001) plane of the undeformed
//! lattice that lies at least half a spacing under the counter. In each slab the atoms fall into clusters of
//! in-plane neighbours (closer than 1.2 a / sqrt 2, the nearest-neighbour distance of a (001)
//! plane with room for thermal motion; periodic in x and y); the slab's cross-section is its
//! largest cluster, each atom carrying the a^2 / 2 of area a (001) plane gives it. The neck's
//! area is the smallest slab's. Atoms that diffused onto the counter or the substrate away from
//! the neck form small clusters of their own and are not counted. The area is zero until a
//! mobile atom lies within 0.6 a of the counter's lowest plane (the asperity touches it), and
//! zero again where a slab is empty (the neck broke).

/// The neck's area of the mobile atoms `mobile` at the counter's lowest plane `counter_bottom`,
/// over the substrate's top plane `substrate_top`, in a periodic box of side `width`, lattice
/// constant `a` (lengths in one unit, the area in its square).
pub fn neck_area(mobile: &[[f64; 3]], substrate_top: f64, counter_bottom: f64, width: f64, a: f64) -> f64 {
    let top = mobile.iter().map(|x| x[2]).fold(f64::NEG_INFINITY, f64::max);
    if top < counter_bottom - 0.6 * a {
        return 0.0;
    }
    // a slab a spacing thick about each plane of the undeformed lattice over the substrate,
    // k = 1, 2, ..., while the plane lies at least half a spacing under the counter's lowest
    // (one slab where the counter has crushed the asperity to less)
    let spacing = a / 2.0;
    let slabs = ((counter_bottom - spacing / 2.0 - substrate_top) / spacing + 1e-9).floor().max(1.0) as usize;
    let mut smallest = usize::MAX;
    for k in 1..=slabs {
        let centre = substrate_top + k as f64 * spacing;
        let (lo, hi) = (centre - spacing / 2.0, centre + spacing / 2.0);
        let slab: Vec<[f64; 2]> = mobile.iter().filter(|x| x[2] >= lo && x[2] < hi).map(|x| [x[0], x[1]]).collect();
        smallest = smallest.min(largest_cluster(&slab, width, 1.2 * a / 2f64.sqrt()));
    }
    smallest as f64 * a * a / 2.0
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
    }
}

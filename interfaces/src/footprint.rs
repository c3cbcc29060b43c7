//! The footprint of a discrete point (an asperity's base): a disc of area A on the surface over
//! which the point's force acts as a uniform traction, and over which the surface displacement
//! is averaged to give the point's distance to the flat.
//!
//! With sample points x_j (weights w_j, sum 1) of a quadrature over the disc, projected along the
//! flat's normal n onto the surface faces, the averaged normal displacement is
//!   u_bar = sum_j w_j n . u(x_j) = sum_a c_a n . u_a,  c_a = sum_j w_j N_a(x_j),
//! a linear combination of node displacements like a single point's shape-function
//! interpolation. The force f of the point is applied as the consistent nodal forces
//! f c_a n (the work-conjugate of u_bar: a uniform traction f / A over the disc), and the
//! tangent is f'(g) c_a c_b n n^T: exact and symmetric. Footprint 0 is the point itself.
//!
//! Quadrature: polar product rule on the disc of radius r = sqrt(A / pi): Gauss-Legendre in the
//! radius (weight r dr) times equally spaced angles, with enough rings to put several samples
//! on each face the disc covers.

use crate::surface_locator::{SurfaceLocator, SurfacePoint};
use std::collections::BTreeMap;
use stiction_core::quadrature::gauss_legendre;

/// Sample points (in-plane offsets from the centre) and weights (sum 1) of a disc of radius
/// `radius` with `rings` Gauss rings of `6 * rings` (at least 8) angles each.
pub fn disc_rule(radius: f64, rings: usize) -> Vec<([f64; 2], f64)> {
    let gauss = gauss_legendre(rings);
    let n_angles = (6 * rings).max(8);
    let mut out = Vec::with_capacity(rings * n_angles);
    for (k, (tk, wk)) in gauss.points.iter().zip(&gauss.weights).enumerate() {
        // r in [0, R]: r = R (1 + t) / 2, dr = R / 2 dt; area weight r dr dtheta / (pi R^2)
        let r = 0.5 * radius * (1.0 + tk[0]);
        let radial = wk * 0.5 * radius * r / (std::f64::consts::PI * radius * radius);
        for m in 0..n_angles {
            // stagger alternate rings so the samples do not line up radially
            let theta = 2.0 * std::f64::consts::PI * (m as f64 + 0.5 * (k % 2) as f64) / n_angles as f64;
            out.push(([r * theta.cos(), r * theta.sin()], radial * 2.0 * std::f64::consts::PI / n_angles as f64));
        }
    }
    out
}

/// A footprint on the surface: the nodes and their weights c_a, the reference level of its
/// centre along the normal (the asperity stands on the surface at its centre; only the
/// displacement is averaged), the centre, and the mean area of the faces it touches.
#[derive(Debug, Clone)]
pub struct Footprint {
    pub nodes: Vec<usize>,
    pub weights: Vec<f64>,
    pub level: f64,
    pub center: SurfacePoint,
    pub face_area: f64,
}

/// Area of the triangle of a face's first three (corner) nodes.
pub(crate) fn corner_area(locator: &SurfaceLocator, hit: &SurfacePoint) -> f64 {
    let x = |a: usize| locator.node(hit.nodes[a]);
    let (a, b, c) = (x(0), x(1), x(2));
    let (e1, e2) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
    let n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

/// The footprint of area `area` centred where the ray from `start` meets the surface; the rays
/// of the samples start at `start + offset_1 e1 + offset_2 e2`. None if any ray misses.
pub fn locate_footprint(
    locator: &SurfaceLocator,
    start: [f64; 3],
    (e1, e2): ([f64; 3], [f64; 3]),
    normal: [f64; 3],
    area: f64,
) -> Option<Footprint> {
    let center = locator.locate(start)?;
    let face_area = corner_area(locator, &center);
    let radius = (area / std::f64::consts::PI).sqrt();
    // about three samples across each face the disc covers (faces of edge ~ sqrt(2 area))
    let face_size = (2.0 * face_area).sqrt();
    let rings = ((3.0 * radius / face_size).ceil() as usize).clamp(2, 8);
    let mut weights: BTreeMap<usize, f64> = BTreeMap::new();
    let (mut touched, mut touched_area) = (std::collections::BTreeSet::new(), 0.0);
    for (offset, w) in disc_rule(radius, rings) {
        let p: [f64; 3] = std::array::from_fn(|k| start[k] + offset[0] * e1[k] + offset[1] * e2[k]);
        let hit = locator.locate(p)?;
        for (&node, &n) in hit.nodes.iter().zip(&hit.shape) {
            *weights.entry(node).or_insert(0.0) += w * n;
        }
        if touched.insert(hit.nodes.clone()) {
            touched_area += corner_area(locator, &hit);
        }
    }
    let (nodes, weights): (Vec<usize>, Vec<f64>) = weights.into_iter().filter(|(_, w)| *w != 0.0).unzip();
    let level = (0..3).map(|k| center.position[k] * normal[k]).sum();
    Some(Footprint { nodes, weights, level, center, face_area: touched_area / touched.len() as f64 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_disc_rule_integrates_polynomials_over_the_disc() {
        let r = 2.0;
        for rings in 2..6 {
            let rule = disc_rule(r, rings);
            let sum: f64 = rule.iter().map(|p| p.1).sum();
            assert!((sum - 1.0).abs() < 1e-13, "weights sum to {sum}");
            // mean of x^2 + y^2 over the disc: r^2 / 2; of x^4: r^4 / 8; of x: 0
            let m2: f64 = rule.iter().map(|(x, w)| w * (x[0] * x[0] + x[1] * x[1])).sum();
            let m4: f64 = rule.iter().map(|(x, w)| w * x[0].powi(4)).sum();
            let m1: f64 = rule.iter().map(|(x, w)| w * x[0]).sum();
            assert!((m2 - r * r / 2.0).abs() < 1e-12, "{rings} rings: {m2}");
            // r^4 r dr is of degree 5: exact from 3 Gauss rings on
            if rings >= 3 {
                assert!((m4 - r.powi(4) / 8.0).abs() < 1e-11, "{rings} rings: {m4}");
            }
            assert!(m1.abs() < 1e-13);
        }
    }
}

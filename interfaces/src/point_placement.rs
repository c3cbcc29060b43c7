//! Placing discrete points (asperities) on a body's surface: each point's in-plane position,
//! measured from the surface's lowest point (the pole) along two directions normal to the
//! flat, is projected along the normal onto the surface faces; with a footprint its node
//! weights average the displacement over a disc ([`crate::footprint`]), without one they are
//! the face's shape functions at the point.

use crate::footprint::{corner_area, locate_footprint};
use crate::surface_locator::{SurfaceLocator, plane_basis};
use stiction_core::CoreError;
use stiction_core::mesh::Mesh;

/// A discrete point: in-plane coordinates (along two directions orthogonal to the normal,
/// measured from the surface's lowest point) and its height toward the flat; and its radius
/// where the layout knows one (a height map's summit), for laws that keep a per-point radius
/// ([`RADIUS_STATE`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscretePoint {
    pub in_plane: [f64; 2],
    pub height: f64,
    pub radius: Option<f64>,
}

/// The state variable through which a force-per-point law takes each point's own radius
/// (e.g. `hertz-asperity`): a law that declares a state of this name gets the layout's radii.
pub const RADIUS_STATE: &str = "radius";

/// One placed point.
#[derive(Debug, Clone)]
pub struct PlacedPoint {
    pub nodes: Vec<usize>,
    /// Node weights (sum 1): the point's interpolation of the surface displacement.
    pub weights: Vec<f64>,
    /// x . n - h: the reference level of the point's tip along the normal.
    pub level: f64,
    pub position: [f64; 3],
    /// Mean corner area of the faces under the point (or its footprint).
    pub face_area: f64,
}

/// The in-plane origin of a surface's points, its pole: the surface's lowest node along
/// `normal`; where several are lowest (a flat face, within a billionth of the surface's
/// extent), the one nearest their middle.
fn pole(nodes: Vec<[f64; 3]>, normal: [f64; 3]) -> [f64; 3] {
    let level_of = |x: &[f64; 3]| (0..3).map(|k| x[k] * normal[k]).sum::<f64>();
    let lowest = nodes.iter().map(level_of).fold(f64::INFINITY, f64::min);
    let extent = nodes.iter().flat_map(|x| x.iter().map(|c| c.abs())).fold(0.0f64, f64::max);
    let bottom: Vec<[f64; 3]> =
        nodes.into_iter().filter(|x| level_of(x) <= lowest + 1e-9 * extent.max(f64::MIN_POSITIVE)).collect();
    let middle: [f64; 3] = std::array::from_fn(|k| bottom.iter().map(|x| x[k]).sum::<f64>() / bottom.len() as f64);
    let distance = |x: &[f64; 3]| (0..3).map(|k| (x[k] - middle[k]).powi(2)).sum::<f64>();
    *bottom.iter().min_by(|a, b| distance(a).total_cmp(&distance(b))).expect("a surface group has nodes")
}

/// Places `discrete` on group `surface` for interface `name` (unit `normal` from the flat
/// toward the body); `footprint_area(i)` is point i's footprint (0: the point itself).
/// Returns the points and the pole's level along the normal.
pub fn place_points(
    mesh: &Mesh,
    name: &str,
    surface: &str,
    normal: [f64; 3],
    discrete: &[DiscretePoint],
    source: &str,
    footprint_area: impl Fn(usize) -> f64,
) -> Result<(Vec<PlacedPoint>, f64), CoreError> {
    let group = mesh.group(surface)?;
    let locator = SurfaceLocator::new(mesh, group, normal)?;
    let level_of = |x: [f64; 3]| (0..3).map(|k| x[k] * normal[k]).sum::<f64>();
    let pole = pole(mesh.group_nodes(group).iter().map(|&n| mesh.nodes[n]).collect(), normal);
    let (e1, e2) = plane_basis(normal);
    let pole_level = level_of(pole);
    let mut points = Vec::with_capacity(discrete.len());
    for (i, d) in discrete.iter().enumerate() {
        let area = footprint_area(i);
        // start the ray well on the flat's side of the body
        let start: [f64; 3] = std::array::from_fn(|k| {
            pole[k] + d.in_plane[0] * e1[k] + d.in_plane[1] * e2[k] - 10.0 * normal[k] * (1.0 + pole_level.abs())
        });
        let outside = || {
            CoreError::Invalid(format!(
                "interface '{name}': point {} of {source} at in-plane ({:.4}, {:.4}){} is outside surface '{surface}'",
                i + 1,
                d.in_plane[0],
                d.in_plane[1],
                if area > 0.0 { " or part of its footprint" } else { "" },
            ))
        };
        if !(d.height >= 0.0 && d.height.is_finite()) {
            return Err(CoreError::Invalid(format!(
                "interface '{name}': point {} of {source} has height {}",
                i + 1,
                d.height
            )));
        }
        let point = if area > 0.0 {
            let f = locate_footprint(&locator, start, (e1, e2), normal, area).ok_or_else(outside)?;
            PlacedPoint {
                nodes: f.nodes,
                weights: f.weights,
                level: f.level - d.height,
                position: f.center.position,
                face_area: f.face_area,
            }
        } else {
            let hit = locator.locate(start).ok_or_else(outside)?;
            let face_area = corner_area(&locator, &hit);
            PlacedPoint {
                level: level_of(hit.position) - d.height,
                position: hit.position,
                face_area,
                nodes: hit.nodes,
                weights: hit.shape,
            }
        };
        points.push(point);
    }
    Ok((points, pole_level))
}

#[cfg(test)]
mod tests {
    use super::pole;

    /// A flat face's pole is its lowest node nearest the middle; a curved surface's its single
    /// lowest node, wherever that lies.
    #[test]
    fn the_pole_of_a_flat_face_is_its_middle_node() {
        let mut face: Vec<[f64; 3]> = (0..9).map(|k| [(k % 3) as f64 * 10.0, (k / 3) as f64 * 10.0, 0.0]).collect();
        face.push([10.0, 10.0, 5.0]); // above the face: not on it
        face.rotate_left(5); // neither a corner nor the middle first
        assert_eq!(pole(face, [0.0, 0.0, 1.0]), [10.0, 10.0, 0.0]);
        let cap: Vec<[f64; 3]> = vec![[0.0, 0.0, 0.2], [3.0, 1.0, 0.0], [5.0, 5.0, 0.1]];
        assert_eq!(pole(cap, [0.0, 0.0, 1.0]), [3.0, 1.0, 0.0]);
    }
}

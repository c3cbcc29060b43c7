//! Places points on a meshed surface by casting a ray along a direction (the flat's normal):
//! each point gets the face it lands on and its reference coordinates there.
//!
//! The hit is computed on the face's corner triangle; its barycentric coordinates are used as
//! the face's reference coordinates, and the point is moved onto the (possibly curved, 6-node)
//! face at those coordinates.

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use stiction_core::CoreError;
use stiction_core::mesh::{Mesh, PhysicalGroup};

/// A point on a surface face.
#[derive(Debug, Clone)]
pub struct SurfacePoint {
    pub nodes: Vec<usize>,
    pub shape: Vec<f64>,
    pub position: [f64; 3],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Faces of a surface group, ready for ray casts along a fixed direction: an R-tree (crate
/// `rstar`) of their corner triangles' bounding boxes projected on the plane normal to the
/// direction finds the faces a ray can hit.
pub struct SurfaceLocator<'a> {
    mesh: &'a Mesh,
    faces: Vec<(stiction_core::mesh::CellType, &'a [usize])>,
    direction: [f64; 3],
    /// Two unit vectors spanning the plane normal to the direction.
    plane: ([f64; 3], [f64; 3]),
    index: RTree<GeomWithData<Rectangle<[f64; 2]>, usize>>,
}

impl<'a> SurfaceLocator<'a> {
    /// `direction`: unit vector the rays travel along (from the flat toward the body).
    pub fn new(mesh: &'a Mesh, group: &'a PhysicalGroup, direction: [f64; 3]) -> Result<Self, CoreError> {
        let faces: Vec<_> = mesh
            .blocks_of(group)
            .filter(|b| b.cell_type.dim() == 2)
            .flat_map(|b| b.cells().map(move |c| (b.cell_type, c)))
            .collect();
        if faces.is_empty() {
            return Err(CoreError::EmptyGroup { name: group.name.clone(), what: "triangular faces".into() });
        }
        let plane = plane_basis(direction);
        let project = |x: [f64; 3]| [dot(x, plane.0), dot(x, plane.1)];
        let boxes = faces
            .iter()
            .enumerate()
            .map(|(i, (_, face))| {
                let corners = [0, 1, 2].map(|a| project(mesh.nodes[face[a]]));
                let lower = [0, 1].map(|k| corners.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min));
                let upper = [0, 1].map(|k| corners.iter().map(|c| c[k]).fold(f64::NEG_INFINITY, f64::max));
                // pad beyond the hit test's barycentric tolerance
                let pad = 1e-6 * (upper[0] - lower[0] + upper[1] - lower[1]) + 1e-300;
                let rectangle =
                    Rectangle::from_corners([lower[0] - pad, lower[1] - pad], [upper[0] + pad, upper[1] + pad]);
                GeomWithData::new(rectangle, i)
            })
            .collect();
        Ok(Self { mesh, faces, direction, plane, index: RTree::bulk_load(boxes) })
    }

    /// Coordinates of node `n` of the mesh.
    pub fn node(&self, n: usize) -> [f64; 3] {
        self.mesh.nodes[n]
    }

    /// The first face hit by the ray through `p` along the direction (the face nearest the
    /// flat); `None` when the ray misses the surface.
    pub fn locate(&self, p: [f64; 3]) -> Option<SurfacePoint> {
        let d = self.direction;
        let mut best: Option<(f64, usize, f64, f64)> = None;
        let q = [dot(p, self.plane.0), dot(p, self.plane.1)];
        for candidate in self.index.locate_in_envelope_intersecting(&AABB::from_point(q)) {
            let i = candidate.data;
            let face = self.faces[i].1;
            let (a, b, c) = (self.mesh.nodes[face[0]], self.mesh.nodes[face[1]], self.mesh.nodes[face[2]]);
            let (e1, e2) = (sub(b, a), sub(c, a));
            let h = cross(d, e2);
            let det = dot(e1, h);
            if det.abs() < 1e-14 * dot(e1, e1).max(dot(e2, e2)) {
                continue;
            }
            let s = sub(p, a);
            let u = dot(s, h) / det;
            let q = cross(s, e1);
            let v = dot(d, q) / det;
            let tol = 1e-9;
            if u < -tol || v < -tol || u + v > 1.0 + tol {
                continue;
            }
            let t = dot(e2, q) / det; // position along the ray
            // the nearest along the ray; on a shared edge the lowest face index, whatever order
            // the index returns the candidates in
            if best.is_none_or(|(bt, bi, ..)| t < bt || (t == bt && i < bi)) {
                best = Some((t, i, u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)));
            }
        }
        let (_, i, u, v) = best?;
        let (cell, face) = self.faces[i];
        let nn = cell.n_nodes();
        let mut shape = vec![0.0; nn];
        let mut dn = vec![[0.0; 3]; nn];
        stiction_elements::shape::evaluate(cell, &[u, v, 0.0], &mut shape, &mut dn);
        let mut position = [0.0; 3];
        for (a, &n) in face.iter().enumerate() {
            for k in 0..3 {
                position[k] += shape[a] * self.mesh.nodes[n][k];
            }
        }
        Some(SurfacePoint { nodes: face.to_vec(), shape, position })
    }
}

/// Two unit vectors spanning the plane normal to n.
pub fn plane_basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = if n[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let d = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    let e1 = [a[0] - d * n[0], a[1] - d * n[1], a[2] - d * n[2]];
    let l = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
    let e1 = [e1[0] / l, e1[1] / l, e1[2] / l];
    let e2 = [n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]];
    (e1, e2)
}

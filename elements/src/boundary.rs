//! Finds the volume cell behind a boundary face, to orient face normals outward whatever
//! orientation the mesher gave the face.

use std::collections::HashMap;
use stiction_core::mesh::CellType;

/// Map from a face's sorted corner nodes to the centroid of the volume cell it bounds.
pub struct BoundaryFinder {
    faces: HashMap<[usize; 3], [f64; 3]>,
}

fn key(corners: &[usize]) -> [usize; 3] {
    let mut k = [usize::MAX; 3];
    k[..corners.len()].copy_from_slice(corners);
    k.sort_unstable();
    k
}

impl BoundaryFinder {
    /// Indexes the facets of the given volume cells.
    pub fn new<'a>(nodes: &[[f64; 3]], cells: impl Iterator<Item = (CellType, &'a [usize])>) -> Self {
        let mut faces = HashMap::new();
        for (cell_type, conn) in cells {
            let nc = cell_type.n_corners();
            let mut c = [0.0; 3];
            for &n in &conn[..nc] {
                for k in 0..3 {
                    c[k] += nodes[n][k] / nc as f64;
                }
            }
            let fc = cell_type.facet().map(|f| f.n_corners()).unwrap_or(0);
            for facet in cell_type.facets() {
                let corners: Vec<usize> = facet[..fc].iter().map(|&i| conn[i]).collect();
                faces.insert(key(&corners), c);
            }
        }
        Self { faces }
    }

    /// Centroid of the indexed cell that has this face, if any.
    pub fn cell_centroid(&self, face_corners: &[usize]) -> Option<[f64; 3]> {
        self.faces.get(&key(face_corners)).copied()
    }

    /// +1 if the face normal computed from `normal` (at the face) points away from the
    /// adjacent cell, -1 if it points into it; `None` if the face bounds no indexed cell.
    pub fn outward_sign(&self, face_corners: &[usize], face_centroid: [f64; 3], normal: [f64; 3]) -> Option<f64> {
        let c = self.faces.get(&key(face_corners))?;
        let d: f64 = (0..3).map(|k| (face_centroid[k] - c[k]) * normal[k]).sum();
        Some(if d >= 0.0 { 1.0 } else { -1.0 })
    }
}

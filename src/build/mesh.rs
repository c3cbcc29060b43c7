//! The case's mesh: a `.msh` file, or a `.geo` meshed by gmsh (cached); and the checks an
//! axisymmetric model puts on it.

use crate::case::{Analysis, LoadedCase};
use crate::error::Result;
use std::path::PathBuf;
use stiction_core::mesh::Mesh;
use stiction_meshes::{GeoOptions, mesh_geo, read_msh};

/// Reads (or meshes) the case's mesh.
pub fn load_mesh(case: &LoadedCase) -> Result<(Mesh, PathBuf)> {
    let spec = &case.case.mesh;
    let base = case.base_dir();
    let path = match (&spec.file, &spec.geo) {
        (Some(file), None) => base.join(file),
        (None, Some(geo)) => {
            let geo = base.join(geo);
            let options = GeoOptions {
                dimension: if case.case.analysis == Analysis::Axisymmetric { 2 } else { 3 },
                order: spec.order,
                size_factor: spec.size_factor,
                parameters: spec.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect(),
            };
            let cache = geo.parent().unwrap_or(base).join(".stiction-cache");
            mesh_geo(&geo, &options, &cache)?
        }
        _ => {
            return Err(case.error("mesh", "give exactly one of 'file' (a .msh) or 'geo' (a .geo meshed by gmsh)"));
        }
    };
    Ok((read_msh(&path)?, path))
}

/// An axisymmetric model needs a planar mesh (z = 0) in x = r >= 0.
pub fn check_axisymmetric(case: &LoadedCase, mesh: &Mesh) -> Result<()> {
    let (lo, hi) = mesh.bounding_box();
    let tol = 1e-9 * (hi[0] - lo[0]).abs().max(hi[1] - lo[1]).max(1e-300);
    if lo[0] < -tol {
        return Err(case.error(
            "analysis",
            format!("axisymmetric models need the mesh in x = r >= 0, but '{}' reaches x = {}", mesh.source, lo[0]),
        ));
    }
    if (hi[2] - lo[2]).abs() > tol {
        return Err(
            case.error("analysis", format!("axisymmetric models need a planar mesh (z = 0); '{}' is not", mesh.source))
        );
    }
    Ok(())
}

/// Mean corner-to-corner edge length of the faces of a group (None if it has none).
pub(crate) fn mean_edge_length(mesh: &Mesh, group: &stiction_core::mesh::PhysicalGroup) -> Option<f64> {
    let (mut sum, mut count) = (0.0, 0usize);
    for block in mesh.blocks_of(group) {
        let nc = block.cell_type.n_corners();
        for face in block.cells() {
            for a in 0..nc {
                let (p, q) = (mesh.nodes[face[a]], mesh.nodes[face[(a + 1) % nc]]);
                sum += ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                count += 1;
                if nc == 2 {
                    break;
                }
            }
        }
    }
    (count > 0).then(|| sum / count as f64)
}

//! The case's mesh: a `.msh` file, or a `.geo` meshed by gmsh (cached); and the checks an
//! axisymmetric model puts on it.

use crate::case::{Analysis, LoadedCase};
use crate::error::Result;
use std::path::{Path, PathBuf};
use stiction_core::mesh::Mesh;
use stiction_meshes::{GeoOptions, declared_parameters, mesh_geo, read_msh};

/// Reads (or meshes) the case's mesh.
pub fn load_mesh(case: &LoadedCase) -> Result<(Mesh, PathBuf)> {
    let spec = &case.case.mesh;
    let base = case.base_dir();
    let path = match (&spec.file, &spec.geo) {
        (Some(file), None) => base.join(file),
        (None, Some(geo)) => {
            let geo = base.join(geo);
            check_geo_parameters(case, &geo)?;
            let options = GeoOptions {
                dimension: if case.case.analysis == Analysis::Axisymmetric { 2 } else { 3 },
                order: spec.order,
                size_factor: spec.size_factor,
                parameters: spec.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect(),
            };
            let cache = geo.parent().unwrap_or(base).join(".stiction-cache");
            return Ok(mesh_geo(&geo, &options, &cache, spec.time_limit)?);
        }
        _ => {
            return Err(case.error("mesh", "give exactly one of 'file' (a .msh) or 'geo' (a .geo meshed by gmsh)"));
        }
    };
    Ok((read_msh(&path)?, path))
}

/// Each of the case's mesh parameters is one the `.geo` declares (gmsh would ignore any other
/// and mesh with the `.geo`'s own value) and lies within the declared `Min`/`Max`.
fn check_geo_parameters(case: &LoadedCase, geo: &Path) -> Result<()> {
    let given = &case.case.mesh.parameters;
    if given.is_empty() {
        return Ok(());
    }
    let text = std::fs::read_to_string(geo)
        .map_err(|e| case.error("mesh.geo", format!("cannot read '{}': {e}", geo.display())))?;
    let declared = declared_parameters(&text);
    for (name, &value) in given {
        let key = format!("mesh.parameters.{name}");
        let Some(parameter) = declared.iter().find(|p| &p.name == name) else {
            let names: Vec<&str> = declared.iter().map(|p| p.name.as_str()).collect();
            let known = if names.is_empty() { "none".to_string() } else { names.join(", ") };
            return Err(case.error(
                key,
                format!(
                    "'{}' declares no parameter '{name}' in a DefineConstant (it declares: {known})",
                    geo.display()
                ),
            ));
        };
        if !parameter.admits(value) {
            return Err(case.error(
                key,
                format!(
                    "{value} is outside the range {} that '{}' line {} declares for '{name}'",
                    parameter.range_text(),
                    geo.display(),
                    parameter.line
                ),
            ));
        }
    }
    Ok(())
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

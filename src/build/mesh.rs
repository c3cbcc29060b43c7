//! The case's mesh: a `.msh` file, or a `.geo` meshed by gmsh (cached); and the checks an
//! axisymmetric model puts on it.

use crate::case::{Analysis, LoadedCase};
use crate::error::Result;
use std::path::{Path, PathBuf};
use stiction_core::mesh::Mesh;
use stiction_meshes::{GeoOptions, error::gib};
use stiction_meshes::{GmshLimits, GmshProgress, MeshError, declared_parameters, mesh_geo, read_msh_within};

/// Reads (or meshes) the case's mesh. gmsh is stopped when it needs more than a third of the
/// memory the run may count on ([`crate::case::MeshSpec::memory_budget`], [`gmsh_limit`]) or
/// takes longer than `mesh.time_limit`, and reports every few seconds of a long meshing on
/// stderr; a mesh file too large to read is refused before it is read. Each refusal names the keys that set the mesh's size.
pub fn load_mesh(case: &LoadedCase) -> Result<(Mesh, PathBuf)> {
    let spec = &case.case.mesh;
    let base = case.base_dir();
    let memory = spec.memory_budget();
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
            let mut report = |p: &GmshProgress| {
                let memory = p.memory_bytes.map_or(String::new(), |m| format!(", {}", gib(m)));
                eprintln!(
                    "meshing '{}' with gmsh: {:.0} s{memory}; {}",
                    p.geo.display(),
                    p.elapsed_seconds,
                    p.last_line
                );
            };
            let mut limits = GmshLimits {
                time_limit_seconds: spec.time_limit,
                memory_limit_bytes: memory.map(gmsh_limit),
                progress: Some(&mut report),
                interrupted: Some(&crate::resources::interrupted),
            };
            return mesh_geo(&geo, &options, &cache, &mut limits).map_err(|e| size_error(case, e));
        }
        _ => {
            return Err(case.error("mesh", "give exactly one of 'file' (a .msh) or 'geo' (a .geo meshed by gmsh)"));
        }
    };
    let mesh = read_msh_within(&path, memory).map_err(|e| match e {
        e @ MeshError::TooLargeToRead { .. } => case.error("mesh.file", format!("{e}{}", declared_limit(case))),
        e => e.into(),
    })?;
    Ok((mesh, path))
}

/// gmsh's resident memory before it holds any mesh, in bytes (measured: ~76 MB).
const GMSH_BASE_BYTES: u64 = 100 << 20;
/// gmsh needs ~0.38 KB per node of the quadratic mesh it makes (measured on the shipped
/// axisymmetric and 3D hemispheres), the model built from that mesh at least 1.1 KB per node
/// ([`super::size`]; 2.2 to 8.3 KB measured) before its factor. A gmsh that passes a third of
/// the budget is making a mesh whose model cannot fit, and is stopped there rather than at the
/// whole budget.
const GMSH_SHARE_OF_BUDGET: u64 = 3;

/// The memory gmsh may use for a run that may count on `budget` bytes.
fn gmsh_limit(budget: u64) -> u64 {
    GMSH_BASE_BYTES + budget / GMSH_SHARE_OF_BUDGET
}

/// The case keys that set the size of a `.geo` mesh: `mesh.size_factor` and the mesh
/// parameters the case gives.
pub(crate) fn size_keys(case: &LoadedCase) -> String {
    let mut keys = vec!["mesh.size_factor".to_string()];
    keys.extend(case.case.mesh.parameters.keys().map(|k| format!("mesh.parameters.{k}")));
    keys.join(", ")
}

/// " (mesh.memory_limit = 2 GiB)" when the case declares the limit a size error is against.
pub(crate) fn declared_limit(case: &LoadedCase) -> String {
    case.case.mesh.memory_limit.map_or(String::new(), |g| format!(" (mesh.memory_limit = {g} GiB)"))
}

/// A meshing stopped for its size or time, as an error naming the keys that set the size.
fn size_error(case: &LoadedCase, e: MeshError) -> crate::error::StictionError {
    match e {
        MeshError::GmshMemoryLimit { .. } => case.error(
            size_keys(case),
            format!(
                "{e}. gmsh may use a third of the {} the run may count on{}, as the model of a mesh needs at least \
                 three times the memory gmsh takes to make it",
                case.case.mesh.memory_budget().map_or("memory".into(), gib),
                declared_limit(case)
            ),
        ),
        MeshError::TooLargeToRead { .. } => case.error(size_keys(case), format!("{e}{}", declared_limit(case))),
        MeshError::GmshTimeLimit { .. } => case.error(size_keys(case), e.to_string()),
        e => e.into(),
    }
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

//! Whether a model fits in the memory the run may count on
//! ([`crate::case::MeshSpec::memory_budget`]): estimated from the mesh before the model is
//! assembled, and from the symbolic factorization before the first numeric one. A model that
//! does not fit is refused with exit 2, naming the keys that set the mesh's size, instead of
//! ending in an allocation failure part-way.

use crate::case::LoadedCase;
use crate::error::Result;
use stiction_core::linear_solver::LinearSolver;
use stiction_core::mesh::Mesh;
use stiction_meshes::error::gib;

/// The least memory a model takes per mesh node before its factor, in bytes: half of what
/// `stiction check` was measured to take on quadratic meshes (2.2 KB per node on the
/// axisymmetric hemisphere, 8.3 KB on the 3D quarter), so that only a model that surely cannot
/// fit is refused on this estimate.
const MODEL_BYTES_PER_NODE_2D: u64 = 1_100;
const MODEL_BYTES_PER_NODE_3D: u64 = 4_150;

/// The keys that set the mesh's size, for messages: those of a `.geo` or `mesh.file`.
fn keys(case: &LoadedCase) -> String {
    match case.case.mesh.geo {
        Some(_) => super::mesh::size_keys(case),
        None => "mesh.file".into(),
    }
}

/// The memory this process may still take: the machine's available memory now, and the
/// declared `mesh.memory_limit` less what this process already holds, whichever is smaller;
/// with the words that say where the figure comes from.
fn remaining(case: &LoadedCase) -> Option<(u64, String)> {
    let available =
        crate::resources::available_memory().map(|a| (a, format!("the {} this machine has available", gib(a))));
    let spec = &case.case.mesh;
    let declared = spec.memory_limit_bytes().zip(spec.memory_limit).map(|(limit, g)| {
        let held = crate::resources::own_memory().unwrap_or(0);
        let left = limit.saturating_sub(held);
        (left, format!("the {} left of mesh.memory_limit = {g} GiB after the {} this run holds", gib(left), gib(held)))
    });
    match (declared, available) {
        (Some(d), Some(a)) => Some(if d.0 <= a.0 { d } else { a }),
        (d, a) => d.or(a),
    }
}

/// Refuses a mesh whose model would surely not fit, before the model is assembled.
pub fn check_model_fits(case: &LoadedCase, mesh: &Mesh) -> Result<()> {
    let Some((budget, budget_text)) = remaining(case) else { return Ok(()) };
    let per_node = if mesh.dim() == 3 { MODEL_BYTES_PER_NODE_3D } else { MODEL_BYTES_PER_NODE_2D };
    let needed = (mesh.nodes.len() as u64).saturating_mul(per_node);
    if needed > budget {
        return Err(case.error(
            keys(case),
            format!(
                "the mesh '{}' has {} nodes; its model needs at least {} before its factor, more than {budget_text}: \
                 make the mesh coarser",
                mesh.source,
                mesh.nodes.len(),
                gib(needed),
            ),
        ));
    }
    Ok(())
}

/// Refuses a factorization whose factor would not fit, after the symbolic analysis (which
/// counts the factor's entries) and before the first numeric factorization; `bytes_per_entry`
/// is 8 for a factor in double precision, 4 in single.
pub fn check_factor_fits(
    case: &LoadedCase,
    solver: &impl LinearSolver,
    dofs: usize,
    bytes_per_entry: u64,
) -> Result<()> {
    let Some((budget, budget_text)) = remaining(case) else { return Ok(()) };
    let entries = solver.factor_nnz() as u64;
    let needed = entries.saturating_mul(bytes_per_entry);
    if needed > budget {
        return Err(case.error(
            keys(case),
            format!(
                "the sparse factor of this model ({dofs} free dofs) has {entries} entries and needs {}, more than \
                 {budget_text}: make the mesh coarser",
                gib(needed),
            ),
        ));
    }
    Ok(())
}

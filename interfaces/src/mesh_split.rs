//! Splitting a mesh along interior surfaces for zero-thickness cohesive elements: every node of
//! the split faces gets a duplicate, used by the volume cells of one side (and by boundary cells
//! that bound those cells); the other side keeps the original node.

use std::collections::{HashMap, HashSet};
use stiction_core::CoreError;
use stiction_core::mesh::Mesh;

/// The split mesh and, for every split node, (original, duplicate).
pub struct Split {
    pub mesh: Mesh,
    pub pairs: HashMap<usize, usize>,
}

/// Duplicates the nodes of the faces of `surfaces` (groups of dimension model_dim - 1) for the
/// cells of the volume group `side`.
pub fn split_mesh(mesh: &Mesh, surfaces: &[String], side: &str) -> Result<Split, CoreError> {
    let dim = mesh.dim();
    let side_group = mesh.group(side)?.clone();
    if side_group.dim != dim {
        return Err(CoreError::Invalid(format!("split side '{side}' must be a group of dimension {dim}")));
    }
    let mut split_nodes: HashSet<usize> = HashSet::new();
    for s in surfaces {
        let g = mesh.group(s)?;
        if g.dim + 1 != dim {
            return Err(CoreError::Invalid(format!("split surface '{s}' must be a group of dimension {}", dim - 1)));
        }
        let nodes = mesh.group_nodes(g);
        if nodes.is_empty() {
            return Err(CoreError::EmptyGroup { name: s.clone(), what: "faces".into() });
        }
        split_nodes.extend(nodes);
    }
    let mut out = mesh.clone();
    let mut pairs = HashMap::new();
    // nodes of the side's cells that lie on the split surfaces get duplicates
    let mut side_nodes: HashSet<usize> = HashSet::new();
    for b in mesh.blocks_of(&side_group) {
        side_nodes.extend(b.connectivity.iter().copied().filter(|n| split_nodes.contains(n)));
    }
    if side_nodes.is_empty() {
        return Err(CoreError::Invalid(format!("no cell of '{side}' touches the split surfaces")));
    }
    let mut sorted: Vec<usize> = side_nodes.iter().copied().collect();
    sorted.sort_unstable();
    for n in sorted {
        out.nodes.push(mesh.nodes[n]);
        pairs.insert(n, out.nodes.len() - 1);
    }
    // side cells use the duplicates; so do boundary cells (other than the split surfaces) all of
    // whose split nodes belong to a side cell's facet
    let side_facets: HashSet<Vec<usize>> = mesh
        .blocks_of(&side_group)
        .flat_map(|b| {
            let ct = b.cell_type;
            b.cells().flat_map(move |c| {
                let nc = ct.facet().map(|f| f.n_corners()).unwrap_or(0);
                ct.facets().iter().map(move |f| {
                    let mut k: Vec<usize> = f[..nc].iter().map(|&i| c[i]).collect();
                    k.sort_unstable();
                    k
                })
            })
        })
        .collect();
    let split_tags: HashSet<(usize, i32)> =
        surfaces.iter().map(|s| mesh.group(s).map(|g| (g.dim, g.tag))).collect::<Result<_, _>>()?;
    for block in &mut out.blocks {
        let is_side = block.physical_tag == side_group.tag && block.cell_type.dim() == dim;
        let is_split = split_tags.contains(&(block.cell_type.dim(), block.physical_tag));
        if is_side {
            for n in block.connectivity.iter_mut() {
                if let Some(&d) = pairs.get(n) {
                    *n = d;
                }
            }
        } else if !is_split && block.cell_type.dim() == dim - 1 {
            let nn = block.cell_type.n_nodes();
            let nc = block.cell_type.n_corners();
            for cell in block.connectivity.chunks_exact_mut(nn) {
                let mut key: Vec<usize> = cell[..nc].to_vec();
                key.sort_unstable();
                if side_facets.contains(&key) {
                    for n in cell.iter_mut() {
                        if let Some(&d) = pairs.get(n) {
                            *n = d;
                        }
                    }
                }
            }
        }
    }
    Ok(Split { mesh: out, pairs })
}

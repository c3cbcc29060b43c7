//! gmsh MSH 4.1 reader (ASCII and binary) on top of mshio.
//!
//! Node indices: when the file's node tags are dense, mshio drops them and tag t is node
//! t - min_tag (gmsh writes dense tags in block order); sparse tags are mapped explicitly.

use crate::error::MeshError;
use crate::physical_names::parse_physical_names;
use mshio::mshfile::ElementType;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use stiction_core::mesh::{CellBlock, CellType, Mesh, PhysicalGroup};

fn cell_type(t: ElementType) -> Result<Option<CellType>, (String, i32)> {
    Ok(Some(match t {
        ElementType::Lin2 => CellType::Line2,
        ElementType::Lin3 => CellType::Line3,
        ElementType::Tri3 => CellType::Tri3,
        ElementType::Tri6 => CellType::Tri6,
        ElementType::Tet4 => CellType::Tet4,
        ElementType::Tet10 => CellType::Tet10,
        ElementType::Pnt => return Ok(None),
        other => return Err((format!("{other:?} elements"), other as i32)),
    }))
}

/// Reads the `$MeshFormat` version string.
fn format_version(bytes: &[u8]) -> Option<String> {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(200)]).to_string();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        if l.trim() == "$MeshFormat" {
            return lines.next().and_then(|v| v.split_whitespace().next()).map(str::to_string);
        }
    }
    None
}

/// Reads a gmsh MSH 4.1 file.
pub fn read_msh(path: &Path) -> Result<Mesh, MeshError> {
    read_msh_within(path, None)
}

/// Reading a mesh holds about this many times its file's size in memory at once (the file's
/// bytes, mshio's parsed sections and the mesh).
pub const READ_MEMORY_PER_FILE_BYTE: u64 = 3;

/// [`read_msh`], refusing a file whose reading would need more than `memory_limit_bytes`
/// ([`READ_MEMORY_PER_FILE_BYTE`] times its size) before reading any of it.
pub fn read_msh_within(path: &Path, memory_limit_bytes: Option<u64>) -> Result<Mesh, MeshError> {
    if let Some(limit) = memory_limit_bytes {
        let len = std::fs::metadata(path).map_err(|source| MeshError::Io { path: path.to_path_buf(), source })?.len();
        let needed = len.saturating_mul(READ_MEMORY_PER_FILE_BYTE);
        if needed > limit {
            return Err(MeshError::TooLargeToRead {
                path: path.to_path_buf(),
                file_bytes: len,
                needed_bytes: needed,
                limit_bytes: limit,
            });
        }
    }
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io { path: path.to_path_buf(), source })?;
    match format_version(&bytes) {
        None => {
            return Err(MeshError::Parse {
                path: path.to_path_buf(),
                message: "no $MeshFormat section at the start of the file".into(),
            });
        }
        Some(v) if v != "4.1" => {
            return Err(MeshError::UnsupportedVersion { path: path.to_path_buf(), version: v });
        }
        _ => {}
    }
    let groups_named = parse_physical_names(path, &bytes)?;
    let msh = mshio::parse_msh_bytes(&bytes).map_err(|e| MeshError::Parse {
        path: path.to_path_buf(),
        message: e.to_string().lines().take(6).collect::<Vec<_>>().join(" | "),
    })?;
    let parse_err = |message: String| MeshError::Parse { path: path.to_path_buf(), message };
    let nodes_section = msh.data.nodes.as_ref().ok_or_else(|| parse_err("the file has no $Nodes section".into()))?;
    let mut nodes = Vec::with_capacity(nodes_section.num_nodes as usize);
    let mut sparse: HashMap<u64, usize> = HashMap::new();
    let dense = nodes_section.node_blocks.iter().all(|b| b.node_tags.is_none());
    for block in &nodes_section.node_blocks {
        let offset = nodes.len();
        if let Some(tags) = &block.node_tags {
            for (&tag, &local) in tags {
                sparse.insert(tag, offset + local);
            }
        }
        nodes.extend(block.nodes.iter().map(|n| [n.x, n.y, n.z]));
    }
    let min_tag = nodes_section.min_node_tag;
    let n_nodes = nodes.len();
    let index_of = |tag: u64| -> Result<usize, MeshError> {
        let idx = if dense { tag.checked_sub(min_tag).map(|i| i as usize) } else { sparse.get(&tag).copied() };
        idx.filter(|&i| i < n_nodes)
            .ok_or_else(|| parse_err(format!("an element refers to node tag {tag}, which is not in $Nodes")))
    };
    // (dim, entity tag) -> physical tags
    let mut entity_physicals: HashMap<(i32, i32), Vec<i32>> = HashMap::new();
    if let Some(e) = &msh.data.entities {
        for p in &e.points {
            entity_physicals.insert((0, p.tag), p.physical_tags.clone());
        }
        for c in &e.curves {
            entity_physicals.insert((1, c.tag), c.physical_tags.clone());
        }
        for s in &e.surfaces {
            entity_physicals.insert((2, s.tag), s.physical_tags.clone());
        }
        for v in &e.volumes {
            entity_physicals.insert((3, v.tag), v.physical_tags.clone());
        }
    }
    let elements = msh.data.elements.as_ref().ok_or_else(|| parse_err("the file has no $Elements section".into()))?;
    let mut blocks: HashMap<(CellType, i32), Vec<usize>> = HashMap::new();
    let mut used_tags: BTreeSet<(usize, i32)> = BTreeSet::new();
    for block in &elements.element_blocks {
        let ct = match cell_type(block.element_type) {
            Ok(Some(ct)) => ct,
            Ok(None) => continue,
            Err((what, code)) => {
                return Err(MeshError::UnsupportedElement { path: path.to_path_buf(), what, code });
            }
        };
        let physicals = entity_physicals.get(&(block.entity_dim, block.entity_tag)).cloned().unwrap_or_default();
        let physicals = if physicals.is_empty() { vec![0] } else { physicals };
        for &ptag in &physicals {
            let conn = blocks.entry((ct, ptag)).or_default();
            for el in &block.elements {
                if el.nodes.len() != ct.n_nodes() {
                    return Err(parse_err(format!(
                        "element {} has {} nodes, a {} has {}",
                        el.element_tag,
                        el.nodes.len(),
                        ct.name(),
                        ct.n_nodes()
                    )));
                }
                for &t in &el.nodes {
                    conn.push(index_of(t)?);
                }
            }
            if ptag != 0 {
                used_tags.insert((ct.dim(), ptag));
            }
        }
    }
    let mut groups = groups_named;
    for (dim, tag) in used_tags {
        if !groups.iter().any(|g| g.dim == dim && g.tag == tag) {
            groups.push(PhysicalGroup { name: tag.to_string(), dim, tag });
        }
    }
    let mut blocks: Vec<CellBlock> = blocks
        .into_iter()
        .map(|((cell_type, physical_tag), connectivity)| CellBlock { cell_type, physical_tag, connectivity })
        .collect();
    blocks.sort_by_key(|b| (b.cell_type, b.physical_tag));
    Ok(Mesh { nodes, blocks, groups, source: path.display().to_string() })
}

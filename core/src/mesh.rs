//! The mesh model: nodes, cells grouped in blocks by type, and named physical groups.
//!
//! Readers (the `stiction-meshes` crate) fill it; everything else only reads it. Node indices
//! are 0-based positions in [`Mesh::nodes`]; connectivity uses gmsh's local node order.

use crate::error::{CoreError, Result};
use std::collections::BTreeMap;

/// Cell types Stiction understands, with gmsh's local node order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellType {
    Line2,
    Line3,
    Tri3,
    Tri6,
    Tet4,
    Tet10,
}

impl CellType {
    pub fn n_nodes(self) -> usize {
        match self {
            CellType::Line2 => 2,
            CellType::Line3 => 3,
            CellType::Tri3 => 3,
            CellType::Tri6 => 6,
            CellType::Tet4 => 4,
            CellType::Tet10 => 10,
        }
    }
    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            CellType::Line2 | CellType::Line3 => 1,
            CellType::Tri3 | CellType::Tri6 => 2,
            CellType::Tet4 | CellType::Tet10 => 3,
        }
    }
    /// Number of corner (vertex) nodes.
    pub fn n_corners(self) -> usize {
        match self {
            CellType::Line2 | CellType::Line3 => 2,
            CellType::Tri3 | CellType::Tri6 => 3,
            CellType::Tet4 | CellType::Tet10 => 4,
        }
    }
    pub fn is_quadratic(self) -> bool {
        matches!(self, CellType::Line3 | CellType::Tri6 | CellType::Tet10)
    }
    pub fn name(self) -> &'static str {
        match self {
            CellType::Line2 => "2-node line",
            CellType::Line3 => "3-node line",
            CellType::Tri3 => "3-node triangle",
            CellType::Tri6 => "6-node triangle",
            CellType::Tet4 => "4-node tetrahedron",
            CellType::Tet10 => "10-node tetrahedron",
        }
    }
    /// The boundary cell type of this cell (faces of a tet, edges of a triangle).
    pub fn facet(self) -> Option<CellType> {
        match self {
            CellType::Tet4 => Some(CellType::Tri3),
            CellType::Tet10 => Some(CellType::Tri6),
            CellType::Tri3 => Some(CellType::Line2),
            CellType::Tri6 => Some(CellType::Line3),
            _ => None,
        }
    }
    /// Local node lists of the facets, in the facet's own gmsh order.
    pub fn facets(self) -> &'static [&'static [usize]] {
        match self {
            CellType::Tet4 => &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]],
            CellType::Tet10 => &[&[0, 2, 1, 6, 5, 4], &[0, 1, 3, 4, 9, 7], &[0, 3, 2, 7, 8, 6], &[1, 2, 3, 5, 8, 9]],
            CellType::Tri3 => &[&[0, 1], &[1, 2], &[2, 0]],
            CellType::Tri6 => &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]],
            _ => &[],
        }
    }
}

/// All cells of one type that belong to one physical group.
#[derive(Debug, Clone)]
pub struct CellBlock {
    pub cell_type: CellType,
    /// Physical tag of the group these cells belong to (0 if none).
    pub physical_tag: i32,
    /// Flattened connectivity, `n_nodes` entries per cell.
    pub connectivity: Vec<usize>,
}

impl CellBlock {
    pub fn n_cells(&self) -> usize {
        self.connectivity.len() / self.cell_type.n_nodes()
    }
    pub fn cell(&self, i: usize) -> &[usize] {
        let n = self.cell_type.n_nodes();
        &self.connectivity[i * n..(i + 1) * n]
    }
    pub fn cells(&self) -> impl Iterator<Item = &[usize]> {
        self.connectivity.chunks_exact(self.cell_type.n_nodes())
    }
}

/// A named physical group.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicalGroup {
    pub name: String,
    pub dim: usize,
    pub tag: i32,
}

/// A finite-element mesh.
#[derive(Debug, Clone, Default)]
pub struct Mesh {
    pub nodes: Vec<[f64; 3]>,
    pub blocks: Vec<CellBlock>,
    pub groups: Vec<PhysicalGroup>,
    /// Where the mesh came from, for messages.
    pub source: String,
}

impl Mesh {
    /// Highest topological dimension of any cell.
    pub fn dim(&self) -> usize {
        self.blocks.iter().map(|b| b.cell_type.dim()).max().unwrap_or(0)
    }

    /// Looks a group up by name, or by its numeric tag written as text.
    pub fn group(&self, name: &str) -> Result<&PhysicalGroup> {
        if let Some(g) = self.groups.iter().find(|g| g.name == name) {
            return Ok(g);
        }
        if let Ok(tag) = name.parse::<i32>() {
            let hits: Vec<_> = self.groups.iter().filter(|g| g.tag == tag).collect();
            if hits.len() == 1 {
                return Ok(hits[0]);
            }
        }
        Err(CoreError::UnknownGroup { name: name.to_string(), known: self.group_list() })
    }

    /// "name (dim D, tag T), ..." for messages.
    pub fn group_list(&self) -> String {
        if self.groups.is_empty() {
            return "none: the mesh defines no physical groups".into();
        }
        self.groups
            .iter()
            .map(|g| format!("'{}' (dim {}, tag {})", g.name, g.dim, g.tag))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Blocks of the given group.
    pub fn blocks_of<'a>(&'a self, group: &'a PhysicalGroup) -> impl Iterator<Item = &'a CellBlock> + 'a {
        self.blocks.iter().filter(move |b| b.physical_tag == group.tag && b.cell_type.dim() == group.dim)
    }

    /// Sorted, unique node indices touched by a group.
    pub fn group_nodes(&self, group: &PhysicalGroup) -> Vec<usize> {
        let mut nodes: Vec<usize> = self.blocks_of(group).flat_map(|b| b.connectivity.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Groups indexed by name (for tables in output).
    pub fn groups_by_name(&self) -> BTreeMap<&str, &PhysicalGroup> {
        self.groups.iter().map(|g| (g.name.as_str(), g)).collect()
    }

    /// Characteristic size: the bounding-box diagonal.
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &self.nodes {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
}

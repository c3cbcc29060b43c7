//! VTK XML unstructured grids (`.vtu`, through vtkio) and the `.pvd` collection that ParaView
//! opens as a time series.

use super::atomic::write_atomically;
use crate::error::{CoreError, Result};
use crate::mesh::CellType;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType as VtkCell, Cells, DataArray, DataSet, ElementType, IOBuffer,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// A named field with `n_components` numbers per point or per cell.
#[derive(Debug, Clone)]
pub struct Field {
    pub name: String,
    pub n_components: usize,
    pub values: Vec<f64>,
}

impl Field {
    pub fn new(name: impl Into<String>, n_components: usize, values: Vec<f64>) -> Self {
        Self { name: name.into(), n_components, values }
    }
}

/// VTK cell type and the permutation from gmsh to VTK local node order
/// (`vtk_nodes[k] = gmsh_nodes[perm[k]]`). gmsh and VTK differ only for the 10-node
/// tetrahedron, whose last two edge nodes are swapped.
pub fn vtk_cell(cell: CellType) -> (VtkCell, &'static [usize]) {
    match cell {
        CellType::Line2 => (VtkCell::Line, &[0, 1]),
        CellType::Line3 => (VtkCell::QuadraticEdge, &[0, 1, 2]),
        CellType::Tri3 => (VtkCell::Triangle, &[0, 1, 2]),
        CellType::Tri6 => (VtkCell::QuadraticTriangle, &[0, 1, 2, 3, 4, 5]),
        CellType::Tet4 => (VtkCell::Tetra, &[0, 1, 2, 3]),
        CellType::Tet10 => (VtkCell::QuadraticTetra, &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
    }
}

/// Cells to write: a type and the gmsh-ordered connectivity of each.
pub struct CellList<'a> {
    pub cell_type: CellType,
    pub connectivity: &'a [usize],
}

fn attribute(f: &Field) -> Attribute {
    let elem = match f.n_components {
        1 => ElementType::Scalars { num_comp: 1, lookup_table: None },
        3 => ElementType::Vectors,
        n => ElementType::Generic(n as u32),
    };
    Attribute::DataArray(DataArray { name: f.name.clone(), elem, data: IOBuffer::F64(f.values.clone()) })
}

/// Writes an unstructured grid with point and cell fields to `path` (atomically).
pub fn write_vtu(
    path: &Path,
    points: &[[f64; 3]],
    cells: &[CellList<'_>],
    point_fields: &[Field],
    cell_fields: &[Field],
) -> Result<()> {
    let mut connectivity = Vec::new();
    let mut offsets = Vec::new();
    let mut types = Vec::new();
    for list in cells {
        let (vtk, perm) = vtk_cell(list.cell_type);
        for cell in list.connectivity.chunks_exact(list.cell_type.n_nodes()) {
            connectivity.extend(perm.iter().map(|&k| cell[k] as u64));
            offsets.push(connectivity.len() as u64);
            types.push(vtk);
        }
    }
    for f in point_fields {
        check_len(path, f, points.len())?;
    }
    for f in cell_fields {
        check_len(path, f, types.len())?;
    }
    let piece = UnstructuredGridPiece {
        points: IOBuffer::F64(points.iter().flatten().copied().collect()),
        cells: Cells { cell_verts: VertexNumbers::XML { connectivity, offsets }, types },
        data: Attributes {
            point: point_fields.iter().map(attribute).collect(),
            cell: cell_fields.iter().map(attribute).collect(),
        },
    };
    write_piece(path, piece)
}

/// Serializes one unstructured-grid piece as VTK XML and writes it atomically.
fn write_piece(path: &Path, piece: UnstructuredGridPiece) -> Result<()> {
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::inline(piece),
        file_path: None,
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)
        .map_err(|e| CoreError::Write { path: path.to_path_buf(), source: std::io::Error::other(e.to_string()) })?;
    write_atomically(path, &bytes)
}

fn check_len(path: &Path, f: &Field, n: usize) -> Result<()> {
    if f.values.len() != n * f.n_components {
        return Err(CoreError::Invalid(format!(
            "field '{}' for {} has {} values, expected {} x {}",
            f.name,
            path.display(),
            f.values.len(),
            n,
            f.n_components
        )));
    }
    Ok(())
}

/// A ParaView data collection (`.pvd`): rewritten atomically after every added step, so it
/// always lists exactly the `.vtu` files that exist.
#[derive(Debug, Clone)]
pub struct PvdSeries {
    path: PathBuf,
    entries: Vec<(f64, String)>,
}

impl PvdSeries {
    pub fn new(path: PathBuf) -> Self {
        Self { path, entries: Vec::new() }
    }

    /// Adds a dataset (file name relative to the `.pvd`) at `time` and rewrites the collection.
    pub fn add(&mut self, time: f64, file: &str) -> Result<()> {
        self.entries.push((time, file.to_string()));
        self.write()
    }

    /// The datasets listed: (time, file name relative to the `.pvd`).
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Lists `entries` instead (e.g. those of a checkpoint) and rewrites the collection.
    pub fn replace_entries(&mut self, entries: Vec<(f64, String)>) -> Result<()> {
        self.entries = entries;
        self.write()
    }

    /// Rewrites the collection file with the datasets listed now.
    pub fn write(&self) -> Result<()> {
        let mut xml = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
        );
        for (t, f) in &self.entries {
            xml.push_str(&format!("    <DataSet timestep=\"{t:.12e}\" group=\"\" part=\"0\" file=\"{f}\"/>\n"));
        }
        xml.push_str("  </Collection>\n</VTKFile>\n");
        write_atomically(&self.path, xml.as_bytes())
    }
}

/// Writes points (as VTK vertices) with point fields to `path` (atomically): interface
/// integration points, asperities.
pub fn write_points_vtu(path: &Path, points: &[[f64; 3]], fields: &[Field]) -> Result<()> {
    for f in fields {
        check_len(path, f, points.len())?;
    }
    let piece = UnstructuredGridPiece {
        points: IOBuffer::F64(points.iter().flatten().copied().collect()),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity: (0..points.len() as u64).collect(),
                offsets: (1..=points.len() as u64).collect(),
            },
            types: vec![VtkCell::Vertex; points.len()],
        },
        data: Attributes { point: fields.iter().map(attribute).collect(), cell: Vec::new() },
    };
    write_piece(path, piece)
}

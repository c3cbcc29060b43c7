//! Stiction mesh input: gmsh MSH 4.1 files (ASCII and binary, through mshio) with physical
//! groups by name and tag, and meshing of gmsh `.geo` files with Debian's `gmsh` binary, cached
//! by a hash of the inputs.

pub mod error;
pub mod generate;
pub mod geo;
pub mod msh;
pub mod physical_names;

pub use error::MeshError;
pub use geo::{GeoOptions, mesh_geo};
pub use msh::read_msh;

//! Stiction mesh input: gmsh MSH 4.1 files (ASCII and binary, through mshio) with physical
//! groups by name and tag, and meshing of gmsh `.geo` files with Debian's `gmsh` binary, cached
//! by a hash of the inputs.

pub mod error;
pub mod generate;
pub mod geo;
pub mod geo_parameters;
pub mod msh;
pub mod physical_names;

pub use error::MeshError;
pub use geo::{DEFAULT_TIME_LIMIT_SECONDS, GeoOptions, GmshLimits, GmshProgress, PROGRESS_INTERVAL, mesh_geo};
pub use geo_parameters::{GeoParameter, declared_parameters};
pub use msh::{READ_MEMORY_PER_FILE_BYTE, read_msh, read_msh_within};

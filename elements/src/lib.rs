//! Stiction elements: Lagrange shape functions on the reference cells (gmsh node order),
//! default quadrature per cell, small-strain solid kernels (3D and axisymmetric), and boundary
//! face integration (tractions, pressures, areas, outward normals).

pub mod boundary;
pub mod face;
pub mod shape;
pub mod solid;

pub use boundary::BoundaryFinder;
pub use face::FaceIntegrator;
pub use solid::{QuadratureChoice, SolidKernel};

//! Stiction core: the pieces every analysis shares.
//!
//! * [`mesh`]: the mesh model (nodes, cell blocks, physical groups) that readers fill.
//! * [`quadrature`]: quadrature rules as plain data.
//! * [`material`] and [`element`]: the traits that materials and element kernels implement.
//! * [`sparse`] and [`linear_solver`]: a sparsity pattern built once, element-to-slot maps, and a
//!   faer sparse factorization whose symbolic part is computed once per topology.
//! * [`model`]: degrees of freedom, constraints, loads and parallel assembly.
//! * [`newton`]: the Newton-Raphson driver with line search and step cutting.
//! * [`amplitude`]: piecewise-linear histories in pseudo-time.
//! * [`output`]: VTK XML (`.vtu` + `.pvd`) and CSV writers, each file written atomically.

pub mod amplitude;
pub mod arc_length;
pub mod element;
pub mod error;
pub mod interface_law;
pub mod linear_solver;
pub mod material;
pub mod mesh;
pub mod model;
pub mod newton;
pub mod output;
pub mod quadrature;
pub mod sparse;
pub mod voigt;

pub use error::CoreError;

//! Stiction core: the pieces every analysis shares.
//!
//! * [`mesh`]: the mesh model (nodes, cell blocks, physical groups) that readers fill.
//! * [`quadrature`]: quadrature rules as plain data.
//! * [`material`] and [`element`]: the traits that materials and element kernels implement.
//! * [`sparse`] and [`linear_solver`]: a sparsity pattern built once, element-to-slot maps, and a
//!   faer sparse factorization whose symbolic part is computed once per topology.
//! * [`model`]: degrees of freedom, constraints, loads and parallel assembly.
//! * [`problem`]: the nonlinear problem (residual, tangent, trial/commit/roll-back) that
//!   [`nonlinear`] solvers (Newton, arc length) drive with a [`linear_solver`].
//! * [`path`]: path control (load control with cutting, arc-length crossings) and the step
//!   driver that runs a whole analysis, notifying [`record`] observers of every committed
//!   increment (history.csv, events.csv, VTK series, summary.json).
//! * [`amplitude`]: piecewise-linear histories in pseudo-time.
//! * [`checkpoint`]: a run's committed state on disk, to resume it in another process.
//! * [`output`]: VTK XML (`.vtu` + `.pvd`) and CSV writers, each file written atomically.

pub mod amplitude;
pub mod checkpoint;
pub mod element;
pub mod error;
pub mod interface_law;
pub mod linear_solver;
pub mod material;
pub mod mesh;
pub mod model;
pub mod nonlinear;
pub mod observables;
pub mod output;
pub mod path;
pub mod problem;
pub mod quadrature;
pub mod record;
pub mod sparse;
pub mod tangent_sink;
pub mod vector;
pub mod voigt;

pub use error::CoreError;

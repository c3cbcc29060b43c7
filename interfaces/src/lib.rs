//! Stiction interfaces: the geometries where interface laws act. An interface is a geometry
//! (where gaps are measured and forces act) plus a law ([`stiction_core::interface_law`]).
//!
//! * [`rigid_flat::RigidFlat`]: a body surface against a rigid plane that moves along its normal
//!   following an approach schedule; traction laws are integrated over the surface.

pub mod plugin;
pub mod rigid_flat;

pub use rigid_flat::{RigidFlat, RigidFlatSpec};

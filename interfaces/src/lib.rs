//! Stiction interfaces: the geometries where interface laws act. An interface is a geometry
//! (where gaps are measured and forces act) plus a law ([`stiction_core::interface_law`]).
//!
//! * [`rigid_flat::RigidFlat`]: a rigid plane that moves along its normal following an approach
//!   schedule, against a body surface (traction laws integrated over the faces) or against
//!   discrete points on it (force-per-point laws, e.g. nano-asperities);
//! * [`asperity_layout`]: generated layouts of asperities;
//! * [`surface_locator`]: placing points on a meshed surface;
//! * [`plugin`]: interface laws behind the C ABI (plugins and built-in laws).

pub mod asperity_layout;
pub mod cohesive;
pub mod contact_resistance;
pub mod damage_dissipation;
pub mod footprint;
pub mod footprint_compliance;
pub mod height_map;
pub mod local_footprint;
pub mod mesh_split;
pub mod plugin;
pub mod point_law;
pub mod point_placement;
pub mod rigid_flat;
pub mod surface_locator;

pub use point_placement::DiscretePoint;
pub use rigid_flat::{RigidFlat, RigidFlatSpec};

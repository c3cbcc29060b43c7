//! Stiction: implicit finite elements for adhesive and cohesive contact.
//!
//! This crate composes a problem from a case file: [`case`] defines and validates the TOML
//! schema (with `--set` overrides), [`build`] turns a case into a core [`Model`], [`run`] drives
//! the steps and writes `history.csv`, VTK and `summary.json`, and [`fields`] derives output
//! fields (nodal stresses, von Mises, material outputs).
//!
//! [`Model`]: stiction_core::model::Model

pub mod build;
pub mod case;
pub mod error;
pub mod fields;
pub mod laws;
pub mod plots;
pub mod plugin_check;
pub mod run;

pub use error::StictionError;

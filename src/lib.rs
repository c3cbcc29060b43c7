//! Stiction: implicit finite elements for adhesive and cohesive contact.
//!
//! This crate composes a problem from a case file: [`case`] defines and validates the TOML
//! schema (with `--set` overrides) and validates it, [`build`] turns a case into a core
//! [`Model`] and its step plans, [`run`] sets up the output observers and hands the run to the
//! core's step driver, [`sweep`] and [`ensemble`] drive several runs, [`fit`] fits case keys to measured results, and [`report`] prints a run's summary.
//!
//! [`Model`]: stiction_core::model::Model

pub mod build;
pub mod case;
pub mod ensemble;
pub mod error;
pub mod fit;
pub mod laws;
pub mod md;
pub mod output_folder;
pub mod plots;
pub mod plugin_check;
pub mod progress;
pub mod report;
pub mod resources;
pub mod resume;
pub mod run;
pub mod surface;
pub mod sweep;

pub use error::StictionError;

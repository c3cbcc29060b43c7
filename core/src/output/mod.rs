//! Output writers. Every file is written to a temporary sibling and renamed into place, so a
//! reader (or a killed run) never sees a half-written file.

pub mod atomic;
pub mod fields;
pub mod history;
pub mod vtk;

pub use atomic::write_atomically;
pub use history::HistoryWriter;

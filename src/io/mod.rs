//! Serde types of every input and output file, and the CSV / JSON / SVG writers.

pub mod rpr;
pub mod rrr;

pub use rpr::{load_design, load_motion};

//! Serde types of every input and output file, and the CSV / JSON / SVG writers.

pub mod canvas;
pub mod chart;
pub mod draw;
pub mod leg_lines;
pub mod report;
pub mod rpr;
pub mod rrr;
pub mod rrr_draw;
pub mod scene;
pub mod svg;

pub use rpr::{load_design, load_motion};

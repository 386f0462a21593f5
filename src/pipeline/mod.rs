//! The stages of the main job (docs/theory.md §8): ab-initio, user homotopy, parameter
//! homotopy, post-processing.

pub mod ab_initio;
pub mod ab_initio_stage;
pub mod bisection;
pub mod curve;
pub mod family;
pub mod postprocess;
pub mod rrr;
pub mod start_file;
pub mod start_pair;
pub mod sweep;

/// Start-solution files embedded at build time from `supplementary/start/` (see `build.rs`).
pub mod embedded {
    include!(concat!(env!("OUT_DIR"), "/start_files.rs"));
}

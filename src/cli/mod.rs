//! One file per command. Every `run` returns `anyhow::Result`; errors become a
//! one-line message on stderr naming the file and field at fault.

pub mod ab_initio;
pub mod curve;
pub mod distance;
pub mod draw;
pub mod indices;
pub mod map;
pub mod plot;
pub mod prrr;
pub mod rrr;
pub mod schemes;
pub mod solve;
pub mod system;

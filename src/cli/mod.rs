//! One file per command, plus the checks and reports they share (`outcome`: exit codes
//! and the one-line error message; `output`: output files; `resources`: threads and
//! pose limits; `failures`: lost paths). Every `run` returns `anyhow::Result`; errors
//! become a one-line message on stderr naming the file and field at fault.

pub mod ab_initio;
pub mod certify;
pub mod curve;
pub mod curve_log;
pub mod distance;
pub mod draw;
pub mod failures;
pub mod indices;
pub mod indices_plot;
pub mod indices_stream;
pub mod map;
pub mod outcome;
pub mod output;
pub mod plot;
pub mod prrr;
pub mod resources;
pub mod rrr;
pub mod rrr_draw;
pub mod schemes;
pub mod solve;
pub mod system;

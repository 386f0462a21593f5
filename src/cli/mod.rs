//! One file per command, plus the checks and reports they share (`args`: the option
//! groups several commands flatten in; `deferred`: subcommand arguments built only
//! when used; `values`: list values such as a pose `x,y,phi`; `outcome`: exit codes
//! and the one-line error message; `output`: output files; `resources`: threads and
//! pose limits; `failures`: lost paths; `start_check`: the re-check of stored
//! start-solution files). Every `run` returns `anyhow::Result<Outcome>`, which `main`
//! turns into the exit code; errors become a one-line message on stderr naming the
//! file and field at fault.

pub mod ab_initio;
pub mod args;
pub mod certify;
pub mod curve;
pub mod curve_log;
pub mod deferred;
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
pub mod start_check;
pub mod system;
pub mod values;

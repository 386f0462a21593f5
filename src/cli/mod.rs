//! One file per command. Every `run` returns `anyhow::Result`; errors become a
//! one-line message on stderr naming the file and field at fault.

pub mod ab_initio;
pub mod curve;
pub mod distance;
pub mod indices;
pub mod map;
pub mod prrr;
pub mod rrr;
pub mod schemes;
pub mod solve;
pub mod system;

/// Error for a command whose pipeline has not landed yet.
pub fn not_yet_available(command: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "`singdist {command}` is not yet available in this build: its pipeline is still being built (see the open issues)"
    )
}

/// Process exit code for an error: 2 for commands not yet available, 1 otherwise.
pub fn exit_code(error: &anyhow::Error) -> i32 {
    if error.to_string().contains("is not yet available") {
        2
    } else {
        1
    }
}

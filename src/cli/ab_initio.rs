//! `singdist ab-initio`.

use clap::Args;

/// Arguments of `singdist ab-initio`.
#[derive(Args, Debug)]
pub struct AbInitioArgs {}

/// Runs `singdist ab-initio`.
pub fn run(_args: AbInitioArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("ab-initio"))
}

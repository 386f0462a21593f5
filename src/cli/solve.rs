//! `singdist solve`.

use clap::Args;

/// Arguments of `singdist solve`.
#[derive(Args, Debug)]
pub struct SolveArgs {}

/// Runs `singdist solve`.
pub fn run(_args: SolveArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("solve"))
}

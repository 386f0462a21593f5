//! `singdist distance`.

use clap::Args;

/// Arguments of `singdist distance`.
#[derive(Args, Debug)]
pub struct DistanceArgs {}

/// Runs `singdist distance`.
pub fn run(_args: DistanceArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("distance"))
}

//! `singdist map`.

use clap::Args;

/// Arguments of `singdist map`.
#[derive(Args, Debug)]
pub struct MapArgs {}

/// Runs `singdist map`.
pub fn run(_args: MapArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("map"))
}

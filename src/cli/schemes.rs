//! `singdist schemes`.

use clap::Args;

/// Arguments of `singdist schemes`.
#[derive(Args, Debug)]
pub struct SchemesArgs {}

/// Runs `singdist schemes`.
pub fn run(_args: SchemesArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("schemes"))
}

//! `singdist indices`.

use clap::Args;

/// Arguments of `singdist indices`.
#[derive(Args, Debug)]
pub struct IndicesArgs {}

/// Runs `singdist indices`.
pub fn run(_args: IndicesArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("indices"))
}

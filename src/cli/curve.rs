//! `singdist curve`.

use clap::Args;

/// Arguments of `singdist curve`.
#[derive(Args, Debug)]
pub struct CurveArgs {}

/// Runs `singdist curve`.
pub fn run(_args: CurveArgs) -> anyhow::Result<()> {
    Err(super::not_yet_available("curve"))
}

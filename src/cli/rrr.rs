//! `singdist rrr`.

use clap::Subcommand;

/// Sub-commands of `singdist rrr`.
#[derive(Subcommand, Debug)]
pub enum RrrCommand {}

/// Runs `singdist rrr`.
pub fn run(command: RrrCommand) -> anyhow::Result<()> {
    match command {}
}

//! `singdist prrr`.

use clap::Subcommand;

/// Sub-commands of `singdist prrr`.
#[derive(Subcommand, Debug)]
pub enum PrrrCommand {}

/// Runs `singdist prrr`.
pub fn run(command: PrrrCommand) -> anyhow::Result<()> {
    match command {}
}

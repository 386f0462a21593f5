//! `singdist system`.

use clap::Subcommand;

/// Sub-commands of `singdist system`.
#[derive(Subcommand, Debug)]
pub enum SystemCommand {}

/// Runs `singdist system`.
pub fn run(command: SystemCommand) -> anyhow::Result<()> {
    match command {}
}

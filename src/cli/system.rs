//! `singdist system`: inspect and convert polynomial system files.

use super::outcome::Outcome;
use super::output::{check_writable, write_file};
use super::solve::search_name;
use super::values::parse_assignment;
use anyhow::Context;
use clap::{Subcommand, ValueEnum};
use singdist::homotopy::multihomogeneous::{
    MonomialSupports, PartitionSearchOptions, best_partition,
};
use singdist::system::{System, bertini, phc};
use std::path::{Path, PathBuf};

/// File formats of polynomial systems.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Bertini input file (INPUT … END; section).
    Bertini,
    /// PHCpack input file (expanded polynomials).
    Phc,
}

/// Sub-commands of `singdist system`.
#[derive(Subcommand, Debug)]
pub enum SystemCommand {
    /// Print the variables, parameters, number of equations, degrees, Bézout number and
    /// (square systems) the least multi-homogeneous Bézout number found with its
    /// variable grouping.
    Show {
        /// The system file.
        file: PathBuf,
        /// Format of the file.
        #[arg(long, value_enum, default_value = "bertini")]
        from: Format,
    },
    /// Convert a system file to Bertini or PHCpack input.
    Export {
        /// The system file.
        file: PathBuf,
        /// Output format.
        #[arg(long, value_enum)]
        to: Format,
        /// Format of the input file.
        #[arg(long, value_enum, default_value = "bertini")]
        from: Format,
        /// Output file (standard output if absent).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Value of a parameter, `NAME=VALUE` (VALUE like `1.5` or `0.5+2*I`); PHCpack
        /// output needs one per parameter.
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
    },
}

fn read_system(file: &Path, format: Format) -> anyhow::Result<System> {
    let text =
        std::fs::read_to_string(file).with_context(|| format!("cannot read {}", file.display()))?;
    let system = match format {
        Format::Bertini => bertini::read(&text),
        Format::Phc => phc::read(&text),
    };
    system.with_context(|| format!("{}", file.display()))
}

/// The summary printed by `singdist system show`.
pub fn summary(system: &System) -> String {
    let degrees = system.degrees();
    let degree_list: Vec<String> = degrees.iter().map(|d| d.to_string()).collect();
    let list = |names: &[String]| {
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    };
    let square = system.num_equations() == system.variables().len();
    let multihomogeneous = match MonomialSupports::from_system(system) {
        Ok(supports) if square => best_partition(&supports, &PartitionSearchOptions::default())
            .map(|c| {
                format!(
                    "multi-homogeneous Bézout number: {} for {} ({} search)\n",
                    c.bezout_number,
                    c.partition.describe(system.variables()),
                    search_name(c.method)
                )
            })
            .unwrap_or_default(),
        _ => String::new(),
    };
    format!(
        "variables ({}): {}\nparameters ({}): {}\nequations: {}\ndegrees: {}\nBézout number: {}\n{multihomogeneous}",
        system.variables().len(),
        list(system.variables()),
        system.parameters().len(),
        list(system.parameters()),
        system.num_equations(),
        degree_list.join(", "),
        system.bezout_number()
    )
}

/// Runs `singdist system`.
pub fn run(command: SystemCommand) -> anyhow::Result<Outcome> {
    match command {
        SystemCommand::Show { file, from } => {
            let system = read_system(&file, from)?;
            print!("{}", summary(&system));
            Ok(Outcome::Complete)
        }
        SystemCommand::Export {
            file,
            to,
            from,
            out,
            set,
        } => {
            if let Some(path) = &out {
                check_writable("--out", path)?;
            }
            let system = read_system(&file, from)?;
            let values = set
                .iter()
                .map(|assignment| parse_assignment(assignment))
                .collect::<anyhow::Result<Vec<_>>>()?;
            let text = match to {
                Format::Bertini => {
                    let system = if values.is_empty() {
                        system
                    } else {
                        system.with_parameter_values(&values)?
                    };
                    bertini::write(&system)?
                }
                Format::Phc => phc::write(&system, &values)?,
            };
            match out {
                Some(path) => write_file("--out", &path, text)?,
                None => print!("{text}"),
            }
            Ok(Outcome::Complete)
        }
    }
}

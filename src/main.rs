//! The `singdist` command line. Each command parses its arguments, calls one library
//! function and formats the result; all numerics live in the library.

mod cli;

use clap::{Parser, Subcommand};

/// Distance to the nearest singularity of planar parallel manipulators
/// (3-RPR with nine extrinsic metrics, 3-RRR, 3-PRRR indices), by homotopy continuation.
#[derive(Parser, Debug)]
#[command(name = "singdist", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Singularity-distance curves of a 3-RPR along a motion (the main job).
    Curve(cli::curve::CurveArgs),
    /// Singularity distances of a 3-RPR at one pose, in full detail.
    Distance(cli::distance::DistanceArgs),
    /// Drawing (SVG) of a 3-RPR at one pose with each metric's closest singular configuration.
    Draw(cli::draw::DrawArgs),
    /// Kinematic performance indices of a 3-RPR along a motion or at one pose.
    Indices(cli::indices::IndicesArgs),
    /// Indices and metric distances side by side (`indices --with-metrics all`).
    Compare(cli::indices::IndicesArgs),
    /// Inspect and export polynomial systems (Bertini input format).
    #[command(subcommand)]
    System(cli::system::SystemCommand),
    /// Solve a polynomial system by homotopy continuation.
    Solve(cli::solve::SolveArgs),
    /// Compute, store and verify generic start solutions of every sub-problem.
    AbInitio(cli::ab_initio::AbInitioArgs),
    /// 3-PRRR indices and redundancy resolution.
    #[command(subcommand)]
    Prrr(cli::prrr::PrrrCommand),
    /// Conditioning maps of 3RRR and 3PRRR over the workspace.
    Map(cli::map::MapArgs),
    /// 3RRR actuation schemes, singularity loci and GCI.
    Schemes(cli::schemes::SchemesArgs),
    /// 3-RRR distances to parallel and leg singularities along a motion.
    #[command(subcommand)]
    Rrr(cli::rrr::RrrCommand),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Curve(args) => cli::curve::run(args),
        Command::Distance(args) => cli::distance::run(args),
        Command::Draw(args) => cli::draw::run(args),
        Command::Indices(args) => cli::indices::run(args),
        Command::Compare(args) => cli::indices::run_compare(args),
        Command::System(cmd) => cli::system::run(cmd),
        Command::Solve(args) => cli::solve::run(args),
        Command::AbInitio(args) => cli::ab_initio::run(args),
        Command::Prrr(cmd) => cli::prrr::run(cmd),
        Command::Map(args) => cli::map::run(args),
        Command::Schemes(args) => cli::schemes::run(args),
        Command::Rrr(cmd) => cli::rrr::run(cmd),
    };
    if let Err(error) = result {
        eprintln!("singdist: error: {error:#}");
        std::process::exit(1);
    }
}

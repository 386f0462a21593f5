//! The `singdist` command line. Each command parses its arguments, calls one library
//! function and formats the result; all numerics live in the library.

mod cli;

use clap::{Parser, Subcommand};
use cli::deferred::Deferred;
use std::io::Write;
use std::process::ExitCode;

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
    ///
    /// τ: the motion parameter (the unit of the motion file's `tau_range`); a pose is
    /// (x, y, φ), position in the design's length unit, φ in radians. K: the
    /// configuration (anchors a1..a3 of the base, b1..b3 of the platform). S(K): the
    /// singularity polynomial det[b_i − a_i | a_i × b_i] (S = 0: leg lines concurrent or
    /// parallel; unit: length⁴). D(K, K′): the distance to the closest singular
    /// configuration K′ under a metric PLATFORM/BASE, each part a deformable triangular
    /// `plate`, a triangle of three deformable `bars`, or `rigid` (K′ moves it only by a
    /// Euclidean motion), in the design's length unit; signed D carries the sign of S.
    ///
    /// Outputs: `--out FILE.csv` (signed distance per metric, and `lost_paths` per pose:
    /// paths lost there plus those lost at the seed, which affect every pose),
    /// `FILE.jsonl` (JSON Lines, full detail: a header record, one object per pose, a
    /// record per window, a closing summary with every failure) or `FILE.json` (one
    /// document, full detail); without `--out` a compact table on stdout. While running,
    /// every window of poses is appended to `FILE.partial` (JSON Lines) as soon as it is
    /// final; `--resume` continues from it. `--plot`: the signed distance curves against
    /// τ, singular poses marked.
    Curve(Deferred<cli::curve::CurveArgs>),
    /// Singularity distances of a 3-RPR at one pose, in full detail.
    ///
    /// τ: the motion parameter (the unit of the motion file's `tau_range`); a pose is
    /// (x, y, φ), position in the design's length unit, φ in radians. K: the
    /// configuration (anchors a1..a3 of the base, b1..b3 of the platform). S(K): the
    /// singularity polynomial det[b_i − a_i | a_i × b_i] (S = 0: leg lines concurrent or
    /// parallel; unit: length⁴). D(K, K′): the distance to the closest singular
    /// configuration K′ under a metric PLATFORM/BASE, each part a deformable triangular
    /// `plate`, a triangle of three deformable `bars`, or `rigid` (K′ moves it only by a
    /// Euclidean motion), in the design's length unit; signed D carries the sign of S.
    Distance(Deferred<cli::distance::DistanceArgs>),
    /// Re-checks a saved `curve` result: re-solves its poses with another seed,
    /// certifies them, and compares the file's distances (exit 3 if one is contradicted).
    Certify(Deferred<cli::certify::CertifyArgs>),
    /// Drawing (SVG) of a 3-RPR at one pose with each metric's closest singular configuration.
    ///
    /// τ: the motion parameter (the unit of the motion file's `tau_range`); a pose is
    /// (x, y, φ), position in the design's length unit, φ in radians. K: the
    /// configuration (anchors a1..a3 of the base, b1..b3 of the platform). S(K): the
    /// singularity polynomial det[b_i − a_i | a_i × b_i] (S = 0: leg lines concurrent or
    /// parallel; unit: length⁴). D(K, K′): the distance to the closest singular
    /// configuration K′ under a metric PLATFORM/BASE, each part a deformable triangular
    /// `plate`, a triangle of three deformable `bars`, or `rigid` (K′ moves it only by a
    /// Euclidean motion), in the design's length unit; signed D carries the sign of S.
    Draw(Deferred<cli::draw::DrawArgs>),
    /// Kinematic performance indices of a 3-RPR along a motion or at one pose.
    ///
    /// M = |det J| (manipulability, J the inverse Jacobian of unit leg lines); S the
    /// singularity polynomial (length⁴, S = 0 at singular poses); IR the incircle
    /// radius of the triangle of the leg lines (length); TI = min_i |cos α_i| with α_i
    /// the pressure angles (transmission index, 1); DS the pressure-angle index of
    /// Gómez et al., reconstructed (1); MTI = min(TI, TI*) and MDS = min(DS, DS*), *
    /// with base and platform exchanged; CN the control number and MCN = 1/√λ_max;
    /// orientation_distance (rad) and position_distance (length) to the nearest singular
    /// orientation / position; cylinder_radius the singularity-free cylinder radius.
    /// τ: the motion parameter; lengths in the design's unit.
    ///
    /// Outputs: `--out` the table of every index along the motion, `.csv`, `.jsonl`
    /// (JSON Lines: a header record, one object per pose, a closing summary with every
    /// lost path) or `.json` (one document); default: CSV on stdout. `--plot`: the
    /// indices along the motion, each scaled to [0, 1] by its maximum. `--seed` seeds
    /// the metric computation (`--with-metrics`, as `curve --seed`).
    Indices(Deferred<cli::indices::IndicesArgs>),
    /// Indices and metric distances side by side (`indices --with-metrics all`).
    ///
    /// M = |det J| (manipulability, J the inverse Jacobian of unit leg lines); S the
    /// singularity polynomial (length⁴, S = 0 at singular poses); IR the incircle
    /// radius of the triangle of the leg lines (length); TI = min_i |cos α_i| with α_i
    /// the pressure angles (transmission index, 1); DS the pressure-angle index of
    /// Gómez et al., reconstructed (1); MTI = min(TI, TI*) and MDS = min(DS, DS*), *
    /// with base and platform exchanged; CN the control number and MCN = 1/√λ_max;
    /// orientation_distance (rad) and position_distance (length) to the nearest singular
    /// orientation / position; cylinder_radius the singularity-free cylinder radius.
    /// τ: the motion parameter; lengths in the design's unit.
    /// D: the metric distances to the closest singular configuration (see `curve --help`).
    ///
    /// Outputs as `indices --help` describes; the plot shows the metric distances next
    /// to the indices.
    Compare(Deferred<cli::indices::IndicesArgs>),
    /// Inspect and export polynomial systems (Bertini input format).
    #[command(subcommand)]
    System(Deferred<cli::system::SystemCommand>),
    /// Solve a polynomial system by homotopy continuation.
    Solve(Deferred<cli::solve::SolveArgs>),
    /// Compute, store and verify generic start solutions of every sub-problem.
    AbInitio(Deferred<cli::ab_initio::AbInitioArgs>),
    /// 3-PRRR indices and redundancy resolution.
    #[command(subcommand)]
    Prrr(Deferred<cli::prrr::PrrrCommand>),
    /// Conditioning maps of 3RRR and 3PRRR over the workspace.
    Map(Deferred<cli::map::MapArgs>),
    /// 3RRR actuation schemes, singularity loci and GCI.
    ///
    /// Outputs: `--out` the GCI table (`.csv` or `.json`); `--plot` the singularity loci
    /// (rows = orientations, columns = schemes).
    Schemes(Deferred<cli::schemes::SchemesArgs>),
    /// 3-RRR distances to parallel and leg singularities along a motion.
    #[command(subcommand)]
    Rrr(Deferred<cli::rrr::RrrCommand>),
}

/// Restores the default action of `SIGPIPE` (terminate quietly), as Unix command-line
/// tools have it: `singdist curve | head` then ends when `head` stops reading, instead
/// of failing on a write to the closed pipe. (The Rust runtime ignores the signal.)
#[cfg(unix)]
fn restore_default_sigpipe() {
    // SIGPIPE is signal 13 and SIG_DFL is 0 on Linux and the BSDs/macOS.
    const SIGPIPE: i32 = 13;
    const SIG_DFL: usize = 0;
    unsafe extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    // SAFETY: `signal` is the C library's; setting the default disposition of SIGPIPE
    // before any thread starts has no other effect on this program.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

fn main() -> ExitCode {
    #[cfg(unix)]
    restore_default_sigpipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Curve(args) => cli::curve::run(args.0),
        Command::Distance(args) => cli::distance::run(args.0),
        Command::Certify(args) => cli::certify::run(args.0),
        Command::Draw(args) => cli::draw::run(args.0),
        Command::Indices(args) => cli::indices::run(args.0),
        Command::Compare(args) => cli::indices::run_compare(args.0),
        Command::System(cmd) => cli::system::run(cmd.0),
        Command::Solve(args) => cli::solve::run(args.0),
        Command::AbInitio(args) => cli::ab_initio::run(args.0),
        Command::Prrr(cmd) => cli::prrr::run(cmd.0),
        Command::Map(args) => cli::map::run(args.0),
        Command::Schemes(args) => cli::schemes::run(args.0),
        Command::Rrr(cmd) => cli::rrr::run(cmd.0),
    };
    // What is still buffered goes out before the exit code is decided; a reader that
    // has gone away is not an error of the run.
    let _ = std::io::stdout().flush();
    cli::outcome::exit_code_of(result)
}

#[cfg(test)]
mod tests {
    use super::Cli;
    use clap::CommandFactory;

    /// clap's own check of the definition: every flattened group's ids are unique,
    /// every `conflicts_with`/`requires` names an argument, defaults parse.
    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}

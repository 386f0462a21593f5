//! `singdist ab-initio`: compute, store and verify the generic start solutions.
//!
//! `--verify` without `--problem` re-checks every stored file: those of the 3-RPR
//! problems and of the four 3-RRR sub-problems (`rrr ab-initio --verify` checks the
//! latter alone), each read from `--dir` or, where the folder has none, from the copy
//! embedded in the binary.

use super::args::ThreadsArg;
use super::outcome::Outcome;
use super::output::check_output_folder;
use super::resources::thread_count;
use super::start_check::{all_passed, check_stored, trace_text, write_start_file};
use anyhow::{Context, Result, bail};
use clap::Args;
use singdist::pipeline::ab_initio::{self, AbInitioOptions};
use singdist::problem::rrr::{RrrProblem, RrrSubProblem};
use singdist::problem::{LagrangeProblem, ProblemError, ProblemId};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `singdist ab-initio`.
#[derive(Args, Debug)]
pub struct AbInitioArgs {
    /// One problem, `PLATFORM/BASE:SUBPROBLEM` (e.g. `bars/rigid:collinear-platform`).
    #[arg(long, conflicts_with = "all")]
    problem: Option<String>,
    /// Every problem of every metric.
    #[arg(long)]
    all: bool,
    /// Seed of the start pair and the monodromy loops.
    #[arg(long, default_value_t = ab_initio::DEFAULT_SEED)]
    seed: u64,
    /// Re-check the stored files (residuals, counts, distinctness, trace test) instead
    /// of computing: the one of `--problem`, or else every stored file (the 3-RRR ones
    /// too).
    #[arg(long)]
    verify: bool,
    /// Directory of the start-solution files (where it has no file of a problem,
    /// `--verify` checks the copy embedded in the binary).
    #[arg(long, default_value = "supplementary/start")]
    dir: PathBuf,
    #[command(flatten)]
    threads: ThreadsArg,
}

/// Runs `singdist ab-initio`.
pub fn run(args: AbInitioArgs) -> Result<Outcome> {
    if let Some(threads) = thread_count(args.threads)? {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("--threads")?;
    }
    let problem = match &args.problem {
        Some(name) => Some(
            name.parse::<ProblemId>()
                .with_context(|| format!("--problem `{name}`"))?,
        ),
        None => None,
    };
    let started = Instant::now();
    let failures = if args.verify {
        verify_stored(problem, &args.dir)?
    } else {
        let ids = match (problem, args.all) {
            (Some(id), _) => vec![id],
            (None, true) => ProblemId::all(),
            (None, false) => bail!(
                "give --problem NAME or --all to compute, or --verify to re-check the stored files"
            ),
        };
        compute(&ids, &args)?
    };
    eprintln!("total {:.2} s", started.elapsed().as_secs_f64());
    all_passed(failures)
}

/// The problem of `id`, or `None` (with a line saying why) if no metric needs it.
fn applicable(id: ProblemId) -> Result<Option<LagrangeProblem>> {
    match LagrangeProblem::new(id) {
        Ok(problem) => Ok(Some(problem)),
        Err(ProblemError::NotApplicable { reason, .. }) => {
            println!("{:<40} not applicable: {reason}", id.name());
            Ok(None)
        }
        Err(error) => Err(error.into()),
    }
}

/// `--verify`: re-checks the stored file of `problem`, or without one every stored
/// file of the 3-RPR problems and the 3-RRR sub-problems; returns how many failed.
fn verify_stored(problem: Option<ProblemId>, dir: &Path) -> Result<usize> {
    let ids = problem.map_or_else(ProblemId::all, |id| vec![id]);
    let mut problems = Vec::new();
    for id in ids {
        problems.extend(applicable(id)?);
    }
    let mut failures = check_stored(dir, &problems)?;
    if problem.is_none() {
        let rrr: Vec<RrrProblem> = RrrSubProblem::ALL
            .into_iter()
            .map(RrrProblem::new)
            .collect::<Result<_, _>>()?;
        failures += check_stored(dir, &rrr)?;
    }
    Ok(failures)
}

/// Computes, prints and writes the start solutions of `ids` into `--dir`; returns how
/// many failed their checks.
fn compute(ids: &[ProblemId], args: &AbInitioArgs) -> Result<usize> {
    check_output_folder("--dir", &args.dir, true)?;
    let mut failures = 0;
    for &id in ids {
        let Some(problem) = applicable(id)? else {
            continue;
        };
        let clock = Instant::now();
        let options = AbInitioOptions {
            seed: args.seed,
            ..AbInitioOptions::default()
        };
        let file = ab_initio::compute_start_solutions(&problem, &options)?;
        let expected = ab_initio::expected_count(id);
        let ok = file.certificate.passed && expected.is_none_or(|e| e == file.solutions.len());
        println!(
            "{:<40} {} solutions (expected {}), max residual {:.1e}, certificate {} (trace {}), {} loops, {} failed paths, {:.2} s{}",
            id.name(),
            file.solutions.len(),
            expected.map_or("unknown".to_string(), |e| e.to_string()),
            file.max_residual,
            file.certificate.kind,
            trace_text(file.certificate.trace_residual),
            file.certificate.loops,
            file.certificate.failed_paths,
            clock.elapsed().as_secs_f64(),
            if ok { "" } else { "  FAILED" }
        );
        failures += usize::from(!ok);
        std::fs::create_dir_all(&args.dir).with_context(|| format!("{}", args.dir.display()))?;
        write_start_file("--dir", &args.dir, &problem, &file, true)?;
    }
    Ok(failures)
}

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
use singdist::problem::{LagrangeProblem, ProblemError, ProblemId, Stratum};
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
    /// The stratum of the design space to pose the problems on: `generic`, or rigid
    /// parts with collinear anchors, `collinear-base-anchors`,
    /// `collinear-platform-anchors` or `collinear-anchors` (both). Its files are named
    /// `PLATFORM-BASE-SUBPROBLEM.STRATUM.json`; designs on it use them where they exist.
    /// With `--all`, every problem that has the stratum.
    #[arg(long, default_value = "generic", value_parser = parse_stratum)]
    stratum: Stratum,
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
        verify_stored(problem, args.stratum, &args.dir)?
    } else {
        let ids = match (problem, args.all) {
            (Some(id), _) => vec![id],
            (None, true) => ProblemId::all(),
            (None, false) => bail!(
                "give --problem NAME or --all to compute, or --verify to re-check the stored files"
            ),
        };
        let on_stratum = |id: &ProblemId| {
            args.stratum.is_generic() || Stratum::special(*id).contains(&args.stratum)
        };
        if let Some(id) = problem.filter(|id| !on_stratum(id)) {
            bail!(
                "--stratum {}: {} has no rigid part it puts on a line",
                args.stratum.name().unwrap_or("generic"),
                id.name()
            );
        }
        let ids: Vec<ProblemId> = ids.into_iter().filter(on_stratum).collect();
        compute(&ids, &args)?
    };
    eprintln!("total {:.2} s", started.elapsed().as_secs_f64());
    all_passed(failures)
}

/// A `--stratum` value.
fn parse_stratum(name: &str) -> Result<Stratum, String> {
    Stratum::from_name(name).ok_or_else(|| {
        "expected generic, collinear-base-anchors, collinear-platform-anchors or \
         collinear-anchors"
            .to_string()
    })
}

/// The problem of `id` on `stratum`, or `None` (with a line saying why) if no metric
/// needs it.
fn applicable(id: ProblemId, stratum: Stratum) -> Result<Option<LagrangeProblem>> {
    match LagrangeProblem::new_on(id, Default::default(), stratum) {
        Ok(problem) => Ok(Some(problem)),
        Err(ProblemError::NotApplicable { reason, .. }) => {
            println!("{:<40} not applicable: {reason}", id.name());
            Ok(None)
        }
        Err(error) => Err(error.into()),
    }
}

/// `--verify`: re-checks the stored file of `problem` on `stratum`, or without one
/// every stored file of the 3-RPR problems (generic ones, and those of special strata
/// that exist, in `dir` or embedded) and of the 3-RRR sub-problems; returns how many
/// failed.
fn verify_stored(problem: Option<ProblemId>, stratum: Stratum, dir: &Path) -> Result<usize> {
    let mut problems = Vec::new();
    match problem {
        Some(id) => problems.extend(applicable(id, stratum)?),
        None => {
            for id in ProblemId::all() {
                problems.extend(applicable(id, Stratum::GENERIC)?);
                for special in Stratum::special(id) {
                    let stored = dir.join(format!("{}.json", special.file_stem(id))).exists()
                        || ab_initio::embedded_start_solutions_on(id, special).is_some();
                    if stored {
                        problems.extend(applicable(id, special)?);
                    }
                }
            }
        }
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
        let Some(problem) = applicable(id, args.stratum)? else {
            continue;
        };
        let clock = Instant::now();
        let options = AbInitioOptions {
            seed: args.seed,
            ..AbInitioOptions::default()
        };
        let file = ab_initio::compute_start_solutions(&problem, &options)?;
        let expected = ab_initio::AbInitioProblem::expected_count(&problem);
        let ok = file.certificate.passed && expected.is_none_or(|e| e == file.solutions.len());
        println!(
            "{:<40} {} solutions (expected {}), max residual {:.1e}, certificate {} (trace {}), {} loops, {} failed paths, {:.2} s{}",
            ab_initio::AbInitioProblem::name(&problem),
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

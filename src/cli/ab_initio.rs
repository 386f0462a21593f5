//! `singdist ab-initio`: compute, store and verify the generic start solutions.

use super::output::{check_output_folder, write_file};
use super::resources::thread_count;
use anyhow::{Context, bail};
use clap::Args;
use singdist::pipeline::ab_initio::{self, AbInitioOptions, embedded_start_solutions};
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::{LagrangeProblem, ProblemError, ProblemId};
use std::path::PathBuf;
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
    /// Re-check the stored files (residuals, counts, distinctness, trace test) instead of computing.
    #[arg(long)]
    verify: bool,
    /// Directory of the start-solution files.
    #[arg(long, default_value = "supplementary/start")]
    dir: PathBuf,
    /// Number of threads (default: all cores; more than the cores is clamped to them).
    #[arg(long)]
    threads: Option<usize>,
}

/// Runs `singdist ab-initio`.
pub fn run(args: AbInitioArgs) -> anyhow::Result<()> {
    if let Some(threads) = thread_count(args.threads)? {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("--threads")?;
    }
    let ids: Vec<ProblemId> = match (&args.problem, args.all) {
        (Some(name), _) => vec![
            name.parse()
                .with_context(|| format!("--problem `{name}`"))?,
        ],
        (None, true) => ProblemId::all(),
        (None, false) => bail!("give --problem NAME or --all"),
    };
    if !args.verify {
        check_output_folder("--dir", &args.dir, true)?;
    }
    let mut failures = 0;
    let started = Instant::now();
    for id in ids {
        let problem = match LagrangeProblem::new(id) {
            Ok(problem) => problem,
            Err(ProblemError::NotApplicable { reason, .. }) => {
                println!("{:<40} not applicable: {reason}", id.name());
                continue;
            }
            Err(error) => return Err(error.into()),
        };
        let path = args.dir.join(format!("{}.json", id.file_stem()));
        if args.verify {
            let file: StartSolutions = if path.exists() {
                let text = std::fs::read_to_string(&path)
                    .with_context(|| format!("{}", path.display()))?;
                serde_json::from_str(&text).with_context(|| format!("{}", path.display()))?
            } else {
                match embedded_start_solutions(id) {
                    Some(file) => file?,
                    None => {
                        println!("{:<40} MISSING ({})", id.name(), path.display());
                        failures += 1;
                        continue;
                    }
                }
            };
            let check = ab_initio::verify(&problem, &file)?;
            println!(
                "{:<40} {} solutions (expected {}), max residual {:.1e}, min separation {:.1e}, trace {}: {}",
                check.problem,
                check.count,
                check
                    .expected
                    .map_or("unknown".to_string(), |e| e.to_string()),
                check.max_residual,
                check.min_separation,
                check
                    .trace_residual
                    .map_or("not run".to_string(), |t| format!("{t:.1e}")),
                if check.passed { "ok" } else { "FAILED" }
            );
            failures += usize::from(!check.passed);
            continue;
        }
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
            file.certificate
                .trace_residual
                .map_or("not run".to_string(), |t| format!("{t:.1e}")),
            file.certificate.loops,
            file.certificate.failed_paths,
            clock.elapsed().as_secs_f64(),
            if ok { "" } else { "  FAILED" }
        );
        failures += usize::from(!ok);
        std::fs::create_dir_all(&args.dir).with_context(|| format!("{}", args.dir.display()))?;
        write_file("--dir", &path, serde_json::to_string_pretty(&file)?)?;
    }
    eprintln!("total {:.2} s", started.elapsed().as_secs_f64());
    if failures > 0 {
        bail!("{failures} problem(s) failed their checks");
    }
    Ok(())
}

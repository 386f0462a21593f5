//! `singdist solve`: all isolated solutions of a square polynomial system in a Bertini
//! input file, by the total-degree homotopy (default) or by monodromy with a trace test
//! on the constant-term family (`--monodromy`). Exit code 3 when paths failed (listed
//! with their reasons on stderr).

use super::args::ThreadsArg;
use super::outcome::Outcome;
use super::resources::thread_count;
use super::values::parse_assignment;
use anyhow::Context;
use clap::Args;
use serde::Serialize;
use singdist::homotopy::{
    FailureReason, MonodromyOptions, PathStatus, SolveOptions, SolveResult, SolveSummary,
    solve_by_monodromy, solve_total_degree,
};
use singdist::system::{System, bertini};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `singdist solve`.
#[derive(Args, Debug)]
pub struct SolveArgs {
    /// Bertini input file of a square system.
    pub file: PathBuf,
    /// Print `{"summary": …, "solutions": […]}` as JSON instead of the text summary.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub threads: ThreadsArg,
    /// Seed of every random choice; the same seed gives the same result on any
    /// number of threads.
    #[arg(long, default_value_t = 0x5eed)]
    pub seed: u64,
    /// Solve by monodromy + trace test instead of the total-degree homotopy.
    #[arg(long)]
    pub monodromy: bool,
    /// Value of a parameter, `NAME=VALUE` (VALUE like `1.5` or `0.5+2*I`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

/// One solution in the JSON output.
#[derive(Serialize)]
struct SolutionOutput {
    path: usize,
    status: String,
    coordinates: Vec<[f64; 2]>,
    residual: f64,
    condition: f64,
    winding_number: usize,
    multiplicity: usize,
    real: bool,
    steps: usize,
    rejected_steps: usize,
}

#[derive(Serialize)]
struct JsonOutput<'a> {
    summary: &'a SolveSummary,
    variables: &'a [String],
    seconds: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    trace_residual: Option<f64>,
    solutions: Vec<SolutionOutput>,
}

fn status_name(status: PathStatus) -> String {
    match status {
        PathStatus::Nonsingular => "nonsingular".into(),
        PathStatus::Singular => "singular".into(),
        PathStatus::AtInfinity => "at_infinity".into(),
        PathStatus::Failed(reason) => format!("failed: {}", reason_name(reason)),
    }
}

/// The name of a failure reason (as in the `reasons` of `curve`'s failures).
fn reason_name(reason: FailureReason) -> &'static str {
    match reason {
        FailureReason::InvalidStartPoint => "InvalidStartPoint",
        FailureReason::StepSizeTooSmall => "StepSizeTooSmall",
        FailureReason::TooManySteps => "TooManySteps",
        FailureReason::DivergedBeforeEndgame => "DivergedBeforeEndgame",
        FailureReason::WindingNumberTooLarge => "WindingNumberTooLarge",
        FailureReason::EndgameDidNotConverge => "EndgameDidNotConverge",
        FailureReason::NonFiniteValue => "NonFiniteValue",
        FailureReason::PathJumped => "PathJumped",
        FailureReason::CorrectorDidNotConverge => "CorrectorDidNotConverge",
    }
}

/// Prints a one-line warning listing the failed paths with their reasons; returns
/// whether any path failed.
fn warn_failed_paths(result: &SolveResult) -> bool {
    let failed: Vec<(usize, FailureReason)> = result
        .paths
        .iter()
        .filter_map(|p| match p.status {
            PathStatus::Failed(reason) => Some((p.path_index, reason)),
            _ => None,
        })
        .collect();
    if failed.is_empty() {
        return false;
    }
    let mut reasons: BTreeMap<&str, usize> = BTreeMap::new();
    for (_, reason) in &failed {
        *reasons.entry(reason_name(*reason)).or_insert(0) += 1;
    }
    let reasons: Vec<String> = reasons.iter().map(|(r, n)| format!("{r} {n}")).collect();
    const SHOWN: usize = 20;
    let mut paths: Vec<String> = failed
        .iter()
        .take(SHOWN)
        .map(|(j, _)| j.to_string())
        .collect();
    if failed.len() > SHOWN {
        paths.push(format!("… and {} more", failed.len() - SHOWN));
    }
    eprintln!(
        "singdist: warning: {} of {} paths failed ({}): paths {}; solutions may be missing",
        failed.len(),
        result.paths.len(),
        reasons.join(", "),
        paths.join(", ")
    );
    true
}

/// Runs `singdist solve`.
pub fn run(args: SolveArgs) -> anyhow::Result<Outcome> {
    let text = std::fs::read_to_string(&args.file)
        .with_context(|| format!("cannot read {}", args.file.display()))?;
    let mut system: System =
        bertini::read(&text).with_context(|| format!("{}", args.file.display()))?;
    if !args.set.is_empty() {
        let values = args
            .set
            .iter()
            .map(|s| parse_assignment(s))
            .collect::<anyhow::Result<Vec<_>>>()?;
        system = system
            .with_parameter_values(&values)
            .with_context(|| format!("{}: --set", args.file.display()))?;
    }
    if !system.parameters().is_empty() {
        anyhow::bail!(
            "{}: parameters {} have no values; give each with --set NAME=VALUE",
            args.file.display(),
            system.parameters().join(", ")
        );
    }
    let compiled = system.compile();
    let degrees: Vec<u32> = system
        .degrees()
        .iter()
        .map(|&d| u32::try_from(d))
        .collect::<Result<_, _>>()
        .context("an equation degree exceeds 2³²")?;
    let options = SolveOptions {
        seed: args.seed,
        ..SolveOptions::default()
    };
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(threads) = thread_count(args.threads)? {
        builder = builder.num_threads(threads);
    }
    let pool = builder.build().context("cannot start the thread pool")?;
    let started = Instant::now();
    let (result, trace_residual): (SolveResult, Option<f64>) = pool.install(|| {
        if args.monodromy {
            let (monodromy, solved) =
                solve_by_monodromy(&compiled, &[], &MonodromyOptions::default(), &options)?;
            Ok::<_, anyhow::Error>((solved, monodromy.trace_residual))
        } else {
            Ok((
                solve_total_degree(&compiled, &degrees, &[], &options)?,
                None,
            ))
        }
    })?;
    let seconds = started.elapsed().as_secs_f64();
    let s = &result.summary;
    if args.json {
        let solutions = result
            .paths
            .iter()
            .filter(|p| p.status.is_finite())
            .map(|p| SolutionOutput {
                path: p.path_index,
                status: status_name(p.status),
                coordinates: p.solution.iter().map(|z| [z.re, z.im]).collect(),
                residual: p.residual,
                condition: p.condition,
                winding_number: p.winding_number,
                multiplicity: p.multiplicity,
                real: p.is_real(options.real_tolerance),
                steps: p.steps,
                rejected_steps: p.rejected_steps,
            })
            .collect();
        let output = JsonOutput {
            summary: s,
            variables: system.variables(),
            seconds,
            trace_residual,
            solutions,
        };
        emit(&format!("{}\n", serde_json::to_string_pretty(&output)?))?;
    } else {
        let method = if args.monodromy {
            "monodromy + trace test"
        } else {
            "total-degree homotopy"
        };
        let mut text = format!(
            "system        {}\nmethod        {method}\npaths         {}\nnonsingular   {}\nsingular      {} ({} paths)\nat infinity   {}\nfailed        {}\nreal          {}\n",
            args.file.display(),
            s.paths,
            s.nonsingular,
            s.singular,
            s.singular_paths,
            s.at_infinity,
            s.failed,
            s.real
        );
        if let Some(r) = trace_residual {
            text.push_str(&format!("trace residual {r:.3e}\n"));
        }
        text.push_str(&format!("time          {seconds:.3} s\n"));
        emit(&text)?;
    }
    Ok(Outcome::paths_lost_if(warn_failed_paths(&result)))
}

/// Writes to standard output; a closed pipe (`| head`) ends quietly.
fn emit(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

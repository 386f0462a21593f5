//! `singdist solve`: all isolated solutions of a square polynomial system in a Bertini
//! input file, by a straight-line homotopy from a start system (`--start`: by default
//! the polyhedral one where it has at most half the paths of the total degree, else
//! the total degree; or the multi-homogeneous one of the best variable grouping) or
//! by monodromy with a trace test on the constant-term
//! family (`--monodromy`). Exit code 3 when paths failed (listed
//! with their reasons on stderr).

use super::args::ThreadsArg;
use super::outcome::Outcome;
use super::resources::thread_count;
use super::values::parse_assignment;
use anyhow::Context;
use clap::{Args, ValueEnum};
use rand::Rng;
use serde::Serialize;
use singdist::C64;
use singdist::homotopy::multihomogeneous::{
    MonomialSupports, PartitionSearchOptions, SearchMethod, total_degree_paths,
};
use singdist::homotopy::{
    FailureReason, MonodromyOptions, PathStatus, PolyhedralSolve, PolyhedralStartSystem,
    STALLED_NEAR_ROOTS, SolveOptions, SolveResult, SolveSummary, StartChoice, StartRequest,
    Supports, choose_start_system, distinct_nonsingular_roots, polyhedral_if_fewer_paths,
    solve_by_monodromy, solve_from_polyhedral_start, solve_multihomogeneous, solve_total_degree,
};
use singdist::system::scaling::Scaling;
use singdist::system::sparse::{ExpansionError, SparsePolynomial};
use singdist::system::{CompiledSystem, System, bertini};
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
    /// Solve by monodromy + trace test instead of a start-system homotopy.
    #[arg(long, conflicts_with = "start")]
    pub monodromy: bool,
    /// Start system. Default: the polyhedral one when its mixed volume is at most half
    /// the total degree and its mixed cells are found cheaply, else the total degree;
    /// where one to three polyhedral paths fail, a polyhedral run from a fresh random
    /// lifting follows; where paths of the better run still fail, the total-degree
    /// homotopy runs too and the run with more nonsingular roots (then fewer failed
    /// paths) is reported. `auto` also
    /// considers the multi-homogeneous start system of the variable grouping of least
    /// Bézout number; it is not the default: on two of PHCpack's demo systems
    /// (`chemequs`, `des22_24`) it misses a root without a failed path.
    #[arg(long, value_enum)]
    pub start: Option<StartArg>,
    /// Value of a parameter, `NAME=VALUE` (VALUE like `1.5` or `0.5+2*I`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Equation and variable scaling by powers of two (least squares on the logarithms
    /// of the coefficients): `auto` scales when the coefficients spread over more than
    /// 2⁴ on average around each equation's mean and the scaling at least halves that
    /// spread, else normalises the equations alone when their sizes differ by more than
    /// 2⁸; solutions are always reported in the file's variables.
    #[arg(long, value_enum, default_value_t = ScalingArg::Auto)]
    pub scaling: ScalingArg,
}

/// `--scaling`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ScalingArg {
    /// Scale badly scaled systems only.
    Auto,
    /// Always scale (when the equations can be expanded).
    Always,
    /// Never scale.
    Never,
}

/// The scaling in the JSON output.
#[derive(Serialize)]
struct ScalingOutput {
    /// `x_j = 2^{d_j} y_j`, one exponent per variable.
    variable_exponents: Vec<i32>,
    /// Equation `i` times `2^{c_i}`.
    equation_exponents: Vec<i32>,
    /// Root-mean-square binary orders of magnitude of the coefficients around their
    /// equation's mean, before and after.
    rms_before: f64,
    rms_after: f64,
}

/// `--start`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StartArg {
    /// Polyhedral when the mixed volume is at most half of the best Bézout number
    /// (and its cells are cheap), else multi-homogeneous when it beats the total
    /// degree, else total degree.
    Auto,
    /// `x_i^{d_i} − 1`.
    TotalDegree,
    /// Products of linear forms over the best variable grouping found.
    MultiHomogeneous,
    /// Polyhedral homotopy: as many paths as the mixed volume of the Newton
    /// polytopes, each with the origin added (roots with zero coordinates included).
    Polyhedral,
}

/// The start system in the JSON output.
#[derive(Serialize)]
struct StartOutput {
    /// `total-degree` or `multi-homogeneous`.
    name: &'static str,
    /// The variable groups of the multi-homogeneous start system.
    #[serde(skip_serializing_if = "Option::is_none")]
    partition: Option<Vec<Vec<String>>>,
    /// Paths of the start system (tracked).
    paths: u128,
    /// Π d_i.
    total_degree_paths: u128,
    /// Least multi-homogeneous Bézout number found, when searched.
    #[serde(skip_serializing_if = "Option::is_none")]
    multihomogeneous_paths: Option<u128>,
    /// The groups as `{x, y} {z}` (text summary only).
    #[serde(skip)]
    described: Option<String>,
    /// `exhaustive` or `local`. when searched.
    #[serde(skip_serializing_if = "Option::is_none")]
    partition_search: Option<&'static str>,
    /// Mixed volume of the supports with the origin (polyhedral only).
    #[serde(skip_serializing_if = "Option::is_none")]
    mixed_volume: Option<u128>,
    /// Number of mixed cells (polyhedral only).
    #[serde(skip_serializing_if = "Option::is_none")]
    mixed_cells: Option<usize>,
    /// The default's polyhedral run, which lost paths and found fewer roots (or as many
    /// with more failed paths) than the run reported: a polyhedral re-run from a fresh
    /// lifting, or the total-degree run.
    #[serde(skip_serializing_if = "Option::is_none")]
    superseded: Option<Superseded>,
    /// Distinct nonsingular roots that another run of the default start (a superseded
    /// polyhedral run, a polyhedral re-run, or the total-degree run) found and the
    /// reported run lacks ([`roots_missing_from`]): the reported run lost them without
    /// a failed path, and the solve exits with code 3.
    #[serde(skip_serializing_if = "is_zero")]
    roots_only_in_other_runs: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// A polyhedral run the default start replaced by a polyhedral re-run or by the
/// total-degree run.
#[derive(Serialize)]
struct Superseded {
    /// `polyhedral`.
    name: &'static str,
    /// Its paths (the mixed volume).
    paths: u128,
    /// Its nonsingular roots.
    nonsingular: usize,
    /// Its failed paths.
    failed: usize,
}

impl Superseded {
    fn of(solve: &PolyhedralSolve) -> Self {
        Superseded {
            name: "polyhedral",
            paths: solve.mixed_volume,
            nonsingular: solve.result.summary.nonsingular,
            failed: solve.result.summary.failed,
        }
    }
}

/// Polyhedral re-runs the default start makes when a polyhedral run loses paths,
/// before it falls back on the total-degree homotopy.
const POLYHEDRAL_RERUNS: u64 = 1;

/// Re-solves from fresh polyhedral start systems (another random lifting, start
/// coefficients and γ, all drawn from a seed derived from `options.seed`) until a run
/// loses no path, at most [`POLYHEDRAL_RERUNS`] times (none when `first` lost more
/// than [`POLYHEDRAL_RERUN_MAX_FAILED`] paths or the `bezout_paths` of the fallback
/// are fewer than [`POLYHEDRAL_RERUN_PATH_RATIO`] times the mixed volume), and returns the best run by
/// [`solves_better`] (`first` when no re-run beats it). A run without failed paths
/// is complete with probability one, so a path lost to the particular lifting or γ
/// of the first run (PHCpack's `butcher`, `cassou`) costs a second polyhedral run,
/// not the total-degree homotopy; a loss that every run repeats (paths to a
/// positive-dimensional component) still ends in the total-degree fallback. No re-run
/// without `supports` (the system's polyhedral supports). The second value tells
/// whether a re-run replaced `first`.
fn rerun_polyhedral(
    compiled: &CompiledSystem,
    supports: Option<&Supports>,
    bezout_paths: u128,
    options: &SolveOptions,
    first: PolyhedralSolve,
    others: &mut Vec<Vec<C64>>,
) -> anyhow::Result<(PolyhedralSolve, bool)> {
    if first.result.summary.failed > POLYHEDRAL_RERUN_MAX_FAILED
        || first
            .mixed_volume
            .saturating_mul(POLYHEDRAL_RERUN_PATH_RATIO)
            > bezout_paths
    {
        return Ok((first, false));
    }
    let Some(supports) = supports else {
        return Ok((first, false));
    };
    let mut best = first;
    let mut replaced = false;
    for rerun in 1..=POLYHEDRAL_RERUNS {
        let seed =
            singdist::random::stream(options.seed, POLYHEDRAL_RERUN_STREAM + rerun).next_u64();
        let Some(start) = polyhedral_if_fewer_paths(supports, seed, bezout_paths) else {
            continue;
        };
        let rerun_options = SolveOptions {
            seed,
            ..options.clone()
        };
        let solved = solve_from_polyhedral_start(compiled, &start, &[], &rerun_options)?;
        if solves_better(&solved.result.summary, &best.result.summary) {
            others.extend(best.result.nonsingular_solutions());
            best = solved;
            replaced = true;
        } else {
            others.extend(solved.result.nonsingular_solutions());
        }
        if best.result.summary.failed == 0 {
            break;
        }
    }
    Ok((best, replaced))
}

/// A polyhedral run that lost more paths than this is not re-run: a few lost paths
/// are often the lifting's or γ's (PHCpack's `butcher` 1 of 24, `cassou` 1–2 of 24,
/// `cohn2` 0–3 of 150 over four seeds, `redcyc7` 1–3 of 228 over seeds 1–7), many are
/// the system's (`cohn3` 37–44 of 269 over four seeds).
const POLYHEDRAL_RERUN_MAX_FAILED: usize = 3;

/// A re-run is tried only where the fallback it may save tracks at least this many
/// times the polyhedral paths: `discret3s` (128 polyhedral paths, 256 by total
/// degree, a path lost on every lifting) took 0.40 s with the fallback alone and
/// 0.58 s with a re-run before it; `redcyc7` (228 polyhedral paths, 720 by total
/// degree, one thread) takes 1.2–1.3 s with a re-run that loses nothing and 4.3 s with
/// the fallback, whose paths to its singular roots fail by the dozen (seeds 1, 2 and
/// 4: a re-run completes the polyhedral solve; 3, 5 and 7: it loses a path too).
const POLYHEDRAL_RERUN_PATH_RATIO: u128 = 3;

/// The random stream (of `options.seed`) the re-runs' seeds are drawn from.
const POLYHEDRAL_RERUN_STREAM: u64 = 0x5e_7e00;

/// Whether run `a` solved better than run `b` of the same system: more nonsingular
/// roots (each found once), then fewer failed paths.
fn solves_better(a: &SolveSummary, b: &SolveSummary) -> bool {
    (a.nonsingular, std::cmp::Reverse(a.failed)) > (b.nonsingular, std::cmp::Reverse(b.failed))
}

impl StartOutput {
    fn new(choice: &StartChoice, total_degree_paths: u128, variables: &[String]) -> Self {
        let (name, search, partition) = match choice {
            StartChoice::TotalDegree { search, .. } => ("total-degree", search.as_ref(), None),
            StartChoice::MultiHomogeneous { search, .. } => {
                let groups = search.partition.groups().iter();
                let named: Vec<Vec<String>> = groups
                    .map(|g| g.iter().map(|&v| variables[v].clone()).collect())
                    .collect();
                (
                    "multi-homogeneous",
                    Some(search),
                    Some((named, search.partition.describe(variables))),
                )
            }
        };
        StartOutput {
            name,
            described: partition.as_ref().map(|(_, d)| d.clone()),
            partition: partition.map(|(p, _)| p),
            paths: choice.paths(),
            total_degree_paths,
            multihomogeneous_paths: search.map(|s| s.bezout_number),
            partition_search: search.map(|s| search_name(s.method)),
            mixed_volume: None,
            mixed_cells: None,
            superseded: None,
            roots_only_in_other_runs: 0,
        }
    }

    fn polyhedral(solve: &PolyhedralSolve, total_degree_paths: u128) -> Self {
        StartOutput {
            name: "polyhedral",
            partition: None,
            paths: solve.mixed_volume,
            total_degree_paths,
            multihomogeneous_paths: None,
            described: Some(format!(
                "polyhedral, mixed volume {} in {} cells",
                solve.mixed_volume, solve.cells
            )),
            partition_search: None,
            mixed_volume: Some(solve.mixed_volume),
            mixed_cells: Some(solve.cells),
            superseded: None,
            roots_only_in_other_runs: 0,
        }
    }

    /// The `start system` lines of the text summary.
    fn text(&self) -> String {
        let described = match (&self.described, self.mixed_volume) {
            (Some(text), Some(_)) => text.clone(),
            (Some(groups), None) => format!("multi-homogeneous {groups}"),
            (None, _) => self.name.to_string(),
        };
        let best = match (self.partition.is_none(), self.multihomogeneous_paths) {
            (true, Some(b)) => format!(", best multi-homogeneous {b}"),
            _ => String::new(),
        };
        let superseded = match &self.superseded {
            Some(run) => format!(
                "superseded    {} ({} paths, {} nonsingular, {} failed)\n",
                run.name, run.paths, run.nonsingular, run.failed
            ),
            None => String::new(),
        };
        let others = match self.roots_only_in_other_runs {
            0 => String::new(),
            n => format!("other runs    {n} nonsingular root(s) found only by another run\n"),
        };
        format!(
            "start system  {described}\nstart paths   {} (total degree {}{best})\n{superseded}{others}",
            self.paths, self.total_degree_paths
        )
    }
}

/// `exhaustive` or `local`.
pub fn search_name(method: SearchMethod) -> &'static str {
    match method {
        SearchMethod::Exhaustive => "exhaustive",
        SearchMethod::LocalSearch => "local",
    }
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
    start_system: Option<StartOutput>,
    /// The scaling the system was solved in (coordinates and residuals are the file's
    /// system's, condition numbers those of the scaled system).
    #[serde(skip_serializing_if = "Option::is_none")]
    scaling: Option<ScalingOutput>,
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
        FailureReason::DivergedOnRoute => "DivergedOnRoute",
        FailureReason::WindingNumberTooLarge => "WindingNumberTooLarge",
        FailureReason::EndgameDidNotConverge => "EndgameDidNotConverge",
        FailureReason::NonFiniteValue => "NonFiniteValue",
        FailureReason::PathJumped => "PathJumped",
        FailureReason::CorrectorDidNotConverge => "CorrectorDidNotConverge",
        FailureReason::HyperplaneUndecided => "HyperplaneUndecided",
    }
}

/// Prints a one-line warning listing the failed paths with their reasons; returns
/// whether any path failed.
fn warn_failed_paths(result: &SolveResult) -> bool {
    let unconfirmed = result.summary.unconfirmed_at_infinity;
    if unconfirmed > 0 {
        eprintln!(
            "singdist: warning: {unconfirmed} path(s) classified at infinity only because their norm passed 1e8 were not confirmed in a projective chart (JSON unconfirmed_at_infinity): a root of large norm may be missing"
        );
    }
    let stalled = result.summary.stalled_near_roots;
    if stalled > 0 {
        eprintln!(
            "singdist: warning: {stalled} path(s) were put at infinity after stalling near t = 1 at a norm within {STALLED_NEAR_ROOTS} times the largest root found (JSON stalled_near_roots): a root of large norm may be missing"
        );
    }
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
    // One expansion for the scaling, the degrees and the polyhedral supports.
    let expansion = system.expand();
    let scaling = match args.scaling {
        ScalingArg::Never => None,
        ScalingArg::Always => Scaling::least_squares(&system),
        ScalingArg::Auto => expansion
            .as_ref()
            .ok()
            .and_then(|e| Scaling::automatic_of_expansion(&system, e)),
    };
    if args.scaling == ScalingArg::Always && scaling.is_none() {
        eprintln!(
            "singdist: warning: {}: --scaling always: no scaling (an equation cannot be expanded, or the exponents would leave the double range); solved unscaled",
            args.file.display()
        );
    }
    let compiled = match &scaling {
        Some(scaling) => scaling.apply(&system).compile(),
        None => system.compile(),
    };
    let degrees: Vec<u32> = match &expansion {
        Ok(e) => system.degrees_of_expansion(e),
        Err(_) => system.degrees(),
    }
    .iter()
    .map(|&d| u32::try_from(d))
    .collect::<Result<_, _>>()
    .context("an equation degree exceeds 2³²")?;
    let options = SolveOptions {
        seed: args.seed,
        ..SolveOptions::default()
    };
    // The calling thread is worker 0: `install` runs the solve on it directly, one
    // thread fewer is started, and no hand-off to another thread and back (two
    // wake-ups, 0.2-0.4 ms together) is paid. One pool per process, so rayon's leak of
    // such a pool's registry at exit is harmless.
    let mut builder = rayon::ThreadPoolBuilder::new().use_current_thread();
    if let Some(threads) = thread_count(args.threads)? {
        builder = builder.num_threads(threads);
    }
    let pool = builder.build().context("cannot start the thread pool")?;
    let started = Instant::now();
    let forced_polyhedral = args.start == Some(StartArg::Polyhedral);
    let default_start = args.start.is_none() && !args.monodromy;
    let choice = if args.monodromy || forced_polyhedral {
        None
    } else {
        let request = match args.start.unwrap_or(StartArg::TotalDegree) {
            StartArg::Auto => StartRequest::Auto,
            StartArg::TotalDegree => StartRequest::TotalDegree,
            StartArg::MultiHomogeneous | StartArg::Polyhedral => StartRequest::MultiHomogeneous,
        };
        let supports = match request {
            StartRequest::TotalDegree => None,
            _ => MonomialSupports::from_system(&system).ok(),
        };
        Some(
            choose_start_system(
                &degrees,
                supports.as_ref(),
                request,
                &PartitionSearchOptions::default(),
            )
            .with_context(|| format!("{}: --start", args.file.display()))?,
        )
    };
    // The polyhedral start system: when asked for, or under `auto` when it has at most
    // half the paths of the best Bézout-type one and its mixed cells come cheaply.
    let supports = supports_of(&system, &expansion);
    let polyhedral_start = if forced_polyhedral {
        let supports = supports
            .as_ref()
            .map_err(Clone::clone)
            .with_context(|| format!("{}: --start polyhedral", args.file.display()))?;
        Some(
            PolyhedralStartSystem::new(supports, options.seed)
                .with_context(|| format!("{}: --start polyhedral", args.file.display()))?,
        )
    } else if args.start == Some(StartArg::Auto) || default_start {
        let paths = choice.as_ref().map_or(u128::MAX, StartChoice::paths);
        supports
            .as_ref()
            .ok()
            .and_then(|supports| polyhedral_if_fewer_paths(supports, options.seed, paths))
    } else {
        None
    };
    let bezout_paths = choice.as_ref().map_or(u128::MAX, StartChoice::paths);
    let mut polyhedral_output = None;
    let mut superseded = None;
    // The nonsingular roots of the default start's runs that are not reported.
    let mut other_runs: Vec<Vec<C64>> = Vec::new();
    let (result, trace_residual): (SolveResult, Option<f64>) =
        pool.install(|| match (&polyhedral_start, &choice) {
            (Some(start), _) => {
                let mut solved = solve_from_polyhedral_start(&compiled, start, &[], &options)?;
                let total = total_degree_paths(&degrees);
                if default_start && solved.result.summary.failed > 0 {
                    let first = Superseded::of(&solved);
                    let (best, rerun) = rerun_polyhedral(
                        &compiled,
                        supports.as_ref().ok(),
                        bezout_paths,
                        &options,
                        solved,
                        &mut other_runs,
                    )?;
                    if rerun {
                        superseded = Some(first);
                    }
                    solved = best;
                }
                if default_start && solved.result.summary.failed > 0 {
                    // A lost path may be a lost root: the total-degree homotopy too.
                    let by_degree = solve_total_degree(&compiled, &degrees, &[], &options)?;
                    if solves_better(&by_degree.summary, &solved.result.summary) {
                        superseded = Some(Superseded::of(&solved));
                        other_runs.extend(solved.result.nonsingular_solutions());
                        return Ok((by_degree, None));
                    }
                    other_runs.extend(by_degree.nonsingular_solutions());
                }
                polyhedral_output = Some(StartOutput::polyhedral(&solved, total));
                Ok::<_, anyhow::Error>((solved.result, None))
            }
            (None, None) => {
                let (monodromy, solved) =
                    solve_by_monodromy(&compiled, &[], &MonodromyOptions::default(), &options)?;
                Ok::<_, anyhow::Error>((solved, monodromy.trace_residual))
            }
            (None, Some(StartChoice::TotalDegree { .. })) => Ok((
                solve_total_degree(&compiled, &degrees, &[], &options)?,
                None,
            )),
            (None, Some(StartChoice::MultiHomogeneous { search, degrees })) => Ok((
                solve_multihomogeneous(&compiled, &search.partition, degrees, &[], &options)?,
                None,
            )),
        })?;
    let roots_only_in_other_runs = roots_missing_from(&compiled, &result, &other_runs);
    let start_output = polyhedral_output
        .or_else(|| {
            choice
                .as_ref()
                .map(|c| StartOutput::new(c, total_degree_paths(&degrees), system.variables()))
        })
        .map(|output| StartOutput {
            superseded,
            roots_only_in_other_runs,
            ..output
        });
    let seconds = started.elapsed().as_secs_f64();
    let s = &result.summary;
    if args.json {
        let solutions = result
            .paths
            .iter()
            .filter(|p| p.status.is_finite())
            .map(|p| {
                let (coordinates, residual) = match &scaling {
                    Some(s) => {
                        let x = s.unscale(&p.solution);
                        let residual = original_residual(&system, &x);
                        (x, residual)
                    }
                    None => (p.solution.clone(), p.residual),
                };
                (p, coordinates, residual)
            })
            .map(|(p, coordinates, residual)| SolutionOutput {
                path: p.path_index,
                status: status_name(p.status),
                coordinates: coordinates.iter().map(|z| [z.re, z.im]).collect(),
                residual,
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
            start_system: start_output,
            scaling: scaling.as_ref().map(|s| ScalingOutput {
                variable_exponents: s.variables.clone(),
                equation_exponents: s.equations.clone(),
                rms_before: s.rms_before,
                rms_after: s.rms_after,
            }),
            trace_residual,
            solutions,
        };
        emit(&format!("{}\n", serde_json::to_string_pretty(&output)?))?;
    } else {
        let method = if args.monodromy {
            "monodromy + trace test"
        } else {
            "start-system homotopy"
        };
        let start_text = start_output
            .as_ref()
            .map(StartOutput::text)
            .unwrap_or_default();
        let mut text = format!(
            "system        {}\nmethod        {method}\n{start_text}paths         {}\nnonsingular   {}\nsingular      {} ({} paths)\nat infinity   {}\nfailed        {}\nreal          {}\n",
            args.file.display(),
            s.paths,
            s.nonsingular,
            s.singular,
            s.singular_paths,
            s.at_infinity,
            s.failed,
            s.real
        );
        if s.completed_by_conjugation > 0 {
            text.push_str(&format!(
                "conjugates    {} root(s) found as the conjugate of a root, at paths not accounted for\n",
                s.completed_by_conjugation
            ));
        }
        if s.recovered_in_chart + s.at_infinity_in_charts > 0 {
            text.push_str(&format!(
                "charts        {} failed path(s) reached a finite root in a projective chart, {} ended at infinity in two\n",
                s.recovered_in_chart, s.at_infinity_in_charts
            ));
        }
        if let Some(s) = &scaling {
            let exponents = |v: &[i32]| {
                v.iter()
                    .map(|d| d.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            if s.variables.iter().all(|&d| d == 0) {
                text.push_str(&format!(
                    "scaling       equations only, 2^[{}]\n",
                    exponents(&s.equations)
                ));
            } else {
                text.push_str(&format!(
                    "scaling       variables 2^[{}], coefficient spread {:.1} -> {:.1} binary orders\n",
                    exponents(&s.variables),
                    s.rms_before,
                    s.rms_after
                ));
            }
        }
        if let Some(r) = trace_residual {
            text.push_str(&format!("trace residual {r:.3e}\n"));
        }
        text.push_str(&format!("time          {seconds:.3} s\n"));
        emit(&text)?;
    }
    let lost_roots = roots_only_in_other_runs > 0;
    if lost_roots {
        eprintln!(
            "singdist: warning: {}: {roots_only_in_other_runs} nonsingular root(s) found by another run of the default start are missing from the reported run, which lost them without a failed path (JSON start_system.roots_only_in_other_runs)",
            args.file.display()
        );
    }
    Ok(Outcome::paths_lost_if(
        warn_failed_paths(&result) | lost_roots,
    ))
}

/// How many distinct nonsingular roots of `others` (roots of other runs on the same
/// system) `result` lacks: the distinct roots of `result`'s nonsingular solutions
/// together with `others`, beyond those of `result`'s alone
/// ([`distinct_nonsingular_roots`]: refined by Newton's method, grouped at their
/// accuracy). Every run's nonsingular roots are roots of the system, so a run that
/// reports no failed path but lacks one has classified a path to it wrongly (at
/// infinity, or singular): on PHCpack's `discret3s` at seed 12, before its
/// ill-conditioned roots were followed in extended precision, the total-degree run
/// reported 114 nonsingular roots and no failed path, and the polyhedral run it
/// superseded (114 and two failed paths) had found others.
fn roots_missing_from(system: &CompiledSystem, result: &SolveResult, others: &[Vec<C64>]) -> usize {
    if others.is_empty() {
        return 0;
    }
    let reported = result.nonsingular_solutions();
    let alone = distinct_nonsingular_roots(system, &reported).len();
    let mut all = reported;
    all.extend_from_slice(others);
    distinct_nonsingular_roots(system, &all)
        .len()
        .saturating_sub(alone)
}

/// The polyhedral supports of `system` from its `expansion`.
fn supports_of(
    system: &System,
    expansion: &Result<Vec<SparsePolynomial>, ExpansionError>,
) -> Result<Supports, ExpansionError> {
    let expansion = expansion.as_ref().map_err(Clone::clone)?;
    Ok(Supports::from_expansion(
        system.variables().len(),
        expansion,
    ))
}

/// `‖F(x)‖∞` of the file's system (a solution found in scaled coordinates).
fn original_residual(system: &System, x: &[C64]) -> f64 {
    system
        .evaluate_naive(x, &[])
        .iter()
        .fold(0.0f64, |m, v| m.max(v.norm()))
}

/// Writes to standard output; a closed pipe (`| head`) ends quietly.
fn emit(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> CompiledSystem {
        let text = "INPUT\nvariable_group x;\nfunction f;\nf = (x^2 - 1)*(x - 2);\nEND;\n";
        bertini::read(text).unwrap().compile()
    }

    /// A run that put the path to one root at infinity (no failed path) lacks the
    /// root another run found: counted once, however often the other run lists it or
    /// however far its copy is from the refined root; the roots it has are not.
    #[test]
    fn roots_only_another_run_found_are_counted() {
        let system = cubic();
        let mut result = solve_total_degree(&system, &[3], &[], &SolveOptions::default()).unwrap();
        assert_eq!(result.summary.nonsingular, 3);
        let lost = result
            .paths
            .iter()
            .position(|p| (p.solution[0] - 2.0).norm() < 1e-12)
            .unwrap();
        result.paths[lost].status = PathStatus::AtInfinity;
        let others = result.finite_endpoints();
        assert_eq!(roots_missing_from(&system, &result, &others), 0);
        let two = vec![C64::new(2.0 + 1e-9, 0.0)];
        let found = [others.clone(), vec![two.clone(), two]].concat();
        assert_eq!(roots_missing_from(&system, &result, &found), 1);
        assert_eq!(roots_missing_from(&system, &result, &[]), 0);
    }

    /// The text summary names the roots only other runs found.
    #[test]
    fn the_summary_names_roots_only_other_runs_found() {
        let mut output = StartOutput::new(
            &StartChoice::TotalDegree {
                paths: 3,
                search: None,
            },
            3,
            &[],
        );
        assert!(!output.text().contains("other runs"));
        output.roots_only_in_other_runs = 2;
        assert!(
            output
                .text()
                .contains("other runs    2 nonsingular root(s) found only by another run\n"),
            "{}",
            output.text()
        );
    }
}

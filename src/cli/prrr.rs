//! `singdist prrr`: 3-PRRR indices at one pose (docs/theory.md §11.2) and redundancy
//! resolution (docs/theory.md §11.3).

use super::outcome::Outcome;
use super::output::{check_writable, write_file};
use super::values::parse_numbers;
use anyhow::{Context, bail};
use clap::{Args, Subcommand};
use singdist::analysis::redundancy::{
    Aggregate, RedundancyProblem, Resolution, Scheme, TaskIndex, Trajectory, resolve,
};
use singdist::index::prrr::{LciVariant, all_indices};
use singdist::mechanism::prrr::{Pose, PrrrDesign, Robot, parse_modes};
use singdist::optimize::{GeneticOptions, LocalOptions};
use std::path::PathBuf;

/// Sub-commands of `singdist prrr`.
#[derive(Subcommand, Debug)]
pub enum PrrrCommand {
    /// LCI (both variants) and NSIR of one configuration (SI units).
    Index(IndexArgs),
    /// Redundancy resolution along a task: GA + local refinement of δ (Farias Filho, da Silva, Fontes 2021, §4).
    Resolve(ResolveArgs),
}

/// Arguments of `singdist prrr index`.
#[derive(Args, Debug)]
pub struct IndexArgs {
    /// Pose `x,y,alpha` (m, m, rad).
    #[arg(long, allow_hyphen_values = true)]
    pose: String,
    /// Prismatic inputs `d1,d2,d3` (m).
    #[arg(long, allow_hyphen_values = true, default_value = "0,0,0")]
    delta: String,
    /// Design preset: farias2021 (Farias Filho, da Silva, Fontes 2021) or fontes2017 (Fontes, Vieira, da Silva).
    #[arg(long, default_value = "farias2021")]
    preset: String,
    /// Working modes σ_i, e.g. `+,-,+`.
    #[arg(long, allow_hyphen_values = true, default_value = "+,+,+")]
    modes: String,
    /// Robot: 3prrr, or 3rrr (δ must then be 0).
    #[arg(long, default_value = "3prrr")]
    robot: String,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Arguments of `singdist prrr resolve`.
#[derive(Args, Debug)]
pub struct ResolveArgs {
    /// Task: line, circle, spiral, square, or all.
    #[arg(long, default_value = "line")]
    trajectory: String,
    /// Scheme: prepositioning, continuous, or all.
    #[arg(long, default_value = "prepositioning")]
    scheme: String,
    /// Index maximised: lci (1/κ(Ā⁻¹B̄)), nsir, or all.
    #[arg(long, default_value = "lci")]
    index: String,
    /// Aggregate along the task: mean (default) or min.
    #[arg(long, default_value = "mean")]
    aggregate: String,
    /// Seed of the genetic algorithm.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// GA population.
    #[arg(long, default_value_t = 60)]
    population: usize,
    /// GA generations.
    #[arg(long, default_value_t = 100)]
    generations: usize,
    /// Samples along the task (default: 361 for the spiral, 121 otherwise).
    #[arg(long)]
    samples: Option<usize>,
    /// Design preset.
    #[arg(long, default_value = "farias2021")]
    preset: String,
    /// Working modes along the task.
    #[arg(long, allow_hyphen_values = true, default_value = "+,+,+")]
    modes: String,
    /// Passes along the task used to time each index evaluation.
    #[arg(long, default_value_t = 200)]
    timing_repetitions: usize,
    /// Write the table to this file: JSON if it ends in `.json`, CSV otherwise.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the optimised joint trajectories (s, pose, δ, LCI, NSIR per sample) as CSV.
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Print JSON on stdout instead of CSV.
    #[arg(long)]
    json: bool,
}

/// Runs `singdist prrr`.
pub fn run(command: PrrrCommand) -> anyhow::Result<Outcome> {
    match command {
        PrrrCommand::Index(args) => run_index(args)?,
        PrrrCommand::Resolve(args) => run_resolve(args)?,
    }
    Ok(Outcome::Complete)
}

fn run_index(args: IndexArgs) -> anyhow::Result<()> {
    let design = PrrrDesign::preset(&args.preset).context("--preset")?;
    let [x, y, alpha] = parse_numbers(&args.pose, "--pose", ["x", "y", "alpha"])?;
    let delta = parse_numbers(&args.delta, "--delta", ["d1", "d2", "d3"])?;
    let modes = parse_modes(&args.modes).context("--modes")?;
    let robot: Robot = args.robot.parse().context("--robot")?;
    if robot == Robot::ThreeRrr && delta != [0.0; 3] {
        bail!("--delta: the 3RRR has no prismatic joints, δ must be 0,0,0");
    }
    let configuration = design
        .inverse_kinematics(&Pose::new(x, y, alpha), &delta, &modes)
        .context("inverse kinematics")?;
    let indices = all_indices(&design, &configuration, robot);
    let inverse_measure = configuration.inverse_singularity_measure(&design, robot);
    if args.json {
        let value = serde_json::json!({
            "preset": args.preset,
            "robot": robot,
            "pose": {"x": x, "y": y, "alpha": alpha},
            "delta": delta,
            "modes": modes.map(|m| m.sign()),
            "lci": indices.lci_inv_a_b,
            "lci_variant": LciVariant::InverseAB.formula(),
            "lci_inv_a_b": indices.lci_inv_a_b,
            "lci_a": indices.lci_a,
            "nsir": indices.nsir,
            "r_norm": indices.r_norm,
            "xi": indices.xi,
            "incircle_radius": indices.incircle_radius,
            "direct_singularity_measure": indices.direct_singularity_measure,
            "inverse_singularity_measure": inverse_measure,
            "theta": configuration.theta,
            "beta": configuration.beta,
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        println!(
            "preset {} ({}), pose ({x}, {y}, {alpha}), delta ({}, {}, {}), modes {}",
            args.preset, args.robot, delta[0], delta[1], delta[2], args.modes
        );
        println!("lci   1/κ(Ā⁻¹B̄) = {:.6}", indices.lci_inv_a_b);
        println!("lci_a 1/κ(Ā)     = {:.6}", indices.lci_a);
        println!(
            "nsir             = {:.6}  (r_norm {:.6} × xi {:.6})",
            indices.nsir, indices.r_norm, indices.xi
        );
        println!(
            "det Ā / l2³      = {:.6e}",
            indices.direct_singularity_measure
        );
        println!("inverse measure  = {inverse_measure:.6e}");
    }
    Ok(())
}

fn choices<T: Copy + std::str::FromStr>(
    text: &str,
    all: &[T],
    option: &str,
) -> anyhow::Result<Vec<T>>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    if text.trim().eq_ignore_ascii_case("all") {
        return Ok(all.to_vec());
    }
    text.split(',')
        .map(|part| part.parse::<T>().with_context(|| format!("--{option}")))
        .collect()
}

const CSV_HEADER: [&str; 23] = [
    "trajectory",
    "scheme",
    "index",
    "aggregate",
    "objective",
    "objective_at_delta0",
    "lci_mean",
    "lci_min",
    "lci_max",
    "nsir_mean",
    "nsir_min",
    "nsir_max",
    "unreachable_samples",
    "samples",
    "ga_evaluations",
    "local_evaluations",
    "optimisation_s",
    "ns_per_lci",
    "ns_per_nsir",
    "variables",
    "seed",
    "population",
    "generations",
];

fn csv_row(r: &Resolution, args: &ResolveArgs) -> Vec<String> {
    vec![
        r.trajectory.name().into(),
        r.scheme.name().into(),
        r.index.name().into(),
        format!("{:?}", r.aggregate).to_lowercase(),
        format!("{:.6}", r.objective),
        format!("{:.6}", r.objective_at_zero),
        format!("{:.6}", r.lci.mean),
        format!("{:.6}", r.lci.min),
        format!("{:.6}", r.lci.max),
        format!("{:.6}", r.nsir.mean),
        format!("{:.6}", r.nsir.min),
        format!("{:.6}", r.nsir.max),
        r.unreachable_samples.to_string(),
        r.samples.to_string(),
        r.genetic.evaluations.to_string(),
        r.local.evaluations.to_string(),
        format!("{:.3}", r.optimisation_seconds),
        format!("{:.1}", r.ns_per_lci),
        format!("{:.1}", r.ns_per_nsir),
        r.variables
            .iter()
            .map(|v| format!("{v:.6}"))
            .collect::<Vec<_>>()
            .join(" "),
        args.seed.to_string(),
        args.population.to_string(),
        args.generations.to_string(),
    ]
}

fn run_resolve(args: ResolveArgs) -> anyhow::Result<()> {
    let design = PrrrDesign::preset(&args.preset).context("--preset")?;
    let trajectories = choices(&args.trajectory, &Trajectory::ALL, "trajectory")?;
    let schemes = choices(&args.scheme, &Scheme::ALL, "scheme")?;
    let indices = choices(&args.index, &TaskIndex::ALL, "index")?;
    let aggregate: Aggregate = args.aggregate.parse().context("--aggregate")?;
    let modes = parse_modes(&args.modes).context("--modes")?;
    if let Some(path) = &args.out {
        check_writable("--out", path)?;
    }
    if let Some(path) = &args.profile {
        check_writable("--profile", path)?;
    }
    let genetic = GeneticOptions {
        population: args.population,
        generations: args.generations,
        seed: args.seed,
        ..GeneticOptions::default()
    };
    let local = LocalOptions::default();
    let mut results = Vec::new();
    let mut profile = csv::Writer::from_writer(Vec::new());
    profile.write_record([
        "trajectory",
        "scheme",
        "index",
        "s",
        "x",
        "y",
        "alpha",
        "delta1",
        "delta2",
        "delta3",
        "lci",
        "nsir",
    ])?;
    for &trajectory in &trajectories {
        for &scheme in &schemes {
            for &index in &indices {
                let samples = args.samples.unwrap_or(trajectory.default_samples());
                let problem = RedundancyProblem::new(
                    design.clone(),
                    trajectory,
                    scheme,
                    index,
                    aggregate,
                    modes,
                    samples,
                )?;
                // Initial individuals: δ = 0 (the non-redundant reference) and, for continuous
                // positioning, the prepositioning optimum as a constant profile (δ_o = δ_f).
                let mut initial = vec![vec![0.0; scheme.dimension()]];
                if scheme == Scheme::Continuous
                    && let Some(pre) = results.iter().find(|r: &&Resolution| {
                        r.trajectory == trajectory
                            && r.index == index
                            && r.scheme == Scheme::Prepositioning
                    })
                {
                    initial.push(
                        pre.variables
                            .iter()
                            .chain(&pre.variables)
                            .copied()
                            .collect(),
                    );
                }
                let genetic = GeneticOptions {
                    initial,
                    ..genetic.clone()
                };
                let result = resolve(&problem, &genetic, &local, args.timing_repetitions)?;
                eprintln!(
                    "{} {} {}: F = {:.4} (δ = 0: {:.4}), {:.2} s",
                    trajectory.name(),
                    scheme.name(),
                    index.name(),
                    result.objective,
                    result.objective_at_zero,
                    result.optimisation_seconds
                );
                for sample in problem.profile(&result.variables) {
                    let field = |v: Option<f64>| v.map(|v| format!("{v:.6}")).unwrap_or_default();
                    profile.write_record([
                        trajectory.name().to_string(),
                        scheme.name().to_string(),
                        index.name().to_string(),
                        format!("{:.6}", sample.s),
                        format!("{:.6}", sample.pose.x),
                        format!("{:.6}", sample.pose.y),
                        format!("{:.6}", sample.pose.alpha),
                        format!("{:.6}", sample.delta[0]),
                        format!("{:.6}", sample.delta[1]),
                        format!("{:.6}", sample.delta[2]),
                        field(sample.lci),
                        field(sample.nsir),
                    ])?;
                }
                results.push(result);
            }
        }
    }
    let csv_text = || -> anyhow::Result<String> {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(CSV_HEADER)?;
        for r in &results {
            w.write_record(csv_row(r, &args))?;
        }
        Ok(String::from_utf8(w.into_inner()?)?)
    };
    let json_text = || serde_json::to_string_pretty(&results);
    if let Some(path) = &args.out {
        let text = if path.extension().is_some_and(|e| e == "json") {
            json_text()?
        } else {
            csv_text()?
        };
        write_file("--out", path, text)?;
    }
    if let Some(path) = &args.profile {
        write_file("--profile", path, profile.into_inner()?)?;
    }
    if args.json {
        println!("{}", json_text()?);
    } else {
        print!("{}", csv_text()?);
    }
    Ok(())
}

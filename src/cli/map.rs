//! `singdist map`: conditioning maps of the 3RRR and 3-PRRR (Fontes, Vieira, da Silva,
//! "The impact of kinematic redundancies on the conditioning of a planar parallel
//! manipulator").

use super::outcome::Outcome;
use super::output::check_output_file;
use super::values::parse_numbers;
use anyhow::{Context, bail};
use clap::Args;
use singdist::index::map::{MapOptions, ModeSelection, conditioning_map};
use singdist::index::prrr::LciVariant;
use singdist::mechanism::prrr::{PrrrDesign, Robot, parse_modes};
use std::path::PathBuf;

/// Arguments of `singdist map`.
#[derive(Args, Debug)]
pub struct MapArgs {
    /// Robot: 3rrr (one configuration per node) or 3prrr (best over a k³ δ grid).
    #[arg(long, default_value = "3prrr")]
    robot: String,
    /// Design preset: fontes2017 (Fontes, Vieira, da Silva) or farias2021 (Farias Filho,
    /// da Silva, Fontes 2021).
    #[arg(long, default_value = "fontes2017")]
    preset: String,
    /// Fixed orientation α (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    alpha: f64,
    /// Grid extent in x, `lo,hi` (m).
    #[arg(long, default_value = "-0.4,0.4", allow_hyphen_values = true)]
    x_range: String,
    /// Grid extent in y, `lo,hi` (m).
    #[arg(long, default_value = "-0.25,0.45", allow_hyphen_values = true)]
    y_range: String,
    /// Grid spacing (m).
    #[arg(long, default_value_t = 0.005)]
    step: f64,
    /// Levels k of each δ_i (3prrr).
    #[arg(long, default_value_t = 11)]
    levels: usize,
    /// Working modes `+,+,+`, or `all` to search them per node.
    #[arg(long, default_value = "+,+,+", allow_hyphen_values = true)]
    modes: String,
    /// Index: lci_a (1/κ(Ā), as Fontes, Vieira, da Silva) or lci_inv_a_b (1/κ(Ā⁻¹B̄), as
    /// Farias Filho, da Silva, Fontes).
    #[arg(long, default_value = "lci_a")]
    variant: String,
    /// SVG heat map (3prrr: index and the three arg-max δ maps).
    #[arg(long)]
    out: Option<PathBuf>,
    /// CSV table of the nodes.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// Parses `lo,hi` (finite, within ±1e12, `lo < hi`), the value of `option`.
fn parse_range(text: &str, option: &str) -> anyhow::Result<(f64, f64)> {
    let [lo, hi] = parse_numbers(text, option, ["lo", "hi"])?;
    if lo >= hi {
        bail!("{option}: [{lo}, {hi}] must have lo < hi");
    }
    Ok((lo, hi))
}

/// Runs `singdist map`.
pub fn run(args: MapArgs) -> anyhow::Result<Outcome> {
    let design = PrrrDesign::preset(&args.preset).context("--preset")?;
    let robot: Robot = args.robot.parse().context("--robot")?;
    let x_range = parse_range(&args.x_range, "--x-range")?;
    let y_range = parse_range(&args.y_range, "--y-range")?;
    if !(args.step.is_finite() && args.step > 0.0) {
        bail!("--step: {} must be a positive length", args.step);
    }
    let nodes = |(lo, hi): (f64, f64)| -> anyhow::Result<usize> {
        let n = ((hi - lo) / args.step).round() + 1.0;
        if !(n.is_finite() && (2.0..=100_000.0).contains(&n)) {
            bail!("--step: {} gives {n} nodes over [{lo}, {hi}]", args.step);
        }
        Ok(n as usize)
    };
    let modes = if args.modes.trim().eq_ignore_ascii_case("all") {
        ModeSelection::Best
    } else {
        ModeSelection::Fixed(parse_modes(&args.modes).context("--modes")?)
    };
    let variant = match args.variant.as_str() {
        "lci_a" => LciVariant::DirectA,
        "lci_inv_a_b" => LciVariant::InverseAB,
        other => bail!("--variant: unknown `{other}` (lci_a or lci_inv_a_b)"),
    };
    let options = MapOptions {
        robot,
        alpha: args.alpha,
        x_range,
        y_range,
        nx: nodes(x_range)?,
        ny: nodes(y_range)?,
        delta_levels: args.levels,
        modes,
        variant,
    };
    if let Some(path) = &args.csv {
        check_output_file("--csv", path, &["csv"])?;
    }
    if let Some(path) = &args.out {
        check_output_file("--out", path, &["svg"])?;
    }
    let start = std::time::Instant::now();
    let map = conditioning_map(&design, &options)?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(path) = &args.csv {
        let file =
            std::fs::File::create(path).with_context(|| format!("--csv {}", path.display()))?;
        map.write_csv(std::io::BufWriter::new(file))
            .with_context(|| format!("--csv {}", path.display()))?;
    }
    if let Some(path) = &args.out {
        map.write_svg(path, design.delta_range)
            .with_context(|| format!("--out {}", path.display()))?;
    }
    let cell = map.cell_area();
    let summary = serde_json::json!({
        "robot": args.robot,
        "preset": args.preset,
        "index": variant.formula(),
        "alpha": args.alpha,
        "nodes": map.values.len(),
        "reachable_nodes": map.reachable_nodes(),
        "reachable_area_m2": map.reachable_nodes() as f64 * cell,
        "unreachable_holes": map.unreachable_holes(),
        "min": map.min_value(),
        "max": map.max_value(),
        "nodes_at_least_0.8": map.nodes_at_least(0.8),
        "area_at_least_0.8_m2": map.nodes_at_least(0.8) as f64 * cell,
        "nodes_below_0.2": map.reachable_nodes() - map.nodes_at_least(0.2),
        "seconds": seconds,
    });
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else if let serde_json::Value::Object(fields) = summary {
        for (key, value) in fields {
            println!("{key}: {value}");
        }
    }
    Ok(Outcome::Complete)
}

//! `singdist schemes`: the eight actuation schemes of the 3-RRR (docs/theory.md §11.5,
//! Ramana Babu et al.): GCI table per scheme and orientation, singularity-loci plot, and
//! with `--optimize` the GA-optimal design vector `(a, b, c)` per scheme.
//!
//! The example geometry (Ramana Babu et al. gives none) is documented in
//! [`singdist::index::actuation::ExampleGeometry`]: base radius 5, `(a, b, c) = (1.5, 3.0, 3.5)`,
//! grid `[−5, 5]²`, positive working modes, no joint limits.

use super::args::TableOutputArgs;
use super::outcome::Outcome;
use super::output::{check_output_file, write_file};
use anyhow::{Context, bail};
use clap::Args;
use singdist::analysis::actuation_design::{DesignOptimum, DesignProblem, optimize_design};
use singdist::index::actuation::{
    ConditionNorm, ExampleGeometry, GciDomain, GciOptions, GciResult, LociMap, PsiModel, Scheme,
    WorkspaceGrid, gci, plot_loci_svg, singularity_loci,
};
use singdist::mechanism::rrr::{ElbowMode, WorkingModes};
use singdist::optimize::GeneticOptions;

/// Arguments of `singdist schemes` (boxed: the option set is large).
#[derive(Args, Debug)]
pub struct SchemesArgs {
    #[command(flatten)]
    options: Box<SchemesOptions>,
}

/// The options of `singdist schemes`.
#[derive(Args, Debug)]
struct SchemesOptions {
    /// Constant platform orientation in degrees (default: both 0 and 20, as in Ramana Babu, Ramachandra Raju, Ramji).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    orientation: Option<f64>,
    /// Also optimise (a, b, c) per scheme with the GA (a + b + c <= lambda).
    #[arg(long)]
    optimize: bool,
    /// Scheme number 1..8, name (θθψ / ttp) or `all`.
    #[arg(long, default_value = "all")]
    scheme: String,
    #[command(flatten)]
    output: TableOutputArgs,
    /// Seed of the GA.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Base circumradius R of the symmetric design.
    #[arg(long, default_value_t = ExampleGeometry::default().base_radius)]
    base_radius: f64,
    /// `a` of Ramana Babu et al.: platform circumradius |PC_i|.
    #[arg(long, default_value_t = ExampleGeometry::default().platform_radius)]
    platform: f64,
    /// `b` of Ramana Babu et al.: proximal link |O_iB_i|.
    #[arg(long, default_value_t = ExampleGeometry::default().proximal)]
    proximal: f64,
    /// `c` of Ramana Babu et al.: distal link |B_iC_i|.
    #[arg(long, default_value_t = ExampleGeometry::default().distal)]
    distal: f64,
    /// Nodes per side of the square grid [-half_width, half_width]^2.
    #[arg(long, default_value_t = 81)]
    grid: usize,
    /// Half width of the grid (default: the base radius).
    #[arg(long)]
    half_width: Option<f64>,
    /// Nodes per side of the grid used inside the GA objective.
    #[arg(long, default_value_t = 41)]
    optimize_grid: usize,
    /// Working modes of the three legs, e.g. `+++` or `+-+`.
    #[arg(long, default_value = "+++")]
    modes: String,
    /// ψ-actuation model: `seed` (absolute ψ, the matrices of Ramana Babu et al.) or
    /// `relative` (elbow motor).
    #[arg(long, default_value = "seed")]
    psi_model: String,
    /// Norm of the condition number: `2-norm` or `weighted-frobenius`.
    #[arg(long, default_value = "2-norm")]
    norm: String,
    /// GCI mean of the table: `reachable` (Ramana Babu et al., Eq. 20) or `grid`
    /// (unreachable = 0).
    #[arg(long, default_value = "reachable")]
    domain: String,
    /// GCI mean inside the GA objective (default `grid`: reachable-only rewards shrinking).
    #[arg(long, default_value = "grid")]
    optimize_domain: String,
    /// Size limit lambda of a + b + c <= lambda.
    #[arg(long, default_value_t = 9.3)]
    lambda: f64,
    /// GA population.
    #[arg(long, default_value_t = 60)]
    population: usize,
    /// GA generations.
    #[arg(long, default_value_t = 100)]
    generations: usize,
}

/// One row of the output table.
#[derive(Debug, Clone, serde::Serialize)]
struct Row {
    orientation_deg: f64,
    scheme: u8,
    name: String,
    gci: f64,
    gci_domain: &'static str,
    mean_reachable: f64,
    mean_grid: f64,
    reachable_nodes: usize,
    singular_nodes: usize,
    total_nodes: usize,
    type_ii_locus_points: usize,
    a: f64,
    b: f64,
    c: f64,
    optimal_a: Option<f64>,
    optimal_b: Option<f64>,
    optimal_c: Option<f64>,
    optimal_objective: Option<f64>,
    optimal_gci_reachable: Option<f64>,
    initial_objective: Option<f64>,
    ga_evaluations: Option<usize>,
}

fn parse_modes(text: &str) -> anyhow::Result<WorkingModes> {
    let signs: Vec<ElbowMode> = text
        .chars()
        .map(|ch| match ch {
            '+' => Ok(ElbowMode::Positive),
            '-' => Ok(ElbowMode::Negative),
            other => bail!("--modes: `{other}` is not + or -"),
        })
        .collect::<anyhow::Result<_>>()?;
    if signs.len() != 3 {
        bail!("--modes: need three signs like +++, got `{text}`");
    }
    Ok([signs[0], signs[1], signs[2]])
}

/// Runs `singdist schemes`.
pub fn run(args: SchemesArgs) -> anyhow::Result<Outcome> {
    let args = *args.options;
    let schemes: Vec<Scheme> = if args.scheme.eq_ignore_ascii_case("all") {
        Scheme::all().to_vec()
    } else {
        vec![args.scheme.parse().context("--scheme")?]
    };
    let orientations_deg: Vec<f64> = match args.orientation {
        Some(deg) if deg.is_finite() => vec![deg],
        Some(deg) => bail!("--orientation must be finite, got {deg}"),
        None => vec![0.0, 20.0],
    };
    let geometry = ExampleGeometry {
        base_radius: args.base_radius,
        platform_radius: args.platform,
        proximal: args.proximal,
        distal: args.distal,
    };
    let design = geometry.design().context("design")?;
    let half_width = args.half_width.unwrap_or(args.base_radius);
    let grid = WorkspaceGrid::square(half_width, args.grid);
    grid.validate().context("--grid/--half-width")?;
    let options = GciOptions {
        modes: parse_modes(&args.modes)?,
        model: args.psi_model.parse::<PsiModel>()?,
        norm: args.norm.parse::<ConditionNorm>()?,
        domain: args.domain.parse::<GciDomain>()?,
        length_scale: None,
    };
    let optimize_domain: GciDomain = args.optimize_domain.parse()?;

    eprintln!(
        "3-RRR example geometry: R = {}, (a, b, c) = ({}, {}, {}); grid {}x{} on [-{hw}, {hw}]^2; modes {}; psi model {}; norm {}; GCI over {} nodes",
        args.base_radius,
        args.platform,
        args.proximal,
        args.distal,
        args.grid,
        args.grid,
        args.modes,
        options.model.name(),
        options.norm.name(),
        options.domain.name(),
        hw = half_width,
    );

    if let Some(path) = &args.output.out {
        check_output_file("--out", path, &["csv", "json"])?;
    }
    if let Some(path) = &args.output.plot {
        check_output_file("--plot", path, &["svg"])?;
    }
    let mut rows = Vec::new();
    let mut maps: Vec<LociMap> = Vec::new();
    for &deg in &orientations_deg {
        let phi = deg.to_radians();
        for &scheme in &schemes {
            let result: GciResult = gci(&design, scheme, phi, &grid, &options)?;
            let loci =
                singularity_loci(&design, scheme, phi, &grid, &options.modes, options.model)?;
            let optimum: Option<DesignOptimum> = if args.optimize {
                let mut problem = DesignProblem::example(scheme, phi, args.optimize_grid);
                problem.base_radius = args.base_radius;
                problem.size_limit = args.lambda;
                problem.grid = WorkspaceGrid::square(half_width, args.optimize_grid);
                problem.gci = GciOptions {
                    domain: optimize_domain,
                    ..options
                };
                let ga = GeneticOptions {
                    population: args.population,
                    generations: args.generations,
                    seed: args.seed,
                    ..GeneticOptions::default()
                };
                eprintln!("optimising scheme {scheme} at {deg} deg ...");
                Some(optimize_design(&problem, geometry.design_vector(), &ga)?)
            } else {
                None
            };
            rows.push(Row {
                orientation_deg: deg,
                scheme: scheme.number(),
                name: scheme.name(),
                gci: result.gci,
                gci_domain: options.domain.name(),
                mean_reachable: result.mean_reachable,
                mean_grid: result.mean_grid,
                reachable_nodes: result.reachable_nodes,
                singular_nodes: result.singular_nodes,
                total_nodes: result.total_nodes,
                type_ii_locus_points: loci.type_ii.len(),
                a: args.platform,
                b: args.proximal,
                c: args.distal,
                optimal_a: optimum.as_ref().map(|o| o.design_vector[0]),
                optimal_b: optimum.as_ref().map(|o| o.design_vector[1]),
                optimal_c: optimum.as_ref().map(|o| o.design_vector[2]),
                optimal_objective: optimum.as_ref().map(|o| o.objective),
                optimal_gci_reachable: optimum.as_ref().map(|o| o.gci.mean_reachable),
                initial_objective: optimum.as_ref().map(|o| o.initial_objective),
                ga_evaluations: optimum.as_ref().map(|o| o.evaluations),
            });
            maps.push(loci);
        }
    }

    print_table(&rows, args.optimize, optimize_domain);
    print_orientation_verdict(&rows, &orientations_deg, "GCI", |r| Some(r.gci));
    if args.optimize {
        print_orientation_verdict(&rows, &orientations_deg, "optimised objective", |r| {
            r.optimal_objective
        });
    }

    if let Some(path) = &args.output.out {
        write_table(path, &rows)?;
        eprintln!("table written to {}", path.display());
    }
    if let Some(path) = &args.output.plot {
        plot_loci_svg(path, &maps, schemes.len())?;
        eprintln!(
            "loci plot written to {} (grey reachable, blue Type I, red Type II)",
            path.display()
        );
    }
    Ok(Outcome::Complete)
}

fn print_table(rows: &[Row], optimized: bool, optimize_domain: GciDomain) {
    print!(
        "{:>7} {:>6} {:>4} {:>8} {:>8} {:>9} {:>9}",
        "phi_deg", "scheme", "name", "GCI", "GCI_grid", "reachable", "TypeII_pts"
    );
    if optimized {
        print!(
            " | {:>6} {:>6} {:>6} {:>9} {:>9}",
            "a*",
            "b*",
            "c*",
            format!("opt_{}", optimize_domain.name()),
            "initial"
        );
    }
    println!();
    for row in rows {
        print!(
            "{:>7.1} {:>6} {:>4} {:>8.4} {:>8.4} {:>9} {:>9}",
            row.orientation_deg,
            row.scheme,
            row.name,
            row.gci,
            row.mean_grid,
            row.reachable_nodes,
            row.type_ii_locus_points
        );
        if let (Some(a), Some(b), Some(c), Some(v), Some(v0)) = (
            row.optimal_a,
            row.optimal_b,
            row.optimal_c,
            row.optimal_objective,
            row.initial_objective,
        ) {
            print!(" | {a:>6.3} {b:>6.3} {c:>6.3} {v:>9.4} {v0:>9.4}");
        }
        println!();
    }
}

/// Relative tolerance under which two GCIs count as tied when naming the best scheme (the
/// symmetric design makes θθψ ≡ θψθ ≡ ψθθ and θψψ ≡ ψψθ ≡ ψθψ up to a 120° rotation of the
/// workspace, so their GCIs differ only by the grid discretisation).
const TIE_TOLERANCE: f64 = 0.005;

/// Ramana Babu et al.'s qualitative claim: the best scheme depends on the orientation. At each
/// orientation the "best set" is every scheme within [`TIE_TOLERANCE`] of the maximum of
/// `value`; the claim holds when the best sets of two orientations are disjoint.
fn print_orientation_verdict(
    rows: &[Row],
    orientations_deg: &[f64],
    label: &str,
    value: impl Fn(&Row) -> Option<f64>,
) {
    let mut best_sets: Vec<Vec<u8>> = Vec::new();
    for &deg in orientations_deg {
        let at: Vec<(&Row, f64)> = rows
            .iter()
            .filter(|r| r.orientation_deg == deg)
            .filter_map(|r| value(r).map(|v| (r, v)))
            .collect();
        let Some(max) = at.iter().map(|(_, v)| *v).max_by(f64::total_cmp) else {
            return;
        };
        let set: Vec<(&Row, f64)> = at
            .into_iter()
            .filter(|(_, v)| *v >= max * (1.0 - TIE_TOLERANCE))
            .collect();
        let names: Vec<String> = set
            .iter()
            .map(|(r, v)| format!("{} ({}) {v:.4}", r.scheme, r.name))
            .collect();
        println!("best {label} at phi = {deg} deg: {}", names.join(", "));
        best_sets.push(set.iter().map(|(r, _)| r.scheme).collect());
    }
    if best_sets.len() > 1 {
        let depends = best_sets
            .windows(2)
            .any(|w| w[0].iter().all(|s| !w[1].contains(s)));
        println!(
            "Ramana Babu et al.'s claim 'the best scheme depends on the orientation' ({label}): {} for this geometry",
            if depends { "TRUE" } else { "FALSE" }
        );
    }
}

fn write_table(path: &std::path::Path, rows: &[Row]) -> anyhow::Result<()> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match extension.as_str() {
        "json" => {
            let text = serde_json::to_string_pretty(rows)?;
            write_file("--out", path, text)?;
        }
        "csv" => {
            let mut writer = csv::Writer::from_writer(Vec::new());
            for row in rows {
                writer.serialize(row)?;
            }
            write_file("--out", path, writer.into_inner()?)?;
        }
        other => bail!(
            "--out {}: unknown extension `{other}` (use .csv or .json)",
            path.display()
        ),
    }
    Ok(())
}

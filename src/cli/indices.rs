//! `singdist indices`: kinematic performance indices of a 3-RPR (SPEC Part B) along a
//! motion (CSV / JSON table, SVG plot) or at one pose (`--pose x,y,phi --json`).

use anyhow::{Context, Result, bail};
use clap::Args;
use rayon::prelude::*;
use singdist::index::rpr::{
    CnVariant, DEFAULT_CYLINDER_HALF_WIDTH, DsAggregate, INDEX_COLUMN_NAMES, IndexOptions,
    RprIndices, compute_indices, index_columns,
};
use singdist::io::{load_design, load_motion};
use singdist::mechanism::rpr::{Design, Motion, Pose, example_design, example_motion};
use std::path::{Path, PathBuf};

/// Arguments of `singdist indices`.
#[derive(Args, Debug)]
pub struct IndicesArgs {
    /// Design file (JSON `{"base": [[x,y],…], "platform": [[x,y],…]}`); default: the
    /// built-in example (systems/rpr_example_design.json).
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// Motion file (poses or analytic motion); default: the built-in example.
    #[arg(long, value_name = "FILE")]
    motion: Option<PathBuf>,
    /// Number of poses evenly spaced in τ (analytic motions; pose lists are used as given).
    #[arg(long, value_name = "N", default_value_t = 90)]
    poses: usize,
    /// Table of every index along the motion: `.csv` or `.json` (default: CSV on stdout).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// SVG plot of the indices along the motion, each scaled to [0, 1] by its maximum.
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// One pose `x,y,phi` instead of a motion.
    #[arg(long, value_name = "X,Y,PHI", allow_hyphen_values = true)]
    pose: Option<String>,
    /// With `--pose`: print one JSON object (keys M, S, IR, TI, DS, MTI, MDS, CN, MCN,
    /// orientation_distance, position_distance, …).
    #[arg(long)]
    json: bool,
    /// DS aggregate of the pressure-angle cosines (DS is reconstructed): product,
    /// geometric-mean or arithmetic-mean.
    #[arg(long, value_name = "AGGREGATE", default_value = "product")]
    ds: String,
    /// Control number variant: lambda-ratio (λ_min/λ_max) or sqrt-lambda-ratio.
    #[arg(long, value_name = "VARIANT", default_value = "lambda-ratio")]
    cn: String,
    /// Half width w (radians) of the orientation range [φ − w, φ + w] of the
    /// singularity-free cylinder.
    #[arg(long, value_name = "RAD", default_value_t = DEFAULT_CYLINDER_HALF_WIDTH)]
    cylinder_half_width: f64,
}

/// Runs `singdist indices`.
pub fn run(args: IndicesArgs) -> Result<()> {
    let ds: DsAggregate = args.ds.parse().context("--ds")?;
    let cn: CnVariant = args.cn.parse().context("--cn")?;
    if !args.cylinder_half_width.is_finite() || args.cylinder_half_width < 0.0 {
        bail!(
            "--cylinder-half-width: expected a finite number >= 0, got {}",
            args.cylinder_half_width
        );
    }
    let options = IndexOptions {
        ds,
        cn,
        cylinder_half_width: args.cylinder_half_width,
    };
    let design = match &args.design {
        Some(path) => load_design(path)?,
        None => example_design(),
    };
    if let Some(text) = &args.pose {
        let pose = parse_pose(text)?;
        let indices = compute_indices(&design, pose, &options);
        if args.json {
            println!("{}", single_pose_json(&indices, &options)?);
        } else {
            print_single_pose(&indices, &options);
        }
        return Ok(());
    }
    if args.json {
        bail!("--json applies to a single pose (--pose x,y,phi); use --out FILE.json for a motion");
    }
    let motion = match &args.motion {
        Some(path) => load_motion(path)?,
        None => example_motion(),
    };
    let table = motion_table(&design, &motion, args.poses, &options)?;
    match &args.out {
        Some(path) => write_table(path, &table, &options)?,
        None => print!("{}", csv_text(&table, &options)?),
    }
    if let Some(path) = &args.plot {
        plot(path, &table)?;
    }
    Ok(())
}

/// One row of the motion table.
struct Row {
    tau: f64,
    indices: RprIndices,
}

fn motion_table(
    design: &Design,
    motion: &Motion,
    poses: usize,
    options: &IndexOptions,
) -> Result<Vec<Row>> {
    if poses == 0 {
        bail!("--poses: expected at least 1");
    }
    let samples = motion.sample(poses);
    Ok(samples
        .par_iter()
        .map(|s| Row {
            tau: s.tau,
            indices: compute_indices(design, s.pose, options),
        })
        .collect())
}

fn parse_pose(text: &str) -> Result<Pose> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        bail!("--pose: expected x,y,phi (three numbers), got `{text}`");
    }
    let mut v = [0.0; 3];
    for (k, (part, name)) in parts.iter().zip(["x", "y", "phi"]).enumerate() {
        v[k] = part
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .with_context(|| format!("--pose: {name}: expected a finite number, got `{part}`"))?;
    }
    Ok(Pose::new(v[0], v[1], v[2]))
}

/// Column headers with the variant named where a Choice was made.
fn headers(options: &IndexOptions) -> Vec<String> {
    let mut out: Vec<String> = ["tau", "x", "y", "phi"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let w = options.cylinder_half_width;
    for name in INDEX_COLUMN_NAMES {
        out.push(match name {
            "DS" => format!("DS({},reconstructed)", options.ds.name()),
            "MDS" => format!("MDS({},reconstructed)", options.ds.name()),
            "CN" => format!("CN({})", options.cn.name()),
            "cylinder_radius" => format!("cylinder_radius(phi+-{w})"),
            other => other.to_string(),
        });
    }
    out
}

fn cell(value: Option<f64>) -> String {
    match value {
        Some(v) if v.is_finite() => format!("{v:.12e}"),
        _ => "undefined".into(),
    }
}

fn csv_text(table: &[Row], options: &IndexOptions) -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(headers(options))?;
    for row in table {
        let p = row.indices.pose;
        let mut record = vec![
            format!("{}", row.tau),
            format!("{}", p.x),
            format!("{}", p.y),
            format!("{}", p.phi),
        ];
        record.extend(index_columns(&row.indices).iter().map(|(_, v)| cell(*v)));
        writer.write_record(record)?;
    }
    Ok(String::from_utf8(writer.into_inner()?)?)
}

fn write_table(path: &Path, table: &[Row], options: &IndexOptions) -> Result<()> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let text = match extension.as_deref() {
        Some("csv") => csv_text(table, options)?,
        Some("json") => {
            let rows: Vec<serde_json::Value> = table
                .iter()
                .map(|r| {
                    let mut v = serde_json::to_value(&r.indices)?;
                    v["tau"] = serde_json::json!(r.tau);
                    Ok(v)
                })
                .collect::<Result<_, serde_json::Error>>()?;
            serde_json::to_string_pretty(&serde_json::json!({
                "variants": options.variants(),
                "undefined": "null marks an index that is undefined at that pose",
                "poses": rows,
            }))?
        }
        _ => bail!(
            "--out {}: expected a .csv or .json file name",
            path.display()
        ),
    };
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}

fn single_pose_json(indices: &RprIndices, options: &IndexOptions) -> Result<String> {
    let mut value = serde_json::to_value(indices)?;
    value["variants"] = serde_json::to_value(options.variants())?;
    Ok(serde_json::to_string_pretty(&value)?)
}

fn print_single_pose(indices: &RprIndices, options: &IndexOptions) {
    let p = indices.pose;
    println!("pose x = {}, y = {}, phi = {}", p.x, p.y, p.phi);
    for (name, value) in index_columns(indices) {
        println!("{name:>28}  {}", cell(value));
    }
    let v = options.variants();
    println!("variants: DS = {}; CN = {}; IR = {}", v.ds, v.cn, v.ir);
}

/// Curves of the plot: name and values (absolute value for S).
fn plot_curves(table: &[Row]) -> Vec<(String, Vec<Option<f64>>)> {
    // Every index column except the signed duplicates of the two distances.
    let names = INDEX_COLUMN_NAMES
        .iter()
        .copied()
        .filter(|name| !name.ends_with("_signed"));
    names
        .map(|name| {
            let values = table
                .iter()
                .map(|r| {
                    index_columns(&r.indices)
                        .iter()
                        .find(|(n, _)| *n == name)
                        .and_then(|(_, v)| *v)
                        .map(f64::abs)
                })
                .collect();
            let label = if name == "S" {
                "|S|".to_string()
            } else {
                name.to_string()
            };
            (label, values)
        })
        .collect()
}

/// Parameter values where S changes sign (linear interpolation) or vanishes.
fn singular_taus(table: &[Row]) -> Vec<f64> {
    let mut out = Vec::new();
    for pair in table.windows(2) {
        let (s0, s1) = (pair[0].indices.s, pair[1].indices.s);
        if s0 == 0.0 {
            out.push(pair[0].tau);
        } else if s0 * s1 < 0.0 {
            out.push(pair[0].tau + (pair[1].tau - pair[0].tau) * s0 / (s0 - s1));
        }
    }
    if let Some(last) = table.last()
        && last.indices.s == 0.0
    {
        out.push(last.tau);
    }
    out
}

fn plot(path: &Path, table: &[Row]) -> Result<()> {
    if table.len() < 2 {
        bail!("--plot: need at least 2 poses");
    }
    let curves: Vec<super::plot::Curve> = plot_curves(table)
        .into_iter()
        .map(|(label, values)| {
            let max = values.iter().flatten().fold(0.0_f64, |m, v| m.max(*v));
            let scale = if max > 0.0 { max } else { 1.0 };
            // Split at undefined values so gaps stay gaps.
            let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for (row, value) in table.iter().zip(&values) {
                match value {
                    Some(v) => {
                        if let Some(segment) = segments.last_mut() {
                            segment.push((row.tau, v / scale));
                        }
                    }
                    None => segments.push(Vec::new()),
                }
            }
            super::plot::Curve {
                label: format!("{label} (/ {max:.4e})"),
                segments,
            }
        })
        .collect();
    let layout = super::plot::Layout {
        caption: "3-RPR kinematic indices along the motion (each curve divided by its maximum)",
        y_description: "index / max along the motion",
        tau_range: (table[0].tau, table[table.len() - 1].tau),
        y_range: (0.0, 1.05),
    };
    let singular: Vec<f64> = singular_taus(table).into_iter().collect();
    super::plot::plot_against_tau(path, &layout, &curves, &singular)
}

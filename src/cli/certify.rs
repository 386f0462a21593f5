//! `singdist certify FILE`: re-checks a saved `curve` result independently of the run
//! that produced it.
//!
//! Every pose of the file (or of `--poses`) is solved again by the curve pipeline with
//! another seed than the file's (so other random start systems, detours and chains),
//! its critical points are certified ([`singdist::certify::distance`]), and each
//! distance of the file is compared with what is proved:
//!
//! - `G` **certified**: the re-solve certifies the global minimum, and the file's
//!   distance lies in its enclosure;
//! - `m` **minimiser certified**: completeness is not proved, but the file's distance
//!   lies in the enclosure of a certified real critical point's `D`;
//! - `?` **unproved**: neither;
//! - `X` **contradicted**: the file's distance is larger than the enclosure of a
//!   certified real critical value (a closer singular configuration exists), or below a
//!   certified global minimum. Any contradiction gives exit code 3.

use super::args::ThreadsArg;
use super::curve::load_inputs;
use super::outcome::Outcome;
use super::resources::with_threads;
use super::values::parse_metrics;
use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use serde_json::Value;
use singdist::certify::distance::CertifiedStatus;
use singdist::io::rpr::{FieldError, ParseError, design_from_json};
use singdist::mechanism::rpr::{Design, Motion, Pose, PoseList};
use singdist::metric::Metric;
use singdist::pipeline::curve::{CurveOptions, compute_curve, default_start_solutions};
use singdist::pipeline::postprocess::MetricDistance;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Arguments of `singdist certify`.
#[derive(Args, Debug)]
pub struct CertifyArgs {
    /// A result written by `curve --out`: a `.json` document or a `.jsonl` log.
    file: PathBuf,
    /// The design of the run (a `.jsonl` log records its own; a `.json` document does
    /// not: default the built-in example).
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// Pose indices to re-check (`0,5,10-20`); default: every pose of the file.
    #[arg(long, value_name = "LIST")]
    poses: Option<String>,
    /// Seed of the re-solve (default: the file's seed + 7,919; must differ from it).
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    #[command(flatten)]
    threads: ThreadsArg,
    /// Print only the contradictions and the summary.
    #[arg(long)]
    quiet: bool,
}

/// A pose of the saved result.
struct SavedPose {
    index: usize,
    pose: [f64; 3],
    /// Distance per metric name.
    distances: BTreeMap<String, f64>,
}

/// What the file holds that the re-check needs.
struct SavedRun {
    design: Option<Design>,
    metric_names: Vec<String>,
    seed: u64,
    poses: Vec<SavedPose>,
}

fn field<'a>(value: &'a Value, name: &str, at: &str) -> Result<&'a Value> {
    value
        .get(name)
        .ok_or_else(|| anyhow!("{at}: missing field `{name}`"))
}

fn saved_pose(value: &Value, at: &str) -> Result<SavedPose> {
    let index = field(value, "index", at)?
        .as_u64()
        .ok_or_else(|| anyhow!("{at}.index: not a non-negative integer"))? as usize;
    let numbers = field(value, "pose", at)?
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| anyhow!("{at}.pose: expected [x, y, phi]"))?;
    let mut pose = [0.0; 3];
    for (k, v) in numbers.iter().enumerate() {
        pose[k] = v
            .as_f64()
            .filter(|v| v.is_finite() && v.abs() <= singdist::mechanism::MAX_INPUT_MAGNITUDE)
            .ok_or_else(|| anyhow!("{at}.pose[{k}]: not a finite number within ±1e12"))?;
    }
    let metrics = field(value, "metrics", at)?
        .as_object()
        .ok_or_else(|| anyhow!("{at}.metrics: not an object"))?;
    let mut distances = BTreeMap::new();
    for (name, m) in metrics {
        let d = field(m, "distance", &format!("{at}.metrics.{name}"))?
            .as_f64()
            .filter(|d| d.is_finite() && *d >= 0.0)
            .ok_or_else(|| anyhow!("{at}.metrics.{name}.distance: not a finite number ≥ 0"))?;
        distances.insert(name.clone(), d);
    }
    Ok(SavedPose {
        index,
        pose,
        distances,
    })
}

fn metric_names(value: &Value, at: &str) -> Result<Vec<String>> {
    field(value, "metric_names", at)?
        .as_array()
        .and_then(|a| a.iter().map(|v| v.as_str().map(String::from)).collect())
        .ok_or_else(|| anyhow!("{at}.metric_names: not a list of names"))
}

fn seed(value: &Value, at: &str) -> Result<u64> {
    field(value, "seed", at)?
        .as_u64()
        .ok_or_else(|| anyhow!("{at}.seed: not a non-negative integer"))
}

/// Reads a `.json` document (a whole `curve` result).
fn read_document(text: &str) -> Result<SavedRun> {
    let value: Value = serde_json::from_str(text).context("not a JSON document")?;
    let poses = field(&value, "poses", "document")?
        .as_array()
        .ok_or_else(|| anyhow!("poses: not a list"))?
        .iter()
        .enumerate()
        .map(|(i, p)| saved_pose(p, &format!("poses[{i}]")))
        .collect::<Result<_>>()?;
    Ok(SavedRun {
        design: None,
        metric_names: metric_names(&value, "document")?,
        seed: seed(&value, "document")?,
        poses,
    })
}

/// Reads a `.jsonl` log: the header record (seed, metrics, the design among its
/// arguments), then pose lines and other records.
fn read_log(text: &str) -> Result<SavedRun> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let parse = |number: usize, line: &str| -> Result<Value> {
        serde_json::from_str(line).with_context(|| format!("line {}: not JSON", number + 1))
    };
    let (number, first) = lines.next().ok_or_else(|| anyhow!("empty log"))?;
    let header = parse(number, first)?;
    let at = format!("line {} (header)", number + 1);
    if header.get("record").and_then(Value::as_str) != Some("header") {
        bail!("{at}: not a `curve` log header");
    }
    let arguments = field(&header, "arguments", &at)?
        .as_array()
        .ok_or_else(|| anyhow!("{at}.arguments: not a list"))?;
    let design_value = arguments
        .iter()
        .find(|a| a.get(0).and_then(Value::as_str) == Some("design"))
        .and_then(|a| a.get(1))
        .ok_or_else(|| anyhow!("{at}.arguments: no design"))?;
    let design = design_from_json(design_value).map_err(|e| match e {
        ParseError::Field(FieldError { field, reason }) => {
            anyhow!("{at}.design.{field}: {reason}")
        }
        ParseError::Invalid(error) => anyhow!("{at}.design: {error}"),
    })?;
    let mut poses = Vec::new();
    for (number, line) in lines {
        let value = parse(number, line)?;
        if value.get("record").is_none() {
            poses.push(saved_pose(&value, &format!("line {}", number + 1))?);
        }
    }
    Ok(SavedRun {
        design: Some(design),
        metric_names: metric_names(&header, &at)?,
        seed: seed(&header, &at)?,
        poses,
    })
}

fn read_saved(path: &Path) -> Result<SavedRun> {
    let text = std::fs::read_to_string(path).context("cannot read")?;
    let is_log = path
        .extension()
        .is_some_and(|e| e == "jsonl" || e == "partial");
    if is_log {
        read_log(&text)
    } else {
        read_document(&text)
    }
}

/// Parses `0,5,10-20` into pose indices.
fn parse_pose_list(text: &str) -> Result<Vec<usize>> {
    let mut out = Vec::new();
    for part in text.split(',').map(str::trim) {
        let number = |s: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|_| anyhow!("--poses: `{part}` is not an index or a range a-b"))
        };
        match part.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (number(a)?, number(b)?);
                if b < a || b - a > 1_000_000 {
                    bail!("--poses: `{part}` is not an increasing range");
                }
                out.extend(a..=b);
            }
            None => out.push(number(part)?),
        }
    }
    Ok(out)
}

/// The verdict on one distance of the file.
#[derive(Clone, Debug, PartialEq)]
enum Verdict {
    Certified,
    MinimiserCertified,
    Unproved,
    Contradicted(String),
}

impl Verdict {
    fn mark(&self) -> &'static str {
        match self {
            Verdict::Certified => "G",
            Verdict::MinimiserCertified => "m",
            Verdict::Unproved => "?",
            Verdict::Contradicted(_) => "X",
        }
    }
}

/// Relative slack between a distance computed in double precision and an enclosure
/// (as in the run's own certificates).
const SLACK: f64 = 1e-9;

/// Compares the file's distance `d` with the re-solve's certified result `m`.
fn verdict(d: f64, m: &MetricDistance) -> Verdict {
    let slack = SLACK * d.abs().max(1e-300);
    // The smallest certified real critical value, over the sub-problems.
    let lowest = m
        .subproblems
        .iter()
        .filter_map(|(name, s)| Some((name, s.certificate.as_ref()?.distance?)))
        .min_by(|a, b| a.1[1].total_cmp(&b.1[1]));
    if let Some((name, [lo, hi])) = lowest
        && d > hi + slack
    {
        return Verdict::Contradicted(format!(
            "the file's distance {d:e} exceeds a certified real critical value in [{lo:e}, {hi:e}] ({name})"
        ));
    }
    let Some(certificate) = &m.certificate else {
        return Verdict::Unproved;
    };
    let inside = |e: [f64; 2]| e[0] - slack <= d && d <= e[1] + slack;
    match (certificate.status, certificate.distance) {
        (CertifiedStatus::GlobalMinimum, Some(e)) if inside(e) => Verdict::Certified,
        (CertifiedStatus::GlobalMinimum, Some(e)) if d < e[0] - slack => {
            Verdict::Contradicted(format!(
                "the file's distance {d:e} is below the certified global minimum [{:e}, {:e}]",
                e[0], e[1]
            ))
        }
        (CertifiedStatus::MinimiserOnly, Some(e)) if inside(e) => Verdict::MinimiserCertified,
        _ => Verdict::Unproved,
    }
}

/// Runs `singdist certify`.
pub fn run(args: CertifyArgs) -> Result<Outcome> {
    let file = args.file.display().to_string();
    let saved = read_saved(&args.file).with_context(|| file.clone())?;
    let design = match (&args.design, saved.design) {
        (Some(path), _) => load_inputs(Some(path), None)?.0,
        (None, Some(design)) => design,
        (None, None) => load_inputs(None, None)?.0,
    };
    let metrics: Vec<Metric> =
        parse_metrics(&saved.metric_names).with_context(|| format!("{file}: metric_names"))?;
    let selected: Vec<&SavedPose> = match &args.poses {
        None => saved.poses.iter().collect(),
        Some(list) => parse_pose_list(list)?
            .into_iter()
            .map(|j| {
                saved
                    .poses
                    .iter()
                    .find(|p| p.index == j)
                    .ok_or_else(|| anyhow!("--poses: {file} has no pose {j}"))
            })
            .collect::<Result<_>>()?,
    };
    if selected.is_empty() {
        bail!("{file}: no poses to re-check");
    }
    let seed = args.seed.unwrap_or(saved.seed.wrapping_add(7_919));
    if seed == saved.seed {
        bail!("--seed: {seed} is the file's own seed; the re-check needs another");
    }
    let motion = Motion::Poses(PoseList {
        poses: selected
            .iter()
            .map(|p| Pose::new(p.pose[0], p.pose[1], p.pose[2]))
            .collect(),
    });
    let options = CurveOptions {
        seed,
        certify: true,
        self_check: false,
        ..CurveOptions::default()
    };
    let result = with_threads(args.threads, || {
        compute_curve(
            &design,
            &motion,
            selected.len(),
            &metrics,
            &options,
            &default_start_solutions,
            &|_| {},
        )
    })??;
    let mut counts: BTreeMap<&'static str, usize> = BTreeMap::new();
    let mut contradictions = Vec::new();
    for (saved_pose, solved) in selected.iter().zip(&result.poses) {
        let mut marks = Vec::new();
        for metric in &metrics {
            let name = metric.name();
            let Some(&d) = saved_pose.distances.get(&name) else {
                continue;
            };
            let v = match solved.metrics.get(&name) {
                Some(m) => verdict(d, m),
                None => Verdict::Unproved,
            };
            *counts.entry(v.mark()).or_default() += 1;
            if let Verdict::Contradicted(reason) = &v {
                contradictions.push(format!("pose {} {name}: {reason}", saved_pose.index));
            }
            marks.push(format!("{name} {}", v.mark()));
        }
        if !args.quiet {
            let [x, y, phi] = saved_pose.pose;
            println!(
                "pose {} ({x}, {y}, {phi}): {}",
                saved_pose.index,
                marks.join("  ")
            );
        }
    }
    for line in &contradictions {
        println!("CONTRADICTED {line}");
    }
    let count = |mark: &str| counts.get(mark).copied().unwrap_or(0);
    let total: usize = counts.values().sum();
    println!(
        "{file}: {} poses, {total} distances re-checked (seed {seed}): {} certified global minima (G), {} minimiser certified (m), {} unproved (?), {} contradicted (X)",
        selected.len(),
        count("G"),
        count("m"),
        count("?"),
        count("X"),
    );
    if !result.failures.is_empty() {
        eprintln!(
            "singdist: warning: the re-solve lost paths at {} (pose, sub-problem) pairs; their certificates are incomplete",
            result.failures.len()
        );
    }
    Ok(if contradictions.is_empty() {
        Outcome::Complete
    } else {
        Outcome::Contradicted
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_lists_parse_and_bad_ones_are_refused() {
        assert_eq!(parse_pose_list("0, 3-5,9").unwrap(), vec![0, 3, 4, 5, 9]);
        for bad in ["", "a", "5-3", "1,,2", "-1"] {
            assert!(parse_pose_list(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn bad_documents_name_the_field() {
        let message = |text: &str| format!("{:#}", read_document(text).err().unwrap());
        assert!(message("{").contains("not a JSON document"));
        let pose = r#"{"index": 0, "pose": [1, 2], "metrics": {}}"#;
        let doc = format!(r#"{{"metric_names": ["plate/plate"], "seed": 1, "poses": [{pose}]}}"#);
        assert!(message(&doc).contains("poses[0].pose"), "{}", message(&doc));
        let doc = r#"{"metric_names": ["plate/plate"], "seed": 1, "poses": [{"index": 0, "pose": [1, 2, 0], "metrics": {"plate/plate": {"distance": "x"}}}]}"#;
        assert!(message(doc).contains("poses[0].metrics.plate/plate.distance"));
        assert!(read_log("{\"record\":\"window\"}").is_err());
    }
}

//! The design matrix: the curve pipeline on every class of test design
//! (`singdist::reference::designs`) against the independent many-start local
//! reference (`singdist::reference::local_search`).
//!
//! For every class × motion (the analytic motion that crosses `S = 0`, and the
//! scattered pose list) the curve runs for the selected metrics; the harness records
//! wall time, lost paths (`failures`) and the status (`ok`, `lost` = exit code 3,
//! `error`, `panic`, `rejected` by `Design::new`), then compares at a few poses
//! (first, last, smallest distance, one third, two thirds) every metric's and every
//! sub-problem's distance with the reference: `(homotopy − reference)/reference`,
//! positive = the homotopy missed a minimum. It checks the feasibility of the
//! homotopy's closest configurations, compares `distance` (one pose) with the curve
//! at the pose of smallest distance, and seeds on a subset.
//!
//! Environment (all optional):
//! - `SINGDIST_MATRIX_CLASSES`: comma-separated class names (default: all), or
//!   `example` for the built-in example design and motion (scattered: four poses);
//! - `SINGDIST_MATRIX_METRICS`: metric list as for `--metric` (default `all`);
//! - `SINGDIST_MATRIX_POSES`: poses of the analytic curve (default 12);
//! - `SINGDIST_MATRIX_MOTIONS`: `analytic`, `scattered` or both (default both);
//! - `SINGDIST_MATRIX_STARTS`: reference starts (default 200);
//! - `SINGDIST_MATRIX_SEEDS`: last seed of the seed comparison, seeds 2..=N (default 5; 1 = none);
//! - `SINGDIST_MATRIX_SEED_CLASSES`: classes of the seed comparison (default
//!   `random-scale-1,equilateral-both-aligned,tiny-platform`);
//! - `SINGDIST_MATRIX_COMPARE`: `all` compares the reference at every pose, not five;
//! - `SINGDIST_MATRIX_REPORT`: defects with `|relative| ≥` this are listed (default 1e-7);
//! - `SINGDIST_MATRIX_OUT`: file for one JSON line per compared (class, motion, pose, metric);
//! - `SINGDIST_MATRIX_DUMP`: a directory that receives every class's design and motions
//!   as singdist input files (`CLASS.design.json`, `CLASS.analytic.json`,
//!   `CLASS.scattered.json`), to reproduce a row with the command-line tool.

use singdist::mechanism::rpr::{Design, Motion, Pose, PoseList, example_design, example_motion};
use singdist::metric::Metric;
use singdist::pipeline::curve::{CurveOptions, CurveResult, compute_curve_from_embedded_starts};
use singdist::reference::designs::{CLASS_NAMES, DesignCase, design_case};
use singdist::reference::local_search::{
    Constraint, ReferenceOptions, configuration_size, feasibility, reference_distances,
};
use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

fn env_or(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn fail(message: String) -> ! {
    eprintln!("design_matrix: {message}");
    std::process::exit(2);
}

fn parse_usize(name: &str, default: usize) -> usize {
    let text = env_or(name, &default.to_string());
    text.trim()
        .parse()
        .unwrap_or_else(|_| fail(format!("{name}: `{text}` is not a non-negative integer")))
}

fn constraint_of(name: &str) -> Option<Constraint> {
    [
        Constraint::Singularity,
        Constraint::CollinearPlatform,
        Constraint::CollinearBase,
        Constraint::AllCollinear,
        Constraint::CoincidentPlatform,
        Constraint::CoincidentBase,
    ]
    .into_iter()
    .find(|c| c.name() == name)
}

/// Distances below `ZERO · ℓ` count as 0 in relative comparisons: both the
/// homotopy and the reference report about 1e-16 ℓ for a configuration on the
/// constraint set, and their ratio means nothing.
const ZERO: f64 = 1e-8;

/// `(h − r)/r`, with `r` floored at [`ZERO`]` · ℓ`; 0 when both are below that floor
/// (the configuration is on the constraint set: both distances are rounding).
fn relative(homotopy: Option<f64>, reference: Option<f64>, size: f64) -> f64 {
    match (homotopy, reference) {
        (Some(h), Some(r)) if h.max(r) <= ZERO * size => 0.0,
        (Some(h), Some(r)) => (h - r) / r.max(ZERO * size),
        (None, Some(_)) => f64::INFINITY,
        (Some(_), None) => f64::NEG_INFINITY,
        (None, None) => 0.0,
    }
}

/// Outcome of one curve run.
struct Run {
    status: String,
    seconds: f64,
    result: Option<CurveResult>,
}

fn run_curve(design: &Design, motion: &Motion, poses: usize, metrics: &[Metric], seed: u64) -> Run {
    let options = CurveOptions {
        seed,
        ..CurveOptions::default()
    };
    let started = Instant::now();
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        compute_curve_from_embedded_starts(design, motion, poses, metrics, &options)
    }));
    let seconds = started.elapsed().as_secs_f64();
    match outcome {
        Ok(Ok(result)) => Run {
            status: if result.failures.is_empty() {
                "ok".into()
            } else {
                "lost".into()
            },
            seconds,
            result: Some(result),
        },
        Ok(Err(e)) => Run {
            status: format!("error: {e}"),
            seconds,
            result: None,
        },
        Err(_) => Run {
            status: "panic".into(),
            seconds,
            result: None,
        },
    }
}

fn lost_paths(result: &CurveResult) -> usize {
    result
        .failures
        .iter()
        .map(|f| f.expected.saturating_sub(f.accounted))
        .sum()
}

/// Lost paths by problem name (`PLATFORM/BASE:SUBPROBLEM`).
fn lost_by_problem(result: &CurveResult) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    for f in &result.failures {
        *out.entry(f.problem.clone()).or_insert(0) += f.expected.saturating_sub(f.accounted);
    }
    out
}

/// One row of the summary table.
struct Row {
    class: String,
    motion: &'static str,
    status: String,
    seconds: f64,
    reference_seconds: f64,
    lost: usize,
    worst_positive: f64,
    worst_negative: f64,
    worst_where: String,
    infeasibility: f64,
    distance_vs_curve: Option<f64>,
}

/// One disagreement of a sub-problem or metric distance.
struct Defect {
    relative: f64,
    text: String,
}

#[allow(clippy::too_many_arguments)]
fn compare_poses(
    case: &DesignCase,
    motion_name: &'static str,
    design: &Design,
    result: &CurveResult,
    metrics: &[Metric],
    reference_options: &ReferenceOptions,
    threshold: f64,
    defects: &mut Vec<Defect>,
    out: &mut Option<std::fs::File>,
    row: &mut Row,
) -> Option<usize> {
    let n = result.poses.len();
    if n == 0 {
        return None;
    }
    let smallest = (0..n).min_by(|&a, &b| {
        let d = |j: usize| {
            result.poses[j]
                .metrics
                .values()
                .map(|m| m.distance)
                .fold(f64::INFINITY, f64::min)
        };
        d(a).total_cmp(&d(b))
    })?;
    let mut chosen = if std::env::var("SINGDIST_MATRIX_COMPARE").as_deref() == Ok("all") {
        (0..n).collect()
    } else {
        vec![0, n - 1, smallest, n / 3, (2 * n) / 3]
    };
    chosen.sort_unstable();
    chosen.dedup();
    let started = Instant::now();
    for &j in &chosen {
        let pose = &result.poses[j];
        let k = design.configuration(pose.pose.into()).to_array();
        let size = configuration_size(&k);
        let references = reference_distances(design, &k, metrics, reference_options);
        for reference in &references {
            let name = reference.metric.name();
            let homotopy = pose.metrics.get(&name);
            let rel = relative(
                homotopy.map(|m| m.distance),
                reference.distance.is_finite().then_some(reference.distance),
                size,
            );
            let mut record = serde_json::json!({
                "class": case.name, "motion": motion_name, "pose_index": j, "tau": pose.tau,
                "pose": pose.pose, "metric": name,
                "homotopy": homotopy.map(|m| m.distance), "reference": reference.distance,
                "relative": rel, "reference_subproblem": reference.constraint.name(),
                "homotopy_subproblem": homotopy.map(|m| m.subproblem.clone()),
            });
            if rel.abs() >= threshold {
                defects.push(Defect {
                    relative: rel,
                    text: format!(
                        "{} {} pose {j} (tau {:.4}) {name}: homotopy {} via {} vs reference {:.12e} via {} ({:+.3e})",
                        case.name,
                        motion_name,
                        pose.tau,
                        homotopy
                            .map(|m| format!("{:.12e}", m.distance))
                            .unwrap_or_else(|| "none".into()),
                        homotopy.map(|m| m.subproblem.as_str()).unwrap_or("-"),
                        reference.distance,
                        reference.constraint,
                        rel
                    ),
                });
            }
            if rel > row.worst_positive {
                row.worst_positive = rel;
                row.worst_where = format!("{name} pose {j}");
            }
            row.worst_negative = row.worst_negative.min(rel);
            let mut subs = serde_json::Map::new();
            for sub in &reference.subproblems {
                let h = homotopy.and_then(|m| m.subproblems.get(sub.constraint.name()));
                let r = sub.best.as_ref().map(|b| b.distance);
                let rel_sub = relative(h.and_then(|s| s.distance), r, size);
                let infeasible = h
                    .and_then(|s| s.closest)
                    .map(|kp| feasibility(&k, reference.metric, sub.constraint, &kp).worst());
                if let Some(v) = infeasible {
                    row.infeasibility = row.infeasibility.max(v);
                }
                if rel_sub.abs() >= threshold {
                    defects.push(Defect {
                        relative: rel_sub,
                        text: format!(
                            "{} {} pose {j} (tau {:.4}) {name}:{}: homotopy {} vs reference {} ({:+.3e}; homotopy {} of {} paths accounted, {} real)",
                            case.name,
                            motion_name,
                            pose.tau,
                            sub.constraint,
                            h.and_then(|s| s.distance)
                                .map(|v| format!("{v:.12e}"))
                                .unwrap_or_else(|| "none".into()),
                            r.map(|v| format!("{v:.12e}")).unwrap_or_else(|| "none".into()),
                            rel_sub,
                            h.map(|s| s.accounted_paths).unwrap_or(0),
                            h.map(|s| s.expected_paths).unwrap_or(0),
                            h.map(|s| s.real_critical_points).unwrap_or(0),
                        ),
                    });
                }
                subs.insert(
                    sub.constraint.name().into(),
                    serde_json::json!({
                        "homotopy": h.and_then(|s| s.distance), "reference": r,
                        "relative": rel_sub, "homotopy_infeasibility": infeasible,
                        "reference_converged": sub.converged, "reference_hits": sub.hits,
                        "reference_feasibility": sub.best.as_ref().map(|b| b.feasibility.worst()),
                    }),
                );
            }
            // The attaining sub-problem's closest configuration must be feasible.
            if let Some(m) = homotopy
                && let Some(c) = constraint_of(&m.subproblem)
            {
                let v = feasibility(&k, reference.metric, c, &m.closest).worst();
                row.infeasibility = row.infeasibility.max(v);
                record["homotopy_infeasibility"] = serde_json::json!(v);
            }
            record["subproblems"] = serde_json::Value::Object(subs);
            if let Some(file) = out {
                let _ = writeln!(file, "{record}");
            }
        }
    }
    row.reference_seconds += started.elapsed().as_secs_f64();
    Some(smallest)
}

fn max_relative_difference(design: &Design, a: &CurveResult, b: &CurveResult) -> f64 {
    let mut worst: f64 = 0.0;
    for (p, q) in a.poses.iter().zip(&b.poses) {
        let floor = ZERO * configuration_size(&design.configuration(p.pose.into()).to_array());
        for (name, m) in &p.metrics {
            // Two zero distances (both below the floor, e.g. 1e-16 for a base whose
            // coincident anchors make it collinear) agree, as in the `distance` check.
            let d = match q.metrics.get(name) {
                Some(n) if n.distance.max(m.distance) <= floor => 0.0,
                Some(n) => (m.distance - n.distance).abs() / m.distance.max(floor),
                None => f64::INFINITY,
            };
            worst = worst.max(d);
        }
    }
    worst
}

/// The built-in example as a case of the matrix.
fn example_case() -> DesignCase {
    let design = example_design();
    let Motion::Analytic(motion) = example_motion() else {
        unreachable!("the built-in motion is analytic")
    };
    DesignCase {
        name: "example".into(),
        base: *design.base(),
        platform: *design.platform(),
        motion,
        crossings: Vec::new(),
        scattered: vec![
            Pose::new(4.0, 3.0, 0.3),
            Pose::new(5.0, 4.0, -0.5),
            Pose::new(3.5, 2.5, 1.0),
            Pose::new(4.5, 3.5, 2.0),
        ],
    }
}

fn points_json(points: &[singdist::algebra::Point<f64>; 3]) -> serde_json::Value {
    serde_json::json!(points)
}

fn coordinate_json(c: &singdist::mechanism::rpr::MotionCoordinate) -> serde_json::Value {
    serde_json::json!({
        "polynomial": c.polynomial,
        "cosines": c
            .cosines
            .iter()
            .map(|t| [t.amplitude, t.frequency, t.phase])
            .collect::<Vec<_>>(),
    })
}

/// Writes the class's design and both motions as singdist input files.
fn dump_case(dir: &std::path::Path, class: &str, case: &DesignCase) {
    let write = |suffix: &str, value: serde_json::Value| {
        let path = dir.join(format!("{class}.{suffix}.json"));
        let text = serde_json::to_string_pretty(&value).expect("JSON of numbers");
        std::fs::write(&path, text + "\n")
            .unwrap_or_else(|e| fail(format!("SINGDIST_MATRIX_DUMP: {}: {e}", path.display())));
    };
    write(
        "design",
        serde_json::json!({"base": points_json(&case.base), "platform": points_json(&case.platform)}),
    );
    let m = &case.motion;
    write(
        "analytic",
        serde_json::json!({
            "tau_range": m.tau_range,
            "x": coordinate_json(&m.x),
            "y": coordinate_json(&m.y),
            "phi": coordinate_json(&m.phi),
        }),
    );
    write(
        "scattered",
        serde_json::json!({"poses": case.scattered.iter().map(|p| [p.x, p.y, p.phi]).collect::<Vec<_>>()}),
    );
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is accepted.
    let classes: Vec<String> = match std::env::var("SINGDIST_MATRIX_CLASSES") {
        Ok(list) => list
            .split(',')
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .collect(),
        Err(_) => CLASS_NAMES.iter().map(|s| s.to_string()).collect(),
    };
    for c in &classes {
        if c != "example" && !CLASS_NAMES.contains(&c.as_str()) {
            fail(format!(
                "SINGDIST_MATRIX_CLASSES: unknown class `{c}` (one of {})",
                CLASS_NAMES.join(", ")
            ));
        }
    }
    let metrics = Metric::parse_list(&env_or("SINGDIST_MATRIX_METRICS", "all"))
        .unwrap_or_else(|e| fail(format!("SINGDIST_MATRIX_METRICS: {e}")));
    let poses = parse_usize("SINGDIST_MATRIX_POSES", 12);
    let starts = parse_usize("SINGDIST_MATRIX_STARTS", 200);
    let last_seed = parse_usize("SINGDIST_MATRIX_SEEDS", 5) as u64;
    let motions = env_or("SINGDIST_MATRIX_MOTIONS", "analytic,scattered");
    for m in motions.split(',') {
        if !matches!(m.trim(), "analytic" | "scattered") {
            fail(format!(
                "SINGDIST_MATRIX_MOTIONS: `{m}` is not analytic or scattered"
            ));
        }
    }
    let seed_classes = env_or(
        "SINGDIST_MATRIX_SEED_CLASSES",
        "random-scale-1,equilateral-both-aligned,tiny-platform",
    );
    let threshold: f64 = env_or("SINGDIST_MATRIX_REPORT", "1e-7")
        .parse()
        .unwrap_or_else(|_| fail("SINGDIST_MATRIX_REPORT: not a number".into()));
    let mut out = std::env::var("SINGDIST_MATRIX_OUT").ok().map(|path| {
        std::fs::File::create(&path)
            .unwrap_or_else(|e| fail(format!("SINGDIST_MATRIX_OUT: {path}: {e}")))
    });
    let reference_options = ReferenceOptions {
        starts,
        ..ReferenceOptions::default()
    };
    println!(
        "design matrix: {} classes, metrics {}, {poses} poses, reference {starts} starts",
        classes.len(),
        metrics
            .iter()
            .map(Metric::name)
            .collect::<Vec<_>>()
            .join(",")
    );
    let mut rows: Vec<Row> = Vec::new();
    let mut defects: Vec<Defect> = Vec::new();
    let mut lost_detail: Vec<String> = Vec::new();
    let mut seed_lines: Vec<String> = Vec::new();
    for class in &classes {
        let case = if class == "example" {
            example_case()
        } else {
            design_case(class, 1).expect("known class")
        };
        if let Ok(dir) = std::env::var("SINGDIST_MATRIX_DUMP") {
            dump_case(std::path::Path::new(&dir), class, &case);
        }
        for motion_name in motions.split(',').map(str::trim) {
            let motion_name: &'static str = if motion_name == "analytic" {
                "analytic"
            } else {
                "scattered"
            };
            let mut row = Row {
                class: class.clone(),
                motion: motion_name,
                status: String::new(),
                seconds: 0.0,
                reference_seconds: 0.0,
                lost: 0,
                worst_positive: f64::NEG_INFINITY,
                worst_negative: f64::INFINITY,
                worst_where: String::new(),
                infeasibility: 0.0,
                distance_vs_curve: None,
            };
            let design = match case.design() {
                Ok(d) => d,
                Err(e) => {
                    row.status = format!("rejected: {e}");
                    println!("{:<28} {:<9} {}", class, motion_name, row.status);
                    rows.push(row);
                    continue;
                }
            };
            let motion = if motion_name == "analytic" {
                case.analytic_motion()
            } else {
                case.scattered_motion()
            };
            let run = run_curve(&design, &motion, poses, &metrics, 1);
            row.status = run.status.clone();
            row.seconds = run.seconds;
            if let Some(result) = &run.result {
                row.lost = lost_paths(result);
                for (problem, lost) in lost_by_problem(result) {
                    lost_detail.push(format!(
                        "{class} {motion_name} {problem}: {lost} paths lost"
                    ));
                }
                let smallest = compare_poses(
                    &case,
                    motion_name,
                    &design,
                    result,
                    &metrics,
                    &reference_options,
                    threshold,
                    &mut defects,
                    &mut out,
                    &mut row,
                );
                if let Some(j) = smallest {
                    let single = Motion::Poses(PoseList {
                        poses: vec![result.poses[j].pose.into()],
                    });
                    let one = run_curve(&design, &single, 1, &metrics, 1);
                    let k = design.configuration(result.poses[j].pose.into()).to_array();
                    let floor = ZERO * configuration_size(&k);
                    if let Some(one) = one.result {
                        let mut worst: f64 = 0.0;
                        for (name, m) in &result.poses[j].metrics {
                            let d = match one.poses[0].metrics.get(name) {
                                Some(n) if n.distance.max(m.distance) <= floor => 0.0,
                                Some(n) => (n.distance - m.distance) / m.distance.max(floor),
                                None => f64::INFINITY,
                            };
                            if d.abs() > worst.abs() {
                                worst = d;
                            }
                        }
                        row.distance_vs_curve = Some(worst);
                    }
                }
                if last_seed >= 2 && seed_classes.split(',').any(|c| c.trim() == class) {
                    for seed in 2..=last_seed {
                        let other = run_curve(&design, &motion, poses, &metrics, seed);
                        let line = match &other.result {
                            Some(r) => format!(
                                "{class} {motion_name} seed {seed}: {}, {:.2} s, {} paths lost, max relative difference to seed 1: {:.3e}",
                                other.status,
                                other.seconds,
                                lost_paths(r),
                                max_relative_difference(&design, result, r)
                            ),
                            None => format!("{class} {motion_name} seed {seed}: {}", other.status),
                        };
                        println!("  {line}");
                        seed_lines.push(line);
                    }
                }
            }
            println!(
                "{:<28} {:<9} {:<6} {:>8.2} s  lost {:>6}  worst (h-r)/r {:>+10.3e} [{}]  min {:>+10.3e}  infeasibility {:.1e}  distance-vs-curve {}  (reference {:.1} s)",
                row.class,
                row.motion,
                row.status,
                row.seconds,
                row.lost,
                row.worst_positive,
                row.worst_where,
                row.worst_negative,
                row.infeasibility,
                row.distance_vs_curve
                    .map(|v| format!("{v:+.1e}"))
                    .unwrap_or_else(|| "-".into()),
                row.reference_seconds
            );
            let _ = std::io::stdout().flush();
            rows.push(row);
        }
    }
    let generic = |motion: &str| {
        rows.iter()
            .find(|r| r.class == "random-scale-1" && r.motion == motion && r.seconds > 0.0)
            .map(|r| r.seconds)
    };
    println!();
    println!(
        "| class | motion | status | wall s | time / generic | lost paths | worst (h−r)/r | at | most negative | homotopy K′ infeasibility | distance − curve |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for r in &rows {
        let ratio = generic(r.motion)
            .filter(|_| r.seconds > 0.0)
            .map(|g| format!("{:.2}", r.seconds / g))
            .unwrap_or_else(|| "-".into());
        let number = |v: f64| {
            if v.is_finite() {
                format!("{v:+.2e}")
            } else if v == f64::INFINITY {
                "missing".into()
            } else {
                "-".into()
            }
        };
        println!(
            "| {} | {} | {} | {:.2} | {} | {} | {} | {} | {} | {:.1e} | {} |",
            r.class,
            r.motion,
            r.status,
            r.seconds,
            ratio,
            r.lost,
            number(r.worst_positive),
            r.worst_where,
            number(r.worst_negative),
            r.infeasibility,
            r.distance_vs_curve
                .map(|v| format!("{v:+.1e}"))
                .unwrap_or_else(|| "-".into())
        );
    }
    println!();
    println!("lost paths by (class, motion, problem):");
    for line in &lost_detail {
        println!("  {line}");
    }
    defects.sort_by(|a, b| b.relative.total_cmp(&a.relative));
    println!();
    println!(
        "disagreements |(h − r)/r| ≥ {threshold:e} ({}), worst first:",
        defects.len()
    );
    for d in &defects {
        println!("  {}", d.text);
    }
    if !seed_lines.is_empty() {
        println!();
        println!("seeds:");
        for line in &seed_lines {
            println!("  {line}");
        }
    }
}

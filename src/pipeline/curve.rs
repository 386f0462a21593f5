//! Distance-to-singularity curves of a 3-RPR along a motion (SPEC A.9, paper §5).
//!
//! Stages, for every (metric, sub-problem) the selected metrics need:
//!
//! 1. **User homotopy** (paper Eqs. 65–66): the generic start solutions at their
//!    source parameters `p_src` (ab-initio stage) are tracked along the straight
//!    parameter segment `p(t) = (1 − t) p_src + t p*` to the *seed* `p*`: the motion at
//!    a random complex `τ*` (seeded), `K* = K(x(τ*), y(τ*), φ(τ*))` with complex
//!    `cos`, `sin`, plus a small random complex perturbation of all twelve coordinates
//!    so that the fixed real base does not make the seed special; for explicit pose
//!    lists a random complex perturbation of the first pose's configuration. The rigid
//!    parts' shape constants are those of the design ([`LagrangeProblem::parameters_for`]).
//!    One seed solve serves every pose.
//! 2. **Parameter homotopy** (paper §5.3, Paramotopy): the seed solutions are tracked
//!    along `p(t) = (1 − t) p* + t p(K_j)` to the real configuration `K_j` of every pose;
//!    poses × sub-problems run in parallel (rayon). Every path is a pure function of
//!    its inputs, so results are identical for any thread count.
//! 3. **No silent losses**: a (pose, sub-problem) whose number of finite endpoints is
//!    below the start count is re-tracked with [`TrackerOptions::conservative`] along
//!    a different complex detour `p* → p(K_j) + ε·ξ → p(K_j)` (ξ random complex,
//!    seeded per pose, sub-problem and attempt); finite endpoints of all attempts are
//!    merged. What is still missing is reported as a [`PathFailure`].
//! 4. **Post-processing** ([`super::postprocess`]).

use super::postprocess::{self, Candidate, MetricDistance};

/// Per (pose, sub-problem): real candidates, finite endpoints, failure, paths tracked.
type PoseEntry = (Vec<Candidate>, usize, Option<PathFailure>, usize);
use super::start_file::StartSolutions;
use crate::C64;
use crate::homotopy::{
    Homotopy, ParameterHomotopy, PathResult, PolylineParameterHomotopy, Tracker, TrackerOptions,
};
use crate::mechanism::rpr::{Design, Motion, Pose, SampledPose, singularity_polynomial};
use crate::metric::Metric;
use crate::problem::{LagrangeProblem, ProblemError, ProblemId, subproblems_of};
use crate::random;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Errors of the curve pipeline.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// No pose to compute (`--poses 0`).
    #[error("poses: at least one pose is required, got {0}")]
    NoPoses(usize),
    /// Empty metric selection.
    #[error("metric: no metric selected")]
    NoMetrics,
    /// The motion is invalid (names the field).
    #[error("motion: {0}")]
    Motion(String),
    /// A sub-problem's system could not be built.
    #[error(transparent)]
    Problem(#[from] ProblemError),
    /// The start solutions of a sub-problem are unavailable or inconsistent.
    #[error("start solutions of {problem}: {message}")]
    StartSolutions {
        /// `PLATFORM/BASE:SUBPROBLEM`.
        problem: String,
        /// What went wrong.
        message: String,
    },
    /// An option is out of range.
    #[error("{field}: {reason}")]
    Option {
        /// Name of the option.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
}

/// Where the generic start solutions of a sub-problem come from (the ab-initio stage;
/// tests may supply their own). Errors are plain messages.
pub type StartProvider<'a> =
    &'a (dyn Fn(ProblemId) -> Result<std::sync::Arc<StartSolutions>, String> + Sync);

/// Knobs of the curve pipeline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveOptions {
    /// Seed of every random choice (τ*, perturbations, detours).
    pub seed: u64,
    /// Tracker settings of the user and parameter homotopies.
    pub tracker: TrackerOptions,
    /// Tracker settings of the re-runs (safer).
    pub retry_tracker: TrackerOptions,
    /// Number of detour re-runs of a (pose, sub-problem) that lost paths.
    pub retry_attempts: usize,
    /// A critical point is real when `max |Im x| ≤ real_tolerance · (1 + ‖x‖∞)`.
    pub real_tolerance: f64,
    /// Two minimisers within this distance of each other make a cut locus.
    pub cut_locus_tolerance: f64,
    /// Track pose to pose (`τ_j → τ_{j+1}` via a complex midpoint) instead of seed →
    /// every pose; the straight seed → pose homotopy is the reference.
    pub pose_to_pose: bool,
}

impl Default for CurveOptions {
    fn default() -> Self {
        CurveOptions {
            seed: 1,
            tracker: TrackerOptions::default(),
            retry_tracker: TrackerOptions::conservative(),
            retry_attempts: 1,
            real_tolerance: 1e-8,
            cut_locus_tolerance: 1e-9,
            pose_to_pose: false,
        }
    }
}

/// A path (or group of paths) lost at some pose, reported instead of dropped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathFailure {
    /// Index of the pose (`None` for the seed stage, which affects every pose).
    pub pose_index: Option<usize>,
    /// τ of the pose.
    pub tau: Option<f64>,
    /// `PLATFORM/BASE:SUBPROBLEM`.
    pub problem: String,
    /// Start-solution count.
    pub expected: usize,
    /// Paths that reached a finite endpoint (best attempt).
    pub finite: usize,
}

/// One sub-problem prepared at the seed.
pub struct SeededProblem {
    /// Which metric and sub-problem.
    pub id: ProblemId,
    /// The compiled Lagrange system.
    pub problem: LagrangeProblem,
    /// Seed parameters `p* = (K*, shape constants)`.
    pub seed_parameters: Vec<C64>,
    /// Finite solutions at the seed.
    pub seed_solutions: Vec<Vec<C64>>,
    /// Number of generic start solutions.
    pub start_count: usize,
}

/// The output of the user homotopy: every sub-problem at the common seed.
pub struct SeedStage {
    /// The prepared sub-problems, in the order of [`Metric::all`] and
    /// [`subproblems_of`].
    pub problems: Vec<SeededProblem>,
    /// Sub-problems reported as not applicable for this design (SPEC A.6.3).
    pub not_applicable: Vec<String>,
    /// The complex motion parameter of the seed (`None` for pose lists).
    pub tau_star: Option<C64>,
    /// The seed configuration `K*`.
    pub seed_configuration: [C64; 12],
    /// Paths lost in the user homotopy.
    pub failures: Vec<PathFailure>,
    /// Paths tracked in this stage.
    pub paths_tracked: usize,
}

/// Result at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PoseResult {
    /// Index of the pose along the motion.
    pub index: usize,
    /// Motion parameter.
    pub tau: f64,
    /// `[x, y, φ]`.
    pub pose: [f64; 3],
    /// `S(K)` (SPEC A.2).
    #[serde(rename = "S")]
    pub singularity: f64,
    /// Per metric name: distance, signed distance, closest configuration, …
    pub metrics: BTreeMap<String, MetricDistance>,
    /// Paths lost at this pose.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub failures: Vec<PathFailure>,
    /// Paths tracked at this pose (re-runs included).
    #[serde(skip)]
    pub paths_tracked: usize,
}

/// A whole curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveResult {
    /// The metrics computed, by name.
    pub metric_names: Vec<String>,
    /// Seed of the run.
    pub seed: u64,
    /// `[Re τ*, Im τ*]` of the seed (analytic motions).
    pub tau_star: Option<[f64; 2]>,
    /// Sub-problems not applicable to this design.
    pub not_applicable: Vec<String>,
    /// Every pose, in order.
    pub poses: Vec<PoseResult>,
    /// Every path failure (seed stage and poses).
    pub failures: Vec<PathFailure>,
    /// Total number of paths tracked (seed stage, poses and re-runs).
    pub paths_tracked: usize,
}

fn to_real(k: &[f64; 12]) -> [C64; 12] {
    k.map(|v| C64::new(v, 0.0))
}

/// Every (metric, sub-problem) the metrics need, each once.
pub fn problem_ids(metrics: &[Metric]) -> Vec<ProblemId> {
    let mut ids = Vec::new();
    for &metric in metrics {
        for subproblem in subproblems_of(metric) {
            let id = ProblemId { metric, subproblem };
            if !ids.contains(&id) {
                ids.push(id);
            }
        }
    }
    ids
}

/// Seed configuration `K*` (stage 1): see the module documentation.
pub fn seed_configuration(design: &Design, motion: &Motion, seed: u64) -> (Option<C64>, [C64; 12]) {
    let mut rng = random::stream(seed, 0x5eed);
    let scale = design.length_scale();
    let [lo, hi] = motion.tau_range();
    let width = (hi - lo).max(1e-3);
    let tau_star = C64::new(
        random::uniform(&mut rng, lo, hi),
        random::uniform(&mut rng, 0.1, 0.3) * width.min(3.0),
    );
    let (tau, mut k) = match motion.pose_complex(tau_star) {
        Some([x, y, phi]) => (Some(tau_star), design.configuration_complex(x, y, phi)),
        None => {
            let first = motion.pose(lo).unwrap_or_else(|| Pose::new(0.0, 0.0, 0.0));
            (None, to_real(&design.configuration(first).to_array()))
        }
    };
    let amplitude = if tau.is_some() { 0.05 } else { 0.3 };
    for v in k.iter_mut() {
        *v += random::complex_normal(&mut rng) * (amplitude * scale);
    }
    (tau, k)
}

/// Tracks every start solution through `homotopy`; returns the path results in order.
fn track_all<H: Homotopy + ?Sized>(
    homotopy: &H,
    starts: &[Vec<C64>],
    options: &TrackerOptions,
) -> Vec<PathResult> {
    let mut tracker = Tracker::new(homotopy, options.clone());
    starts
        .iter()
        .enumerate()
        .map(|(i, x)| tracker.track(x, i))
        .collect()
}

fn finite_solutions(paths: &[PathResult]) -> Vec<Vec<C64>> {
    paths
        .iter()
        .filter(|p| p.status.is_finite())
        .map(|p| p.solution.clone())
        .collect()
}

/// Random complex detour point near `target`: `target + ε·ξ`, ξ standard complex normal,
/// `ε = 0.1·(1 + ‖target‖∞)` (only the first twelve parameters, the configuration).
fn detour_point(target: &[C64], seed: u64, stream: u64) -> Vec<C64> {
    let mut rng = random::stream(seed, stream);
    let scale = 0.1 * (1.0 + target.iter().fold(0.0f64, |m, v| m.max(v.norm())));
    target
        .iter()
        .enumerate()
        .map(|(i, v)| {
            if i < 12 {
                v + random::complex_normal(&mut rng) * scale
            } else {
                *v
            }
        })
        .collect()
}

/// Tracks `starts` from `from` to `to` (straight); if fewer than `expected` finite
/// endpoints result, re-tracks the lost paths with the safer settings, then (if still
/// short) every path along complex detours. Returns the merged finite
/// endpoints (deduplicated only across attempts), the best attempt's finite count and
/// the number of paths tracked.
fn track_with_retries(
    problem: &LagrangeProblem,
    starts: &[Vec<C64>],
    from: &[C64],
    to: &[C64],
    expected: usize,
    options: &CurveOptions,
    stream: u64,
) -> (Vec<Vec<C64>>, usize, usize) {
    let system = problem.evaluator();
    let straight = ParameterHomotopy::new(system, from, to);
    let mut paths = track_all(&straight, starts, &options.tracker);
    let mut tracked = starts.len();
    if paths.iter().filter(|p| p.status.is_finite()).count() < expected {
        // First re-run: only the lost paths, same homotopy, safer settings.
        let mut careful = Tracker::new(&straight, options.retry_tracker.clone());
        for (i, path) in paths.iter_mut().enumerate() {
            if !path.status.is_finite() {
                *path = careful.track(&starts[i], i);
                tracked += 1;
            }
        }
    }
    let mut endpoints = finite_solutions(&paths);
    let mut best = endpoints.len();
    for attempt in 0..options.retry_attempts {
        if best >= expected {
            break;
        }
        let via = detour_point(
            to,
            options.seed,
            stream.wrapping_mul(16).wrapping_add(attempt as u64 + 1),
        );
        let polyline =
            PolylineParameterHomotopy::new(system, vec![from.to_vec(), via, to.to_vec()]);
        let paths = track_all(&polyline, starts, &options.retry_tracker);
        tracked += starts.len();
        let found = finite_solutions(&paths);
        best = best.max(found.len());
        for x in found {
            let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            let known = endpoints.iter().any(|y| {
                y.iter()
                    .zip(&x)
                    .all(|(a, b)| (a - b).norm() <= 1e-8 * scale)
            });
            if !known {
                endpoints.push(x);
            }
        }
    }
    (endpoints, best, tracked)
}

/// Stage 1, the user homotopy: builds every needed sub-problem, fetches its start
/// solutions from `provider` and tracks them to the common seed (in parallel).
pub fn seed_stage(
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    options: &CurveOptions,
    provider: StartProvider<'_>,
) -> Result<SeedStage, PipelineError> {
    if metrics.is_empty() {
        return Err(PipelineError::NoMetrics);
    }
    motion
        .validate()
        .map_err(|e| PipelineError::Motion(e.to_string()))?;
    let (tau_star, k_star) = seed_configuration(design, motion, options.seed);
    let mut prepared = Vec::new();
    let mut not_applicable = Vec::new();
    for id in problem_ids(metrics) {
        let problem = match LagrangeProblem::for_design(id, design) {
            Ok(p) => p,
            Err(ProblemError::NotApplicable { .. }) => {
                not_applicable.push(id.name());
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        let start = provider(id).map_err(|message| PipelineError::StartSolutions {
            problem: id.name(),
            message,
        })?;
        let source = start
            .parameter_vector(problem.parameter_names())
            .map_err(|name| PipelineError::StartSolutions {
                problem: id.name(),
                message: format!("parameter `{name}` missing"),
            })?;
        let n = problem.variable_names().len();
        if let Some(bad) = start.solutions.iter().find(|x| x.len() != n) {
            return Err(PipelineError::StartSolutions {
                problem: id.name(),
                message: format!("a solution has {} entries, expected {n}", bad.len()),
            });
        }
        let seed_parameters = problem.parameters_for(design, &k_star);
        prepared.push((
            id,
            problem,
            source,
            seed_parameters,
            start.solutions.clone(),
        ));
    }
    let tracked: Vec<(SeededProblem, Option<PathFailure>, usize)> = prepared
        .into_par_iter()
        .enumerate()
        .map(|(index, (id, problem, source, seed_parameters, starts))| {
            let expected = starts.len();
            let (solutions, best, tracked) = track_with_retries(
                &problem,
                &starts,
                &source,
                &seed_parameters,
                expected,
                options,
                (index as u64) << 32,
            );
            let failure = (best < expected).then(|| PathFailure {
                pose_index: None,
                tau: None,
                problem: id.name(),
                expected,
                finite: best,
            });
            (
                SeededProblem {
                    id,
                    problem,
                    seed_parameters,
                    seed_solutions: solutions,
                    start_count: expected,
                },
                failure,
                tracked,
            )
        })
        .collect();
    let mut problems = Vec::new();
    let mut failures = Vec::new();
    let mut paths_tracked = 0;
    for (problem, failure, count) in tracked {
        problems.push(problem);
        failures.extend(failure);
        paths_tracked += count;
    }
    Ok(SeedStage {
        problems,
        not_applicable,
        tau_star,
        seed_configuration: k_star,
        failures,
        paths_tracked,
    })
}

/// Real critical points of one sub-problem at the real configuration `k`, as
/// candidates `(D(K, K′), K′)` for `metric`.
fn candidates(
    problem: &LagrangeProblem,
    metric: Metric,
    endpoints: &[Vec<C64>],
    parameters: &[C64],
    k: &[f64; 12],
    real_tolerance: f64,
) -> Vec<Candidate> {
    let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
    endpoints
        .iter()
        .filter(|x| postprocess::is_real(x, real_tolerance))
        .map(|x| {
            let k_prime = problem
                .configuration(x, parameters, &mut work)
                .map(|v| v.re);
            Candidate {
                distance: metric.distance(k, &k_prime),
                closest: k_prime,
            }
        })
        .collect()
}

/// Stages 2–4 at one pose: parameter homotopy from the seed for every sub-problem (in
/// parallel), re-runs of lost paths, post-processing.
pub fn solve_pose(
    stage: &SeedStage,
    design: &Design,
    metrics: &[Metric],
    index: usize,
    sample: SampledPose,
    options: &CurveOptions,
) -> PoseResult {
    let k = design.configuration(sample.pose).to_array();
    let per_problem: Vec<PoseEntry> = stage
        .problems
        .par_iter()
        .enumerate()
        .map(|(problem_index, seeded)| {
            let target = seeded.problem.parameters_for(design, &to_real(&k));
            let stream = ((index as u64 + 1) << 32) | problem_index as u64;
            let (endpoints, best, tracked) = track_with_retries(
                &seeded.problem,
                &seeded.seed_solutions,
                &seeded.seed_parameters,
                &target,
                seeded.start_count,
                options,
                stream,
            );
            let failure = (best < seeded.start_count).then(|| PathFailure {
                pose_index: Some(index),
                tau: Some(sample.tau),
                problem: seeded.id.name(),
                expected: seeded.start_count,
                finite: best,
            });
            let list = candidates(
                &seeded.problem,
                seeded.id.metric,
                &endpoints,
                &target,
                &k,
                options.real_tolerance,
            );
            (list, best, failure, tracked)
        })
        .collect();
    assemble_pose(stage, metrics, index, sample, &k, per_problem, options)
}

fn assemble_pose(
    stage: &SeedStage,
    metrics: &[Metric],
    index: usize,
    sample: SampledPose,
    k: &[f64; 12],
    per_problem: Vec<PoseEntry>,
    options: &CurveOptions,
) -> PoseResult {
    let singularity = singularity_polynomial(k);
    let mut failures = Vec::new();
    let mut paths_tracked = 0;
    let mut by_metric: BTreeMap<String, Vec<postprocess::SubproblemCandidates>> = BTreeMap::new();
    for (seeded, (list, finite, failure, tracked)) in stage.problems.iter().zip(per_problem) {
        failures.extend(failure);
        paths_tracked += tracked;
        by_metric.entry(seeded.id.metric.name()).or_default().push((
            seeded.id.subproblem,
            list,
            finite,
            seeded.start_count,
        ));
    }
    let mut results = BTreeMap::new();
    for metric in metrics {
        let name = metric.name();
        if let Some(data) = by_metric.get(&name)
            && let Some(result) = postprocess::metric_distance(
                *metric,
                data,
                singularity,
                options.cut_locus_tolerance,
            )
        {
            results.insert(name, result);
        }
    }
    PoseResult {
        index,
        tau: sample.tau,
        pose: [sample.pose.x, sample.pose.y, sample.pose.phi],
        singularity,
        metrics: results,
        failures,
        paths_tracked,
    }
}

/// Samples the motion: `n` poses evenly spaced in τ (explicit pose lists as given).
pub fn sample_motion(motion: &Motion, n: usize) -> Result<Vec<SampledPose>, PipelineError> {
    if n == 0 && matches!(motion, Motion::Analytic(_)) {
        return Err(PipelineError::NoPoses(n));
    }
    motion
        .validate()
        .map_err(|e| PipelineError::Motion(e.to_string()))?;
    Ok(motion.sample(n))
}

/// The whole curve: seed stage, then every pose in parallel; `on_pose` is called as
/// each pose completes (in completion order, e.g. to append partial results).
pub fn compute_curve(
    design: &Design,
    motion: &Motion,
    poses: usize,
    metrics: &[Metric],
    options: &CurveOptions,
    provider: StartProvider<'_>,
    on_pose: &(dyn Fn(&PoseResult) + Sync),
) -> Result<CurveResult, PipelineError> {
    let samples = sample_motion(motion, poses)?;
    let stage = seed_stage(design, motion, metrics, options, provider)?;
    let results: Vec<PoseResult> = if options.pose_to_pose {
        pose_to_pose(&stage, design, metrics, &samples, options, on_pose)
    } else {
        samples
            .par_iter()
            .enumerate()
            .map(|(j, sample)| {
                let result = solve_pose(&stage, design, metrics, j, *sample, options);
                on_pose(&result);
                result
            })
            .collect()
    };
    let mut failures = stage.failures.clone();
    failures.extend(results.iter().flat_map(|r| r.failures.iter().cloned()));
    let paths_tracked =
        stage.paths_tracked + results.iter().map(|r| r.paths_tracked).sum::<usize>();
    Ok(CurveResult {
        metric_names: metrics.iter().map(Metric::name).collect(),
        seed: options.seed,
        tau_star: stage.tau_star.map(|t| [t.re, t.im]),
        not_applicable: stage.not_applicable.clone(),
        poses: results,
        failures,
        paths_tracked,
    })
}

/// Alternative stage 2: per sub-problem (in parallel), the seed is tracked to the
/// first pose, then pose `j` to pose `j + 1` along the polyline
/// `p(K_j) → (p(K_j) + p(K_{j+1}))/2 + i·δ·ξ → p(K_{j+1})` (a complex detour of size
/// `δ = |K_{j+1} − K_j|∞`, ξ random), so the path never runs along the real
/// discriminant. A (pose, sub-problem) that loses paths falls back to the reference
/// seed → pose homotopy with re-runs, and the walk continues from the full set.
fn pose_to_pose(
    stage: &SeedStage,
    design: &Design,
    metrics: &[Metric],
    samples: &[SampledPose],
    options: &CurveOptions,
    on_pose: &(dyn Fn(&PoseResult) + Sync),
) -> Vec<PoseResult> {
    let configurations: Vec<[f64; 12]> = samples
        .iter()
        .map(|s| design.configuration(s.pose).to_array())
        .collect();
    let columns: Vec<Vec<PoseEntry>> = stage
        .problems
        .par_iter()
        .enumerate()
        .map(|(problem_index, seeded)| {
            let system = seeded.problem.evaluator();
            let mut current: Vec<Vec<C64>> = Vec::new();
            let mut previous: Option<Vec<C64>> = None;
            let mut column = Vec::with_capacity(samples.len());
            for (j, sample) in samples.iter().enumerate() {
                let target = seeded
                    .problem
                    .parameters_for(design, &to_real(&configurations[j]));
                let stream = ((j as u64 + 1) << 32) | problem_index as u64;
                let mut tracked = 0;
                let mut endpoints = Vec::new();
                if let Some(from) = &previous
                    && current.len() == seeded.start_count
                {
                    let mut rng = random::stream(options.seed, stream | (1 << 63));
                    let size = from
                        .iter()
                        .zip(&target)
                        .take(12)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()))
                        .max(1e-6);
                    let via: Vec<C64> = from
                        .iter()
                        .zip(&target)
                        .enumerate()
                        .map(|(i, (a, b))| {
                            let mid = (a + b) * 0.5;
                            if i < 12 {
                                mid + random::complex_normal(&mut rng) * (0.5 * size)
                            } else {
                                mid
                            }
                        })
                        .collect();
                    let homotopy = PolylineParameterHomotopy::new(
                        system,
                        vec![from.clone(), via, target.clone()],
                    );
                    let paths = track_all(&homotopy, &current, &options.tracker);
                    tracked += paths.len();
                    endpoints = paths
                        .iter()
                        .filter(|p| p.status == crate::homotopy::PathStatus::Nonsingular)
                        .map(|p| p.solution.clone())
                        .collect();
                }
                let mut best = endpoints.len();
                if best < seeded.start_count {
                    let (found, b, t) = track_with_retries(
                        &seeded.problem,
                        &seeded.seed_solutions,
                        &seeded.seed_parameters,
                        &target,
                        seeded.start_count,
                        options,
                        stream,
                    );
                    endpoints = found;
                    best = b;
                    tracked += t;
                }
                let failure = (best < seeded.start_count).then(|| PathFailure {
                    pose_index: Some(j),
                    tau: Some(sample.tau),
                    problem: seeded.id.name(),
                    expected: seeded.start_count,
                    finite: best,
                });
                let list = candidates(
                    &seeded.problem,
                    seeded.id.metric,
                    &endpoints,
                    &target,
                    &configurations[j],
                    options.real_tolerance,
                );
                current = endpoints;
                previous = Some(target);
                column.push((list, best, failure, tracked));
            }
            column
        })
        .collect();
    let mut columns: Vec<std::vec::IntoIter<PoseEntry>> =
        columns.into_iter().map(|c| c.into_iter()).collect();
    samples
        .iter()
        .enumerate()
        .map(|(j, sample)| {
            let per_problem: Vec<PoseEntry> = columns
                .iter_mut()
                .map(|c| c.next().unwrap_or_else(|| (Vec::new(), 0, None, 0)))
                .collect();
            let result = assemble_pose(
                stage,
                metrics,
                j,
                *sample,
                &configurations[j],
                per_problem,
                options,
            );
            on_pose(&result);
            result
        })
        .collect()
}

/// Parameters τ where `S(K(τ))` changes sign between consecutive samples, refined by
/// bisection on the analytic motion to `|Δτ| ≤ 1e-14·(1 + |τ|)` (SPEC A.8: the
/// distance vanishes there). For pose lists, the midpoint of the sign change.
pub fn singular_parameters(design: &Design, motion: &Motion, samples: &[SampledPose]) -> Vec<f64> {
    let s_of = |tau: f64| {
        motion
            .pose(tau)
            .map(|p| design.configuration(p).singularity())
    };
    let mut roots = Vec::new();
    for pair in samples.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let sa = design.configuration(a.pose).singularity();
        let sb = design.configuration(b.pose).singularity();
        if sa == 0.0 {
            roots.push(a.tau);
            continue;
        }
        if sa * sb >= 0.0 {
            continue;
        }
        if matches!(motion, Motion::Poses(_)) {
            roots.push(0.5 * (a.tau + b.tau));
            continue;
        }
        let (mut lo, mut hi, mut s_lo) = (a.tau, b.tau, sa);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if (hi - lo).abs() <= 1e-14 * (1.0 + mid.abs()) {
                break;
            }
            let Some(s_mid) = s_of(mid) else { break };
            if s_mid == 0.0 {
                lo = mid;
                hi = mid;
                break;
            }
            if (s_mid < 0.0) == (s_lo < 0.0) {
                lo = mid;
                s_lo = s_mid;
            } else {
                hi = mid;
            }
        }
        roots.push(0.5 * (lo + hi));
    }
    if let Some(last) = samples.last()
        && design.configuration(last.pose).singularity() == 0.0
    {
        roots.push(last.tau);
    }
    roots
}

/// The default start provider: [`super::ab_initio::start_solutions`] (embedded files,
/// else monodromy on the fly, cached per process).
pub fn default_start_solutions(id: ProblemId) -> Result<std::sync::Arc<StartSolutions>, String> {
    super::ab_initio::start_solutions(id).map_err(|e| e.to_string())
}

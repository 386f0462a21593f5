//! 3-RRR singularity-distance curves along a motion (Kapilavai and Nawratil, §6.3, Fig.
//! 17; docs/theory.md §10).
//!
//! Four sub-problems ([`crate::problem::rrr::RrrSubProblem`]): the parallel singularity and the three leg
//! singularities, each with the all-deformable metric of docs/theory.md §10. Stages, as
//! for the 3-RPR (docs/theory.md §8):
//!
//! 1. **Seed** (user homotopy, Kapilavai and Nawratil, Eqs. 65–66; [`super::seed`]):
//!    the generic start solutions ([`super::ab_initio`]) are tracked to `K*`, the
//!    trajectory's configuration at a random complex `τ*` plus a small random complex
//!    perturbation, in the run's normalised frame ([`RrrFrame`]: centroid and RMS radius
//!    of the first configuration), so that a design and its scaled copy are solved alike.
//!    At most the generic count of distinct seed solutions is kept; a count below it must
//!    be confirmed at an independent seed point or is reported.
//! 2. **Parameter homotopy** (Kapilavai and Nawratil, §5.3): seed solutions → the real
//!    (normalised) configuration of one pose per block of
//!    [`RrrCurveOptions::chain_length`] poses, and from there pose to pose along the block
//!    ([`super::chain`]); every (block, sub-problem) pair in parallel (rayon). Blocks
//!    sit at fixed pose indices and each path is a pure function of its inputs, so
//!    results depend neither on the thread count nor on the windows a caller asks for.
//! 3. **No silent losses** (the 3-RPR machinery, [`crate::pipeline::curve`]): a (pose,
//!    sub-problem) with failed paths re-tracks them with conservative settings, then
//!    every path along polylines through a random complex detour point near the target
//!    ([`crate::homotopy::PolylinePath`]); finite endpoints of all attempts are merged. A path counts as
//!    accounted for only with a finite endpoint or when the endgame classifies it
//!    [`crate::homotopy::PathStatus::AtInfinity`] (e.g. `λ → ∞` with `K′` finite: `K′`
//!    tends to a singular point of the constraint variety); what is still missing is
//!    reported as an [`RrrPathFailure`].
//! 4. **Post-processing**: real critical points (`max |Im| ≤ tol·(1+‖x‖∞)`), `K′` mapped
//!    back to the caller's frame, `D(K, K′)` recomputed in f64 ([`distance`]), minimum per sub-problem; the signed distance
//!    carries the sign of the sub-problem's determinant at K (parallel determinant, or
//!    the leg determinant); the overall singularity distance is the smallest |value| of
//!    the four (Kapilavai and Nawratil, Remark 11).

use super::ab_initio::{RrrAbInitioError, rrr_start_solutions};
use super::motion_route::{MotionRoute, SeedRoute};
use super::seed::route;
pub use super::seed::{RrrFrame, RrrSeedStage, RrrSeededProblem, rrr_seed_stage};
pub use super::window::RrrCurveRun;
use crate::C64;
use crate::homotopy::TrackerOptions;
use crate::mechanism::rrr::{
    CONFIGURATION_LEN, RrrConfiguration, RrrTrajectory, distance, parallel_polynomial,
};
use crate::pipeline::bisection::bisect_sign_change;
use crate::pipeline::start_file::StartSolutions;
use crate::pipeline::sweep::{Retried, TrackingPlan, distinct_solutions, track_with_retries};
use crate::problem::rrr::{RrrProblem, RrrProblemError};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Errors of the 3-RRR curve pipeline.
#[derive(Debug, thiserror::Error)]
pub enum RrrCurveError {
    /// No pose to compute.
    #[error("poses: at least one pose is required, got {0}")]
    NoPoses(usize),
    /// A sub-problem's system could not be built.
    #[error(transparent)]
    Problem(#[from] RrrProblemError),
    /// Start solutions unavailable.
    #[error(transparent)]
    Start(#[from] RrrAbInitioError),
    /// The start solutions of a sub-problem are inconsistent with its system.
    #[error("start solutions of {problem}: {message}")]
    StartSolutions {
        /// Problem name.
        problem: String,
        /// What is wrong.
        message: String,
    },
    /// Inverse kinematics fails at a sampled pose.
    #[error("pose {index} (tau = {tau}): {message}")]
    Pose {
        /// Pose index.
        index: usize,
        /// τ.
        tau: f64,
        /// The IK error.
        message: String,
    },
}

/// Knobs of the 3-RRR curve pipeline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RrrCurveOptions {
    /// Seed of every random choice (τ*, perturbations, detours).
    pub seed: u64,
    /// Tracker settings of the seed and seed → pose homotopies: the 3-RPR curve's
    /// preset ([`TrackerOptions::curve`]; on the built-in example 1.09 × faster than the
    /// default preset, same distances to 1e-14).
    pub tracker: TrackerOptions,
    /// Tracker settings of the re-runs.
    pub retry_tracker: TrackerOptions,
    /// Detour re-runs of a (pose, sub-problem) that lost paths.
    pub retry_attempts: usize,
    /// Detour re-runs of the source → seed homotopy of a sub-problem that lost paths (it
    /// runs once per curve and every pose inherits what it misses).
    #[serde(default = "default_seed_retry_attempts")]
    pub seed_retry_attempts: usize,
    /// A critical point is real when `max |Im x| ≤ real_tolerance · (1 + ‖x‖∞)`.
    pub real_tolerance: f64,
    /// Poses per chain ([`super::chain`]): one pose of every block of
    /// `chain_length` consecutive poses is solved from the seed, the others from their
    /// neighbours' complete solution sets; `1` solves every pose from the seed.
    #[serde(default = "default_chain_length")]
    pub chain_length: usize,
    /// Re-solve the first and last pose and each sub-problem's closest pose of every
    /// window from an independent seed stage ([`super::self_check`]); a closer
    /// singular configuration found there replaces the run's and is reported.
    #[serde(default = "default_self_check")]
    pub self_check: bool,
    /// Tracker settings of the pose-to-pose paths of a chain
    /// ([`TrackerOptions::curve_neighbour`]: steps up to 0.5; on the built-in example
    /// 1.44 × faster than the default preset).
    #[serde(default = "default_neighbour_tracker")]
    pub neighbour_tracker: TrackerOptions,
    /// Within a chain, solve a pose first by Newton's method from critical points
    /// extrapolated from the preceding poses, one per complex conjugate pair, without
    /// tracking (the sweep engine's Newton jump, as for the 3-RPR); pose-to-pose paths
    /// only for what that leaves unaccounted for. `false`: every pose from its
    /// neighbour along paths. On by default: on the built-in example 1.9 × faster
    /// (5,096 → 3,542 paths), the same distances to 10⁻¹⁴.
    #[serde(default = "default_jump")]
    pub jump: bool,
    /// The seed → pose route along the complexified motion (`K(τ)` from `τ*` to the
    /// pose's τ, as the 3-RPR's) where the elbows' square-root branch can be followed
    /// unambiguously; `false`, or a pose list: the straight segment between the two
    /// configurations. Off by default: on the built-in example with every pose from
    /// the seed (`chain_length` 1, no self-check) it took 0.84 s instead of 0.60 s,
    /// with the same paths and the same distances (to 5·10⁻¹⁴); the straight segment
    /// between two configurations is the shorter route for this family.
    #[serde(default = "default_motion_route")]
    pub motion_route: bool,
}

impl Default for RrrCurveOptions {
    fn default() -> Self {
        RrrCurveOptions {
            seed: 1,
            tracker: TrackerOptions::curve(),
            retry_tracker: TrackerOptions::conservative(),
            retry_attempts: 2,
            seed_retry_attempts: default_seed_retry_attempts(),
            real_tolerance: 1e-8,
            chain_length: default_chain_length(),
            self_check: default_self_check(),
            neighbour_tracker: default_neighbour_tracker(),
            jump: default_jump(),
            motion_route: default_motion_route(),
        }
    }
}

fn default_motion_route() -> bool {
    false
}

fn default_jump() -> bool {
    true
}

fn default_self_check() -> bool {
    true
}

fn default_chain_length() -> usize {
    20
}

fn default_neighbour_tracker() -> TrackerOptions {
    TrackerOptions::curve_neighbour()
}

fn default_seed_retry_attempts() -> usize {
    6
}

/// Paths lost at some pose (or at the seed), reported instead of dropped: the 3-RPR
/// record ([`crate::pipeline::curve::PathFailure`]); `problem` is e.g. `rrr:leg2`, `accounted` the
/// paths with a finite endpoint or classified at infinity.
pub type RrrPathFailure = crate::pipeline::curve::PathFailure;

/// One sub-problem at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RrrSubproblemResult {
    /// Smallest `D(K, K′)` over the real critical points (`None` if none).
    pub distance: Option<f64>,
    /// The minimising `K′` (18 coordinates, `O1x … C3y`).
    pub closest: Option<[f64; CONFIGURATION_LEN]>,
    /// The sub-problem's determinant at K (its sign is the sign of the signed distance).
    pub determinant: f64,
    /// Real critical points found.
    pub real_critical_points: usize,
    /// Finite endpoints (all attempts merged).
    pub finite_endpoints: usize,
    /// Paths accounted for: finite endpoint or classified at infinity by the endgame (best
    /// attempt, or the attempts' merged finite endpoints plus the reference route's paths
    /// at infinity). Fewer than `expected_endpoints` means lost paths (an entry in
    /// `failures`).
    pub accounted_paths: usize,
    /// Paths tracked from the seed: the seed's distinct finite solutions, at most the
    /// generic root count (below it only when confirmed at an independent seed point, or
    /// with a seed-stage failure). `accounted_paths` never exceeds it.
    pub expected_endpoints: usize,
}

/// Result at one pose (stable JSON field names: `tau`, `parallel`, `leg1`,
/// `leg2`, `leg3`, `distance`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RrrPoseResult {
    /// Index of the pose along the motion.
    pub index: usize,
    /// Motion parameter.
    pub tau: f64,
    /// `[x, y, φ]`.
    pub pose: [f64; 3],
    /// Working modes σ_i ∈ {+1, −1} at this pose (continued along the motion).
    pub working_modes: [i8; 3],
    /// Signed distance to the parallel singularity (sign of the parallel determinant).
    pub parallel: Option<f64>,
    /// Signed distance to the leg-1 singularity (sign of the leg-1 determinant).
    pub leg1: Option<f64>,
    /// Signed distance to the leg-2 singularity.
    pub leg2: Option<f64>,
    /// Signed distance to the leg-3 singularity.
    pub leg3: Option<f64>,
    /// Overall singularity distance: the smallest |value| of the four (Kapilavai and
    /// Nawratil, Remark 11).
    pub distance: Option<f64>,
    /// Which curve attains it (`parallel`, `leg1`, `leg2`, `leg3`).
    pub nearest: Option<String>,
    /// Comparison index of Kapilavai and Nawratil, Fig. 17: `|det|` of the parallel
    /// determinant (`det[C_i − B_i | B_i × C_i]`, docs/theory.md §10) divided by its
    /// largest |value| over the sampled poses, so in [0, 1].
    pub parallel_determinant_abs_scaled: f64,
    /// Per sub-problem (`parallel`, `leg1`, …): distance, closest configuration, counts.
    pub subproblems: BTreeMap<String, RrrSubproblemResult>,
    /// Paths lost at this pose.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub failures: Vec<RrrPathFailure>,
    /// Paths tracked at this pose (re-runs included).
    #[serde(skip)]
    pub paths_tracked: usize,
}

/// A whole 3-RRR curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RrrCurveResult {
    /// Seed of the run.
    pub seed: u64,
    /// `[Re τ*, Im τ*]` of the seed (analytic motions).
    pub tau_star: Option<[f64; 2]>,
    /// Start-solution count per sub-problem.
    pub start_counts: BTreeMap<String, usize>,
    /// τ where the parallel determinant changes sign (bisection on the motion).
    pub parallel_singular_parameters: Vec<f64>,
    /// Per leg, τ where it passes through a leg singularity (its working mode flips).
    pub leg_singular_parameters: [Vec<f64>; 3],
    /// What the self-check compared (`None` without it).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub self_check: Option<crate::pipeline::curve::SelfCheck>,
    /// Every pose, in order.
    pub poses: Vec<RrrPoseResult>,
    /// Every path failure (seed stage and poses).
    pub failures: Vec<RrrPathFailure>,
    /// Total number of paths tracked.
    pub paths_tracked: usize,
}

/// One sub-problem at one pose after tracking.
#[derive(Clone, Debug)]
pub(crate) struct Entry {
    /// What the pose reports for the sub-problem.
    pub result: RrrSubproblemResult,
    /// The paths that are not accounted for, if any.
    pub failure: Option<RrrPathFailure>,
    /// Paths tracked for this (pose, sub-problem), over every route and re-run.
    pub tracked: usize,
}

/// The parameters of the real configuration `k` in `frame`.
pub(crate) fn target_parameters(frame: &RrrFrame, k: &[f64; CONFIGURATION_LEN]) -> Vec<C64> {
    frame.apply(k).iter().map(|&v| C64::new(v, 0.0)).collect()
}

/// The random stream of (pose `index`, sub-problem `problem_index`).
pub(crate) fn path_stream(index: usize, problem_index: usize) -> u64 {
    ((index as u64 + 1) << 32) | problem_index as u64
}

/// The seed's solutions tracked to the real pose's parameters `target` (straight, then
/// detours; [`route`]); a conjugate pair half found is completed
/// ([`RrrProblem::conjugate`]). Where the seed has fewer solutions than the expected
/// count (raised by the other seed stage's, `reconcile_seed_counts`), the generic
/// route first: the start file's solutions tracked to `target` the same way.
pub(crate) fn track_from_seed(
    seeded: &RrrSeededProblem,
    target: &[C64],
    stream: u64,
    options: &RrrCurveOptions,
    along: Option<&MotionRoute<'_>>,
) -> Retried {
    let plan = TrackingPlan::with_endgame(&options.tracker, &options.retry_tracker)
        .with_conjugate(Some(&RrrProblem::conjugate));
    let track = |(source, starts): (&[C64], &[Vec<C64>]),
                 salt: u64,
                 along: Option<&MotionRoute<'_>>| {
        track_with_retries(
            seeded.problem.evaluator(),
            starts,
            |attempt| match along {
                Some(motion) if attempt == 0 => SeedRoute::Motion(Box::new(motion.clone())),
                _ => {
                    SeedRoute::Polyline(route(source, target, options.seed, stream ^ salt, attempt))
                }
            },
            options.retry_attempts,
            plan,
        )
    };
    let mut generic_tracked = 0;
    if seeded.at_seed.solutions.len() < seeded.at_seed.start_count {
        // The other seed stage reached more critical points than this one's seed has
        // (`reconcile_seed_counts`): the seed route cannot complete the pose, the
        // generic route can. Complete on its own terms: every generic path accounted
        // for and exactly the expected count of distinct finite endpoints.
        let (source, starts) = &seeded.at_seed.generic_start;
        let generic = track((source, starts), GENERIC_ROUTE_SALT, None);
        let endpoints = distinct_solutions(generic.endpoints, seeded.at_seed.generic_count);
        if generic.accounted == seeded.at_seed.generic_count
            && endpoints.len() == seeded.at_seed.start_count
        {
            return Retried {
                endpoints,
                accounted: seeded.at_seed.start_count,
                ..generic
            };
        }
        generic_tracked = generic.tracked;
    }
    let seed_set = (
        &seeded.at_seed.parameters[..],
        &seeded.at_seed.solutions[..],
    );
    let mut retried = track(seed_set, 0, along);
    retried.tracked += generic_tracked;
    retried
}

/// Random stream tag of the generic route (`track_from_seed`), apart from the seed
/// route's streams.
const GENERIC_ROUTE_SALT: u64 = 0x9e37_79b9_7f4a_7c15;

/// The sub-problem's result at `k` from what tracking found there: real critical points
/// (`max |Im x| ≤ tol·(1+‖x‖∞)`), `K′` mapped back to the caller's frame, the smallest
/// `D(K, K′)`, and a failure when fewer than the seed's paths are accounted for.
pub(crate) fn subproblem_entry(
    seeded: &RrrSeededProblem,
    frame: &RrrFrame,
    k: &[f64; CONFIGURATION_LEN],
    (index, tau): (usize, f64),
    retried: &Retried,
    options: &RrrCurveOptions,
) -> Entry {
    let Retried {
        endpoints,
        accounted,
        tracked,
        reasons,
        ..
    } = retried;
    let accounted = *accounted;
    let kind = seeded.problem.kind();
    let failure = (accounted < seeded.at_seed.start_count).then(|| RrrPathFailure {
        pose_index: Some(index),
        tau: Some(tau),
        problem: kind.name(),
        expected: seeded.at_seed.start_count,
        accounted,
        reasons: reasons.clone(),
    });
    let mut best_candidate: Option<(f64, [f64; CONFIGURATION_LEN])> = None;
    let mut real = 0;
    for x in endpoints {
        if !crate::pipeline::postprocess::is_real(x, options.real_tolerance) {
            continue;
        }
        real += 1;
        let k_prime = frame.restore(&RrrProblem::configuration(x).map(|v| v.re));
        let d = distance(k, &k_prime);
        if best_candidate.is_none_or(|(b, _)| d < b) {
            best_candidate = Some((d, k_prime));
        }
    }
    let determinant = kind.constraint(k);
    Entry {
        result: RrrSubproblemResult {
            distance: best_candidate.map(|(d, _)| d),
            closest: best_candidate.map(|(_, c)| c),
            determinant,
            real_critical_points: real,
            finite_endpoints: endpoints.len(),
            accounted_paths: accounted,
            expected_endpoints: seeded.at_seed.start_count,
        },
        failure,
        tracked: *tracked,
    }
}

pub(crate) fn signed(result: &RrrSubproblemResult) -> Option<f64> {
    let sign = if result.determinant < 0.0 { -1.0 } else { 1.0 };
    result.distance.map(|d| sign * d)
}

/// Pose `index` at `tau`: `[x, y, φ]` and the configuration (errors name the pose).
pub(crate) fn configuration_at(
    trajectory: &RrrTrajectory,
    index: usize,
    tau: f64,
) -> Result<([f64; 3], RrrConfiguration), RrrCurveError> {
    let pose_error = |message: String| RrrCurveError::Pose {
        index,
        tau,
        message,
    };
    let pose = trajectory
        .pose(tau)
        .ok_or_else(|| pose_error("no pose at this parameter".to_string()))?;
    trajectory
        .configuration(tau)
        .map(|c| ([pose.x, pose.y, pose.phi], c))
        .map_err(|e| pose_error(e.to_string()))
}

/// The configurations at the given τ (errors name the first pose outside the workspace).
pub fn configurations_at(
    trajectory: &RrrTrajectory,
    taus: &[f64],
) -> Result<Vec<(f64, [f64; 3], RrrConfiguration)>, RrrCurveError> {
    if taus.is_empty() {
        return Err(RrrCurveError::NoPoses(0));
    }
    taus.iter()
        .enumerate()
        .map(|(index, &tau)| configuration_at(trajectory, index, tau).map(|(p, k)| (tau, p, k)))
        .collect()
}

/// τ where the parallel determinant changes sign between consecutive samples, refined by
/// bisection on the motion ([`bisect_sign_change`]; pose lists: the midpoint).
pub fn parallel_singular_parameters(trajectory: &RrrTrajectory, taus: &[f64]) -> Vec<f64> {
    let value = |tau: f64| {
        trajectory
            .configuration(tau)
            .ok()
            .map(|c| parallel_polynomial(&c.to_array()))
    };
    let analytic = matches!(
        trajectory.motion(),
        crate::mechanism::rpr::Motion::Analytic(_)
    );
    let mut roots = Vec::new();
    for pair in taus.windows(2) {
        let (Some(sa), Some(sb)) = (value(pair[0]), value(pair[1])) else {
            continue;
        };
        if sa * sb >= 0.0 {
            continue;
        }
        if !analytic {
            roots.push(0.5 * (pair[0] + pair[1]));
            continue;
        }
        roots.push(bisect_sign_change((pair[0], pair[1]), sa, value));
    }
    roots
}

/// The whole curve at `poses` poses evenly spaced in τ (pose lists: as given).
pub fn compute_rrr_curve(
    trajectory: &RrrTrajectory,
    poses: usize,
    options: &RrrCurveOptions,
    provider: &(dyn Fn(&RrrProblem) -> Result<StartSolutions, RrrAbInitioError> + Sync),
) -> Result<RrrCurveResult, RrrCurveError> {
    if poses == 0
        && matches!(
            trajectory.motion(),
            crate::mechanism::rpr::Motion::Analytic(_)
        )
    {
        return Err(RrrCurveError::NoPoses(0));
    }
    let taus: Vec<f64> = trajectory
        .motion()
        .sample(poses)
        .iter()
        .map(|s| s.tau)
        .collect();
    compute_rrr_curve_at(trajectory, &taus, options, provider)
}

/// The curve at the given parameter values: seed stage, then every (pose, sub-problem)
/// in parallel ([`RrrCurveRun`] with one window of every pose).
pub fn compute_rrr_curve_at(
    trajectory: &RrrTrajectory,
    taus: &[f64],
    options: &RrrCurveOptions,
    provider: &(dyn Fn(&RrrProblem) -> Result<StartSolutions, RrrAbInitioError> + Sync),
) -> Result<RrrCurveResult, RrrCurveError> {
    let run = RrrCurveRun::new(trajectory, taus, options, provider)?;
    let window = run.solve_range(0..taus.len(), &|_| {})?;
    Ok(run.collect(vec![window]))
}

/// The default start provider: embedded `supplementary/start/rrr-*.json`, else computed.
pub fn default_rrr_start_solutions(
    problem: &RrrProblem,
) -> Result<StartSolutions, RrrAbInitioError> {
    rrr_start_solutions(problem)
}

//! Distance-to-singularity curves of a 3-RPR along a motion (Kapilavai and Nawratil, §5;
//! docs/theory.md §8).
//!
//! Stages, for every (metric, sub-problem) the selected metrics need. Every parameter
//! vector lives in one normalised frame per curve ([`Normalization`]: centroid and RMS
//! size of the first configuration), so coordinates and multipliers stay of order one.
//!
//! 1. **User homotopy** (Kapilavai and Nawratil, Eqs. 65–66): the generic start solutions
//!    at their source parameters `p_src` (ab-initio stage) are tracked along the straight
//!    parameter segment `p(t) = (1 − t) p_src + t p*` to the *seed* `p*`: the motion at
//!    a random complex `τ*` (seeded), `K* = K(x(τ*), y(τ*), φ(τ*))` with complex
//!    `cos`, `sin` (for explicit pose lists: the first pose plus a complex
//!    perturbation), plus a small random complex perturbation δ of all twelve
//!    coordinates so that the fixed real base does not make the seed special
//!    ([`seed_point`]). The rigid parts' shape constants are those of the design. One
//!    seed solve serves every pose. Paths that end at infinity there are critical
//!    points the design's fixed shape does not have (e.g. the example design's base and
//!    platform have equal angles at anchor 1, so leg-collapse singular points of Kapilavai
//!    and Nawratil, Thm 3 case 4 exist and absorb some critical points); the poses expect
//!    the seed's finite count.
//! 2. **Parameter homotopy** (Kapilavai and Nawratil, §5.3): the seed solutions are
//!    tracked to the real configuration `K_j` of every pose along the complexified motion
//!    (`MotionPath`: straight from τ* to τ_j in the τ-plane, or from the seed pose to
//!    pose j in pose coordinates, with δ fading), so every intermediate parameter is a
//!    pose of the design; poses × sub-problems run in parallel (rayon). Every path is a
//!    pure function of its inputs, so results are identical for any thread count.
//!    **Chains** ([`CurveOptions::chain_length`]): only one pose of every block of
//!    consecutive poses goes the seed route, the one nearest `Re τ*` (the shortest
//!    route; by default the whole motion is one block). From it the chain runs
//!    forwards and backwards at once; each next pose in chain order is solved from
//!    its predecessors' complete finite solution sets ([`CurveOptions::jump`]):
//!    every critical point is extrapolated
//!    from the last three poses and corrected by Newton's method at the new pose,
//!    one per complex conjugate pair (the poses are real, so the other is its
//!    conjugate). What fails or coincides is tracked from the predecessor, through a
//!    random complex midpoint between the two poses (short paths, a few steps each);
//!    where the set is still incomplete, every critical point is tracked that way,
//!    and then the pose falls back to the seed route. A set counts as complete when it
//!    has the seed's number of distinct nonsingular finite points: no more exist, so
//!    a Newton sequence or a path that lands on another one's point is caught. The
//!    blocks are fixed by the pose indices, not by the thread count.
//!
//!    All tracking is in isotropic coordinates `(x ± iy)/√2` of the unknown
//!    points ([`crate::problem::Coordinates::Isotropic`]): the rigid metrics have
//!    complex critical points far out along isotropic lines, hopelessly ill-conditioned
//!    in Cartesian coordinates (κ ≈ 10¹³ and up, double-double tracking needed, some
//!    lost even then) and well-conditioned up to scaling in isotropic ones. Start
//!    solutions are converted on entry, endpoints back to Cartesian for
//!    post-processing.
//!
//!    Optionally ([`CurveOptions::multipliers`]) the multipliers are tracked in a
//!    projective chart ([`crate::problem::Multipliers::Chart`], the Fritz John form `λ₀ ∇D² − λ ∇C −
//!    Σ μ ∇g = 0` with a random affine chart on `[λ₀ : λ : μ …]`): a critical point
//!    near a singular point of the constraint set has huge multipliers, and its path
//!    no longer passes near a pole of λ that the endgame mistakes for a path to
//!    infinity; endpoints with `λ₀ = 0` are classified at infinity
//!    ([`crate::homotopy::Homotopy::homogenizing_variable`]).
//! 3. **No silent losses**: a (pose, sub-problem) with failed paths re-tracks them with
//!    [`TrackerOptions::conservative`], then tracks every path along a detour through a
//!    random complex motion point near the pose (seeded per pose, sub-problem and
//!    attempt; at the seed, through random complex parameters near `p*`, more
//!    attempts); finite endpoints of all attempts are merged. Paths classified at
//!    infinity are accounted for.
//!    **Rescue from neighbours**: once every pose of a window
//!    ([`CurveOptions::window_poses`]) is done, each run of consecutive
//!    poses at which a sub-problem still lost paths is re-solved pose by pose from the
//!    complete finite solution set of the pose before the run (forward), then of the
//!    pose after it (backward), through a random complex midpoint between the two
//!    poses; a re-solved pose whose set is complete seeds the next one.
//!    **Seed at the pose** (`local_seed`): a metric that still lost paths at a pose is
//!    solved there once more from a seed stage of its own next to the pose (what
//!    `singdist distance` runs), and its result taken where it lost nothing and
//!    expects as many critical points. The self-check's stage and the run's expect the
//!    larger of their two seed counts at every pose, and a checked pose where the run
//!    lost paths that the check did not takes the check's result. What still fails is
//!    reported as a [`PathFailure`].
//! 4. **Post-processing** ([`super::postprocess`]).

use super::bisection::bisect_sign_change;
use super::family::frame_scale;
use super::postprocess::{self, Candidate, MetricDistance};

/// One sub-problem at one pose after tracking: what post-processing and the failure
/// report need.
#[derive(Clone, Default)]
struct PoseEntry {
    /// The real critical points as candidate closest configurations.
    candidates: Vec<Candidate>,
    /// Paths accounted for (distinct finite endpoints, or paths shown to diverge),
    /// at most the sub-problem's generic count.
    accounted: usize,
    /// The paths that are not accounted for, if any.
    failure: Option<PathFailure>,
    /// Paths tracked for this (pose, sub-problem), over every route and re-run.
    tracked: usize,
    /// The certificate of its critical points, computed when the pose is assembled
    /// ([`CurveOptions::certify`]).
    certificate: Option<PendingCertificate>,
}
use super::start_file::StartSolutions;
use crate::C64;
use crate::certify::distance::{self as certification, SubproblemCertificate};
use crate::homotopy::{
    ParameterPath, PathParameterHomotopy, PathResult, PolylinePath, TrackerOptions,
};
use crate::mechanism::rpr::{Design, Motion, Pose, SampledPose, singularity_polynomial};
use crate::metric::Metric;
use crate::problem::{
    Coordinates, LagrangeProblem, Multipliers, ProblemError, ProblemId, Stratum, equilateral,
    pedal, subproblems_of,
};
use crate::random;
use crate::system::Evaluator;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

mod certificates;
mod chain;
mod jump;
mod local_seed;
mod options;
mod seed;
mod self_check;
mod window;
pub use super::sweep::FAR_POSE_STEP;
pub use crate::pipeline::sweep::PathFailure;
pub use crate::pipeline::sweep::window_ranges;
use crate::pipeline::sweep::{
    JUMP_HISTORY, ProjectiveTwin, Retried, TrackingPlan, detour_point, distinct_solutions,
    track_with_retries, with_conjugates,
};
pub use crate::pipeline::sweep::{SELF_CHECK_TOLERANCE, SelfCheck};
pub(crate) use crate::pipeline::sweep::{check_seed, checked_poses};
use certificates::*;
pub use chain::solve_pose;
use chain::*;
use jump::*;
pub use options::*;
pub use seed::*;
pub use window::{CurveFamily, CurveHeader, CurveRun, CurveWindow, collect_curve};

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

/// Where the start solutions of a sub-problem on a stratum come from (the ab-initio
/// stage; tests may supply their own). Errors are plain messages; on a special stratum
/// an error means no file (the sub-problem is posed on the generic stratum instead).
pub type StartProvider<'a> =
    &'a (dyn Fn(ProblemId, Stratum) -> Result<std::sync::Arc<StartSolutions>, String> + Sync);

/// Result at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PoseResult {
    /// Index of the pose along the motion.
    pub index: usize,
    /// Motion parameter.
    pub tau: f64,
    /// `[x, y, φ]`.
    pub pose: [f64; 3],
    /// `S(K)` (docs/theory.md §1.3).
    #[serde(rename = "S")]
    pub singularity: f64,
    /// Per metric name: distance, signed distance, closest configuration, …
    pub metrics: BTreeMap<String, MetricDistance>,
    /// Paths lost at this pose.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub failures: Vec<PathFailure>,
    /// Critical points continued to this pose: paths tracked (re-runs included) and
    /// Newton continuations from neighbouring poses, each counted once (a conjugate
    /// filled in is not counted).
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
    /// Total number of critical points continued: paths tracked (seed stage, poses and
    /// re-runs) and Newton continuations from neighbouring poses.
    pub paths_tracked: usize,
    /// The run's check of a few poses by an independent route
    /// ([`CurveOptions::self_check`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_check: Option<SelfCheck>,
}

fn to_real(k: &[f64; 12]) -> [C64; 12] {
    k.map(|v| C64::new(v, 0.0))
}

/// The similarity `K ↦ (K − c)/s` of the pipeline's normalised frame: `c` the
/// centroid of the six points of the motion's first configuration, `s` their
/// root-mean-square distance from it. One frame serves the whole curve.
///
/// Every sub-problem is equivariant under similarities (D² scales by `s²`, S and the
/// collinearity polynomials are invariant up to a factor, a rigid part's `u, v` are
/// invariant and `r² = |e|²` scales by `s²`), so the critical points at `K` are the
/// images of those at the normalised configuration. Tracking in the normalised frame
/// keeps coordinates and multipliers of order one whatever the design's units: with
/// anchors ~10 apart, the multiplier of the quartic S is ~10⁻³ and the Jacobians'
/// condition numbers grow by orders of magnitude.
#[derive(Clone, Copy, Debug)]
pub struct Normalization {
    center: [C64; 2],
    scale: f64,
}

impl Normalization {
    /// The frame of configuration `k`.
    pub fn of(k: &[C64; 12]) -> Self {
        let mut center = [C64::new(0.0, 0.0); 2];
        for i in 0..6 {
            center[0] += k[2 * i] / 6.0;
            center[1] += k[2 * i + 1] / 6.0;
        }
        let spread: f64 = (0..6)
            .map(|i| (k[2 * i] - center[0]).norm_sqr() + (k[2 * i + 1] - center[1]).norm_sqr())
            .sum::<f64>()
            / 6.0;
        Normalization {
            center,
            scale: frame_scale(spread),
        }
    }

    /// `(K − c)/s`.
    pub fn apply(&self, k: &[C64; 12]) -> [C64; 12] {
        std::array::from_fn(|i| (k[i] - self.center[i % 2]) / self.scale)
    }

    /// The similarity as a certification frame (real centre).
    pub fn frame(&self) -> certification::Frame {
        certification::Frame {
            center: [self.center[0].re, self.center[1].re],
            scale: self.scale,
        }
    }

    /// `s·K + c`.
    pub fn restore(&self, k: &[C64; 12]) -> [C64; 12] {
        std::array::from_fn(|i| k[i] * self.scale + self.center[i % 2])
    }
}

/// Parameters of `problem` at the normalised configuration `k_normalized` of `design`:
/// `k_normalized` and the rigid shape constants in the frame's units.
fn normalized_parameters(
    problem: &LagrangeProblem,
    design: &Design,
    k_normalized: &[C64; 12],
    normalization: Normalization,
) -> Vec<C64> {
    problem.parameters_in_units(design, k_normalized, normalization.scale)
}

/// Parameters of `seeded`'s system at the real `pose` (in its labelling), in the stage's
/// normalised frame: the target of the seed → pose homotopy (`p = (N(K(pose)), shape
/// constants)`, the seed's being
/// [`SeedSolutions::parameters`](crate::pipeline::sweep::SeedSolutions::parameters)).
pub fn pose_parameters(stage: &SeedStage, seeded: &SeededProblem, pose: Pose) -> Vec<C64> {
    let design = &seeded.design;
    let k = design.configuration(pose).to_array();
    let k_normalized = stage.normalization.apply(&to_real(&k));
    normalized_parameters(&seeded.problem, design, &k_normalized, stage.normalization)
}

/// A point of the complexified motion: complex τ of an analytic motion, or a complex
/// pose `(x, y, φ)` for explicit pose lists (which are interpolated linearly in pose
/// coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MotionPoint {
    /// Motion parameter τ.
    Tau(C64),
    /// Pose `(x, y, φ)`.
    Pose([C64; 3]),
}

impl MotionPoint {
    fn target(motion: &Motion, sample: &SampledPose) -> Self {
        match motion {
            Motion::Analytic(_) => MotionPoint::Tau(C64::new(sample.tau, 0.0)),
            Motion::Poses(_) => MotionPoint::Pose([
                C64::new(sample.pose.x, 0.0),
                C64::new(sample.pose.y, 0.0),
                C64::new(sample.pose.phi, 0.0),
            ]),
        }
    }

    /// `self + ε·ξ` with ξ standard complex normal (per coordinate).
    fn perturbed(&self, epsilon: f64, rng: &mut random::SeededRng) -> Self {
        match *self {
            MotionPoint::Tau(t) => MotionPoint::Tau(t + random::complex_normal(rng) * epsilon),
            MotionPoint::Pose(p) => {
                MotionPoint::Pose(p.map(|v| v + random::complex_normal(rng) * epsilon))
            }
        }
    }

    /// The midpoint of `self` and `other` (same kind).
    fn midpoint(&self, other: &Self) -> Self {
        match (*self, *other) {
            (MotionPoint::Tau(a), MotionPoint::Tau(b)) => MotionPoint::Tau((a + b) * 0.5),
            (MotionPoint::Pose(a), MotionPoint::Pose(b)) => {
                MotionPoint::Pose(std::array::from_fn(|i| (a[i] + b[i]) * 0.5))
            }
            _ => *self,
        }
    }

    fn distance(&self, other: &Self) -> f64 {
        match (self, other) {
            (MotionPoint::Tau(a), MotionPoint::Tau(b)) => (a - b).norm(),
            (MotionPoint::Pose(a), MotionPoint::Pose(b)) => a
                .iter()
                .zip(b)
                .fold(0.0f64, |m, (u, v)| m.max((u - v).norm())),
            _ => 1.0,
        }
    }
}
/// The parameter path of a seed → pose homotopy (stage 2): along the complexified
/// motion through `waypoints` (straight segments in τ, or in pose coordinates for pose
/// lists), `p(t) = (N(K(w(t))) + (1 − t)·δ, shape constants)` with `N` the
/// normalisation and δ the seed perturbation. Unlike a straight segment in
/// configuration space — whose interpolated platform shrinks when the rotation angle
/// changes a lot, which drives critical points through infinity — every point of this
/// path is a (complex) pose of the design's rigid platform.
struct MotionPath<'a> {
    design: &'a Design,
    motion: &'a Motion,
    waypoints: Vec<MotionPoint>,
    breakpoints: Vec<f64>,
    perturbation: [C64; 12],
    normalization: Normalization,
    shape: Vec<C64>,
}

impl<'a> MotionPath<'a> {
    fn new(
        design: &'a Design,
        motion: &'a Motion,
        waypoints: Vec<MotionPoint>,
        perturbation: [C64; 12],
        normalization: Normalization,
        shape: Vec<C64>,
    ) -> Self {
        let segments = waypoints.len().saturating_sub(1).max(1);
        MotionPath {
            design,
            motion,
            breakpoints: (1..segments).map(|k| k as f64 / segments as f64).collect(),
            waypoints,
            perturbation,
            normalization,
            shape,
        }
    }

    /// Complex pose at `t` and its derivative `d(x, y, φ)/dt`.
    fn pose_and_rate(&self, t: C64) -> ([C64; 3], [C64; 3]) {
        let segments = self.waypoints.len() - 1;
        let scaled = t * segments as f64;
        let k = (scaled.re.floor().max(0.0) as usize).min(segments - 1);
        let s = scaled - k as f64;
        let zero = C64::new(0.0, 0.0);
        match (self.waypoints[k], self.waypoints[k + 1]) {
            (MotionPoint::Tau(a), MotionPoint::Tau(b)) => {
                let tau = a + s * (b - a);
                let rate = (b - a) * segments as f64;
                let pose = self.motion.pose_complex(tau).unwrap_or([zero; 3]);
                let derivative = self
                    .motion
                    .pose_derivative_complex(tau)
                    .unwrap_or([zero; 3]);
                (pose, derivative.map(|d| d * rate))
            }
            (MotionPoint::Pose(a), MotionPoint::Pose(b)) => (
                std::array::from_fn(|i| a[i] + s * (b[i] - a[i])),
                std::array::from_fn(|i| (b[i] - a[i]) * segments as f64),
            ),
            // Waypoints of one path are all of the motion's kind (see `MotionPoint::target`).
            _ => ([zero; 3], [zero; 3]),
        }
    }

    fn fill(&self, t: C64, pose: &[C64; 3], p: &mut [C64]) {
        let [x, y, phi] = *pose;
        let k = self
            .normalization
            .apply(&self.design.configuration_complex(x, y, phi));
        let fade = C64::new(1.0, 0.0) - t;
        for i in 0..12 {
            p[i] = k[i] + fade * self.perturbation[i];
        }
        p[12..].copy_from_slice(&self.shape);
    }
}

impl ParameterPath for MotionPath<'_> {
    fn len(&self) -> usize {
        12 + self.shape.len()
    }

    fn point(&self, t: C64, p: &mut [C64]) {
        let (pose, _) = self.pose_and_rate(t);
        self.fill(t, &pose, p);
    }

    /// `dK/dt`: base anchors fixed; platform anchor `b_i = (x, y) + R(φ) P_i` moves
    /// with `(ẋ − (sin φ P_ix + cos φ P_iy) φ̇, ẏ + (cos φ P_ix − sin φ P_iy) φ̇)`;
    /// divided by the frame's scale, minus the fading perturbation.
    fn point_and_velocity(&self, t: C64, p: &mut [C64], dp: &mut [C64]) {
        let (pose, rate) = self.pose_and_rate(t);
        self.fill(t, &pose, p);
        let (c, s) = (pose[2].cos(), pose[2].sin());
        let inverse_scale = 1.0 / self.normalization.scale;
        for i in 0..3 {
            dp[2 * i] = -self.perturbation[2 * i];
            dp[2 * i + 1] = -self.perturbation[2 * i + 1];
            let [px, py] = self.design.platform()[i];
            dp[6 + 2 * i] = (rate[0] - (s * px + c * py) * rate[2]) * inverse_scale
                - self.perturbation[6 + 2 * i];
            dp[6 + 2 * i + 1] = (rate[1] + (c * px - s * py) * rate[2]) * inverse_scale
                - self.perturbation[6 + 2 * i + 1];
        }
        for d in dp[12..].iter_mut() {
            *d = C64::new(0.0, 0.0);
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
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

/// Real critical points of one sub-problem at the real configuration `k`, as
/// candidates `(D(K, K′), K′)` for `metric`.
fn candidates(
    seeded: &SeededProblem,
    endpoints: &[Vec<C64>],
    (parameters, normalization): (&[C64], Normalization),
    k: &[f64; 12],
    real_tolerance: f64,
) -> Vec<Candidate> {
    let problem = &seeded.problem;
    let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
    endpoints
        .iter()
        .filter(|x| {
            // Realness of K′ (and of the other unknowns before the multipliers): the
            // multipliers of a real point then solve real linear equations and are real
            // themselves, and they are the least accurate entries of an endpoint — a
            // chart's `λ = λ′/λ₀` with a small `λ₀` (10⁻⁸ relative where K′ has 10⁻¹²),
            // and affine multipliers of ill-conditioned points: on the built-in example
            // (pose 10, `rigid/plate`) a critical point with λ ≈ −53 has Im λ ≈ 1.4·10⁻⁶
            // while K′ is real to 10⁻¹¹, and Krawczyk's test in double-double proves it
            // real.
            let cartesian = problem.to_cartesian(x);
            postprocess::is_real(&cartesian[..problem.first_multiplier()], real_tolerance)
        })
        .map(|x| {
            let k_prime = normalization
                .restore(&problem.configuration(x, parameters, &mut work))
                .map(|v| v.re);
            Candidate {
                // D is invariant under relabelling the legs of both K and K′.
                distance: seeded.id.metric.distance(k, &k_prime),
                closest: seeded.to_user_labels(&k_prime),
            }
        })
        .collect()
}

/// Which leg of a route a parameter path is: from the seed (attempt 0 straight, a
/// later attempt through a random complex point near the target), or between
/// neighbouring poses.
#[derive(Clone, Copy)]
enum RouteLeg {
    FromSeed { attempt: usize },
    BetweenNeighbours,
}

/// The parameter path of `leg` from `origin` to `target`: from the seed (with its
/// perturbation fading) straight, or for `attempt > 0` through a random complex point
/// near the target; between neighbouring poses through a random complex midpoint.
fn route_path<'a>(
    (stage, seeded): (&SeedStage, &SeededProblem),
    (design, motion): (&'a Design, &'a Motion),
    (origin, target): (MotionPoint, MotionPoint),
    leg: RouteLeg,
    mut rng: random::SeededRng,
    shape: Vec<C64>,
) -> MotionPath<'a> {
    let neighbour = matches!(leg, RouteLeg::BetweenNeighbours);
    let attempt = match leg {
        RouteLeg::FromSeed { attempt } => attempt,
        RouteLeg::BetweenNeighbours => 0,
    };
    let mut waypoints = vec![origin];
    if neighbour {
        // Between two real poses the straight segment may meet a real branch point
        // (two real critical points merging into a complex pair), so every route
        // passes through a random complex midpoint.
        let epsilon = 0.5 * origin.distance(&target);
        waypoints.push(origin.midpoint(&target).perturbed(epsilon, &mut rng));
    } else if attempt > 0 {
        let epsilon = 0.3 * origin.distance(&target) + 0.05;
        waypoints.push(target.perturbed(epsilon, &mut rng));
    }
    waypoints.push(target);
    let perturbation = if neighbour {
        [C64::new(0.0, 0.0); 12]
    } else {
        seeded.seed.perturbation
    };
    MotionPath::new(
        design,
        motion,
        waypoints,
        perturbation,
        stage.normalization,
        shape,
    )
}

/// Where the paths of a (pose, sub-problem) start.
#[derive(Clone, Copy)]
enum Route<'a> {
    /// From the seed solutions at the seed (stage 2).
    Seed,
    /// From the complete finite solution set of a neighbouring pose (the rescue pass).
    Neighbour {
        /// The neighbour's point of the motion.
        from: MotionPoint,
        /// Its finite critical points (normalised frame), one per start solution.
        solutions: &'a [Vec<C64>],
    },
}

/// One (pose, sub-problem) after tracking: what post-processing needs, and the finite
/// endpoints when they form a complete set (every path accounted for, all of them
/// finite), from which neighbouring poses can be re-solved.
struct ProblemAtPose {
    entry: PoseEntry,
    complete: Option<Vec<Vec<C64>>>,
}

/// What stage 2 solves every (pose, sub-problem) with: the seed stage (the
/// sub-problems, their seed solutions and the normalisation), the motion and the
/// options.
#[derive(Clone, Copy)]
pub(super) struct SolveContext<'a> {
    pub stage: &'a SeedStage,
    pub motion: &'a Motion,
    pub options: &'a CurveOptions,
}

impl<'a> SolveContext<'a> {
    /// Sub-problem `problem_index` at `sample`: the seeded problem, the pose's
    /// configuration in the sub-problem's own labelling (its rigid parts' reference
    /// anchors), the pose's point of the motion and its normalised parameters.
    fn problem_at(
        &self,
        problem_index: usize,
        sample: &SampledPose,
    ) -> (&'a SeededProblem, [f64; 12], MotionPoint, Vec<C64>) {
        let seeded = &self.stage.problems[problem_index];
        let design = &seeded.design;
        let k = design.configuration(sample.pose).to_array();
        let target = MotionPoint::target(self.motion, sample);
        let normalization = self.stage.normalization;
        let k_normalized = normalization.apply(&to_real(&k));
        let parameters =
            normalized_parameters(&seeded.problem, design, &k_normalized, normalization);
        (seeded, k, target, parameters)
    }
}

/// Tracks one sub-problem to pose `index` along `route`, with re-runs and detours.
fn track_problem(
    context: SolveContext<'_>,
    (index, sample): (usize, SampledPose),
    problem_index: usize,
    route: Route<'_>,
) -> ProblemAtPose {
    let SolveContext {
        stage,
        motion,
        options,
    } = context;
    let (seeded, k, target, parameters) = context.problem_at(problem_index, &sample);
    let design = &seeded.design;
    let (starts, origin, salt) = match route {
        Route::Seed => (seeded.at_seed.solutions.as_slice(), seeded.seed.point, 0),
        Route::Neighbour { from, solutions } => (solutions, from, 8),
    };
    let stream = ((index as u64 + 1) << 32) | problem_index as u64;
    let seed_route = matches!(route, Route::Seed);
    // The seed route's first run to a pose list's first pose, tracked in the seed stage.
    let probe = (seeded.seed_route_probe.as_ref()).filter(|p| seed_route && p.target == target);
    // The pose is real: the endpoints' conjugates are critical points too.
    let conjugate = |x: &[C64]| seeded.problem.conjugate(x);
    let track_route = |hand_over_when_steps_run_out: bool| {
        track_with_retries(
            seeded.problem.evaluator(),
            starts,
            |attempt| {
                let rng = random::stream(
                    options.seed,
                    stream.wrapping_mul(16) + salt + attempt as u64,
                );
                let leg = match route {
                    Route::Seed => RouteLeg::FromSeed { attempt },
                    Route::Neighbour { .. } => RouteLeg::BetweenNeighbours,
                };
                let shape = parameters[12..].to_vec();
                route_path(
                    (stage, seeded),
                    (design, motion),
                    (origin, target),
                    leg,
                    rng,
                    shape,
                )
            },
            options.retry_attempts,
            // At a generic real pose every critical point is finite and nonsingular (the
            // seed's points at infinity are gone already): no endgame needed; a path that
            // diverges, fails or ends singular is re-run with it.
            TrackingPlan {
                first: match route {
                    Route::Seed => &options.tracker,
                    Route::Neighbour { .. } => &options.neighbour_tracker,
                },
                retry: &options.retry_tracker,
                endgame: false,
                whole_detours: true,
                twin: seeded.twin.as_ref().map(|t| t as &dyn ProjectiveTwin),
                patient_twin: false,
                hand_over_when_steps_run_out,
                abandon_when_steps_run_out: true,
                conjugate: Some(&conjugate),
                first_run: probe.and_then(|p| p.first_run.as_deref()),
            },
        )
    };
    // Complete on its own terms: every path of the generic route accounted for (a
    // finite endpoint or one at infinity) and exactly the seed's count of distinct
    // finite ones. (Not the union with the seed route's endpoints: where the points are
    // ill-conditioned, one point reached by both routes can differ by more than the
    // same-point tolerance and would hide a missed one.) A seed point the route did not
    // reach as a finite one may instead be one of the paths the projective twin ended
    // at `λ₀ = 0` with the configuration finite: a critical point within about `|λ₀|`
    // of a Fritz John point, a singular point of the constraint set, whose distance the
    // singular-point sub-problems bound (Kapilavai and Nawratil, §4). On two base
    // anchors 10⁻⁴ apart one `bars/rigid` critical point has multipliers of 10¹²
    // (`λ₀ ≈ 10⁻¹²`) at every pose; the seed route reached it after re-runs and detours
    // of 1.3–2.1 s per pose, where the generic route took 0.4 s.
    let generic_complete = |generic: &Retried| {
        let (finite, generic_count) = (generic.endpoints.len(), seeded.at_seed.generic_count);
        generic.accounted == generic_count
            && (finite == seeded.at_seed.start_count
                || (finite < seeded.at_seed.start_count
                    && finite + generic.at_infinity_in_twin >= generic_count))
    };
    // Where the seed has fewer solutions than the expected count (a seed count refuted
    // at a real pose, see `probe_seed_counts`), the seed route cannot complete a pose,
    // and where it ran out of steps at a pose list's first pose (`probe_seed_route`)
    // it hardly will: the generic route first.
    let mut generic = None;
    let mut generic_tracked = 0;
    let seed_route_hopeless = seeded.at_seed.solutions.len() < seeded.at_seed.start_count
        || (seeded.seed_route_probe.as_ref()).is_some_and(SeedRouteProbe::ran_out_of_steps);
    if seed_route && seed_route_hopeless {
        let from_generic = generic_route(seeded, &parameters, stream, options);
        if generic_complete(&from_generic) {
            let at = (&parameters[..], &k);
            let counts = (seeded.at_seed.start_count, None, from_generic.tracked);
            return problem_at_pose(stage, seeded, from_generic.endpoints, at, counts, options);
        }
        generic_tracked = from_generic.tracked;
        generic = Some(from_generic);
    }
    // The seed route first; where its paths run out of steps (a route that is hard
    // all along), the generic route before the seed route's re-runs and detours.
    let mut retried = track_route(seed_route && generic.is_none());
    retried.tracked += generic_tracked;
    if retried.handed_over {
        let from_generic = generic_route(seeded, &parameters, stream, options);
        let tracked = retried.tracked + from_generic.tracked;
        if generic_complete(&from_generic) {
            retried = Retried {
                accounted: seeded.at_seed.start_count,
                tracked,
                reasons: BTreeMap::new(),
                ..from_generic
            };
        } else {
            retried = track_route(false);
            retried.tracked += tracked;
            generic = Some(from_generic);
        }
    }
    let Retried {
        endpoints,
        accounted: best,
        tracked,
        reasons,
        ..
    } = retried;
    let (endpoints, best, tracked, reasons) = if best < seeded.at_seed.start_count && seed_route {
        let (generic, tracked) = match generic {
            // Already tracked (and counted) when the seed route handed over.
            Some(generic) => (generic, tracked),
            None => {
                let generic = generic_route(seeded, &parameters, stream, options);
                let tracked = tracked + generic.tracked;
                (generic, tracked)
            }
        };
        if generic_complete(&generic) {
            (
                generic.endpoints,
                seeded.at_seed.start_count,
                tracked,
                BTreeMap::new(),
            )
        } else {
            (endpoints, best, tracked, reasons)
        }
    } else {
        (endpoints, best, tracked, reasons)
    };
    let (endpoints, best, reasons) = if best < seeded.at_seed.start_count {
        // At a real pose the critical points are real or come in conjugate pairs (on
        // two platform anchors 10⁻⁴ apart `rigid/rigid` poses ended with 85 of 88
        // distinct points: an odd count, one of them without its partner).
        let mut endpoints = endpoints;
        let conjugate = |x: &[C64]| seeded.problem.conjugate(x);
        let added = with_conjugates(&conjugate, &mut endpoints, seeded.at_seed.start_count);
        if endpoints.len() == seeded.at_seed.start_count {
            (endpoints, seeded.at_seed.start_count, BTreeMap::new())
        } else {
            (
                endpoints,
                (best + added).min(seeded.at_seed.start_count),
                reasons,
            )
        }
    } else {
        (endpoints, best, reasons)
    };
    let failure = (best < seeded.at_seed.start_count).then(|| PathFailure {
        pose_index: Some(index),
        tau: Some(sample.tau),
        problem: seeded.id.name(),
        expected: seeded.at_seed.start_count,
        accounted: best,
        reasons,
    });
    let at = (&parameters[..], &k);
    problem_at_pose(
        stage,
        seeded,
        endpoints,
        at,
        (best, failure, tracked),
        options,
    )
}

/// The generic route to a pose: the user homotopy from the start file's generic
/// parameters straight to the pose's (detours on retries), as the seed stage tracks to
/// the seed. Where the design is close to a degenerate one (two anchors of a rigid
/// part 1e-4 apart), critical points come in clusters at every parameter of the
/// design, and a seed → pose path must stay inside its cluster along the whole route;
/// from the generic point the cluster forms only as `t → 1`, where the step size
/// shrinks geometrically. Returns the route's distinct finite endpoints.
///
/// The first run has the endgame only where the sub-problem's expected count is below
/// its generic count, i.e. where paths end at infinity at a real pose. Elsewhere every
/// path ends at a finite critical point, and as on the seed route the endpoints are
/// refined by Newton's method at `t = 1`; a path that diverges, fails or crosses
/// another one is re-run with the endgame. On two base anchors 10⁻⁴ apart the
/// endgame's loops around the near-double critical points there (pairs 10⁻¹⁰ apart
/// relative to their norm) took 0.11–0.42 s per pose of `bars/rigid` against
/// 0.09–0.25 s without (design matrix, 8 scattered poses: 4.89 → 4.31 s; no other
/// class slower by more than the timing noise, every distance the same to 2.3·10⁻¹⁵).
fn generic_route(
    seeded: &SeededProblem,
    parameters: &[C64],
    stream: u64,
    options: &CurveOptions,
) -> Retried {
    let (source, starts) = &seeded.at_seed.generic_start;
    let mut tracker = options.tracker.clone();
    tracker.step.max_corrector_iterations = GENERIC_ROUTE_CORRECTOR_ITERATIONS;
    // The target pose is real (see `TrackingPlan::conjugate`).
    let conjugate = |x: &[C64]| seeded.problem.conjugate(x);
    let retried = track_with_retries(
        seeded.problem.evaluator(),
        starts,
        |attempt| {
            let mut points = vec![source.clone()];
            if attempt > 0 {
                let mut rng = random::stream(
                    options.seed,
                    (stream.wrapping_mul(16) + 12 + attempt as u64) ^ 0x9e37_79b9,
                );
                points.push(detour_point(parameters, 12, &mut rng));
            } else if options.generic_route_bend {
                let mut rng = random::stream(options.seed, (stream.wrapping_mul(16) + 12) ^ BEND);
                points.push(bend_point(source, parameters, &mut rng));
            }
            points.push(parameters.to_vec());
            PolylinePath::new(points)
        },
        options.seed_retry_attempts,
        TrackingPlan {
            endgame: seeded.at_seed.start_count < seeded.at_seed.generic_count,
            ..TrackingPlan::with_endgame(&tracker, &options.retry_tracker)
        }
        .lost_paths_only()
        .with_twin(seeded.twin.as_ref().map(|t| t as &dyn ProjectiveTwin))
        .with_conjugate(Some(&conjugate)),
    );
    Retried {
        endpoints: distinct_solutions(retried.endpoints, seeded.at_seed.generic_count),
        ..retried
    }
}

/// Newton iterations per step of the generic route's first run and detours (3 on
/// the seed route). Its paths end in clusters of critical points where the design is
/// close to a degenerate one, and near them a fourth iteration converges where three
/// do not, which would halve the step (design matrix, nine metrics, 8 poses, 2
/// threads: `close-base-12` scattered 4.00 → 3.90 s, analytic 4.29 → 4.22 s, no class
/// slower by more than 2 %, every distance the same to 2.9·10⁻¹⁵).
const GENERIC_ROUTE_CORRECTOR_ITERATIONS: usize = 4;

/// Random stream tag of [`bend_point`].
const BEND: u64 = 0x5bd1_e995;

/// Size of the bend of [`bend_point`] relative to the segment. The check stage's
/// generic routes cost more the larger it is (design matrix, 8 analytic poses, whole
/// run: close-base-23 9.4 s straight, 10.3 s at 1/20, 11.9 s at 1/10, 14.3 s at 1/4;
/// close-base-12 22.1, 23.1, 24.4, 27.2 s).
const BEND_SIZE: f64 = 0.05;

/// The bend of a generic route from `source` to `target` ([`CurveOptions::generic_route_bend`]):
/// `(source + target)/2 + BEND_SIZE·|target − source|∞·ξ`, ξ standard complex normal
/// per parameter, so that the two legs are hardly longer than the segment.
fn bend_point(source: &[C64], target: &[C64], rng: &mut random::SeededRng) -> Vec<C64> {
    let length = source
        .iter()
        .zip(target)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
    source
        .iter()
        .zip(target)
        .map(|(a, b)| (a + b) * 0.5 + random::complex_normal(rng) * (BEND_SIZE * length))
        .collect()
}

/// A sub-problem's result at a pose from its finite endpoints (normalised frame) at
/// the pose's `(parameters, configuration)`: the real candidates, and the endpoints
/// themselves when they are complete (the seed's count).
fn problem_at_pose(
    stage: &SeedStage,
    seeded: &SeededProblem,
    endpoints: Vec<Vec<C64>>,
    (parameters, k): (&[C64], &[f64; 12]),
    (best, failure, tracked): (usize, Option<PathFailure>, usize),
    options: &CurveOptions,
) -> ProblemAtPose {
    let list = candidates(
        seeded,
        &endpoints,
        (parameters, stage.normalization),
        k,
        options.real_tolerance,
    );
    let certificate = options
        .certify
        .then(|| PendingCertificate::new(endpoints.clone(), *k));
    let complete = (endpoints.len() == seeded.at_seed.start_count).then_some(endpoints);
    ProblemAtPose {
        entry: PoseEntry {
            candidates: list,
            accounted: best,
            failure,
            tracked,
            certificate,
        },
        complete,
    }
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
    // The sub-problems' certificates in parallel (a chain assembles its poses one
    // after the other).
    let mut certificates: BTreeMap<(String, String), SubproblemCertificate> = if options.certify {
        stage
            .problems
            .par_iter()
            .zip(per_problem.par_iter())
            .filter_map(|(seeded, entry)| {
                let certificate = entry.certificate.as_ref()?.get(stage, seeded);
                let key = (
                    seeded.id.metric.name(),
                    seeded.id.subproblem.name().to_string(),
                );
                Some((key, certificate))
            })
            .collect()
    } else {
        BTreeMap::new()
    };
    for (seeded, entry) in stage.problems.iter().zip(per_problem) {
        failures.extend(entry.failure);
        paths_tracked += entry.tracked;
        by_metric.entry(seeded.id.metric.name()).or_default().push((
            seeded.id.subproblem,
            entry.candidates,
            entry.accounted,
            seeded.at_seed.start_count,
        ));
    }
    for (&id, system) in stage.closed_form.iter().zip(&stage.closed_form_systems) {
        if let Some(system) = system.as_ref().filter(|_| options.certify)
            && let Some(certificate) = closed_form_certificate(stage, id, system, k)
        {
            let key = (id.metric.name(), id.subproblem.name().to_string());
            certificates.insert(key, certificate);
        }
        // Pedal points: both critical points (generic count 2); the circle of an
        // equilateral pair: its closest point.
        let closest: Vec<[f64; 12]> = match pedal::critical_points(id, k) {
            Some(points) => points.to_vec(),
            None => equilateral::closest_on_circle(id, k).into_iter().collect(),
        };
        let count = closest.len();
        let list: Vec<Candidate> = closest
            .into_iter()
            .map(|closest| Candidate {
                distance: id.metric.distance(k, &closest),
                closest,
            })
            .collect();
        let entry = (id.subproblem, list, count, count);
        by_metric.entry(id.metric.name()).or_default().push(entry);
    }
    let mut results = BTreeMap::new();
    for metric in metrics {
        let name = metric.name();
        if let Some(data) = by_metric.get(&name)
            && let Some(mut result) = postprocess::metric_distance(
                *metric,
                data,
                singularity,
                options.cut_locus_tolerance,
            )
        {
            if options.certify {
                attach_certificates(&name, &mut result, &mut certificates);
            }
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

/// The whole curve: seed stage, then every window of poses ([`CurveRun`]) in order,
/// each with its poses in parallel; `on_pose` is called as each pose completes (in
/// completion order, e.g. for progress). Holds every pose's results until the end:
/// long runs use [`CurveRun`] and hand each window on instead.
pub fn compute_curve(
    design: &Design,
    motion: &Motion,
    poses: usize,
    metrics: &[Metric],
    options: &CurveOptions,
    provider: StartProvider<'_>,
    on_pose: &(dyn Fn(&PoseResult) + Sync),
) -> Result<CurveResult, PipelineError> {
    let run = CurveRun::new((design, motion, metrics), poses, options, provider)?;
    let header = run.header();
    let windows = (0..header.windows)
        .map(|w| run.solve_window(w, on_pose))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(collect_curve(header, windows))
}

/// [`compute_curve`] from the start solutions embedded in the binary
/// ([`default_start_solutions`]), without progress reports.
pub fn compute_curve_from_embedded_starts(
    design: &Design,
    motion: &Motion,
    poses: usize,
    metrics: &[Metric],
    options: &CurveOptions,
) -> Result<CurveResult, PipelineError> {
    compute_curve(
        design,
        motion,
        poses,
        metrics,
        options,
        &default_start_solutions,
        &|_| {},
    )
}

/// Parameters τ where `S(K(τ))` changes sign between consecutive samples, refined by
/// bisection on the analytic motion to `|Δτ| ≤ 1e-14·(1 + |τ|)` (docs/theory.md §7: the
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
        roots.push(bisect_sign_change((a.tau, b.tau), sa, s_of));
    }
    if let Some(last) = samples.last()
        && design.configuration(last.pose).singularity() == 0.0
    {
        roots.push(last.tau);
    }
    roots
}

/// The default start provider: [`super::ab_initio::start_solutions_on`] (embedded
/// files, else on the generic stratum monodromy on the fly, cached per process).
pub fn default_start_solutions(
    id: ProblemId,
    stratum: Stratum,
) -> Result<std::sync::Arc<StartSolutions>, String> {
    match super::ab_initio::start_solutions_on(id, stratum) {
        Ok(Some(file)) => Ok(file),
        Ok(None) => Err(format!(
            "no start file of {} on the stratum {}",
            id.name(),
            stratum.name().unwrap_or("generic")
        )),
        Err(e) => Err(e.to_string()),
    }
}

#[cfg(test)]
mod tests;

//! Distance-to-singularity curves of a 3-RPR along a motion (SPEC A.9, paper §5).
//!
//! Stages, for every (metric, sub-problem) the selected metrics need. Every parameter
//! vector lives in one normalised frame per curve ([`Normalization`]: centroid and RMS
//! size of the first configuration), so coordinates and multipliers stay of order one.
//!
//! 1. **User homotopy** (paper Eqs. 65–66): the generic start solutions at their
//!    source parameters `p_src` (ab-initio stage) are tracked along the straight
//!    parameter segment `p(t) = (1 − t) p_src + t p*` to the *seed* `p*`: the motion at
//!    a random complex `τ*` (seeded), `K* = K(x(τ*), y(τ*), φ(τ*))` with complex
//!    `cos`, `sin` (for explicit pose lists: the first pose plus a complex
//!    perturbation), plus a small random complex perturbation δ of all twelve
//!    coordinates so that the fixed real base does not make the seed special
//!    ([`seed_point`]). The rigid parts' shape constants are those of the design. One
//!    seed solve serves every pose. Paths that end at infinity there are critical
//!    points the design's fixed shape does not have (e.g. the example design's base and
//!    platform have equal angles at anchor 1, so leg-collapse singular points of paper
//!    Thm 3 case 4 exist and absorb some critical points); the poses expect the seed's
//!    finite count.
//! 2. **Parameter homotopy** (paper §5.3): the seed solutions are tracked to the real
//!    configuration `K_j` of every pose along the complexified motion
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
//! 3. **No silent losses**: a (pose, sub-problem) with failed paths re-tracks them with
//!    [`TrackerOptions::conservative`], then tracks every path along a detour through a
//!    random complex motion point near the pose (seeded per pose, sub-problem and
//!    attempt; at the seed, through random complex parameters near `p*`, more
//!    attempts); finite endpoints of all attempts are merged. Paths classified at
//!    infinity are accounted for.
//!    **Rescue from neighbours**: once every pose is done, each run of consecutive
//!    poses at which a sub-problem still lost paths is re-solved pose by pose from the
//!    complete finite solution set of the pose before the run (forward), then of the
//!    pose after it (backward), through a random complex midpoint between the two
//!    poses; a re-solved pose whose set is complete seeds the next one. What still
//!    fails is reported as a [`PathFailure`].
//! 4. **Post-processing** ([`super::postprocess`]).

use super::postprocess::{self, Candidate, MetricDistance};

/// Per (pose, sub-problem): real candidates, finite endpoints, failure, paths tracked.
type PoseEntry = (Vec<Candidate>, usize, Option<PathFailure>, usize);
use super::start_file::StartSolutions;
use crate::C64;
use crate::homotopy::{
    FailureReason, Homotopy, ParameterPath, PathParameterHomotopy, PathResult, PathStatus,
    PolylinePath, Tracker, TrackerOptions,
};
use crate::mechanism::rpr::{Design, Motion, Pose, SampledPose, singularity_polynomial};
use crate::metric::Metric;
use crate::problem::{
    Coordinates, LagrangeProblem, ProblemError, ProblemId, equilateral, pedal, subproblems_of,
};
use crate::random;
use crate::system::Evaluator;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

mod options;
mod seed;
mod self_check;
pub use options::*;
pub use seed::*;
pub use self_check::{SELF_CHECK_TOLERANCE, SelfCheck};

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
    /// Paths whose endpoint was classified (finite, or at infinity), best attempt; the
    /// difference to `expected` is the number of paths that failed.
    pub accounted: usize,
    /// Why paths were unaccounted for on the reference route after the careful
    /// re-runs, by reason: a [`FailureReason`] name (e.g. `TooManySteps`), or
    /// `PathCrossing` for a path that ended on another one's endpoint. The detours may
    /// have recovered some of them since.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub reasons: BTreeMap<String, usize>,
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
        let scale = spread.sqrt();
        Normalization {
            center,
            // Designs are validated non-degenerate; guard anyway.
            scale: if scale.is_finite() && scale > 0.0 {
                scale
            } else {
                1.0
            },
        }
    }

    /// `(K − c)/s`.
    pub fn apply(&self, k: &[C64; 12]) -> [C64; 12] {
        std::array::from_fn(|i| (k[i] - self.center[i % 2]) / self.scale)
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
/// constants)`, the seed's being [`SeededProblem::seed_parameters`]).
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

/// Tracks every start solution through `homotopy` (with the endgame, or without:
/// [`Tracker::track_between`] `0 → 1`, Newton at the end); returns the path results in
/// order.
fn track_all<H: Homotopy + ?Sized>(
    homotopy: &H,
    starts: &[Vec<C64>],
    options: &TrackerOptions,
    endgame: bool,
) -> Vec<PathResult> {
    // In parallel over chunks of paths too (nested in the parallel poses ×
    // sub-problems), so a stage with few groups — the seed stage, a rescue chain — uses
    // every core; one tracker (workspace) per chunk. Per path instead of per chunk was
    // 30 % slower on the example. Each path is a pure function of its start, so the
    // results do not depend on the thread count.
    const CHUNK: usize = 16;
    let chunks: Vec<Vec<PathResult>> = starts
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut tracker = Tracker::new(homotopy, options.clone());
            chunk
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    if endgame {
                        tracker.track(x, c * CHUNK + i)
                    } else {
                        tracker.track_between(x, 0.0, 1.0, c * CHUNK + i)
                    }
                })
                .collect()
        })
        .collect();
    chunks.into_iter().flatten().collect()
}

/// Why paths of one run are unaccounted for ([`accounted`]): per failure reason (its
/// name), and `PathCrossing` for each path beyond the first on a shared endpoint.
fn unaccounted_reasons(paths: &[PathResult]) -> BTreeMap<String, usize> {
    let mut reasons = BTreeMap::new();
    for p in paths {
        if let PathStatus::Failed(reason) = p.status {
            *reasons.entry(format!("{reason:?}")).or_insert(0) += 1;
        }
    }
    let crossed: usize = shared_endpoints(paths).iter().map(|g| g.len() - 1).sum();
    if crossed > 0 {
        reasons.insert("PathCrossing".into(), crossed);
    }
    reasons
}

/// What [`track_with_retries`] found for one group of paths.
pub(crate) struct Retried {
    /// The distinct finite endpoints of all attempts.
    pub endpoints: Vec<Vec<C64>>,
    /// Paths accounted for, best over the attempts (see [`accounted`]).
    pub accounted: usize,
    /// Paths tracked, re-runs and detours included.
    pub tracked: usize,
    /// Why paths were unaccounted for on the reference route after the careful
    /// re-runs ([`unaccounted_reasons`]; empty if none were).
    pub reasons: BTreeMap<String, usize>,
}

/// Relative distance under which two endpoints are the same point.
const SAME_ENDPOINT: f64 = 1e-8;

fn same_endpoint(a: &[C64], b: &[C64]) -> bool {
    // Squared moduli: this runs for every pair of endpoints of every run.
    let scale = 1.0 + a.iter().fold(0.0f64, |m, v| m.max(v.norm_sqr())).sqrt();
    let tolerance = (SAME_ENDPOINT * scale).powi(2);
    a.iter()
        .zip(b)
        .all(|(u, v)| (u - v).norm_sqr() <= tolerance)
}

/// Whether a path's endpoint is finite and was reached without winding (winding number
/// 1): nonsingular endpoints, and those classified singular only because their
/// condition number is large (e.g. far out along an isotropic line, where the unscaled
/// condition number exceeds `singular_condition` although the point is simple).
fn simple_endpoint(path: &PathResult) -> bool {
    path.status.is_finite() && path.winding_number == 1
}

/// For every path, whether it is a *path crossing*: its endpoint is simple
/// ([`simple_endpoint`]) and another such path ends at the same point. A nonsingular
/// solution is the endpoint of exactly one path of a parameter homotopy, so one of them
/// jumped (and missed a critical point). Endpoints reached with winding (Cauchy
/// endgame, winding number > 1) may legitimately be shared (multiplicity); a genuinely
/// singular endpoint reached without winding is reported as a crossing, which can only
/// cost a re-run, never hide a lost path. Paths classified at infinity on the same
/// point at the same `t` cross too ([`shared_endpoints`]).
fn crossings(paths: &[PathResult]) -> Vec<bool> {
    let mut crossed = vec![false; paths.len()];
    for group in shared_endpoints(paths) {
        for i in group {
            crossed[i] = true;
        }
    }
    crossed
}

/// Groups (two or more paths) that share an endpoint no two paths may share: simple
/// finite endpoints ([`simple_endpoint`]), and paths classified at infinity that
/// stopped at the same `t` on the same point. Distinct paths of a homotopy never meet
/// before `t = 1` (and the branches of one Puiseux cycle are apart at any one radius),
/// so a shared point at infinity means one path jumped onto another one's divergent
/// path, hiding the critical point it should have reached.
fn shared_endpoints(paths: &[PathResult]) -> Vec<Vec<usize>> {
    let shareable = |a: &PathResult, b: &PathResult| {
        (simple_endpoint(a) && simple_endpoint(b))
            || (a.status == PathStatus::AtInfinity
                && b.status == PathStatus::AtInfinity
                && a.last_t == b.last_t)
    };
    let eligible = |p: &PathResult| simple_endpoint(p) || p.status == PathStatus::AtInfinity;
    // Sort and sweep: two endpoints within `same_endpoint`'s tolerance have first
    // coordinates within `window` (the largest tolerance of any pair), so only
    // neighbours in the order of Re x₀ closer than that are compared.
    let key = |i: usize| paths[i].solution.first().map_or(0.0, |v| v.re);
    let mut order: Vec<usize> = (0..paths.len()).filter(|&i| eligible(&paths[i])).collect();
    if order.len() < 2 {
        return Vec::new();
    }
    let largest = order.iter().fold(0.0f64, |m, &i| {
        paths[i]
            .solution
            .iter()
            .fold(m, |m, v| m.max(v.re.abs()).max(v.im.abs()))
    });
    let window = SAME_ENDPOINT * (1.0 + 2.0 * largest);
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
    // Pairs `(i, j)`, `i < j`, that share an endpoint, with `i`'s tolerance.
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for (position, &a) in order.iter().enumerate() {
        for &b in &order[position + 1..] {
            if key(b) - key(a) > window {
                break;
            }
            let (i, j) = (a.min(b), a.max(b));
            if shareable(&paths[i], &paths[j])
                && same_endpoint(&paths[i].solution, &paths[j].solution)
            {
                pairs.push((i, j));
            }
        }
    }
    pairs.sort_unstable();
    // Each group: the first ungrouped path and every later ungrouped one sharing its
    // endpoint.
    let mut grouped = vec![false; paths.len()];
    let mut groups = Vec::new();
    for run in pairs.chunk_by(|x, y| x.0 == y.0) {
        let i = run[0].0;
        if grouped[i] {
            continue;
        }
        let mut group = vec![i];
        for &(_, j) in run {
            if !grouped[j] {
                group.push(j);
                grouped[j] = true;
            }
        }
        if group.len() > 1 {
            groups.push(group);
        }
    }
    groups
}

/// Paths whose fate is known: a finite endpoint, or an endpoint at infinity (a
/// critical point that does not exist at these parameters, classified by the endgame),
/// less one per extra path on a shared endpoint ([`shared_endpoints`]: a path crossing
/// hides a missed critical point just as a failed path does).
fn accounted(paths: &[PathResult]) -> usize {
    let classified = paths
        .iter()
        .filter(|p| !matches!(p.status, PathStatus::Failed(_)))
        .count();
    let extra: usize = shared_endpoints(paths).iter().map(|g| g.len() - 1).sum();
    classified - extra
}

/// The distinct finite endpoints: every endpoint reached with winding (shared ones
/// count with their multiplicity of paths, as the start count does) and each simple
/// endpoint ([`simple_endpoint`]) once.
fn finite_solutions(paths: &[PathResult]) -> Vec<Vec<C64>> {
    let mut out: Vec<Vec<C64>> = Vec::new();
    for p in paths.iter().filter(|p| p.status.is_finite()) {
        let duplicate = simple_endpoint(p) && out.iter().any(|x| same_endpoint(x, &p.solution));
        if !duplicate {
            out.push(p.solution.clone());
        }
    }
    out
}

/// Random complex detour point near `target`: `target + ε·ξ`, ξ standard complex normal,
/// `ε = 0.1·(1 + ‖target‖∞)` (only the first twelve parameters, the configuration).
fn detour_point(target: &[C64], rng: &mut random::SeededRng) -> Vec<C64> {
    let scale = 0.1 * (1.0 + target.iter().fold(0.0f64, |m, v| m.max(v.norm())));
    target
        .iter()
        .enumerate()
        .map(|(i, v)| {
            if i < 12 {
                v + random::complex_normal(rng) * scale
            } else {
                *v
            }
        })
        .collect()
}

/// Half-width in `t` of the arcs around a point where a path diverged before the
/// endgame zone ([`track_with_retries`]).
const DIVERGENCE_ARC: f64 = 0.05;

/// The tracker settings of [`track_with_retries`].
#[derive(Clone, Copy)]
pub(crate) struct TrackingPlan<'a> {
    /// Options of the first run and of the detours.
    pub first: &'a TrackerOptions,
    /// Options of the re-runs of failed or crossed paths (always with the endgame).
    pub retry: &'a TrackerOptions,
    /// Whether the first run and the detours end with the endgame. Without it (between
    /// two generic parameter points, where every critical point is finite and
    /// nonsingular) the endpoint is Newton-refined at `t = 1`; a path that fails,
    /// crosses another one or diverges is re-run with the endgame.
    pub endgame: bool,
}

impl<'a> TrackingPlan<'a> {
    /// Both runs with the endgame.
    pub fn with_endgame(first: &'a TrackerOptions, retry: &'a TrackerOptions) -> Self {
        TrackingPlan {
            first,
            retry,
            endgame: true,
        }
    }
}

/// Tracks `starts` (solutions of `system` at `path(k)`'s start) along `path(0)` (the
/// reference route, `plan.first`), then, while paths are unaccounted for:
/// 1. re-tracks the failed paths and path crossings (two paths on one nonsingular
///    endpoint) with `plan.retry` and the endgame, except paths that diverged before
///    the endgame zone (passing close to infinity is a property of the route, not of
///    the step size); without the endgame also the paths that diverged;
/// 2. tracks each path that diverged before the endgame zone
///    around the point where it did, along a small arc in the `t`-plane on either
///    side ([`Tracker::track_via`]); an endpoint counts only if it is finite and
///    distinct from every endpoint found (an endpoint of any route is a solution at
///    the target, but which one a path reaches may depend on the route);
/// 3. tracks every path along the detours `path(1)`, … `path(attempts)`, merging the
///    distinct finite endpoints.
///
/// Returns the merged finite endpoints, the number of accounted paths ([`accounted`]:
/// of the best attempt, or the distinct finite endpoints of all attempts plus the
/// most paths one attempt classified at infinity) and the number of paths tracked.
pub(crate) fn track_with_retries<E: Evaluator + ?Sized, P: ParameterPath>(
    system: &E,
    starts: &[Vec<C64>],
    path: impl Fn(usize) -> P,
    attempts: usize,
    plan: TrackingPlan<'_>,
) -> Retried {
    let TrackingPlan {
        first: tracker,
        retry: retry_tracker,
        endgame,
    } = plan;
    let expected = starts.len();
    let reference = PathParameterHomotopy::new(system, path(0));
    let mut paths = track_all(&reference, starts, tracker, endgame);
    let mut tracked = starts.len();
    let crossed = crossings(&paths);
    let diverged_mid_path =
        |p: &PathResult| p.status == PathStatus::Failed(FailureReason::DivergedBeforeEndgame);
    // Without the endgame, "at infinity" only means the norm grew past
    // `at_infinity_norm` somewhere along the route: re-run with the endgame to tell a
    // point at infinity of the target from a pole passed on the way.
    let rerun = |p: &PathResult, crossed: bool| {
        (matches!(p.status, PathStatus::Failed(_)) && !diverged_mid_path(p))
            || crossed
            || (!endgame && p.status == PathStatus::AtInfinity)
    };
    if paths.iter().zip(&crossed).any(|(p, &c)| rerun(p, c)) {
        let mut careful = Tracker::new(&reference, retry_tracker.clone());
        for (i, path) in paths.iter_mut().enumerate() {
            if rerun(path, crossed[i]) {
                *path = careful.track(&starts[i], i);
                tracked += 1;
            }
        }
    }
    let mut endpoints = finite_solutions(&paths);
    let mut best = accounted(&paths);
    let reasons = if best < expected {
        unaccounted_reasons(&paths)
    } else {
        BTreeMap::new()
    };
    let count_at_infinity = |paths: &[PathResult]| {
        paths
            .iter()
            .filter(|p| p.status == PathStatus::AtInfinity)
            .count()
    };
    let mut at_infinity = count_at_infinity(&paths);
    let merge = |endpoints: &mut Vec<Vec<C64>>, found: Vec<Vec<C64>>| {
        for x in found {
            if !endpoints.iter().any(|y| same_endpoint(y, &x)) {
                endpoints.push(x);
            }
        }
    };
    if best < expected {
        // Paths that passed too close to infinity on the reference route: around the
        // trouble spot `t_c` along a small arc in the t-plane, on either side (where
        // the route has no breakpoint, at which a complex t would not be analytic).
        // Away from branch points both arcs continue the same path, to the endpoint
        // the reference route would reach.
        let mut arcs = Tracker::new(&reference, tracker.clone());
        let breakpoints = reference.breakpoints();
        for p in paths.iter().filter(|p| diverged_mid_path(p)) {
            let t_c = p.last_t.re;
            let delta = DIVERGENCE_ARC.min(t_c).min(1.0 - t_c);
            if breakpoints.iter().any(|b| (b - t_c).abs() <= delta) {
                continue;
            }
            for side in [1.0, -1.0] {
                let via = [
                    C64::new(t_c - delta, 0.0),
                    C64::new(t_c, side * delta),
                    C64::new(t_c + delta, 0.0),
                ];
                let around = arcs.track_via(&starts[p.path_index], &via, p.path_index);
                tracked += 1;
                if simple_endpoint(&around)
                    && !endpoints.iter().any(|y| same_endpoint(y, &around.solution))
                {
                    endpoints.push(around.solution);
                    break;
                }
            }
        }
        best = best.max(endpoints.len() + at_infinity);
    }
    // The starts whose paths are still unaccounted for on the reference route.
    let missing: Vec<Vec<C64>> = if best < expected {
        let crossed = crossings(&paths);
        paths
            .iter()
            .zip(&crossed)
            .filter(|&(p, &c)| matches!(p.status, PathStatus::Failed(_)) || c)
            .map(|(p, _)| starts[p.path_index].clone())
            .collect()
    } else {
        Vec::new()
    };
    for attempt in 1..=attempts {
        if best >= expected {
            break;
        }
        let detour = PathParameterHomotopy::new(system, path(attempt));
        if attempt == 1 && !missing.is_empty() && missing.len() < starts.len() {
            // First only those on the detour: any distinct finite endpoint they reach
            // is a critical point the reference route missed (e.g. 2 of the example's
            // 80 `rigid/rigid` seed → pose-0 paths, which pass through a pole on the
            // way). The whole detour only if they do not complete the set.
            let found = track_all(&detour, &missing, tracker, endgame);
            tracked += missing.len();
            merge(&mut endpoints, finite_solutions(&found));
            best = best.max(endpoints.len() + at_infinity);
            if best >= expected {
                break;
            }
        }
        let paths = track_all(&detour, starts, tracker, endgame);
        tracked += starts.len();
        best = best.max(accounted(&paths));
        at_infinity = at_infinity.max(count_at_infinity(&paths));
        merge(&mut endpoints, finite_solutions(&paths));
        // The union of the attempts' distinct finite endpoints, plus the most paths
        // any one attempt classified at infinity, may account for more than any
        // single attempt.
        best = best.max(endpoints.len() + at_infinity);
    }
    Retried {
        endpoints,
        // The union of attempts can exceed the paths (duplicates beyond tolerance).
        accounted: best.min(expected),
        tracked,
        reasons,
    }
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
        .filter(|x| postprocess::is_real(&problem.to_cartesian(x), real_tolerance))
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

/// The parameter path of attempt `attempt` from `origin` to `target`: from the seed
/// (with its perturbation fading) straight, or for `attempt > 0` through a random
/// complex point near the target; between neighbouring poses through a random complex
/// midpoint.
#[allow(clippy::too_many_arguments)]
fn route_path<'a>(
    (stage, seeded): (&SeedStage, &SeededProblem),
    design: &'a Design,
    motion: &'a Motion,
    (origin, target): (MotionPoint, MotionPoint),
    neighbour: bool,
    attempt: usize,
    mut rng: random::SeededRng,
    shape: Vec<C64>,
) -> MotionPath<'a> {
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

/// Tracks one sub-problem to pose `index` along `route`, with re-runs and detours.
#[allow(clippy::too_many_arguments)]
fn track_problem(
    stage: &SeedStage,
    motion: &Motion,
    (index, sample): (usize, SampledPose),
    problem_index: usize,
    route: Route<'_>,
    options: &CurveOptions,
) -> ProblemAtPose {
    let seeded = &stage.problems[problem_index];
    // The sub-problem's own labelling (its rigid parts' reference anchors).
    let design = &seeded.design;
    let k = design.configuration(sample.pose).to_array();
    let target = MotionPoint::target(motion, &sample);
    let k_normalized = stage.normalization.apply(&to_real(&k));
    let parameters =
        normalized_parameters(&seeded.problem, design, &k_normalized, stage.normalization);
    let (starts, origin, salt) = match route {
        Route::Seed => (seeded.seed_solutions.as_slice(), seeded.seed.point, 0),
        Route::Neighbour { from, solutions } => (solutions, from, 8),
    };
    let stream = ((index as u64 + 1) << 32) | problem_index as u64;
    let Retried {
        endpoints,
        accounted: best,
        tracked,
        reasons,
    } = track_with_retries(
        seeded.problem.evaluator(),
        starts,
        |attempt| {
            let rng = random::stream(
                options.seed,
                stream.wrapping_mul(16) + salt + attempt as u64,
            );
            let neighbour = matches!(route, Route::Neighbour { .. });
            let ends = (origin, target);
            let shape = parameters[12..].to_vec();
            route_path(
                (stage, seeded),
                design,
                motion,
                ends,
                neighbour,
                attempt,
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
        },
    );
    let failure = (best < seeded.start_count).then(|| PathFailure {
        pose_index: Some(index),
        tau: Some(sample.tau),
        problem: seeded.id.name(),
        expected: seeded.start_count,
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
    let complete = (endpoints.len() == seeded.start_count).then_some(endpoints);
    ProblemAtPose {
        entry: (list, best, failure, tracked),
        complete,
    }
}

/// A known value of one critical point along the motion: `(s, x)`, `s` in units of
/// the pose spacing from the latest solved pose (`0`; earlier poses at `−1`, `−2`,
/// sub-steps towards the next pose at `0 < s < 1`).
type Node<'a> = (f64, &'a [C64]);

/// The polynomial through the latest (up to three) nodes (`nodes[0]` the latest), at
/// `s` (Lagrange form); for nodes at `0, −1, −2` and `s = 1`: `3x₀ − 3x₁ + x₂`.
fn extrapolate(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
    let nodes = &nodes[..nodes.len().min(3)];
    for o in out.iter_mut() {
        *o = C64::new(0.0, 0.0);
    }
    for (k, &(sk, xk)) in nodes.iter().enumerate() {
        let weight = nodes
            .iter()
            .enumerate()
            .filter(|&(l, _)| l != k)
            .fold(1.0, |w, (_, &(sl, _))| w * (s - sl) / (sk - sl));
        for (o, x) in out.iter_mut().zip(xk) {
            *o += x * weight;
        }
    }
}

/// Per coordinate, the Möbius function `(p + q s)/(1 + r s)` through the latest three
/// nodes (`p + q s_k − r s_k x_k = x_k`, Cramer's rule), at `s`. Exact for a
/// coordinate with a simple pole in τ, like the far-out critical points that pass near
/// infinity between poses; the polynomial ([`extrapolate`]) where the fit is
/// degenerate.
fn extrapolate_moebius(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
    let [(s0, x0), (s1, x1), (s2, x2), ..] = *nodes else {
        return extrapolate(nodes, s, out);
    };
    extrapolate(nodes, s, out);
    let one = C64::new(1.0, 0.0);
    let det3 = |m: [[C64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    for (i, o) in out.iter_mut().enumerate() {
        let rows = [(s0, x0[i]), (s1, x1[i]), (s2, x2[i])];
        let matrix = rows.map(|(sk, xk)| [one, C64::new(sk, 0.0), -xk * sk]);
        let rhs = rows.map(|(_, xk)| xk);
        let det = det3(matrix);
        let column = |c: usize| {
            let mut m = matrix;
            for (row, value) in m.iter_mut().zip(rhs) {
                row[c] = value;
            }
            det3(m) / det
        };
        let (p, q, r) = (column(0), column(1), column(2));
        let value = (p + q * s) / (one + r * s);
        if value.re.is_finite() && value.im.is_finite() {
            *o = value;
        }
    }
}

/// A prediction of a critical point at `s` from its known values ([`Node`]).
type Predictor = fn(&[Node<'_>], f64, &mut [C64]);

/// The predictions [`jump_problem`] tries in turn, given `depth` known values: the
/// polynomial extrapolation, then the Möbius one, then the latest value. (Measured on
/// the built-in example: the Möbius and constant retries cut the critical points
/// left to pose-to-pose paths from 1,252 to 841.)
fn predictors(depth: usize) -> &'static [Predictor] {
    fn latest(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
        extrapolate(&nodes[..1], s, out);
    }
    match depth {
        0 | 1 => &[extrapolate],
        2 => &[extrapolate, latest],
        _ => &[extrapolate, extrapolate_moebius, latest],
    }
}

/// Newton's method at `s` ([`Tracker::correct_at`]) from each prediction in turn;
/// the first limit that is a simple endpoint, else the last attempt.
fn correct_predicted<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    nodes: &[Node<'_>],
    s: f64,
    prediction: &mut [C64],
    path_index: usize,
) -> PathResult {
    let mut result = None;
    for predict in predictors(nodes.len()) {
        predict(nodes, s, prediction);
        let limit = tracker.correct_at(prediction, s, path_index);
        let simple = simple_endpoint(&limit);
        result = Some(limit);
        if simple {
            break;
        }
    }
    result.expect("at least one predictor")
}

/// Smallest sub-step (in pose spacings) of [`substep_to_pose`].
const MIN_SUBSTEP: f64 = 1.0 / 16.0;

/// Newton continuation of one critical point from the latest pose (`s = 0`) to the
/// next (`s = 1`) along the straight real route (`homotopy` at `t = s`): sub-steps
/// from `½` down to [`MIN_SUBSTEP`] pose spacings, each predicted from the latest
/// three known values ([`correct_predicted`]), halved when Newton's method fails,
/// doubled when it succeeds. `None` if a sub-step would fall below the minimum.
fn substep_to_pose<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    history: &[&[C64]],
    path_index: usize,
) -> Option<PathResult> {
    let mut nodes: Vec<(f64, Vec<C64>)> = history
        .iter()
        .enumerate()
        .map(|(k, x)| (-(k as f64), x.to_vec()))
        .collect();
    let mut prediction = vec![C64::new(0.0, 0.0); history[0].len()];
    let (mut s, mut h): (f64, f64) = (0.0, 0.5);
    loop {
        let target = (s + h).min(1.0);
        let known: Vec<Node<'_>> = nodes.iter().map(|(s, x)| (*s, x.as_slice())).collect();
        let result = correct_predicted(tracker, &known, target, &mut prediction, path_index);
        if simple_endpoint(&result) {
            if target >= 1.0 {
                return Some(result);
            }
            nodes.insert(0, (target, result.solution));
            nodes.truncate(3);
            s = target;
            h *= 2.0;
        } else {
            h *= 0.5;
            if h < MIN_SUBSTEP {
                return None;
            }
        }
    }
}

/// For every point of a solution set at a real parameter, the index of its complex
/// conjugate in the set ([`LagrangeProblem::conjugate`]; itself for a real point), or
/// `None` if the conjugate is not in the set or the pairing is not mutual.
fn conjugate_partners(problem: &LagrangeProblem, set: &[Vec<C64>]) -> Vec<Option<usize>> {
    let found: Vec<Option<usize>> = set
        .iter()
        .map(|x| {
            let conjugate = problem.conjugate(x);
            set.iter().position(|y| same_endpoint(y, &conjugate))
        })
        .collect();
    (0..set.len())
        .map(|i| found[i].filter(|&j| found[j] == Some(i)))
        .collect()
}

/// Solves one sub-problem at pose `index` from the complete solution sets of the
/// preceding poses (`history`, latest first, each in the same order) without tracking:
/// every critical point is extrapolated ([`extrapolate`]) and corrected by Newton's
/// method at the pose ([`Tracker::correct_at`]). Of each complex conjugate pair only
/// one is continued and the other is its conjugate ([`conjugate_partners`]; the poses
/// are real). Which critical point a Newton sequence converges to is not controlled,
/// but the set is checked: the number of nonsingular solutions is at most the generic
/// one, so `start_count` distinct nonsingular limits are all the critical points.
/// Limits that fail or coincide are re-tracked from the latest pose (short paths
/// through a random complex midpoint); `None` when the set is still incomplete.
#[allow(clippy::too_many_arguments)]
fn jump_problem(
    stage: &SeedStage,
    motion: &Motion,
    (index, sample): (usize, SampledPose),
    problem_index: usize,
    from: MotionPoint,
    history: &[&[Vec<C64>]],
    options: &CurveOptions,
) -> Option<ProblemAtPose> {
    let seeded = &stage.problems[problem_index];
    // The sub-problem's own labelling (its rigid parts' reference anchors).
    let design = &seeded.design;
    let latest = *history.first()?;
    let k = design.configuration(sample.pose).to_array();
    let target = MotionPoint::target(motion, &sample);
    let k_normalized = stage.normalization.apply(&to_real(&k));
    let parameters =
        normalized_parameters(&seeded.problem, design, &k_normalized, stage.normalization);
    let stream = ((index as u64 + 1) << 32) | problem_index as u64;
    let rng = random::stream(options.seed, stream.wrapping_mul(16) + 8);
    let path = route_path(
        (stage, seeded),
        design,
        motion,
        (from, target),
        true,
        0,
        rng,
        parameters[12..].to_vec(),
    );
    let homotopy = PathParameterHomotopy::new(seeded.problem.evaluator(), path);
    // At a real pose the critical points come in complex conjugate pairs (and real
    // ones): only one of each pair is continued, its partner is the conjugate.
    let partner = conjugate_partners(&seeded.problem, latest);
    let representatives: Vec<usize> = (0..latest.len())
        .filter(|&i| partner[i].is_none_or(|j| j >= i))
        .collect();
    const CHUNK: usize = 16;
    let mut reps: Vec<PathResult> = representatives
        .par_chunks(CHUNK)
        .map(|chunk| {
            let mut tracker = Tracker::new(&homotopy, options.neighbour_tracker.clone());
            let mut prediction = vec![C64::new(0.0, 0.0); homotopy.dimension()];
            chunk
                .iter()
                .map(|&i| {
                    // At most JUMP_HISTORY known values, on the stack.
                    let mut nodes: [Node<'_>; JUMP_HISTORY] = [(0.0, &[]); JUMP_HISTORY];
                    let depth = history.len().min(JUMP_HISTORY);
                    for (k, (node, set)) in nodes.iter_mut().zip(history).enumerate() {
                        *node = (-(k as f64), set[i].as_slice());
                    }
                    let nodes = &nodes[..depth];
                    correct_predicted(&mut tracker, nodes, 1.0, &mut prediction, i)
                })
                .collect::<Vec<_>>()
        })
        .flatten()
        .collect();
    let mut tracked = reps.len();
    // Newton limits that failed or coincide: continued in sub-steps along the straight
    // real route, else tracked (short paths through the complex midpoint).
    let straight = PathParameterHomotopy::new(
        seeded.problem.evaluator(),
        MotionPath::new(
            design,
            motion,
            vec![from, target],
            [C64::new(0.0, 0.0); 12],
            stage.normalization,
            parameters[12..].to_vec(),
        ),
    );
    let redo = |which: &[usize], substeps: bool| -> Vec<PathResult> {
        which
            .par_chunks(4)
            .map(|chunk| {
                let mut newton = Tracker::new(&straight, options.neighbour_tracker.clone());
                let mut paths = Tracker::new(&homotopy, options.neighbour_tracker.clone());
                chunk
                    .iter()
                    .map(|&i| {
                        let known: Vec<&[C64]> =
                            history.iter().map(|set| set[i].as_slice()).collect();
                        substeps
                            .then(|| substep_to_pose(&mut newton, &known, i))
                            .flatten()
                            .unwrap_or_else(|| paths.track_between(&latest[i], 0.0, 1.0, i))
                    })
                    .collect::<Vec<_>>()
            })
            .flatten()
            .collect()
    };
    let crossed = crossings(&reps);
    let which: Vec<usize> = (0..reps.len())
        .filter(|&r| !simple_endpoint(&reps[r]) || crossed[r])
        .collect();
    let indices: Vec<usize> = which.iter().map(|&r| reps[r].path_index).collect();
    for (r, result) in which.iter().zip(redo(&indices, true)) {
        reps[*r] = result;
    }
    tracked += which.len();
    let mut paths: Vec<Option<PathResult>> = vec![None; latest.len()];
    for result in reps {
        let i = result.path_index;
        if let Some(j) = partner[i].filter(|&j| j != i) {
            let mut conjugate = result.clone();
            conjugate.solution = seeded.problem.conjugate(&result.solution);
            conjugate.path_index = j;
            paths[j] = Some(conjugate);
        }
        paths[i] = Some(result);
    }
    let mut paths = paths.into_iter().collect::<Option<Vec<PathResult>>>()?;
    // A pair whose continuation became real (two real critical points), or a path
    // crossing between pairs: those critical points are tracked one by one, by paths
    // through the complex midpoint only. Newton sub-steps along the real route cannot
    // separate them: the iterates from a point and from its conjugate stay conjugate,
    // so a pair that turned real between the poses lands twice on one real point.
    let crossed = crossings(&paths);
    let which: Vec<usize> = (0..paths.len())
        .filter(|&i| !simple_endpoint(&paths[i]) || crossed[i])
        .collect();
    for (&i, result) in which.iter().zip(redo(&which, false)) {
        paths[i] = result;
    }
    tracked += which.len();
    let complete = paths.iter().all(simple_endpoint)
        && !crossings(&paths).contains(&true)
        && paths.len() == seeded.start_count;
    if !complete {
        return None;
    }
    let endpoints: Vec<Vec<C64>> = paths.into_iter().map(|p| p.solution).collect();
    let at = (&parameters[..], &k);
    let count = (seeded.start_count, None, tracked);
    Some(problem_at_pose(
        stage, seeded, endpoints, at, count, options,
    ))
}

/// Stages 2–4 at one pose along the reference route: parameter homotopy from the seed
/// along the complexified motion (`MotionPath`) for every sub-problem (in parallel),
/// re-runs of failed paths (detours through a random complex point near the pose),
/// post-processing. ([`compute_curve`] solves most poses from their neighbours instead,
/// see [`CurveOptions::chain_length`].)
pub fn solve_pose(
    stage: &SeedStage,
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    index: usize,
    sample: SampledPose,
    options: &CurveOptions,
) -> PoseResult {
    let entries = (0..stage.problems.len())
        .into_par_iter()
        .map(|problem_index| {
            let at = (index, sample);
            track_problem(stage, motion, at, problem_index, Route::Seed, options).entry
        })
        .collect();
    let k = design.configuration(sample.pose).to_array();
    assemble_pose(stage, metrics, index, sample, &k, entries, options)
}

/// Poses a block of [`solve_chain`] runs through per sub-problem before they are
/// assembled (and reported as partial results).
const POSES_PER_BLOCK: usize = 10;

/// One sub-problem at pose `at` of a chain, from the solution sets of the preceding
/// poses in chain order (`history`, latest first; the latest is pose `previous`):
/// Newton jumps ([`jump_problem`]), else pose-to-pose paths from the latest set, else
/// the seed route. Returns the result and whether its solution set is in the order of
/// `history` (not after the seed route).
#[allow(clippy::too_many_arguments)]
fn solve_problem_in_chain(
    stage: &SeedStage,
    motion: &Motion,
    samples: &[SampledPose],
    (j, sample): (usize, SampledPose),
    problem_index: usize,
    (previous, history): (usize, &[Vec<Vec<C64>>]),
    options: &CurveOptions,
) -> (ProblemAtPose, bool) {
    let at = (j, sample);
    let from = || MotionPoint::target(motion, &samples[previous]);
    if options.jump && !history.is_empty() {
        let sets: Vec<&[Vec<C64>]> = history.iter().map(|s| s.as_slice()).collect();
        let jumped = jump_problem(stage, motion, at, problem_index, from(), &sets, options);
        if let Some(result) = jumped {
            return (result, true);
        }
    }
    let from_neighbour = history.first().map(|solutions| {
        let route = Route::Neighbour {
            from: from(),
            solutions,
        };
        track_problem(stage, motion, at, problem_index, route, options)
    });
    match from_neighbour {
        Some(result) if result.complete.is_some() => (result, true),
        neighbour => {
            let seed = Route::Seed;
            let mut result = track_problem(stage, motion, at, problem_index, seed, options);
            if let Some(neighbour) = neighbour {
                let tracked = result.entry.3 + neighbour.entry.3;
                if neighbour.entry.1 > result.entry.1 {
                    result = neighbour;
                }
                result.entry.3 = tracked;
            }
            (result, false)
        }
    }
}

/// Solution sets kept per sub-problem for [`extrapolate`].
const JUMP_HISTORY: usize = 3;

/// The pose of `poses` where a chain starts from the seed: the one nearest `Re τ*`
/// (the shortest seed route: on the built-in example the `rigid/rigid` seed route to
/// the motion's first pose took 13 × as long as to the pose nearest `Re τ*`), or the
/// first pose for explicit pose lists (whose seed is the first pose perturbed).
fn chain_anchor(
    stage: &SeedStage,
    samples: &[SampledPose],
    poses: &std::ops::Range<usize>,
) -> usize {
    match stage.seed.point {
        MotionPoint::Tau(tau) => poses
            .clone()
            .min_by(|&a, &b| {
                (samples[a].tau - tau.re)
                    .abs()
                    .total_cmp(&(samples[b].tau - tau.re).abs())
            })
            .unwrap_or(poses.start),
        MotionPoint::Pose(_) => poses.start,
    }
}

/// Stage 2 along one block of consecutive poses (see [`CurveOptions::chain_length`]):
/// the anchor ([`chain_anchor`]) from the seed, then the poses after it (forwards) and
/// before it (backwards), each per sub-problem from the preceding pose's (in chain
/// order) complete finite solution set, or from the seed when that set is incomplete
/// or the pose-to-pose paths do not reach a complete set. Calls `on_pose` per pose;
/// returns the poses in index order.
#[allow(clippy::too_many_arguments)]
fn solve_chain(
    stage: &SeedStage,
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    samples: &[SampledPose],
    poses: std::ops::Range<usize>,
    options: &CurveOptions,
    on_pose: &(dyn Fn(&PoseResult) + Sync),
) -> Vec<(PoseResult, Vec<ProblemAtPose>)> {
    let problems = stage.problems.len();
    let anchor = chain_anchor(stage, samples, &poses);
    // The two directions, in chain order after the anchor.
    let directions: [Vec<usize>; 2] = [
        (anchor + 1..poses.end).collect(),
        (poses.start..anchor).rev().collect(),
    ];
    // Per (direction, sub-problem), the complete solution sets of the last poses
    // (latest first) and the latest pose: cleared where a pose went the seed route.
    type History = (usize, Vec<Vec<Vec<C64>>>);
    let assemble = |j: usize, at_pose: Vec<ProblemAtPose>| {
        let sample = samples[j];
        let k = design.configuration(sample.pose).to_array();
        let entries = at_pose.iter().map(|p| p.entry.clone()).collect();
        let result = assemble_pose(stage, metrics, j, sample, &k, entries, options);
        on_pose(&result);
        (result, at_pose)
    };
    // Runs one sub-problem's chain through `block` (poses in chain order).
    let run =
        |history: &mut History, problem_index: usize, block: &[usize]| -> Vec<ProblemAtPose> {
            block
                .iter()
                .map(|&j| {
                    let (previous, sets) = (history.0, &history.1);
                    let (result, same_order) = solve_problem_in_chain(
                        stage,
                        motion,
                        samples,
                        (j, samples[j]),
                        problem_index,
                        (previous, sets),
                        options,
                    );
                    let sets = &mut history.1;
                    if !same_order {
                        sets.clear();
                    }
                    match &result.complete {
                        Some(set) => {
                            sets.insert(0, set.clone());
                            sets.truncate(JUMP_HISTORY);
                        }
                        None => sets.clear(),
                    }
                    history.0 = j;
                    result
                })
                .collect()
        };
    let mut anchor_history: Vec<History> = vec![(anchor, Vec::new()); problems];
    let at_anchor: Vec<ProblemAtPose> = anchor_history
        .par_iter_mut()
        .enumerate()
        .map(|(problem_index, history)| run(history, problem_index, &[anchor]).remove(0))
        .collect();
    let mut out = vec![assemble(anchor, at_anchor)];
    // Both directions continue from the anchor's sets.
    let mut histories: Vec<History> = [anchor_history.clone(), anchor_history].concat();
    // The sub-problems' chains are independent: each runs through a block of poses
    // on its own (no barrier per pose), both directions at once, then the blocks'
    // poses are assembled.
    let blocks: [Vec<&[usize]>; 2] = directions
        .each_ref()
        .map(|d| d.chunks(POSES_PER_BLOCK).collect());
    for step in 0..blocks[0].len().max(blocks[1].len()) {
        let per_task: Vec<Vec<ProblemAtPose>> = histories
            .par_iter_mut()
            .enumerate()
            .map(|(task, history)| {
                let (direction, problem_index) = (task / problems, task % problems);
                match blocks[direction].get(step) {
                    Some(block) => run(history, problem_index, block),
                    None => Vec::new(),
                }
            })
            .collect();
        let mut per_task: Vec<std::vec::IntoIter<ProblemAtPose>> =
            per_task.into_iter().map(|v| v.into_iter()).collect();
        for (direction, tasks) in per_task.chunks_mut(problems).enumerate() {
            let Some(block) = blocks[direction].get(step) else {
                continue;
            };
            for &j in *block {
                let at_pose: Vec<ProblemAtPose> = tasks
                    .iter_mut()
                    .map(|results| results.next().expect("one result per pose"))
                    .collect();
                out.push(assemble(j, at_pose));
            }
        }
    }
    out.sort_by_key(|(result, _)| result.index);
    out
}

/// The rescue pass (stage 3b): every run of consecutive poses at which a sub-problem
/// lost paths is re-solved pose by pose from a neighbouring pose whose finite solution
/// set is complete — first forward from the pose before the run, then backward from the
/// pose after it for what is still incomplete. Near a pose the critical points move
/// little, so short pose-to-pose paths (through a complex midpoint) follow critical
/// points that the long seed → pose paths lose, e.g. huge ill-conditioned ones.
/// Returns the indices of the poses whose entries changed.
fn rescue_from_neighbours(
    stage: &SeedStage,
    motion: &Motion,
    samples: &[SampledPose],
    work: &mut [Vec<ProblemAtPose>],
    options: &CurveOptions,
) -> Vec<usize> {
    let n = samples.len();
    let lost = |work: &[Vec<ProblemAtPose>], j: usize, p: usize| work[j][p].entry.2.is_some();
    // (sub-problem, first pose, last pose) of every run of failing poses.
    let mut runs = Vec::new();
    for p in 0..stage.problems.len() {
        let mut j = 0;
        while j < n {
            if lost(work, j, p) {
                let first = j;
                while j + 1 < n && lost(work, j + 1, p) {
                    j += 1;
                }
                runs.push((p, first, j));
            }
            j += 1;
        }
    }
    let view: &[Vec<ProblemAtPose>] = work;
    // Per run: the improved (pose, result) pairs and the paths tracked per pose.
    type RunOutcome = (BTreeMap<usize, ProblemAtPose>, BTreeMap<usize, usize>);
    let outcomes: Vec<(usize, RunOutcome)> = runs
        .par_iter()
        .map(|&(p, first, last)| {
            let mut improved: BTreeMap<usize, ProblemAtPose> = BTreeMap::new();
            let mut tracked: BTreeMap<usize, usize> = BTreeMap::new();
            // Solves pose `to` from the complete set at pose `from`; keeps the result
            // if it accounts for more paths than the best so far. Returns the
            // complete set at `to`, if reached.
            let mut step = |from: usize, to: usize, solutions: &[Vec<C64>]| {
                let result = track_problem(
                    stage,
                    motion,
                    (to, samples[to]),
                    p,
                    Route::Neighbour {
                        from: MotionPoint::target(motion, &samples[from]),
                        solutions,
                    },
                    options,
                );
                *tracked.entry(to).or_default() += result.entry.3;
                let best = improved.get(&to).map_or(view[to][p].entry.1, |r| r.entry.1);
                let complete = result.complete.clone();
                if result.entry.1 > best {
                    improved.insert(to, result);
                }
                complete
            };
            // Forward from the pose before the run.
            let mut reached = first;
            if first > 0
                && let Some(mut solutions) = view[first - 1][p].complete.clone()
            {
                while reached <= last {
                    match step(reached - 1, reached, &solutions) {
                        Some(next) => {
                            solutions = next;
                            reached += 1;
                        }
                        None => break,
                    }
                }
            }
            // Backward from the pose after the run, down to where forward stopped.
            if reached <= last
                && last + 1 < n
                && let Some(mut solutions) = view[last + 1][p].complete.clone()
            {
                let mut j = last;
                while j >= reached {
                    match step(j + 1, j, &solutions) {
                        Some(next) if j > reached => {
                            solutions = next;
                            j -= 1;
                        }
                        _ => break,
                    }
                }
            }
            (p, (improved, tracked))
        })
        .collect();
    let mut changed = Vec::new();
    for (p, (improved, tracked)) in outcomes {
        for (j, count) in tracked {
            work[j][p].entry.3 += count;
            changed.push(j);
        }
        for (j, mut result) in improved {
            // Every path tracked counts: the seed route's and the rescue's.
            result.entry.3 = work[j][p].entry.3;
            work[j][p] = result;
        }
    }
    changed.sort_unstable();
    changed.dedup();
    changed
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
    for &id in &stage.closed_form {
        let closest = pedal::closest_by_pedal_points(id, k)
            .map(|solution| solution.closest)
            .or_else(|| equilateral::closest_on_circle(id, k));
        let list: Vec<Candidate> = closest
            .map(|closest| Candidate {
                distance: id.metric.distance(k, &closest),
                closest,
            })
            .into_iter()
            .collect();
        let entry = (id.subproblem, list, 1, 1);
        by_metric.entry(id.metric.name()).or_default().push(entry);
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

/// Largest step between consecutive poses that a chain continues across: the
/// largest coordinate change of the normalised configuration (units of the RMS size
/// of the configuration). Across a larger step the Newton jumps and pose-to-pose
/// paths of a chain cost more than the seed route (30 scattered poses of the
/// example design: chained through every step 2.2 × the CPU time of the seed route
/// per pose), so a new chain starts there. The built-in example's steps are 0.05.
pub const FAR_POSE_STEP: f64 = 0.25;

/// The chains of stage 2 as index ranges `[first, last)`: at most `chain_length`
/// poses each ([`CurveOptions::chain_length`]), split where consecutive poses are
/// farther apart than [`FAR_POSE_STEP`]. Depends on the poses only, not on the
/// thread count.
fn chain_blocks(
    design: &Design,
    samples: &[SampledPose],
    chain_length: usize,
    normalization: Normalization,
) -> Vec<(usize, usize)> {
    let normalised =
        |j: usize| normalization.apply(&to_real(&design.configuration(samples[j].pose).to_array()));
    let mut blocks = Vec::new();
    let mut first = 0;
    let mut previous = samples.first().map(|_| normalised(0));
    for j in 1..samples.len() {
        let current = normalised(j);
        let step = previous.map_or(0.0, |p| {
            p.iter()
                .zip(&current)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()))
        });
        if j - first >= chain_length.max(1) || step > FAR_POSE_STEP {
            blocks.push((first, j));
            first = j;
        }
        previous = Some(current);
    }
    if !samples.is_empty() {
        blocks.push((first, samples.len()));
    }
    blocks
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
    let blocks = chain_blocks(design, &samples, options.chain_length, stage.normalization);
    let (mut results, mut work): (Vec<PoseResult>, Vec<Vec<ProblemAtPose>>) = blocks
        .par_iter()
        .flat_map_iter(|&(first, last)| {
            solve_chain(
                &stage,
                design,
                motion,
                metrics,
                &samples,
                first..last,
                options,
                on_pose,
            )
        })
        .collect::<Vec<_>>()
        .into_iter()
        .unzip();
    for j in rescue_from_neighbours(&stage, motion, &samples, &mut work, options) {
        let k = design.configuration(samples[j].pose).to_array();
        let entries = work[j].iter().map(|p| p.entry.clone()).collect();
        results[j] = assemble_pose(&stage, metrics, j, samples[j], &k, entries, options);
        on_pose(&results[j]);
    }
    let self_check = if options.self_check {
        let context = (design, motion, metrics);
        Some(self_check::self_check(
            context,
            &samples,
            &mut results,
            options,
            provider,
        )?)
    } else {
        None
    };
    let mut failures = stage.failures.clone();
    failures.extend(results.iter().flat_map(|r| r.failures.iter().cloned()));
    let paths_tracked =
        stage.paths_tracked + results.iter().map(|r| r.paths_tracked).sum::<usize>();
    Ok(CurveResult {
        metric_names: metrics.iter().map(Metric::name).collect(),
        seed: options.seed,
        tau_star: match stage.seed.point {
            MotionPoint::Tau(t) => Some([t.re, t.im]),
            MotionPoint::Pose(_) => None,
        },
        not_applicable: stage.not_applicable.clone(),
        poses: results,
        failures,
        paths_tracked,
        self_check,
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rpr::{example_design, example_motion};

    /// The predictors are exact on their model functions at any nodes: a quadratic
    /// per coordinate for [`extrapolate`], a Möbius function (a simple pole at
    /// `s = 2.5` and `s = −4`) for [`extrapolate_moebius`], which the quadratic misses.
    #[test]
    fn predictors_reproduce_their_model_functions() {
        let quadratic = |s: f64| {
            [
                C64::new(1.0 - 2.0 * s + 0.5 * s * s, s),
                C64::new(3.0, -s * s),
            ]
        };
        let moebius = |s: f64| {
            [
                C64::new(2.0 + 3.0 * s, 1.0) / (1.0 - 0.4 * s),
                C64::new(-1.0, 0.5 * s) / C64::new(1.0 + 0.25 * s, 0.1 * s),
            ]
        };
        let nodes_of = |at: &[f64; 3], values: &[[C64; 2]; 3]| -> Vec<(f64, Vec<C64>)> {
            at.iter()
                .zip(values)
                .map(|(&t, v)| (t, v.to_vec()))
                .collect()
        };
        for nodes_at in [[0.0, -1.0, -2.0], [0.5, 0.0, -1.0], [0.75, 0.5, 0.0]] {
            for s in [1.0, 0.875] {
                let mut out = [C64::new(0.0, 0.0); 2];
                let owned = nodes_of(&nodes_at, &nodes_at.map(quadratic));
                let nodes: Vec<Node<'_>> = owned.iter().map(|(t, v)| (*t, &v[..])).collect();
                extrapolate(&nodes, s, &mut out);
                let exact = quadratic(s);
                assert!(
                    (0..2).all(|i| (out[i] - exact[i]).norm() < 1e-12),
                    "{out:?} vs {exact:?}"
                );
                let owned = nodes_of(&nodes_at, &nodes_at.map(moebius));
                let nodes: Vec<Node<'_>> = owned.iter().map(|(t, v)| (*t, &v[..])).collect();
                extrapolate_moebius(&nodes, s, &mut out);
                let exact = moebius(s);
                assert!(
                    (0..2).all(|i| (out[i] - exact[i]).norm() < 1e-10),
                    "{out:?} vs {exact:?}"
                );
                extrapolate(&nodes, s, &mut out);
                assert!(
                    (out[0] - exact[0]).norm() > 1e-3,
                    "the quadratic should miss the pole"
                );
            }
        }
    }

    fn path(index: usize, status: PathStatus, point: [f64; 2]) -> PathResult {
        PathResult {
            path_index: index,
            solution: point.iter().map(|&v| C64::new(v, 0.5)).collect(),
            status,
            residual: 0.0,
            condition: 1.0,
            winding_number: 1,
            multiplicity: 1,
            steps: 10,
            rejected_steps: 0,
            used_extended_precision: false,
            last_t: C64::new(1.0, 0.0),
        }
    }

    /// Two paths on one nonsingular endpoint are a crossing (one critical point
    /// missed): both are flagged, one is unaccounted for and the point is listed once;
    /// two paths on one singular endpoint reached with winding (Cauchy endgame,
    /// winding number 2) are a double root (both accounted for); two paths on one
    /// endpoint classified singular only by its condition number (winding number 1,
    /// e.g. far out along an isotropic line) are a crossing too.
    #[test]
    fn path_crossings_are_unaccounted_and_shared_singular_endpoints_are_not() {
        use PathStatus::{AtInfinity, Failed, Nonsingular, Singular};
        let winding = |mut p: PathResult| {
            p.winding_number = 2;
            p
        };
        let paths = vec![
            path(0, Nonsingular, [1.0, 2.0]),
            path(1, Nonsingular, [1.0, 2.0 + 1e-12]),
            path(2, Nonsingular, [3.0, 4.0]),
            winding(path(3, Singular, [5.0, 6.0])),
            winding(path(4, Singular, [5.0, 6.0])),
            path(5, AtInfinity, [1e9, 0.0]),
            path(
                6,
                Failed(crate::homotopy::FailureReason::TooManySteps),
                [7.0, 7.0],
            ),
            path(7, Singular, [8.0, 9.0]),
            path(8, Singular, [8.0, 9.0]),
        ];
        assert_eq!(
            crossings(&paths),
            vec![true, true, false, false, false, false, false, true, true]
        );
        // 9 paths: one failed, one extra on each of the two crossings.
        assert_eq!(accounted(&paths), 6);
        assert_eq!(finite_solutions(&paths).len(), 5);
        // The three unaccounted paths, by reason (as `PathFailure::reasons`).
        let reasons = unaccounted_reasons(&paths);
        assert_eq!(
            reasons.into_iter().collect::<Vec<_>>(),
            vec![
                ("PathCrossing".to_string(), 2),
                ("TooManySteps".to_string(), 1)
            ]
        );
        assert!(unaccounted_reasons(&paths[..3]).len() == 1);
        assert!(unaccounted_reasons(&paths[2..6]).is_empty());
    }

    /// Two paths classified at infinity on the same point at the same `t` cross (one
    /// jumped onto the other's divergent path); at different `t`, or on different
    /// points, they do not.
    #[test]
    fn paths_diverging_together_are_a_crossing() {
        use PathStatus::{AtInfinity, Nonsingular};
        let at = |mut p: PathResult, t: f64| {
            p.last_t = C64::new(t, 0.0);
            p
        };
        let paths = vec![
            at(path(0, AtInfinity, [146.6, 3.0]), 0.9999755859375),
            at(path(1, AtInfinity, [146.6, 3.0]), 0.9999755859375),
            at(path(2, AtInfinity, [146.6, 3.0]), 0.99990234375),
            at(path(3, AtInfinity, [70.0, 3.0]), 0.9999755859375),
            path(4, Nonsingular, [1.0, 2.0]),
        ];
        assert_eq!(crossings(&paths), vec![true, true, false, false, false]);
        assert_eq!(accounted(&paths), 4);
    }

    /// `MotionPath::point_and_velocity` is the derivative of `MotionPath::point`
    /// (central differences in complex t), on every segment of a detoured path.
    #[test]
    fn motion_path_velocity_matches_finite_differences() {
        let design = example_design();
        let motion = example_motion();
        let seed = seed_point(&design, &motion, 3);
        let k0 = design
            .configuration(motion.pose(0.3).expect("pose"))
            .to_array();
        let normalization = Normalization::of(&to_real(&k0));
        let target = MotionPoint::Tau(C64::new(1.7, 0.0));
        let mut rng = random::stream(3, 99);
        let waypoints = vec![seed.point, target.perturbed(0.5, &mut rng), target];
        let path = MotionPath::new(
            &design,
            &motion,
            waypoints,
            seed.perturbation,
            normalization,
            vec![C64::new(0.4, 0.1); 6],
        );
        let m = path.len();
        let (mut p, mut dp, mut plus, mut minus) = (
            vec![C64::new(0.0, 0.0); m],
            vec![C64::new(0.0, 0.0); m],
            vec![C64::new(0.0, 0.0); m],
            vec![C64::new(0.0, 0.0); m],
        );
        for t in [0.1, 0.37, 0.62, 0.9] {
            for direction in [C64::new(1.0, 0.0), C64::new(0.0, 1.0)] {
                let t = C64::new(t, 0.0);
                let h = direction * 1e-6;
                path.point_and_velocity(t, &mut p, &mut dp);
                path.point(t + h, &mut plus);
                path.point(t - h, &mut minus);
                for i in 0..m {
                    let fd = (plus[i] - minus[i]) / (h * 2.0);
                    assert!(
                        (fd - dp[i]).norm() <= 1e-6 * (1.0 + dp[i].norm()),
                        "t = {t}, i = {i}: {fd} vs {}",
                        dp[i]
                    );
                }
            }
        }
    }
}

//! Predictor–corrector path tracking with a Cauchy endgame.
//!
//! A path `x(t)` of `H(x(t), t) = 0` satisfies the Davidenko equation
//! `∂H/∂x · ẋ = −∂H/∂t`. One step from `t` to `t + h`:
//!
//! 1. **Predictor**: classical fourth-order Runge–Kutta on the Davidenko equation
//!    (local error `O(h⁵)`), every stage one LU solve. The first stage reuses the
//!    factorisation of the corrector's last Newton iteration (a point within the
//!    corrector tolerance of the accepted one), so a step costs three fresh Jacobians
//!    for the predictor and one or two for the corrector. On a stiff stretch (a
//!    cluster of solutions nearby, where the velocity field off the path varies on a
//!    far shorter scale than the path: ten accepted steps in a row that each shrank
//!    the step, now below 1 % of the distance to `t = 1`) the rest of the segment is
//!    predicted by cubic Hermite extrapolation from the last two points and their
//!    velocities (`hermite`; in the curve pipeline's presets).
//! 2. **Corrector**: Newton's method at `t + h`, accepted only if it *contracts*:
//!    the second update must be at most `max_contraction` times the first
//!    (`‖Δ₁‖ ≤ κ‖Δ₀‖`). By Smale's α-theory an approximate zero has `‖Δ₁‖ ≤ ½‖Δ₀‖`,
//!    and a ratio `κ ≪ ½` keeps the prediction deep inside the quadratic basin of the
//!    path being followed, the standard guard against path jumping. At most
//!    `max_corrector_iterations` updates.
//! 3. **Step control**: the first Newton update `‖Δ₀‖` measures the predictor error
//!    `≈ C h⁵`; the next step is `h·(ε_pred/‖Δ₀‖)^{1/5}` (clamped to `[½, 2]`), so
//!    the prediction error stays near `prediction_tolerance` (relative). A rejected step
//!    halves `h`.
//! 4. **Adaptive precision** (in the spirit of Bates, Hauenstein, Sommese & Wampler's
//!    adaptive multiprecision): after `extended_after_rejections` consecutive rejected
//!    steps at a condition number κ > 10⁶ (below it double precision is accurate to
//!    κ·ε ≈ 10⁻¹⁰ and a rejection means the step was too long) the tracker switches to double-double arithmetic
//!    ([`crate::system::double_double`]): residuals `H`, Jacobians `∂H/∂x` and `∂H/∂t`
//!    come from the compiled tapes run in double-double
//!    ([`Homotopy::evaluate_extended`],
//!    [`Homotopy::evaluate_with_jacobian_and_time_derivative_extended`]) and every
//!    linear solve (predictor velocities, Newton updates) is a double-double LU
//!    ([`super::linalg::DdLuWorkspace`]). In double precision a solve at condition κ
//!    loses `κ·ε` of relative accuracy: once `κ·ε` exceeds the corrector tolerance
//!    Newton's updates are noise, and well before that the velocities are, which caps
//!    the step size (the predictor error grows like `κ·ε·‖ẋ‖h` instead of `h⁵`). Rounding
//!    the Jacobian to double costs the same `κ·ε` even with an exact residual, hence
//!    the double-double Jacobian and LU; they hold up to `κ ≈ 10²⁵`, e.g. along
//!    critical points that run out to `‖x‖ ~ 10⁴–10⁶` in an isotropic direction. Every
//!    `extended_accepted_steps` accepted steps it returns to double if `κ ≤ 10⁶`; steps
//!    in extended precision cost about ten double ones and have their own budget
//!    (`max_extended_steps`).
//!
//! **Endgame** (`t → 1`, `s = 1 − t`): at the radii `s_k = s₀ r^k` the tracker
//! - estimates the valuations `v_i = Re(s ẋ_i(s) / x_i)` (`x_i ~ s^{v_i}`): a stable
//!   negative valuation of a coordinate that has grown by a factor 100 since the start
//!   of the endgame (below `s = 10⁻⁸` without growth), or a norm beyond
//!   `at_infinity_norm`, means the path diverges (solution at infinity, Huber &
//!   Verschelde's power-series test); an endgame stopped by the step size or budget
//!   with stable negative valuations is at infinity too; while large
//!   coordinates (‖x‖ ≥ 10) still have negative valuations no Cauchy loop is run (it
//!   could not close on a finite estimate, and is costly that far out);
//! - if the Jacobian is well conditioned, tracks straight to `t = 1` and refines the
//!   endpoint by Newton (finite nonsingular);
//! - otherwise runs the **Cauchy endgame** (Morgan, Sommese & Wampler 1991): it tracks
//!   around the circle `|s| = s_k` until the path closes after `c` loops (the winding
//!   number, `x(s) = x* + Σ a_j s^{j/c}`), and the mean of the samples is the Cauchy
//!   integral `x* = (1/2πi)∮ x(τ) dτ/τ` in `τ = s^{1/c}` (trapezoid rule, spectrally
//!   accurate). Two successive estimates agreeing gives a finite singular endpoint.
//!
//! The pieces: `options` (the knobs and presets), `step` (one predictor–corrector
//! step and the step-size control), `hermite` (the predictor of stiff stretches),
//! `precision` (double / double-double evaluations
//! and the switching rule), `endpoint` (Newton's method at a fixed `t`), `endgame`
//! (the classification near `t = 1`); this module holds the loop along a route and
//! the result types. Along a route the tracker reports only reached, diverged or
//! failed; only the endgame classifies a path as at infinity.

use super::homotopies::Homotopy;
use super::newton::max_norm;
use crate::C64;
use precision::{Evaluation, NewtonUpdate, Precision, RETURN_TO_DOUBLE_CONDITION};
use serde::{Deserialize, Serialize};
use step::{MIN_ABSOLUTE_STEP, step_factor, step_floor, step_fraction};

mod endgame;
mod endpoint;
mod hermite;
mod options;
mod precision;
mod step;

pub(crate) use endgame::is_averaged_estimate;
pub use options::{
    CURVE_AT_INFINITY_NORM, CURVE_EXTENDED_AFTER_REJECTIONS, CURVE_MAX_STEPS,
    CURVE_PREDICTION_TOLERANCE, CURVE_SEED_EXTENDED_AFTER_REJECTIONS, EndgameOptions,
    PrecisionOptions, StepOptions, TrackerOptions,
};

/// Why a path failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum FailureReason {
    /// The start point does not satisfy `H(x, 0) = 0` to Newton accuracy.
    InvalidStartPoint,
    /// The step size fell below `min_step_fraction` (even with extended precision).
    StepSizeTooSmall,
    /// More than `max_steps` steps.
    TooManySteps,
    /// The path diverged before the endgame zone (a non-generic γ or start system).
    DivergedBeforeEndgame,
    /// The path's norm passed `at_infinity_norm` on a route tracked without endgame
    /// ([`Tracker::track_between`]): a pole passed on the way, or a root at infinity of
    /// the end system; only an endgame can tell which.
    DivergedOnRoute,
    /// The Cauchy loop did not close within `max_winding_number` loops.
    WindingNumberTooLarge,
    /// The endgame reached `endgame_min_radius` without two agreeing estimates.
    EndgameDidNotConverge,
    /// NaN or infinity appeared in the evaluation.
    NonFiniteValue,
    /// The path ended at a nonsingular root another path of the run also reached
    /// (even after re-tracking): one of them jumped, and a root may be missing.
    PathJumped,
    /// Newton's method from a predicted point ([`Tracker::correct_at`]) stopped
    /// contracting, or its limit is singular.
    CorrectorDidNotConverge,
    /// A finite endpoint's homogenising coordinate is nearly zero, but Newton's method
    /// in extended precision neither converges to a point off the hyperplane at
    /// infinity nor approaches the hyperplane linearly: the endpoint is neither shown
    /// finite nor shown at infinity.
    HyperplaneUndecided,
}

/// Classification of a path's endpoint at `t = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum PathStatus {
    /// Finite endpoint with a well-conditioned Jacobian, refined to full precision.
    Nonsingular,
    /// Finite endpoint with a singular Jacobian (winding number and multiplicity given).
    Singular,
    /// The path diverges: a solution at infinity.
    AtInfinity,
    /// The tracker gave up; see the reason.
    Failed(FailureReason),
}

impl PathStatus {
    /// Finite endpoint (nonsingular or singular).
    pub fn is_finite(&self) -> bool {
        matches!(self, PathStatus::Nonsingular | PathStatus::Singular)
    }
}

/// Outcome of one tracked path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathResult {
    /// Index of the path (start solution) in its run.
    pub path_index: usize,
    /// Endpoint (the last point reached for failed or diverging paths).
    pub solution: Vec<C64>,
    /// Classification.
    pub status: PathStatus,
    /// `‖H(x, 1)‖∞` at the endpoint.
    pub residual: f64,
    /// 1-norm condition estimate of `∂H/∂x` at the endpoint.
    pub condition: f64,
    /// Winding number `c` of the Cauchy endgame (1 for nonsingular endpoints).
    pub winding_number: usize,
    /// Number of paths of the run ending at the same finite point (set by `solve`).
    pub multiplicity: usize,
    /// Accepted plus rejected steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected_steps: usize,
    /// Whether double-double refinement was switched on along the path.
    pub used_extended_precision: bool,
    /// The value of `t` at the last accepted point (`1` for a finished path; for a
    /// failed one, where it stopped, possibly on an endgame loop around `t = 1`).
    #[serde(default)]
    pub last_t: C64,
    /// Whether the endgame put the path at infinity after it stalled (its steps fell
    /// below the resolution of `t`, or ran out) on the evidence of its growth alone,
    /// rather than by a test that settled it.
    #[serde(default)]
    pub stalled_at_infinity: bool,
}

impl PathResult {
    /// Records `root`, a nonsingular root Newton's method refined on the target system
    /// from another route than this path (a projective chart, a conjugate), as this
    /// path's endpoint: status, point, residual and condition, winding number 1.
    pub(crate) fn record_nonsingular_root(&mut self, root: &crate::homotopy::refine::Refinement) {
        self.status = PathStatus::Nonsingular;
        self.solution.clone_from(&root.point);
        self.residual = root.residual;
        self.condition = root.condition;
        self.winding_number = 1;
    }

    /// Whether every coordinate is real up to `tolerance · (1 + ‖x‖∞)`.
    pub fn is_real(&self, tolerance: f64) -> bool {
        let scale = 1.0 + max_norm(&self.solution);
        self.solution
            .iter()
            .all(|v| v.im.abs() <= tolerance * scale)
    }
}

/// Newton updates of [`Tracker::correct_at`].
pub const CORRECT_AT_ITERATIONS: usize = 8;

/// A finite endpoint is at infinity ([`Homotopy::homogenizing_variable`]) when its
/// homogenising coordinate is at most this, relative to `1 + ‖x‖∞`, and the endpoint
/// is singular (condition above `singular_condition`, or reached with winding); a
/// nonsingular endpoint only when that coordinate is at most [`HOMOGENEOUS_ZERO_REGULAR`].
///
/// For the Fritz John form of the Lagrange conditions (`λ₀` the multiplier of the
/// objective) the paths that end on the Fritz John points (`λ₀ = 0`: singular points
/// of the constraint set, a positive-dimensional set of the chart system) converge
/// slowly and stop with `|λ₀|` of `10⁻¹¹ … 10⁻⁹` and condition numbers of `10¹²` and
/// more; a singular endpoint that close is a point within about `|λ₀|` (relative) of
/// a singular point of the constraint set either way, whose distance the
/// singular-point sub-problems bound.
pub const HOMOGENEOUS_ZERO: f64 = 1e-8;

/// Extended-precision Newton iterations of the test that a finite endpoint with a
/// small homogenising coordinate is off the hyperplane at infinity
/// (`Tracker::hyperplane_test`). On the `bars/rigid` critical points of a
/// design with two base anchors 10⁻⁴ apart (`λ₀` down to 2·10⁻⁹, condition up to
/// 6·10¹²) the corrections fell below 10⁻¹⁶ within two iterations; at the Fritz John
/// endpoints of the built-in example's `rigid/rigid` seed they halve at each step.
pub const OFF_HYPERPLANE_ITERATIONS: usize = 6;

/// Relative size of a correction at which that test has converged.
pub const OFF_HYPERPLANE_CONVERGED: f64 = 1e-14;

/// Largest relative change of the homogenising coordinate during that test for it to
/// count as stable.
pub const OFF_HYPERPLANE_STABLE: f64 = 1e-3;

/// Ratios of successive Newton corrections that count as linear convergence to the
/// hyperplane at infinity in that test: at a double point on it each correction is
/// about half the previous one (`1 − 1/m` at multiplicity `m`: ½, ⅔, ¾ …).
pub const TO_HYPERPLANE_RATIOS: std::ops::RangeInclusive<f64> = 0.3..=0.9;

/// Where extended-precision Newton's method takes a finite endpoint with a small
/// homogenising coordinate (`Tracker::hyperplane_test`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum HyperplaneTest {
    /// Quadratic convergence to a point whose homogenising coordinate is stable and
    /// not zero: a finite (ill-conditioned) solution.
    Off,
    /// Linear convergence, the homogenising coordinate shrinking with the
    /// corrections (or quadratic convergence to a zero one): a point at infinity.
    On,
    /// Neither: the corrections stagnate or jump.
    Undecided,
}

/// See [`HOMOGENEOUS_ZERO`]: the bound for a nonsingular endpoint (a regular solution
/// of the chart system on the hyperplane at infinity).
pub const HOMOGENEOUS_ZERO_REGULAR: f64 = 1e-12;

/// Double-double Newton updates [`Tracker::correct_at`] may add once double precision
/// stagnates above its tolerance.
pub const CORRECT_AT_EXTENDED_ITERATIONS: usize = 4;

/// [`Tracker::correct_at`] goes on in double-double when double-precision Newton
/// stagnates after a last contracting update below this (relative to `1 + ‖x‖∞`).
pub const CORRECT_AT_EXTENDED_START: f64 = 1e-4;

/// Largest ratio of successive Newton updates in [`Tracker::correct_at`].
pub const CORRECT_AT_CONTRACTION: f64 = 1.0;

/// Coordinates smaller than this do not veto the endgame's direct finish by a negative
/// valuation (see [`Tracker::endgame`]); the divergence test itself only looks at
/// coordinates of modulus ≥ 1.
const DIRECT_FINISH_FLOOR: f64 = 0.1;

/// Largest rise (relative) of a grown coordinate's valuation between two radii that
/// still counts as stable; any fall does (see [`MIN_COORDINATE_GROWTH`]).
const GROWN_VALUATION_DRIFT: f64 = 0.05;

/// Largest distance of a loop valuation from a multiple of `1/c` that still counts as
/// a Puiseux exponent ([`Tracker::puiseux_exponents_at_infinity`]); valuations from
/// loops outside the disc of convergence, or of a coordinate with a zero inside the
/// loop, are off by 10⁻² and more.
const PUISEUX_EXPONENT_TOLERANCE: f64 = 1e-4;

/// Below this radius `s = 1 − t` a stable negative valuation classifies a path as
/// diverging without the growth of [`MIN_COORDINATE_GROWTH`]: `t = 1 − s` is resolved
/// to `ε/s` relative, and the endgame cannot go much deeper.
const DEEP_RADIUS: f64 = 1e-8;

/// A stable negative valuation classifies a path as diverging only once the coordinate
/// has grown by this factor since the start of the endgame (the criterion of
/// Breiding & Timme's endgame, "HomotopyContinuation.jl: a package for homotopy
/// continuation in Julia", 2018). A path to a large finite root `x* ~ a/ε` looks like
/// `a/(s + ε)` — valuation −1, stable — until `s` reaches `ε`; badly scaled systems
/// (chemical equilibria with roots of modulus 10⁴ reached from 10² at `s = 0.1`) have
/// such roots.
const MIN_COORDINATE_GROWTH: f64 = 100.0;

/// Why the tracker stopped before the end of a route (one segment or a chain of them).
/// The tracking layer reports only three outcomes: the route's end was reached (`Ok`),
/// the path diverged (its norm passed [`EndgameOptions::at_infinity_norm`]), or the
/// tracker failed. Whether a divergence is a solution at infinity — rather than a pole
/// passed on the way — is not the tracker's to say: only the endgame
/// ([`Tracker::track`]'s last stretch to `t = 1`) classifies a path as
/// [`PathStatus::AtInfinity`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RouteStop {
    Failed(FailureReason),
    Diverged,
}

/// Accepted steps in a row shorter than [`MIN_ABSOLUTE_STEP`] after which a path is
/// failed with [`FailureReason::StepSizeTooSmall`] (it no longer advances in `t`).
const CRAWL_STEPS: usize = 200;

/// A path tracker bound to one homotopy, owning all per-thread buffers (allocated once
/// in [`Tracker::new`]; tracking allocates only the returned [`PathResult`]).
pub struct Tracker<'h, H: Homotopy + ?Sized> {
    homotopy: &'h H,
    options: TrackerOptions,
    n: usize,
    eval: Evaluation,
    x: Vec<C64>,
    x_predicted: Vec<C64>,
    x_stage: Vec<C64>,
    k1: Vec<C64>,
    k2: Vec<C64>,
    k3: Vec<C64>,
    k4: Vec<C64>,
    x_saved: Vec<C64>,
    x_checkpoint: Vec<C64>,
    /// The endgame's estimates and valuations ([`endgame::EndgameState`]).
    state: endgame::EndgameState,
    /// The last points of the segment for the predictor of stiff stretches
    /// ([`hermite::HermiteHistory`]).
    hermite: hermite::HermiteHistory,
    step: f64,
    steps: usize,
    /// Steps after which [`Tracker::track_segment`] stops with
    /// [`FailureReason::TooManySteps`]: `max_steps`, lowered for the duration of one
    /// Cauchy loop to its own budget.
    step_limit: usize,
    /// Accepted steps in a row shorter than [`MIN_ABSOLUTE_STEP`] (see [`CRAWL_STEPS`]).
    crawled: usize,
    /// Smallest ratio of successive Newton updates of the last [`Tracker::refine_at`]
    /// (infinite if it made fewer than two in one precision).
    refinement_contraction: f64,
    rejected: usize,
    /// Double or double-double arithmetic, and the counters that switch between them.
    precision: Precision,
    winding: usize,
    /// `eval.lu` holds J at (≈ x, t) of the current point (set after an accepted step).
    factorization_current: bool,
    /// `t` of the last accepted point.
    t: C64,
}

impl<'h, H: Homotopy + ?Sized> Tracker<'h, H> {
    /// Tracker for `homotopy` with `options`.
    pub fn new(homotopy: &'h H, options: TrackerOptions) -> Self {
        let n = homotopy.dimension();
        let z = C64::new(0.0, 0.0);
        Tracker {
            homotopy,
            eval: Evaluation::new(
                n,
                homotopy.workspace_len(),
                options.precision.extended_residual,
            ),
            n,
            x: vec![z; n],
            x_predicted: vec![z; n],
            x_stage: vec![z; n],
            k1: vec![z; n],
            k2: vec![z; n],
            k3: vec![z; n],
            k4: vec![z; n],
            x_saved: vec![z; n],
            x_checkpoint: vec![z; n],
            state: endgame::EndgameState::new(n),
            hermite: hermite::HermiteHistory::new(n),
            step: 0.0,
            steps: 0,
            step_limit: options.step.max_steps,
            crawled: 0,
            refinement_contraction: f64::INFINITY,
            rejected: 0,
            precision: Precision::default(),
            winding: 1,
            factorization_current: false,
            t: C64::new(0.0, 0.0),
            options,
        }
    }

    /// The options in use.
    pub fn options(&self) -> &TrackerOptions {
        &self.options
    }

    pub(super) fn reset(&mut self, start: &[C64], t0: f64) {
        self.x.copy_from_slice(start);
        self.t = C64::new(t0, 0.0);
        self.step = self.options.step.initial_step;
        self.steps = 0;
        self.step_limit = self.options.step.max_steps;
        self.crawled = 0;
        self.rejected = 0;
        self.precision = Precision::default();
        self.eval.extended = false;
        self.winding = 1;
        self.state.gave_up_at_infinity = false;
    }

    /// Tracks `start` (a solution of `H(x, 0) = 0`) to `t = 1`, runs the endgame and
    /// classifies and refines the endpoint.
    pub fn track(&mut self, start: &[C64], path_index: usize) -> PathResult {
        self.reset(start, 0.0);
        let endgame_start = {
            let last = self.homotopy.breakpoints().last().copied().unwrap_or(0.0);
            self.options.endgame.endgame_start.min(0.5 * (1.0 - last))
        };
        let status = match self.track_real_interval(0.0, 1.0 - endgame_start) {
            Ok(()) => self.endgame(endgame_start),
            Err(RouteStop::Diverged) => PathStatus::Failed(FailureReason::DivergedBeforeEndgame),
            Err(RouteStop::Failed(reason)) => PathStatus::Failed(reason),
        };
        self.finish(path_index, status)
    }

    /// Like [`Tracker::track`], but along straight segments in the complex `t`-plane
    /// through the points `via` (then on to the endgame zone): e.g. a small arc around
    /// the point where the real path passed too close to infinity. The homotopy must be
    /// analytic along the route (`via` off the real axis only where no breakpoint lies).
    pub fn track_via(&mut self, start: &[C64], via: &[C64], path_index: usize) -> PathResult {
        self.reset(start, 0.0);
        let endgame_start = {
            let last = self.homotopy.breakpoints().last().copied().unwrap_or(0.0);
            self.options.endgame.endgame_start.min(0.5 * (1.0 - last))
        };
        let end = C64::new(1.0 - endgame_start, 0.0);
        let mut from = C64::new(0.0, 0.0);
        let mut outcome = Ok(());
        for &to in via.iter().chain(std::iter::once(&end)) {
            outcome = self.track_segment(from, to);
            if outcome.is_err() {
                break;
            }
            from = to;
        }
        let status = match outcome {
            Ok(()) => self.endgame(endgame_start),
            Err(RouteStop::Diverged) => PathStatus::Failed(FailureReason::DivergedBeforeEndgame),
            Err(RouteStop::Failed(reason)) => PathStatus::Failed(reason),
        };
        self.finish(path_index, status)
    }

    /// Tracks `start` from `t0` to `t1` (real, either direction) without endgame, e.g.
    /// a monodromy loop or a parameter homotopy between generic parameters. The
    /// endpoint is Newton-refined and returned as `Nonsingular` (or `Singular` if its
    /// condition exceeds `singular_condition`). A path whose norm passes
    /// `at_infinity_norm` on the way is `Failed(DivergedOnRoute)`, never `AtInfinity`:
    /// without an endgame a pole passed on the way cannot be told from a root at
    /// infinity of the end system.
    pub fn track_between(
        &mut self,
        start: &[C64],
        t0: f64,
        t1: f64,
        path_index: usize,
    ) -> PathResult {
        self.reset(start, t0);
        let status = match self.track_real_interval(t0, t1) {
            Ok(()) => {
                let (converged, _) = self.refine_at(C64::new(t1, 0.0));
                let condition = self.condition_at(C64::new(t1, 0.0));
                if converged && condition < self.options.endgame.singular_condition {
                    PathStatus::Nonsingular
                } else {
                    PathStatus::Singular
                }
            }
            Err(RouteStop::Diverged) => PathStatus::Failed(FailureReason::DivergedOnRoute),
            Err(RouteStop::Failed(reason)) => PathStatus::Failed(reason),
        };
        self.finish_at(path_index, status, C64::new(t1, 0.0))
    }

    fn finish(&mut self, path_index: usize, status: PathStatus) -> PathResult {
        self.finish_at(path_index, status, C64::new(1.0, 0.0))
    }

    fn finish_at(&mut self, path_index: usize, status: PathStatus, t: C64) -> PathResult {
        let (residual, condition) = if self.x.iter().all(|v| v.re.is_finite() && v.im.is_finite()) {
            self.homotopy
                .evaluate(&self.x, t, &mut self.eval.work, &mut self.eval.h);
            (max_norm(&self.eval.h), self.condition_at(t))
        } else {
            (f64::INFINITY, f64::INFINITY)
        };
        let status = if self.homogenizing_coordinate_vanishes(status) {
            match self.hyperplane_test(t) {
                HyperplaneTest::Off => status,
                HyperplaneTest::On => PathStatus::AtInfinity,
                HyperplaneTest::Undecided => PathStatus::Failed(FailureReason::HyperplaneUndecided),
            }
        } else {
            status
        };
        self.result(path_index, status, residual, condition)
    }

    /// Whether a finite endpoint with `status` lies at infinity of the affine system:
    /// its homogenising coordinate ([`Homotopy::homogenizing_variable`]) is zero to
    /// within [`HOMOGENEOUS_ZERO`] (singular endpoints) or
    /// [`HOMOGENEOUS_ZERO_REGULAR`] (nonsingular ones) times `1 + ‖x‖∞`.
    fn homogenizing_coordinate_vanishes(&self, status: PathStatus) -> bool {
        let tolerance = match status {
            PathStatus::Nonsingular => HOMOGENEOUS_ZERO_REGULAR,
            _ if status.is_finite() => HOMOGENEOUS_ZERO,
            _ => return false,
        };
        self.homotopy
            .homogenizing_variable()
            .and_then(|i| self.x.get(i))
            .is_some_and(|h| h.norm() <= tolerance * (1.0 + max_norm(&self.x)))
    }

    /// Where Newton's method in extended precision at `t` takes a finite endpoint with
    /// a small homogenising coordinate ([`HyperplaneTest`]). A true (ill-conditioned)
    /// solution of the affine system converges quadratically and keeps its
    /// homogenising coordinate: [`HyperplaneTest::Off`]. At a point at infinity reached
    /// in the chart (in the Fritz John form of the Lagrange conditions, a singular
    /// point of the constraint set) the iteration converges only linearly, each
    /// correction a fixed fraction (about half) of the previous one, and the
    /// homogenising coordinate shrinks with it towards 0 (Griewank and Osborne,
    /// *Analysis of Newton's method at irregular singularities*, SIAM J. Numer. Anal.
    /// 20, 1983): [`HyperplaneTest::On`]. Anything else — corrections that stagnate
    /// or jump, a limit that moves the coordinate — decides nothing:
    /// [`HyperplaneTest::Undecided`], so that the path is reported rather than
    /// dropped at infinity. The current point is left unchanged.
    fn hyperplane_test(&mut self, t: C64) -> HyperplaneTest {
        let Some(h) = self.homotopy.homogenizing_variable() else {
            return HyperplaneTest::Undecided;
        };
        let before = self.x[h];
        self.x_saved.copy_from_slice(&self.x);
        let mut converged = false;
        let mut corrections = [0.0f64; OFF_HYPERPLANE_ITERATIONS];
        let mut taken = 0;
        for correction in corrections.iter_mut() {
            match self.eval.newton(self.homotopy, &mut self.x, t, true) {
                NewtonUpdate::Singular => break,
                NewtonUpdate::Step(norm) => {
                    *correction = norm;
                    taken += 1;
                    if norm <= OFF_HYPERPLANE_CONVERGED * (1.0 + max_norm(&self.x)) {
                        converged = true;
                        break;
                    }
                }
            }
        }
        let after = self.x[h];
        let scale = 1.0 + max_norm(&self.x);
        self.x.copy_from_slice(&self.x_saved);
        if converged {
            return if after.norm() <= HOMOGENEOUS_ZERO_REGULAR * scale {
                HyperplaneTest::On
            } else if (after - before).norm() <= OFF_HYPERPLANE_STABLE * after.norm() {
                HyperplaneTest::Off
            } else {
                HyperplaneTest::Undecided
            };
        }
        // Linear: the last three ratios of successive corrections in
        // `TO_HYPERPLANE_RATIOS`, and the coordinate at most half what it was.
        let linear = taken >= 4
            && corrections[taken - 4..taken]
                .windows(2)
                .all(|w| w[0] > 0.0 && TO_HYPERPLANE_RATIOS.contains(&(w[1] / w[0])));
        if linear && after.norm() <= 0.5 * before.norm() {
            HyperplaneTest::On
        } else {
            HyperplaneTest::Undecided
        }
    }

    /// The [`PathResult`] at the current point.
    fn result(
        &self,
        path_index: usize,
        status: PathStatus,
        residual: f64,
        condition: f64,
    ) -> PathResult {
        PathResult {
            path_index,
            solution: self.x.clone(),
            status,
            residual,
            condition,
            winding_number: match status {
                PathStatus::Nonsingular => 1,
                _ => self.winding,
            },
            multiplicity: 1,
            steps: self.steps,
            rejected_steps: self.rejected,
            used_extended_precision: self.precision.used,
            last_t: self.t,
            stalled_at_infinity: status == PathStatus::AtInfinity && self.state.gave_up_at_infinity,
        }
    }

    /// The path's velocity `ẋ = −J⁻¹ ∂H/∂t` at `(x, t)`, in double precision (the
    /// tracker leaves extended mode; the next route resets it anyway); `None` where the
    /// Jacobian is singular or the velocity not finite.
    pub fn velocity_at(&mut self, x: &[C64], t: C64) -> Option<&[C64]> {
        self.precision.extended = false;
        self.eval.extended = false;
        self.eval
            .velocity(self.homotopy, x, t, C64::new(1.0, 0.0), &mut self.k1)
            .then_some(self.k1.as_slice())
    }

    /// Tracks along the real interval `[t0, t1]`, stopping at the homotopy's breakpoints.
    fn track_real_interval(&mut self, t0: f64, t1: f64) -> Result<(), RouteStop> {
        let mut a = t0;
        let forward = t1 >= t0;
        let breakpoints: Vec<f64> = {
            let mut b: Vec<f64> = self
                .homotopy
                .breakpoints()
                .iter()
                .copied()
                .filter(|&b| (b - t0) * (t1 - b) > 0.0)
                .collect();
            if !forward {
                b.reverse();
            }
            b
        };
        for b in breakpoints.into_iter().chain(std::iter::once(t1)) {
            self.track_segment(C64::new(a, 0.0), C64::new(b, 0.0))?;
            a = b;
        }
        Ok(())
    }

    /// Tracks `self.x` along the straight segment from `ta` to `tb` in the complex plane.
    fn track_segment(&mut self, ta: C64, tb: C64) -> Result<(), RouteStop> {
        let dt = tb - ta;
        let length = dt.norm();
        if length == 0.0 {
            return Ok(());
        }
        let mut u = 0.0f64;
        self.factorization_current = false;
        self.hermite
            .start_segment(self.options.step.hermite_on_stiff_stretches);
        let floor = step_floor(&self.options, length);
        while u < 1.0 {
            if self.steps >= self.step_limit || self.precision.budget_spent(&self.options) {
                return Err(RouteStop::Failed(FailureReason::TooManySteps));
            }
            let mut h = step_fraction(self.step, self.options.step.max_step, length, u);
            let t = ta + dt * u;
            let t_mid = ta + dt * (u + 0.5 * h);
            let t_new = ta + dt * (u + h);
            self.steps += 1;
            self.precision.count_step();
            let accepted = if self.predict(t, t_mid, t_new, dt, h).is_some() {
                self.correct(t_new)
            } else {
                None
            };
            match accepted {
                Some(first_update) => {
                    self.x.copy_from_slice(&self.x_predicted);
                    self.factorization_current = true;
                    u = if h >= 1.0 - u { 1.0 } else { u + h };
                    self.t = ta + dt * u;
                    let scale = 1.0 + max_norm(&self.x);
                    if scale > self.options.endgame.at_infinity_norm {
                        return Err(RouteStop::Diverged);
                    }
                    let factor =
                        step_factor(first_update / scale, self.options.step.prediction_tolerance);
                    self.step = (h * length * factor).min(self.options.step.max_step);
                    let distance = (C64::new(1.0, 0.0) - self.t).norm();
                    self.hermite.accepted(factor, (self.step, distance));
                    // Below [`MIN_ABSOLUTE_STEP`] `t` hardly moves near 1 (its spacing
                    // there is 1.1e-16): accepted steps of 1e-17 at t = 1 − 5e-8 once
                    // crawled on for 5,000 steps towards a singular endpoint far out. A
                    // few such steps are a passing near-singularity; CRAWL_STEPS in a
                    // row are a path that no longer advances.
                    self.crawled = if self.step < MIN_ABSOLUTE_STEP {
                        self.crawled + 1
                    } else {
                        0
                    };
                    if u < 1.0 && self.crawled >= CRAWL_STEPS {
                        return Err(RouteStop::Failed(FailureReason::StepSizeTooSmall));
                    }
                    if self.options.endgame.growth_before_divergence
                        && u < 1.0
                        && self.step < floor * length
                    {
                        // Accepted steps whose predictor error stays far above the
                        // tolerance shrink the step as surely as rejections do (noise of
                        // the velocities at a large, ill-conditioned point); below the
                        // floor `u + h` would no longer advance.
                        if self.precision.extended {
                            return Err(RouteStop::Failed(FailureReason::StepSizeTooSmall));
                        }
                        self.switch_to_extended();
                        self.step *= 4.0;
                    }
                    // Back to double precision once the ill-conditioned stretch is
                    // behind (κ·ε ≤ 1e-10): switching back inside it costs rejected
                    // steps and an 8-fold smaller step each time.
                    if self.precision.accepted(&self.options)
                        && self.eval.condition_estimate() <= RETURN_TO_DOUBLE_CONDITION
                    {
                        self.precision.extended = false;
                        self.eval.extended = false;
                    }
                }
                None => {
                    self.rejected += 1;
                    h *= 0.5;
                    if self.precision.rejected(&self.options)
                        && self.eval.condition_estimate() > RETURN_TO_DOUBLE_CONDITION
                    {
                        // Only where double precision is the likely culprit: below
                        // κ = 10⁶ Newton's updates are accurate to κ·ε ≈ 10⁻¹⁰, under
                        // the corrector tolerance, and rejections mean a step too long.
                        self.switch_to_extended();
                    }
                    if h < floor {
                        if !self.precision.extended {
                            self.switch_to_extended();
                            h *= 4.0;
                        } else {
                            let bad = self
                                .x
                                .iter()
                                .any(|v| !(v.re.is_finite() && v.im.is_finite()));
                            return Err(RouteStop::Failed(if bad {
                                FailureReason::NonFiniteValue
                            } else {
                                FailureReason::StepSizeTooSmall
                            }));
                        }
                    }
                    self.step = h * length;
                }
            }
        }
        Ok(())
    }

    /// Switches to extended (double-double) precision ([`precision`]).
    fn switch_to_extended(&mut self) {
        self.precision.switch_to_extended();
        self.eval.extended = true;
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    use crate::homotopy::ParameterHomotopy;
    use crate::system::{CompiledSystem, Expr, System};

    /// `q·x − 1 = 0`, one unknown `x` and one parameter `q`.
    pub(crate) fn reciprocal_family() -> CompiledSystem {
        let (x, q) = (Expr::variable("x"), Expr::parameter("q"));
        System::new(["x"], ["q"], vec![q * x - Expr::one()])
            .unwrap()
            .compile()
    }

    /// `x² − q = 0`, one unknown `x` and one parameter `q`.
    pub(crate) fn square_root_family() -> CompiledSystem {
        let (x, q) = (Expr::variable("x"), Expr::parameter("q"));
        System::new(["x"], ["q"], vec![x.clone() * x - q])
            .unwrap()
            .compile()
    }

    /// `q·x³ − x − 1 = 0`, one unknown `x` and one parameter `q`.
    fn cubic_family() -> CompiledSystem {
        let (x, q) = (Expr::variable("x"), Expr::parameter("q"));
        System::new(
            ["x"],
            ["q"],
            vec![q * x.clone() * x.clone() * x.clone() - x - Expr::one()],
        )
        .unwrap()
        .compile()
    }

    fn real_segment(
        system: &CompiledSystem,
        from: f64,
        to: f64,
    ) -> ParameterHomotopy<'_, CompiledSystem> {
        ParameterHomotopy::segment(system, &[C64::new(from, 0.0)], &[C64::new(to, 0.0)])
    }

    /// `H(x, t) = (p − t)·x − 1` ([`reciprocal_family`] with `q` from `p` to
    /// `p − 1`): the path `x(t) = 1/(p − t)` from `x(0) = 1/p` has a pole at `t = p`
    /// (a divergence mid-route for `p < 1`, a root at infinity of `H(·, 1)` for
    /// `p = 1`).
    pub(crate) fn pole(system: &CompiledSystem, p: f64) -> ParameterHomotopy<'_, CompiledSystem> {
        real_segment(system, p, p - 1.0)
    }

    /// `H(x, t) = x² − (1 + t)` ([`square_root_family`] with `q` from 1 to 2): the
    /// paths `x(t) = ±√(1 + t)`.
    pub(crate) fn square(system: &CompiledSystem) -> ParameterHomotopy<'_, CompiledSystem> {
        real_segment(system, 1.0, 2.0)
    }

    /// Runs `test` on a tracker with the default options for [`square`], reset to
    /// `x = start` at `t = t0`.
    pub(crate) fn on_square<R>(
        start: f64,
        t0: f64,
        test: impl FnOnce(&mut Tracker<'_, ParameterHomotopy<'_, CompiledSystem>>) -> R,
    ) -> R {
        let system = square_root_family();
        let homotopy = square(&system);
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        tracker.reset(&[C64::new(start, 0.0)], t0);
        test(&mut tracker)
    }

    /// The path of [`pole`] from `x(0) = 1/p`, tracked with `options` to `t = 1`
    /// with the endgame ([`Tracker::track`]) or without ([`Tracker::track_between`]).
    fn along_pole(p: f64, options: TrackerOptions, endgame: bool) -> PathResult {
        let system = reciprocal_family();
        let homotopy = pole(&system, p);
        let mut tracker = Tracker::new(&homotopy, options);
        let start = [C64::new(1.0 / p, 0.0)];
        if endgame {
            tracker.track(&start, 0)
        } else {
            tracker.track_between(&start, 0.0, 1.0, 0)
        }
    }

    /// Steps of at most 0.01 and divergence at `‖x‖ > 10`: the tracker lands within
    /// `|t − p| < 0.1` of a pole instead of stepping across it (a simple pole of a
    /// rational path is no obstacle to the RK4 predictor).
    fn near_pole_options() -> TrackerOptions {
        let mut options = TrackerOptions::default();
        options.step.initial_step = 0.01;
        options.step.max_step = 0.01;
        options.endgame.at_infinity_norm = 10.0;
        options
    }

    /// `(λ₀ − q)·(λ₀ − q − δ) = 0` and the chart `λ₀ + λ₁ = 1`, `λ₀` declared the
    /// homogenising unknown: at `q = 10⁻⁹`, `δ = 10⁻¹¹` two roots with `λ₀ ≈ 10⁻⁹`,
    /// simple but 10⁻¹¹ apart (condition ~10¹¹, below the singular bound's `λ₀`), off
    /// the hyperplane at infinity: extended-precision Newton converges quadratically
    /// and leaves `λ₀` where it is. `λ₀² − q·λ₀ = 0` at `q = 0` instead has the double
    /// root `λ₀ = 0` on the hyperplane: from `λ₀ = 10⁻⁹` Newton converges linearly,
    /// halving `λ₀` at each step. `w³ − 2w + 2 = 0` in `w = λ₀/s`, `s = 10⁻⁹`, has a
    /// finite real root (`w ≈ −1.77`) but Newton's method from `w = 1` cycles between
    /// `w = 1` and `w = 0`: neither shown finite nor at infinity, the path fails (the
    /// rule before called every non-converging endpoint at infinity).
    #[test]
    fn a_small_homogenising_coordinate_is_at_infinity_only_when_newton_sends_it_to_zero() {
        let (l0, l1, q) = (
            Expr::variable("lambda0"),
            Expr::variable("lambda1"),
            Expr::parameter("q"),
        );
        let delta = 1e-11;
        let separated = (l0.clone() - q.clone())
            * (l0.clone() - q.clone() - Expr::constant(C64::new(delta, 0.0)));
        let double = l0.clone() * l0.clone() - q * l0.clone();
        let s: f64 = 1e-9;
        let cycling =
            Expr::constant(C64::new(s.powi(-3), 0.0)) * l0.clone() * l0.clone() * l0.clone()
                - Expr::constant(C64::new(2.0 / s, 0.0)) * l0.clone()
                + Expr::constant(C64::new(2.0, 0.0));
        let chart = l0 + l1 - Expr::one();
        for (equation, q, expected) in [
            (separated, 1e-9, HyperplaneTest::Off),
            (double, 0.0, HyperplaneTest::On),
            (cycling, 0.0, HyperplaneTest::Undecided),
        ] {
            let system = System::new(["lambda0", "lambda1"], ["q"], vec![equation, chart.clone()])
                .and_then(|s| s.with_homogenizing_variable("lambda0"))
                .unwrap()
                .compile();
            let homotopy = real_segment(&system, q, q);
            let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
            let start = [C64::new(1e-9, 0.0), C64::new(1.0 - 1e-9, 0.0)];
            tracker.reset(&start, 1.0);
            assert!(tracker.homogenizing_coordinate_vanishes(PathStatus::Singular));
            let t = C64::new(1.0, 0.0);
            assert_eq!(tracker.hyperplane_test(t), expected);
            assert_eq!(
                tracker.x[0], start[0],
                "the current point is left unchanged"
            );
            let status = tracker.finish_at(0, PathStatus::Singular, t).status;
            let expected = match expected {
                HyperplaneTest::Off => PathStatus::Singular,
                HyperplaneTest::On => PathStatus::AtInfinity,
                HyperplaneTest::Undecided => PathStatus::Failed(FailureReason::HyperplaneUndecided),
            };
            assert_eq!(status, expected);
        }
    }

    /// A pole at `t = ½` is a divergence on the route, a failure whether the route
    /// ends with the endgame or not, never a point at infinity.
    #[test]
    fn a_divergence_on_the_route_is_a_failure_not_a_point_at_infinity() {
        for (endgame, reason) in [
            (false, FailureReason::DivergedOnRoute),
            (true, FailureReason::DivergedBeforeEndgame),
        ] {
            let result = along_pole(0.5, near_pole_options(), endgame);
            assert_eq!(result.status, PathStatus::Failed(reason), "{result:?}");
            assert!(result.last_t.re < 0.5, "{result:?}");
        }
    }

    /// `H(x, t) = (1 − t)·x³ − x − 1`: the real root of `x³ − x − 1` goes to infinity
    /// on a Puiseux cycle of winding number 2, `x ≈ s^{−1/2}(1 + s^{1/2}/2 + …)` with
    /// `s = 1 − t`. The mean of `ln|x|` over the Cauchy loops at `s = 0.025` and
    /// `0.00625`, well inside the disc of convergence (the branch point of the other two
    /// roots is at `s ≈ 0.15`), gives the exponent −1/2 (Jensen's formula) to 10⁻⁵, which
    /// [`Tracker::puiseux_exponents_at_infinity`] accepts; an exponent off a multiple of
    /// `1/c` by 10⁻³, or a non-negative one, it rejects.
    #[test]
    fn a_puiseux_cycle_to_infinity_is_recognised_from_two_cauchy_loops() {
        let cubic = cubic_family();
        let homotopy = real_segment(&cubic, 1.0, 0.0);
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        tracker.reset(&[C64::new(1.324_717_957_244_746, 0.0)], 0.0);
        let mut log_means = Vec::new();
        let mut t = C64::new(0.0, 0.0);
        for s in [0.025, 0.006_25] {
            let end = C64::new(1.0 - s, 0.0);
            assert!(tracker.track_segment(t, end).is_ok());
            t = end;
            assert_eq!(tracker.cauchy_loop(s).ok(), Some(2));
            log_means.push(tracker.state.log_mean[0]);
        }
        let valuation = (log_means[1] - log_means[0]) / 0.25f64.ln();
        assert!((valuation + 0.5).abs() < 1e-5, "{valuation}");
        tracker.state.loop_valuations[0] = valuation;
        // |x| ≈ 13 here: not grown by MIN_COORDINATE_GROWTH from an endgame that began
        // at |x| ≤ 1, so no evidence yet (a large finite root looks the same) …
        assert!(!tracker.puiseux_exponents_at_infinity(2, 0.006_25));
        // … and evidence from an endgame that began at |x| = 0.1 (origin max(1, ·)
        // made 0.1 here to stand for that growth).
        tracker.state.endgame_origin[0] = 0.1;
        assert!(tracker.puiseux_exponents_at_infinity(2, 0.006_25));
        tracker.state.loop_valuations[0] = -0.5 + 1e-3;
        assert!(!tracker.puiseux_exponents_at_infinity(2, 0.006_25));
        tracker.state.loop_valuations[0] = 0.5;
        assert!(!tracker.puiseux_exponents_at_infinity(2, 0.006_25));
    }

    /// The direct finish's step budget: on [`square`] from `t = 0.9` to 1 with steps
    /// of at most `10⁻³` (100 steps) it arrives; with at most `2·10⁻⁴` (500 steps)
    /// it stops after [`endgame::DIRECT_FINISH_STEPS`] more steps, short of `t = 1`.
    #[test]
    fn a_segment_within_a_step_budget_stops_at_the_budget() {
        for (max_step, arrives) in [(1e-3, true), (2e-4, false)] {
            let system = square_root_family();
            let homotopy = square(&system);
            let mut options = TrackerOptions::default();
            options.step.max_step = max_step;
            let mut tracker = Tracker::new(&homotopy, options);
            let t0 = C64::new(0.9, 0.0);
            tracker.reset(&[C64::new(1.9f64.sqrt(), 0.0)], 0.9);
            let reached =
                tracker.segment_within(t0, C64::new(1.0, 0.0), endgame::DIRECT_FINISH_STEPS);
            assert_eq!(reached, arrives, "{} steps", tracker.steps);
            if !arrives {
                assert_eq!(tracker.steps, endgame::DIRECT_FINISH_STEPS);
                assert!(tracker.t.re < 1.0);
            }
            // The path's own limit is back.
            assert_eq!(tracker.step_limit, tracker.options.step.max_steps);
        }
    }

    /// Steps capped at 10⁻¹⁶ (below [`MIN_ABSOLUTE_STEP`]) no longer advance `t`:
    /// after [`CRAWL_STEPS`] of them the path fails with
    /// [`FailureReason::StepSizeTooSmall`] instead of spending its whole budget.
    #[test]
    fn a_path_whose_accepted_steps_no_longer_advance_t_fails_early() {
        let mut options = TrackerOptions::default();
        options.step.max_step = 1e-16;
        let system = square_root_family();
        let homotopy = square(&system);
        let mut tracker = Tracker::new(&homotopy, options);
        tracker.reset(&[C64::new(1.0, 0.0)], 0.0);
        let stop = tracker.track_segment(C64::new(0.0, 0.0), C64::new(0.5, 0.0));
        assert_eq!(
            stop,
            Err(RouteStop::Failed(FailureReason::StepSizeTooSmall))
        );
        assert_eq!(tracker.steps, CRAWL_STEPS);
    }

    /// One Cauchy loop at `s = 0.025` on [`cubic_family`] (`q` from 1 to 0, where two
    /// sheets form a cycle) with `options`, from the real root of `x³ − x − 1`: the
    /// loop's outcome, the point and `t` before and after it, and its steps.
    fn cubic_loop(
        options: TrackerOptions,
    ) -> (Result<usize, RouteStop>, [Vec<C64>; 2], C64, usize) {
        let cubic = cubic_family();
        let homotopy = real_segment(&cubic, 1.0, 0.0);
        let s = 0.025;
        let mut tracker = Tracker::new(&homotopy, options);
        tracker.reset(&[C64::new(1.324_717_957_244_746, 0.0)], 0.0);
        let end = C64::new(1.0 - s, 0.0);
        assert!(tracker.track_segment(C64::new(0.0, 0.0), end).is_ok());
        let (before, steps_before) = (tracker.x.clone(), tracker.steps);
        let looped = tracker.cauchy_loop(s);
        let after = tracker.x.clone();
        (
            looped,
            [before, after],
            tracker.t,
            tracker.steps - steps_before,
        )
    }

    /// A Cauchy loop that needs more than its step budget (here: steps of at most
    /// 10⁻⁴ around a circle of length 0.16 at `s = 0.025`) is abandoned: the path is
    /// back where the loop started, at `t = 1 − s`, and the endgame may go on to a
    /// smaller radius. The same loop with its usual steps closes after two turns.
    #[test]
    fn a_cauchy_loop_over_its_step_budget_returns_to_where_it_started() {
        let (closed, ..) = cubic_loop(TrackerOptions::default());
        assert_eq!(closed.ok(), Some(2));
        let mut options = TrackerOptions::default();
        options.step.max_step = 1e-4;
        let (looped, [before, after], t, steps) = cubic_loop(options.clone());
        assert_eq!(
            looped,
            Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
        );
        assert_eq!((after, t), (before, C64::new(0.975, 0.0)));
        // The loop's budget was spent, not the rest of the path's.
        let budget = endgame::LOOP_STEPS_PER_SAMPLE
            * options.endgame.cauchy_samples_per_loop
            * options.endgame.max_winding_number;
        assert_eq!(steps, budget);
    }

    /// A Cauchy loop that has not closed after the largest winding number allowed
    /// (here one turn, around the two-sheet cycle of [`cubic_loop`]) ends on another
    /// path's sheet: the path goes back to where the loop started, so the endgame goes
    /// on along its own branch. Left on the other sheet, the paths of `redcyc7`
    /// (PHCpack's demo suite) ended on roots other paths had reached, and were lost as
    /// jumped paths.
    #[test]
    fn a_loop_that_does_not_close_within_its_winding_bound_returns_to_where_it_started() {
        let mut options = TrackerOptions::default();
        options.endgame.max_winding_number = 1;
        let (looped, [before, after], t, steps) = cubic_loop(options.clone());
        assert_eq!(
            looped,
            Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
        );
        // The loop was tracked (one turn, within its budget), and undone.
        let budget = endgame::LOOP_STEPS_PER_SAMPLE * options.endgame.cauchy_samples_per_loop;
        assert!(steps > 0 && steps < budget);
        assert_eq!((after, t), (before, C64::new(0.975, 0.0)));
    }

    /// A path to a large finite root: `x(t) = 1/(p − t)` with `p = 1 + 10⁻⁵` ends at
    /// `x = 10⁵`. Its valuation is that of a pole, −s/(s + 10⁻⁵), stable to 10⁻² over
    /// the radii 0.1, 0.025 and 0.006 25, where `x` has grown from 10 to 160 only: the
    /// classic power-series test called it at infinity there. It is at infinity only
    /// once grown by [`MIN_COORDINATE_GROWTH`], by which time its valuation has begun
    /// to rise, and the endgame reaches the root.
    #[test]
    fn a_large_finite_root_is_not_taken_for_a_pole() {
        let result = along_pole(1.0 + 1e-5, TrackerOptions::default(), true);
        assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
        assert!((result.solution[0] - 1e5).norm() < 1e-6, "{result:?}");
    }

    /// `x⁵ = q` with `q` from 1 to 0: the path `x = (1 − t)^{1/5}` ends at the
    /// singular root 0 with winding number 5. A loop at the endgame's first radius
    /// makes at most [`endgame::FIRST_RADIUS_MAX_WINDING`] (4) turns and gives up
    /// there, back where it started; at a smaller radius it closes after 5, and the
    /// whole endgame ends at the singular root with winding number 5.
    #[test]
    fn loops_at_the_first_radius_make_at_most_four_turns() {
        let (x, q) = (Expr::variable("x"), Expr::parameter("q"));
        let quintic = System::new(
            ["x"],
            ["q"],
            vec![x.clone() * x.clone() * x.clone() * x.clone() * x - q],
        )
        .unwrap()
        .compile();
        let homotopy = real_segment(&quintic, 1.0, 0.0);
        let s = 0.1;
        let end = C64::new(1.0 - s, 0.0);
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        tracker.reset(&[C64::new(1.0, 0.0)], 0.0);
        assert!(tracker.track_segment(C64::new(0.0, 0.0), end).is_ok());
        let before = tracker.x.clone();
        tracker.state.first_radius = s;
        assert_eq!(
            tracker.cauchy_loop(s),
            Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
        );
        assert_eq!(tracker.x, before);
        tracker.state.first_radius = 0.5;
        assert_eq!(tracker.cauchy_loop(s).ok(), Some(5));
        let result =
            Tracker::new(&homotopy, TrackerOptions::default()).track(&[C64::new(1.0, 0.0)], 0);
        assert_eq!(result.status, PathStatus::Singular, "{result:?}");
        assert_eq!(result.winding_number, 5, "{result:?}");
        assert!(result.solution[0].norm() < 1e-6, "{result:?}");
    }

    #[test]
    fn the_endgame_classifies_a_pole_at_t_one_as_at_infinity() {
        let result = along_pole(1.0, TrackerOptions::default(), true);
        assert_eq!(result.status, PathStatus::AtInfinity, "{result:?}");
    }

    #[test]
    fn a_route_without_a_pole_reaches_its_end() {
        let result = along_pole(2.0, TrackerOptions::default(), false);
        assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
        assert!((result.solution[0] - 1.0).norm() < 1e-12, "{result:?}");
    }
}

//! A second formulation of the same family — its *projective twin* — for the paths
//! the first one loses or sends to infinity.
//!
//! In the Lagrange systems of the singularity distance a critical point close to a
//! singular point of the constraint set has huge multipliers (`∇C` nearly vanishes),
//! and its path in affine multipliers runs far out like a path to infinity: the
//! endgame may classify it at infinity, or the path fails. In homogeneous multipliers
//! `[λ₀ : λ : μ]` on a random affine chart (the Fritz John form) the same point has a
//! small `λ₀` and bounded coordinates (the random affine charts of projective space
//! that Bertini tracks in: Bates, Hauenstein, Sommese and Wampler, *Numerically
//! Solving Polynomial Systems with Bertini*, SIAM 2013). Tracking such a path once more in the
//! twin is an independent route to its endpoint: a finite endpoint there is a critical
//! point the first formulation missed; an endpoint at infinity there too confirms the
//! first one's classification.

use super::{simple_endpoint, track_all};
use crate::C64;
use crate::homotopy::{
    FailureReason, HOMOGENEOUS_ZERO, ParameterPath, PathParameterHomotopy, PathResult, PathStatus,
    TrackerOptions,
};
use crate::system::{CompiledSystem, Evaluator};

/// The same family in other coordinates: a system with the same parameters and the
/// bijection between the two formulations' solutions where both are finite.
pub trait ProjectiveTwin: Sync {
    /// The twin's compiled system `G(y; p)` (same parameters as the first one).
    fn system(&self) -> &CompiledSystem;
    /// A solution `x` of the first formulation as one of the twin.
    fn lift(&self, x: &[C64]) -> Vec<C64>;
    /// A finite solution `y` of the twin as one of the first formulation (finite
    /// where the twin's homogenising coordinate is not zero, which the tracker checks
    /// before it calls a twin endpoint finite).
    fn lower(&self, y: &[C64]) -> Vec<C64>;
}

/// Steps of a path re-tracked in the twin: paths near a cluster of critical points
/// (two anchors of a rigid part 10⁻⁴ apart) need 2,300–14,000 steps there, in double
/// precision.
pub(crate) const TWIN_MAX_STEPS: usize = 15_000;

/// Paths a patient twin run re-tracks at most ([`recheck_patiently`]).
pub(crate) const PATIENT_TWIN_PATHS: usize = 4;

/// Steps of a patient twin run, each of which may be in double-double arithmetic. On
/// a base with two anchors 10⁻⁴ apart, four `rigid/rigid` seed paths end at two close
/// pairs of critical points with multipliers near 10⁵ (twin condition numbers
/// 10¹¹): they ran out of the tracker's 1,000 double-double steps within 5·10⁻⁶ of
/// `t = 1` at every seed point, and reached their endpoints in 6,100–11,100 steps.
pub(crate) const PATIENT_TWIN_STEPS: usize = 15_000;

/// Steps of the first, straight run of a lost path in the twin ([`recheck_in_twin`]):
/// on two base anchors 10⁻⁴ apart (8 scattered poses), the lost `bars/rigid` pose
/// paths it completed took 101–1,237 steps, where the endgame's Cauchy loops around
/// such ill-conditioned endpoints take thousands (`rigid/rigid` 2.3 → 1.3 s).
const STRAIGHT_FIRST_STEPS: usize = 2_000;

/// Largest condition number of an endpoint tracked straight to `t = 1` (no endgame)
/// that counts as a finite solution of the twin: a singular endpoint reached that way
/// typically has one near `1/ε ≈ 10¹⁶`. The bound does not exclude every singular
/// endpoint (one reached by two paths may then count twice); the kept count never
/// exceeds the generic one, and at most [`PATIENT_TWIN_PATHS`] paths of a seed point
/// are tracked this way. On a base 10⁻³ from a line, four
/// `rigid/rigid` critical points of the self-check's seed stage have 1.3·10¹³ in the
/// twin: with a bound of 10¹³ the endgame's run confirmed them as simple finite points
/// (2.4 s where the straight run had taken 0.14 s).
const STRAIGHT_MAX_CONDITION: f64 = 1e14;

/// Distance to `t = 1` within which a twin path that ran out of steps counts as having
/// nearly arrived ([`TwinCheck::ran_out_near_the_end`]).
const NEAR_THE_END: f64 = 1e-3;

/// What re-tracking some paths in the twin found.
pub(crate) struct TwinCheck {
    /// Finite endpoints (first formulation's coordinates), one per path that reached a
    /// simple one, in the order of the paths.
    pub finite: Vec<(usize, Vec<C64>)>,
    /// Paths whose twin endpoint is at infinity too, on the twin's hyperplane at
    /// infinity (its homogenising coordinate zero, the other coordinates finite): a
    /// classification the first formulation could not make, so an independent one.
    pub at_infinity: Vec<usize>,
    /// Paths whose twin run ran out of steps (or of double-double steps) within
    /// `10⁻³` of `t = 1`: on their way to an ill-conditioned endpoint, for
    /// [`recheck_patiently`].
    pub ran_out_near_the_end: Vec<usize>,
    /// Paths tracked.
    pub tracked: usize,
}

impl TwinCheck {
    /// Paths the twin classified: a simple finite endpoint or one at infinity.
    pub fn finite_or_at_infinity(&self) -> usize {
        self.finite.len() + self.at_infinity.len()
    }

    /// This check with `again`'s re-tracking of some of its paths taken in: what
    /// `again` classified counts as classified here.
    pub fn absorb(&mut self, again: TwinCheck) {
        let settled =
            |i: &usize| again.finite.iter().any(|(j, _)| j == i) || again.at_infinity.contains(i);
        self.ran_out_near_the_end.retain(|i| !settled(i));
        self.finite.extend(again.finite);
        self.at_infinity.extend(again.at_infinity);
        for i in again.ran_out_near_the_end {
            if !self.ran_out_near_the_end.contains(&i) {
                self.ran_out_near_the_end.push(i);
            }
        }
        self.tracked += again.tracked;
    }
}

/// Re-tracks the paths `indices` of `starts` (first formulation) in `twin` along
/// `path()`: those of `straight_first` (paths the first formulation lost, not those
/// it sent to infinity) first straight to `t = 1` with [`STRAIGHT_FIRST_STEPS`] steps,
/// where an endpoint counts as finite only below [`STRAIGHT_MAX_CONDITION`] and one
/// on the twin's hyperplane at infinity counts there; the others, and those that
/// reach neither so, with the endgame and a step budget of [`TWIN_MAX_STEPS`].
pub(crate) fn recheck_in_twin<P: ParameterPath>(
    twin: &dyn ProjectiveTwin,
    (starts, indices, straight_first): (&[Vec<C64>], &[usize], &[usize]),
    path: impl Fn() -> P,
    tracker: &TrackerOptions,
) -> TwinCheck {
    let mut check = TwinCheck {
        finite: Vec::new(),
        at_infinity: Vec::new(),
        ran_out_near_the_end: Vec::new(),
        tracked: 0,
    };
    if !straight_first.is_empty() {
        let mut quick = tracker.clone();
        quick.step.max_steps = STRAIGHT_FIRST_STEPS;
        check = retrack_in_twin(twin, (starts, straight_first), path(), &quick, false);
        check.ran_out_near_the_end.clear();
    }
    let rest: Vec<usize> = indices
        .iter()
        .copied()
        .filter(|i| !check.finite.iter().any(|(j, _)| j == i) && !check.at_infinity.contains(i))
        .collect();
    if !rest.is_empty() {
        let mut options = tracker.clone();
        options.step.max_steps = options.step.max_steps.max(TWIN_MAX_STEPS);
        check.absorb(retrack_in_twin(
            twin,
            (starts, &rest),
            path(),
            &options,
            true,
        ));
    }
    check
}

/// Re-tracks the paths `indices` of `starts` in `twin` along `path` with the options
/// `options`, with the endgame or (`endgame == false`) straight to `t = 1` and
/// Newton's method there, where an endpoint counts as finite only below
/// [`STRAIGHT_MAX_CONDITION`].
fn retrack_in_twin<P: ParameterPath>(
    twin: &dyn ProjectiveTwin,
    (starts, indices): (&[Vec<C64>], &[usize]),
    path: P,
    options: &TrackerOptions,
    endgame: bool,
) -> TwinCheck {
    let lifted: Vec<Vec<C64>> = indices.iter().map(|&i| twin.lift(&starts[i])).collect();
    let homotopy = PathParameterHomotopy::new(twin.system(), path);
    let results: Vec<PathResult> = track_all(&homotopy, &lifted, options, endgame);
    let mut check = TwinCheck {
        finite: Vec::new(),
        at_infinity: Vec::new(),
        ran_out_near_the_end: Vec::new(),
        tracked: indices.len(),
    };
    for (&i, result) in indices.iter().zip(&results) {
        if simple_endpoint(result) && (endgame || result.condition < STRAIGHT_MAX_CONDITION) {
            check.finite.push((i, twin.lower(&result.solution)));
        } else if result.status == PathStatus::AtInfinity
            && on_the_hyperplane_at_infinity(twin, &result.solution)
        {
            check.at_infinity.push(i);
        } else if result.status == PathStatus::Failed(FailureReason::TooManySteps)
            && (C64::new(1.0, 0.0) - result.last_t).norm() < NEAR_THE_END
        {
            check.ran_out_near_the_end.push(i);
        }
        // A path that diverges in the twin too (coordinates the twin shares with the
        // first formulation grow without bound) is at infinity by the same evidence as
        // in the first formulation: no independent confirmation, left unclassified.
    }
    check
}

/// [`recheck_in_twin`] with a patient budget: [`PATIENT_TWIN_STEPS`] steps per path,
/// all of which may be in double-double arithmetic, for at most
/// [`PATIENT_TWIN_PATHS`] paths that ran out of steps near the end of an ordinary twin
/// run (`None` for more: the cost is bounded by the caller's few lost paths), along
/// `path()`. First straight to `t = 1` without the endgame: its Cauchy loops around
/// `t = 1`, at radii from 2·10⁻⁵ down to 2·10⁻⁸, took 7,800–11,100 steps for the four
/// paths of [`PATIENT_TWIN_STEPS`]'s example at one seed point (5.6 s), straight to
/// `t = 1` 1,180–1,330 (0.24 s), to the same endpoints (condition numbers
/// 1.5·10¹¹–2.9·10¹¹, residuals 10⁻¹¹). A path that nears a singular endpoint that way
/// usually ends at a point whose condition number is of the order of 1/ε, which
/// [`STRAIGHT_MAX_CONDITION`] does not count as finite. The paths that reach no finite
/// endpoint so are tracked once more with the endgame, which tells a point at infinity
/// (a base on a line posed in the generic family: four of its 88 `rigid/rigid` paths
/// run out of steps on their way to infinity at every seed point, and only the
/// endgame's twin run confirms them there).
pub(crate) fn recheck_patiently<P: ParameterPath>(
    twin: &dyn ProjectiveTwin,
    starts: &[Vec<C64>],
    indices: &[usize],
    path: impl Fn() -> P,
    tracker: &TrackerOptions,
) -> Option<TwinCheck> {
    if indices.is_empty() || indices.len() > PATIENT_TWIN_PATHS {
        return None;
    }
    let mut patient = tracker.clone();
    patient.step.max_steps = PATIENT_TWIN_STEPS;
    patient.precision.max_extended_steps = PATIENT_TWIN_STEPS;
    let mut check = retrack_in_twin(twin, (starts, indices), path(), &patient, false);
    let rest: Vec<usize> = indices
        .iter()
        .copied()
        .filter(|i| !check.finite.iter().any(|(j, _)| j == i))
        .collect();
    check.ran_out_near_the_end.clear();
    if !rest.is_empty() {
        check.absorb(retrack_in_twin(
            twin,
            (starts, &rest),
            path(),
            &patient,
            true,
        ));
    }
    Some(check)
}

/// Whether `y`'s homogenising coordinate is zero to within [`HOMOGENEOUS_ZERO`] times
/// `1 + ‖y‖∞` (the tracker's own bound, [`crate::homotopy::Tracker`]).
fn on_the_hyperplane_at_infinity(twin: &dyn ProjectiveTwin, y: &[C64]) -> bool {
    let norm = y.iter().fold(0.0f64, |m, v| m.max(v.norm()));
    twin.system()
        .homogenizing_variable()
        .and_then(|h| y.get(h))
        .is_some_and(|h| h.norm() <= HOMOGENEOUS_ZERO * (1.0 + norm))
}

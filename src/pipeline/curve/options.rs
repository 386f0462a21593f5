//! Options of the curve pipeline and the tuned tracker settings.

use super::*;

/// Knobs of the curve pipeline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveOptions {
    /// Seed of every random choice (τ*, perturbations, detours).
    pub seed: u64,
    /// Tracker settings of the user and parameter homotopies
    /// ([`TrackerOptions::fast`]: on the built-in example 1.5 × faster than the default
    /// preset with the same endpoints and distances).
    pub tracker: TrackerOptions,
    /// Tracker settings of the pose-to-pose paths ([`CurveOptions::chain_length`], the
    /// rescue pass): the `fast` preset with steps up to 0.5 (two segments through a
    /// complex midpoint between nearby poses; steps of at most 0.2 made the built-in
    /// example's `plate/*` curves about 1.2 × slower).
    #[serde(default = "default_neighbour_tracker")]
    pub neighbour_tracker: TrackerOptions,
    /// Tracker settings of the re-runs (safer).
    pub retry_tracker: TrackerOptions,
    /// Number of detour re-runs of a (pose, sub-problem) that lost paths.
    pub retry_attempts: usize,
    /// Number of detour re-runs of the user homotopy (source → seed) of a sub-problem
    /// that lost paths: it runs once per curve and every pose inherits what it misses.
    #[serde(default = "default_seed_retry_attempts")]
    pub seed_retry_attempts: usize,

    /// Poses per chain of stage 2: one pose of every block of `chain_length`
    /// consecutive poses is solved from the seed (the one nearest `Re τ*`; the first
    /// for pose lists), the others forwards and backwards from it, each from its
    /// predecessors' (in chain order) complete finite solution sets ([`CurveOptions::jump`], or short
    /// pose-to-pose paths through a random complex midpoint), falling back to the seed
    /// route wherever that set is incomplete. `1` solves every pose from the seed (the
    /// reference route). The blocks do not depend on the thread count, so neither do
    /// the results. Default 1000: a seed-route pose costs about as much as twenty
    /// chained ones, and the chained poses run their sub-problems and critical points
    /// in parallel.
    #[serde(default = "default_chain_length")]
    pub chain_length: usize,
    /// Within a chain, solve a pose first by Newton's method from critical points
    /// extrapolated from the preceding poses, one per complex conjugate pair, without
    /// tracking; pose-to-pose paths only for what that leaves unaccounted for (see the
    /// module documentation). `false`: every critical point along a path.
    #[serde(default = "default_jump")]
    pub jump: bool,
    /// Coordinates of the unknown points while tracking ([`Coordinates::Isotropic`] by
    /// default: critical points far out along isotropic lines stay well-conditioned,
    /// see [`crate::algebra::Isotropic`]); results are reported in Cartesian ones.
    #[serde(default = "default_coordinates")]
    pub coordinates: Coordinates,
    /// A critical point is real when `max |Im x| ≤ real_tolerance · (1 + ‖x‖∞)`.
    pub real_tolerance: f64,
    /// Two minimisers within this distance of each other make a cut locus.
    pub cut_locus_tolerance: f64,
    /// Re-solve the first and last pose and each metric's closest pose from an
    /// independent seed stage and compare ([`SelfCheck`]); on by default.
    #[serde(default = "default_self_check")]
    pub self_check: bool,
    /// Poses per window: the motion is solved in consecutive windows of this many
    /// poses, each completely (chains, rescue from neighbours, self-check) before the
    /// next, so a run holds one window's results at a time and can hand each window
    /// on (written, then dropped) as soon as it is final. Chains and the rescue pass
    /// stay within a window. Fixed by the arguments, never by the thread count, so
    /// neither are the results. Default [`DEFAULT_WINDOW_POSES`].
    #[serde(default = "default_window_poses")]
    pub window_poses: usize,
    /// Certify every pose's critical points in interval arithmetic
    /// ([`crate::certify::distance`]) and report per metric whether the distance is a
    /// proved global minimum; off by default.
    #[serde(default)]
    pub certify: bool,
}

/// Default [`CurveOptions::window_poses`]: 1000, the default chain length, so that a
/// window is one chain. Its working set is a few MB (one metric) to a few tens of MB
/// (nine), and its self-check (three to eleven poses along the seed route) costs
/// little next to its 1000 chained poses.
pub const DEFAULT_WINDOW_POSES: usize = 1000;

fn default_window_poses() -> usize {
    DEFAULT_WINDOW_POSES
}

fn default_self_check() -> bool {
    true
}

/// Step budget per path of the curve's trackers. On the built-in example (`plate/rigid`)
/// paths take 18 steps (median), 114 (90 %) and 500 (99 %); the longest follow
/// critical points far out along isotropic directions (‖x‖ ~ 10⁴–10⁶, κ ~ 10¹⁴–10¹⁶)
/// in extended precision, which has its own budget
/// ([`TrackerOptions::max_extended_steps`]). Paths that exhaust it are re-run, then
/// reported as lost, never dropped silently.
pub const CURVE_MAX_STEPS: usize = 1500;

/// [`TrackerOptions::extended_after_rejections`] of the curve's first-run trackers: 0,
/// extended precision only where the step size underflows. In isotropic coordinates
/// the far-out critical points are well-conditioned up to scaling, and on the built-in
/// example extended precision switched on after rejections changed no step of any
/// path (same step counts, same JSON for seeds 1–8) while costing 11 % of the time.
/// The conservative re-runs keep switching after rejections. (Tracking in Cartesian
/// coordinates needs the switch after 3 rejections, as in [`TrackerOptions::fast`]:
/// without it the `rigid/rigid` seed → pose paths near τ = −1 are lost.)
pub const CURVE_EXTENDED_AFTER_REJECTIONS: usize = 0;

/// [`TrackerOptions::prediction_tolerance`] of the curve's seed-stage and seed → pose
/// tracker: 10⁻⁴ instead of the fast preset's 10⁻⁵. Path jumps it may cause are caught
/// (crossings, completeness) and re-run. Measured on the built-in example, seeds 1–8:
/// 12–16 % fewer LU factorisations over the whole curve, the same distances (to
/// 3·10⁻¹⁴), and seed 5's lost `rigid/rigid` seed path is found.
pub const CURVE_PREDICTION_TOLERANCE: f64 = 1e-4;

/// [`TrackerOptions::at_infinity_norm`] of the curve's first-run trackers: 10¹²
/// instead of 10⁸. On the built-in example the `rigid/rigid` critical points pass close
/// to infinity near τ ≈ −0.8 (a pole near the real axis): at poses 3 and 4 one of them
/// is finite with norm between 10⁸ and 10¹⁰ (normalised frame), which 10⁸ classified
/// at infinity, sending those poses to the seed route; in isotropic coordinates such
/// points are well-conditioned enough to track. Seeds 1–8: 5 % fewer LU
/// factorisations, the same distances.
pub const CURVE_AT_INFINITY_NORM: f64 = 1e12;

impl Default for CurveOptions {
    fn default() -> Self {
        CurveOptions {
            seed: 1,
            tracker: TrackerOptions {
                max_steps: CURVE_MAX_STEPS,
                extended_after_rejections: CURVE_EXTENDED_AFTER_REJECTIONS,
                prediction_tolerance: CURVE_PREDICTION_TOLERANCE,
                at_infinity_norm: CURVE_AT_INFINITY_NORM,
                ..TrackerOptions::fast()
            },
            neighbour_tracker: default_neighbour_tracker(),
            retry_tracker: TrackerOptions {
                max_steps: CURVE_MAX_STEPS,
                ..TrackerOptions::conservative()
            },
            retry_attempts: 1,
            seed_retry_attempts: default_seed_retry_attempts(),
            chain_length: default_chain_length(),
            jump: default_jump(),
            coordinates: default_coordinates(),
            real_tolerance: 1e-8,
            cut_locus_tolerance: 1e-9,
            self_check: default_self_check(),
            window_poses: default_window_poses(),
            certify: false,
        }
    }
}

fn default_seed_retry_attempts() -> usize {
    6
}

fn default_neighbour_tracker() -> TrackerOptions {
    TrackerOptions {
        max_steps: CURVE_MAX_STEPS,
        initial_step: 0.25,
        max_step: 0.5,
        at_infinity_norm: CURVE_AT_INFINITY_NORM,
        extended_after_rejections: CURVE_EXTENDED_AFTER_REJECTIONS,
        ..TrackerOptions::fast()
    }
}

fn default_coordinates() -> Coordinates {
    Coordinates::Isotropic
}

fn default_jump() -> bool {
    true
}

fn default_chain_length() -> usize {
    1000
}

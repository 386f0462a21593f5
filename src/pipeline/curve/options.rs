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
    /// Tracker settings of the seed stages' first runs, detours and monodromy loops
    /// (source → seed): [`TrackerOptions::curve_seed`], the first-run tracker with
    /// double-double arithmetic after five rejections.
    #[serde(default = "default_seed_tracker")]
    pub seed_tracker: TrackerOptions,
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
    /// How the tracked systems represent their Lagrange multipliers; results are
    /// reported with affine ones. [`Multipliers::Affine`] by default.
    /// [`Multipliers::Chart`] keeps a critical point near a singular point of the
    /// constraint set (huge multipliers) on a bounded path and finds every generic
    /// critical point at the seed of designs with two anchors 10⁻⁴ apart; but on a
    /// platform 100× smaller than the base, seed 2 without the self-check gives a
    /// `rigid/bars` distance of 1.2155 with no failure reported, where an independent
    /// 2,000-start local search (and affine multipliers) give 0.0020815 — the
    /// self-check catches it — so it is opt-in until that is explained.
    #[serde(default = "default_multipliers")]
    pub multipliers: Multipliers,
    /// Re-track the paths that end at infinity or are lost, with affine multipliers,
    /// once more with multipliers in a random chart (the projective twin,
    /// [`crate::pipeline::sweep::ProjectiveTwin`]): a finite endpoint there is a
    /// critical point the affine route missed, one at infinity there too confirms it.
    /// On by default.
    #[serde(default = "default_twin_check")]
    pub twin_check: bool,
    /// A critical point is real when `max |Im x| ≤ real_tolerance · (1 + ‖x‖∞)` over its
    /// unknowns before the multipliers (Cartesian).
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
    /// The generic route (start file → pose) bends through a complex point near the
    /// middle of its segment, drawn from [`CurveOptions::seed`], instead of running
    /// straight. Off for a run's own poses; on in the self-check's stage: the straight
    /// segment from the start file does not depend on the seed, so where both stages
    /// take the generic route (a seed count refuted at a real pose sends every pose
    /// there first; a seed route that runs out of steps hands its pose over to it) the
    /// check would retrace the run's own paths.
    #[serde(default)]
    pub generic_route_bend: bool,
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

/// The curve's tuned tracker settings, kept with the presets they define
/// ([`TrackerOptions::curve`], [`TrackerOptions::curve_neighbour`],
/// [`TrackerOptions::curve_seed`], [`TrackerOptions::curve_retry`]).
pub use crate::homotopy::tracker::{
    CURVE_AT_INFINITY_NORM, CURVE_EXTENDED_AFTER_REJECTIONS, CURVE_MAX_STEPS,
    CURVE_PREDICTION_TOLERANCE, CURVE_SEED_EXTENDED_AFTER_REJECTIONS,
};

impl Default for CurveOptions {
    fn default() -> Self {
        CurveOptions {
            seed: 1,
            tracker: TrackerOptions::curve(),
            neighbour_tracker: default_neighbour_tracker(),
            seed_tracker: default_seed_tracker(),
            retry_tracker: TrackerOptions::curve_retry(),
            retry_attempts: 1,
            seed_retry_attempts: default_seed_retry_attempts(),
            chain_length: default_chain_length(),
            jump: default_jump(),
            coordinates: default_coordinates(),
            multipliers: default_multipliers(),
            twin_check: default_twin_check(),
            real_tolerance: 1e-8,
            cut_locus_tolerance: 1e-9,
            self_check: default_self_check(),
            window_poses: default_window_poses(),
            certify: false,
            generic_route_bend: false,
        }
    }
}

fn default_seed_retry_attempts() -> usize {
    6
}

fn default_neighbour_tracker() -> TrackerOptions {
    TrackerOptions::curve_neighbour()
}

fn default_seed_tracker() -> TrackerOptions {
    TrackerOptions::curve_seed()
}

fn default_multipliers() -> Multipliers {
    Multipliers::Affine
}

fn default_twin_check() -> bool {
    true
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

//! The tracker's options ([`TrackerOptions`]) in three groups — step control
//! ([`StepOptions`]), arithmetic ([`PrecisionOptions`]) and endgame
//! ([`EndgameOptions`]) — and their named presets.
//!
//! The groups are flattened in the serialised form: a [`TrackerOptions`] reads and
//! writes the same flat JSON object as before the split, field for field in the same
//! order.

use serde::{Deserialize, Serialize};

/// Every knob of the tracker and endgame, in three groups, with presets
/// [`TrackerOptions::fast`], [`TrackerOptions::default`],
/// [`TrackerOptions::conservative`] and the curve pipeline's tuned ones
/// ([`TrackerOptions::curve`], [`TrackerOptions::curve_neighbour`],
/// [`TrackerOptions::curve_retry`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TrackerOptions {
    /// Predictor, corrector and step-size control.
    #[serde(flatten)]
    pub step: StepOptions,
    /// Double / double-double switching.
    #[serde(flatten)]
    pub precision: PrecisionOptions,
    /// The endgame near `t = 1`, divergence and endpoint classification.
    #[serde(flatten)]
    pub endgame: EndgameOptions,
}

/// Predictor–corrector steps and their length (see `step`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepOptions {
    /// First step length in `t`.
    pub initial_step: f64,
    /// Largest step length in `t`.
    pub max_step: f64,
    /// Smallest step, as a fraction of the segment being tracked; below it the path fails.
    pub min_step_fraction: f64,
    /// Maximal number of predictor–corrector steps per path (endgame included).
    pub max_steps: usize,
    /// Target relative predictor error `‖Δ₀‖/(1 + ‖x‖)` that sets the step size.
    pub prediction_tolerance: f64,
    /// Relative Newton tolerance along the path.
    pub corrector_tolerance: f64,
    /// Newton updates allowed per step.
    pub max_corrector_iterations: usize,
    /// Largest accepted contraction `‖Δ_{k+1}‖/‖Δ_k‖` of the corrector.
    pub max_contraction: f64,
    /// Relative noise floor of the corrector: two successive Newton updates below it
    /// (the second below this, the first below ten times this) accept the step even
    /// without contraction. At condition numbers κ with `κ·ε > corrector_tolerance`
    /// Newton's updates stagnate at rounding level and would otherwise reject every
    /// step until the step size underflows.
    pub corrector_noise_tolerance: f64,
    /// Whether stiff stretches are predicted by Hermite extrapolation
    /// (`super::hermite`): on in the curve pipeline's presets, where it takes the
    /// design matrix from 216 to 166 s (the close-anchor classes 1.4–4.6 × faster,
    /// designs with orbits at infinity up to 1.45 × slower); off elsewhere, since on
    /// PHCpack's `cohn3` it cost a failed path and 1.8 → 11 s. Serialised only when on;
    /// off when left out.
    #[serde(default, skip_serializing_if = "is_false")]
    pub hermite_on_stiff_stretches: bool,
}

/// When the tracker computes in double-double arithmetic (see `precision`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PrecisionOptions {
    /// Adaptive precision: after this many consecutive rejected steps at a condition
    /// number above 10⁶ the tracker switches to extended precision (residuals,
    /// Jacobians and LU solves in double-double). At condition numbers κ with `κ·ε`
    /// near or above the corrector tolerance — e.g. critical points far out along an
    /// isotropic direction — double-precision velocities and Newton updates are noise
    /// and no useful step size is accepted. 0 switches only when the step underflows
    /// `min_step_fraction`.
    #[serde(default = "default_extended_after_rejections")]
    pub extended_after_rejections: usize,
    /// Whether extended precision computes in double-double (`true`, the default):
    /// residuals, Jacobians and linear solves. `false` keeps double precision, so
    /// extended mode only changes the step control (for comparisons).
    #[serde(default = "default_extended_residual")]
    pub extended_residual: bool,
    /// Every this many accepted steps in extended precision the tracker checks the
    /// condition number and returns to double precision if `κ ≤ 10⁶` (it switches
    /// again after `extended_after_rejections` rejections).
    #[serde(default = "default_extended_accepted_steps")]
    pub extended_accepted_steps: usize,
    /// Step budget in extended precision (each such step costs about ten double
    /// steps): a path that needs more fails with
    /// [`super::FailureReason::TooManySteps`].
    #[serde(default = "default_max_extended_steps")]
    pub max_extended_steps: usize,
}

/// The endgame near `t = 1` (see `endgame`), the divergence bound and the
/// classification of endpoints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EndgameOptions {
    /// Endgame zone starts at `s = 1 − t = endgame_start`.
    pub endgame_start: f64,
    /// Geometric ratio `r` of the endgame radii `s_k = s₀ r^k`.
    pub endgame_ratio: f64,
    /// Smallest endgame radius before the path is declared failed.
    pub endgame_min_radius: f64,
    /// Sample points per loop of the Cauchy endgame.
    pub cauchy_samples_per_loop: usize,
    /// Largest winding number the Cauchy endgame tries.
    pub max_winding_number: usize,
    /// Relative agreement of two successive Cauchy estimates that ends the endgame.
    pub endgame_tolerance: f64,
    /// Paths whose max-norm exceeds this diverge: anywhere on a route the tracker
    /// stops there; in the endgame such a path is at infinity.
    pub at_infinity_norm: f64,
    /// Stable valuation below `−valuation_threshold` (with large norm) ⇒ at infinity.
    pub valuation_threshold: f64,
    /// Condition estimate above which the direct finish to `t = 1` is skipped and the
    /// Cauchy endgame used.
    pub direct_finish_condition: f64,
    /// Endpoints with a 1-norm condition estimate above this are singular.
    pub singular_condition: f64,
    /// Newton iterations that refine a finite endpoint at `t = 1`.
    pub refinement_iterations: usize,
    /// A singular (Cauchy) endpoint must have `‖H(x, 1)‖∞` below this (relative).
    pub endpoint_residual: f64,
    /// The endgame of Breiding and Timme ("HomotopyContinuation.jl: a package for
    /// homotopy continuation in Julia", 2018) for badly scaled systems: a grown
    /// coordinate's valuation may drift towards a negative limit, an endgame stopped
    /// with stable negative valuations is at infinity, and accepted steps below the
    /// step floor fail instead of crawling. (Its first rule — a stable negative
    /// valuation means divergence only for a coordinate grown by
    /// `MIN_COORDINATE_GROWTH` since the endgame began, or below `s = DEEP_RADIUS` —
    /// holds in every endgame.) On for `solve` ([`crate::homotopy::SolveOptions`]);
    /// off in the presets, which the curve pipeline's near-degenerate designs are
    /// tuned for.
    #[serde(default)]
    pub growth_before_divergence: bool,
    /// Where the direct finish reached `t = 1` with a small residual but a singular
    /// Jacobian (the endpoint is singular) and a Cauchy loop then cannot close within
    /// `max_winding_number` turns, the path ends at that singular endpoint instead of
    /// looping again at smaller radii. Near a positive-dimensional solution set the
    /// loops close (if at all) after 11–24 turns that differ from radius to radius:
    /// PHCpack's `fbrfive4` spent 10,000–18,000 steps per such path. On for `solve`,
    /// off in the presets.
    #[serde(default)]
    pub settle_on_direct_endpoint: bool,
    /// Where the endgame stops (its step size too small, or its steps used up) at a
    /// radius `s = |1 − t|` below `DEEP_RADIUS` (10⁻⁸), after Cauchy loops that closed
    /// with winding number 1 on estimates that still moved (a path converging to a
    /// positive-dimensional solution set, whose loops close after one turn at each
    /// radius while the estimate drifts along the set), the path ends at the last
    /// estimate if its residual is small: Newton's method refines it to a nonsingular
    /// root if it converges there with a condition number below
    /// `singular_condition` (a duplicate of another path's root is then reported as a
    /// jumped path), else the endpoint is singular. PHCpack's `fourbar` lost two such
    /// paths per run. An estimate at a point that is not singular after equilibration
    /// is refined the same way and ends the path at a nonsingular root if Newton's
    /// method converges there with an equilibrated condition number below
    /// `singular_condition` (a regular root too badly scaled for the loops' estimates
    /// to agree), else the path fails. On for `solve`, off in the presets.
    #[serde(default)]
    pub settle_on_stalled_estimate: bool,
    /// In a chart of projective space (a homotopy with a homogenising coordinate
    /// `x₀`): a valuation of `x₀` above `valuation_threshold` (`x₀ ~ s^v`, `v > 0`),
    /// stable over two successive radii, classifies the path at infinity without
    /// converging to the (usually singular) point on `x₀ = 0`. The chart re-check of
    /// `solve` turns it on; off in the presets.
    #[serde(default)]
    pub homogenizing_valuation_test: bool,
    /// The direct finish to `t = 1` also above `direct_finish_condition` (up to
    /// `singular_condition`) once the condition number has settled: at most 1.5 ×
    /// its value at the previous radius, at two radii in a row. Towards a singular
    /// endpoint of winding number `c` it grows like `s^{-(1 - 1/c)}` (at least 2 × per
    /// radius); a nonsingular but ill-conditioned root keeps its condition number, and
    /// a Cauchy loop around it may enclose the branch points where its path meets a
    /// neighbour's (PHCpack's `discret3s`: roots of condition 10⁸–10⁹ at norms
    /// 10⁴–10⁵, 11 % apart). On for `solve`, off in the presets.
    #[serde(default, skip_serializing_if = "is_false")]
    pub direct_finish_at_settled_condition: bool,
    /// A Cauchy estimate of winding number `c ≥ 2` whose residual is above
    /// `10^(c − 10)` relative to `1 + ‖x‖∞` ([`super::is_averaged_estimate`]) is not
    /// accepted; the endgame goes on to smaller radii. Such a loop encloses a branch
    /// point where two paths to distinct roots meet, not the endpoint: the mean of
    /// the two sheets is analytic inside it, so the estimates agree from radius to
    /// radius, but inside the branch point's radius the loop closes after one turn
    /// on the path's own root (`discret3s`: two roots of norm 2·10⁴, loops of winding
    /// number 2 down to `s = 3.7·10⁻¹⁰`, one turn at `9·10⁻¹¹`). On for `solve`, off
    /// in the presets.
    #[serde(default, skip_serializing_if = "is_false")]
    pub reject_averaging_loops: bool,
}

fn is_false(value: &bool) -> bool {
    !*value
}

fn default_extended_after_rejections() -> usize {
    3
}

fn default_extended_residual() -> bool {
    true
}

fn default_max_extended_steps() -> usize {
    1000
}

fn default_extended_accepted_steps() -> usize {
    16
}

impl Default for StepOptions {
    /// Balanced steps: reliable on the katsura/cyclic benchmarks and singdist's systems.
    fn default() -> Self {
        StepOptions {
            initial_step: 0.05,
            max_step: 0.1,
            min_step_fraction: 1e-10,
            max_steps: 20_000,
            prediction_tolerance: 1e-6,
            corrector_tolerance: 1e-9,
            max_corrector_iterations: 3,
            max_contraction: 0.25,
            corrector_noise_tolerance: 1e-8,
            hermite_on_stiff_stretches: false,
        }
    }
}

impl StepOptions {
    /// Larger steps and looser contraction (the steps of [`TrackerOptions::fast`]).
    pub fn fast() -> Self {
        StepOptions {
            initial_step: 0.1,
            max_step: 0.2,
            prediction_tolerance: 1e-5,
            max_contraction: 0.3,
            ..Self::default()
        }
    }

    /// Small steps and strict contraction (the steps of
    /// [`TrackerOptions::conservative`]).
    pub fn conservative() -> Self {
        StepOptions {
            initial_step: 0.01,
            max_step: 0.02,
            min_step_fraction: 1e-13,
            max_steps: 10_000,
            prediction_tolerance: 1e-8,
            corrector_tolerance: 1e-10,
            max_contraction: 0.1,
            ..Self::default()
        }
    }
}

impl Default for PrecisionOptions {
    /// Extended precision after 3 rejections at κ > 10⁶, back to double every 16
    /// accepted steps where κ ≤ 10⁶, at most 1000 extended steps.
    fn default() -> Self {
        PrecisionOptions {
            extended_after_rejections: default_extended_after_rejections(),
            extended_residual: default_extended_residual(),
            extended_accepted_steps: default_extended_accepted_steps(),
            max_extended_steps: default_max_extended_steps(),
        }
    }
}

impl Default for EndgameOptions {
    /// Endgame from `s = 0.1` with radii shrinking by 4, the classic power-series
    /// divergence test.
    fn default() -> Self {
        EndgameOptions {
            endgame_start: 0.1,
            endgame_ratio: 0.25,
            endgame_min_radius: 1e-13,
            cauchy_samples_per_loop: 8,
            max_winding_number: 16,
            endgame_tolerance: 1e-8,
            at_infinity_norm: 1e8,
            valuation_threshold: 0.1,
            direct_finish_condition: 1e8,
            singular_condition: 1e10,
            refinement_iterations: 6,
            endpoint_residual: 1e-8,
            growth_before_divergence: false,
            settle_on_direct_endpoint: false,
            settle_on_stalled_estimate: false,
            homogenizing_valuation_test: false,
            direct_finish_at_settled_condition: false,
            reject_averaging_loops: false,
        }
    }
}

impl EndgameOptions {
    /// A longer endgame (radii shrinking by 10/3, down to 10⁻¹⁵, winding numbers up to
    /// 32): the endgame of [`TrackerOptions::conservative`].
    pub fn conservative() -> Self {
        EndgameOptions {
            endgame_ratio: 0.3,
            endgame_min_radius: 1e-15,
            max_winding_number: 32,
            ..Self::default()
        }
    }
}

/// Step budget per path of the curve pipeline's trackers. On the built-in example
/// (`plate/rigid`) paths take 18 steps (median), 114 (90 %) and 500 (99 %); the
/// longest follow critical points far out along isotropic directions
/// (‖x‖ ~ 10⁴–10⁶, κ ~ 10¹⁴–10¹⁶) in extended precision, which has its own budget
/// ([`PrecisionOptions::max_extended_steps`]). Paths that exhaust it are re-run, then
/// reported as lost, never dropped silently.
pub const CURVE_MAX_STEPS: usize = 1500;

/// [`PrecisionOptions::extended_after_rejections`] of the curve pipeline's first-run
/// trackers: 0, extended precision only where the step size underflows. In isotropic
/// coordinates the far-out critical points are well-conditioned up to scaling, and on
/// the built-in example extended precision switched on after rejections changed no
/// step of any path (same step counts, same JSON for seeds 1–8) while costing 11 % of
/// the time. The conservative re-runs keep switching after rejections. (Tracking in
/// Cartesian coordinates needs the switch after 3 rejections, as in
/// [`TrackerOptions::fast`]: without it the `rigid/rigid` seed → pose paths near
/// τ = −1 are lost.)
pub const CURVE_EXTENDED_AFTER_REJECTIONS: usize = 0;

/// [`PrecisionOptions::extended_after_rejections`] of the curve pipeline's seed-stage
/// tracker ([`TrackerOptions::curve_seed`]). On designs whose rigid parts send whole
/// orbits of critical points to infinity at every seed, seed-stage paths crawl at
/// condition numbers of 10¹⁵ and more in double precision; in double-double they
/// finish. Measured (design matrix, all nine metrics, 8 scattered poses, 2 threads;
/// never / after 3 / after 5 / after 8 rejections): `similar` 3.6 / 1.6 / 2.2 / 2.3 s,
/// `congruent` 4.1 / 3.7 / 3.6 / 3.7 s, `coincident-base-12` 3.1 / 2.6 / 2.6 / 2.5 s,
/// but the generic `tiny-platform` 1.05 / 1.38 / 1.14 / 1.06 s, with the same
/// distances to 10⁻¹⁴.
pub const CURVE_SEED_EXTENDED_AFTER_REJECTIONS: usize = 5;

/// [`StepOptions::prediction_tolerance`] of the curve pipeline's seed-stage and
/// seed → pose tracker: 10⁻⁴ instead of the fast preset's 10⁻⁵. Path jumps it may
/// cause are caught (crossings, completeness) and re-run. Measured on the built-in
/// example, seeds 1–8: 12–16 % fewer LU factorisations over the whole curve, the same
/// distances (to 3·10⁻¹⁴), and seed 5's lost `rigid/rigid` seed path is found.
pub const CURVE_PREDICTION_TOLERANCE: f64 = 1e-4;

/// [`EndgameOptions::at_infinity_norm`] of the curve pipeline's first-run trackers:
/// 10¹² instead of 10⁸. On the built-in example the `rigid/rigid` critical points pass
/// close to infinity near τ ≈ −0.8 (a pole near the real axis): at poses 3 and 4 one
/// of them is finite with norm between 10⁸ and 10¹⁰ (normalised frame), which 10⁸
/// classified at infinity, sending those poses to the seed route; in isotropic
/// coordinates such points are well-conditioned enough to track. Seeds 1–8: 5 % fewer
/// LU factorisations, the same distances.
pub const CURVE_AT_INFINITY_NORM: f64 = 1e12;

impl TrackerOptions {
    /// Larger steps and looser contraction: for well-conditioned families (e.g. a
    /// parameter homotopy between nearby poses). About twice as fast as the default.
    pub fn fast() -> Self {
        TrackerOptions {
            step: StepOptions::fast(),
            ..Self::default()
        }
    }

    /// Small steps, strict contraction, long endgame: for re-running failed paths.
    pub fn conservative() -> Self {
        TrackerOptions {
            step: StepOptions::conservative(),
            endgame: EndgameOptions::conservative(),
            ..Self::default()
        }
    }

    /// The curve pipeline's first-run tracker (user and parameter homotopies): the
    /// fast preset with [`CURVE_MAX_STEPS`], [`CURVE_PREDICTION_TOLERANCE`],
    /// [`CURVE_EXTENDED_AFTER_REJECTIONS`] and [`CURVE_AT_INFINITY_NORM`]. On the
    /// built-in example 1.5 × faster than the default preset with the same endpoints
    /// and distances.
    pub fn curve() -> Self {
        let mut options = Self::fast().with_curve_budgets();
        options.step.prediction_tolerance = CURVE_PREDICTION_TOLERANCE;
        options
    }

    /// The curve pipeline's seed-stage tracker: [`TrackerOptions::curve`] with
    /// double-double arithmetic after [`CURVE_SEED_EXTENDED_AFTER_REJECTIONS`]
    /// rejections.
    pub fn curve_seed() -> Self {
        let mut options = Self::curve();
        options.precision.extended_after_rejections = CURVE_SEED_EXTENDED_AFTER_REJECTIONS;
        options
    }

    /// The curve pipeline's pose-to-pose tracker: the fast preset with steps from 0.25
    /// up to 0.5 (two segments through a complex midpoint between nearby poses; steps
    /// of at most 0.2 made the built-in example's `plate/*` curves about 1.2 × slower),
    /// [`CURVE_MAX_STEPS`], [`CURVE_AT_INFINITY_NORM`] and
    /// [`CURVE_EXTENDED_AFTER_REJECTIONS`].
    pub fn curve_neighbour() -> Self {
        let mut options = Self::fast().with_curve_budgets();
        options.step.initial_step = 0.25;
        options.step.max_step = 0.5;
        options
    }

    /// `self` with the step budget, divergence bound and precision switching the
    /// curve pipeline's first-run and pose-to-pose trackers share.
    fn with_curve_budgets(mut self) -> Self {
        self.step.max_steps = CURVE_MAX_STEPS;
        self.step.hermite_on_stiff_stretches = true;
        self.precision.extended_after_rejections = CURVE_EXTENDED_AFTER_REJECTIONS;
        self.endgame.at_infinity_norm = CURVE_AT_INFINITY_NORM;
        self
    }

    /// The curve pipeline's re-run tracker: the conservative preset with
    /// [`CURVE_MAX_STEPS`].
    pub fn curve_retry() -> Self {
        let mut options = Self::conservative();
        options.step.max_steps = CURVE_MAX_STEPS;
        options.step.hermite_on_stiff_stretches = true;
        options
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The serialised presets, one JSON object a line, as written by the flat
    /// `TrackerOptions` before its fields were grouped: the grouped one writes the same
    /// bytes and reads them back.
    const FLAT_PRESETS: &str = include_str!("../../../tests/data/tracker_options_presets.txt");

    fn presets() -> [(&'static str, TrackerOptions); 6] {
        [
            ("default", TrackerOptions::default()),
            ("fast", TrackerOptions::fast()),
            ("conservative", TrackerOptions::conservative()),
            ("curve", TrackerOptions::curve()),
            ("curve_neighbour", TrackerOptions::curve_neighbour()),
            ("curve_retry", TrackerOptions::curve_retry()),
        ]
    }

    #[test]
    fn the_grouped_options_serialise_to_the_flat_format() {
        let lines: Vec<&str> = FLAT_PRESETS.lines().collect();
        assert_eq!(lines.len(), 6);
        for ((name, options), line) in presets().into_iter().zip(lines) {
            let (label, json) = line.split_once(' ').unwrap();
            assert_eq!(label, name);
            assert_eq!(serde_json::to_string(&options).unwrap(), json, "{name}");
            let read: TrackerOptions = serde_json::from_str(json).unwrap();
            assert_eq!(read, options, "{name}");
        }
    }

    /// Fields with serde defaults (the precision group, `growth_before_divergence`,
    /// `settle_on_direct_endpoint`, `settle_on_stalled_estimate`,
    /// `homogenizing_valuation_test`)
    /// may be left out, as before; the others are required.
    #[test]
    fn optional_fields_default_and_required_ones_are_required() {
        let mut value = serde_json::to_value(TrackerOptions::fast()).unwrap();
        let object = value.as_object_mut().unwrap();
        for key in [
            "extended_after_rejections",
            "extended_residual",
            "extended_accepted_steps",
            "max_extended_steps",
            "growth_before_divergence",
            "settle_on_direct_endpoint",
            "settle_on_stalled_estimate",
            "homogenizing_valuation_test",
        ] {
            assert!(object.remove(key).is_some(), "{key}");
        }
        let read: TrackerOptions = serde_json::from_value(value.clone()).unwrap();
        assert_eq!(read, TrackerOptions::fast());
        value.as_object_mut().unwrap().remove("endgame_ratio");
        let error = serde_json::from_value::<TrackerOptions>(value).unwrap_err();
        assert!(error.to_string().contains("endgame_ratio"), "{error}");
    }

    #[test]
    fn the_curve_presets_differ_from_their_bases_only_where_tuned() {
        let mut curve = TrackerOptions::curve();
        assert_eq!(curve.step.max_steps, CURVE_MAX_STEPS);
        assert_eq!(curve.step.prediction_tolerance, CURVE_PREDICTION_TOLERANCE);
        assert_eq!(curve.endgame.at_infinity_norm, CURVE_AT_INFINITY_NORM);
        assert!(curve.step.hermite_on_stiff_stretches);
        curve.step.hermite_on_stiff_stretches = false;
        curve.step.max_steps = StepOptions::fast().max_steps;
        curve.step.prediction_tolerance = StepOptions::fast().prediction_tolerance;
        curve.precision.extended_after_rejections =
            PrecisionOptions::default().extended_after_rejections;
        curve.endgame.at_infinity_norm = EndgameOptions::default().at_infinity_norm;
        assert_eq!(curve, TrackerOptions::fast());
        let retry = TrackerOptions::curve_retry();
        assert_eq!(retry.endgame, EndgameOptions::conservative());
        assert_eq!(retry.step.max_steps, CURVE_MAX_STEPS);
        assert!(retry.step.hermite_on_stiff_stretches);
        assert!(
            !TrackerOptions::conservative()
                .step
                .hermite_on_stiff_stretches
        );
    }
}

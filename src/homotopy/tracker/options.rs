//! The tracker's options ([`TrackerOptions`]) and their presets.

use serde::{Deserialize, Serialize};

/// Every knob of the tracker and endgame, with presets [`TrackerOptions::fast`],
/// [`TrackerOptions::default`] and [`TrackerOptions::conservative`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrackerOptions {
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
    /// Adaptive precision: after this many consecutive rejected steps at a condition
    /// number above 10⁶ the tracker switches to extended precision (residuals, Jacobians and LU solves in
    /// double-double, see the module documentation). At condition numbers κ with
    /// `κ·ε` near or above the corrector tolerance — e.g. critical points far out along
    /// an isotropic direction — double-precision velocities and Newton updates are
    /// noise and no useful step size is accepted. 0 switches only when the step
    /// underflows `min_step_fraction`.
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
    /// steps): a path that needs more fails with [`FailureReason::TooManySteps`].
    #[serde(default = "default_max_extended_steps")]
    pub max_extended_steps: usize,
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
    /// Paths whose max-norm exceeds this are declared at infinity.
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
    /// homotopy continuation in Julia", 2018) for badly scaled systems: a stable
    /// negative valuation means divergence only for a coordinate grown by
    /// `MIN_COORDINATE_GROWTH` since the endgame began (or below `s = DEEP_RADIUS`), a
    /// grown coordinate's valuation may drift towards a negative limit, an endgame
    /// stopped with stable negative valuations is at infinity, and accepted steps
    /// below the step floor fail instead of crawling. On for `solve`
    /// ([`crate::homotopy::SolveOptions`]); off (the classic power-series test) in the
    /// presets, which the curve pipeline's near-degenerate designs are tuned for.
    #[serde(default)]
    pub growth_before_divergence: bool,
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

impl Default for TrackerOptions {
    /// Balanced preset: reliable on the katsura/cyclic benchmarks and singdist's systems.
    fn default() -> Self {
        TrackerOptions {
            initial_step: 0.05,
            max_step: 0.1,
            min_step_fraction: 1e-10,
            max_steps: 20_000,
            prediction_tolerance: 1e-6,
            corrector_tolerance: 1e-9,
            max_corrector_iterations: 3,
            max_contraction: 0.25,
            corrector_noise_tolerance: 1e-8,
            extended_after_rejections: default_extended_after_rejections(),
            extended_accepted_steps: default_extended_accepted_steps(),
            max_extended_steps: default_max_extended_steps(),
            extended_residual: default_extended_residual(),
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
        }
    }
}

impl TrackerOptions {
    /// Larger steps and looser contraction: for well-conditioned families (e.g. a
    /// parameter homotopy between nearby poses). About twice as fast as the default.
    pub fn fast() -> Self {
        TrackerOptions {
            initial_step: 0.1,
            max_step: 0.2,
            prediction_tolerance: 1e-5,
            max_contraction: 0.3,
            ..Self::default()
        }
    }

    /// Small steps, strict contraction, long endgame: for re-running failed paths.
    pub fn conservative() -> Self {
        TrackerOptions {
            initial_step: 0.01,
            max_step: 0.02,
            min_step_fraction: 1e-13,
            max_steps: 10_000,
            prediction_tolerance: 1e-8,
            corrector_tolerance: 1e-10,
            max_contraction: 0.1,
            endgame_ratio: 0.3,
            endgame_min_radius: 1e-15,
            max_winding_number: 32,
            ..Self::default()
        }
    }
}

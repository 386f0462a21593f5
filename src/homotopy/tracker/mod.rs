//! Predictor–corrector path tracking with a Cauchy endgame.
//!
//! A path `x(t)` of `H(x(t), t) = 0` satisfies the Davidenko equation
//! `∂H/∂x · ẋ = −∂H/∂t`. One step from `t` to `t + h`:
//!
//! 1. **Predictor**: classical fourth-order Runge–Kutta on the Davidenko equation
//!    (local error `O(h⁵)`), every stage one LU solve. The first stage reuses the
//!    factorisation of the corrector's last Newton iteration (a point within the
//!    corrector tolerance of the accepted one), so a step costs three fresh Jacobians
//!    for the predictor and one or two for the corrector.
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

use super::homotopies::Homotopy;
use super::linalg::{DdLuWorkspace, LuWorkspace};
use crate::C64;
use serde::{Deserialize, Serialize};

mod endgame;

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
}

impl PathResult {
    /// Whether every coordinate is real up to `tolerance · (1 + ‖x‖∞)`.
    pub fn is_real(&self, tolerance: f64) -> bool {
        let scale = 1.0 + max_norm(&self.solution);
        self.solution
            .iter()
            .all(|v| v.im.abs() <= tolerance * scale)
    }
}

/// Condition number below which extended mode returns to double precision
/// (κ·ε ≈ 2·10⁻¹⁰, well under the corrector tolerance).
const RETURN_TO_DOUBLE_CONDITION: f64 = 1e6;

/// Newton updates of [`Tracker::correct_at`].
pub const CORRECT_AT_ITERATIONS: usize = 8;

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

/// Smallest step in `t` (absolute): `t` near 1 is resolved to `ε ≈ 2.2·10⁻¹⁶`, and
/// steps below a few of its units no longer move the path (they only re-evaluate the
/// homotopy at the same rounded `t`).
const MIN_ABSOLUTE_STEP: f64 = 1e-15;

/// Largest rise (relative) of a grown coordinate's valuation between two radii that
/// still counts as stable; any fall does (see [`MIN_COORDINATE_GROWTH`]).
const GROWN_VALUATION_DRIFT: f64 = 0.05;

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

fn max_norm(x: &[C64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.norm_sqr())).sqrt()
}

/// Scratch for evaluations and linear solves.
struct Evaluation {
    work: Vec<C64>,
    h: Vec<C64>,
    jac: Vec<C64>,
    dh: Vec<C64>,
    lu: LuWorkspace,
    /// [`TrackerOptions::extended_residual`].
    extended_residual: bool,
    /// Extended mode: Jacobians in double-double, solves by `dd_lu`.
    extended: bool,
    /// Trailing parts of the double-double Jacobian in `jac`.
    jac_low: Vec<C64>,
    dd_lu: DdLuWorkspace,
    /// The current factorisation is `dd_lu`'s (else `lu`'s).
    dd_current: bool,
    /// `lu` does not hold the factorisation of `jac` (extended mode factors only
    /// `dd_lu`; [`Evaluation::condition_estimate`] factors `lu` on demand).
    lu_stale: bool,
}

/// Result of a Newton update.
enum NewtonUpdate {
    Step(f64),
    Singular,
}

impl Evaluation {
    fn new(n: usize, work_len: usize, extended_residual: bool) -> Self {
        let z = C64::new(0.0, 0.0);
        Evaluation {
            extended_residual,
            extended: false,
            jac_low: vec![z; n * n],
            dd_lu: DdLuWorkspace::new(n),
            dd_current: false,
            lu_stale: false,
            work: vec![z; work_len],
            h: vec![z; n],
            jac: vec![z; n * n],
            dh: vec![z; n],
            lu: LuWorkspace::new(n),
        }
    }

    /// `out ← dx/du = −J⁻¹ ∂H/∂t · dt` at `(x, t)`. In extended mode (`self.extended`)
    /// `J` and `∂H/∂t` are evaluated in double-double and the solve is the
    /// double-double LU: velocities keep their accuracy up to κ ≈ 10²⁵.
    fn velocity<H: Homotopy + ?Sized>(
        &mut self,
        homotopy: &H,
        x: &[C64],
        t: C64,
        dt: C64,
        out: &mut [C64],
    ) -> bool {
        if self.extended && self.extended_residual {
            homotopy.evaluate_with_jacobian_and_time_derivative_extended(
                x,
                t,
                &mut self.work,
                &mut self.h,
                (&mut self.jac, &mut self.jac_low),
                &mut self.dh,
            );
            if !self.dd_lu.factor(&self.jac, &self.jac_low) {
                return false;
            }
            self.dd_current = true;
            self.lu_stale = true;
        } else {
            homotopy.evaluate_with_jacobian_and_time_derivative(
                x,
                t,
                &mut self.work,
                &mut self.h,
                &mut self.jac,
                &mut self.dh,
            );
            if !self.lu.factor(&self.jac) {
                return false;
            }
            self.dd_current = false;
            self.lu_stale = false;
        }
        self.solve_velocity(dt, out)
    }

    /// 1-norm condition estimate of the last Jacobian (`jac`, rounded to double where
    /// it was evaluated in double-double); factors it in double if only the
    /// double-double factorisation is current.
    fn condition_estimate(&mut self) -> f64 {
        if self.lu_stale {
            if !self.lu.factor(&self.jac) {
                return f64::INFINITY;
            }
            self.lu_stale = false;
        }
        self.lu.condition_estimate()
    }

    /// `out ← −J⁻¹ dh · dt` with the current factorisation and `self.dh`.
    fn solve_velocity(&mut self, dt: C64, out: &mut [C64]) -> bool {
        for (o, d) in out.iter_mut().zip(&self.dh) {
            *o = -d * dt;
        }
        if self.dd_current {
            self.dd_lu.solve_in_place(out);
        } else {
            self.lu.solve_in_place(out);
        }
        out.iter().all(|v| v.re.is_finite() && v.im.is_finite())
    }

    /// One Newton update `x ← x − J⁻¹ H(x, t)`; returns `‖Δ‖∞`. In extended mode the
    /// residual is evaluated in double-double, and with the double-double LU also the
    /// Jacobian and the solve.
    fn newton<H: Homotopy + ?Sized>(
        &mut self,
        homotopy: &H,
        x: &mut [C64],
        t: C64,
        extended: bool,
    ) -> NewtonUpdate {
        let factored = if extended && self.extended_residual {
            homotopy.evaluate_with_jacobian_extended(
                x,
                t,
                &mut self.work,
                &mut self.h,
                (&mut self.jac, &mut self.jac_low),
            );
            self.dd_current = true;
            self.lu_stale = true;
            self.dd_lu.factor(&self.jac, &self.jac_low)
        } else {
            homotopy.evaluate_with_jacobian(x, t, &mut self.work, &mut self.h, &mut self.jac);
            if extended && self.extended_residual {
                // Residual beyond double precision: the update is then limited by κ·ε
                // of the linear solve, not by the rounding noise of H.
                homotopy.evaluate_extended(x, t, &mut self.work, &mut self.h);
            }
            self.dd_current = false;
            self.lu_stale = false;
            self.lu.factor(&self.jac)
        };
        if !factored {
            return NewtonUpdate::Singular;
        }
        for (d, h) in self.dh.iter_mut().zip(&self.h) {
            *d = -h;
        }
        if self.dd_current {
            self.dd_lu.solve_in_place(&mut self.dh);
        } else {
            self.lu.solve_in_place(&mut self.dh);
        }
        let mut norm: f64 = 0.0;
        for (xi, d) in x.iter_mut().zip(&self.dh) {
            *xi += d;
            norm = norm.max(crate::modulus(*d));
        }
        if norm.is_finite() {
            NewtonUpdate::Step(norm)
        } else {
            NewtonUpdate::Singular
        }
    }
}

/// Why the tracker stopped before the end of a route (one segment or a chain of them).
/// The tracking layer reports only three outcomes: the route's end was reached (`Ok`),
/// the path diverged (its norm passed [`TrackerOptions::at_infinity_norm`]), or the
/// tracker failed. Whether a divergence is a solution at infinity — rather than a pole
/// passed on the way — is not the tracker's to say: only the endgame
/// ([`Tracker::track`]'s last stretch to `t = 1`) classifies a path as
/// [`PathStatus::AtInfinity`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RouteStop {
    Failed(FailureReason),
    Diverged,
}

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
    cauchy_sum: Vec<C64>,
    estimate: Vec<C64>,
    previous_estimate: Vec<C64>,
    valuations: Vec<f64>,
    previous_valuations: Vec<f64>,
    log_sum: Vec<f64>,
    log_mean: Vec<f64>,
    previous_log_mean: Vec<f64>,
    loop_valuations: Vec<f64>,
    previous_loop_valuations: Vec<f64>,
    /// `max(1, |x_i|)` at the start of the endgame (see [`MIN_COORDINATE_GROWTH`]).
    endgame_origin: Vec<f64>,
    /// Change of each valuation between the last two radii of the endgame.
    valuation_changes: Vec<f64>,
    /// The endgame's last valuation check found stable negative valuations.
    divergence_evidence: bool,
    step: f64,
    steps: usize,
    /// Steps taken in extended precision.
    extended_steps: usize,
    rejected: usize,
    extended: bool,
    used_extended: bool,
    /// Rejected steps since the last accepted one.
    consecutive_rejections: usize,
    /// Accepted steps since extended precision was switched on.
    extended_streak: usize,
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
            eval: Evaluation::new(n, homotopy.workspace_len(), options.extended_residual),
            options,
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
            cauchy_sum: vec![z; n],
            estimate: vec![z; n],
            previous_estimate: vec![z; n],
            valuations: vec![0.0; n],
            previous_valuations: vec![0.0; n],
            log_sum: vec![0.0; n],
            log_mean: vec![0.0; n],
            previous_log_mean: vec![0.0; n],
            loop_valuations: vec![0.0; n],
            previous_loop_valuations: vec![0.0; n],
            endgame_origin: vec![1.0; n],
            valuation_changes: vec![f64::NAN; n],
            divergence_evidence: false,
            step: 0.0,
            steps: 0,
            extended_steps: 0,
            rejected: 0,
            extended: false,
            used_extended: false,
            consecutive_rejections: 0,
            extended_streak: 0,
            winding: 1,
            factorization_current: false,
            t: C64::new(0.0, 0.0),
        }
    }

    /// The options in use.
    pub fn options(&self) -> &TrackerOptions {
        &self.options
    }

    fn reset(&mut self, start: &[C64], t0: f64) {
        self.x.copy_from_slice(start);
        self.t = C64::new(t0, 0.0);
        self.step = self.options.initial_step;
        self.steps = 0;
        self.extended_steps = 0;
        self.rejected = 0;
        self.extended = false;
        self.eval.extended = false;
        self.used_extended = false;
        self.consecutive_rejections = 0;
        self.extended_streak = 0;
        self.winding = 1;
    }

    /// Tracks `start` (a solution of `H(x, 0) = 0`) to `t = 1`, runs the endgame and
    /// classifies and refines the endpoint.
    pub fn track(&mut self, start: &[C64], path_index: usize) -> PathResult {
        self.reset(start, 0.0);
        let endgame_start = {
            let last = self.homotopy.breakpoints().last().copied().unwrap_or(0.0);
            self.options.endgame_start.min(0.5 * (1.0 - last))
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
            self.options.endgame_start.min(0.5 * (1.0 - last))
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
                if converged && condition < self.options.singular_condition {
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

    /// Newton's method at `t` from `prediction` (an approximation of a nonsingular
    /// solution of `H(x, t) = 0`, e.g. extrapolated from the solutions at neighbouring
    /// parameters), without path tracking: `x ← x − J⁻¹H(x, t)` while the updates
    /// contract (`‖Δ_{k+1}‖ ≤ ½‖Δ_k‖`), at most [`CORRECT_AT_ITERATIONS`] updates, until
    /// `‖Δ‖ ≤ 10⁻¹¹(1 + ‖x‖∞)`, in double precision. Where the updates contract to
    /// below [`CORRECT_AT_EXTENDED_START`] and then stagnate above `10⁻⁹(1 + ‖x‖∞)`
    /// (the rounding floor of the double-precision residual of a far-out point), up to
    /// [`CORRECT_AT_EXTENDED_ITERATIONS`] more updates run in double-double (residual,
    /// Jacobian and LU). `Nonsingular` if the limit has condition below
    /// `singular_condition`, `Singular` above it, else `Failed(CorrectorDidNotConverge)`.
    ///
    /// Which solution Newton's method converges to is not controlled (no path is
    /// followed): callers must check the set of limits, e.g. that they are distinct
    /// and as many as the generic solution count.
    pub fn correct_at(&mut self, prediction: &[C64], t: f64, path_index: usize) -> PathResult {
        self.reset(prediction, t);
        let t = C64::new(t, 0.0);
        let failed = PathStatus::Failed(FailureReason::CorrectorDidNotConverge);
        let mut previous = f64::INFINITY;
        let mut status = failed;
        let mut condition = f64::INFINITY;
        let mut residual = f64::INFINITY;
        let mut extended = false;
        let mut extended_left = CORRECT_AT_EXTENDED_ITERATIONS;
        let mut double_left = CORRECT_AT_ITERATIONS;
        while if extended {
            extended_left > 0
        } else {
            double_left > 0
        } {
            if extended {
                extended_left -= 1;
            } else {
                double_left -= 1;
            }
            self.x_saved.copy_from_slice(&self.x);
            self.steps += 1;
            let NewtonUpdate::Step(norm) =
                self.eval.newton(self.homotopy, &mut self.x, t, extended)
            else {
                break;
            };
            let scale = 1.0 + max_norm(&self.x);
            let stagnated = norm > CORRECT_AT_CONTRACTION * previous;
            if stagnated {
                // Updates at the rounding level of an ill-conditioned limit stop
                // contracting: below 1e-9 relative that is the attainable accuracy
                // (as in the endpoint refinement), keep the previous iterate.
                self.x.copy_from_slice(&self.x_saved);
                if previous > 1e-9 * scale {
                    if !extended && previous <= CORRECT_AT_EXTENDED_START * scale {
                        // Converging, but double precision's rounding floor (residual
                        // terms of a far-out point) is above the tolerance: go on in
                        // double-double from the last contracting iterate.
                        extended = true;
                        self.used_extended = true;
                        previous = f64::INFINITY;
                        continue;
                    }
                    break;
                }
            }
            if stagnated || norm <= 1e-11 * scale {
                // `eval.lu` holds J at the previous iterate, within 1e-9 of the limit.
                condition = self.eval.condition_estimate();
                status = if condition < self.options.singular_condition {
                    PathStatus::Nonsingular
                } else {
                    PathStatus::Singular
                };
                break;
            }
            previous = norm;
        }
        if status.is_finite() {
            self.homotopy
                .evaluate(&self.x, t, &mut self.eval.work, &mut self.eval.h);
            residual = max_norm(&self.eval.h);
        }
        self.t = t;
        self.result(path_index, status, residual, condition)
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
        self.result(path_index, status, residual, condition)
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
            used_extended_precision: self.used_extended,
            last_t: self.t,
        }
    }

    fn condition_at(&mut self, t: C64) -> f64 {
        let e = &mut self.eval;
        self.homotopy
            .evaluate_with_jacobian(&self.x, t, &mut e.work, &mut e.h, &mut e.jac);
        if e.lu.factor(&e.jac) {
            e.lu.condition_estimate()
        } else {
            f64::INFINITY
        }
    }

    /// Newton refinement at `t`, keeping the best iterate; returns (converged, ‖Δ‖).
    /// In double precision (unless the tracker is in extended mode) while the updates
    /// contract; where they stagnate above `10⁻¹³` relative (rounding noise of an
    /// ill-conditioned point) the remaining iterations run in extended precision.
    fn refine_at(&mut self, t: C64) -> (bool, f64) {
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut extended = self.extended;
        for _ in 0..self.options.refinement_iterations {
            self.x_saved.copy_from_slice(&self.x);
            match self.eval.newton(self.homotopy, &mut self.x, t, extended) {
                NewtonUpdate::Singular => {
                    self.x.copy_from_slice(&self.x_saved);
                    break;
                }
                NewtonUpdate::Step(norm) => {
                    let scale = 1.0 + max_norm(&self.x);
                    if norm > previous && norm > 1e-14 * scale {
                        // No longer contracting: keep the previous iterate. In double
                        // precision try again in extended precision; there, if the
                        // updates were already at rounding level for the condition of
                        // the point (below 1e-9 relative), that is the attainable
                        // accuracy: converged.
                        self.x.copy_from_slice(&self.x_saved);
                        if !extended {
                            extended = true;
                            continue;
                        }
                        converged = previous <= 1e-9 * scale;
                        break;
                    }
                    if norm <= 1e-13 * scale {
                        converged = true;
                        break;
                    }
                    previous = norm;
                }
            }
        }
        (converged, previous)
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
        let floor = if self.options.growth_before_divergence {
            self.options
                .min_step_fraction
                .max(MIN_ABSOLUTE_STEP / length)
        } else {
            self.options.min_step_fraction
        };
        while u < 1.0 {
            if self.steps >= self.options.max_steps
                || self.extended_steps >= self.options.max_extended_steps
            {
                return Err(RouteStop::Failed(FailureReason::TooManySteps));
            }
            let mut h = (self.step.min(self.options.max_step) / length).min(1.0 - u);
            if 1.0 - u - h < 0.05 * h {
                h = 1.0 - u;
            }
            let t = ta + dt * u;
            let t_mid = ta + dt * (u + 0.5 * h);
            let t_new = ta + dt * (u + h);
            self.steps += 1;
            if self.extended {
                self.extended_steps += 1;
            }
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
                    if scale > self.options.at_infinity_norm {
                        return Err(RouteStop::Diverged);
                    }
                    let error = first_update / scale;
                    let factor = if error > 0.0 {
                        (0.9 * (self.options.prediction_tolerance / error).powf(0.2))
                            .clamp(0.5, 2.0)
                    } else {
                        2.0
                    };
                    self.step = (h * length * factor).min(self.options.max_step);
                    self.consecutive_rejections = 0;
                    if self.options.growth_before_divergence
                        && u < 1.0
                        && self.step < floor * length
                    {
                        // Accepted steps whose predictor error stays far above the
                        // tolerance shrink the step as surely as rejections do (noise of
                        // the velocities at a large, ill-conditioned point); below the
                        // floor `u + h` would no longer advance.
                        if self.extended {
                            return Err(RouteStop::Failed(FailureReason::StepSizeTooSmall));
                        }
                        self.switch_to_extended();
                        self.step *= 4.0;
                    }
                    if self.extended {
                        self.extended_streak += 1;
                        if self.extended_streak >= self.options.extended_accepted_steps
                            && self.options.extended_after_rejections > 0
                        {
                            // Back to double precision once the ill-conditioned stretch
                            // is behind (κ·ε ≤ 1e-10): switching back inside it costs
                            // rejected steps and an 8-fold smaller step each time.
                            self.extended_streak = 0;
                            if self.eval.condition_estimate() <= RETURN_TO_DOUBLE_CONDITION {
                                self.extended = false;
                                self.eval.extended = false;
                            }
                        }
                    }
                }
                None => {
                    self.rejected += 1;
                    self.consecutive_rejections += 1;
                    h *= 0.5;
                    if !self.extended
                        && self.options.extended_after_rejections > 0
                        && self.consecutive_rejections >= self.options.extended_after_rejections
                        && self.eval.condition_estimate() > RETURN_TO_DOUBLE_CONDITION
                    {
                        // Only where double precision is the likely culprit: below
                        // κ = 10⁶ Newton's updates are accurate to κ·ε ≈ 10⁻¹⁰, under
                        // the corrector tolerance, and rejections mean a step too long.
                        self.switch_to_extended();
                    }
                    if h < floor {
                        if !self.extended {
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

    fn switch_to_extended(&mut self) {
        self.extended = true;
        self.eval.extended = true;
        self.used_extended = true;
        self.extended_streak = 0;
    }

    /// RK4 prediction from `(x, t)` to `t_new` into `x_predicted`.
    fn predict(&mut self, t: C64, t_mid: C64, t_new: C64, dt: C64, h: f64) -> Option<()> {
        let hom = self.homotopy;
        let e = &mut self.eval;
        if self.factorization_current {
            // The corrector's last factorisation is of J at a point within the corrector
            // tolerance of (x, t): reuse it, only ∂H/∂t is new.
            hom.evaluate_time_derivative(&self.x, t, &mut e.work, &mut e.dh);
            if !e.solve_velocity(dt, &mut self.k1) {
                return None;
            }
        } else if !e.velocity(hom, &self.x, t, dt, &mut self.k1) {
            return None;
        }
        self.factorization_current = false;
        for ((s, x), k) in self.x_stage.iter_mut().zip(&self.x).zip(&self.k1) {
            *s = x + k * (0.5 * h);
        }
        if !e.velocity(hom, &self.x_stage, t_mid, dt, &mut self.k2) {
            return None;
        }
        for ((s, x), k) in self.x_stage.iter_mut().zip(&self.x).zip(&self.k2) {
            *s = x + k * (0.5 * h);
        }
        if !e.velocity(hom, &self.x_stage, t_mid, dt, &mut self.k3) {
            return None;
        }
        for ((s, x), k) in self.x_stage.iter_mut().zip(&self.x).zip(&self.k3) {
            *s = x + k * h;
        }
        if !e.velocity(hom, &self.x_stage, t_new, dt, &mut self.k4) {
            return None;
        }
        let w = h / 6.0;
        for i in 0..self.n {
            self.x_predicted[i] =
                self.x[i] + (self.k1[i] + 2.0 * self.k2[i] + 2.0 * self.k3[i] + self.k4[i]) * w;
        }
        Some(())
    }

    /// Newton corrector on `x_predicted` at `t`; `Some(‖Δ₀‖)` if accepted.
    fn correct(&mut self, t: C64) -> Option<f64> {
        let mut first = 0.0;
        let mut previous = 0.0;
        for k in 0..self.options.max_corrector_iterations.max(1) {
            let norm =
                match self
                    .eval
                    .newton(self.homotopy, &mut self.x_predicted, t, self.extended)
                {
                    NewtonUpdate::Step(norm) => norm,
                    NewtonUpdate::Singular => return None,
                };
            let scale = 1.0 + max_norm(&self.x_predicted);
            let tolerance = self.options.corrector_tolerance * scale;
            if k == 0 {
                first = norm;
                if norm <= tolerance {
                    return Some(first);
                }
            } else {
                // Noise floor: at an ill-conditioned point (κ·ε above the tolerance)
                // the updates stop contracting once they only reflect rounding; two
                // successive updates below the noise tolerance mean the iterate is as
                // accurate as the arithmetic allows, and far too close to its path for
                // a jump to another one.
                let noise = self.options.corrector_noise_tolerance * scale;
                if norm <= noise && previous <= 10.0 * noise {
                    return Some(first);
                }
                if norm > self.options.max_contraction * previous {
                    return None;
                }
                if norm <= tolerance {
                    return Some(first);
                }
            }
            previous = norm;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `H(x, t) = (p − t)·x − 1`, one unknown: the path `x(t) = 1/(p − t)` from
    /// `x(0) = 1/p` has a pole at `t = p` (a divergence mid-route for `p < 1`, a root
    /// at infinity of `H(·, 1)` for `p = 1`).
    pub(super) struct Pole(pub(super) f64);

    impl Homotopy for Pole {
        fn dimension(&self) -> usize {
            1
        }
        fn workspace_len(&self) -> usize {
            0
        }
        fn evaluate(&self, x: &[C64], t: C64, _: &mut [C64], h: &mut [C64]) {
            h[0] = (C64::new(self.0, 0.0) - t) * x[0] - 1.0;
        }
        fn evaluate_with_jacobian(
            &self,
            x: &[C64],
            t: C64,
            work: &mut [C64],
            h: &mut [C64],
            jac: &mut [C64],
        ) {
            self.evaluate(x, t, work, h);
            jac[0] = C64::new(self.0, 0.0) - t;
        }
        fn evaluate_time_derivative(&self, x: &[C64], _: C64, _: &mut [C64], dh: &mut [C64]) {
            dh[0] = -x[0];
        }
    }

    fn start(p: f64) -> Vec<C64> {
        vec![C64::new(1.0 / p, 0.0)]
    }

    /// Steps of at most 0.01 and divergence at `‖x‖ > 10`: the tracker lands within
    /// `|t − p| < 0.1` of a pole instead of stepping across it (a simple pole of a
    /// rational path is no obstacle to the RK4 predictor).
    fn near_pole_options() -> TrackerOptions {
        TrackerOptions {
            initial_step: 0.01,
            max_step: 0.01,
            at_infinity_norm: 10.0,
            ..TrackerOptions::default()
        }
    }

    #[test]
    fn a_divergence_without_endgame_is_a_failure_not_a_point_at_infinity() {
        let homotopy = Pole(0.5);
        let mut tracker = Tracker::new(&homotopy, near_pole_options());
        let result = tracker.track_between(&start(0.5), 0.0, 1.0, 0);
        assert_eq!(
            result.status,
            PathStatus::Failed(FailureReason::DivergedOnRoute),
            "{result:?}"
        );
        assert!(result.last_t.re < 0.5, "{result:?}");
    }

    #[test]
    fn the_endgame_classifies_a_pole_at_t_one_as_at_infinity() {
        let homotopy = Pole(1.0);
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        let result = tracker.track(&start(1.0), 0);
        assert_eq!(result.status, PathStatus::AtInfinity, "{result:?}");
    }

    #[test]
    fn a_divergence_before_the_endgame_zone_is_reported_as_such() {
        let homotopy = Pole(0.5);
        let mut tracker = Tracker::new(&homotopy, near_pole_options());
        let result = tracker.track(&start(0.5), 0);
        assert_eq!(
            result.status,
            PathStatus::Failed(FailureReason::DivergedBeforeEndgame),
            "{result:?}"
        );
    }

    #[test]
    fn a_route_without_a_pole_reaches_its_end() {
        let homotopy = Pole(2.0);
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        let result = tracker.track_between(&start(2.0), 0.0, 1.0, 0);
        assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
        assert!((result.solution[0] - 1.0).norm() < 1e-12, "{result:?}");
    }
}

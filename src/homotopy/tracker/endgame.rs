//! The endgame of a path near `t = 1`: the direct finish, power-series estimates and
//! Cauchy loops around `t = 1` (winding number), and the classification of the
//! endpoint (see the module documentation of [`super`]).

use super::*;

/// Average step budget of a Cauchy loop per sample point and winding number tried
/// ([`Tracker::cauchy_loop`]): loops near the endpoint take one to three.
pub(super) const LOOP_STEPS_PER_SAMPLE: usize = 16;

/// Turns a Cauchy loop at the endgame's first radius makes at most (at smaller radii
/// `max_winding_number`). The first radius (s = 0.1) often encloses branch points
/// other than the endpoint's own, and a loop there that does not close comes back
/// having spent all its turns; one that closes there after more turns closes at the
/// next radius too. On the 3-RPR design classes (27 × 2 curves of 8 poses, every
/// distance unchanged) 189 → 180 s in all, `congruent` scattered 4.1 → 3.7 s and
/// `collinear-base` analytic 7.8 → 5.7 s; PHCpack's demo suite the same roots and
/// failures in the same time (30.4 s).
pub(super) const FIRST_RADIUS_MAX_WINDING: usize = 4;

/// Step budget of the endgame's direct finish to `t = 1`: successful ones took at
/// most 102 steps (99 % at most 30) on the built-in example's curve and on the
/// similar, congruent, collinear-platform and close-base-12 designs (8 poses each).
pub(super) const DIRECT_FINISH_STEPS: usize = 400;

/// Successive radii of growing condition number (by more than 1.5 × per radius, as
/// `s^{-(1 - 1/c)}` does towards a singular endpoint of winding number `c ≥ 2`) after
/// which a bounded path below the deep radius `s = 10⁻⁸` gets Cauchy loops even while
/// its condition number is below `direct_finish_condition`: otherwise neither the
/// direct finish (which needs a stable condition number) nor a loop runs, and the
/// path reaches the smallest radius without an estimate (PHCpack's `redcyc5`: a
/// double root whose second path gave up at `s = 4·10⁻¹³` with `x₄ ~ s`,
/// `x₁, x₂ ~ s^{1/2}`; `tangents1`: 4 such paths). Not above the deep radius: there a
/// pair of nearby nonsingular roots still looks double, and a loop around both
/// averages them (`discret3s`: two of its roots came out as one singular point).
pub(super) const SINGULAR_CONDITION_GROWTH: usize = 3;

/// Two successive cycle-number estimates of the endgame agree when they differ by at
/// most this fraction of the last.
const CYCLE_ESTIMATE_AGREEMENT: f64 = 0.1;

/// Radii after a failed direct finish at which the endgame waits for a stable
/// cycle-number estimate before it loops anyway.
const MAX_WAITING_RADII: usize = 4;

/// Largest ratio of successive Newton updates that [`Tracker::refines_to_regular_root`]
/// takes for quadratic convergence (at a double root each update is half the last).
const QUADRATIC_CONVERGENCE_RATIO: f64 = 0.01;

/// Exponent of the averaging test ([`is_averaged_estimate`]).
const AVERAGING_LOOP_EXPONENT: i32 = 10;

/// Whether a singular endpoint of winding number `c ≥ 2` with residual `residual` and
/// max-norm `norm` is the average of distinct roots rather than a root: its residual
/// exceeds `10^(min(c, 10) − 10)` relative to `1 + norm`. A Cauchy loop whose radius
/// encloses two nearby nonsingular roots closes after two turns, and its estimate,
/// stable from radius to radius, is their mean: PHCpack's `discret3s` at seed 7
/// counted two such means (residual 4.5·10⁻⁶ relative) as double roots. The genuine
/// singular endpoints of the demo suite (three seeds) stay far below the bound:
/// winding 2 at most 1.7·10⁻¹³ (`caprasse`), 3 at 8·10⁻¹³, 8 and 9 at 3·10⁻⁹ and
/// 1.3·10⁻⁸ (`cohn3`).
pub(crate) fn is_averaged_estimate(winding: usize, residual: f64, norm: f64) -> bool {
    let exponent = (winding as i32).min(AVERAGING_LOOP_EXPONENT) - AVERAGING_LOOP_EXPONENT;
    winding >= 2 && residual > 10f64.powi(exponent) * (1.0 + norm)
}

/// The endgame's per-path buffers: Cauchy sums and estimates, valuations and their
/// history (allocated once per tracker).
pub(super) struct EndgameState {
    cauchy_sum: Vec<C64>,
    estimate: Vec<C64>,
    previous_estimate: Vec<C64>,
    valuations: Vec<f64>,
    previous_valuations: Vec<f64>,
    log_sum: Vec<f64>,
    pub(super) log_mean: Vec<f64>,
    previous_log_mean: Vec<f64>,
    pub(super) loop_valuations: Vec<f64>,
    previous_loop_valuations: Vec<f64>,
    /// `max(1, |x_i|)` at the start of the endgame (see [`MIN_COORDINATE_GROWTH`]).
    pub(super) endgame_origin: Vec<f64>,
    /// Change of each valuation between the last two radii of the endgame.
    valuation_changes: Vec<f64>,
    /// The direct finish's singular endpoint (`settle_on_direct_endpoint`).
    direct_endpoint: Vec<C64>,
    /// The path's point at the previous radius of the endgame (for the cycle-number
    /// estimate of [`Tracker::endgame`]).
    radius_point: Vec<C64>,
    /// The endgame's last valuation check found stable negative valuations.
    divergence_evidence: bool,
    /// [`Tracker::give_up`] put the path at infinity on that evidence.
    pub(super) gave_up_at_infinity: bool,
    /// The endgame's first radius `s₀` (loops there make at most
    /// [`FIRST_RADIUS_MAX_WINDING`] turns); infinite outside an endgame.
    pub(super) first_radius: f64,
}

impl EndgameState {
    /// Buffers for `n` unknowns.
    pub(super) fn new(n: usize) -> Self {
        let zero = C64::new(0.0, 0.0);
        EndgameState {
            cauchy_sum: vec![zero; n],
            direct_endpoint: vec![zero; n],
            radius_point: vec![zero; n],
            estimate: vec![zero; n],
            previous_estimate: vec![zero; n],
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
            gave_up_at_infinity: false,
            first_radius: f64::INFINITY,
        }
    }
}

impl<H: Homotopy + ?Sized> Tracker<'_, H> {
    /// The endgame from `t = 1 − s0` (see the module documentation).
    pub(super) fn endgame(&mut self, s0: f64) -> PathStatus {
        let n = self.n;
        let mut s = s0;
        self.state.first_radius = s0;
        let mut direct_failed = false;
        let mut have_valuations = false;
        let mut have_estimate = false;
        let mut previous_condition = f64::INFINITY;
        // Successive radii at which the condition number grew (`condition_stable`
        // false).
        let mut condition_growing = 0;
        let mut stable_divergence = 0;
        // Successive radii at which a grown coordinate had a negative valuation.
        let mut grown_divergence = 0;
        // Cauchy-loop valuations: by Jensen's formula the mean of log|x_i| over the
        // loop is exactly `log|a_i| + w_i log s` once the radius is small, so two
        // consecutive differences agreeing pin the valuation `w_i` down.
        let mut loops_done = 0;
        let mut previous_loop_radius = 0.0f64;
        let mut have_direct_endpoint = false;
        // Successive radii with a stable positive valuation of the homogenising
        // coordinate (`homogenizing_valuation_test`).
        let mut vanishing = 0;
        self.state.divergence_evidence = false;
        self.state
            .valuation_changes
            .iter_mut()
            .for_each(|c| *c = f64::NAN);
        for (o, x) in self.state.endgame_origin.iter_mut().zip(&self.x) {
            *o = x.norm().max(1.0);
        }
        // The cycle-number estimate from the path's points at three successive radii
        // (`x(s) = x₀ + a s^{1/c} + …` moves by factors `r^{1/c}`, `r` the radius
        // ratio): `c ≈ ln r / ln ρ`, `ρ` the ratio of the last two moves (the
        // estimate of Morgan, Sommese and Wampler, "A power series method for
        // computing singular solutions to nonlinear analytic systems", Numer. Math.
        // 1992).
        let mut previous_move = f64::NAN;
        let mut previous_cycle_estimate = f64::NAN;
        let mut have_radius_point = false;
        // Radii at which a loop after a failed direct finish waited for the estimate.
        let mut waited = 0;
        // Successive radii at which the condition number was stable.
        let mut settled = 0;
        loop {
            let t = C64::new(1.0 - s, 0.0);
            let mut cycle_estimate_stable = false;
            if have_radius_point {
                let moved = self
                    .x
                    .iter()
                    .zip(&self.state.radius_point)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
                let cycle = self.options.endgame.endgame_ratio.ln() / (moved / previous_move).ln();
                cycle_estimate_stable = cycle.is_finite()
                    && cycle > 0.0
                    && (cycle - previous_cycle_estimate).abs() <= CYCLE_ESTIMATE_AGREEMENT * cycle;
                previous_cycle_estimate = cycle;
                previous_move = moved;
            }
            self.state.radius_point.copy_from_slice(&self.x);
            have_radius_point = true;
            let scale = max_norm(&self.x);
            if scale > self.options.endgame.at_infinity_norm {
                return PathStatus::AtInfinity;
            }
            // Valuations from dx/ds (dt/ds = −1).
            let ok =
                self.eval
                    .velocity(self.homotopy, &self.x, t, C64::new(-1.0, 0.0), &mut self.k1);
            let condition = if ok {
                self.eval.condition_estimate()
            } else {
                f64::INFINITY
            };
            let mut diverging = false;
            let mut vanishing_now = false;
            if ok {
                for i in 0..n {
                    self.state.valuations[i] = if self.x[i].norm() > 0.0 {
                        (self.k1[i] * s / self.x[i]).re
                    } else {
                        0.0
                    };
                }
                if let Some(h) = self
                    .homotopy
                    .homogenizing_variable()
                    .filter(|_| self.options.endgame.homogenizing_valuation_test)
                {
                    let (v, previous) =
                        (self.state.valuations[h], self.state.previous_valuations[h]);
                    vanishing = if have_valuations
                        && v > self.options.endgame.valuation_threshold
                        && (v - previous).abs() <= 0.01
                    {
                        vanishing + 1
                    } else {
                        0
                    };
                    if vanishing >= 2 {
                        return PathStatus::AtInfinity;
                    }
                    // Heading for the hyperplane at infinity: no Cauchy loop around the
                    // (singular) point there; the next radius decides.
                    vanishing_now = v > self.options.endgame.valuation_threshold;
                }
                let mut stable = have_valuations;
                let mut smallest = f64::INFINITY;
                let mut smallest_grown = f64::INFINITY;
                for i in 0..n {
                    if self.x[i].norm() >= 1.0 {
                        // A grown coordinate's valuation may still drift (the correction
                        // terms of x_i ~ a s^v (1 + b s^{1/c}) decay slowly for large
                        // winding numbers c): falling further is divergence, and so is a
                        // rise that slows down geometrically (ratio q ≤ 0.6) towards a
                        // negative limit v + Δ·q/(1 − q) (Aitken's extrapolation); a
                        // rise towards 0 (a large finite limit being approached)
                        // accelerates and is not stable.
                        let change = self.state.valuations[i] - self.state.previous_valuations[i];
                        let ratio = change / self.state.valuation_changes[i];
                        let converging = have_valuations
                            && (0.0..=0.6).contains(&ratio)
                            && self.state.valuations[i] + change * ratio / (1.0 - ratio)
                                < -self.options.endgame.valuation_threshold;
                        if change.abs() > 0.01
                            && !(self.options.endgame.growth_before_divergence
                                && self.has_grown(i)
                                && (change
                                    <= GROWN_VALUATION_DRIFT * self.state.valuations[i].abs()
                                    || converging))
                        {
                            stable = false;
                        }
                        self.state.valuation_changes[i] = change;
                        smallest = smallest.min(self.state.valuations[i]);
                        if self.has_grown(i) {
                            smallest_grown = smallest_grown.min(self.state.valuations[i]);
                        }
                    }
                }
                diverging = smallest < -self.options.endgame.valuation_threshold && scale >= 10.0;
                // Below DEEP_RADIUS the resolution of t ends the endgame soon anyway: a
                // stable negative valuation decides without growth.
                let deep = s <= DEEP_RADIUS;
                let threshold = -self.options.endgame.valuation_threshold;
                if stable && (smallest_grown < threshold || deep && smallest < threshold) {
                    stable_divergence += 1;
                    if stable_divergence >= 2 {
                        return PathStatus::AtInfinity;
                    }
                } else {
                    stable_divergence = 0;
                }
                grown_divergence = if smallest_grown < threshold {
                    grown_divergence + 1
                } else {
                    0
                };
                self.state.divergence_evidence =
                    stable && smallest < threshold || grown_divergence >= 2;
                self.state
                    .previous_valuations
                    .copy_from_slice(&self.state.valuations);
                have_valuations = true;
            }
            // The direct finish needs every coordinate to stay bounded, including ones
            // still below 1 that have begun to diverge: a multiplier growing like 1/s
            // (a critical point escaping to infinity at t = 1 while K′ converges) is
            // only ~0.2 at s = 0.025, and a straight run to t = 1 from there can jump
            // onto another path's endpoint. Coordinates below DIRECT_FINISH_FLOOR are
            // ignored (their valuations are noise when they pass near 0).
            let valuations_finite = have_valuations
                && (0..n).all(|i| {
                    self.x[i].norm() < DIRECT_FINISH_FLOOR
                        || self.state.valuations[i] > -self.options.endgame.valuation_threshold
                });
            // A singular endpoint shows as a condition number growing like
            // s^{-(1 - 1/c)} (factor ≥ 2 per checkpoint for c ≥ 2 and r = 1/4).
            let condition_stable = condition <= 1.5 * previous_condition;
            condition_growing = if condition_stable {
                0
            } else {
                condition_growing + 1
            };
            previous_condition = condition;
            settled = if condition_stable { settled + 1 } else { 0 };
            let settled_below_singular = self.options.endgame.direct_finish_at_settled_condition
                && settled >= 2
                && condition < self.options.endgame.singular_condition;
            if !direct_failed
                && valuations_finite
                && condition_stable
                && (condition < self.options.endgame.direct_finish_condition
                    || settled_below_singular)
            {
                self.x_checkpoint.copy_from_slice(&self.x);
                let saved_step = self.step;
                let reached = self.segment_within(t, C64::new(1.0, 0.0), DIRECT_FINISH_STEPS);
                if reached {
                    let (converged, _) = self.refine_at(C64::new(1.0, 0.0));
                    let final_condition = self.condition_at(C64::new(1.0, 0.0));
                    if converged
                        && final_condition < self.options.endgame.singular_condition
                        && final_condition < 100.0 * condition
                    {
                        return PathStatus::Nonsingular;
                    }
                    if self.options.endgame.settle_on_direct_endpoint
                        && self.residual_small_at_one(false)
                    {
                        self.state.direct_endpoint.copy_from_slice(&self.x);
                        have_direct_endpoint = true;
                    }
                }
                self.x.copy_from_slice(&self.x_checkpoint);
                self.t = t;
                self.step = saved_step;
                direct_failed = true;
            }
            // After a failed direct finish (a singular endpoint ahead), loops only once
            // the path moves like a Puiseux series (a stable cycle-number estimate),
            // in the deep zone, or after MAX_WAITING_RADII radii: further out a loop
            // encloses other branch points and runs many turns in vain (PHCpack's
            // `fbrfive4`: loops of 4–14 turns at radii 1.6·10⁻³ … 10⁻⁴, 400–600
            // steps per path, before the winding number 1 of its singular endpoints).
            let loop_after_direct = direct_failed
                && (cycle_estimate_stable
                    || !valuations_finite
                    || s <= DEEP_RADIUS
                    || waited >= MAX_WAITING_RADII);
            if direct_failed && !loop_after_direct {
                waited += 1;
            }
            // While the large coordinates still grow (negative valuations), the path is
            // heading to infinity or has not reached the endgame's asymptotic regime:
            // a Cauchy loop (costly far out, where the Jacobian is ill-conditioned)
            // would not close on a finite estimate; the next radius is cheaper and the
            // valuation test above classifies a divergent path.
            if !diverging
                && !vanishing_now
                && (loop_after_direct
                    || condition_growing >= SINGULAR_CONDITION_GROWTH
                        && valuations_finite
                        && s <= DEEP_RADIUS
                    || condition >= self.options.endgame.direct_finish_condition)
            {
                match self.cauchy_loop(s) {
                    Ok(c) => {
                        if loops_done >= 1 {
                            let log_ratio = (s / previous_loop_radius).ln();
                            for i in 0..n {
                                self.state.loop_valuations[i] = (self.state.log_mean[i]
                                    - self.state.previous_log_mean[i])
                                    / log_ratio;
                            }
                            if loops_done >= 2 {
                                let stable = (0..n).all(|i| {
                                    (self.state.loop_valuations[i]
                                        - self.state.previous_loop_valuations[i])
                                        .abs()
                                        < 1e-3
                                });
                                let deep = s <= DEEP_RADIUS;
                                let smallest = (0..n)
                                    .filter(|&i| deep || self.has_grown(i))
                                    .fold(f64::INFINITY, |a, i| {
                                        a.min(self.state.loop_valuations[i])
                                    });
                                if stable && smallest < -self.options.endgame.valuation_threshold {
                                    return PathStatus::AtInfinity;
                                }
                            }
                            if self.puiseux_exponents_at_infinity(c, s) {
                                return PathStatus::AtInfinity;
                            }
                            self.state
                                .previous_loop_valuations
                                .copy_from_slice(&self.state.loop_valuations);
                        }
                        self.state
                            .previous_log_mean
                            .copy_from_slice(&self.state.log_mean);
                        previous_loop_radius = s;
                        loops_done += 1;
                        let scale = 1.0 + max_norm(&self.state.estimate);
                        let change = self
                            .state
                            .estimate
                            .iter()
                            .zip(&self.state.previous_estimate)
                            .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
                        self.state
                            .previous_estimate
                            .copy_from_slice(&self.state.estimate);
                        if have_estimate
                            && change <= self.options.endgame.endgame_tolerance * scale
                            && self.estimate_residual_small()
                            && !(self.options.endgame.reject_averaging_loops
                                && self.estimate_is_averaged(c))
                        {
                            self.winding = c;
                            return self.classify_estimate(c);
                        }
                        self.winding = c;
                        have_estimate = true;
                    }
                    Err(RouteStop::Diverged) => return PathStatus::AtInfinity,
                    Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge)) => {
                        if have_direct_endpoint {
                            self.x.copy_from_slice(&self.state.direct_endpoint);
                            self.t = C64::new(1.0, 0.0);
                            return PathStatus::Singular;
                        }
                    }
                    Err(RouteStop::Failed(reason)) => {
                        return self.give_up(have_estimate, reason);
                    }
                }
            }
            let s_next = s * self.options.endgame.endgame_ratio;
            if s_next < self.options.endgame.endgame_min_radius {
                return self.give_up(have_estimate, FailureReason::EndgameDidNotConverge);
            }
            match self.track_segment(t, C64::new(1.0 - s_next, 0.0)) {
                Ok(()) => s = s_next,
                Err(RouteStop::Diverged) => return PathStatus::AtInfinity,
                Err(RouteStop::Failed(reason)) => return self.give_up(have_estimate, reason),
            }
        }
    }

    /// Whether coordinate `i` has grown by [`MIN_COORDINATE_GROWTH`] since the start of
    /// the endgame (relative to `max(1, |x_i(s₀)|)`): only such a coordinate's negative
    /// valuation classifies a path as diverging (in either endgame, with or without
    /// `growth_before_divergence`). A path to a large finite point `a/(s + ε)` has the
    /// valuation −1 of a pole until `s` nears `ε`: on two base anchors 10⁻⁴ apart the
    /// classic test sent such `rigid/rigid` critical points (multipliers of 10³–10⁵)
    /// to infinity at the seed, and the poses, expecting the 88 a real pose has, lost
    /// them.
    fn has_grown(&self, i: usize) -> bool {
        self.x[i].norm() >= MIN_COORDINATE_GROWTH * self.state.endgame_origin[i]
    }

    /// End of the endgame without converged estimates: the last Cauchy estimate if
    /// there is one with winding number above 1, or with winding number 1 below
    /// `s = DEEP_RADIUS` where `settle_on_stalled_estimate` asks for it (classified by
    /// [`Tracker::classify_estimate`]); else at infinity if the last
    /// valuations were negative and stable (agreeing at two successive radii: a slowly
    /// diverging path whose step size reached the resolution of `t` before it grew by
    /// [`MIN_COORDINATE_GROWTH`]) or a coordinate grown by that factor had negative
    /// valuations at the last two radii; else failure.
    pub(super) fn give_up(&mut self, have_estimate: bool, reason: FailureReason) -> PathStatus {
        // With winding number 1 only deep in the endgame and where the options ask
        // for it (`settle_on_stalled_estimate`); without an estimate there is
        // nothing to settle on (and `previous_estimate` may be another path's).
        let settle = have_estimate
            && (self.winding > 1
                || (self.options.endgame.settle_on_stalled_estimate
                    && (C64::new(1.0, 0.0) - self.t).norm() <= DEEP_RADIUS
                    && self.stalled_at_singular_point()));
        if settle && {
            self.state
                .estimate
                .copy_from_slice(&self.state.previous_estimate);
            self.estimate_residual_small()
        } {
            self.classify_estimate(self.winding)
        } else if have_estimate
            && self.winding == 1
            && self.options.endgame.settle_on_stalled_estimate
            && (C64::new(1.0, 0.0) - self.t).norm() <= DEEP_RADIUS
            && self.refines_to_regular_root()
        {
            PathStatus::Nonsingular
        } else if self.options.endgame.growth_before_divergence && self.state.divergence_evidence {
            self.state.gave_up_at_infinity = true;
            PathStatus::AtInfinity
        } else {
            PathStatus::Failed(reason)
        }
    }

    /// Whether Newton's method at `t = 1` from the last Cauchy estimate
    /// (`previous_estimate`) converges *quadratically* to a root whose equilibrated
    /// condition number ([`Tracker::equilibrated_condition_at`]) is below
    /// `singular_condition`: a regular root too badly scaled for the loops' estimates
    /// to agree to the endgame's tolerance. Its raw condition number may exceed
    /// `singular_condition` (PHCpack's `cohn3`: a root of norm 10⁴, found by neither
    /// PHCpack nor singdist before, condition 10¹¹ in the scaled variables, 10⁵ after
    /// equilibration). Equilibration alone does not prove regularity (at a double root
    /// a Jacobian row may vanish with the distance to it, and dividing it by its size
    /// hides that), so some Newton update must have been at most
    /// [`QUADRATIC_CONVERGENCE_RATIO`] of the one before (they halve at a double
    /// root; on `cohn3`'s root 2.4·10⁻⁶ → 4.2·10⁻¹⁴). If so the tracker stays at that
    /// root; else it is left where it was.
    fn refines_to_regular_root(&mut self) -> bool {
        self.x_checkpoint.copy_from_slice(&self.x);
        let t_checkpoint = self.t;
        self.x.copy_from_slice(&self.state.previous_estimate);
        self.t = C64::new(1.0, 0.0);
        let (converged, _) = self.refine_at(self.t);
        if converged
            && self.refinement_contraction <= QUADRATIC_CONVERGENCE_RATIO
            && self.equilibrated_condition_at(self.t) < self.options.endgame.singular_condition
        {
            return true;
        }
        self.x.copy_from_slice(&self.x_checkpoint);
        self.t = t_checkpoint;
        false
    }

    /// Whether the Jacobian at the last Cauchy estimate (`previous_estimate`, `t = 1`)
    /// is singular after equilibration ([`Tracker::equilibrated_condition_at`] above
    /// `singular_condition`): the stalled endgame of [`Tracker::give_up`] ends there
    /// only at a singular point, not at a badly scaled nonsingular root. Leaves `x` as
    /// it was.
    fn stalled_at_singular_point(&mut self) -> bool {
        self.x_checkpoint.copy_from_slice(&self.x);
        self.x.copy_from_slice(&self.state.previous_estimate);
        let condition = self.equilibrated_condition_at(C64::new(1.0, 0.0));
        self.x.copy_from_slice(&self.x_checkpoint);
        condition > self.options.endgame.singular_condition
    }

    /// Whether the valuations of the last two Cauchy loops (`loop_valuations`, from the
    /// loops' mean `ln|x_i|`) are the leading exponents of a Puiseux cycle of winding
    /// number `c` with a pole: every one within [`PUISEUX_EXPONENT_TOLERANCE`] of a
    /// multiple of `1/c`, and the smallest (of the coordinates that may decide
    /// divergence) negative. Once both loops lie inside the cycle's disc of
    /// convergence the mean of `ln|x_i|` over a loop is exactly `ln|a_i| + v_i ln s`
    /// (Jensen's formula: the series `x_i = a_i s^{v_i}(1 + b s^{1/c} + …)` has no
    /// zero there), so the exponents come out exact at the first pair of loops; the
    /// stability test of two successive pairs needs one radius more, and on cycles
    /// with `c ≥ 3` its velocity-based counterpart converges only like `s^{1/c}`,
    /// down to radii where the branches of the cycle come within the same-point
    /// tolerance of each other.
    pub(super) fn puiseux_exponents_at_infinity(&self, c: usize, s: f64) -> bool {
        let deep = s <= DEEP_RADIUS;
        let valuations = &self.state.loop_valuations;
        let c = c as f64;
        let rational = valuations
            .iter()
            .all(|v| (v * c - (v * c).round()).abs() <= PUISEUX_EXPONENT_TOLERANCE * c);
        let smallest = (0..self.n)
            .filter(|&i| deep || self.has_grown(i))
            .fold(f64::INFINITY, |a, i| a.min(valuations[i]));
        rational && smallest < -self.options.endgame.valuation_threshold
    }

    /// [`is_averaged_estimate`] of the Cauchy estimate of winding number `c`, its
    /// residual evaluated in extended precision.
    fn estimate_is_averaged(&mut self, c: usize) -> bool {
        let e = &mut self.eval;
        self.homotopy.evaluate_extended(
            &self.state.estimate,
            C64::new(1.0, 0.0),
            &mut e.work,
            &mut e.h,
        );
        is_averaged_estimate(c, max_norm(&e.h), max_norm(&self.state.estimate))
    }

    /// Whether `‖H(estimate, 1)‖∞ ≤ endpoint_residual · (1 + ‖estimate‖∞)^d̂` with a
    /// generous d̂ = 2 (a Cauchy mean of a diverging path has an O(1) residual).
    pub(super) fn estimate_residual_small(&mut self) -> bool {
        self.residual_small_at_one(true)
    }

    /// Whether `‖H(p, 1)‖∞ ≤ endpoint_residual · (1 + ‖p‖∞)²` at `p` the Cauchy
    /// estimate (`estimate`) or the current point.
    fn residual_small_at_one(&mut self, estimate: bool) -> bool {
        let point = if estimate {
            &self.state.estimate
        } else {
            &self.x
        };
        let e = &mut self.eval;
        self.homotopy
            .evaluate(point, C64::new(1.0, 0.0), &mut e.work, &mut e.h);
        let scale = 1.0 + max_norm(point);
        max_norm(&e.h) <= self.options.endgame.endpoint_residual * scale * scale
    }

    /// Moves to the Cauchy estimate and classifies it (winding number 1 endpoints are
    /// refined by Newton and are nonsingular if well conditioned).
    pub(super) fn classify_estimate(&mut self, winding: usize) -> PathStatus {
        self.x.copy_from_slice(&self.state.estimate);
        self.t = C64::new(1.0, 0.0);
        if winding == 1 {
            let (converged, _) = self.refine_at(C64::new(1.0, 0.0));
            if converged
                && self.condition_at(C64::new(1.0, 0.0)) < self.options.endgame.singular_condition
            {
                return PathStatus::Nonsingular;
            }
            self.x.copy_from_slice(&self.state.estimate);
        }
        PathStatus::Singular
    }

    /// [`Tracker::track_segment`] from `ta` to `tb` within `budget` more steps (and
    /// the path's own limit); whether `tb` was reached. The endgame's direct finish
    /// runs within [`DIRECT_FINISH_STEPS`]: one that crawls (accepted steps of 1e-17
    /// at t = 1 − 5e-9 for 29,000 steps, on a base similar to the platform) is
    /// heading for a near-singular endpoint, which the Cauchy loops estimate in a
    /// few dozen steps.
    pub(super) fn segment_within(&mut self, ta: C64, tb: C64, budget: usize) -> bool {
        let limit = self.step_limit;
        self.step_limit = limit.min(self.steps.saturating_add(budget));
        let reached = self.track_segment(ta, tb).is_ok();
        self.step_limit = limit;
        reached
    }

    /// Loops around `|1 − t| = s` until the path closes; the mean of the samples (in
    /// `self.state.estimate`) is the Cauchy-integral estimate of the endpoint. Returns `c`.
    ///
    /// A loop gets [`LOOP_STEPS_PER_SAMPLE`] steps per sample point and winding number
    /// on average. One that needs more passes close to another branch point of the
    /// path at this radius (a large radius can enclose more than the endpoint's own
    /// branch point): the path goes back to where the loop started and the endgame
    /// goes on to a smaller radius, as after [`FailureReason::WindingNumberTooLarge`]
    /// (which is returned). On a base congruent with the platform single loops took
    /// up to 1,900 steps where their winding numbers changed from radius to radius.
    pub(super) fn cauchy_loop(&mut self, s: f64) -> Result<usize, RouteStop> {
        let m = self.options.endgame.cauchy_samples_per_loop.max(3);
        let mut turns = self.options.endgame.max_winding_number.max(1);
        if s >= self.state.first_radius {
            turns = turns.min(FIRST_RADIUS_MAX_WINDING);
        }
        let budget = LOOP_STEPS_PER_SAMPLE * m * turns;
        let (limit, step) = (self.step_limit, self.step);
        self.step_limit = limit.min(self.steps.saturating_add(budget));
        let looped = self.loop_around(s, m, turns);
        let over_budget = self.steps >= self.step_limit && self.step_limit < limit;
        self.step_limit = limit;
        match looped {
            // A loop that did not close within the largest winding number ends on
            // another path's sheet (the radius encloses other branch points): the path
            // goes back to where the loop started, like one over its step budget.
            Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge)) => {
                self.x.copy_from_slice(&self.x_checkpoint);
                self.t = C64::new(1.0 - s, 0.0);
                self.step = step;
                self.factorization_current = false;
                Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
            }
            Err(RouteStop::Failed(FailureReason::TooManySteps))
                if over_budget && !self.precision.budget_spent(&self.options) =>
            {
                self.x.copy_from_slice(&self.x_checkpoint);
                self.t = C64::new(1.0 - s, 0.0);
                self.step = step;
                self.factorization_current = false;
                Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
            }
            other => other,
        }
    }

    /// [`Tracker::cauchy_loop`] within the current step limit, `m` samples per loop,
    /// at most `turns` turns.
    fn loop_around(&mut self, s: f64, m: usize, turns: usize) -> Result<usize, RouteStop> {
        self.x_checkpoint.copy_from_slice(&self.x);
        self.state
            .cauchy_sum
            .iter_mut()
            .for_each(|v| *v = C64::new(0.0, 0.0));
        self.state.log_sum.iter_mut().for_each(|v| *v = 0.0);
        let point = |j: usize| {
            C64::new(1.0, 0.0) - C64::from_polar(s, std::f64::consts::TAU * j as f64 / m as f64)
        };
        let mut extent: f64 = 0.0;
        for c in 1..=turns {
            for j in 0..m {
                for ((acc, log_acc), x) in self
                    .state
                    .cauchy_sum
                    .iter_mut()
                    .zip(self.state.log_sum.iter_mut())
                    .zip(&self.x)
                {
                    *acc += x;
                    *log_acc += x.norm().max(1e-300).ln();
                }
                self.track_segment(point(j), point(j + 1))?;
                let distance = self
                    .x
                    .iter()
                    .zip(&self.x_checkpoint)
                    .fold(0.0f64, |d, (a, b)| d.max((a - b).norm()));
                if j + 1 < m {
                    extent = extent.max(distance);
                } else {
                    let scale = 1.0 + max_norm(&self.x);
                    let noise = 100.0 * self.options.step.corrector_tolerance * scale;
                    if distance <= (1e-2 * extent).max(noise) {
                        let weight = 1.0 / (c * m) as f64;
                        for (e, acc) in self.state.estimate.iter_mut().zip(&self.state.cauchy_sum) {
                            *e = acc * weight;
                        }
                        for (l, acc) in self.state.log_mean.iter_mut().zip(&self.state.log_sum) {
                            *l = acc * weight;
                        }
                        return Ok(c);
                    }
                    extent = extent.max(distance);
                }
            }
        }
        Err(RouteStop::Failed(FailureReason::WindingNumberTooLarge))
    }
}

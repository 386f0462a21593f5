//! Newton's method at a fixed `t`: the refinement of an endpoint
//! ([`Tracker::refine_at`]), its condition number, and the correction of a predicted
//! point without path tracking ([`Tracker::correct_at`]).
//!
//! Both iterate `x ← x − J⁻¹H(x, t)` while the updates contract and go on in
//! double-double arithmetic where double-precision updates stagnate at the rounding
//! level of an ill-conditioned or far-out point (see [`super::precision`]).

use super::precision::NewtonUpdate;
use super::{
    CORRECT_AT_CONTRACTION, CORRECT_AT_EXTENDED_ITERATIONS, CORRECT_AT_EXTENDED_START,
    CORRECT_AT_ITERATIONS, FailureReason, Homotopy, PathResult, PathStatus, Tracker, max_norm,
};
use crate::C64;

/// Ratio of successive Newton updates above which [`Tracker::refine_at`] leaves double
/// precision: near a regular root each update is at most half the last (Smale's
/// α-theory), so a larger ratio is rounding noise or a singular root.
const REFINEMENT_STAGNATION: f64 = 0.5;

/// Newton iterations [`Tracker::refine_at`] has at least left after switching to
/// extended precision: its first update removes the double-precision iterate's error,
/// the next ones confirm quadratic convergence.
const EXTENDED_REFINEMENT_ITERATIONS: usize = 3;

impl<H: Homotopy + ?Sized> Tracker<'_, H> {
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
                        self.precision.used = true;
                        previous = f64::INFINITY;
                        continue;
                    }
                    break;
                }
            }
            if stagnated || norm <= 1e-11 * scale {
                // `eval.lu` holds J at the previous iterate, within 1e-9 of the limit.
                condition = self.eval.condition_estimate();
                status = if condition < self.options.endgame.singular_condition {
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

    pub(super) fn condition_at(&mut self, t: C64) -> f64 {
        let e = &mut self.eval;
        self.homotopy
            .evaluate_with_jacobian(&self.x, t, &mut e.work, &mut e.h, &mut e.jac);
        if e.lu.factor(&e.jac) {
            e.lu.condition_estimate()
        } else {
            f64::INFINITY
        }
    }

    /// Condition estimate of `∂H/∂x` at `(x, t)` after row and column equilibration
    /// (each row, then each column, divided by its largest modulus): diagonal scalings
    /// do not change the rank, so a singular Jacobian stays ill-conditioned, while a
    /// nonsingular root whose coordinates or equations are badly scaled (PHCpack's
    /// `comb3000` unscaled, coordinates down to 10⁻¹¹) comes out well conditioned.
    pub(super) fn equilibrated_condition_at(&mut self, t: C64) -> f64 {
        let n = self.n;
        let e = &mut self.eval;
        self.homotopy
            .evaluate_with_jacobian(&self.x, t, &mut e.work, &mut e.h, &mut e.jac);
        for row in e.jac.chunks_mut(n) {
            let largest = row.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            if largest > 0.0 {
                row.iter_mut().for_each(|v| *v /= largest);
            }
        }
        for j in 0..n {
            let largest = (0..n).fold(0.0f64, |m, i| m.max(e.jac[i * n + j].norm()));
            if largest > 0.0 {
                (0..n).for_each(|i| e.jac[i * n + j] /= largest);
            }
        }
        if e.lu.factor(&e.jac) {
            e.lu.condition_estimate()
        } else {
            f64::INFINITY
        }
    }

    /// Newton refinement at `t`, keeping the best iterate; returns (converged, ‖Δ‖)
    /// and leaves the smallest ratio of successive updates (within one precision) in
    /// `refinement_contraction`.
    /// In double precision (unless the tracker is in extended mode) while each update
    /// is at most half the last ([`REFINEMENT_STAGNATION`]); where they stagnate
    /// above `10⁻¹³` relative (rounding noise of an ill-conditioned point, or a
    /// Jacobian rounded there) the remaining iterations, at least
    /// [`EXTENDED_REFINEMENT_ITERATIONS`], run in extended precision.
    pub(super) fn refine_at(&mut self, t: C64) -> (bool, f64) {
        let mut previous = f64::INFINITY;
        let mut converged = false;
        self.refinement_contraction = f64::INFINITY;
        let mut extended = self.precision.extended;
        let mut remaining = self.options.endgame.refinement_iterations;
        while remaining > 0 {
            remaining -= 1;
            self.x_saved.copy_from_slice(&self.x);
            match self.eval.newton(self.homotopy, &mut self.x, t, extended) {
                NewtonUpdate::Singular => {
                    self.x.copy_from_slice(&self.x_saved);
                    break;
                }
                NewtonUpdate::Step(norm) => {
                    let scale = 1.0 + max_norm(&self.x);
                    if previous.is_finite() && previous > 0.0 {
                        self.refinement_contraction =
                            self.refinement_contraction.min(norm / previous);
                    }
                    if norm <= 1e-13 * scale {
                        converged = true;
                        previous = norm;
                        break;
                    }
                    if !extended && norm > REFINEMENT_STAGNATION * previous {
                        // Double precision stagnates: rounding noise of an
                        // ill-conditioned point (or the linear convergence at a
                        // singular one). A worse iterate is dropped; extended
                        // precision takes over, its first update measuring the error
                        // of the double-precision iterate.
                        if norm > previous {
                            self.x.copy_from_slice(&self.x_saved);
                        }
                        extended = true;
                        previous = f64::INFINITY;
                        remaining = remaining.max(EXTENDED_REFINEMENT_ITERATIONS);
                        continue;
                    }
                    if norm > previous {
                        // No longer contracting in extended precision: keep the
                        // previous iterate; if its update was already at rounding level
                        // for the condition of the point (below 1e-9 relative), that
                        // is the attainable accuracy: converged.
                        self.x.copy_from_slice(&self.x_saved);
                        converged = previous <= 1e-9 * scale;
                        break;
                    }
                    previous = norm;
                }
            }
        }
        (converged, previous)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::tracker::tests::on_square;
    use crate::homotopy::{Homotopy, TrackerOptions};

    #[test]
    fn correct_at_converges_to_the_nearest_root_and_counts_its_updates() {
        let result = on_square(0.0, 1.0, |tracker| {
            tracker.correct_at(&[C64::new(-1.3, 0.0)], 1.0, 7)
        });
        assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
        assert_eq!(result.path_index, 7);
        assert!(
            (result.solution[0] + 2.0f64.sqrt()).norm() < 1e-14,
            "{result:?}"
        );
        assert!(result.steps >= 3 && result.steps <= CORRECT_AT_ITERATIONS);
        assert!(result.residual < 1e-14);
    }

    /// From `x = 0` the Jacobian `2x` of `x² − 2` is singular: no update at all.
    #[test]
    fn correct_at_fails_at_a_singular_jacobian() {
        let result = on_square(0.0, 1.0, |tracker| {
            tracker.correct_at(&[C64::new(0.0, 0.0)], 1.0, 0)
        });
        assert_eq!(
            result.status,
            PathStatus::Failed(FailureReason::CorrectorDidNotConverge),
            "{result:?}"
        );
    }

    /// A regular root of condition 4·10¹⁰ (two nearly parallel lines): in double
    /// precision Newton's updates are rounding noise of about 10⁻⁶, neither shrinking
    /// nor growing steadily; the refinement switches to extended precision, where two
    /// updates reach the root.
    #[test]
    fn refinement_of_an_ill_conditioned_root_converges_in_extended_precision() {
        use crate::homotopy::test_support::read_xy;
        use crate::homotopy::{StraightLineHomotopy, TotalDegreeStartSystem};
        let target = read_xy("f = x + y - 2;\ng = x + 1.0000000001*y - 2.0000000001;");
        let start = TotalDegreeStartSystem::new(vec![1, 1]);
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], C64::new(0.6, 0.8));
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        let one = C64::new(1.0, 0.0);
        for offset in [1e-3, 1e-6, -3e-5] {
            tracker.reset(
                &[C64::new(1.0 + offset, 0.0), C64::new(1.0 - offset, 0.0)],
                1.0,
            );
            let (converged, last) = tracker.refine_at(one);
            assert!(converged, "offset {offset}: last update {last:e}");
            assert!(tracker.condition_at(one) > 1e10);
            let error = (tracker.x[0] - one).norm().max((tracker.x[1] - one).norm());
            assert!(error < 1e-4, "offset {offset}: {:?}", tracker.x);
        }
    }

    /// `H(x, t) = x − 1` whose double-precision Jacobian is off by a factor 5 (as a
    /// Jacobian rounded at an ill-conditioned point is) while the extended one is
    /// exact: Newton's updates in double precision shrink by 0.8 each, never growing.
    struct InaccurateDoubleJacobian;

    impl Homotopy for InaccurateDoubleJacobian {
        fn dimension(&self) -> usize {
            1
        }
        fn workspace_len(&self) -> usize {
            0
        }
        fn evaluate(&self, x: &[C64], _: C64, _: &mut [C64], h: &mut [C64]) {
            h[0] = x[0] - 1.0;
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
            jac[0] = C64::new(5.0, 0.0);
        }
        fn evaluate_time_derivative(&self, _: &[C64], _: C64, _: &mut [C64], dh: &mut [C64]) {
            dh[0] = C64::new(0.0, 0.0);
        }
        fn evaluate_with_jacobian_extended(
            &self,
            x: &[C64],
            t: C64,
            work: &mut [C64],
            h: &mut [C64],
            (jac, jac_low): (&mut [C64], &mut [C64]),
        ) {
            self.evaluate(x, t, work, h);
            jac[0] = C64::new(1.0, 0.0);
            jac_low[0] = C64::new(0.0, 0.0);
        }
    }

    /// Double-precision updates that contract only linearly (by 0.8 here) hand over
    /// to extended precision, which converges; before, six such updates ended the
    /// refinement unconverged.
    #[test]
    fn linearly_contracting_double_updates_hand_over_to_extended_precision() {
        let homotopy = InaccurateDoubleJacobian;
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        let one = C64::new(1.0, 0.0);
        tracker.reset(&[C64::new(1.5, 0.0)], 1.0);
        let (converged, _) = tracker.refine_at(one);
        assert!(converged);
        assert!((tracker.x[0] - one).norm() < 1e-15, "{:?}", tracker.x);
    }

    #[test]
    fn refinement_reaches_full_accuracy_and_reports_the_condition() {
        on_square(1.4, 1.0, |tracker| {
            let (converged, _) = tracker.refine_at(C64::new(1.0, 0.0));
            assert!(converged);
            assert!((tracker.x[0] - 2.0f64.sqrt()).norm() < 1e-15);
            // One unknown: the 1-norm condition number of a nonzero 1×1 matrix is 1.
            assert_eq!(tracker.condition_at(C64::new(1.0, 0.0)), 1.0);
        });
    }
}

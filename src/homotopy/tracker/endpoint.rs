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

    /// Newton refinement at `t`, keeping the best iterate; returns (converged, ‖Δ‖).
    /// In double precision (unless the tracker is in extended mode) while the updates
    /// contract; where they stagnate above `10⁻¹³` relative (rounding noise of an
    /// ill-conditioned point) the remaining iterations run in extended precision.
    pub(super) fn refine_at(&mut self, t: C64) -> (bool, f64) {
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut extended = self.precision.extended;
        for _ in 0..self.options.endgame.refinement_iterations {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::tracker::tests::on_square;

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

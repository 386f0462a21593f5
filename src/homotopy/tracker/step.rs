//! One predictor–corrector step and the step-size control (see the module
//! documentation of [`super`]).
//!
//! The predictor is the classical fourth-order Runge–Kutta method on the Davidenko
//! equation `∂H/∂x · ẋ = −∂H/∂t`, so its local error is `≈ C h⁵`. The corrector's
//! first Newton update `‖Δ₀‖` measures that error, and the next step is
//! `h·0.9·(ε_pred/e)^{1/5}` with `e = ‖Δ₀‖/(1 + ‖x‖∞)`, clamped to `[½, 2]` — the
//! standard error-per-step controller (Hairer, Nørsett & Wanner, "Solving Ordinary
//! Differential Equations I", 1993, §II.4). A rejected step halves `h`.

use super::{Homotopy, NewtonUpdate, Tracker, TrackerOptions, max_norm};
use crate::C64;

/// Smallest step in `t` (absolute): `t` near 1 is resolved to `ε ≈ 2.2·10⁻¹⁶`, and
/// steps below a few of its units no longer move the path (they only re-evaluate the
/// homotopy at the same rounded `t`).
pub(super) const MIN_ABSOLUTE_STEP: f64 = 1e-15;

/// Factor of the next step after an accepted one with relative predictor error
/// `error` (`‖Δ₀‖/(1 + ‖x‖∞)`): `0.9·(tolerance/error)^{1/5}` clamped to `[½, 2]`,
/// and 2 for an exact prediction.
pub(super) fn step_factor(error: f64, tolerance: f64) -> f64 {
    if error > 0.0 {
        (0.9 * (tolerance / error).powf(0.2)).clamp(0.5, 2.0)
    } else {
        2.0
    }
}

/// The fraction `h` of a segment of length `length` for the next step from fraction
/// `u`: the step length (at most `max_step`) over the segment's length, cut at the
/// segment's end, and stretched to the end where less than 5 % of `h` would remain.
pub(super) fn step_fraction(step: f64, max_step: f64, length: f64, u: f64) -> f64 {
    let mut h = (step.min(max_step) / length).min(1.0 - u);
    if 1.0 - u - h < 0.05 * h {
        h = 1.0 - u;
    }
    h
}

/// Smallest step, as a fraction of a segment of length `length`, below which the
/// tracker switches to extended precision and then fails: `min_step_fraction`, with
/// the growth-before-divergence endgame also at least [`MIN_ABSOLUTE_STEP`] in `t`.
pub(super) fn step_floor(options: &TrackerOptions, length: f64) -> f64 {
    if options.endgame.growth_before_divergence {
        options
            .step
            .min_step_fraction
            .max(MIN_ABSOLUTE_STEP / length)
    } else {
        options.step.min_step_fraction
    }
}

impl<H: Homotopy + ?Sized> Tracker<'_, H> {
    /// RK4 prediction from `(x, t)` to `t_new` into `x_predicted` (on a stiff stretch,
    /// Hermite extrapolation: [`super::hermite`]).
    pub(super) fn predict(
        &mut self,
        t: C64,
        t_mid: C64,
        t_new: C64,
        dt: C64,
        h: f64,
    ) -> Option<()> {
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
        self.hermite.record(t, &self.x, &self.k1);
        if self.hermite.extrapolate(dt, h, &mut self.x_predicted) {
            return Some(());
        }
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
    pub(super) fn correct(&mut self, t: C64) -> Option<f64> {
        let mut first = 0.0;
        let mut previous = 0.0;
        for k in 0..self.options.step.max_corrector_iterations.max(1) {
            let norm = match self.eval.newton(
                self.homotopy,
                &mut self.x_predicted,
                t,
                self.precision.extended,
            ) {
                NewtonUpdate::Step(norm) => norm,
                NewtonUpdate::Singular => return None,
            };
            let scale = 1.0 + max_norm(&self.x_predicted);
            let tolerance = self.options.step.corrector_tolerance * scale;
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
                let noise = self.options.step.corrector_noise_tolerance * scale;
                if norm <= noise && previous <= 10.0 * noise {
                    return Some(first);
                }
                if norm > self.options.step.max_contraction * previous {
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
    use crate::homotopy::tracker::tests::on_square;

    #[test]
    fn the_step_factor_holds_the_error_at_the_tolerance_and_is_clamped() {
        assert_eq!(step_factor(1e-6, 1e-6), 0.9);
        // Error 32 times the tolerance: (1/32)^{1/5} = 1/2, times 0.9, clamped.
        assert_eq!(step_factor(32e-6, 1e-6), 0.5);
        let grow = step_factor(1e-6 / 1.5f64.powi(5), 1e-6);
        assert!((grow - 1.35).abs() < 1e-12, "{grow}");
        assert_eq!(step_factor(1e-20, 1e-6), 2.0);
        assert_eq!(step_factor(0.0, 1e-6), 2.0);
    }

    #[test]
    fn the_step_fraction_is_cut_and_stretched_at_the_segment_end() {
        assert_eq!(step_fraction(0.05, 0.1, 2.0, 0.0), 0.025);
        assert_eq!(step_fraction(0.5, 0.1, 1.0, 0.0), 0.1);
        assert_eq!(step_fraction(0.1, 0.1, 1.0, 0.95), 1.0 - 0.95);
        // 0.004 would remain after a step of 0.1: less than 5 %, so go to the end.
        assert_eq!(step_fraction(0.1, 0.1, 1.0, 0.896), 1.0 - 0.896);
        assert_eq!(step_fraction(0.1, 0.1, 1.0, 0.5), 0.1);
    }

    #[test]
    fn the_absolute_step_floor_applies_with_growth_before_divergence_only() {
        let classic = TrackerOptions::default();
        assert_eq!(step_floor(&classic, 1e-7), classic.step.min_step_fraction);
        let mut growth = TrackerOptions::default();
        growth.endgame.growth_before_divergence = true;
        assert_eq!(step_floor(&growth, 1.0), growth.step.min_step_fraction);
        assert_eq!(step_floor(&growth, 1e-7), MIN_ABSOLUTE_STEP / 1e-7);
    }

    /// One step of `x(t) = √(1 + t)` from `t = 0` to `0.1`: the RK4 prediction is
    /// within `O(h⁵)` of the path (5.5·10⁻⁹ here), the corrector's first update
    /// measures that error, and the corrected point is on the path.
    #[test]
    fn one_predictor_corrector_step_follows_the_path() {
        on_square(1.0, 0.0, |tracker| {
            let (t, dt) = (C64::new(0.0, 0.0), C64::new(1.0, 0.0));
            let h = 0.1;
            assert!(tracker.predict(t, t + 0.5 * h, t + h, dt, h).is_some());
            let exact = 1.1f64.sqrt();
            let error = (tracker.x_predicted[0] - exact).norm();
            assert!(error > 1e-9 && error < 1e-8, "{error}");
            let first = tracker.correct(t + h).expect("accepted");
            assert!((first - error).abs() < 1e-3 * error, "{first} vs {error}");
            assert!((tracker.x_predicted[0] - exact).norm() < 1e-15);
        });
    }

    /// A prediction on no path at all (a point far from the solution curve) does not
    /// contract fast enough and is rejected.
    #[test]
    fn the_corrector_rejects_a_prediction_outside_the_basin() {
        // x² − (1 + t) from x = 40: Newton's updates only halve (ratio ≈ ½ > 0.25).
        on_square(1.0, 0.0, |tracker| {
            tracker.x_predicted[0] = C64::new(40.0, 0.0);
            assert_eq!(tracker.correct(C64::new(0.1, 0.0)), None);
            // Near the root the same corrector accepts.
            tracker.x_predicted[0] = C64::new(1.05, 0.0);
            assert!(tracker.correct(C64::new(0.1, 0.0)).is_some());
            assert!((tracker.x_predicted[0] - 1.1f64.sqrt()).norm() < 1e-12);
        });
    }
}

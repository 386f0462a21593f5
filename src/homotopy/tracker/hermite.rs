//! The predictor of stiff stretches: cubic Hermite extrapolation from the last two
//! points of the path and their velocities.
//!
//! The Runge–Kutta predictor ([`super::step`]) samples the velocity field
//! `ẋ = −J⁻¹ ∂H/∂t` at three points off the path. Near a cluster of solutions (a
//! Jacobian with condition numbers of 10¹¹–10¹⁴) that field changes over distances far
//! shorter than the path's own scale: the Runge–Kutta error becomes proportional to
//! the step (about 1 % of it, whatever its length), and the error-per-step control,
//! which assumes an error `≈ C h⁵`, shrinks the step by a constant factor at every
//! accepted step. On two base anchors 10⁻⁴ apart, `rigid/rigid` seed-stage paths
//! advanced by 0.1–0.2 % of their distance to `t = 1` per step, 1,100 steps for one
//! radius of the endgame, in double and in double-double precision alike.
//!
//! The cubic Hermite polynomial through `(u₀, x₀, ẋ₀)` and `(u₁, x₁, ẋ₁)` (two accepted
//! points of the segment, `u` its parameter, `ẋ = dx/du`) uses the path alone; its
//! extrapolation to `u₁ + h` has an error `O(h⁴)` (a two-step predictor, as in the
//! predictor–corrector methods of Allgower and Georg, *Introduction to Numerical
//! Continuation Methods*, SIAM 2003; the corrector and the step control are
//! unchanged). It costs one velocity per step
//! (Runge–Kutta: four). After [`STIFF_STEPS`] accepted steps in a row that each
//! shrank the step, once it is below [`STIFF_STEP_RATIO`] times the distance to
//! `t = 1`, the tracker predicts with it for the rest of the segment.

use crate::C64;

/// Accepted steps in a row, each shrinking the step, after which the rest of the
/// segment is predicted by Hermite extrapolation (on a smooth stretch the predictor
/// error falls with the step, and the step grows again within a few steps). 20 instead
/// of 10 made the `close-base-12` `rigid/rigid` curve 7 % slower (measured before the
/// [`STIFF_STEP_RATIO`] bound was added).
pub(super) const STIFF_STEPS: usize = 10;

/// Only where the steps have become shorter than this fraction of the distance to
/// `t = 1`: stiff stretches near a cluster crawl at 10⁻³ of it, while a path nearing a
/// singular endpoint (steps shrinking with the distance, at a tenth of it or more) is
/// predicted better by Runge–Kutta. Without this bound the `similar` scattered curve
/// took 2.3 → 4.7 s; with it as before (designs with orbits of critical points at
/// infinity, like `coincident-base-12`, still up to 1.45 times slower).
pub(super) const STIFF_STEP_RATIO: f64 = 0.01;

/// The last accepted point of the segment and the point the current prediction
/// starts from, each with its `t` and velocity `dx/du` (allocated once per tracker).
pub(super) struct HermiteHistory {
    /// `(t, x, ẋ)` of the accepted point before the current one.
    previous: (C64, Vec<C64>, Vec<C64>),
    /// Whether `previous` lies on the current segment.
    previous_valid: bool,
    /// `(t, x, ẋ)` of the point the current prediction starts from.
    current: (C64, Vec<C64>, Vec<C64>),
    /// Accepted steps in a row that shrank the step.
    shrinking: usize,
    /// Hermite extrapolation is on (for the rest of the segment).
    pub(super) active: bool,
    /// It may switch on ([`super::StepOptions::hermite_on_stiff_stretches`]).
    allowed: bool,
}

impl HermiteHistory {
    /// Buffers for `n` unknowns.
    pub(super) fn new(n: usize) -> Self {
        let zero = C64::new(0.0, 0.0);
        HermiteHistory {
            previous: (zero, vec![zero; n], vec![zero; n]),
            previous_valid: false,
            current: (zero, vec![zero; n], vec![zero; n]),
            shrinking: 0,
            active: false,
            allowed: false,
        }
    }

    /// A new segment: no history, Runge–Kutta again; Hermite extrapolation may switch
    /// on in it only if `allowed`.
    pub(super) fn start_segment(&mut self, allowed: bool) {
        self.previous_valid = false;
        self.shrinking = 0;
        self.active = false;
        self.allowed = allowed;
    }

    /// Records the point `(t, x)` and its velocity the next prediction starts from
    /// (nothing where Hermite extrapolation is not allowed: no copies per step).
    pub(super) fn record(&mut self, t: C64, x: &[C64], velocity: &[C64]) {
        if !self.allowed {
            return;
        }
        self.current.0 = t;
        self.current.1.copy_from_slice(x);
        self.current.2.copy_from_slice(velocity);
    }

    /// The step from the recorded point was accepted with step factor `factor`, and
    /// the next step is `step` long, at `distance` from `t = 1`: the recorded point
    /// becomes the previous one, and Hermite extrapolation switches on after
    /// [`STIFF_STEPS`] shrinking steps in a row shorter than [`STIFF_STEP_RATIO`] times
    /// `distance`.
    pub(super) fn accepted(&mut self, factor: f64, (step, distance): (f64, f64)) {
        if !self.allowed {
            return;
        }
        std::mem::swap(&mut self.previous, &mut self.current);
        self.previous_valid = true;
        self.shrinking = if factor < 1.0 { self.shrinking + 1 } else { 0 };
        if self.allowed && self.shrinking >= STIFF_STEPS && step < STIFF_STEP_RATIO * distance {
            self.active = true;
        }
    }

    /// The Hermite extrapolation from the previous point and the recorded one to the
    /// segment parameter `h` beyond the recorded point, into `out` (`dt` the segment's
    /// `t`-length as a complex number, so that `(t₁ − t₀)/dt` is the parameter step
    /// between the two points); `false` where there is no previous point on the segment.
    pub(super) fn extrapolate(&self, dt: C64, h: f64, out: &mut [C64]) -> bool {
        if !(self.active && self.previous_valid) {
            return false;
        }
        let (t0, x0, v0) = &self.previous;
        let (t1, x1, v1) = &self.current;
        let span = ((t1 - t0) / dt).re;
        if span <= 0.0 || !span.is_finite() {
            return false;
        }
        // τ = (u − u₀)/span at u = u₁ + h, and the cubic Hermite basis there.
        let tau = 1.0 + h / span;
        let (tau2, tau3) = (tau * tau, tau * tau * tau);
        let h00 = 2.0 * tau3 - 3.0 * tau2 + 1.0;
        let h10 = (tau3 - 2.0 * tau2 + tau) * span;
        let h01 = -2.0 * tau3 + 3.0 * tau2;
        let h11 = (tau3 - tau2) * span;
        for (i, o) in out.iter_mut().enumerate() {
            *o = x0[i] * h00 + v0[i] * h10 + x1[i] * h01 + v1[i] * h11;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic is extrapolated exactly; a quartic with an error of order `h⁴`.
    #[test]
    fn hermite_extrapolation_is_exact_for_cubics_and_fourth_order_otherwise() {
        let dt = C64::new(0.5, 0.0);
        // x(u) = u³ − 2u + 1 along t = dt·u, sampled at u = 0.2 and 0.3.
        let cubic = |u: f64| u * u * u - 2.0 * u + 1.0;
        let slope = |u: f64| 3.0 * u * u - 2.0;
        let mut history = HermiteHistory::new(1);
        history.start_segment(true);
        let point = |u: f64| C64::new(0.5 * u, 0.0);
        history.record(
            point(0.2),
            &[C64::new(cubic(0.2), 0.0)],
            &[C64::new(slope(0.2), 0.0)],
        );
        history.accepted(0.5, (0.0, 1.0));
        history.record(
            point(0.3),
            &[C64::new(cubic(0.3), 0.0)],
            &[C64::new(slope(0.3), 0.0)],
        );
        let mut out = [C64::new(0.0, 0.0)];
        // Not active yet: Runge–Kutta predicts.
        assert!(!history.extrapolate(dt, 0.1, &mut out));
        history.active = true;
        assert!(history.extrapolate(dt, 0.1, &mut out));
        assert!((out[0].re - cubic(0.4)).abs() < 1e-14, "{out:?}");
        // x(u) = u⁴: error ∝ h⁴ (the spans scaled together).
        let error = |h: f64| {
            let mut history = HermiteHistory::new(1);
            history.start_segment(true);
            history.active = true;
            let f = |u: f64| C64::new(u.powi(4), 0.0);
            let d = |u: f64| C64::new(4.0 * u.powi(3), 0.0);
            history.record(point(1.0 - h), &[f(1.0 - h)], &[d(1.0 - h)]);
            history.accepted(0.5, (0.0, 1.0));
            history.record(point(1.0), &[f(1.0)], &[d(1.0)]);
            let mut out = [C64::new(0.0, 0.0)];
            assert!(history.extrapolate(dt, h, &mut out));
            (out[0] - f(1.0 + h)).norm()
        };
        let ratio = error(1e-2) / error(5e-3);
        assert!((ratio - 16.0).abs() < 0.5, "{ratio}");
    }

    /// Shrinking steps switch it on after [`STIFF_STEPS`] in a row, a growing one
    /// restarts the count, a new segment switches it off.
    #[test]
    fn hermite_extrapolation_starts_after_a_run_of_shrinking_steps() {
        let mut history = HermiteHistory::new(1);
        history.start_segment(true);
        for _ in 0..STIFF_STEPS - 1 {
            history.accepted(0.99, (0.0, 1.0));
        }
        history.accepted(1.2, (0.0, 1.0));
        assert!(!history.active);
        for _ in 0..STIFF_STEPS {
            history.accepted(0.99, (0.0, 1.0));
        }
        assert!(history.active);
        history.start_segment(true);
        assert!(!history.active);
        // Not where the options leave it off.
        history.start_segment(false);
        for _ in 0..2 * STIFF_STEPS {
            history.accepted(0.99, (0.0, 1.0));
        }
        assert!(!history.active);
        history.start_segment(true);
        // Steps shrinking towards an endpoint at a tenth of their distance to it.
        for _ in 0..2 * STIFF_STEPS {
            history.accepted(0.99, (0.1, 1.0));
        }
        assert!(!history.active);
    }
}

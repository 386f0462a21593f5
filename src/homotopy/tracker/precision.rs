//! Double and double-double arithmetic in the tracker: the evaluation and LU
//! workspaces of both precisions ([`Evaluation`]) and the rule that switches between
//! them ([`Precision`]).
//!
//! In double precision a linear solve at condition number κ loses `κ·ε` of relative
//! accuracy (`ε ≈ 2.2·10⁻¹⁶`); once `κ·ε` nears the corrector tolerance, Newton's
//! updates and the predictor's velocities are rounding noise and no step is accepted.
//! Following the adaptive multiprecision of Bates, Hauenstein, Sommese & Wampler
//! ("Adaptive multiprecision path tracking", SIAM J. Numer. Anal., 2008), the tracker
//! switches to double-double arithmetic (about 32 digits, [`crate::system::double_double`])
//! after [`super::PrecisionOptions::extended_after_rejections`] consecutive rejected steps at a
//! condition number above [`RETURN_TO_DOUBLE_CONDITION`] (below it a rejection means a
//! step too long, not too little precision), and returns to double precision every
//! [`super::PrecisionOptions::extended_accepted_steps`] accepted steps if the condition number
//! is back below that bound.

use super::TrackerOptions;
use crate::C64;
use crate::homotopy::homotopies::Homotopy;
use crate::homotopy::linalg::{DdLuWorkspace, LuWorkspace};

/// Condition number below which extended mode returns to double precision
/// (κ·ε ≈ 2·10⁻¹⁰, well under the corrector tolerance).
pub(super) const RETURN_TO_DOUBLE_CONDITION: f64 = 1e6;

/// The tracker's precision mode and the counters that switch it (see the module
/// documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Precision {
    /// Extended (double-double) mode is on.
    pub(super) extended: bool,
    /// Extended mode was on at some point of the path.
    pub(super) used: bool,
    /// Rejected steps since the last accepted one.
    pub(super) consecutive_rejections: usize,
    /// Accepted steps since extended mode was switched on or last checked.
    pub(super) streak: usize,
    /// Steps attempted in extended mode (their budget is
    /// [`super::PrecisionOptions::max_extended_steps`]).
    pub(super) steps: usize,
}

impl Precision {
    /// Extended mode on; restarts the count of accepted steps.
    pub(super) fn switch_to_extended(&mut self) {
        self.extended = true;
        self.used = true;
        self.streak = 0;
    }

    /// Counts one attempted step (in extended mode against its budget).
    pub(super) fn count_step(&mut self) {
        if self.extended {
            self.steps += 1;
        }
    }

    /// Whether the extended-precision step budget is spent.
    pub(super) fn budget_spent(&self, options: &TrackerOptions) -> bool {
        self.steps >= options.precision.max_extended_steps
    }

    /// Records an accepted step; `true` when, in extended mode, the condition number
    /// is due to be checked for a return to double precision (every
    /// `extended_accepted_steps` accepted steps, unless switching is off).
    pub(super) fn accepted(&mut self, options: &TrackerOptions) -> bool {
        self.consecutive_rejections = 0;
        if !self.extended {
            return false;
        }
        self.streak += 1;
        if self.streak >= options.precision.extended_accepted_steps
            && options.precision.extended_after_rejections > 0
        {
            self.streak = 0;
            return true;
        }
        false
    }

    /// Records a rejected step; `true` when, in double precision, enough consecutive
    /// rejections have accumulated for extended mode (if the condition number, which
    /// the caller checks, is above [`RETURN_TO_DOUBLE_CONDITION`]).
    pub(super) fn rejected(&mut self, options: &TrackerOptions) -> bool {
        self.consecutive_rejections += 1;
        !self.extended
            && options.precision.extended_after_rejections > 0
            && self.consecutive_rejections >= options.precision.extended_after_rejections
    }
}

/// Scratch for evaluations and linear solves.
pub(super) struct Evaluation {
    pub(super) work: Vec<C64>,
    pub(super) h: Vec<C64>,
    pub(super) jac: Vec<C64>,
    pub(super) dh: Vec<C64>,
    pub(super) lu: LuWorkspace,
    /// [`super::PrecisionOptions::extended_residual`].
    pub(super) extended_residual: bool,
    /// Extended mode: Jacobians in double-double, solves by `dd_lu`.
    pub(super) extended: bool,
    /// Trailing parts of the double-double Jacobian in `jac`.
    pub(super) jac_low: Vec<C64>,
    pub(super) dd_lu: DdLuWorkspace,
    /// The current factorisation is `dd_lu`'s (else `lu`'s).
    pub(super) dd_current: bool,
    /// `lu` does not hold the factorisation of `jac` (extended mode factors only
    /// `dd_lu`; [`Evaluation::condition_estimate`] factors `lu` on demand).
    pub(super) lu_stale: bool,
}

/// Result of a Newton update.
pub(super) enum NewtonUpdate {
    Step(f64),
    Singular,
}

impl Evaluation {
    pub(super) fn new(n: usize, work_len: usize, extended_residual: bool) -> Self {
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
    pub(super) fn velocity<H: Homotopy + ?Sized>(
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
    pub(super) fn condition_estimate(&mut self) -> f64 {
        if self.lu_stale {
            if !self.lu.factor(&self.jac) {
                return f64::INFINITY;
            }
            self.lu_stale = false;
        }
        self.lu.condition_estimate()
    }

    /// `out ← −J⁻¹ dh · dt` with the current factorisation and `self.dh`.
    pub(super) fn solve_velocity(&mut self, dt: C64, out: &mut [C64]) -> bool {
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
    pub(super) fn newton<H: Homotopy + ?Sized>(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::tracker::tests::{pole, reciprocal_family};

    fn options(after: usize, every: usize) -> TrackerOptions {
        let mut options = TrackerOptions::default();
        options.precision.extended_after_rejections = after;
        options.precision.extended_accepted_steps = every;
        options
    }

    #[test]
    fn extended_mode_is_due_after_the_given_number_of_consecutive_rejections() {
        let options = options(3, 16);
        let mut precision = Precision::default();
        assert!(!precision.rejected(&options));
        assert!(!precision.rejected(&options));
        // An accepted step resets the count.
        assert!(!precision.accepted(&options));
        assert!(!precision.rejected(&options));
        assert!(!precision.rejected(&options));
        assert!(precision.rejected(&options));
        precision.switch_to_extended();
        assert!(precision.extended && precision.used);
        // Already extended: no further switch is due.
        assert!(!precision.rejected(&options));
    }

    #[test]
    fn zero_rejections_disables_both_switches() {
        let options = options(0, 2);
        let mut precision = Precision::default();
        for _ in 0..10 {
            assert!(!precision.rejected(&options));
        }
        precision.switch_to_extended();
        for _ in 0..10 {
            assert!(!precision.accepted(&options));
        }
    }

    #[test]
    fn the_return_to_double_is_checked_every_given_number_of_accepted_steps() {
        let options = options(3, 4);
        let mut precision = Precision::default();
        assert!(
            !precision.accepted(&options),
            "double mode has nothing to check"
        );
        precision.switch_to_extended();
        let due: Vec<bool> = (0..8).map(|_| precision.accepted(&options)).collect();
        assert_eq!(due, [false, false, false, true, false, false, false, true]);
    }

    #[test]
    fn only_extended_steps_count_against_their_budget() {
        let mut options = TrackerOptions::default();
        options.precision.max_extended_steps = 2;
        let mut precision = Precision::default();
        precision.count_step();
        precision.count_step();
        assert!(!precision.budget_spent(&options));
        precision.switch_to_extended();
        precision.count_step();
        assert!(!precision.budget_spent(&options));
        precision.count_step();
        assert!(precision.budget_spent(&options));
    }

    /// One Newton update of `(p − t)x − 1 = 0` is exact (the residual is linear in
    /// `x`), in double and in double-double; the velocity is `ẋ = x/(p − t)`.
    #[test]
    fn newton_and_velocity_agree_in_both_precisions() {
        let system = reciprocal_family();
        let homotopy = pole(&system, 2.0);
        let t = C64::new(0.5, 0.0);
        for extended in [false, true] {
            let mut eval = Evaluation::new(1, homotopy.workspace_len(), true);
            eval.extended = extended;
            let mut x = vec![C64::new(0.3, 0.1)];
            let NewtonUpdate::Step(norm) = eval.newton(&homotopy, &mut x, t, extended) else {
                panic!("singular");
            };
            assert!((x[0] - 1.0 / 1.5).norm() < 1e-15, "{x:?}");
            assert!(norm > 0.3, "{norm}");
            let mut v = vec![C64::new(0.0, 0.0)];
            assert!(eval.velocity(&homotopy, &x, t, C64::new(1.0, 0.0), &mut v));
            assert!((v[0] - x[0] / 1.5).norm() < 1e-14, "{v:?}");
            assert!((eval.condition_estimate() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_singular_jacobian_stops_newton() {
        let system = reciprocal_family();
        let homotopy = pole(&system, 0.5);
        let mut eval = Evaluation::new(1, homotopy.workspace_len(), true);
        let mut x = vec![C64::new(1.0, 0.0)];
        assert!(matches!(
            eval.newton(&homotopy, &mut x, C64::new(0.5, 0.0), false),
            NewtonUpdate::Singular
        ));
    }
}

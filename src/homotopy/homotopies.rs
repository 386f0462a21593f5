//! Homotopies `H(x, t)`: families of square systems joining a start system at `t = 0`
//! to the target at `t = 1`.
//!
//! - [`StraightLineHomotopy`]: `H = (1 − t)·γ·G(x) + t·F(x; p)` with a random unit
//!   complex γ (the "γ-trick": for all but finitely many γ on the unit circle the paths
//!   are smooth for `t ∈ [0, 1)`, Sommese & Wampler, *The Numerical Solution of Systems
//!   of Polynomials*, Lemma 7.1.3).
//! - [`ParameterHomotopy`]: `H = F(x; p(t))` with `p(t) = (1 − t) p₀ + t p₁` (the
//!   coefficient-parameter homotopy, Morgan & Sommese 1989); for generic complex `p₀, p₁`
//!   the segment avoids the discriminant.
//! - [`PolylineParameterHomotopy`]: `p(t)` piecewise linear through `p₀, …, p_K`
//!   (complex detours; the monodromy loops of [`crate::homotopy::monodromy`]).
//!
//! The tracker sees only the [`Homotopy`] trait; callers may implement it themselves.

use crate::C64;
use crate::system::Evaluator;

/// A square homotopy `H: Cⁿ × C → Cⁿ`, evaluated into caller buffers with a per-thread
/// scratch workspace of [`Homotopy::workspace_len`] entries (no allocation).
///
/// `t` is complex: the tracker walks real segments of `[0, 1]` and the Cauchy endgame
/// walks small circles around `t = 1`. Jacobians are row-major n × n.
pub trait Homotopy: Send + Sync {
    /// Number of unknowns (= number of equations) n.
    fn dimension(&self) -> usize;
    /// Scratch length the evaluation calls need.
    fn workspace_len(&self) -> usize;
    /// The unknown whose zero means a point at infinity of the affine system the
    /// homotopy's systems are charts of ([`Evaluator::homogenizing_variable`]); the
    /// tracker classifies a finite endpoint with that coordinate zero at infinity.
    fn homogenizing_variable(&self) -> Option<usize> {
        None
    }
    /// `h ← H(x, t)`.
    fn evaluate(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]);
    /// `h ← H(x, t)` with the system evaluated in double-double arithmetic where the
    /// homotopy supports it ([`Evaluator::evaluate_extended`]): the Newton residual of
    /// the tracker's extended-precision mode. The default evaluates in double precision.
    fn evaluate_extended(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        self.evaluate(x, t, work, h);
    }
    /// `h ← H(x, t)`, `jac ← ∂H/∂x (x, t)`.
    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
    );
    /// `dh ← ∂H/∂t (x, t)`.
    fn evaluate_time_derivative(&self, x: &[C64], t: C64, work: &mut [C64], dh: &mut [C64]);
    /// `h ← H`, `jac ← ∂H/∂x`, `dh ← ∂H/∂t` in one call (the predictor's need).
    /// The default calls [`Homotopy::evaluate_with_jacobian`] and
    /// [`Homotopy::evaluate_time_derivative`]; implementations override it to share work.
    fn evaluate_with_jacobian_and_time_derivative(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
        dh: &mut [C64],
    ) {
        self.evaluate_with_jacobian(x, t, work, h, jac);
        self.evaluate_time_derivative(x, t, work, dh);
    }
    /// `h ← H`, `jac + jac_low ← ∂H/∂x` in double-double arithmetic where supported
    /// ([`Evaluator::evaluate_with_jacobian_extended`]). The default evaluates in double
    /// precision (`jac_low = 0`).
    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        (jac, jac_low): (&mut [C64], &mut [C64]),
    ) {
        self.evaluate_with_jacobian(x, t, work, h, jac);
        jac_low.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    }
    /// [`Homotopy::evaluate_with_jacobian_and_time_derivative`] in double-double
    /// arithmetic where supported (the predictor's velocities in extended-precision
    /// mode): `h ← H`, `jac + jac_low ← ∂H/∂x`, `dh ← ∂H/∂t`. The default evaluates in
    /// double precision (`jac_low = 0`).
    #[allow(clippy::too_many_arguments)]
    fn evaluate_with_jacobian_and_time_derivative_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        (jac, jac_low): (&mut [C64], &mut [C64]),
        dh: &mut [C64],
    ) {
        self.evaluate_with_jacobian_and_time_derivative(x, t, work, h, jac, dh);
        jac_low.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    }
    /// Values of `t` in `(0, 1)` where `H` is only piecewise smooth (the tracker stops
    /// there so no predictor step straddles a kink). Empty by default.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }
}

/// `H(x, t) = (1 − t)·γ·G(x) + t·F(x; p)` with fixed target parameters `p`.
///
/// In the tracker's extended mode both systems' values are evaluated in double-double
/// arithmetic ([`Evaluator::evaluate_extended`]) and blended from their rounded parts,
/// which costs `ε·(|t·F| + |(1 − t)·γ·G|)`: near `t = 1`, where a large root's terms
/// cancel in `F` (PHCpack's `discret3s`: terms of 10⁹ at roots of norm 10⁵, condition
/// 10⁹), that is far below the `ε·Σ|terms|` of a double-precision evaluation, whose
/// noise (10⁻⁸ relative there) kept Newton's corrections from converging. The
/// Jacobians stay in double precision (the tracker still solves with them in
/// double-double): double-double Jacobians too made PHCpack's `cassou` and `cohn3`
/// 1.3× slower than this and changed no count of `discret3s` at 31 seeds.
pub struct StraightLineHomotopy<'a, G: Evaluator + ?Sized, F: Evaluator + ?Sized> {
    start: &'a G,
    target: &'a F,
    target_parameters: Vec<C64>,
    gamma: C64,
    n: usize,
}

impl<'a, G: Evaluator + ?Sized, F: Evaluator + ?Sized> StraightLineHomotopy<'a, G, F> {
    /// Homotopy from `start` (no parameters) to `target` at `target_parameters`.
    /// Both systems must be square with the same number of unknowns (checked by
    /// [`crate::homotopy::solve`]; here a mismatch is a programming error).
    pub fn new(start: &'a G, target: &'a F, target_parameters: Vec<C64>, gamma: C64) -> Self {
        let n = target.num_variables();
        assert_eq!(
            start.num_variables(),
            n,
            "start and target dimensions differ"
        );
        assert_eq!(target_parameters.len(), target.num_parameters());
        StraightLineHomotopy {
            start,
            target,
            target_parameters,
            gamma,
            n,
        }
    }

    /// The γ of the homotopy.
    pub fn gamma(&self) -> C64 {
        self.gamma
    }

    /// `g ← G(x)` (returned, at the head of `work`) and `f ← F(x; p)`, in double-double
    /// arithmetic and rounded if `extended` ([`Evaluator::evaluate_extended`]).
    fn start_and_target<'w>(
        &self,
        x: &[C64],
        work: &'w mut [C64],
        f: &mut [C64],
        extended: bool,
    ) -> &'w [C64] {
        let n = self.n;
        let (g, rest) = work.split_at_mut(n);
        let rest = &mut rest[n * n..];
        if extended {
            self.start.evaluate_extended(x, &[], rest, g);
            self.target
                .evaluate_extended(x, &self.target_parameters, rest, f);
        } else {
            self.start.evaluate(x, &[], rest, g);
            self.target.evaluate(x, &self.target_parameters, rest, f);
        }
        g
    }

    /// `(g, ∂G/∂x)` (returned, at the head of `work`), `f ← F(x; p)`, `jac ← ∂F/∂x`.
    fn start_and_target_with_jacobians<'w>(
        &self,
        x: &[C64],
        work: &'w mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) -> (&'w [C64], &'w [C64]) {
        let n = self.n;
        let (g, rest) = work.split_at_mut(n);
        let (g_jac, rest) = rest.split_at_mut(n * n);
        self.start.evaluate_with_jacobian(x, &[], rest, g, g_jac);
        self.target
            .evaluate_with_jacobian(x, &self.target_parameters, rest, f, jac);
        (g, g_jac)
    }

    /// `h ← H` from both systems' values in double-double arithmetic, rounded;
    /// `jac ← ∂H/∂x` in double precision (`jac_low = 0`); `dh ← ∂H/∂t = F − γG` from
    /// the double-double values if asked.
    fn evaluate_extended_residual(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        (jac, jac_low): (&mut [C64], &mut [C64]),
        dh: Option<&mut [C64]>,
    ) {
        let a = self.start_weight(t);
        let (_, g_jac) = self.start_and_target_with_jacobians(x, work, h, jac);
        blend(t, a, jac, g_jac);
        jac_low.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        let g = self.start_and_target(x, work, h, true);
        if let Some(dh) = dh {
            for ((di, fi), gi) in dh.iter_mut().zip(h.iter()).zip(g) {
                *di = *fi - self.gamma * gi;
            }
        }
        blend(t, a, h, g);
    }

    /// `(1 − t)·γ`, the start system's weight at `t`.
    fn start_weight(&self, t: C64) -> C64 {
        (C64::new(1.0, 0.0) - t) * self.gamma
    }
}

/// `target ← t·target + a·start` entrywise (the blend of target and start values).
fn blend(t: C64, a: C64, target: &mut [C64], start: &[C64]) {
    for (v, s) in target.iter_mut().zip(start) {
        *v = t * *v + a * s;
    }
}

impl<G: Evaluator + ?Sized, F: Evaluator + ?Sized> Homotopy for StraightLineHomotopy<'_, G, F> {
    fn dimension(&self) -> usize {
        self.n
    }

    fn workspace_len(&self) -> usize {
        self.n + self.n * self.n + self.start.workspace_len().max(self.target.workspace_len())
    }

    fn evaluate(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        let g = self.start_and_target(x, work, h, false);
        blend(t, self.start_weight(t), h, g);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
    ) {
        let (g, g_jac) = self.start_and_target_with_jacobians(x, work, h, jac);
        let a = self.start_weight(t);
        blend(t, a, h, g);
        blend(t, a, jac, g_jac);
    }

    fn evaluate_with_jacobian_and_time_derivative(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
        dh: &mut [C64],
    ) {
        let (g, g_jac) = self.start_and_target_with_jacobians(x, work, h, jac);
        for ((di, hi), gi) in dh.iter_mut().zip(h.iter()).zip(g) {
            *di = *hi - self.gamma * gi;
        }
        let a = self.start_weight(t);
        blend(t, a, h, g);
        blend(t, a, jac, g_jac);
    }

    fn evaluate_time_derivative(&self, x: &[C64], _t: C64, work: &mut [C64], dh: &mut [C64]) {
        let g = self.start_and_target(x, work, dh, false);
        for (di, gi) in dh.iter_mut().zip(g) {
            *di -= self.gamma * gi;
        }
    }

    fn evaluate_extended(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        let g = self.start_and_target(x, work, h, true);
        blend(t, self.start_weight(t), h, g);
    }

    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: (&mut [C64], &mut [C64]),
    ) {
        self.evaluate_extended_residual(x, t, work, h, jac, None);
    }

    fn evaluate_with_jacobian_and_time_derivative_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: (&mut [C64], &mut [C64]),
        dh: &mut [C64],
    ) {
        self.evaluate_extended_residual(x, t, work, h, jac, Some(dh));
    }
}

/// `p(t)` piecewise linear through `p₀, …, p_K` at `t = 0, 1/K, …, 1` (a closed loop
/// when `p_K = p₀`): complex detours and the monodromy loops of
/// [`crate::homotopy::monodromy`].
#[derive(Clone, Debug)]
pub struct PolylinePath {
    points: Vec<Vec<C64>>,
    breakpoints: Vec<f64>,
}

impl PolylinePath {
    /// Polyline through `points` (at least two, all of the same length).
    pub fn new(points: Vec<Vec<C64>>) -> Self {
        assert!(points.len() >= 2, "a polyline needs two points");
        let m = points[0].len();
        for p in &points {
            assert_eq!(p.len(), m);
        }
        let segments = points.len() - 1;
        PolylinePath {
            breakpoints: (1..segments).map(|k| k as f64 / segments as f64).collect(),
            points,
        }
    }

    /// Segment index and local coordinate of `t` (segment chosen by `Re t`).
    fn locate(&self, t: C64) -> (usize, C64) {
        let segments = self.points.len() - 1;
        let scaled = t * segments as f64;
        let k = (scaled.re.floor().max(0.0) as usize).min(segments - 1);
        (k, scaled - k as f64)
    }
}

impl ParameterPath for PolylinePath {
    fn len(&self) -> usize {
        self.points[0].len()
    }

    fn point(&self, t: C64, p: &mut [C64]) {
        let (k, s) = self.locate(t);
        for ((pi, a), b) in p.iter_mut().zip(&self.points[k]).zip(&self.points[k + 1]) {
            *pi = a + s * (b - a);
        }
    }

    fn point_and_velocity(&self, t: C64, p: &mut [C64], dp: &mut [C64]) {
        let segments = (self.points.len() - 1) as f64;
        let (k, s) = self.locate(t);
        for (((pi, di), a), b) in p
            .iter_mut()
            .zip(dp.iter_mut())
            .zip(&self.points[k])
            .zip(&self.points[k + 1])
        {
            *pi = a + s * (b - a);
            *di = (b - a) * segments;
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
}

/// `H(x, t) = F(x; p(t))` with `p` piecewise linear through `p₀, …, p_K`
/// ([`PolylinePath`]).
pub type PolylineParameterHomotopy<'a, F> = PathParameterHomotopy<'a, F, PolylinePath>;

/// `H(x, t) = F(x; (1 − t) p₀ + t p₁)`, so `∂H/∂t = (∂F/∂p)(p₁ − p₀)`: the
/// coefficient-parameter homotopy (Morgan & Sommese 1989), a one-segment polyline.
pub type ParameterHomotopy<'a, F> = PolylineParameterHomotopy<'a, F>;

impl<'a, F: Evaluator + ?Sized> PathParameterHomotopy<'a, F, PolylinePath> {
    /// Polyline through `points` (at least two, each of length `num_parameters()`).
    pub fn through(system: &'a F, points: Vec<Vec<C64>>) -> Self {
        PathParameterHomotopy::new(system, PolylinePath::new(points))
    }

    /// The segment from `start_parameters` (t = 0) to `target_parameters` (t = 1).
    pub fn segment(system: &'a F, start_parameters: &[C64], target_parameters: &[C64]) -> Self {
        Self::through(
            system,
            vec![start_parameters.to_vec(), target_parameters.to_vec()],
        )
    }
}

/// A smooth curve `t ↦ p(t)` in parameter space (piecewise smooth at
/// [`ParameterPath::breakpoints`]), for homotopies whose parameters do not move on a
/// straight line, e.g. along a mechanism's motion at complex motion parameter.
pub trait ParameterPath: Send + Sync {
    /// Number of parameters.
    fn len(&self) -> usize;
    /// Whether the path has no parameters.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// `p ← p(t)`.
    fn point(&self, t: C64, p: &mut [C64]);
    /// `p ← p(t)` and `dp ← dp/dt (t)`.
    fn point_and_velocity(&self, t: C64, p: &mut [C64], dp: &mut [C64]);
    /// Kinks of the path in `(0, 1)`.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }
}

/// `H(x, t) = F(x; p(t))` along a [`ParameterPath`], so `∂H/∂t = (∂F/∂p)·p′(t)`.
pub struct PathParameterHomotopy<'a, F: Evaluator + ?Sized, P: ParameterPath> {
    system: &'a F,
    path: P,
    n: usize,
}

impl<'a, F: Evaluator + ?Sized, P: ParameterPath> PathParameterHomotopy<'a, F, P> {
    /// The homotopy of `system` along `path` (`path.len()` must equal the system's
    /// number of parameters).
    pub fn new(system: &'a F, path: P) -> Self {
        assert_eq!(path.len(), system.num_parameters());
        PathParameterHomotopy {
            system,
            n: system.num_variables(),
            path,
        }
    }
}

impl<F: Evaluator + ?Sized, P: ParameterPath> PathParameterHomotopy<'_, F, P> {
    /// `p ← p(t)` at the head of `work`; returns `p` and the system's scratch.
    fn parameters_at<'w>(&self, t: C64, work: &'w mut [C64]) -> (&'w [C64], &'w mut [C64]) {
        let m = self.path.len();
        let (p, rest) = work.split_at_mut(m);
        self.path.point(t, p);
        (p, &mut rest[m..])
    }

    /// `p ← p(t)`, `dp ← p′(t)` at the head of `work`; returns both and the scratch.
    fn parameters_and_velocity_at<'w>(
        &self,
        t: C64,
        work: &'w mut [C64],
    ) -> (&'w [C64], &'w [C64], &'w mut [C64]) {
        let m = self.path.len();
        let (p, rest) = work.split_at_mut(m);
        let (dp, rest) = rest.split_at_mut(m);
        self.path.point_and_velocity(t, p, dp);
        (p, dp, rest)
    }
}

impl<F: Evaluator + ?Sized, P: ParameterPath> Homotopy for PathParameterHomotopy<'_, F, P> {
    fn dimension(&self) -> usize {
        self.n
    }

    fn workspace_len(&self) -> usize {
        2 * self.path.len() + self.system.workspace_len()
    }

    fn homogenizing_variable(&self) -> Option<usize> {
        self.system.homogenizing_variable()
    }

    fn evaluate(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        let (p, rest) = self.parameters_at(t, work);
        self.system.evaluate(x, p, rest, h);
    }

    fn evaluate_extended(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        let (p, rest) = self.parameters_at(t, work);
        self.system.evaluate_extended(x, p, rest, h);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
    ) {
        let (p, rest) = self.parameters_at(t, work);
        self.system.evaluate_with_jacobian(x, p, rest, h, jac);
    }

    fn evaluate_time_derivative(&self, x: &[C64], t: C64, work: &mut [C64], dh: &mut [C64]) {
        let (p, dp, rest) = self.parameters_and_velocity_at(t, work);
        self.system
            .evaluate_parameter_derivative(x, p, dp, rest, dh);
    }

    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        (jac, jac_low): (&mut [C64], &mut [C64]),
    ) {
        let (p, rest) = self.parameters_at(t, work);
        self.system
            .evaluate_with_jacobian_extended(x, p, rest, h, jac, jac_low);
    }

    fn evaluate_with_jacobian_and_time_derivative_extended(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        (jac, jac_low): (&mut [C64], &mut [C64]),
        dh: &mut [C64],
    ) {
        let (p, dp, rest) = self.parameters_and_velocity_at(t, work);
        self.system
            .evaluate_with_jacobian_extended(x, p, rest, h, jac, jac_low);
        self.system
            .evaluate_parameter_derivative_extended(x, p, dp, rest, dh);
    }

    fn breakpoints(&self) -> &[f64] {
        self.path.breakpoints()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::TotalDegreeStartSystem;
    use crate::homotopy::test_support::read_xy;

    /// `F = (x² − c, y − 1)` at `x = 10⁸ + 1`, `c = 10¹⁶ + 2·10⁸`: `x² − c = 1`, but
    /// `x²` rounds to a multiple of 2 in double precision. The extended evaluation of
    /// the homotopy at `t = 1` gets the residual and the Jacobian entry `2x` exactly,
    /// and `∂H/∂t = F − γG` from the same values.
    #[test]
    fn the_extended_evaluation_keeps_the_target_residual_double_precision_loses() {
        let target = read_xy("f = x^2 - 10000000200000000;\ng = y - 1;");
        let start = TotalDegreeStartSystem::new(vec![2, 1]);
        let gamma = C64::new(0.6, 0.8);
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], gamma);
        let x = [C64::new(1e8 + 1.0, 0.0), C64::new(1.0, 0.0)];
        let one = C64::new(1.0, 0.0);
        let mut work = vec![C64::new(0.0, 0.0); homotopy.workspace_len()];
        let mut h = [C64::new(0.0, 0.0); 2];
        homotopy.evaluate(&x, one, &mut work, &mut h);
        assert_ne!(h[0], one, "double precision loses the residual");
        homotopy.evaluate_extended(&x, one, &mut work, &mut h);
        assert_eq!(h[0], one);
        let (mut jac, mut jac_low) = ([C64::new(0.0, 0.0); 4], [C64::new(0.0, 0.0); 4]);
        let mut dh = [C64::new(0.0, 0.0); 2];
        homotopy.evaluate_with_jacobian_and_time_derivative_extended(
            &x,
            one,
            &mut work,
            &mut h,
            (&mut jac, &mut jac_low),
            &mut dh,
        );
        assert_eq!(h[0], one);
        assert_eq!(jac[0] + jac_low[0], C64::new(2e8 + 2.0, 0.0));
        // G = (x² − 1, y − 1) rounded: F − γG.
        let g = C64::new((1e8 + 1.0) * (1e8 + 1.0) - 1.0, 0.0);
        assert!(
            (dh[0] - (one - gamma * g)).norm() <= 1e-15 * g.norm(),
            "{dh:?}"
        );
    }
}

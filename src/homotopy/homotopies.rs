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

    /// `g ← G(x)` (returned, at the head of `work`) and `f ← F(x; p)`.
    fn start_and_target<'w>(&self, x: &[C64], work: &'w mut [C64], f: &mut [C64]) -> &'w [C64] {
        let n = self.n;
        let (g, rest) = work.split_at_mut(n);
        let rest = &mut rest[n * n..];
        self.start.evaluate(x, &[], rest, g);
        self.target.evaluate(x, &self.target_parameters, rest, f);
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
        let g = self.start_and_target(x, work, h);
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
        let g = self.start_and_target(x, work, dh);
        for (di, gi) in dh.iter_mut().zip(g) {
            *di -= self.gamma * gi;
        }
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

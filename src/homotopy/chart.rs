//! Any homotopy in a random affine chart of projective space: an independent route
//! for the paths the affine formulation sends to infinity.
//!
//! An affine path that grows without bound either ends at infinity or at a finite
//! root too large (or too badly scaled) for the endgame to tell apart from infinity.
//! In homogeneous coordinates `[x₀ : y]` with `x = y / x₀` on the random chart
//! `x₀ + b·y = 1`, both are finite points: a root at infinity has `x₀ = 0`, a large
//! finite root a small non-zero `x₀`. The homotopy `H(x, t)` of equation degrees `d_i`
//! becomes
//!
//! `G_i(x₀, y, t) = x₀^{d_i} H_i(y / x₀, t)` (i < n), `G_n = x₀ + b·y − 1`,
//!
//! with `∂G_i/∂y_k = x₀^{d_i − 1} ∂H_i/∂x_k`,
//! `∂G_i/∂x₀ = x₀^{d_i − 1} (d_i H_i − Σ_j ∂H_i/∂x_j x_j)` and
//! `∂G_i/∂t = x₀^{d_i} ∂H_i/∂t`: the homogenisation of the system in the random
//! chart that Bertini tracks in (Bates, Hauenstein, Sommese and Wampler, *Numerically
//! Solving Polynomial Systems with Bertini*, SIAM 2013, §1.3; A. P. Morgan, *A
//! transformation to avoid solutions at infinity for polynomial systems*, Appl. Math.
//! Comput. 18, 1986). The wrapper evaluates `H` at `x = y / x₀`, so it needs no
//! expansion of the system; each term `a_α x^α x₀^{d_i}` keeps its relative rounding.

use super::newton::max_norm;
use super::refine::newton_refine;
use super::solve::TargetSystem;
use super::{FailureReason, Homotopy, PathResult, PathStatus, Tracker, TrackerOptions};
use crate::C64;
use crate::random;
use crate::system::PlainSystem;
use rayon::prelude::*;

/// `H(x, t)` homogenised with degrees `d_i` on the chart `x₀ + b·y = 1`; unknowns
/// `(x₀, y_1, …, y_n)`, `x₀` the homogenising coordinate.
pub struct ChartHomotopy<'a, H: Homotopy + ?Sized> {
    inner: &'a H,
    degrees: Vec<i32>,
    chart: Vec<C64>,
    n: usize,
}

impl<'a, H: Homotopy + ?Sized> ChartHomotopy<'a, H> {
    /// `inner` (each `H_i(·, t)` of total degree at most `degrees[i]` for every `t`) on
    /// a chart drawn from `seed`.
    pub fn new(inner: &'a H, degrees: &[u32], seed: u64) -> Self {
        let n = inner.dimension();
        assert_eq!(degrees.len(), n, "one degree per equation");
        let mut rng = random::seeded(seed);
        let chart = (0..n).map(|_| random::unit_complex(&mut rng)).collect();
        ChartHomotopy {
            inner,
            degrees: degrees.iter().map(|&d| d as i32).collect(),
            chart,
            n,
        }
    }

    /// An affine point `x` in the chart: `x₀ = 1 / (1 + b·x)`, `y = x₀ x`.
    pub fn lift(&self, x: &[C64], z: &mut [C64]) {
        let bx: C64 = self.chart.iter().zip(x).map(|(b, v)| b * v).sum();
        let x0 = (C64::new(1.0, 0.0) + bx).inv();
        z[0] = x0;
        for (zi, v) in z[1..].iter_mut().zip(x) {
            *zi = v * x0;
        }
    }

    /// A chart point with `x₀ ≠ 0` as an affine point: `x = y / x₀`.
    pub fn lower(&self, z: &[C64]) -> Vec<C64> {
        z[1..].iter().map(|v| v / z[0]).collect()
    }

    /// Splits the workspace into the inner one and `x`, `H`, `∂H/∂x`, `∂H/∂t`.
    #[allow(clippy::type_complexity)]
    fn split<'w>(
        &self,
        work: &'w mut [C64],
    ) -> (
        &'w mut [C64],
        &'w mut [C64],
        &'w mut [C64],
        &'w mut [C64],
        &'w mut [C64],
    ) {
        let n = self.n;
        let (inner, rest) = work.split_at_mut(self.inner.workspace_len());
        let (x, rest) = rest.split_at_mut(n);
        let (h, rest) = rest.split_at_mut(n);
        let (jac, rest) = rest.split_at_mut(n * n);
        (inner, x, h, jac, &mut rest[..n])
    }

    fn affine(&self, z: &[C64], x: &mut [C64]) {
        let inverse = z[0].inv();
        for (xi, y) in x.iter_mut().zip(&z[1..]) {
            *xi = y * inverse;
        }
    }

    fn chart_equation(&self, z: &[C64]) -> C64 {
        z[0] + self
            .chart
            .iter()
            .zip(&z[1..])
            .map(|(b, y)| b * y)
            .sum::<C64>()
            - C64::new(1.0, 0.0)
    }

    /// `G ← (x₀^{d_i} H_i, chart equation)` from `H` at `x = y / x₀`.
    fn homogenized(&self, z: &[C64], h: &[C64], g: &mut [C64]) {
        for i in 0..self.n {
            g[i] = z[0].powi(self.degrees[i]) * h[i];
        }
        g[self.n] = self.chart_equation(z);
    }

    /// Rows `0..n` of `∂G/∂z` from `H` and `∂H/∂x` at `x`, and the chart row.
    fn jacobian(&self, z: &[C64], x: &[C64], h: &[C64], inner_jac: &[C64], jac: &mut [C64]) {
        let (n, m) = (self.n, self.n + 1);
        for i in 0..n {
            let d = self.degrees[i];
            let power = z[0].powi(d - 1);
            let row = &inner_jac[i * n..(i + 1) * n];
            let euler: C64 = row.iter().zip(x).map(|(a, v)| a * v).sum();
            jac[i * m] = power * (h[i] * d as f64 - euler);
            for k in 0..n {
                jac[i * m + 1 + k] = power * row[k];
            }
        }
        jac[n * m] = C64::new(1.0, 0.0);
        jac[n * m + 1..].copy_from_slice(&self.chart);
    }
}

impl<H: Homotopy + ?Sized> Homotopy for ChartHomotopy<'_, H> {
    fn dimension(&self) -> usize {
        self.n + 1
    }

    fn workspace_len(&self) -> usize {
        self.inner.workspace_len() + 3 * self.n + self.n * self.n
    }

    fn homogenizing_variable(&self) -> Option<usize> {
        Some(0)
    }

    fn evaluate(&self, z: &[C64], t: C64, work: &mut [C64], g: &mut [C64]) {
        let (inner, x, h, _, _) = self.split(work);
        self.affine(z, x);
        self.inner.evaluate(x, t, inner, h);
        self.homogenized(z, h, g);
    }

    fn evaluate_with_jacobian(
        &self,
        z: &[C64],
        t: C64,
        work: &mut [C64],
        g: &mut [C64],
        jac: &mut [C64],
    ) {
        let (inner, x, h, inner_jac, _) = self.split(work);
        self.affine(z, x);
        self.inner.evaluate_with_jacobian(x, t, inner, h, inner_jac);
        self.jacobian(z, x, h, inner_jac, jac);
        self.homogenized(z, h, g);
    }

    fn evaluate_time_derivative(&self, z: &[C64], t: C64, work: &mut [C64], dg: &mut [C64]) {
        let (inner, x, _, _, dh) = self.split(work);
        self.affine(z, x);
        self.inner.evaluate_time_derivative(x, t, inner, dh);
        for i in 0..self.n {
            dg[i] = z[0].powi(self.degrees[i]) * dh[i];
        }
        dg[self.n] = C64::new(0.0, 0.0);
    }

    fn breakpoints(&self) -> &[f64] {
        self.inner.breakpoints()
    }
}

/// `|x₀|` (relative to the chart point) at which a path the chart tracker stopped
/// counts as on the hyperplane at infinity: an affine root there would have norm
/// `10²⁰`, beyond anything double precision tracks (`des18_3`'s undecided chart
/// endpoints have `x₀` of 10⁻³²–10⁻²⁴).
const VANISHED: f64 = 1e-20;

/// Step budget of a chart path. In the chart a path to infinity ends at a finite,
/// usually singular, point on `x₀ = 0`, whose endgame costs several times the affine
/// path; a large finite root is reached in a few hundred steps (`pb601`: 210–240).
/// On PHCpack's demo suite one chart of 400 steps left 31 paths unconfirmed, most of
/// them out of steps at `t ≈ 1 − 10⁻⁴` with `x₀` of 10⁻⁹–10⁻¹⁰ (`stewgou40` 18,
/// `butcher8` 3, `butcher` 2); 4,000 steps confirm all of `butcher`'s and
/// `butcher8`'s and 10 of `stewgou40`'s (15 left in the suite), for 10 % (`stewgou40`,
/// `butcher`) to 40 % (`butcher8`, 0.07 → 0.10 s) more time on those systems and none
/// elsewhere.
const CHART_MAX_STEPS: usize = 4_000;

/// Seed offset of the chart, so that it differs from the homotopy's γ drawn from the
/// same seed.
const CHART_SEED: u64 = 0xc4a7_0001;

/// Largest condition number of a root recovered from a chart endpoint: the chart's
/// own estimate is meaningless there (its Jacobian scales with powers of a small
/// `x₀`), so the root must be a nonsingular one of the affine system.
const RECOVERED_MAX_CONDITION: f64 = 1e14;

/// Re-tracks every path of `paths` that the endgame sent to infinity because its norm
/// passed [`EndgameOptions::at_infinity_norm`](super::EndgameOptions::at_infinity_norm)
/// (not on the evidence of stable negative valuations of its power series, which is
/// how paths to infinity are classified otherwise) in the random chart of
/// `homotopy` (degrees `degrees`); a chart endpoint that is a nonsingular finite root
/// (its homogenising coordinate not zero, Newton's method on `H(·, 1)` converging)
/// and distinct from every finite endpoint (`same_point`) replaces the path's result.
/// A chart endpoint at infinity, singular, failed or already known leaves the path as
/// it was; the paths left neither confirmed nor recovered are tracked in up to
/// [`CHARTS`] charts in all.
pub(crate) fn recover_from_infinity<H, S>(
    homotopy: &H,
    degrees: &[u32],
    paths: &mut [PathResult],
    start: S,
    options: &TrackerOptions,
    seed: u64,
    same_point: impl Fn(&[C64], &[C64]) -> bool + Sync,
) -> ChartRecheck
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    // Classified by the norm cap: no valuation evidence of divergence.
    let capped = 0.5 * options.endgame.at_infinity_norm;
    let at_infinity: Vec<usize> = paths
        .iter()
        .filter(|p| p.status == PathStatus::AtInfinity && max_norm(&p.solution) >= capped)
        .map(|p| p.path_index)
        .collect();
    let mut outcome = ChartRecheck {
        rechecked: at_infinity.len(),
        unconfirmed_paths: at_infinity,
        ..ChartRecheck::default()
    };
    // The paths a chart left unconfirmed, once more in another random chart: its
    // paths meet other trouble spots (a path that reaches a known root, or stalls on
    // the way, in one chart rarely does so in the next: `pb601` at seed 17 found its
    // 18th root in the third chart). Those that stalled at `t = 1` on the hyperplane
    // itself ([`stalled_on_hyperplane`]) get one more chart only: the second one
    // confirms `cohn2`'s two, while `stewgou40`'s 7 stall in every chart (0.6 s each).
    let mut pending = std::mem::take(&mut outcome.unconfirmed_paths);
    for chart in 0..CHARTS {
        if pending.is_empty() {
            break;
        }
        let chart_seed = seed ^ CHART_SEED ^ (chart as u64).wrapping_mul(NEXT_CHART);
        let (pass, stalled) = recheck_in_chart(
            (homotopy, degrees, chart_seed),
            (paths, &pending),
            &start,
            options,
            &same_point,
        );
        outcome.confirmed += pass.confirmed;
        outcome.recovered += pass.recovered;
        pending = pass.unconfirmed_paths;
        if chart == 0 {
            pending.extend(stalled);
        } else {
            outcome.unconfirmed_paths.extend(stalled);
        }
    }
    outcome.unconfirmed_paths.extend(pending);
    outcome.unconfirmed_paths.sort_unstable();
    outcome
}

/// Whether a chart path stopped (failed) at `t = 1` to within 10⁻⁶ with its
/// homogenising coordinate below 10⁻⁸ of its norm: on the hyperplane at infinity as
/// far as the endgame got, though not below [`VANISHED`].
fn stalled_on_hyperplane(result: &PathResult) -> bool {
    matches!(result.status, PathStatus::Failed(_))
        && (C64::new(1.0, 0.0) - result.last_t).norm() <= 1e-6
        && result.solution[0].norm() <= 1e-8 * (1.0 + max_norm(&result.solution))
}

/// Random charts of [`recover_from_infinity`], each for the paths the ones before
/// left unconfirmed.
const CHARTS: usize = 3;

/// Seed offset between successive charts of [`recover_from_infinity`].
const NEXT_CHART: u64 = 0x2545_f491_4f6c_dd1d;

/// One chart pass of [`recover_from_infinity`] over the paths `indices` (in the chart
/// of seed `chart_seed`; `rechecked` is left 0), and the paths of `indices` left
/// unconfirmed because they [`stalled_on_hyperplane`] (not among the outcome's
/// `unconfirmed_paths`, which another chart may settle).
fn recheck_in_chart<H, S>(
    (homotopy, degrees, chart_seed): (&H, &[u32], u64),
    (paths, indices): (&mut [PathResult], &[usize]),
    start: &S,
    options: &TrackerOptions,
    same_point: &(impl Fn(&[C64], &[C64]) -> bool + Sync),
) -> (ChartRecheck, Vec<usize>)
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let mut outcome = ChartRecheck::default();
    let mut stalled = Vec::new();
    let chart = ChartHomotopy::new(homotopy, degrees, chart_seed);
    let target = TargetSystem { homotopy };
    let found = track_in_chart(&chart, indices, start, options);
    let mut known = finite_endpoints(paths);
    for (index, result) in found {
        // At infinity: classified there, or stopped (hyperplane test undecided, endgame
        // not converged) with its homogenising coordinate below any scale the affine
        // formulation could hold a root at.
        let on_hyperplane = matches!(result.status, PathStatus::Failed(_))
            && result.solution[0].norm() <= VANISHED * (1.0 + max_norm(&result.solution));
        if result.status == PathStatus::AtInfinity || on_hyperplane {
            outcome.confirmed += 1;
            continue;
        }
        // A finite chart endpoint, or one the hyperplane test could not place (its
        // Newton iterates neither converging nor shrinking `x₀`): Newton's method on the
        // affine target decides.
        let undecided = result.status == PathStatus::Failed(FailureReason::HyperplaneUndecided);
        if !result.status.is_finite() && !undecided {
            if stalled_on_hyperplane(&result) {
                stalled.push(index);
            } else {
                outcome.unconfirmed_paths.push(index);
            }
            continue;
        }
        let refined = newton_refine(&target, &chart.lower(&result.solution), &[], 1e-13, 8);
        let finite = refined
            .point
            .iter()
            .all(|v| v.re.is_finite() && v.im.is_finite());
        if !refined.is_nonsingular(RECOVERED_MAX_CONDITION)
            || !finite
            || known.iter().any(|y| same_point(y, &refined.point))
        {
            outcome.unconfirmed_paths.push(index);
            continue;
        }
        let path = &mut paths[index];
        path.record_nonsingular_root(&refined);
        path.steps += result.steps;
        path.rejected_steps += result.rejected_steps;
        path.last_t = result.last_t;
        known.push(refined.point);
        outcome.recovered += 1;
    }
    (outcome, stalled)
}

/// The paths `indices` of `start`, each lifted into `chart` and tracked there (at most
/// [`CHART_MAX_STEPS`] steps, the homogenising coordinate's valuation tested).
fn track_in_chart<H, S>(
    chart: &ChartHomotopy<'_, H>,
    indices: &[usize],
    start: &S,
    options: &TrackerOptions,
) -> Vec<(usize, PathResult)>
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let mut options = options.clone();
    options.step.max_steps = options.step.max_steps.min(CHART_MAX_STEPS);
    options.endgame.homogenizing_valuation_test = true;
    let n = chart.n;
    indices
        .par_iter()
        .map_init(
            || {
                (
                    Tracker::new(chart, options.clone()),
                    vec![C64::new(0.0, 0.0); n],
                    vec![C64::new(0.0, 0.0); n + 1],
                )
            },
            |(tracker, x, z), &index| {
                start(index, x);
                chart.lift(x, z);
                (index, tracker.track(z, index))
            },
        )
        .collect()
}

/// The finite endpoints of `paths`, in path order.
fn finite_endpoints(paths: &[PathResult]) -> Vec<Vec<C64>> {
    paths
        .iter()
        .filter(|p| p.status.is_finite())
        .map(|p| p.solution.clone())
        .collect()
}

/// Charts a failed path is re-tracked in by [`recover_failed_paths`], each for the
/// paths the ones before left failed.
const FAILED_PATH_CHARTS: usize = 4;

/// Charts whose endpoints must lie at infinity before [`recover_failed_paths`] names
/// a failed path at infinity: one chart route may stray onto another path's way to
/// infinity, two independent ones agreeing are the evidence the affine route lacked.
const AT_INFINITY_VOTES: usize = 2;

/// Largest relative residual `‖F(x)‖∞ / (1 + ‖x‖∞)` of a singular endpoint a chart
/// route gives a failed path ([`recover_failed_paths`]).
const RECOVERED_SINGULAR_RESIDUAL: f64 = 1e-8;

/// What [`recover_failed_paths`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct FailedRecovery {
    /// Failed paths now finite (a new nonsingular root, or a singular endpoint).
    pub recovered: usize,
    /// Paths still failed whose endpoints were at infinity in [`AT_INFINITY_VOTES`]
    /// charts, in path order: the caller names them at infinity once no other route
    /// (the conjugate completion) has placed a root at them.
    pub at_infinity: Vec<usize>,
}

/// Re-tracks every failed path of `paths` from its start in up to
/// [`FAILED_PATH_CHARTS`] random charts of `homotopy` (the homogenisation of
/// [`ChartHomotopy`]), where a path that runs far out in affine space stays finite.
/// A finite endpoint settles a path: one that Newton's method refines to a new
/// nonsingular root of the target (condition below the endgame's
/// `singular_condition`: a singular root refines to a condition of 10¹¹ on
/// `des22_24`, within the bound of [`RECOVERED_MAX_CONDITION`]) records that root;
/// any other finite endpoint the chart's endgame reached (off the hyperplane at
/// infinity, below the affine norm cap, residual below
/// [`RECOVERED_SINGULAR_RESIDUAL`]) is recorded singular, as the affine endgame labels
/// an endpoint above that condition number. An endpoint at infinity in one chart
/// settles nothing (a chart route may itself stray: on `chemequs` one did, from a
/// path whose root the conjugate completion then found); a path whose endpoints lie at
/// infinity in [`AT_INFINITY_VOTES`] charts is returned in
/// [`FailedRecovery::at_infinity`].
///
/// On PHCpack's `des22_24`, paths of the polyhedral homotopy's second stage pass
/// norms of 10⁸ within `t < 0.03` (the random system `Q` has roots of norm 3·10⁴),
/// where the affine tracker stops (`DivergedBeforeEndgame`).
pub(crate) fn recover_failed_paths<H, S>(
    (homotopy, degrees, seed): (&H, &[u32], u64),
    paths: &mut [PathResult],
    start: S,
    options: &TrackerOptions,
    same_point: impl Fn(&[C64], &[C64]) -> bool + Sync,
) -> FailedRecovery
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let target = TargetSystem { homotopy };
    let norm_cap = 0.5 * options.endgame.at_infinity_norm;
    let mut recovered = 0;
    let mut votes = vec![0usize; paths.len()];
    for pass in 0..FAILED_PATH_CHARTS {
        let failed: Vec<usize> = paths
            .iter()
            .filter(|p| {
                matches!(p.status, PathStatus::Failed(_)) && votes[p.path_index] < AT_INFINITY_VOTES
            })
            .map(|p| p.path_index)
            .collect();
        if failed.is_empty() {
            break;
        }
        let chart_seed = seed ^ FAILED_CHART_SEED ^ (pass as u64).wrapping_mul(NEXT_CHART);
        let chart = ChartHomotopy::new(homotopy, degrees, chart_seed);
        let found = track_in_chart(&chart, &failed, &start, options);
        let mut known = finite_endpoints(paths);
        for (index, result) in found {
            let off_hyperplane =
                result.solution[0].norm() > VANISHED * (1.0 + max_norm(&result.solution));
            if result.status == PathStatus::AtInfinity
                || (matches!(result.status, PathStatus::Failed(_)) && !off_hyperplane)
            {
                votes[index] += 1;
                continue;
            }
            if !result.status.is_finite() || !off_hyperplane {
                continue;
            }
            let lowered = chart.lower(&result.solution);
            if !lowered.iter().all(|v| v.re.is_finite() && v.im.is_finite())
                || max_norm(&lowered) >= norm_cap
            {
                continue;
            }
            let refined = newton_refine(&target, &lowered, &[], 1e-13, 8);
            let finite = refined
                .point
                .iter()
                .all(|v| v.re.is_finite() && v.im.is_finite());
            let path = &mut paths[index];
            if finite && refined.is_nonsingular(options.endgame.singular_condition) {
                if known.iter().any(|y| same_point(y, &refined.point)) {
                    continue;
                }
                path.record_nonsingular_root(&refined);
                known.push(refined.point);
            } else {
                let residual = target_residual(&target, &lowered);
                if residual > RECOVERED_SINGULAR_RESIDUAL * (1.0 + max_norm(&lowered)) {
                    continue;
                }
                path.status = PathStatus::Singular;
                path.solution = lowered;
                path.residual = residual;
                path.condition = result.condition;
                path.winding_number = result.winding_number;
            }
            path.steps += result.steps;
            path.rejected_steps += result.rejected_steps;
            path.last_t = result.last_t;
            recovered += 1;
        }
    }
    let at_infinity = paths
        .iter()
        .filter(|p| {
            matches!(p.status, PathStatus::Failed(_)) && votes[p.path_index] >= AT_INFINITY_VOTES
        })
        .map(|p| p.path_index)
        .collect();
    FailedRecovery {
        recovered,
        at_infinity,
    }
}

/// `‖F(x)‖∞` of the target system at `x`.
fn target_residual<H: Homotopy + ?Sized>(target: &TargetSystem<'_, H>, x: &[C64]) -> f64 {
    let mut work = vec![C64::new(0.0, 0.0); target.workspace_len()];
    let mut f = vec![C64::new(0.0, 0.0); x.len()];
    target.evaluate(x, &mut work, &mut f);
    max_norm(&f)
}

/// Seed offset of the charts of [`recover_failed_paths`], apart from those of
/// [`recover_from_infinity`].
const FAILED_CHART_SEED: u64 = 0xfa11_0002;

/// What [`recover_from_infinity`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct ChartRecheck {
    /// Paths re-tracked in the chart.
    pub rechecked: usize,
    /// Of those, paths whose chart endpoint lies at infinity too (`x₀ = 0`).
    pub confirmed: usize,
    /// Paths whose chart route reached a new finite root.
    pub recovered: usize,
    /// Paths left at infinity that the chart neither confirmed nor recovered (it
    /// failed, or reached a root already known), in path order: their classification
    /// rests on the norm cap alone.
    pub unconfirmed_paths: Vec<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::StraightLineHomotopy;
    use crate::homotopy::test_support::read_xy as read;
    use crate::system::Evaluator;

    fn c(re: f64, im: f64) -> C64 {
        C64::new(re, im)
    }

    /// The chart system's Jacobian and time derivative agree with central
    /// differences of its values.
    #[test]
    fn derivatives_match_differences() {
        let read = |equations: &str| {
            let text = format!("INPUT\nvariable_group x, y;\nfunction f, g;\n{equations}\nEND;\n");
            crate::system::bertini::read(&text).unwrap().compile()
        };
        let target = read("f = x^2*y - 2*y + 0.5;\ng = x*y - y^2 + 3;");
        let start = read("f = x^3 - 1;\ng = y^2 - 1;");
        let inner = StraightLineHomotopy::new(&start, &target, vec![], c(0.6, 0.8));
        let chart = ChartHomotopy::new(&inner, &[3, 2], 7);
        let mut work = vec![c(0.0, 0.0); chart.workspace_len()];
        let z = [c(0.7, -0.2), c(0.3, 0.4), c(-0.5, 0.1)];
        let t = c(0.4, 0.0);
        let (mut g, mut jac, mut dg) = (
            vec![c(0.0, 0.0); 3],
            vec![c(0.0, 0.0); 9],
            vec![c(0.0, 0.0); 3],
        );
        let mut g2 = g.clone();
        chart.evaluate_with_jacobian_and_time_derivative(
            &z, t, &mut work, &mut g, &mut jac, &mut dg,
        );
        chart.evaluate(&z, t, &mut work, &mut g2);
        assert_eq!(g, g2);
        let h = 1e-6;
        let (mut plus, mut minus) = (vec![c(0.0, 0.0); 3], vec![c(0.0, 0.0); 3]);
        for k in 0..3 {
            let (mut zp, mut zm) = (z, z);
            zp[k] += h;
            zm[k] -= h;
            chart.evaluate(&zp, t, &mut work, &mut plus);
            chart.evaluate(&zm, t, &mut work, &mut minus);
            for i in 0..3 {
                let difference = (plus[i] - minus[i]) / (2.0 * h);
                assert!((difference - jac[i * 3 + k]).norm() < 1e-6, "{i} {k}");
            }
        }
        chart.evaluate(&z, t + h, &mut work, &mut plus);
        chart.evaluate(&z, t - h, &mut work, &mut minus);
        for i in 0..3 {
            assert!(((plus[i] - minus[i]) / (2.0 * h) - dg[i]).norm() < 1e-6);
        }
        // Lift and lower are inverse; a lifted point satisfies the chart equation.
        let point = [c(2.0, -1.0), c(0.25, 3.0)];
        let mut lifted = [c(0.0, 0.0); 3];
        chart.lift(&point, &mut lifted);
        assert!(chart.chart_equation(&lifted).norm() < 1e-14);
        let back = chart.lower(&lifted);
        assert!(back.iter().zip(&point).all(|(a, b)| (a - b).norm() < 1e-14));
        let _ = target.num_variables();
    }

    /// A path the endgame sent to infinity by the norm cap although it ends at a
    /// finite root: the chart route finds that root; a path whose chart endpoint is
    /// a root already known stays at infinity.
    #[test]
    fn a_capped_path_to_a_large_root_is_recovered_in_the_chart() {
        use crate::homotopy::{TotalDegreeStartSystem, newton::max_norm as norm};
        // Roots (±300, 2): norm 300.
        let target = read("f = x^2 - 90000;\ng = y - 2;");
        let start = TotalDegreeStartSystem::new(vec![2, 1]);
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], c(0.6, -0.8));
        let options = TrackerOptions::default();
        let begin = |index: usize, point: &mut [C64]| start.start_solution(index as u64, point);
        let mut paths: Vec<PathResult> = (0..2)
            .map(|i| {
                let mut point = vec![c(0.0, 0.0); 2];
                begin(i, &mut point);
                Tracker::new(&homotopy, options.clone()).track(&point, i)
            })
            .collect();
        assert!(paths.iter().all(|p| p.status == PathStatus::Nonsingular));
        let root = paths[0].solution.clone();
        // Path 0 as the cap would have left it.
        paths[0].status = PathStatus::AtInfinity;
        paths[0].solution = vec![c(2e8, 0.0), c(2.0, 0.0)];
        let same = |a: &[C64], b: &[C64]| {
            a.iter()
                .zip(b)
                .all(|(u, v)| (u - v).norm() <= 1e-6 * (1.0 + norm(a)))
        };
        let outcome =
            recover_from_infinity(&homotopy, &[2, 1], &mut paths, begin, &options, 5, same);
        assert_eq!((outcome.rechecked, outcome.recovered), (1, 1));
        assert_eq!(outcome.unconfirmed_paths.len(), 0);
        assert_eq!(paths[0].status, PathStatus::Nonsingular);
        assert!(same(&paths[0].solution, &root), "{:?}", paths[0].solution);
        // Known already: path 1's root given to path 0 as well is not counted twice.
        paths[0].status = PathStatus::AtInfinity;
        paths[0].solution = vec![c(2e8, 0.0), c(2.0, 0.0)];
        paths[1].solution = root.clone();
        let outcome =
            recover_from_infinity(&homotopy, &[2, 1], &mut paths, begin, &options, 5, same);
        assert_eq!(outcome.recovered, 0);
        // Its chart endpoint is the known root: not a confirmation of infinity.
        assert_eq!(outcome.unconfirmed_paths.len(), 1);
        assert_eq!(paths[0].status, PathStatus::AtInfinity);
    }

    /// Every path of the total-degree homotopy to `f, g` (degrees `degrees`) tracked in
    /// a chart with the valuation test on: status, steps and the affine endpoint.
    fn chart_paths(equations: &str, degrees: [u32; 2]) -> Vec<(PathStatus, usize, Vec<C64>)> {
        use crate::homotopy::TotalDegreeStartSystem;
        let target = read(equations);
        let start = TotalDegreeStartSystem::new(degrees.to_vec());
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], c(0.6, -0.8));
        let chart = ChartHomotopy::new(&homotopy, &degrees, 11);
        let mut options = TrackerOptions::default();
        options.step.max_steps = CHART_MAX_STEPS;
        options.endgame.homogenizing_valuation_test = true;
        let mut tracker = Tracker::new(&chart, options);
        (0..(degrees[0] * degrees[1]) as usize)
            .map(|index| {
                let (mut x, mut z) = (vec![c(0.0, 0.0); 2], vec![c(0.0, 0.0); 3]);
                start.start_solution(index as u64, &mut x);
                chart.lift(&x, &mut z);
                let result = tracker.track(&z, index);
                (result.status, result.steps, chart.lower(&result.solution))
            })
            .collect()
    }

    /// With the valuation test on, a path to a regular point at infinity is still
    /// classified there, and the finite path reaches its root (`x·y = 1`, `y = 2`).
    #[test]
    fn a_path_to_infinity_is_classified_on_the_hyperplane() {
        let paths = chart_paths("f = x*y - 1;\ng = y - 2;", [2, 1]);
        let finite: Vec<&Vec<C64>> = paths
            .iter()
            .filter(|(status, _, _)| *status == PathStatus::Nonsingular)
            .map(|(_, _, root)| root)
            .collect();
        assert_eq!(finite.len(), 1, "{paths:?}");
        assert!((finite[0][0] - c(0.5, 0.0)).norm() < 1e-10, "{paths:?}");
        assert!((finite[0][1] - c(2.0, 0.0)).norm() < 1e-10, "{paths:?}");
        let at_infinity = paths.iter().filter(|p| p.0 == PathStatus::AtInfinity);
        assert_eq!(at_infinity.count(), 1, "{paths:?}");
    }

    /// `x·y = 1`, `x·y = 2`: no finite root; the four paths end at two double points
    /// on the hyperplane at infinity. The valuation test classifies each there in a
    /// few radii (23–81 steps); without it two of them fail (the Cauchy endgame does
    /// not converge at the singular point).
    #[test]
    fn paths_to_singular_points_at_infinity_are_classified() {
        for (status, steps, _) in chart_paths("f = x*y - 1;\ng = x*y - 2;", [2, 2]) {
            assert_eq!(status, PathStatus::AtInfinity);
            assert!(steps < 120, "{steps} steps");
        }
    }
}

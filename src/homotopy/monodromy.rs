//! Monodromy solving of parametric systems, certified by a trace test.
//!
//! **Monodromy** (Duff, Hill, Jensen, Lee, Leykin & Sommars 2019): the solutions of
//! `F(x; p₀) = 0` over a generic parameter point form one fiber of a branched cover of
//! parameter space. Tracking known solutions around a loop `p₀ → p₁ → p₂ → p₀` through
//! random complex points permutes the fiber, so new solutions appear; repeating with
//! fresh loops until `max_stagnant_loops` loops in a row add nothing populates the fiber
//! from a single start pair `(x₀, p₀)`.
//!
//! **Trace test** (Sommese, Verschelde & Wampler 2002; Leykin, Rodriguez & Sottile
//! 2018): stagnation is no proof. Restrict the family to a random line
//! `p(μ) = p₀ + μ v`; the incidence curve `C = {(x, μ) : F(x; p₀ + μ v) = 0}` meets a
//! generic hyperplane `L_c = {μ = a·x + c}` in `deg C` points (a witness set), and for
//! the *parallel* pencil `c ↦ L_c` the sum of those points is an affine-linear function
//! of `c` — but only if no point is missing. We move the known fiber onto `L_c`
//! (a parameter homotopy from the special slice `μ = 0`), populate the witness set by
//! monodromy in the slice coefficients `(a, c)`, evaluate the sums `s(c), s(c ± δ)`, and
//! report `‖s(c+δ) − 2 s(c) + s(c−δ)‖ / Σ‖w‖` as `trace_residual` (≈ 1e-14 when
//! complete, O(1) when a point is missing). Witness points beyond the fiber's count
//! (branches of `C` escaping to infinity as `μ → 0`) are tracked back to `μ = 0`; any
//! finite endpoint not yet known is added, so a passing trace test certifies the fiber.
//! Trace linearity on a pencil that is generic for `C` is the standard criterion; the
//! slice through `μ` and `x` is what makes the pencil generic even when solutions of
//! the family escape to infinity at special parameters (the plain pencil `p₀ + c v`
//! would have a rational, not linear, trace there).

use super::homotopies::{ParameterHomotopy, PolylineParameterHomotopy};
use super::refine::contains_point;
use super::solve::{HomotopyError, check_finite, check_length, check_square};
use super::tracker::{PathResult, PathStatus, Tracker, TrackerOptions};
use crate::C64;
use crate::random::{SeededRng, complex_normal, seeded};
use crate::system::Evaluator;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Options of [`monodromy_solve`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MonodromyOptions {
    /// Tracker options for the loops.
    pub tracker: TrackerOptions,
    /// Stop as soon as this many solutions are known (if given; the trace test still runs).
    pub target_solution_count: Option<usize>,
    /// Stop after this many consecutive loops without a new solution.
    pub max_stagnant_loops: usize,
    /// Hard limit on the number of loops.
    pub max_loops: usize,
    /// Two solutions are equal if closer than `duplicate_tolerance · (1 + ‖x‖∞)`.
    pub duplicate_tolerance: f64,
    /// Run the trace test.
    pub trace_test: bool,
    /// Trace residual below which the solution set counts as certified complete.
    pub trace_tolerance: f64,
    /// Rounds of witness-set monodromy + trace evaluation while the trace fails.
    pub trace_rounds: usize,
    /// `Some(k)`: the trace test slices and sums only the first `k` unknowns (and `μ`),
    /// i.e. it certifies the projection of the incidence curve to those coordinates.
    /// For Lagrange systems whose multipliers (the last unknowns) diverge along the
    /// curve while the coordinates stay finite: those branches have points at infinity
    /// on every slice involving the multipliers, inflating the witness set, but finite
    /// ends in the projection. `None`: every unknown (the default).
    #[serde(default)]
    pub trace_slice_unknowns: Option<usize>,
}

impl Default for MonodromyOptions {
    fn default() -> Self {
        MonodromyOptions {
            tracker: TrackerOptions::default(),
            target_solution_count: None,
            max_stagnant_loops: 5,
            max_loops: 500,
            duplicate_tolerance: 1e-8,
            trace_test: true,
            trace_tolerance: 1e-8,
            trace_rounds: 4,
            trace_slice_unknowns: None,
        }
    }
}

/// Result of [`monodromy_solve`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MonodromyResult {
    /// All solutions found of `F(x; parameters) = 0`.
    pub solutions: Vec<Vec<C64>>,
    /// The parameter point (the start parameters).
    pub parameters: Vec<C64>,
    /// Monodromy loops tracked over the fiber.
    pub loops: usize,
    /// Loops tracked over the witness set of the trace test.
    pub witness_loops: usize,
    /// Number of points of the trace test's witness set (`deg C ≥` fiber count).
    pub witness_points: usize,
    /// Fiber solutions the trace test's back-tracking added after monodromy stagnated.
    pub added_by_trace_test: usize,
    /// Trace residual (`None` if the test was not run or could not be carried out).
    pub trace_residual: Option<f64>,
    /// `trace_residual < trace_tolerance`.
    pub certified: bool,
    /// Paths that failed during the loops (they never add solutions).
    pub failed_paths: usize,
}

fn random_point(rng: &mut SeededRng, m: usize, scale: f64) -> Vec<C64> {
    (0..m).map(|_| complex_normal(rng) * scale).collect()
}

fn parameter_scale(p: &[C64]) -> f64 {
    if p.is_empty() {
        1.0
    } else {
        (p.iter().map(|v| v.norm_sqr()).sum::<f64>() / p.len() as f64)
            .sqrt()
            .max(1.0)
    }
}

/// Every point of `solutions` tracked over `system` around one random triangle
/// `base → p₁ → p₂ → base` (`p₁`, `p₂` complex normal of `base`'s scale, the parameters
/// `pinned` at their base values), in parallel, results in the order of `solutions`.
fn around_a_loop<F: Evaluator + ?Sized>(
    system: &F,
    (base, pinned): (&[C64], std::ops::Range<usize>),
    solutions: &[Vec<C64>],
    tracker: &TrackerOptions,
    rng: &mut SeededRng,
) -> Vec<PathResult> {
    let (m, scale) = (base.len(), parameter_scale(base));
    let mut p1 = random_point(rng, m, scale);
    let mut p2 = random_point(rng, m, scale);
    p1[pinned.clone()].copy_from_slice(&base[pinned.clone()]);
    p2[pinned.clone()].copy_from_slice(&base[pinned]);
    let homotopy =
        PolylineParameterHomotopy::through(system, vec![base.to_vec(), p1, p2, base.to_vec()]);
    solutions
        .par_iter()
        .enumerate()
        .map_init(
            || Tracker::new(&homotopy, tracker.clone()),
            |tracker, (i, x)| tracker.track_between(x, 0.0, 1.0, i),
        )
        .collect()
}

/// Tracks every point of `solutions` over `system` around random triangles based at
/// `base` (the parameters `pinned` keep their base values), adding new endpoints, until
/// stagnation. Returns (loops, failed paths).
fn populate<F: Evaluator + ?Sized>(
    system: &F,
    (base, pinned): (&[C64], std::ops::Range<usize>),
    solutions: &mut Vec<Vec<C64>>,
    options: &MonodromyOptions,
    target: Option<usize>,
    rng: &mut SeededRng,
) -> (usize, usize) {
    let mut loops = 0;
    let mut stagnant = 0;
    let mut failed = 0;
    while stagnant < options.max_stagnant_loops
        && loops < options.max_loops
        && target.is_none_or(|t| solutions.len() < t)
    {
        let results = around_a_loop(
            system,
            (base, pinned.clone()),
            solutions,
            &options.tracker,
            rng,
        );
        loops += 1;
        let mut new = 0;
        for r in results {
            if r.status == PathStatus::Nonsingular {
                if !contains_point(solutions, &r.solution, options.duplicate_tolerance) {
                    solutions.push(r.solution);
                    new += 1;
                }
            } else {
                failed += 1;
            }
        }
        if new == 0 {
            stagnant += 1;
        } else {
            stagnant = 0;
        }
    }
    (loops, failed)
}

/// What [`complete_fiber`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FiberCompletion {
    /// Monodromy loops tracked.
    pub loops: usize,
    /// Paths tracked over all loops.
    pub tracked: usize,
    /// Solutions added to the fiber.
    pub added: usize,
    /// Loop paths that failed (they add nothing).
    pub failed: usize,
    /// Whether the loops stopped because too many of their paths failed
    /// ([`COMPLETION_MAX_FAILED`]): the fiber may still lack points the loops could
    /// have found.
    pub abandoned: bool,
}

/// Completes the known part `solutions` of the fiber of `F(x; p) = 0` over `base` by
/// monodromy in the *restricted* family where only the first `moving` parameters vary
/// (the others, e.g. a design's fixed shape constants, are pinned at their `base`
/// values): every known solution is tracked around random triangles
/// `base → p₁ → p₂ → base` (Duff, Hill, Jensen, Lee, Leykin and Sommars, *Solving
/// polynomial systems via homotopy continuation and monodromy*, IMA J. Numer. Anal.
/// 39, 2019), and each new nonsingular endpoint, refined by Newton's method at `base`,
/// is added, until `target` solutions are known, `stagnant_loops` loops in a row add
/// none, or more than [`COMPLETION_MAX_FAILED`] of the loop paths failed. Loops permute
/// the fiber of each irreducible component of the incidence variety, so a fiber that
/// meets every component is completed (with probability one for random loops);
/// stagnation is no proof of completeness. Deterministic for the state of `rng` (loops
/// drawn in sequence, paths tracked in parallel, endpoints merged in path order).
pub fn complete_fiber<F: Evaluator + ?Sized>(
    system: &F,
    (base, moving): (&[C64], usize),
    solutions: &mut Vec<Vec<C64>>,
    (target, stagnant_loops): (usize, usize),
    tracker: &TrackerOptions,
    rng: &mut SeededRng,
) -> FiberCompletion {
    let m = base.len();
    let known = solutions.len();
    let mut outcome = FiberCompletion::default();
    let mut tracker = tracker.clone();
    tracker.step.max_steps = tracker.step.max_steps.min(COMPLETION_MAX_STEPS);
    let tracker = &tracker;
    let mut stagnant = 0;
    while stagnant < stagnant_loops
        && outcome.loops < COMPLETION_MAX_LOOPS
        && solutions.len() < target
    {
        // The first loop carries at most COMPLETION_TRIAL_PATHS points: where the family
        // is hard to track, their failures give the loops up at a fraction of a loop.
        let carried = if outcome.loops == 0 {
            &solutions[..solutions.len().min(COMPLETION_TRIAL_PATHS)]
        } else {
            &solutions[..]
        };
        let results = around_a_loop(system, (base, moving.min(m)..m), carried, tracker, rng);
        outcome.loops += 1;
        outcome.tracked += results.len();
        let before = solutions.len();
        for result in results {
            if result.status != PathStatus::Nonsingular {
                outcome.failed += 1;
                continue;
            }
            if contains_point(solutions, &result.solution, COMPLETION_DUPLICATE) {
                continue;
            }
            let refined = super::refine::newton_refine(system, &result.solution, base, 1e-13, 8);
            if refined.converged
                && refined.condition < COMPLETION_MAX_CONDITION
                && !contains_point(solutions, &refined.point, COMPLETION_DUPLICATE)
            {
                solutions.push(refined.point);
            }
        }
        if solutions.len() < target
            && outcome.failed as f64 > COMPLETION_MAX_FAILED * outcome.tracked as f64
        {
            outcome.abandoned = true;
            break;
        }
        stagnant = if solutions.len() == before {
            stagnant + 1
        } else {
            0
        };
    }
    outcome.added = solutions.len() - known;
    outcome
}

/// Loops [`complete_fiber`] tracks at most.
const COMPLETION_MAX_LOOPS: usize = 32;

/// Step budget of a loop path of [`complete_fiber`] (three segments): where the family
/// tracks well a loop path needs far fewer (the 3-RPR seed stages of a platform
/// congruent with the base or with two coincident anchors give the same counts in
/// the same time with 300 steps as with 1,500), and where it does not, a path that
/// crawls costs a few hundred steps before it counts as failed (two base anchors 10⁻⁴
/// apart: 1.0 s → 0.3 s for a seed point whose loops are then abandoned).
const COMPLETION_MAX_STEPS: usize = 300;

/// Points the first loop of [`complete_fiber`] carries: a trial of the family's
/// trackability (two base anchors 10⁻⁴ apart: 20–35 % of loop paths fail) before
/// loops over every point.
const COMPLETION_TRIAL_PATHS: usize = 16;

/// Relative distance under which [`complete_fiber`] takes two solutions for one.
const COMPLETION_DUPLICATE: f64 = 1e-8;

/// Fraction of failed loop paths above which [`complete_fiber`] gives up: where the
/// family is hard to track at random parameters, loops lose the very points they
/// should find. Measured on the 3-RPR seed stages (two loops each): 0 % on a base
/// congruent with or similar to the platform, at most 12 % on collinear anchors, and
/// 20–35 % on two anchors of a rigid part 10⁻⁴ apart.
pub const COMPLETION_MAX_FAILED: f64 = 0.15;

/// Condition bound of a solution [`complete_fiber`] adds (one the loop's tracker
/// ended as nonsingular, and Newton's method converges to at `base`): far out along
/// isotropic lines simple critical points have unscaled condition numbers up to
/// about 10¹⁴.
const COMPLETION_MAX_CONDITION: f64 = 1e15;

/// Populates all solutions of `F(x; start_parameters) = 0` from one start solution by
/// monodromy, then certifies the set with the trace test (module documentation).
/// Deterministic for a `seed` (loops drawn sequentially; paths tracked in parallel).
pub fn monodromy_solve<F: Evaluator + ?Sized>(
    system: &F,
    start_solution: &[C64],
    start_parameters: &[C64],
    options: &MonodromyOptions,
    seed: u64,
) -> Result<MonodromyResult, HomotopyError> {
    let n = system.num_variables();
    let m = system.num_parameters();
    check_square(system)?;
    check_length("start_solution", n, start_solution.len())?;
    check_length("start_parameters", m, start_parameters.len())?;
    check_finite("start_solution", start_solution)?;
    check_finite("start_parameters", start_parameters)?;
    let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
    let mut f = vec![C64::new(0.0, 0.0); n];
    system.evaluate(start_solution, start_parameters, &mut work, &mut f);
    let scale = 1.0 + start_solution.iter().fold(0.0f64, |a, v| a.max(v.norm()));
    let residual = f.iter().fold(0.0f64, |a, v| a.max(v.norm()));
    if residual > 1e-6 * scale * scale {
        return Err(HomotopyError::InvalidStartPair { residual });
    }
    let mut rng = seeded(seed);
    let mut solutions = vec![start_solution.to_vec()];
    let (loops, mut failed) = populate(
        system,
        (start_parameters, 0..0),
        &mut solutions,
        options,
        options.target_solution_count,
        &mut rng,
    );
    let mut result = MonodromyResult {
        solutions,
        parameters: start_parameters.to_vec(),
        loops,
        witness_loops: 0,
        witness_points: 0,
        added_by_trace_test: 0,
        trace_residual: None,
        certified: false,
        failed_paths: 0,
    };
    if options.trace_test
        && m > 0
        && let Some(trace) = trace_test(
            system,
            &result.parameters,
            &result.solutions,
            options,
            &mut rng,
        )
    {
        {
            failed += trace.failed_paths;
            result.trace_residual = Some(trace.residual);
            result.certified = trace.residual < options.trace_tolerance;
            result.witness_loops = trace.witness_loops;
            result.witness_points = trace.witness_points;
            result.added_by_trace_test = trace.added_solutions.len();
            result.solutions.extend(trace.added_solutions);
        }
    }
    result.failed_paths = failed;
    Ok(result)
}

/// Outcome of [`trace_test`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TraceCertificate {
    /// `‖s(c+δ) − 2 s(c) + s(c−δ)‖∞ / (1 + Σ‖w‖∞)` over the witness set.
    pub residual: f64,
    /// Size of the witness set on the generic slice.
    pub witness_points: usize,
    /// Monodromy loops run on the witness set.
    pub witness_loops: usize,
    /// Fiber solutions reached by tracking surplus witness points back to `μ = 0` that
    /// were not in the given set.
    pub added_solutions: Vec<Vec<C64>>,
    /// Paths that failed.
    pub failed_paths: usize,
}

/// The trace test of the module documentation for the fiber `solutions` of
/// `F(x; parameters) = 0`. The witness set is populated by monodromy with
/// `options.max_stagnant_loops` (0: the moved fiber only, which tests the fiber itself
/// when `deg C` equals the fiber count). `None` if no witness point could be formed.
pub fn trace_test<F: Evaluator + ?Sized>(
    system: &F,
    parameters: &[C64],
    solutions: &[Vec<C64>],
    options: &MonodromyOptions,
    rng: &mut SeededRng,
) -> Option<TraceCertificate> {
    let n = system.num_variables();
    let m = system.num_parameters();
    let direction = random_point(rng, m, parameter_scale(parameters));
    let curve = IncidenceSlice {
        system,
        base: parameters.to_vec(),
        direction,
    };
    let special = vec![C64::new(0.0, 0.0); n + 1];
    let mut generic = random_point(rng, n + 1, 1.0);
    // Slice coefficients of the unknowns left out of the slice stay zero.
    let sliced = options.trace_slice_unknowns.unwrap_or(n).min(n);
    for a in &mut generic[sliced..n] {
        *a = C64::new(0.0, 0.0);
    }
    let track = |from: &[C64], to: &[C64], starts: &[Vec<C64>], endgame: bool| {
        let homotopy = ParameterHomotopy::segment(&curve, from, to);
        starts
            .par_iter()
            .enumerate()
            .map_init(
                || Tracker::new(&homotopy, options.tracker.clone()),
                |tracker, (i, x)| {
                    if endgame {
                        tracker.track(x, i)
                    } else {
                        tracker.track_between(x, 0.0, 1.0, i)
                    }
                },
            )
            .collect::<Vec<_>>()
    };
    // Fiber → witness points on the generic slice.
    let lifted: Vec<Vec<C64>> = solutions
        .iter()
        .map(|x| {
            let mut y = x.clone();
            y.push(C64::new(0.0, 0.0));
            y
        })
        .collect();
    let mut failed = 0;
    let mut witness: Vec<Vec<C64>> = Vec::new();
    for r in track(&special, &generic, &lifted, false) {
        if r.status == PathStatus::Nonsingular
            && !contains_point(&witness, &r.solution, options.duplicate_tolerance)
        {
            witness.push(r.solution);
        } else {
            failed += 1;
        }
    }
    if witness.is_empty() {
        return None;
    }
    // Populate, test; if the trace is not linear yet, keep looping (up to
    // `trace_rounds` rounds): a failing trace means witness points are missing.
    let delta = complex_normal(rng) * 0.5;
    let mut witness_loops = 0;
    let mut residual = f64::INFINITY;
    for round in 0..options.trace_rounds.max(1) {
        // A failing trace proves points are missing: each further round allows twice
        // as many fruitless loops before it gives up.
        let round_options = MonodromyOptions {
            max_stagnant_loops: options.max_stagnant_loops << round.min(8),
            ..options.clone()
        };
        let (loops, witness_failed) = populate(
            &curve,
            (&generic, sliced..n),
            &mut witness,
            &round_options,
            None,
            rng,
        );
        witness_loops += loops;
        failed += witness_failed;
        match trace_residual(&witness, (&generic, sliced), delta, &track) {
            Some(r) => residual = r,
            None => {
                failed += 1;
                residual = f64::INFINITY;
            }
        }
        if residual < options.trace_tolerance || options.max_stagnant_loops == 0 {
            break;
        }
    }
    // Witness points not coming from the known fiber: back to μ = 0 with endgame.
    let mut added_solutions: Vec<Vec<C64>> = Vec::new();
    if witness.len() > solutions.len() {
        for r in track(&generic, &special, &witness, true) {
            if r.status.is_finite() {
                let x = &r.solution[..n];
                if !contains_point(solutions, x, 1e-6) && !contains_point(&added_solutions, x, 1e-6)
                {
                    added_solutions.push(x.to_vec());
                }
            }
        }
    }
    Some(TraceCertificate {
        residual,
        witness_points: witness.len(),
        witness_loops,
        added_solutions,
        failed_paths: failed,
    })
}

/// `‖s(c+δ) − 2 s(c) + s(c−δ)‖∞ / (1 + Σ‖w‖∞)` for the witness set on the slice
/// `generic` (last coordinate c), over the first `sliced` unknowns and `μ`; `None` if a
/// path fails.
fn trace_residual<T>(
    witness: &[Vec<C64>],
    (generic, sliced): (&[C64], usize),
    delta: C64,
    track: &T,
) -> Option<f64>
where
    T: Fn(&[C64], &[C64], &[Vec<C64>], bool) -> Vec<super::tracker::PathResult>,
{
    let last = generic.len() - 1;
    let mut sums = [
        vec![C64::new(0.0, 0.0); generic.len()],
        vec![C64::new(0.0, 0.0); generic.len()],
    ];
    for (k, sign) in [1.0, -1.0].into_iter().enumerate() {
        let mut moved = generic.to_vec();
        moved[last] += delta * sign;
        for r in track(generic, &moved, witness, false) {
            if r.status != PathStatus::Nonsingular {
                return None;
            }
            for (s, v) in sums[k].iter_mut().zip(&r.solution) {
                *s += v;
            }
        }
    }
    let traced = || (0..sliced).chain(std::iter::once(last));
    let mut magnitude = 1.0;
    let mut center = vec![C64::new(0.0, 0.0); generic.len()];
    for w in witness {
        magnitude += traced().fold(0.0f64, |a, i| a.max(w[i].norm()));
        for (s, v) in center.iter_mut().zip(w) {
            *s += v;
        }
    }
    let second_difference = traced()
        .map(|i| (sums[0][i] - 2.0 * center[i] + sums[1][i]).norm())
        .fold(0.0f64, f64::max);
    Some(second_difference / magnitude)
}

/// The incidence curve of `F` over the line `p₀ + μ v`, cut by the hyperplane
/// `μ = a·x + c`: unknowns `(x, μ)`, parameters `(a, c)`, equations
/// `F(x; p₀ + μ v) = 0` and `μ − a·x − c = 0`.
pub struct IncidenceSlice<'a, F: Evaluator + ?Sized> {
    system: &'a F,
    base: Vec<C64>,
    direction: Vec<C64>,
}

impl<F: Evaluator + ?Sized> IncidenceSlice<'_, F> {
    fn layout(&self) -> (usize, usize) {
        (self.system.num_variables(), self.system.num_parameters())
    }

    /// `p ← p₀ + μ v`, the family's parameters at `μ = x[n]`, at the head of `work`;
    /// returns `(n, p, the rest of work)`.
    fn parameters_at<'w>(
        &self,
        x: &[C64],
        work: &'w mut [C64],
    ) -> (usize, &'w [C64], &'w mut [C64]) {
        let (n, m) = self.layout();
        let (p, rest) = work.split_at_mut(m);
        for ((pi, b), d) in p.iter_mut().zip(&self.base).zip(&self.direction) {
            *pi = b + x[n] * d;
        }
        (n, p, rest)
    }

    /// `μ − a·x − c`, the slice equation at `(x, μ)` with `q = (a, c)`.
    fn slice_residual(x: &[C64], q: &[C64]) -> C64 {
        let n = x.len() - 1;
        let slice: C64 = q[..n].iter().zip(&x[..n]).map(|(a, v)| a * v).sum();
        x[n] - slice - q[n]
    }
}

impl<F: Evaluator + ?Sized> Evaluator for IncidenceSlice<'_, F> {
    fn num_variables(&self) -> usize {
        self.system.num_variables() + 1
    }
    fn num_parameters(&self) -> usize {
        self.system.num_variables() + 1
    }
    fn workspace_len(&self) -> usize {
        let (n, m) = self.layout();
        m + n * n + n + self.system.workspace_len()
    }

    fn evaluate(&self, x: &[C64], q: &[C64], work: &mut [C64], f: &mut [C64]) {
        let (n, p, rest) = self.parameters_at(x, work);
        let rest = &mut rest[n * n + n..];
        self.system.evaluate(&x[..n], p, rest, &mut f[..n]);
        f[n] = Self::slice_residual(x, q);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        q: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        let (n, p, rest) = self.parameters_at(x, work);
        let (inner_jac, rest) = rest.split_at_mut(n * n);
        let (column, rest) = rest.split_at_mut(n);
        self.system
            .evaluate_with_jacobian(&x[..n], p, rest, &mut f[..n], inner_jac);
        self.system
            .evaluate_parameter_derivative(&x[..n], p, &self.direction, rest, column);
        let width = n + 1;
        for i in 0..n {
            jac[i * width..i * width + n].copy_from_slice(&inner_jac[i * n..i * n + n]);
            jac[i * width + n] = column[i];
        }
        for j in 0..n {
            jac[n * width + j] = -q[j];
        }
        jac[n * width + n] = C64::new(1.0, 0.0);
        f[n] = Self::slice_residual(x, q);
    }

    fn evaluate_parameter_derivative(
        &self,
        x: &[C64],
        _q: &[C64],
        dq: &[C64],
        _work: &mut [C64],
        out: &mut [C64],
    ) {
        let (n, _) = self.layout();
        out[..n].iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        let slice: C64 = dq[..n].iter().zip(&x[..n]).map(|(a, v)| a * v).sum();
        out[n] = -slice - dq[n];
    }
}

/// `F(x) − p`: a plain square system made a parametric family by its constant terms
/// (the family [`solve_by_monodromy`] works in). Parameters: n, one per equation.
pub struct ConstantShift<'a, F: Evaluator + ?Sized> {
    system: &'a F,
    fixed_parameters: Vec<C64>,
}

impl<'a, F: Evaluator + ?Sized> ConstantShift<'a, F> {
    /// Family `F(x; fixed_parameters) − p`.
    pub fn new(system: &'a F, fixed_parameters: Vec<C64>) -> Self {
        ConstantShift {
            system,
            fixed_parameters,
        }
    }
}

impl<F: Evaluator + ?Sized> Evaluator for ConstantShift<'_, F> {
    fn num_variables(&self) -> usize {
        self.system.num_variables()
    }
    fn num_equations(&self) -> usize {
        self.system.num_equations()
    }
    fn num_parameters(&self) -> usize {
        self.system.num_equations()
    }
    fn workspace_len(&self) -> usize {
        self.system.workspace_len()
    }
    fn evaluate(&self, x: &[C64], p: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.system.evaluate(x, &self.fixed_parameters, work, f);
        for (fi, pi) in f.iter_mut().zip(p) {
            *fi -= pi;
        }
    }
    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        self.system
            .evaluate_with_jacobian(x, &self.fixed_parameters, work, f, jac);
        for (fi, pi) in f.iter_mut().zip(p) {
            *fi -= pi;
        }
    }
    fn evaluate_parameter_derivative(
        &self,
        _x: &[C64],
        _p: &[C64],
        dp: &[C64],
        _work: &mut [C64],
        out: &mut [C64],
    ) {
        for (o, d) in out.iter_mut().zip(dp) {
            *o = -d;
        }
    }
}

/// Solves the plain square system `F(x; fixed_parameters) = 0` without a start system:
/// monodromy (with trace test) on the family `F(x) − p` from the trivial start pair
/// `(x₀, F(x₀))` for a random `x₀`, then a parameter homotopy with endgame from that
/// generic fiber to `p = 0`, which reaches every isolated solution of `F = 0`.
pub fn solve_by_monodromy<F: Evaluator + ?Sized>(
    system: &F,
    fixed_parameters: &[C64],
    monodromy_options: &MonodromyOptions,
    solve_options: &super::solve::SolveOptions,
) -> Result<(MonodromyResult, super::solve::SolveResult), HomotopyError> {
    let n = system.num_variables();
    if system.num_equations() != n {
        return Err(HomotopyError::NotSquare {
            equations: system.num_equations(),
            variables: n,
        });
    }
    if fixed_parameters.len() != system.num_parameters() {
        return Err(HomotopyError::WrongLength {
            field: "fixed_parameters",
            expected: system.num_parameters(),
            found: fixed_parameters.len(),
        });
    }
    let family = ConstantShift::new(system, fixed_parameters.to_vec());
    let mut rng = crate::random::stream(solve_options.seed, u64::MAX);
    let x0 = random_point(&mut rng, n, 1.0);
    let mut p0 = vec![C64::new(0.0, 0.0); n];
    let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
    system.evaluate(&x0, fixed_parameters, &mut work, &mut p0);
    let monodromy = monodromy_solve(&family, &x0, &p0, monodromy_options, solve_options.seed)?;
    let target = vec![C64::new(0.0, 0.0); n];
    let solved = super::solve::solve_parameter_homotopy(
        &family,
        &monodromy.solutions,
        &p0,
        &target,
        solve_options,
    )?;
    Ok((monodromy, solved))
}

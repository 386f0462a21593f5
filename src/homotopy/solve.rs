//! Parallel solving: many paths of one homotopy, tracked independently with rayon.
//!
//! Results come back in path order and depend only on the seed (γ is drawn from
//! `crate::random::seeded(seed)`; every path is a deterministic function of its start
//! point and the tracker's state is reset per path, so no per-path random stream is
//! needed), so they are bit-identical for any thread count. After the first pass, paths
//! that failed, and nonsingular endpoints reached by more than one path (the signature
//! of path jumping; decided by a Newton-cluster test, not a fixed distance), are
//! re-tracked with [`TrackerOptions::conservative`] — never dropped silently. Endpoints
//! that still share a nonsingular root after that are reported as failed
//! ([`FailureReason::PathJumped`]), so no root is counted twice. Paths whose norm
//! passed `at_infinity_norm` before the endgame zone are at infinity only if the
//! singularity they ran into is located at `t = 1`; any other is a pole passed on the
//! way, and the path is tracked around it to the endgame (see the `divergence` module;
//! with [`EndgameOptions::growth_before_divergence`]), else it stays failed. Finite
//! endpoints are then clustered to give multiplicities.

use super::conjugates::complete_conjugate_roots;
use super::divergence::settle_diverged_paths;
use super::homotopies::{Homotopy, ParameterHomotopy, StraightLineHomotopy};
use super::refine::{accuracy_at_condition, group_roots, newton_refine, same_point};
use super::start::TotalDegreeStartSystem;
use super::tracker::{
    EndgameOptions, FailureReason, PathResult, PathStatus, StepOptions, Tracker, TrackerOptions,
};
use crate::C64;
use crate::system::{Evaluator, PlainSystem};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Errors of the solve entry points (bad input, never a panic).
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum HomotopyError {
    /// The system is not square.
    #[error(
        "the system has {equations} equations in {variables} unknowns; homotopy solving needs a square system"
    )]
    NotSquare {
        /// Number of equations.
        equations: usize,
        /// Number of unknowns.
        variables: usize,
    },
    /// A vector has the wrong length.
    #[error("`{field}` has length {found}, expected {expected}")]
    WrongLength {
        /// Name of the offending argument.
        field: &'static str,
        /// Required length.
        expected: usize,
        /// Given length.
        found: usize,
    },
    /// A value is NaN or infinite.
    #[error("`{field}` contains a NaN or infinite value")]
    NonFinite {
        /// Name of the offending argument.
        field: &'static str,
    },
    /// The start pair of a monodromy run is not a solution.
    #[error("the start pair is not a solution: residual ‖F(x₀; p₀)‖∞ = {residual:.3e}")]
    InvalidStartPair {
        /// The residual.
        residual: f64,
    },
    /// A degree is zero (a constant equation) or the Bézout number overflows.
    #[error("invalid degrees for a total-degree start system: {0}")]
    InvalidDegrees(String),
}

/// Options of [`solve_total_degree`] and [`solve_parameter_homotopy`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveOptions {
    /// Tracker options of the first pass.
    pub tracker: TrackerOptions,
    /// Seed of every random choice (γ).
    pub seed: u64,
    /// Re-track failed paths and duplicated nonsingular endpoints with
    /// [`TrackerOptions::conservative`].
    pub retry_failed: bool,
    /// A finite solution is real if `|Im x_i| ≤ real_tolerance · (1 + ‖x‖∞)`.
    pub real_tolerance: f64,
    /// Two finite endpoints coincide if their distance is below
    /// `cluster_tolerance · (1 + ‖x‖∞)`.
    pub cluster_tolerance: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            // The endgame for badly scaled systems (PHCpack's demo suite: chemequ,
            // kotsireas, game5two have large finite roots approached like s^{-1/2}).
            //
            // The steps of the fast preset (steps up to 0.2, prediction tolerance
            // 10⁻⁵): paths that fail or cross with them are re-tracked with the
            // conservative preset. On PHCpack's 82 demo systems of total degree at most
            // 1,000 (one thread) the time ratio phc/singdist went from a geometric
            // mean of 5.3 to 6.8 with the same counts except `discret3s`'s, which
            // change with the seed either way (the default steps, 10⁻⁶ and 0.1, were
            // 1.3 × slower; a tolerance of 10⁻⁴ counted a duplicated endpoint of
            // `cpdm5` as a second root).
            tracker: TrackerOptions {
                step: StepOptions::fast(),
                endgame: EndgameOptions {
                    growth_before_divergence: true,
                    settle_on_direct_endpoint: true,
                    settle_on_stalled_estimate: true,
                    direct_finish_at_settled_condition: true,
                    reject_averaging_loops: true,
                    ..EndgameOptions::default()
                },
                ..TrackerOptions::default()
            },
            seed: 0x5eed,
            retry_failed: true,
            real_tolerance: 1e-8,
            cluster_tolerance: 1e-6,
        }
    }
}

/// Counts of a solve run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
pub struct SolveSummary {
    /// Paths tracked.
    pub paths: usize,
    /// Nonsingular finite solutions (one path each).
    pub nonsingular: usize,
    /// Distinct singular finite solutions.
    pub singular: usize,
    /// Paths ending at singular solutions (Σ multiplicities).
    pub singular_paths: usize,
    /// Paths diverging to infinity.
    pub at_infinity: usize,
    /// Failed paths (after re-runs).
    pub failed: usize,
    /// Distinct real finite solutions.
    pub real: usize,
    /// Paths re-tracked with conservative options.
    pub retracked: usize,
    /// Paths at infinity re-tracked in a random projective chart
    /// ([`super::chart::ChartHomotopy`]).
    #[serde(default)]
    pub rechecked_at_infinity: usize,
    /// Of those, paths whose chart route reached a new finite root (counted under
    /// `nonsingular`, no longer at infinity).
    #[serde(default)]
    pub recovered_from_infinity: usize,
    /// Of those, paths left at infinity whose chart route neither ended at infinity
    /// nor reached a new root: their classification rests on the norm cap alone.
    #[serde(default)]
    pub unconfirmed_at_infinity: usize,
    /// Paths not accounted for (failed, or left at infinity by the norm cap alone) that
    /// now hold the complex conjugate of a root no path reached, confirmed by Newton's
    /// method in place ([`super::conjugates`]; counted under `nonsingular`).
    #[serde(default)]
    pub completed_by_conjugation: usize,
    /// Failed paths whose route in a random projective chart reached a finite root
    /// (a new nonsingular one, or a singular one), counted there instead of under
    /// `failed`.
    #[serde(default)]
    pub recovered_in_chart: usize,
    /// Failed paths whose routes in two random projective charts both ended at
    /// infinity, counted under `at_infinity` instead of under `failed`.
    #[serde(default)]
    pub at_infinity_in_charts: usize,
    /// Paths put at infinity after they stalled near `t = 1` (on the evidence of their
    /// growth alone) at a norm within [`STALLED_NEAR_ROOTS`] times the largest
    /// nonsingular root's: a root of large norm may be missing.
    #[serde(default)]
    pub stalled_near_roots: usize,
}

/// A path put at infinity after it stalled ([`PathResult::stalled_at_infinity`]) whose
/// norm is at most this many times the largest nonsingular root's is counted in
/// [`SolveSummary::stalled_near_roots`]. PHCpack's `discret3s` has 128 roots (its demo
/// file's list), the largest of norms 4.8·10⁴–1.2·10⁵ along a direction in which the
/// system nearly has solutions at infinity; with residuals in double precision only
/// the paths to five of them stall at `s = 10⁻¹⁰ … 6·10⁻⁹` with norms 1.9–13 times
/// the largest root found (3.1·10⁴). Elsewhere on the demo suite the stalled paths
/// stop at 19 (`reimer5`) to 10⁷ times the largest root, except `fbremb2`'s two (1.2
/// times) and `cohn3`'s at some seeds (1–9 paths, all of its 130 roots found).
pub const STALLED_NEAR_ROOTS: f64 = 10.0;

/// Result of a solve run: every path in path order, and the summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveResult {
    /// Per-path results, `paths[i].path_index == i`.
    pub paths: Vec<PathResult>,
    /// Counts.
    pub summary: SolveSummary,
    /// The γ of a straight-line homotopy (1 for parameter homotopies).
    pub gamma: C64,
}

impl SolveResult {
    /// Nonsingular solutions, in path order.
    pub fn nonsingular_solutions(&self) -> Vec<Vec<C64>> {
        self.paths
            .iter()
            .filter(|p| p.status == PathStatus::Nonsingular)
            .map(|p| p.solution.clone())
            .collect()
    }

    /// Every finite endpoint (nonsingular or singular; a cluster once per path), in
    /// path order.
    pub fn finite_endpoints(&self) -> Vec<Vec<C64>> {
        self.paths
            .iter()
            .filter(|p| p.status.is_finite())
            .map(|p| p.solution.clone())
            .collect()
    }

    /// Distinct finite solutions (one representative per cluster), in path order.
    pub fn finite_solutions(&self) -> Vec<&PathResult> {
        distinct_finite(&self.paths)
    }
}

fn distinct_finite(paths: &[PathResult]) -> Vec<&PathResult> {
    let mut representatives: Vec<&PathResult> = Vec::new();
    for p in paths.iter().filter(|p| p.status.is_finite()) {
        if p.status == PathStatus::Nonsingular
            || !representatives.iter().any(|r| {
                r.status == PathStatus::Singular && same_point(&r.solution, &p.solution, 1e-6)
            })
        {
            representatives.push(p);
        }
    }
    representatives
}

pub(super) fn check_finite(field: &'static str, values: &[C64]) -> Result<(), HomotopyError> {
    if values.iter().all(|v| v.re.is_finite() && v.im.is_finite()) {
        Ok(())
    } else {
        Err(HomotopyError::NonFinite { field })
    }
}

pub(super) fn check_length(
    field: &'static str,
    expected: usize,
    found: usize,
) -> Result<(), HomotopyError> {
    if expected == found {
        Ok(())
    } else {
        Err(HomotopyError::WrongLength {
            field,
            expected,
            found,
        })
    }
}

/// `values` has `expected` entries, all finite (`field` names it in the error).
fn check_values(field: &'static str, expected: usize, values: &[C64]) -> Result<(), HomotopyError> {
    check_length(field, expected, values.len())?;
    check_finite(field, values)
}

pub(super) fn check_square<F: Evaluator + ?Sized>(system: &F) -> Result<(), HomotopyError> {
    if system.num_equations() != system.num_variables() {
        return Err(HomotopyError::NotSquare {
            equations: system.num_equations(),
            variables: system.num_variables(),
        });
    }
    Ok(())
}

/// Solves `F(x; p) = 0` (parameters fixed at `target_parameters`) with the total-degree
/// homotopy `(1 − t)·γ·(x_i^{d_i} − 1) + t·F`, γ random from `options.seed`. Tracks
/// `Π d_i` paths in parallel. `degrees[i]` must be the total degree of equation i.
pub fn solve_total_degree<F: Evaluator + ?Sized>(
    system: &F,
    degrees: &[u32],
    target_parameters: &[C64],
    options: &SolveOptions,
) -> Result<SolveResult, HomotopyError> {
    check_square(system)?;
    check_length("degrees", system.num_variables(), degrees.len())?;
    check_target_parameters(system, target_parameters)?;
    if let Some(i) = degrees.iter().position(|&d| d == 0) {
        return Err(HomotopyError::InvalidDegrees(format!(
            "equation {i} has degree 0"
        )));
    }
    let start = TotalDegreeStartSystem::new(degrees.to_vec());
    let count = start
        .path_count()
        .filter(|&c| c <= 1 << 32)
        .ok_or_else(|| HomotopyError::InvalidDegrees("Bézout number too large".into()))?
        as usize;
    Ok(solve_from_start_system(
        &start,
        system,
        count,
        |index, x| start.start_solution(index as u64, x),
        target_parameters,
        options,
        degrees,
    ))
}

/// `target_parameters` has one finite value per parameter of `system`.
pub(super) fn check_target_parameters<F: Evaluator + ?Sized>(
    system: &F,
    target_parameters: &[C64],
) -> Result<(), HomotopyError> {
    check_values(
        "target_parameters",
        system.num_parameters(),
        target_parameters,
    )
}

/// Tracks the `count` paths of `(1 − t)·γ·G + t·F` (γ random from `options.seed`) from
/// the start solutions `start_point(index, x)` of `G`; equation `i` of `G` and `F` of
/// total degree at most `degrees[i]` (for the chart re-check of the paths at infinity).
pub(super) fn solve_from_start_system<G, F, S>(
    start: &G,
    system: &F,
    count: usize,
    start_point: S,
    target_parameters: &[C64],
    options: &SolveOptions,
    degrees: &[u32],
) -> SolveResult
where
    G: Evaluator + ?Sized,
    F: Evaluator + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let gamma = crate::random::unit_complex(&mut crate::random::seeded(options.seed));
    let homotopy = StraightLineHomotopy::new(start, system, target_parameters.to_vec(), gamma);
    let mut result =
        solve_with_chart_recheck(&homotopy, count, start_point, options, Some(degrees));
    result.gamma = gamma;
    result
}

/// Tracks `start_solutions` of `F(x; start_parameters) = 0` to
/// `F(x; target_parameters) = 0` along the segment between the parameter points.
pub fn solve_parameter_homotopy<F: Evaluator + ?Sized>(
    system: &F,
    start_solutions: &[Vec<C64>],
    start_parameters: &[C64],
    target_parameters: &[C64],
    options: &SolveOptions,
) -> Result<SolveResult, HomotopyError> {
    check_square(system)?;
    check_values(
        "start_parameters",
        system.num_parameters(),
        start_parameters,
    )?;
    check_target_parameters(system, target_parameters)?;
    for s in start_solutions {
        check_values("start_solutions", system.num_variables(), s)?;
    }
    let homotopy = ParameterHomotopy::segment(system, start_parameters, target_parameters);
    Ok(solve_with_homotopy(
        &homotopy,
        start_solutions.len(),
        |index, x| x.copy_from_slice(&start_solutions[index]),
        options,
    ))
}

/// Tracks `count` paths of any homotopy from `t = 0` to `t = 1` with endgame;
/// `start(index, x)` writes start point `index`. Results in path order.
pub fn solve_with_homotopy<H, S>(
    homotopy: &H,
    count: usize,
    start: S,
    options: &SolveOptions,
) -> SolveResult
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    solve_with_chart_recheck(homotopy, count, start, options, None)
}

/// [`solve_with_homotopy`]; with `chart_degrees` (equation `i` of `H(·, t)` of total
/// degree at most `chart_degrees[i]`), the paths at infinity are re-tracked in a random
/// projective chart ([`super::chart::recover_from_infinity`]) and the new finite roots
/// found there are counted.
pub(crate) fn solve_with_chart_recheck<H, S>(
    homotopy: &H,
    count: usize,
    start: S,
    options: &SolveOptions,
    chart_degrees: Option<&[u32]>,
) -> SolveResult
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let n = homotopy.dimension();
    let track_all = |indices: &[usize], tracker_options: &TrackerOptions| -> Vec<PathResult> {
        indices
            .par_iter()
            .map_init(
                || {
                    (
                        Tracker::new(homotopy, tracker_options.clone()),
                        vec![C64::new(0.0, 0.0); n],
                    )
                },
                |(tracker, x), &index| {
                    start(index, x);
                    tracker.track(x, index)
                },
            )
            .collect()
    };
    let all: Vec<usize> = (0..count).collect();
    let mut paths = track_all(&all, &options.tracker);
    let averaged = fail_averaging_loops(&mut paths);
    let mut retracked = 0;
    let mut conservative = TrackerOptions::conservative();
    conservative.step.max_steps = conservative
        .step
        .max_steps
        .max(options.tracker.step.max_steps);
    conservative.endgame.growth_before_divergence =
        options.tracker.endgame.growth_before_divergence;
    conservative.endgame.settle_on_direct_endpoint =
        options.tracker.endgame.settle_on_direct_endpoint;
    conservative.endgame.settle_on_stalled_estimate =
        options.tracker.endgame.settle_on_stalled_estimate;
    conservative.endgame.direct_finish_at_settled_condition =
        options.tracker.endgame.direct_finish_at_settled_condition;
    conservative.endgame.reject_averaging_loops = options.tracker.endgame.reject_averaging_loops;
    if options.retry_failed {
        assign_multiplicities(&mut paths, options.cluster_tolerance);
        let duplicated = duplicated_nonsingular(homotopy, &paths);
        let suspicious: Vec<usize> = paths
            .iter()
            .filter(|p| {
                matches!(p.status, PathStatus::Failed(_))
                    || (p.status == PathStatus::Nonsingular && p.multiplicity > 1)
                    || duplicated[p.path_index]
            })
            .map(|p| p.path_index)
            .collect();
        if !suspicious.is_empty() {
            retracked = suspicious.len();
            for redo in track_all(&suspicious, &conservative) {
                let index = redo.path_index;
                paths[index] = redo;
                if paths[index].status == PathStatus::AtInfinity && averaged.contains(&index) {
                    // A path whose first run averaged roots, sent to infinity by the
                    // re-run: not evidence enough on its own (on `discret3s` at seed 7
                    // two such re-runs stopped at norms 4·10⁴ beside roots of norm
                    // 1.3·10⁴); the projective charts of `recover_failed_paths`
                    // decide, or the path is reported failed.
                    paths[index].status = PathStatus::Failed(FailureReason::EndgameDidNotConverge);
                }
            }
            // The re-run's own averages stay failed for the charts below.
            let _ = fail_averaging_loops(&mut paths);
        }
    }
    if options.tracker.endgame.growth_before_divergence {
        retracked += settle_diverged_paths(homotopy, &mut paths, &start, &conservative, |a, b| {
            same_point(a, b, options.cluster_tolerance)
        });
    }
    promote_nonsingular_endpoints(homotopy, &mut paths, options);
    assign_multiplicities(&mut paths, options.cluster_tolerance);
    mark_jumped_paths(homotopy, &mut paths);
    let recheck = match chart_degrees {
        Some(degrees) => super::chart::recover_from_infinity(
            homotopy,
            degrees,
            &mut paths,
            &start,
            &options.tracker,
            options.seed,
            |a, b| same_point(a, b, options.cluster_tolerance),
        ),
        None => Default::default(),
    };
    let failed_in_charts = match chart_degrees {
        Some(degrees) => super::chart::recover_failed_paths(
            (homotopy, degrees, options.seed),
            &mut paths,
            &start,
            &options.tracker,
            |a, b| same_point(a, b, options.cluster_tolerance),
        ),
        None => Default::default(),
    };
    // Roots whose conjugates no path reported, recorded at the paths not accounted
    // for: those left at infinity by the norm cap alone first, then the failed ones.
    let doubtful: Vec<usize> = recheck
        .unconfirmed_paths
        .iter()
        .copied()
        .chain(
            paths
                .iter()
                .filter(|p| matches!(p.status, PathStatus::Failed(_)))
                .map(|p| p.path_index),
        )
        .collect();
    let conjugates = complete_conjugate_roots(
        homotopy,
        &mut paths,
        &doubtful,
        (
            options.real_tolerance,
            options.cluster_tolerance,
            options.tracker.endgame.singular_condition,
        ),
    );
    // Failed paths that two charts put at infinity, unless the conjugate completion
    // recorded a root at them.
    let mut at_infinity_in_charts = 0;
    for &index in &failed_in_charts.at_infinity {
        if matches!(paths[index].status, PathStatus::Failed(_)) {
            paths[index].status = PathStatus::AtInfinity;
            at_infinity_in_charts += 1;
        }
    }
    if recheck.recovered + failed_in_charts.recovered > 0 || !conjugates.paths.is_empty() {
        assign_multiplicities(&mut paths, options.cluster_tolerance);
    }
    if !conjugates.paths.is_empty() {
        // A conjugate the cluster test did not match but Newton's grouping does is a
        // duplicate: reported as a jumped path, not counted twice.
        mark_jumped_paths(homotopy, &mut paths);
    }
    let mut summary = summarize(&paths, options.real_tolerance, retracked);
    summary.rechecked_at_infinity = recheck.rechecked;
    summary.recovered_from_infinity = recheck.recovered;
    summary.recovered_in_chart = failed_in_charts.recovered;
    summary.at_infinity_in_charts = at_infinity_in_charts;
    summary.unconfirmed_at_infinity = recheck
        .unconfirmed_paths
        .iter()
        .filter(|&&i| paths[i].status == PathStatus::AtInfinity)
        .count();
    let largest_root = paths
        .iter()
        .filter(|p| p.status == PathStatus::Nonsingular)
        .fold(0.0f64, |m, p| m.max(super::newton::max_norm(&p.solution)));
    summary.stalled_near_roots = paths
        .iter()
        .filter(|p| {
            p.status == PathStatus::AtInfinity
                && p.stalled_at_infinity
                && super::newton::max_norm(&p.solution) <= STALLED_NEAR_ROOTS * largest_root
        })
        .count();
    summary.completed_by_conjugation = conjugates
        .paths
        .iter()
        .filter(|&&i| paths[i].status == PathStatus::Nonsingular)
        .count();
    SolveResult {
        paths,
        summary,
        gamma: C64::new(1.0, 0.0),
    }
}

/// Marks failed (`EndgameDidNotConverge`), and returns, every singular endpoint that
/// is the average of distinct roots ([`super::tracker::is_averaged_estimate`]: residual
/// above `10^(c − 10)` relative to `1 + ‖x‖∞` at winding number `c ≥ 2`), the mean a
/// Cauchy loop around two nearby nonsingular roots closes on. The endgame rejects
/// such estimates itself where `reject_averaging_loops` is on; this catches those of
/// trackers without it. A failed path is re-tracked, then tried in projective charts,
/// and reported if it still fails.
fn fail_averaging_loops(paths: &mut [PathResult]) -> Vec<usize> {
    let mut failed = Vec::new();
    for p in paths.iter_mut() {
        if p.status != PathStatus::Singular || p.winding_number < 2 {
            continue;
        }
        if super::tracker::is_averaged_estimate(
            p.winding_number,
            p.residual,
            super::newton::max_norm(&p.solution),
        ) {
            p.status = PathStatus::Failed(FailureReason::EndgameDidNotConverge);
            failed.push(p.path_index);
        }
    }
    failed
}

/// Newton iterations of [`promote_nonsingular_endpoints`]: quadratic convergence
/// reaches the tolerance within them; the linear convergence at a multiple root
/// (each correction about half the last) does not.
const PROMOTION_ITERATIONS: usize = 10;

/// Where Newton's corrections of a promotion stall at rounding noise instead of
/// reaching [`DUPLICATE_NEWTON_TOLERANCE`] (PHCpack's `stewgou40`: a root of condition
/// 4·10⁵, residual 7·10⁻¹⁶, corrections of 1.01·10⁻¹³ relative after 10 iterations),
/// a last relative correction below this …
const PROMOTION_NOISE: f64 = 1e-11;
/// … at a condition number below this fraction of `direct_finish_condition` (10⁶)
/// is convergence too. Near a double root the condition number is about the inverse
/// of the distance `d` to it and the Newton corrections about `d/2`: below 10⁶ they
/// are above 5·10⁻⁷, far above the noise bound.
const PROMOTION_NOISE_CONDITION_FRACTION: f64 = 1e-2;

/// Endpoints classified singular that Newton's method on `H(·, 1)` refines, within
/// [`PROMOTION_ITERATIONS`], to a root with a condition number below the direct
/// finish's bound (`direct_finish_condition`), or to rounding noise
/// ([`PROMOTION_NOISE`]) at a condition number below 1 % of it, are that nonsingular
/// root: the endgame
/// stopped short of its quadratic convergence (a direct finish settled near a cluster
/// of roots, e.g. PHCpack's `redcyc7`), or a Cauchy loop closed after turns no
/// nonsingular root has (`fbrfive4`: 15 turns at a root of condition 3·10³). A double
/// root does not pass (`solotarev`: condition 2·10⁹ after linear convergence). Such
/// a path is relabelled nonsingular
/// at the refined root; a nonsingular root is the endpoint of one path only, so a
/// duplicate of another path's root is then reported by [`mark_jumped_paths`].
fn promote_nonsingular_endpoints<H: Homotopy + ?Sized>(
    homotopy: &H,
    paths: &mut [PathResult],
    options: &SolveOptions,
) {
    let target = TargetSystem { homotopy };
    let bound = options.tracker.endgame.direct_finish_condition;
    paths
        .par_iter_mut()
        .filter(|p| p.status == PathStatus::Singular)
        .for_each(|p| {
            let r = newton_refine(
                &target,
                &p.solution,
                &[],
                DUPLICATE_NEWTON_TOLERANCE,
                PROMOTION_ITERATIONS,
            );
            let at_rounding_level = r.last_correction <= PROMOTION_NOISE
                && r.residual.is_finite()
                && r.condition <= bound * PROMOTION_NOISE_CONDITION_FRACTION;
            if r.is_nonsingular(bound) || at_rounding_level {
                p.status = PathStatus::Nonsingular;
                p.solution = r.point;
                p.residual = r.residual;
                p.condition = r.condition;
            }
        });
}

/// Relative Newton tolerance of the duplicate test on nonsingular endpoints.
const DUPLICATE_NEWTON_TOLERANCE: f64 = 1e-13;
/// Two refined nonsingular endpoints closer than this (relative, plus their accuracy,
/// [`RootAccuracy`]) are the same root.
const DUPLICATE_TOLERANCE: f64 = 1e-10;

/// For every path, the root group of its nonsingular endpoint (the index of the group's
/// first path; `None` for other statuses), by the Newton-cluster test: each endpoint is
/// refined by Newton's method on `H(·, 1)` and the limits are compared at their
/// attainable accuracy ([`super::refine::group_roots`]). Endpoints of an
/// ill-conditioned root can lie further apart than any fixed tolerance and still be
/// one root.
fn nonsingular_root_groups<H: Homotopy + ?Sized>(
    homotopy: &H,
    paths: &[PathResult],
) -> Vec<Option<usize>> {
    root_groups_on(
        &TargetSystem { homotopy },
        paths,
        RootAccuracy::OfTheProblem,
    )
}

/// How far apart two Newton limits may be and still be one root.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RootAccuracy {
    /// The system's coefficients are known to rounding: a root at condition κ moves by
    /// about `κ·ε` relative under such a perturbation, so limits closer than `10·κ·ε`
    /// are one root. A singular root of the exact system splits into a cluster of
    /// nearby nonsingular roots of its rounded coefficients (PHCpack's `tangents1`:
    /// clusters of radius 5·10⁻⁸ at condition 10⁸–4·10⁸), and this counts the cluster
    /// once.
    OfTheProblem,
    /// The system is exactly the one given (the random-coefficient start system of the
    /// polyhedral homotopy, whose roots are nonsingular and distinct): a converged limit
    /// is accurate to its last Newton correction ([`super::refine::Refinement::accuracy`]),
    /// so two roots of a badly scaled system that differ only in a small coordinate stay
    /// two.
    OfTheLimit,
}

/// [`nonsingular_root_groups`] with the endpoints refined on the system `system` (the
/// target of the homotopy the paths ended on), compared at `accuracy`.
pub(crate) fn root_groups_on<F: Evaluator + ?Sized>(
    system: &F,
    paths: &[PathResult],
    accuracy: RootAccuracy,
) -> Vec<Option<usize>> {
    let nonsingular: Vec<&PathResult> = paths
        .iter()
        .filter(|p| p.status == PathStatus::Nonsingular)
        .collect();
    let refined: Vec<(Vec<C64>, f64)> = nonsingular
        .par_iter()
        .map(|p| {
            let r = newton_refine(system, &p.solution, &[], DUPLICATE_NEWTON_TOLERANCE, 8);
            if r.converged {
                let bound = match accuracy {
                    RootAccuracy::OfTheProblem => {
                        accuracy_at_condition(r.condition.max(p.condition))
                    }
                    RootAccuracy::OfTheLimit => r.accuracy(),
                };
                (r.point, bound)
            } else {
                (p.solution.clone(), accuracy_at_condition(p.condition))
            }
        })
        .collect();
    let mut groups = vec![None; paths.len()];
    for (k, g) in group_roots(&refined, DUPLICATE_TOLERANCE)
        .into_iter()
        .enumerate()
    {
        groups[nonsingular[k].path_index] = Some(nonsingular[g].path_index);
    }
    groups
}

/// Whether each path's nonsingular root was also reached by another path.
fn duplicated_nonsingular<H: Homotopy + ?Sized>(homotopy: &H, paths: &[PathResult]) -> Vec<bool> {
    let groups = nonsingular_root_groups(homotopy, paths);
    let mut size = vec![0usize; paths.len()];
    for g in groups.iter().flatten() {
        size[*g] += 1;
    }
    groups
        .iter()
        .map(|g| g.is_some_and(|g| size[g] > 1))
        .collect()
}

/// After the re-runs: of the nonsingular endpoints that still share a root, all but the
/// first (in path order) are marked `Failed(PathJumped)`, so the root is counted once
/// and the lost root is reported rather than hidden.
fn mark_jumped_paths<H: Homotopy + ?Sized>(homotopy: &H, paths: &mut [PathResult]) {
    let groups = nonsingular_root_groups(homotopy, paths);
    for (i, group) in groups.into_iter().enumerate() {
        if group.is_some_and(|g| g != i) {
            paths[i].status = PathStatus::Failed(FailureReason::PathJumped);
            paths[i].multiplicity = 0;
        }
    }
}

/// `H(·, 1)` of a homotopy as an [`Evaluator`] without parameters (the target system),
/// for Newton refinement of endpoints.
pub(crate) struct TargetSystem<'a, H: Homotopy + ?Sized> {
    pub(crate) homotopy: &'a H,
}

impl<H: Homotopy + ?Sized> PlainSystem for TargetSystem<'_, H> {
    fn num_variables(&self) -> usize {
        self.homotopy.dimension()
    }
    fn workspace_len(&self) -> usize {
        self.homotopy.workspace_len()
    }
    fn evaluate(&self, x: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.homotopy.evaluate(x, C64::new(1.0, 0.0), work, f);
    }
    fn evaluate_extended(&self, x: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.homotopy
            .evaluate_extended(x, C64::new(1.0, 0.0), work, f);
    }
    fn evaluate_with_jacobian(&self, x: &[C64], work: &mut [C64], f: &mut [C64], jac: &mut [C64]) {
        self.homotopy
            .evaluate_with_jacobian(x, C64::new(1.0, 0.0), work, f, jac);
    }
}

/// Sets `multiplicity` of every finite path to the number of finite paths ending at
/// the same point (within `tolerance`, relative).
fn assign_multiplicities(paths: &mut [PathResult], tolerance: f64) {
    let finite: Vec<usize> = (0..paths.len())
        .filter(|&i| paths[i].status.is_finite())
        .collect();
    let counts: Vec<usize> = finite
        .iter()
        .map(|&i| {
            finite
                .iter()
                .filter(|&&j| same_point(&paths[i].solution, &paths[j].solution, tolerance))
                .count()
        })
        .collect();
    for p in paths.iter_mut() {
        p.multiplicity = if p.status.is_finite() { 1 } else { 0 };
    }
    for (&i, &c) in finite.iter().zip(&counts) {
        paths[i].multiplicity = c;
    }
}

fn summarize(paths: &[PathResult], real_tolerance: f64, retracked: usize) -> SolveSummary {
    let mut summary = SolveSummary {
        paths: paths.len(),
        retracked,
        ..SolveSummary::default()
    };
    for p in paths {
        match p.status {
            PathStatus::Nonsingular => summary.nonsingular += 1,
            PathStatus::Singular => summary.singular_paths += 1,
            PathStatus::AtInfinity => summary.at_infinity += 1,
            PathStatus::Failed(_) => summary.failed += 1,
        }
    }
    let distinct = distinct_finite(paths);
    summary.singular = distinct
        .iter()
        .filter(|p| p.status == PathStatus::Singular)
        .count();
    summary.real = distinct
        .iter()
        .filter(|p| p.is_real(real_tolerance))
        .count();
    summary
}

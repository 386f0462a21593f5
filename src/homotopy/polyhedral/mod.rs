//! Polyhedral homotopies: start systems with as many paths as the mixed volume of the
//! Newton polytopes (the BKK bound) instead of the Bézout number, for sparse systems.
//!
//! Read in this order: [`supports`] (supports, the origin for roots in `C^n`, random
//! integer liftings), [`lp`] (the LP feasibility tests, from scratch and
//! warm-started), [`cells`] (mixed cells of the lifted supports and the mixed volume),
//! [`binomial`] (the start system of a cell, solved exactly by Hermite normal form),
//! [`random_system`] (the random-coefficient system `Q` on the supports),
//! [`cell_homotopy`] (the homotopy from a cell's binomial system to `Q`), [`start`]
//! (all of it for one system).
//!
//! [`solve_polyhedral`] runs two stages (Huber and Sturmfels, "A polyhedral method for
//! solving sparse polynomial systems", Math. Comp. 1995; Verschelde, Verlinden and
//! Cools, "Homotopies exploiting Newton polytopes for solving sparse polynomial
//! systems", SIAM J. Numer. Anal. 1994; Li, "Numerical solution of polynomial systems
//! by homotopy continuation methods", Handbook of Numerical Analysis XI, 2003):
//! 1. per mixed cell, the cell homotopy from the roots of its binomial system at
//!    `s = 0` to roots of `Q` at `s = 1` — together exactly the `MV` roots of `Q`;
//!    failed or repeated endpoints are re-tracked with conservative options, and the
//!    roots still missing are reported as failed paths;
//! 2. the straight-line homotopy `(1 − t)γQ + tF` from those roots to the target `F`
//!    (a coefficient-parameter homotopy with the γ-trick), with the path classification,
//!    re-runs and endgame of [`crate::homotopy::solve`].
//!
//! With the origin added to every support the number of paths bounds the isolated
//! roots in `C^n`, so no root with zero coordinates is lost (Li and Wang, "The BKK root
//! count in C^n", Math. Comp. 1996).

pub mod binomial;
pub mod cell_homotopy;
pub mod cells;
pub mod lp;
pub mod random_system;
pub mod start;
pub mod supports;

pub use cell_homotopy::LOG_RANGE;
pub use cells::{
    CellError, MixedCell, MixedSubdivision, mixed_cells, mixed_cells_bounded, mixed_cells_within,
};
pub use start::{PolyhedralError, PolyhedralStartSystem};
pub use supports::{Supports, random_lifting};

use super::solve::{
    HomotopyError, RootAccuracy, SolveOptions, SolveResult, check_square, check_target_parameters,
    root_groups_on, solve_from_start_system,
};
use super::tracker::{FailureReason, PathResult, PathStatus, Tracker, TrackerOptions};
use crate::C64;
use crate::system::Evaluator;
use rayon::prelude::*;

/// Most paths a polyhedral run tracks.
const MAX_PATHS: u128 = 1 << 32;
/// Condition number above which a stage-one endpoint counts as singular. `Q` has random
/// coefficients, so its roots are nonsingular; some are still ill-conditioned (PHCpack's
/// `butcher`: a root of norm 4·10⁴ and condition 7·10¹⁰), and the target's bound
/// (10¹⁰) called such a root singular and lost it, which cost two fresh liftings and a
/// second polyhedral run.
const STAGE_ONE_SINGULAR_CONDITION: f64 = 1e13;
/// The stage-one endgame zone starts at `1 − s = ENDGAME_SCALE / max e`.
const ENDGAME_SCALE: f64 = 0.1;

/// LP feasibility tests the automatic start-system choice may spend on the mixed cells,
/// per path of the start system they would replace. The warm-started tests of
/// [`cells`] cost 0.4–4 µs each on PHCpack's demo systems (`eco8` 23,054 in 9 ms,
/// `des18_3` 31,898 in 36 ms, `stewgou40` 118,765 in 472 ms), a total-degree path
/// 0.3–3 ms. At 20 per path `des18_3`, `butemb3`, `ipp2` and `stewgou40` kept the
/// total degree (0.92, 3.8, 1.05 and 18.7 s, against 0.23, 1.05, 0.46 and 4.6 s from
/// their polyhedral start); they need 37, 37, 40 and 24; `des22_24` needs 56–102
/// over seeds (34,398–46,243 tests; 0.12 s from its 42 polyhedral paths against
/// 1.03 s by total degree, 256 paths). The searches the choice then discards (the
/// katsura systems, whose mixed volume is the total degree) cost `katsura9`
/// 0.27 → 0.29 s and `katsura10` 0.65 → 0.70 s at 100 per path against 50, and
/// 0.18 → 0.25 s at 200 on a faster day …
pub const AUTOMATIC_LP_TESTS_PER_PATH: usize = 100;
/// … and in addition to those.
pub const AUTOMATIC_LP_TESTS: usize = 20_000;

/// The polyhedral start system of `supports` (random choices from `seed`) when it has
/// at most half of `paths` paths — it tracks every path twice, through the cell
/// homotopies and then to the target — and its mixed cells are found within
/// `AUTOMATIC_LP_TESTS + AUTOMATIC_LP_TESTS_PER_PATH · paths` LP tests; `None` otherwise.
pub fn polyhedral_if_fewer_paths(
    supports: &Supports,
    seed: u64,
    paths: u128,
) -> Option<PolyhedralStartSystem> {
    let per_path = usize::try_from(paths)
        .unwrap_or(usize::MAX)
        .saturating_mul(AUTOMATIC_LP_TESTS_PER_PATH);
    let budget = AUTOMATIC_LP_TESTS.saturating_add(per_path);
    // A search whose cells pass half the paths cannot be taken: it stops there.
    let start = PolyhedralStartSystem::within_bounds(supports, seed, budget, paths / 2).ok()?;
    (start.mixed_volume().saturating_mul(2) <= paths).then_some(start)
}

/// A polyhedral solve: the result of the second stage, with the stage-one paths that
/// did not reach a root of `Q` appended as failed paths, and the counts of the start.
#[derive(Clone, Debug)]
pub struct PolyhedralSolve {
    /// All paths (`paths.len()` is the mixed volume) and the summary.
    pub result: SolveResult,
    /// Mixed volume of the supports with the origin.
    pub mixed_volume: u128,
    /// Number of mixed cells.
    pub cells: usize,
    /// Stage-one paths re-tracked with conservative options.
    pub start_retracked: usize,
    /// Stage-one paths lost (failed or repeated after the re-runs).
    pub start_failed: usize,
    /// Predictor–corrector steps of stage one (re-runs included).
    pub start_steps: usize,
}

/// Solves `F(x; p) = 0` (parameters fixed at `target_parameters`; `supports` the
/// supports of F's equations in its unknowns) by the two-stage polyhedral homotopy
/// (see the module documentation), every random choice from `options.seed`.
pub fn solve_polyhedral<F: Evaluator + ?Sized>(
    system: &F,
    supports: &Supports,
    target_parameters: &[C64],
    options: &SolveOptions,
) -> Result<PolyhedralSolve, HomotopyError> {
    check_square(system)?;
    check_target_parameters(system, target_parameters)?;
    if supports.num_variables() != system.num_variables()
        || supports.num_equations() != system.num_equations()
    {
        return Err(HomotopyError::InvalidDegrees(
            "the supports do not match the system".into(),
        ));
    }
    let start = PolyhedralStartSystem::new(supports, options.seed)
        .map_err(|e| HomotopyError::InvalidDegrees(format!("polyhedral start system: {e}")))?;
    solve_from_polyhedral_start(system, &start, target_parameters, options)
}

/// [`solve_polyhedral`] from a built start system.
pub fn solve_from_polyhedral_start<F: Evaluator + ?Sized>(
    system: &F,
    start: &PolyhedralStartSystem,
    target_parameters: &[C64],
    options: &SolveOptions,
) -> Result<PolyhedralSolve, HomotopyError> {
    let mixed_volume = start.mixed_volume();
    if mixed_volume > MAX_PATHS {
        return Err(HomotopyError::InvalidDegrees(
            "mixed volume too large".into(),
        ));
    }
    let stage_one = start_roots(start, mixed_volume as usize, options);
    let (roots, lost, start_retracked) = (stage_one.roots, stage_one.lost, stage_one.retracked);
    let mut result = solve_from_start_system(
        &start.system().evaluator(),
        system,
        roots.len(),
        |index, x| x.copy_from_slice(&roots[index]),
        target_parameters,
        options,
        &start.supports().total_degrees(),
    );
    let start_failed = lost.len();
    for mut p in lost {
        p.path_index = result.paths.len();
        p.multiplicity = 0;
        result.paths.push(p);
    }
    result.summary.paths += start_failed;
    result.summary.failed += start_failed;
    Ok(PolyhedralSolve {
        result,
        mixed_volume,
        cells: start.subdivision().cells.len(),
        start_retracked,
        start_failed,
        start_steps: stage_one.steps,
    })
}

/// What stage one reached.
struct StageOne {
    /// The distinct roots of `Q` reached, in path order.
    roots: Vec<Vec<C64>>,
    /// The paths that did not reach a new root.
    lost: Vec<PathResult>,
    /// Paths re-tracked with conservative options.
    retracked: usize,
    /// Predictor–corrector steps, re-runs included.
    steps: usize,
}

/// Fresh liftings of the same `Q` ([`PolyhedralStartSystem::relifted`]) whose cell
/// paths stage one tracks where it lost roots of `Q`, until it has them all.
const STAGE_ONE_RELIFTINGS: u64 = 2;

/// The stage-one paths `indices` of `start` (cell homotopies to the roots of `Q`).
fn track_cells(
    start: &PolyhedralStartSystem,
    indices: &[usize],
    tracker_options: &TrackerOptions,
) -> Vec<PathResult> {
    let n = start.supports().num_variables();
    let homotopies: Vec<_> = (0..start.subdivision().cells.len())
        .map(|c| start.cell_homotopy(c))
        .collect();
    // The factor exp(−eL(1 − τ)) of a term with power e grows like exp(eL·r) on the
    // endgame's circles of radius r around τ = 1: the endgame zone starts within
    // 1/(eL) of the end.
    let endgame_start: Vec<f64> = homotopies
        .iter()
        .map(|h| ENDGAME_SCALE / (LOG_RANGE * h.powers().iter().copied().fold(1.0, f64::max)))
        .collect();
    indices
        .par_iter()
        .map_init(
            || vec![C64::new(0.0, 0.0); n],
            |y, &index| {
                let (c, _) = start.locate(index as u64);
                start.start_solution(index as u64, y);
                let mut cell_options = tracker_options.clone();
                cell_options.endgame.endgame_start =
                    cell_options.endgame.endgame_start.min(endgame_start[c]);
                Tracker::new(&homotopies[c], cell_options).track(y, index)
            },
        )
        .collect()
}

/// Tracks every stage-one path of `start` (`count` of them), re-tracking the failed
/// and repeated ones with the conservative preset; returns the paths and the number
/// re-tracked.
fn track_stage_one(
    start: &PolyhedralStartSystem,
    count: usize,
    options: &SolveOptions,
) -> (Vec<PathResult>, usize) {
    let mut first = options.tracker.clone();
    first.endgame.growth_before_divergence = false;
    first.endgame.singular_condition = STAGE_ONE_SINGULAR_CONDITION;
    let all: Vec<usize> = (0..count).collect();
    let mut paths = track_cells(start, &all, &first);
    let mut retracked = 0;
    if options.retry_failed {
        let groups = root_groups(start, &paths);
        let suspicious: Vec<usize> = (0..count)
            .filter(|&i| paths[i].status != PathStatus::Nonsingular || groups[i] != Some(i))
            .chain((0..count).filter(|&i| {
                // The first member of a repeated root is suspicious too.
                groups[i] == Some(i) && groups.iter().filter(|g| **g == Some(i)).count() > 1
            }))
            .collect();
        if !suspicious.is_empty() {
            retracked = suspicious.len();
            let mut conservative = TrackerOptions::conservative();
            conservative.step.max_steps = conservative.step.max_steps.max(first.step.max_steps);
            conservative.endgame.growth_before_divergence = false;
            conservative.endgame.singular_condition = STAGE_ONE_SINGULAR_CONDITION;
            for redo in track_cells(start, &suspicious, &conservative) {
                let index = redo.path_index;
                paths[index] = redo;
            }
        }
    }
    (paths, retracked)
}

/// Stage one: tracks the `count` cell-homotopy paths to the roots of `Q`. `Q` has
/// random coefficients, so its roots are nonsingular and exactly `count` (the mixed
/// volume); where paths are lost (failed, or two on one root), the cell paths of up
/// to [`STAGE_ONE_RELIFTINGS`] fresh liftings of the same `Q` are tracked too and
/// their new distinct roots added, until all `count` are found. The paths still
/// missing then are reported lost.
fn start_roots(start: &PolyhedralStartSystem, count: usize, options: &SolveOptions) -> StageOne {
    let (paths, mut retracked) = track_stage_one(start, count, options);
    let mut steps: usize = paths.iter().map(|p| p.steps).sum();
    let groups = root_groups(start, &paths);
    // The distinct roots found (as paths, renumbered in order) and the lost paths.
    let mut found: Vec<PathResult> = Vec::with_capacity(count);
    let mut lost = Vec::new();
    for (i, mut p) in paths.into_iter().enumerate() {
        if p.status == PathStatus::Nonsingular && groups[i] == Some(i) {
            p.path_index = found.len();
            found.push(p);
        } else {
            if p.status == PathStatus::Nonsingular {
                p.status = PathStatus::Failed(FailureReason::PathJumped);
            } else if !matches!(p.status, PathStatus::Failed(_)) {
                // A root of Q at infinity or singular means the path went astray.
                p.status = PathStatus::Failed(FailureReason::EndgameDidNotConverge);
            }
            lost.push(p);
        }
    }
    for relifting in 1..=STAGE_ONE_RELIFTINGS {
        if lost.is_empty() {
            break;
        }
        let Ok(other) = start.relifted(relifting) else {
            continue;
        };
        if other.mixed_volume() != start.mixed_volume() {
            continue;
        }
        let (more, more_retracked) = track_stage_one(&other, count, options);
        retracked += more_retracked;
        steps += more.iter().map(|p| p.steps).sum::<usize>();
        let known = found.len();
        found.extend(
            more.into_iter()
                .filter(|p| p.status == PathStatus::Nonsingular)
                .enumerate()
                .map(|(k, mut p)| {
                    p.path_index = known + k;
                    p
                }),
        );
        // Keep the first path of each root: the known ones, then the new ones.
        let groups = root_groups(start, &found);
        found.retain(|p| groups[p.path_index] == Some(p.path_index));
        let new_roots = found.len() - known;
        found.truncate(known + new_roots.min(lost.len()));
        lost.drain(..new_roots.min(lost.len()));
        for (k, p) in found.iter_mut().enumerate() {
            p.path_index = k;
        }
    }
    StageOne {
        roots: found.into_iter().map(|p| p.solution).collect(),
        lost,
        retracked,
        steps,
    }
}

/// For every stage-one path, the group (index of its first path) of its nonsingular
/// endpoint after Newton refinement on `Q`; `None` for other statuses.
fn root_groups(start: &PolyhedralStartSystem, paths: &[PathResult]) -> Vec<Option<usize>> {
    root_groups_on(&start.system().evaluator(), paths, RootAccuracy::OfTheLimit)
}

//! The seed stage of the sweep engine, one implementation for every family: the
//! generic start set of each problem tracked to a seed point, at most the generic
//! count of distinct solutions kept, a lower count only when an independent seed
//! point confirms it.
//!
//! The start set holds the generic number `G` of finite isolated solutions; by
//! coefficient-parameter theory no parameter of the family has more (Morgan and
//! Sommese, *Coefficient-parameter polynomial continuation*, Appl. Math. Comput. 29,
//! 1989), so the distinct finite endpoints are kept only up to `G`. A design's fixed
//! data (e.g. a rigid part's shape) can send solutions to infinity at every seed, but
//! a path lost or wrongly classified at infinity at one seed is not lost at another:
//! a count below `G` counts only when two seed points (different parameters, reached
//! along different routes), each of which classified every path (finite or at
//! infinity: its count not a mere lower bound), agree on it, or when the family's
//! projective twin ([`super::ProjectiveTwin`]) accounts for every path of one seed
//! point (each path not finite there is at infinity in both formulations); otherwise
//! the shortfall is a seed-stage [`PathFailure`]. A seed point whose first run has
//! paths that run out of steps, but already as many solutions as the best point so
//! far, is left at that (its count a lower bound that confirms nothing) for the next
//! seed point, except the first and the last one, which re-run, detour and re-track
//! in the twin.
//!
//! Where a seed point's first run loses points only to path crossings (no path fails),
//! the count is settled first by monodromy ([`SeedPolicy::monodromy_stagnant_loops`]):
//! each of two seed points completes its first run's finite solutions by loops in the
//! design's restricted family (the motion's parameters free, the design's fixed), and
//! the two counts must agree ([`completed_by_monodromy`]). An orbit of critical points
//! at infinity then costs its paths once per first run, not once per detour and twin
//! re-check.

use super::{
    PathFailure, Retried, TrackingPlan, accounted, crossings, detour_point, finite_solutions,
    same_endpoint, track_all, track_with_retries, unaccounted_reasons,
};
use crate::C64;
use crate::homotopy::{
    PathParameterHomotopy, PathResult, PathStatus, PolylinePath, Tracker, TrackerOptions,
    complete_fiber,
};
use crate::pipeline::family::Family;
use crate::random;
use crate::system::Evaluator;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// How the seed stage tracks and confirms.
#[derive(Clone, Copy)]
pub struct SeedPolicy<'a> {
    /// Independent seed points a problem may use (the common one first).
    pub points: usize,
    /// Seed of every random choice (detours).
    pub seed: u64,
    /// Tracker settings of the first runs and the detours.
    pub tracker: &'a TrackerOptions,
    /// Tracker settings of the re-runs.
    pub retry_tracker: &'a TrackerOptions,
    /// Detours of a route that lost paths.
    pub attempts: usize,
    /// Whether seed points re-track just their lost paths along the detours, and a
    /// seed point after the first, which only confirms (or not) a count, hands over to
    /// the next where its paths run out of steps (`false`: whole detours at every seed
    /// point).
    pub confirm_lost_paths_first: bool,
    /// Monodromy completion before the detours (see the module documentation): where a
    /// seed point's first run loses points only to path crossings, its finite
    /// solutions are completed by monodromy loops in the design's restricted family
    /// until this many loops in a row add none (`0`: straight to the re-runs, detours,
    /// projective twin and last chances).
    pub monodromy_stagnant_loops: usize,
}

impl<'a> SeedPolicy<'a> {
    /// `points` seed points, tracked with `tracker` (re-runs with `retry_tracker`)
    /// and `attempts` detours, confirming with lost paths first.
    pub fn new(
        points: usize,
        seed: u64,
        (tracker, retry_tracker): (&'a TrackerOptions, &'a TrackerOptions),
        attempts: usize,
    ) -> Self {
        SeedPolicy {
            points,
            seed,
            tracker,
            retry_tracker,
            attempts,
            confirm_lost_paths_first: true,
            monodromy_stagnant_loops: 0,
        }
    }
}

/// One problem at its chosen seed point.
pub struct Seeded<S> {
    /// The seed point chosen (the one with the most solutions, the earliest of them).
    pub seed: S,
    /// Its parameters.
    pub parameters: Vec<C64>,
    /// Distinct finite solutions there, at most [`Seeded::generic_count`].
    pub solutions: Vec<Vec<C64>>,
    /// The generic count `G` (the start set's size).
    pub generic_count: usize,
    /// The shortfall no second seed point confirmed.
    pub failure: Option<PathFailure>,
    /// Paths tracked at every seed point.
    pub tracked: usize,
    /// Whether the count was settled by seed points completed by monodromy
    /// ([`SeedPolicy::monodromy_stagnant_loops`]): the family tracks well at random
    /// parameters of its restricted family.
    pub completed_by_monodromy: bool,
}

/// A sub-problem at its seed as every pose's route sees it, for any mechanism: the
/// seed's solutions, the counts the poses are held to, and the generic start (the
/// origin of the generic route).
#[derive(Clone, Debug)]
pub struct SeedSolutions {
    /// Seed parameters (the mechanism's normalised frame).
    pub parameters: Vec<C64>,
    /// Distinct simple finite solutions at the seed, at most
    /// [`SeedSolutions::generic_count`].
    pub solutions: Vec<Vec<C64>>,
    /// The generic number of finite isolated solutions of the family (the start
    /// file's count): no parameter of the family has more.
    pub generic_count: usize,
    /// Number of paths every pose must account for: the seed's distinct finite
    /// solutions. Below [`SeedSolutions::generic_count`] only where an independent seed
    /// point (or the projective twin) confirmed the count, or with a seed-stage
    /// [`PathFailure`] reporting the shortfall; above the seed's own count after the
    /// run's and the check's stages were reconciled (another stage reached more), and
    /// then a pose takes the generic route first.
    pub start_count: usize,
    /// The start file's generic parameter point and its solutions (the start of the
    /// seed stage, and of the generic route to a pose).
    pub generic_start: (Vec<C64>, Vec<Vec<C64>>),
    /// Whether the seed count was settled by monodromy completion
    /// ([`Seeded::completed_by_monodromy`]).
    pub completed_by_monodromy: bool,
}

impl SeedSolutions {
    /// The seed stage's result for one problem with its generic start: the count to
    /// hold the poses to is the seed's count.
    pub fn new<S>(seeded: Seeded<S>, generic_start: (Vec<C64>, Vec<Vec<C64>>)) -> (S, Self) {
        let at_seed = SeedSolutions {
            parameters: seeded.parameters,
            start_count: seeded.solutions.len(),
            solutions: seeded.solutions,
            generic_count: seeded.generic_count,
            generic_start,
            completed_by_monodromy: seeded.completed_by_monodromy,
        };
        (seeded.seed, at_seed)
    }
}

/// The distinct points of `endpoints`, at most `limit` of them (a parameter homotopy
/// starts from simple points, and no parameter has more than the generic count).
pub fn distinct_solutions(endpoints: Vec<Vec<C64>>, limit: usize) -> Vec<Vec<C64>> {
    let mut out: Vec<Vec<C64>> = Vec::new();
    for x in endpoints {
        if out.len() < limit && !out.iter().any(|y| same_endpoint(y, &x)) {
            out.push(x);
        }
    }
    out
}

/// Whether the seed points' counts (in order) settle the count: the generic count
/// reached, or the largest count found by at least two seed points.
pub fn seed_count_confirmed(counts: &[usize], generic: usize) -> bool {
    let most = counts.iter().copied().max().unwrap_or(0);
    most == generic || counts.iter().filter(|&&c| c == most).count() >= 2
}

/// One solve of a problem at one seed point.
struct SeedRun<S> {
    seed: S,
    parameters: Vec<C64>,
    solutions: Vec<Vec<C64>>,
    reasons: BTreeMap<String, usize>,
    /// Whether the run's count is only a lower bound, which confirms no other point's
    /// count: it stopped after its first run because paths ran out of steps
    /// ([`Retried::handed_over`]), or no attempt classified every path (a finite
    /// endpoint or one at infinity, no crossing: [`Retried::accounted`] below the
    /// generic count). Two seed points whose same paths fail agree on a shortfall they
    /// never showed to be at infinity: on two base anchors 10⁻⁴ apart, four `rigid/rigid`
    /// critical points with multipliers near 10⁵ ran out of steps at every one of five
    /// seed points, and two of them "confirmed" 84 of the generic 88.
    lower_bound: bool,
}

/// Whether `runs` settle the count: the generic count reached, or the largest count
/// found by any run confirmed by two runs whose counts are not mere lower bounds
/// ([`SeedRun::lower_bound`]; [`seed_count_confirmed`] over those).
fn runs_confirm<S>(runs: &[SeedRun<S>], generic: usize) -> bool {
    let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
    let counted: Vec<usize> = runs
        .iter()
        .filter(|r| !r.lower_bound)
        .map(|r| r.solutions.len())
        .collect();
    most == generic || (counted.contains(&most) && seed_count_confirmed(&counted, generic))
}

/// Problem `problem` of `family` at its seed points, the common one first, the others
/// only while the count is not settled ([`seed_count_confirmed`]). Each route is the
/// straight segment from the generic point to the seed's parameters, its detours
/// through a random complex point near the seed ([`detour_point`]).
pub(crate) fn seed_problem<F: Family>(
    family: &F,
    problem: usize,
    policy: &SeedPolicy<'_>,
) -> Seeded<F::Seed> {
    // What the monodromy points left to the detours: the paths they tracked, the seed
    // points they completed, and the next point's first run if they stopped there.
    let mut fallback = Fallback {
        tracked: 0,
        runs: Vec::new(),
        first_run: None,
    };
    if policy.monodromy_stagnant_loops > 0 {
        match seed_problem_by_monodromy(family, problem, policy) {
            Ok(seeded) => return seeded,
            Err(left) => fallback = left,
        }
    }
    let mut tracked = fallback.tracked;
    let (source, starts) = family.generic_start(problem);
    let generic = starts.len();
    let twin = family.twin(problem);
    // A seed point's lost paths leave its count unconfirmed: those the twin nearly
    // tracked to the end get a patient twin run at every point. Detours re-track the
    // lost paths only: a whole detour re-tracks every path (1.2 s each on a base with
    // two coincident anchors, `plate/rigid`, where two whole detours in a row found
    // nothing), and the next seed point is the independent route for what a point
    // cannot settle (design matrix 139.4 → 129.5 s, every distance identical).
    let plans = [
        TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker)
            .lost_paths_only()
            .with_twin(twin)
            .with_patient_twin(),
        // A confirming point before the last one: where its paths run out of steps,
        // the next seed point (a few hundred milliseconds on the rigid metrics of a
        // base similar to the platform) rather than this one's re-runs and last
        // chance (seconds, and in vain there). The first point and the last one get
        // them all (handing over at the first point too left close-anchor designs
        // with five disagreeing counts).
        TrackingPlan {
            hand_over_when_steps_run_out: true,
            abandon_when_steps_run_out: false,
            ..TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker)
                .lost_paths_only()
                .with_twin(twin)
        },
        TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker)
            .with_twin(twin)
            .with_patient_twin(),
    ];
    // The seed points the monodromy points completed, and the next point's first run.
    let first_point = fallback.runs.len();
    let mut runs: Vec<SeedRun<F::Seed>> = fallback.runs;
    let mut twin_settled = false;
    for point in first_point..policy.points {
        let (seed, parameters) = family.seed(problem, point);
        let stream = ((problem as u64) << 32) + ((point as u64) << 24);
        let track = |plan: &TrackingPlan<'_>| {
            track_with_retries(
                family.system(problem),
                starts,
                |attempt| {
                    let mut points = vec![source.to_vec()];
                    if attempt > 0 {
                        let stream = family.detour_stream(stream, attempt);
                        let mut rng = random::stream(policy.seed, stream);
                        let moving = family.moving_parameters();
                        points.push(detour_point(&parameters, moving, &mut rng));
                    }
                    points.push(parameters.clone());
                    PolylinePath::new(points)
                },
                policy.attempts,
                *plan,
            )
        };
        // Whether `count` would end the search: the generic count, or the largest
        // count so far, found by an earlier point too (one whose count is not a mere
        // lower bound).
        let confirms = |count: usize| {
            let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
            count == generic
                || (count >= most
                    && runs
                        .iter()
                        .any(|r| !r.lower_bound && r.solutions.len() == count))
        };
        let lost_first = point > 0 && policy.confirm_lost_paths_first;
        let hand_over = lost_first && point + 1 < policy.points;
        let plan = if hand_over {
            &plans[1]
        } else if policy.confirm_lost_paths_first {
            &plans[0]
        } else {
            &plans[2]
        };
        // This point's first run, where the monodromy points tracked it already.
        let first_run = if point == first_point {
            fallback.first_run.as_deref()
        } else {
            None
        };
        let mut retried: Retried = track(&TrackingPlan { first_run, ..*plan });
        tracked += retried.tracked;
        let mut solutions = distinct_solutions(retried.endpoints, generic);
        let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
        if retried.handed_over && solutions.len() < most {
            // Below the best count so far: this point's re-runs may find what its first
            // run missed (on two close anchors of a rigid platform they found the
            // generic count where the next three points' first runs fell short; handing
            // over there took 15.7 s instead of 6.6 s for `rigid/plate`).
            retried = track(&plans[0]);
            tracked += retried.tracked;
            solutions = distinct_solutions(retried.endpoints, generic);
        }
        if lost_first
            && first_run.is_some()
            && !retried.handed_over
            && retried.accounted < generic
            && !confirms(solutions.len())
        {
            // The monodromy points' first run left this point unconfirmed: its own
            // reference route afresh (on two base anchors 10⁻⁴ apart this confirmed
            // counts that otherwise took further seed points: `close-base-12`
            // scattered 9.0 → 7.3 s).
            retried = track(&plans[0]);
            tracked += retried.tracked;
            solutions = distinct_solutions(retried.endpoints, generic);
        }
        if retried.handed_over {
            runs.push(SeedRun {
                seed,
                parameters,
                solutions,
                reasons: retried.reasons,
                lower_bound: true,
            });
            continue;
        }
        // Every path of this point accounted for by the twin (finite, or at infinity in
        // both formulations): the count needs no second seed point.
        let settled_by_twin = retried.confirmed_by_twin && retried.accounted == generic;
        let count = solutions.len();
        runs.push(SeedRun {
            seed,
            parameters,
            solutions,
            reasons: retried.reasons,
            lower_bound: retried.accounted < generic,
        });
        let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
        if settled_by_twin && count == most {
            twin_settled = true;
            break;
        }
        if runs_confirm(&runs, generic) {
            break;
        }
    }
    let confirmed = twin_settled || runs_confirm(&runs, generic);
    chosen_run(family.name(problem), runs, (generic, confirmed), tracked)
}

/// The seeded problem from its seed points' `runs`: the earliest run with the most
/// solutions, with a seed-stage failure for the shortfall unless `confirmed`.
fn chosen_run<S>(
    problem: String,
    runs: Vec<SeedRun<S>>,
    (generic, confirmed): (usize, bool),
    tracked: usize,
) -> Seeded<S> {
    let counts: Vec<usize> = runs.iter().map(|r| r.solutions.len()).collect();
    let most = counts.iter().copied().max().unwrap_or(0);
    let chosen = runs
        .into_iter()
        .find(|r| r.solutions.len() == most)
        .expect("at least one seed point is solved");
    let failure = (!confirmed).then(|| {
        let mut reasons = chosen.reasons.clone();
        // The shortfall no second seed point confirmed (the counts disagree, or
        // agree only as lower bounds): counted as lost.
        reasons.insert(
            format!("SeedCountsUnconfirmed{counts:?}").replace(' ', ""),
            generic - most,
        );
        PathFailure {
            pose_index: None,
            tau: None,
            problem,
            expected: generic,
            accounted: most,
            reasons,
        }
    });
    Seeded {
        seed: chosen.seed,
        parameters: chosen.parameters,
        solutions: chosen.solutions,
        generic_count: generic,
        failure,
        tracked,
        completed_by_monodromy: false,
    }
}

/// The first seed points of [`seed_problem`] with monodromy completion
/// ([`SeedPolicy::monodromy_stagnant_loops`]), where every path of the first run ends
/// (at a finite point, or at infinity by the endgame's evidence) and only path
/// crossings leave paths unaccounted for. At each of the first [`MONODROMY_POINTS`]
/// seed points the generic start set is tracked along the straight segment to the seed
/// (first run only), and where its distinct finite endpoints fall short of the generic
/// count they are completed by monodromy in the design's restricted family (only the
/// parameters the motion moves vary; [`complete_fiber`]): a path that jumped onto
/// another one's endpoint hid a point of the same fiber, which loops from the others
/// reach, where the detours track every path again (on a base congruent with the
/// platform the first seed point's `rigid/rigid` detours tracked 88 paths each, 64 of
/// them to infinity, and added nothing). As in
/// [`seed_problem`], a count below the generic one counts only when both points, each
/// reached along its own route, agree on it; the second point's first run is completed
/// only where it has fewer solutions than the first.
///
/// A path that fails may be heading for a finite point far out that loops do not
/// reach either (on a base whose anchors are 10⁻³ from collinear, four of the 88
/// `rigid/rigid` critical points at every seed: two points completed by loops agreed
/// on 84): there, where the loops give up, where the first run accounts for every path
/// with at most [`TWIN_SETTLES_AT_MOST`] at infinity (the projective twin settles the
/// count at that one point), and where the two points disagree, [`seed_problem`] goes
/// on from that point with its re-runs, detours, twin and last chances, the points
/// completed so far kept ([`Fallback`]).
fn seed_problem_by_monodromy<F: Family>(
    family: &F,
    problem: usize,
    policy: &SeedPolicy<'_>,
) -> Result<Seeded<F::Seed>, Fallback<F::Seed>> {
    let (source, starts) = family.generic_start(problem);
    let generic = starts.len();
    let system = family.system(problem);
    let mut runs: Vec<SeedRun<F::Seed>> = Vec::new();
    let mut tracked = 0;
    for point in 0..MONODROMY_POINTS.min(policy.points) {
        let (seed, parameters) = family.seed(problem, point);
        let stream = ((problem as u64) << 32) + ((point as u64) << 24);
        let paths = first_run(system, (source, starts), &parameters, policy.tracker);
        tracked += paths.len();
        let at_infinity = paths
            .iter()
            .filter(|p| p.status == PathStatus::AtInfinity)
            .count();
        let failed = paths
            .iter()
            .any(|p| matches!(p.status, PathStatus::Failed(_)));
        let settled_by_twin =
            point == 0 && accounted(&paths) == generic && at_infinity <= TWIN_SETTLES_AT_MOST;
        if failed || settled_by_twin {
            return Err(Fallback {
                tracked,
                runs,
                first_run: Some(paths),
            });
        }
        // The paths that crossed another one, re-run with the careful tracker first: a
        // few such paths cost less than a loop over every solution.
        let mut paths = paths;
        let crossed = crossings(&paths);
        if crossed.iter().any(|&c| c) {
            let route = PolylinePath::new(vec![source.to_vec(), parameters.clone()]);
            let homotopy = PathParameterHomotopy::new(system, route);
            let mut careful = Tracker::new(&homotopy, policy.retry_tracker.clone());
            for (i, _) in crossed.iter().enumerate().filter(|(_, c)| **c) {
                paths[i] = careful.track(&starts[i], i);
                tracked += 1;
            }
        }
        let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
        let completed = completed_by_monodromy(
            system,
            &paths,
            (&parameters, family.moving_parameters()),
            MonodromyLoops {
                stagnant: policy.monodromy_stagnant_loops,
                at_least: most,
                unless_reached: (point > 0).then_some(most),
            },
            policy.tracker,
            &mut random::stream(policy.seed, stream | MONODROMY_STREAM),
        );
        tracked += completed.tracked;
        if completed.abandoned {
            return Err(Fallback {
                tracked,
                runs,
                first_run: Some(paths),
            });
        }
        runs.push(SeedRun {
            seed,
            parameters,
            solutions: completed.solutions,
            reasons: completed.reasons,
            lower_bound: false,
        });
        if runs_confirm(&runs, generic) {
            let chosen = chosen_run(family.name(problem), runs, (generic, true), tracked);
            return Ok(Seeded {
                completed_by_monodromy: true,
                ..chosen
            });
        }
    }
    Err(Fallback {
        tracked,
        runs,
        first_run: None,
    })
}

/// What [`seed_problem_by_monodromy`] leaves to the detours: the paths it tracked, the
/// seed points it completed (their counts stand, and the detours go on at the next
/// point), and the next point's first run where it stopped there (the detours' first
/// run at that point is the same).
struct Fallback<S> {
    tracked: usize,
    runs: Vec<SeedRun<S>>,
    first_run: Option<Vec<PathResult>>,
}

/// The generic start set `(source, starts)` of `system` tracked along the straight
/// segment to `parameters`, with the endgame.
pub(crate) fn first_run<E: Evaluator + ?Sized>(
    system: &E,
    (source, starts): (&[C64], &[Vec<C64>]),
    parameters: &[C64],
    tracker: &TrackerOptions,
) -> Vec<PathResult> {
    let route = PolylinePath::new(vec![source.to_vec(), parameters.to_vec()]);
    track_all(
        &PathParameterHomotopy::new(system, route),
        starts,
        tracker,
        true,
    )
}

/// How many monodromy loops [`completed_by_monodromy`] tracks.
#[derive(Clone, Copy)]
pub(crate) struct MonodromyLoops {
    /// Loops in a row that add nothing, after which the loops stop.
    pub stagnant: usize,
    /// While below this many solutions (another point's count: the family's finite
    /// count is generically constant), [`CATCH_UP_STAGNANT_LOOPS`] more.
    pub at_least: usize,
    /// No loops at all where the first run reached this many solutions.
    pub unless_reached: Option<usize>,
}

/// What [`completed_by_monodromy`] found at one parameter point.
pub(crate) struct CompletedRun {
    /// Distinct finite solutions, at most the generic count.
    pub solutions: Vec<Vec<C64>>,
    /// Why paths of the route are unaccounted for ([`unaccounted_reasons`]).
    pub reasons: BTreeMap<String, usize>,
    /// Paths tracked by the loops.
    pub tracked: usize,
    /// Whether the monodromy loops gave up (too many of their paths failed): the
    /// family is too hard to track at random parameters for the loops to complete it.
    pub abandoned: bool,
}

/// The distinct finite endpoints of a first run `paths` (of the generic start set to
/// `parameters`), completed where they fall short of the generic count by monodromy
/// in the restricted family of the first `moving` parameters ([`complete_fiber`]) as
/// `loops` says.
pub(crate) fn completed_by_monodromy<E: Evaluator + ?Sized>(
    system: &E,
    paths: &[PathResult],
    (parameters, moving): (&[C64], usize),
    loops: MonodromyLoops,
    tracker: &TrackerOptions,
    rng: &mut random::SeededRng,
) -> CompletedRun {
    let generic = paths.len();
    let mut run = CompletedRun {
        solutions: distinct_solutions(finite_solutions(paths), generic),
        reasons: unaccounted_reasons(paths),
        tracked: 0,
        abandoned: false,
    };
    let reached = loops
        .unless_reached
        .is_some_and(|count| run.solutions.len() >= count);
    if run.solutions.is_empty() || run.solutions.len() >= generic || reached {
        return run;
    }
    for stagnant in [loops.stagnant, CATCH_UP_STAGNANT_LOOPS] {
        let completion = complete_fiber(
            system,
            (parameters, moving),
            &mut run.solutions,
            (generic, stagnant),
            tracker,
            rng,
        );
        run.tracked += completion.tracked;
        run.abandoned = completion.abandoned;
        if run.abandoned || run.solutions.len() >= loops.at_least {
            break;
        }
    }
    run
}

/// Paths at infinity of a first seed point's first run that accounts for every path,
/// up to which the projective twin settles the count there ([`seed_problem`]), as it
/// does for the 8 of the built-in example's 88 `rigid/rigid` paths. Beyond, a second
/// seed point costs less: on a base congruent with the platform 64 of the 88 are at
/// infinity, and the twin's re-check of them took 0.23–0.5 s per seed point.
const TWIN_SETTLES_AT_MOST: usize = 16;

/// Seed points solved with monodromy completion before [`seed_problem`] falls back to
/// the detours: two, the fewest that can agree on a count.
const MONODROMY_POINTS: usize = 2;

/// Stagnant loops a seed point's monodromy gets once more where it has fewer
/// solutions than an earlier point.
const CATCH_UP_STAGNANT_LOOPS: usize = 4;

/// Bit of the random stream of a seed point's monodromy loops (ored with the point's
/// own stream).
const MONODROMY_STREAM: u64 = 1 << 20;

/// Every problem of `family` at its seed ([`seed_problem`]), in parallel, in order.
pub(crate) fn seed_family<F: Family>(family: &F, policy: &SeedPolicy<'_>) -> Vec<Seeded<F::Seed>> {
    (0..family.problems())
        .into_par_iter()
        .map(|problem| seed_problem(family, problem, policy))
        .collect()
}

/// Splits seed results into the seeded problems, their failures and the total number
/// of paths tracked.
pub(crate) fn split_seeded<S>(seeded: Vec<Seeded<S>>) -> (Vec<Seeded<S>>, Vec<PathFailure>, usize) {
    let mut failures = Vec::new();
    let mut paths_tracked = 0;
    let problems = seeded
        .into_iter()
        .map(|mut s| {
            failures.extend(s.failure.take());
            paths_tracked += s.tracked;
            s
        })
        .collect();
    (problems, failures, paths_tracked)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(count: usize, lower_bound: bool) -> SeedRun<()> {
        SeedRun {
            seed: (),
            parameters: Vec::new(),
            solutions: vec![Vec::new(); count],
            reasons: BTreeMap::new(),
            lower_bound,
        }
    }

    /// A lower-bound run's count (handed over, or paths left unclassified) confirms
    /// no other run's count, and a larger one leaves a smaller count agreed on by two
    /// full runs unconfirmed; the generic count settles the count whoever found it.
    #[test]
    fn a_lower_bound_seed_count_confirms_nothing() {
        let confirm = |runs: &[(usize, bool)]| {
            let runs: Vec<SeedRun<()>> = runs.iter().map(|&(c, h)| run(c, h)).collect();
            runs_confirm(&runs, 88)
        };
        assert!(!confirm(&[(28, false), (28, true)]));
        assert!(confirm(&[(28, false), (28, true), (28, false)]));
        assert!(!confirm(&[(28, false), (28, false), (29, true)]));
        assert!(confirm(&[(28, false), (88, true)]));
        // The rule without hand-overs is `seed_count_confirmed`'s.
        assert!(confirm(&[(28, false), (28, false)]));
        assert!(!confirm(&[(27, false), (28, false)]));
    }
}

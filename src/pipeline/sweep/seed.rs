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
//! along different routes) agree on it, or when the family's projective twin
//! ([`super::ProjectiveTwin`]) accounts for every path of one seed point (each path
//! not finite there is at infinity in both formulations); otherwise the shortfall is
//! a seed-stage [`PathFailure`]. A seed point whose first run has paths that run out
//! of steps, but already as many solutions as the best point so far, is left at that
//! (its count a lower bound that confirms nothing) for the next seed point, except the
//! first and the last one, which re-run, detour and re-track in the twin.

use super::{PathFailure, Retried, TrackingPlan, detour_point, same_endpoint, track_with_retries};
use crate::C64;
use crate::homotopy::{PolylinePath, TrackerOptions};
use crate::pipeline::family::Family;
use crate::random;
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
    /// Whether a seed point after the first, which only confirms (or not) a count,
    /// re-tracks just its own lost paths along the detours first, and repeats them
    /// with whole detours only where that does not confirm an earlier point's count
    /// (`false`: whole detours at every seed point).
    pub confirm_lost_paths_first: bool,
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
    /// Whether the run stopped after its first run because paths ran out of steps
    /// ([`Retried::handed_over`]): its count is only a lower bound, and confirms no
    /// other point's count.
    handed_over: bool,
}

/// Whether `runs` settle the count: the generic count reached, or the largest count
/// found by any run confirmed by two runs that were not handed over
/// ([`seed_count_confirmed`] over those).
fn runs_confirm<S>(runs: &[SeedRun<S>], generic: usize) -> bool {
    let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
    let counted: Vec<usize> = runs
        .iter()
        .filter(|r| !r.handed_over)
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
    let (source, starts) = family.generic_start(problem);
    let generic = starts.len();
    let twin = family.twin(problem);
    let plans = [
        TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker)
            .lost_paths_only()
            .with_twin(twin),
        TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker).with_twin(twin),
        // A confirming point before the last one: where its paths run out of steps,
        // the next seed point (a few hundred milliseconds on the rigid metrics of a
        // base similar to the platform) rather than this one's re-runs and last
        // chance (seconds, and in vain there). The first point and the last one get
        // them all (handing over at the first point too left close-anchor designs
        // with five disagreeing counts).
        TrackingPlan {
            hand_over_when_steps_run_out: true,
            ..TrackingPlan::with_endgame(policy.tracker, policy.retry_tracker)
                .lost_paths_only()
                .with_twin(twin)
        },
    ];
    let mut runs: Vec<SeedRun<F::Seed>> = Vec::new();
    let mut tracked = 0;
    let mut twin_settled = false;
    for point in 0..policy.points {
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
        // count so far, found by an earlier point too (one not handed over).
        let confirms = |count: usize| {
            let most = runs.iter().map(|r| r.solutions.len()).max().unwrap_or(0);
            count == generic
                || (count >= most
                    && runs
                        .iter()
                        .any(|r| !r.handed_over && r.solutions.len() == count))
        };
        let lost_first = point > 0 && policy.confirm_lost_paths_first;
        let hand_over = lost_first && point + 1 < policy.points;
        let plan = match (lost_first, hand_over) {
            (true, true) => &plans[2],
            (true, false) => &plans[0],
            (false, _) => &plans[1],
        };
        let mut retried: Retried = track(plan);
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
        if retried.handed_over {
            runs.push(SeedRun {
                seed,
                parameters,
                solutions,
                reasons: retried.reasons,
                handed_over: true,
            });
            continue;
        }
        if lost_first && retried.accounted < generic && !confirms(solutions.len()) {
            retried = track(&plans[1]);
            tracked += retried.tracked;
            solutions = distinct_solutions(retried.endpoints, generic);
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
            handed_over: false,
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
    let counts: Vec<usize> = runs.iter().map(|r| r.solutions.len()).collect();
    let most = counts.iter().copied().max().unwrap_or(0);
    let confirmed = twin_settled || runs_confirm(&runs, generic);
    let chosen = runs
        .into_iter()
        .find(|r| r.solutions.len() == most)
        .expect("at least one seed point is solved");
    let failure = (!confirmed).then(|| {
        let mut reasons = chosen.reasons.clone();
        // The shortfall no second seed point confirmed: counted as lost.
        reasons.insert(
            format!("SeedCountsDisagree{counts:?}").replace(' ', ""),
            generic - most,
        );
        PathFailure {
            pose_index: None,
            tau: None,
            problem: family.name(problem),
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
    }
}

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

    fn run(count: usize, handed_over: bool) -> SeedRun<()> {
        SeedRun {
            seed: (),
            parameters: Vec::new(),
            solutions: vec![Vec::new(); count],
            reasons: BTreeMap::new(),
            handed_over,
        }
    }

    /// A handed-over run's count is a lower bound: it confirms no other run's count,
    /// and a larger one leaves a smaller count agreed on by two full runs unconfirmed;
    /// the generic count settles the count whoever found it.
    #[test]
    fn a_handed_over_seed_count_confirms_nothing() {
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

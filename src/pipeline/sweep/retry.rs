//! Robust tracking of a group of paths and its bookkeeping: re-runs, arcs around
//! divergences, detours, crossings, and which paths are accounted for.

use super::twin::{ProjectiveTwin, recheck_in_twin, recheck_patiently};
use crate::C64;
use crate::homotopy::{
    FailureReason, Homotopy, ParameterPath, PathParameterHomotopy, PathResult, PathStatus, Tracker,
    TrackerOptions,
};
use crate::random;
use crate::system::Evaluator;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Paths per parallel task of [`track_all`] and [`track_all_unless_steps_run_out`]:
/// they run in parallel over chunks of paths too (nested in the parallel poses ×
/// sub-problems), so a stage with few groups — the seed stage, a rescue chain — uses
/// every core; one tracker (workspace) per chunk. Per path instead of per chunk was
/// 30 % slower on the example. Each path is a pure function of its start, so the
/// results do not depend on the thread count.
const PATH_CHUNK: usize = 16;

/// Tracks every start solution through `homotopy` (with the endgame, or without:
/// [`Tracker::track_between`] `0 → 1`, Newton at the end); returns the path results in
/// order.
pub(crate) fn track_all<H: Homotopy + ?Sized>(
    homotopy: &H,
    starts: &[Vec<C64>],
    options: &TrackerOptions,
    endgame: bool,
) -> Vec<PathResult> {
    let chunks: Vec<Vec<PathResult>> = starts
        .par_chunks(PATH_CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut tracker = Tracker::new(homotopy, options.clone());
            chunk
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    if endgame {
                        tracker.track(x, c * PATH_CHUNK + i)
                    } else {
                        tracker.track_between(x, 0.0, 1.0, c * PATH_CHUNK + i)
                    }
                })
                .collect()
        })
        .collect();
    chunks.into_iter().flatten().collect()
}

/// [`track_all`] without the endgame ([`Tracker::track_between`] `0 → 1`), abandoned
/// as soon as a path runs out of steps ([`FailureReason::TooManySteps`]): `None` then,
/// whichever path it was, so the result does not depend on the thread count (a path
/// that runs out of steps in one order does in any). The paths not yet started when
/// one ran out are not tracked.
pub(crate) fn track_all_unless_steps_run_out<H: Homotopy + ?Sized>(
    homotopy: &H,
    starts: &[Vec<C64>],
    options: &TrackerOptions,
) -> Option<Vec<PathResult>> {
    let out_of_steps = std::sync::atomic::AtomicBool::new(false);
    let chunks: Vec<Option<Vec<PathResult>>> = starts
        .par_chunks(PATH_CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut tracker = Tracker::new(homotopy, options.clone());
            let mut paths = Vec::with_capacity(chunk.len());
            for (i, x) in chunk.iter().enumerate() {
                if out_of_steps.load(std::sync::atomic::Ordering::Relaxed) {
                    return None;
                }
                let path = tracker.track_between(x, 0.0, 1.0, c * PATH_CHUNK + i);
                if path.status == PathStatus::Failed(FailureReason::TooManySteps) {
                    out_of_steps.store(true, std::sync::atomic::Ordering::Relaxed);
                    return None;
                }
                paths.push(path);
            }
            Some(paths)
        })
        .collect();
    if out_of_steps.into_inner() {
        return None;
    }
    Some(chunks.into_iter().flatten().flatten().collect())
}

/// Why paths of one run are unaccounted for ([`accounted`]): per failure reason (its
/// name), and `PathCrossing` for each path beyond the first on a shared endpoint.
pub(crate) fn unaccounted_reasons(paths: &[PathResult]) -> BTreeMap<String, usize> {
    let mut reasons = BTreeMap::new();
    for p in paths {
        if let PathStatus::Failed(reason) = p.status {
            *reasons.entry(format!("{reason:?}")).or_insert(0) += 1;
        }
    }
    let crossed: usize = shared_endpoints(paths).iter().map(|g| g.len() - 1).sum();
    if crossed > 0 {
        reasons.insert("PathCrossing".into(), crossed);
    }
    reasons
}

/// What [`track_with_retries`] found for one group of paths.
pub(crate) struct Retried {
    /// The distinct finite endpoints of all attempts.
    pub endpoints: Vec<Vec<C64>>,
    /// Paths accounted for, best over the attempts (see [`accounted`]).
    pub accounted: usize,
    /// Paths tracked, re-runs and detours included.
    pub tracked: usize,
    /// Why paths were unaccounted for on the reference route after the careful
    /// re-runs ([`unaccounted_reasons`]; empty if none were).
    pub reasons: BTreeMap<String, usize>,
    /// Where the projective twin checked every path of the reference route that did
    /// not end at a finite point: whether it confirmed each of them at infinity or
    /// found it finite, so that the distinct finite endpoints and the confirmed
    /// points at infinity account for every path (`false` without a twin, or where a
    /// twin run failed).
    pub confirmed_by_twin: bool,
    /// Paths the projective twin ended on its hyperplane at infinity (`λ₀ = 0`, the
    /// configuration finite): Fritz John points, singular points of the constraint
    /// set, or critical points within about `|λ₀|` of one (see
    /// [`crate::homotopy::HOMOGENEOUS_ZERO`]).
    pub at_infinity_in_twin: usize,
    /// Whether the plan handed the group over after the first run
    /// ([`TrackingPlan::hand_over_when_steps_run_out`]): its paths ran out of steps,
    /// and nothing after the first run was tried.
    pub handed_over: bool,
}

/// Relative distance under which two endpoints are the same point.
pub(crate) const SAME_ENDPOINT: f64 = 1e-8;

pub(crate) fn same_endpoint(a: &[C64], b: &[C64]) -> bool {
    crate::homotopy::refine::same_point(a, b, SAME_ENDPOINT)
}

/// Whether a path's endpoint is finite and was reached without winding (winding number
/// 1): nonsingular endpoints, and those classified singular only because their
/// condition number is large (e.g. far out along an isotropic line, where the unscaled
/// condition number exceeds `singular_condition` although the point is simple).
pub(crate) fn simple_endpoint(path: &PathResult) -> bool {
    path.status.is_finite() && path.winding_number == 1
}

/// For every path, whether it is a *path crossing*: its endpoint is simple
/// ([`simple_endpoint`]) and another such path ends at the same point. A nonsingular
/// solution is the endpoint of exactly one path of a parameter homotopy, so one of them
/// jumped (and missed a critical point). Endpoints reached with winding (Cauchy
/// endgame, winding number > 1) may legitimately be shared (multiplicity); a genuinely
/// singular endpoint reached without winding is reported as a crossing, which can only
/// cost a re-run, never hide a lost path. Paths classified at infinity on the same
/// point at the same `t` cross too ([`shared_endpoints`]).
pub(crate) fn crossings(paths: &[PathResult]) -> Vec<bool> {
    let mut crossed = vec![false; paths.len()];
    for group in shared_endpoints(paths) {
        for i in group {
            crossed[i] = true;
        }
    }
    crossed
}

/// Groups (two or more paths) that share an endpoint no two paths may share: simple
/// finite endpoints ([`simple_endpoint`]), and paths classified at infinity that
/// stopped at the same `t` on the same point. Distinct paths of a homotopy never meet
/// before `t = 1` (and the branches of one Puiseux cycle are apart at any one radius),
/// so a shared point at infinity means one path jumped onto another one's divergent
/// path, hiding the critical point it should have reached.
pub(crate) fn shared_endpoints(paths: &[PathResult]) -> Vec<Vec<usize>> {
    let shareable = |a: &PathResult, b: &PathResult| {
        (simple_endpoint(a) && simple_endpoint(b))
            || (a.status == PathStatus::AtInfinity
                && b.status == PathStatus::AtInfinity
                && a.last_t == b.last_t)
    };
    let eligible = |p: &PathResult| simple_endpoint(p) || p.status == PathStatus::AtInfinity;
    // Sort and sweep: two endpoints within `same_endpoint`'s tolerance have first
    // coordinates within `window` (the largest tolerance of any pair), so only
    // neighbours in the order of Re x₀ closer than that are compared.
    let key = |i: usize| paths[i].solution.first().map_or(0.0, |v| v.re);
    let mut order: Vec<usize> = (0..paths.len()).filter(|&i| eligible(&paths[i])).collect();
    if order.len() < 2 {
        return Vec::new();
    }
    let largest = order.iter().fold(0.0f64, |m, &i| {
        paths[i]
            .solution
            .iter()
            .fold(m, |m, v| m.max(v.re.abs()).max(v.im.abs()))
    });
    let window = SAME_ENDPOINT * (1.0 + 2.0 * largest);
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
    // Pairs `(i, j)`, `i < j`, that share an endpoint, with `i`'s tolerance.
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for (position, &a) in order.iter().enumerate() {
        for &b in &order[position + 1..] {
            if key(b) - key(a) > window {
                break;
            }
            let (i, j) = (a.min(b), a.max(b));
            if shareable(&paths[i], &paths[j])
                && same_endpoint(&paths[i].solution, &paths[j].solution)
            {
                pairs.push((i, j));
            }
        }
    }
    pairs.sort_unstable();
    // Each group: the first ungrouped path and every later ungrouped one sharing its
    // endpoint.
    let mut grouped = vec![false; paths.len()];
    let mut groups = Vec::new();
    for run in pairs.chunk_by(|x, y| x.0 == y.0) {
        let i = run[0].0;
        if grouped[i] {
            continue;
        }
        let mut group = vec![i];
        for &(_, j) in run {
            if !grouped[j] {
                group.push(j);
                grouped[j] = true;
            }
        }
        if group.len() > 1 {
            groups.push(group);
        }
    }
    groups
}

/// Paths whose fate is known: a finite endpoint, or an endpoint at infinity (a
/// critical point that does not exist at these parameters, classified by the endgame),
/// less one per extra path on a shared endpoint ([`shared_endpoints`]: a path crossing
/// hides a missed critical point just as a failed path does).
pub(crate) fn accounted(paths: &[PathResult]) -> usize {
    let classified = paths
        .iter()
        .filter(|p| !matches!(p.status, PathStatus::Failed(_)))
        .count();
    let extra: usize = shared_endpoints(paths).iter().map(|g| g.len() - 1).sum();
    classified - extra
}

/// The distinct finite endpoints: every endpoint reached with winding (shared ones
/// count with their multiplicity of paths, as the start count does) and each simple
/// endpoint ([`simple_endpoint`]) once.
pub(crate) fn finite_solutions(paths: &[PathResult]) -> Vec<Vec<C64>> {
    let mut out: Vec<Vec<C64>> = Vec::new();
    for p in paths.iter().filter(|p| p.status.is_finite()) {
        let duplicate = simple_endpoint(p) && out.iter().any(|x| same_endpoint(x, &p.solution));
        if !duplicate {
            out.push(p.solution.clone());
        }
    }
    out
}

/// The complex conjugation of a family's unknowns at real parameters (see
/// [`TrackingPlan::conjugate`]).
pub(crate) type Conjugation<'c> = dyn Fn(&[C64]) -> Vec<C64> + Sync + 'c;

/// Adds to `endpoints` the image under `conjugate` of every one whose image is not
/// among them (the same point by [`same_endpoint`]), up to `limit` points in all.
/// Where the target parameters are real the system has real coefficients, and the
/// conjugate of a nonsingular solution is a nonsingular solution with the same
/// residual and condition: a route that reached one of a pair and lost the other has
/// found both. Returns how many were added.
pub(crate) fn with_conjugates(
    conjugate: &Conjugation<'_>,
    endpoints: &mut Vec<Vec<C64>>,
    limit: usize,
) -> usize {
    let found = endpoints.len();
    for i in 0..found {
        if endpoints.len() >= limit {
            break;
        }
        let image = conjugate(&endpoints[i]);
        if !endpoints.iter().any(|y| same_endpoint(y, &image)) {
            endpoints.push(image);
        }
    }
    endpoints.len() - found
}

/// Random complex detour point near `target`: `target + ε·ξ` on its first `moving`
/// coordinates (the ones the motion moves; the others, e.g. a rigid part's shape
/// constants, stay), ξ standard complex normal, `ε = 0.1·(1 + ‖target‖∞)`.
pub(crate) fn detour_point(target: &[C64], moving: usize, rng: &mut random::SeededRng) -> Vec<C64> {
    let scale = 0.1 * (1.0 + target.iter().fold(0.0f64, |m, v| m.max(v.norm())));
    target
        .iter()
        .enumerate()
        .map(|(i, v)| {
            if i < moving {
                v + random::complex_normal(rng) * scale
            } else {
                *v
            }
        })
        .collect()
}

/// Half-width in `t` of the arcs around a point where a path diverged before the
/// endgame zone ([`track_with_retries`]).
pub(crate) const DIVERGENCE_ARC: f64 = 0.05;

/// Steps shared by the last re-run of a route's paths that are still lost after the
/// detours ([`track_with_retries`]): each gets `LAST_CHANCE_STEPS / lost` steps when
/// that exceeds the retry tracker's own budget.
pub(super) const LAST_CHANCE_STEPS: usize = 30_000;

/// At most this many lost paths get the last re-run. On designs with two close
/// anchors of a rigid part (10⁻⁴ apart) a pose loses up to eight paths near clusters
/// of critical points; with 3,750–6,000 steps each none of them was found (49 of 49
/// re-runs failed), with 15,000–30,000 steps 5 of 7 were.
pub(super) const LAST_CHANCE_PATHS: usize = 2;

/// Whole detours in a row that add no endpoint and account for no more paths, after
/// which [`track_with_retries`] tracks no further detour.
pub(super) const STAGNANT_DETOURS: usize = 2;

/// The tracker settings of [`track_with_retries`].
#[derive(Clone, Copy)]
pub(crate) struct TrackingPlan<'a> {
    /// Options of the first run and of the detours.
    pub first: &'a TrackerOptions,
    /// Options of the re-runs of failed or crossed paths (always with the endgame).
    pub retry: &'a TrackerOptions,
    /// Whether the first run and the detours end with the endgame. Without it (between
    /// two generic parameter points, where every critical point is finite and
    /// nonsingular) the endpoint is Newton-refined at `t = 1`; a path that fails,
    /// crosses another one or diverges is re-run with the endgame.
    pub endgame: bool,
    /// Whether a detour re-tracks every path when the lost ones alone do not complete
    /// the set (`false`: only the lost ones, along each detour in turn).
    pub whole_detours: bool,
    /// The family in a second formulation ([`ProjectiveTwin`]): the reference route's
    /// paths that end at infinity or stay lost are tracked once more there.
    pub twin: Option<&'a dyn ProjectiveTwin>,
    /// Whether the twin's paths that ran out of steps near `t = 1`, if there are few
    /// of them, get a patient second twin run ([`recheck_patiently`]): for a route
    /// whose lost paths would otherwise leave a count unconfirmed (a seed point), not
    /// for the many routes of the poses.
    pub patient_twin: bool,
    /// Whether to stop right after the first run when a path of it ran out of steps
    /// ([`FailureReason::TooManySteps`]), with [`Retried::handed_over`] set: the
    /// caller has another route to try first. A route along which paths need more
    /// than the tracker's whole step budget is hard everywhere along it (e.g. a design
    /// with two anchors of a rigid part 10⁻⁴ apart, whose critical points have
    /// multipliers of 10⁷ at every parameter of the seed route), and its re-runs,
    /// detours and long last re-runs cost 10–40 times a route that meets that
    /// trouble only at its end.
    pub hand_over_when_steps_run_out: bool,
    /// With [`TrackingPlan::hand_over_when_steps_run_out`] and without the endgame:
    /// the first run stops at the first path that runs out of steps
    /// ([`track_all_unless_steps_run_out`]), for a caller that discards a handed-over
    /// run (a pose's seed route, whose points the generic route then finds). The
    /// [`Retried`] then holds no endpoint and counts every start as tracked.
    pub abandon_when_steps_run_out: bool,
    /// The complex conjugation of the family's unknowns, where the route's target
    /// parameters are real (a real pose): the system there has real coefficients, so
    /// the conjugate of a finite nonsingular endpoint is one too. After each attempt
    /// the endpoints are completed with the conjugates they lack
    /// ([`with_conjugates`]), and a set completed that way ends the attempts.
    pub conjugate: Option<&'a Conjugation<'a>>,
    /// The first run along the reference route, where the caller has tracked it
    /// already (with `first` and the plan's endgame): not tracked again.
    pub first_run: Option<&'a [PathResult]>,
}

impl<'a> TrackingPlan<'a> {
    /// Both runs with the endgame.
    pub fn with_endgame(first: &'a TrackerOptions, retry: &'a TrackerOptions) -> Self {
        TrackingPlan {
            first,
            retry,
            endgame: true,
            whole_detours: true,
            twin: None,
            patient_twin: false,
            hand_over_when_steps_run_out: false,
            abandon_when_steps_run_out: false,
            conjugate: None,
            first_run: None,
        }
    }

    /// The same plan with detours of the lost paths only.
    pub fn lost_paths_only(self) -> Self {
        TrackingPlan {
            whole_detours: false,
            ..self
        }
    }

    /// The same plan with a projective twin (`None`: without).
    pub fn with_twin(self, twin: Option<&'a dyn ProjectiveTwin>) -> Self {
        TrackingPlan { twin, ..self }
    }

    /// The same plan with a patient second twin run ([`TrackingPlan::patient_twin`]).
    pub fn with_patient_twin(self) -> Self {
        TrackingPlan {
            patient_twin: true,
            ..self
        }
    }

    /// The same plan with the target's conjugation (see [`TrackingPlan::conjugate`]).
    pub fn with_conjugate(self, conjugate: Option<&'a Conjugation<'a>>) -> Self {
        TrackingPlan { conjugate, ..self }
    }
}

/// Tracks `starts` (solutions of `system` at `path(k)`'s start) along `path(0)` (the
/// reference route, `plan.first`), then, while paths are unaccounted for:
/// 1. re-tracks the failed paths and path crossings (two paths on one nonsingular
///    endpoint) with `plan.retry` and the endgame, except paths that diverged before
///    the endgame zone (passing close to infinity is a property of the route, not of
///    the step size); without the endgame also the paths that diverged;
/// 2. tracks each path that diverged before the endgame zone
///    around the point where it did, along a small arc in the `t`-plane on either
///    side ([`Tracker::track_via`]); an endpoint counts only if it is finite and
///    distinct from every endpoint found (an endpoint of any route is a solution at
///    the target, but which one a path reaches may depend on the route);
/// 3. tracks the lost paths (failed or crossed) along the first detour `path(1)`;
/// 4. with a projective twin (`plan.twin`), tracks the reference route's paths at
///    infinity and those still lost once more in the twin ([`ProjectiveTwin`]), and
///    with [`TrackingPlan::patient_twin`] the few lost ones that ran out of steps
///    there near their end once more with a long budget ([`recheck_patiently`]);
///    before the further detours, which cost a whole run each where the twin
///    re-tracks a few paths (on two base anchors 10⁻⁴ apart, the `bars/rigid` curve of
///    8 scattered poses tracked 1,738 paths in 12.6 s with the detours first, 1,481 in
///    7.7 s so);
/// 5. tracks every path (or, without `plan.whole_detours`, the lost ones the twin did
///    not classify) along the detours `path(1)`, … `path(attempts)`, merging the
///    distinct finite endpoints, until
///    [`STAGNANT_DETOURS`] whole detours in a row add no endpoint and account for no
///    more paths (on designs whose base is congruent with or similar to the platform,
///    the `rigid/rigid` seed stage sends 64 of 88 paths to infinity and a few of them
///    stay unclassified on every detour);
/// 6. gives the lost paths the twin did not classify a last, long re-run.
///
/// Returns the merged finite endpoints, the number of accounted paths ([`accounted`]:
/// of the best attempt, or the distinct finite endpoints of all attempts plus the
/// most paths one attempt classified at infinity) and the number of paths tracked.
pub(crate) fn track_with_retries<E: Evaluator + ?Sized, P: ParameterPath>(
    system: &E,
    starts: &[Vec<C64>],
    path: impl Fn(usize) -> P,
    attempts: usize,
    plan: TrackingPlan<'_>,
) -> Retried {
    let TrackingPlan {
        first: tracker,
        retry: retry_tracker,
        endgame,
        whole_detours,
        twin,
        patient_twin,
        hand_over_when_steps_run_out,
        abandon_when_steps_run_out,
        conjugate,
        first_run,
    } = plan;
    let expected = starts.len();
    // The endpoints with the conjugates they lack (up to `expected`), where the target
    // is real.
    let complete_conjugates = |endpoints: &mut Vec<Vec<C64>>| {
        if let Some(conjugate) = conjugate {
            with_conjugates(conjugate, endpoints, expected);
        }
    };
    let reference = PathParameterHomotopy::new(system, path(0));
    let (mut paths, mut tracked) = match first_run {
        Some(paths) => (paths.to_vec(), 0),
        None if hand_over_when_steps_run_out && abandon_when_steps_run_out && !endgame => {
            match track_all_unless_steps_run_out(&reference, starts, tracker) {
                Some(paths) => (paths, starts.len()),
                None => {
                    return Retried {
                        endpoints: Vec::new(),
                        accounted: 0,
                        tracked: starts.len(),
                        reasons: BTreeMap::from([("TooManySteps".to_string(), 1)]),
                        confirmed_by_twin: false,
                        at_infinity_in_twin: 0,
                        handed_over: true,
                    };
                }
            }
        }
        None => (
            track_all(&reference, starts, tracker, endgame),
            starts.len(),
        ),
    };
    if hand_over_when_steps_run_out
        && paths
            .iter()
            .any(|p| p.status == PathStatus::Failed(FailureReason::TooManySteps))
    {
        return Retried {
            endpoints: finite_solutions(&paths),
            accounted: accounted(&paths),
            tracked,
            reasons: unaccounted_reasons(&paths),
            confirmed_by_twin: false,
            at_infinity_in_twin: 0,
            handed_over: true,
        };
    }
    let crossed = crossings(&paths);
    let diverged_mid_path =
        |p: &PathResult| p.status == PathStatus::Failed(FailureReason::DivergedBeforeEndgame);
    // Without the endgame a divergence (`DivergedOnRoute`) only means the norm grew
    // past `at_infinity_norm` somewhere along the route: re-run with the endgame to
    // tell a point at infinity of the target from a pole passed on the way.
    let rerun = |p: &PathResult, crossed: bool| {
        (matches!(p.status, PathStatus::Failed(_)) && !diverged_mid_path(p))
            || crossed
            || p.status == PathStatus::Failed(FailureReason::DivergedOnRoute)
    };
    if paths.iter().zip(&crossed).any(|(p, &c)| rerun(p, c)) {
        let mut careful = Tracker::new(&reference, retry_tracker.clone());
        for (i, path) in paths.iter_mut().enumerate() {
            if rerun(path, crossed[i]) {
                *path = careful.track(&starts[i], i);
                tracked += 1;
            }
        }
    }
    let mut endpoints = finite_solutions(&paths);
    let mut best = accounted(&paths);
    let conjugates_before = endpoints.len();
    complete_conjugates(&mut endpoints);
    best += endpoints.len() - conjugates_before;
    let reasons = if best < expected {
        unaccounted_reasons(&paths)
    } else {
        BTreeMap::new()
    };
    let count_at_infinity = |paths: &[PathResult]| {
        paths
            .iter()
            .filter(|p| p.status == PathStatus::AtInfinity)
            .count()
    };
    let mut at_infinity = count_at_infinity(&paths);
    let merge = |endpoints: &mut Vec<Vec<C64>>, found: Vec<Vec<C64>>| {
        for x in found {
            if !endpoints.iter().any(|y| same_endpoint(y, &x)) {
                endpoints.push(x);
            }
        }
    };
    if best < expected {
        // Paths that passed too close to infinity on the reference route: around the
        // trouble spot `t_c` along a small arc in the t-plane, on either side (where
        // the route has no breakpoint, at which a complex t would not be analytic).
        // Away from branch points both arcs continue the same path, to the endpoint
        // the reference route would reach.
        let mut arcs = Tracker::new(&reference, tracker.clone());
        let breakpoints = reference.breakpoints();
        for p in paths.iter().filter(|p| diverged_mid_path(p)) {
            let t_c = p.last_t.re;
            let delta = DIVERGENCE_ARC.min(t_c).min(1.0 - t_c);
            if breakpoints.iter().any(|b| (b - t_c).abs() <= delta) {
                continue;
            }
            for side in [1.0, -1.0] {
                let via = [
                    C64::new(t_c - delta, 0.0),
                    C64::new(t_c, side * delta),
                    C64::new(t_c + delta, 0.0),
                ];
                let around = arcs.track_via(&starts[p.path_index], &via, p.path_index);
                tracked += 1;
                if simple_endpoint(&around)
                    && !endpoints.iter().any(|y| same_endpoint(y, &around.solution))
                {
                    endpoints.push(around.solution);
                    break;
                }
            }
        }
        complete_conjugates(&mut endpoints);
        best = best.max(endpoints.len() + at_infinity);
    }
    // The lost paths along the first detour, before the twin: it costs as many paths
    // as were lost, and where it completes the set the twin re-tracks only the paths
    // at infinity.
    let lost: Vec<usize> = {
        let crossed = crossings(&paths);
        paths
            .iter()
            .zip(&crossed)
            .filter(|&(p, &c)| matches!(p.status, PathStatus::Failed(_)) || c)
            .map(|(p, _)| p.path_index)
            .collect()
    };
    let first_detour_of_lost =
        best < expected && attempts > 0 && !lost.is_empty() && lost.len() < starts.len();
    if first_detour_of_lost {
        let detour = PathParameterHomotopy::new(system, path(1));
        let lost_starts: Vec<Vec<C64>> = lost.iter().map(|&i| starts[i].clone()).collect();
        let found = track_all(&detour, &lost_starts, tracker, endgame);
        tracked += lost.len();
        merge(&mut endpoints, finite_solutions(&found));
        complete_conjugates(&mut endpoints);
        best = best.max(endpoints.len() + at_infinity);
    }
    let mut confirmed_by_twin = false;
    let mut at_infinity_in_twin = 0;
    // Paths the twin classified (finite, or on its hyperplane at infinity): the last
    // chance below is for the others.
    let mut resolved_by_twin: Vec<usize> = Vec::new();
    if let Some(twin) = twin {
        // The reference route's paths at infinity, and those still lost, once more in
        // the projective twin: a finite endpoint there is a critical point this
        // formulation missed (a path classified at infinity that is not, or a lost
        // one); one at infinity there too confirms the classification.
        let crossed = crossings(&paths);
        let unsettled: Vec<usize> = paths
            .iter()
            .zip(&crossed)
            .filter(|&(p, &c)| {
                p.status == PathStatus::AtInfinity
                    || (best < expected && (matches!(p.status, PathStatus::Failed(_)) || c))
            })
            .map(|(p, _)| p.path_index)
            .collect();
        if !unsettled.is_empty() {
            // The lost ones straight to `t = 1` first (see [`recheck_in_twin`]).
            let lost_here: Vec<usize> = unsettled
                .iter()
                .copied()
                .filter(|&i| paths[i].status != PathStatus::AtInfinity)
                .collect();
            let mut check =
                recheck_in_twin(twin, (starts, &unsettled, &lost_here), || path(0), tracker);
            // Lost paths (not those at infinity on the reference route) that ran out
            // of steps in the twin too, close to their endpoints.
            let nearly_there: Vec<usize> = check
                .ran_out_near_the_end
                .iter()
                .copied()
                .filter(|&i| paths[i].status != PathStatus::AtInfinity)
                .collect();
            let patient = patient_twin
                .then(|| recheck_patiently(twin, starts, &nearly_there, || path(0), tracker))
                .flatten();
            if let Some(again) = patient {
                check.absorb(again);
            }
            tracked += check.tracked;
            let mut recovered_from_infinity = 0;
            let classified = check.finite_or_at_infinity();
            resolved_by_twin.extend(check.finite.iter().map(|(i, _)| *i));
            resolved_by_twin.extend(&check.at_infinity);
            for (i, x) in check.finite {
                if !endpoints.iter().any(|y| same_endpoint(y, &x)) {
                    endpoints.push(x);
                    if paths[i].status == PathStatus::AtInfinity {
                        recovered_from_infinity += 1;
                    }
                }
            }
            // A lost path that the twin sends to infinity is accounted for: the twin is
            // a route independent of the one that lost it (e.g. a critical point whose
            // multipliers grow without bound while K′ stays finite, which affine
            // multipliers cannot follow to the end).
            let lost_at_infinity = check
                .at_infinity
                .iter()
                .filter(|&&i| paths[i].status != PathStatus::AtInfinity)
                .count()
                // Never more than the reference route left unaccounted (of two paths
                // crossing on one endpoint, one reached it).
                .min(expected - accounted(&paths));
            let reference_at_infinity = count_at_infinity(&paths);
            let at_infinity = at_infinity
                .max(reference_at_infinity)
                .saturating_sub(recovered_from_infinity)
                + lost_at_infinity;
            complete_conjugates(&mut endpoints);
            best = best.max(endpoints.len() + at_infinity);
            at_infinity_in_twin = check.at_infinity.len();
            confirmed_by_twin = endpoints.len() + check.at_infinity.len() >= expected
                && classified == unsettled.len();
        }
    }
    // The starts whose paths are still unaccounted for on the reference route (and
    // in the twin).
    let missing: Vec<Vec<C64>> = if best < expected {
        let crossed = crossings(&paths);
        paths
            .iter()
            .zip(&crossed)
            .filter(|&(p, &c)| {
                (matches!(p.status, PathStatus::Failed(_)) || c)
                    && !resolved_by_twin.contains(&p.path_index)
            })
            .map(|(p, _)| starts[p.path_index].clone())
            .collect()
    } else {
        Vec::new()
    };
    // Whole detours in a row that found no new endpoint and accounted for no more
    // paths: after STAGNANT_DETOURS of them the rest are not tracked.
    let mut stagnant = 0;
    for attempt in 1..=attempts {
        if best >= expected || stagnant >= STAGNANT_DETOURS {
            break;
        }
        if attempt == 1 && first_detour_of_lost && !whole_detours {
            // Its lost paths are tracked along it already.
            continue;
        }
        let detour = PathParameterHomotopy::new(system, path(attempt));
        let lost_only = if attempt == 1 {
            !first_detour_of_lost
        } else {
            !whole_detours
        };
        if lost_only && !missing.is_empty() && missing.len() < starts.len() {
            // First only those on the detour: any distinct finite endpoint they reach
            // is a critical point the reference route missed (e.g. 2 of the example's
            // 80 `rigid/rigid` seed → pose-0 paths, which pass through a pole on the
            // way). The whole detour only if they do not complete the set (and the
            // plan asks for whole detours).
            let found = track_all(&detour, &missing, tracker, endgame);
            tracked += missing.len();
            merge(&mut endpoints, finite_solutions(&found));
            complete_conjugates(&mut endpoints);
            best = best.max(endpoints.len() + at_infinity);
            if best >= expected || !whole_detours {
                continue;
            }
        }
        let paths = track_all(&detour, starts, tracker, endgame);
        tracked += starts.len();
        let (endpoints_before, best_before) = (endpoints.len(), best);
        best = best.max(accounted(&paths));
        at_infinity = at_infinity.max(count_at_infinity(&paths));
        merge(&mut endpoints, finite_solutions(&paths));
        complete_conjugates(&mut endpoints);
        // The union of the attempts' distinct finite endpoints, plus the most paths
        // any one attempt classified at infinity, may account for more than any
        // single attempt.
        best = best.max(endpoints.len() + at_infinity);
        if endpoints.len() == endpoints_before && best == best_before {
            stagnant += 1;
        } else {
            stagnant = 0;
        }
    }
    if best < expected {
        // Last chance: the reference route's paths that ran out of steps or failed
        // otherwise (not those that passed close to infinity: that is the route's
        // property), once more with a long step budget shared among them. Paths near
        // a cluster of critical points (e.g. a base congruent with the platform, where
        // a critical point tends to the singular configuration with the platform on
        // the base) need thousands of steps; the shared budget bounds the cost of a
        // pose that loses many (only a few lost paths get it: [`LAST_CHANCE_PATHS`]).
        let long_runs: Vec<usize> = paths
            .iter()
            .filter(|p| matches!(p.status, PathStatus::Failed(_)) && !diverged_mid_path(p))
            .map(|p| p.path_index)
            .filter(|i| !resolved_by_twin.contains(i))
            .collect();
        let per_path = LAST_CHANCE_STEPS / long_runs.len().max(1);
        if !long_runs.is_empty()
            && long_runs.len() <= LAST_CHANCE_PATHS
            && per_path > retry_tracker.step.max_steps
        {
            let mut long = retry_tracker.clone();
            long.step.max_steps = per_path;
            long.precision.max_extended_steps = per_path.max(long.precision.max_extended_steps);
            let mut patient = Tracker::new(&reference, long);
            let mut reference_at_infinity = count_at_infinity(&paths);
            for i in long_runs {
                let again = patient.track(&starts[i], i);
                tracked += 1;
                if again.status == PathStatus::AtInfinity {
                    reference_at_infinity += 1;
                } else if simple_endpoint(&again)
                    && !endpoints.iter().any(|y| same_endpoint(y, &again.solution))
                {
                    endpoints.push(again.solution);
                }
            }
            best = best.max(endpoints.len() + reference_at_infinity);
        }
    }
    Retried {
        endpoints,
        // The union of attempts can exceed the paths (duplicates beyond tolerance).
        accounted: best.min(expected),
        tracked,
        reasons,
        confirmed_by_twin,
        at_infinity_in_twin,
        handed_over: false,
    }
}

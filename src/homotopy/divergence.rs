//! Paths of `solve` whose norm passed `at_infinity_norm` before the endgame zone
//! (`Failed(DivergedBeforeEndgame)` after the re-runs): where is the singularity the
//! path ran into, and what lies beyond it.
//!
//! Near a singularity `t_p` of the path (a point where a root of `H(·, t_p)` is at
//! infinity) the largest coordinate behaves like `x_i ≈ a (t_p − t)^{−k}`, so its
//! growth rate `g = ẋ_i / x_i = k / (t_p − t)` has a reciprocal linear in `t`:
//! `1/g(t) = (t_p − t)/k`. Two rates `g(t₁)`, `g(t₂)` on the path give the line and
//! its zero `t_p = t₂ − (1/g(t₂)) / m`, `m = (1/g(t₂) − 1/g(t₁)) / (t₂ − t₁)` (a
//! ratio test in the spirit of the pole estimates of Telen, Van Barel and Verschelde,
//! "A robust numerical path tracking algorithm for polynomial homotopy continuation",
//! SIAM J. Sci. Comput. 2020). A path to infinity at the target grows like a power
//! of `s = 1 − t` (`x_i ≈ a s^v`, `g = −v/s`): its singularity is `t_p = 1`, at
//! distance `s` ahead. A pole passed on the way — a complex `t_p` close to the real
//! segment, e.g. in the second stage of a polyhedral homotopy, where a path may
//! legitimately be huge halfway and finite at `t = 1` — lies a small fraction of `s`
//! ahead, and says nothing about the endpoint.
//!
//! So a diverged path whose singularity is located just ahead of it
//! ([`pole_ahead`]) is never counted as at infinity: it is tracked around that point,
//! along arcs in the complex `t`-plane on both sides ([`around_the_pole`]), and the
//! endgame at `t = 1` classifies its endpoint; if that fails it stays failed. Any
//! other diverged path is at infinity if it grows like a power of `s`
//! ([`power_of_s_growth`]), else it is tracked around the point where it diverged in
//! the same way.

use super::homotopies::Homotopy;
use super::tracker::{FailureReason, PathResult, PathStatus, Tracker, TrackerOptions};
use crate::C64;
use rayon::prelude::*;

/// Largest `|v|` of the valuation `v = −Re(s ẋ_i / x_i)` that counts as growth towards
/// `t = 1`; a pole at a complex `t_p` near the real segment gives
/// `v ≈ −(1 − t)/|t_p − t|`, of the order of `10⁷` where the norm passes 10⁸.
const MAX_EARLY_VALUATION: f64 = 100.0;

/// A located singularity `t_p` is a pole just ahead of a diverged path's last point
/// `t` if `Re t_p > t` and `|t_p − t| ≤ POLE_AHEAD · s` (`s = 1 − t`). Growth like a
/// power of `s` locates `t_p ≈ 1`, at distance `≈ s` (ku10's and des18_3's paths to
/// infinity under total degree: 1.0–2.5 s, or behind the point); eco8's stage-two
/// poles in the polyhedral homotopy lie 0.02–0.1 s ahead.
const POLE_AHEAD: f64 = 0.5;

/// The second growth rate of [`locate_singularity`] is taken at
/// `t₁ = t₂ − RATE_STEP / |g(t₂)|`: a fixed fraction of the distance `k/|g|` to the
/// singularity, where the local model still holds and `1/g` has changed measurably.
const RATE_STEP: f64 = 0.5;

/// Radii of the arcs of [`around_the_pole`], tried in turn: `f · |t_p − t₂|` for `f`
/// in `ARC_FACTORS` (the located pole's distance from the last point, where the norm
/// passed `at_infinity_norm`). An arc through `t_c − r` and `t_c ± i r` stays at least
/// `(r + |Im t_p|)/√2` from the pole, so `f = 4` keeps about 3 times the distance at
/// which the path diverged; smaller arcs enclose fewer other singularities, larger ones
/// pass further from this one.
const ARC_FACTORS: [f64; 3] = [4.0, 2.5, 6.0];
/// Least radius of the arcs of [`around_the_pole`].
const MIN_ARC: f64 = 0.02;
/// Largest radius of the arcs of [`around_the_pole`].
const MAX_ARC: f64 = 0.25;

/// The growth rate `ẋ_i / x_i` of coordinate `i` at the point `x` of a path at `t`
/// ([`Tracker::velocity_at`]); `None` if the Jacobian is singular or the rate is zero or
/// not finite.
fn growth_rate<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    x: &[C64],
    t: C64,
    i: usize,
) -> Option<C64> {
    let g = tracker.velocity_at(x, t)?[i] / x[i];
    (g.re.is_finite() && g.im.is_finite() && g.norm() > 0.0).then_some(g)
}

/// Index of the largest coordinate of `x`.
fn largest(x: &[C64]) -> Option<usize> {
    (0..x.len()).max_by(|&a, &b| x[a].norm().total_cmp(&x[b].norm()))
}

/// The singularity `t_p` the diverged path `p` ran into (see the module
/// documentation): the growth rate `g₂` of its largest coordinate at its last point
/// `t₂` and `g₁` at `t₁ = t₂ − RATE_STEP/|g₂|` (the path re-tracked from `start` to
/// `t₁` by `tracker`, without endgame) give `t_p = t₂ − (1/g₂)/m`,
/// `m = (1/g₂ − 1/g₁)/(t₂ − t₁)`. `None` if a rate is unavailable or the re-run fails.
pub(super) fn locate_singularity<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    start: &[C64],
    p: &PathResult,
) -> Option<C64> {
    let t2 = p.last_t;
    let i = largest(&p.solution)?;
    let g2 = growth_rate(tracker, &p.solution, t2, i)?;
    let t1 = t2.re - RATE_STEP / g2.norm();
    if t2.im != 0.0 || t1.is_nan() || t1 <= 0.0 {
        return None;
    }
    let earlier = tracker.track_between(start, 0.0, t1, p.path_index);
    if !earlier.status.is_finite() {
        return None;
    }
    let g1 = growth_rate(tracker, &earlier.solution, C64::new(t1, 0.0), i)?;
    let slope = (g2.inv() - g1.inv()) / (t2.re - t1);
    let t_p = t2 - g2.inv() / slope;
    (t_p.re.is_finite() && t_p.im.is_finite()).then_some(t_p)
}

/// Whether the singularity `t_p` located for the diverged path `p` is a pole just
/// ahead of its last point (see [`POLE_AHEAD`]).
pub(super) fn pole_ahead(p: &PathResult, t_p: C64) -> bool {
    let s = 1.0 - p.last_t.re;
    t_p.re > p.last_t.re && (t_p - p.last_t).norm() <= POLE_AHEAD * s
}

/// Whether the diverged path `p` grows like a power of `s = 1 − t` towards the target:
/// the valuation `v = −Re(s ẋ_i / x_i)` of its largest coordinate (growth rate
/// `ẋ_i / x_i`) lies in `[−MAX_EARLY_VALUATION, −threshold]`.
pub(super) fn power_of_s_growth(p: &PathResult, growth_rate: C64, threshold: f64) -> bool {
    let s = 1.0 - p.last_t.re;
    let v = -(growth_rate * s).re;
    s > 0.0 && (-MAX_EARLY_VALUATION..=-threshold).contains(&v)
}

/// The growth rate of `p`'s largest coordinate at its last point.
pub(super) fn last_growth_rate<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    p: &PathResult,
) -> Option<C64> {
    growth_rate(tracker, &p.solution, p.last_t, largest(&p.solution)?)
}

/// Tracks the path from `start` that diverged near the pole `t_p` just ahead of it
/// (or, without one, at its last point) around it: along
/// `t_c − r → t_c ± i r → t_c + r` with `t_c = Re t_p` and the radii `r` of
/// [`ARC_FACTORS`] (clamped to `[MIN_ARC, MAX_ARC]` and to the route
/// `[0, 1 − endgame_start]`), then on to the endgame at `t = 1`
/// ([`Tracker::track_via`]). Between the real segment and the arc on its side of the
/// pole there is, for a small enough arc, no singularity, so that arc continues the
/// same path; the arc on the other side does too unless the pole is a branch point.
/// Hence, at the first radius where
/// - both arcs reach the same finite point, or both end at infinity by the endgame:
///   that is the path's endpoint (a repeat of another path's root is caught by the
///   duplicate test of `solve`);
/// - they disagree: an arc's finite endpoint that no other path reached (`is_new`),
///   the one on the real segment's side (away from `Im t_p`) first — every endpoint
///   of any route is a root of the target, and one reached by no other path is not
///   counted twice (as in the curve pipeline's arcs, `pipeline::sweep::retry`).
///
/// Otherwise the path stays failed: a point at infinity is never taken from an arc
/// whose homotopy class is in doubt.
///
/// `None` when no arc fits (breakpoints nearby) or the path is not rescued.
pub(super) fn around_the_pole<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    homotopy: &H,
    start: &[C64],
    p: &PathResult,
    t_p: Option<C64>,
    same_point: impl Fn(&[C64], &[C64]) -> bool,
    is_new: impl Fn(&[C64]) -> bool,
) -> Option<PathResult> {
    let (t_c, distance) = match t_p {
        Some(t_p) => (t_p.re, (t_p - p.last_t).norm()),
        None => (p.last_t.re, 0.0),
    };
    let end = 1.0 - tracker.options().endgame.endgame_start;
    // The real segment passes the pole on the side opposite to Im t_p.
    let near_side = match t_p {
        Some(t_p) if t_p.im > 0.0 => -1.0,
        _ => 1.0,
    };
    let breakpoints = homotopy.breakpoints();
    let mut tried = Vec::with_capacity(ARC_FACTORS.len());
    for factor in ARC_FACTORS {
        let r = (factor * distance)
            .clamp(MIN_ARC, MAX_ARC)
            .min(0.9 * t_c)
            .min(end - t_c);
        // Without a located pole (or after clamping) the radii coincide: one try each.
        if r.is_nan() || r <= 0.0 || t_c - r <= 0.0 || tried.contains(&r) {
            continue;
        }
        tried.push(r);
        if breakpoints.iter().any(|b| (b - t_c).abs() <= r) {
            continue;
        }
        let mut arc = |side: f64| {
            let via = [
                C64::new(t_c - r, 0.0),
                C64::new(t_c, side * r),
                C64::new(t_c + r, 0.0),
            ];
            tracker.track_via(start, &via, p.path_index)
        };
        let near = arc(near_side);
        let far = arc(-near_side);
        let agree = match (near.status, far.status) {
            (PathStatus::AtInfinity, PathStatus::AtInfinity) => true,
            (a, b) if a.is_finite() && b.is_finite() => same_point(&near.solution, &far.solution),
            _ => false,
        };
        if agree {
            return Some(near);
        }
        if let Some(new) = [near, far]
            .into_iter()
            .find(|a| a.status.is_finite() && is_new(&a.solution))
        {
            return Some(new);
        }
    }
    None
}

/// The diverged paths of a `solve` run (status `Failed(DivergedBeforeEndgame)` after
/// the re-runs), in place: at infinity if no pole is located just ahead of them
/// ([`pole_ahead`]) and they grow like a power of `s` ([`power_of_s_growth`]), else
/// tracked around the point where they diverged ([`around_the_pole`], "new" meaning
/// no finite endpoint of the other paths) and replaced by the result if rescued,
/// else left failed. Returns the number of paths tracked
/// around a pole.
pub(super) fn settle_diverged_paths<H, S>(
    homotopy: &H,
    paths: &mut [PathResult],
    start: S,
    options: &TrackerOptions,
    same_point: impl Fn(&[C64], &[C64]) -> bool + Copy + Sync,
) -> usize
where
    H: Homotopy + ?Sized,
    S: Fn(usize, &mut [C64]) + Sync,
{
    let diverged = PathStatus::Failed(FailureReason::DivergedBeforeEndgame);
    if !paths.iter().any(|p| p.status == diverged) {
        return 0;
    }
    let n = homotopy.dimension();
    let known: Vec<Vec<C64>> = paths
        .iter()
        .filter(|p| p.status.is_finite())
        .map(|p| p.solution.clone())
        .collect();
    let is_new = |x: &[C64]| !known.iter().any(|y| same_point(x, y));
    paths
        .par_iter_mut()
        .filter(|p| p.status == diverged)
        .map_init(
            || {
                (
                    Tracker::new(homotopy, options.clone()),
                    vec![C64::new(0.0, 0.0); n],
                )
            },
            |(tracker, x), p| {
                start(p.path_index, x);
                let t_p = locate_singularity(tracker, x, p);
                let g = last_growth_rate(tracker, p);
                let ahead = t_p.is_some_and(|t_p| pole_ahead(p, t_p));
                let threshold = options.endgame.valuation_threshold;
                if !ahead && g.is_some_and(|g| power_of_s_growth(p, g, threshold)) {
                    p.status = PathStatus::AtInfinity;
                    return 0;
                }
                let pole = t_p.filter(|_| ahead);
                if let Some(around) =
                    around_the_pole(tracker, homotopy, x, p, pole, same_point, is_new)
                {
                    *p = around;
                }
                1
            },
        )
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::tracker::tests::{pole, reciprocal_family};

    /// Divergence at `‖x‖ > 10`, steps of at most 0.01, endgame from `s = 0.01`.
    fn options() -> TrackerOptions {
        let mut options = TrackerOptions::default();
        options.step.initial_step = 0.01;
        options.step.max_step = 0.01;
        options.endgame.at_infinity_norm = 10.0;
        options.endgame.endgame_start = 0.01;
        options.endgame.growth_before_divergence = true;
        options
    }

    /// The path `x(t) = 1/(p − t)` of `(p − t)x − 1` from `x(0) = 1/p`, tracked to
    /// `t = 1`: it must diverge before the endgame zone, with its singularity located
    /// within 1e-6 of `p`. Returns the path, the located `t_p` and the growth rate.
    fn diverged(p: f64) -> (PathResult, C64, Option<C64>) {
        let system = reciprocal_family();
        let homotopy = pole(&system, p);
        let mut tracker = Tracker::new(&homotopy, options());
        let start = [C64::new(1.0 / p, 0.0)];
        let result = tracker.track(&start, 0);
        let t_p = locate_singularity(&mut tracker, &start, &result);
        let g = last_growth_rate(&mut tracker, &result);
        assert_eq!(
            result.status,
            PathStatus::Failed(FailureReason::DivergedBeforeEndgame)
        );
        let t_p = t_p.expect("the singularity is located");
        assert!((t_p - p).norm() < 1e-6, "t_p = {t_p}");
        (result, t_p, g)
    }

    /// A simple pole halfway is located where it is, just ahead of the point where the
    /// path diverged: never at infinity.
    #[test]
    fn a_pole_halfway_is_located_ahead_of_the_path() {
        let (result, t_p, _) = diverged(0.5);
        assert!(pole_ahead(&result, t_p));
    }

    /// `1/(1 − t)` diverges before the endgame zone and grows like `s^{−1}`: its
    /// singularity is the target and it is at infinity.
    #[test]
    fn growth_like_a_power_of_s_is_located_at_the_target() {
        let (result, t_p, g) = diverged(1.0);
        assert!(!pole_ahead(&result, t_p));
        assert!(power_of_s_growth(&result, g.unwrap(), 0.1));
    }

    /// The path past the pole at `t = ½` is rescued along the arcs to its finite
    /// endpoint `x(1) = 1/(½ − 1) = −2`.
    #[test]
    fn a_path_past_a_pole_is_tracked_around_it_to_its_endpoint() {
        let system = reciprocal_family();
        let homotopy = pole(&system, 0.5);
        let start = |_: usize, x: &mut [C64]| x[0] = C64::new(2.0, 0.0);
        let mut paths = vec![Tracker::new(&homotopy, options()).track(&[C64::new(2.0, 0.0)], 0)];
        let around = settle_diverged_paths(&homotopy, &mut paths, start, &options(), |a, b| {
            (a[0] - b[0]).norm() < 1e-8
        });
        assert_eq!(around, 1);
        assert_eq!(paths[0].status, PathStatus::Nonsingular, "{:?}", paths[0]);
        assert!(
            (paths[0].solution[0] + 2.0).norm() < 1e-10,
            "{:?}",
            paths[0]
        );
    }
}

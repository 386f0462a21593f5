//! Newton jumps between consecutive poses of a chain, for any family: each critical
//! point of the latest complete sets extrapolated to the next pose and corrected by
//! Newton's method there ([`jump_set`]), one per complex conjugate pair; Newton
//! sub-steps along the straight real route and pose-to-pose paths for what that
//! leaves unaccounted for; the set kept only when it is complete.

use super::{crossings, same_endpoint, simple_endpoint};
use crate::C64;
use crate::homotopy::{Homotopy, PathResult, Tracker, TrackerOptions};
use rayon::prelude::*;

/// A known value of one critical point along the motion: `(s, x)`, `s` in units of
/// the pose spacing from the latest solved pose (`0`; earlier poses at `−1`, `−2`,
/// sub-steps towards the next pose at `0 < s < 1`).
pub(crate) type Node<'a> = (f64, &'a [C64]);

/// The polynomial through the latest (up to three) nodes (`nodes[0]` the latest), at
/// `s` (Lagrange form); for nodes at `0, −1, −2` and `s = 1`: `3x₀ − 3x₁ + x₂`.
pub(crate) fn extrapolate(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
    let nodes = &nodes[..nodes.len().min(3)];
    for o in out.iter_mut() {
        *o = C64::new(0.0, 0.0);
    }
    for (k, &(sk, xk)) in nodes.iter().enumerate() {
        let weight = nodes
            .iter()
            .enumerate()
            .filter(|&(l, _)| l != k)
            .fold(1.0, |w, (_, &(sl, _))| w * (s - sl) / (sk - sl));
        for (o, x) in out.iter_mut().zip(xk) {
            *o += x * weight;
        }
    }
}

/// Per coordinate, the Möbius function `(p + q s)/(1 + r s)` through the latest three
/// nodes (`p + q s_k − r s_k x_k = x_k`, Cramer's rule), at `s`. Exact for a
/// coordinate with a simple pole in τ, like the far-out critical points that pass near
/// infinity between poses; the polynomial ([`extrapolate`]) where the fit is
/// degenerate.
pub(crate) fn extrapolate_moebius(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
    let [(s0, x0), (s1, x1), (s2, x2), ..] = *nodes else {
        return extrapolate(nodes, s, out);
    };
    extrapolate(nodes, s, out);
    let one = C64::new(1.0, 0.0);
    let det3 = |m: [[C64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    for (i, o) in out.iter_mut().enumerate() {
        let rows = [(s0, x0[i]), (s1, x1[i]), (s2, x2[i])];
        let matrix = rows.map(|(sk, xk)| [one, C64::new(sk, 0.0), -xk * sk]);
        let rhs = rows.map(|(_, xk)| xk);
        let det = det3(matrix);
        let column = |c: usize| {
            let mut m = matrix;
            for (row, value) in m.iter_mut().zip(rhs) {
                row[c] = value;
            }
            det3(m) / det
        };
        let (p, q, r) = (column(0), column(1), column(2));
        let value = (p + q * s) / (one + r * s);
        if value.re.is_finite() && value.im.is_finite() {
            *o = value;
        }
    }
}

/// A prediction of a critical point at `s` from its known values ([`Node`]).
pub(crate) type Predictor = fn(&[Node<'_>], f64, &mut [C64]);

/// The predictions [`jump_problem`] tries in turn, given `depth` known values: the
/// polynomial extrapolation, then the Möbius one, then the latest value. (Measured on
/// the built-in example: the Möbius and constant retries cut the critical points
/// left to pose-to-pose paths from 1,252 to 841.)
pub(crate) fn predictors(depth: usize) -> &'static [Predictor] {
    fn latest(nodes: &[Node<'_>], s: f64, out: &mut [C64]) {
        extrapolate(&nodes[..1], s, out);
    }
    match depth {
        0 | 1 => &[extrapolate],
        2 => &[extrapolate, latest],
        _ => &[extrapolate, extrapolate_moebius, latest],
    }
}

/// Newton's method at `s` ([`Tracker::correct_at`]) from each prediction in turn;
/// the first limit that is a simple endpoint, else the last attempt.
pub(crate) fn correct_predicted<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    nodes: &[Node<'_>],
    s: f64,
    prediction: &mut [C64],
    path_index: usize,
) -> PathResult {
    let mut result = None;
    for predict in predictors(nodes.len()) {
        predict(nodes, s, prediction);
        let limit = tracker.correct_at(prediction, s, path_index);
        let simple = simple_endpoint(&limit);
        result = Some(limit);
        if simple {
            break;
        }
    }
    result.expect("at least one predictor")
}

/// Smallest sub-step (in pose spacings) of [`substep_to_pose`].
pub(crate) const MIN_SUBSTEP: f64 = 1.0 / 16.0;

/// Newton continuation of one critical point from the latest pose (`s = 0`) to the
/// next (`s = 1`) along the straight real route (`homotopy` at `t = s`): sub-steps
/// from `½` down to [`MIN_SUBSTEP`] pose spacings, each predicted from the latest
/// three known values ([`correct_predicted`]), halved when Newton's method fails,
/// doubled when it succeeds. `None` if a sub-step would fall below the minimum.
pub(crate) fn substep_to_pose<H: Homotopy + ?Sized>(
    tracker: &mut Tracker<'_, H>,
    history: &[&[C64]],
    path_index: usize,
) -> Option<PathResult> {
    let mut nodes: Vec<(f64, Vec<C64>)> = history
        .iter()
        .enumerate()
        .map(|(k, x)| (-(k as f64), x.to_vec()))
        .collect();
    let mut prediction = vec![C64::new(0.0, 0.0); history[0].len()];
    let (mut s, mut h): (f64, f64) = (0.0, 0.5);
    loop {
        let target = (s + h).min(1.0);
        let known: Vec<Node<'_>> = nodes.iter().map(|(s, x)| (*s, x.as_slice())).collect();
        let result = correct_predicted(tracker, &known, target, &mut prediction, path_index);
        if simple_endpoint(&result) {
            if target >= 1.0 {
                return Some(result);
            }
            nodes.insert(0, (target, result.solution));
            nodes.truncate(3);
            s = target;
            h *= 2.0;
        } else {
            h *= 0.5;
            if h < MIN_SUBSTEP {
                return None;
            }
        }
    }
}

/// For every point of a solution set at a real parameter, the index of its complex
/// conjugate in the set (`conjugate`; itself for a real point), or `None` if the
/// conjugate is not in the set or the pairing is not mutual.
pub(crate) fn conjugate_partners(
    conjugate: &(dyn Fn(&[C64]) -> Vec<C64> + Sync),
    set: &[Vec<C64>],
) -> Vec<Option<usize>> {
    let found: Vec<Option<usize>> = set
        .iter()
        .map(|x| {
            let conjugate = conjugate(x);
            set.iter().position(|y| same_endpoint(y, &conjugate))
        })
        .collect();
    (0..set.len())
        .map(|i| found[i].filter(|&j| found[j] == Some(i)))
        .collect()
}

/// Known values kept per critical point for [`extrapolate`]: the latest three poses.
pub(crate) const JUMP_HISTORY: usize = 3;

/// The homotopies of one Newton jump from the latest pose (`t = 0`) to the next
/// (`t = 1`), the tracker options and the conjugation of the family.
pub(crate) struct JumpRoutes<'a, H: ?Sized, S: ?Sized> {
    /// The pose-to-pose route (through a complex midpoint): Newton's method at its
    /// end, and the paths for what Newton's method leaves.
    pub neighbour: &'a H,
    /// The straight real route, for Newton sub-steps ([`substep_to_pose`]).
    pub straight: &'a S,
    /// Tracker options of the corrections and paths.
    pub tracker: &'a TrackerOptions,
    /// Complex conjugation of a solution (the poses are real).
    pub conjugate: &'a (dyn Fn(&[C64]) -> Vec<C64> + Sync),
}

/// One sub-problem at the next pose from the complete solution sets of the preceding
/// poses (`history`, latest first, each in the same order) without tracking: every
/// critical point is extrapolated ([`extrapolate`]) and corrected by Newton's method
/// at the pose ([`Tracker::correct_at`]). Of each complex conjugate pair only one is
/// continued and the other is its conjugate ([`conjugate_partners`]; the poses are
/// real). Which critical point a Newton sequence converges to is not controlled, but
/// the set is checked: the number of nonsingular solutions is at most the generic
/// one, so `expected` distinct nonsingular limits are all the critical points. Limits
/// that fail or coincide are continued in Newton sub-steps along the straight real
/// route, else re-tracked from the latest pose along the neighbour route. Returns the
/// set (in the order of `history`) and the number of corrections and paths, `None`
/// when the set is still incomplete.
pub(crate) fn jump_set<H, S>(
    routes: JumpRoutes<'_, H, S>,
    history: &[&[Vec<C64>]],
    expected: usize,
) -> Option<(Vec<Vec<C64>>, usize)>
where
    H: Homotopy + Sync + ?Sized,
    S: Homotopy + Sync + ?Sized,
{
    let JumpRoutes {
        neighbour: homotopy,
        straight,
        tracker: options,
        conjugate,
    } = routes;
    let latest = *history.first()?;
    // At a real pose the critical points come in complex conjugate pairs (and real
    // ones): only one of each pair is continued, its partner is the conjugate.
    let partner = conjugate_partners(conjugate, latest);
    let representatives: Vec<usize> = (0..latest.len())
        .filter(|&i| partner[i].is_none_or(|j| j >= i))
        .collect();
    const CHUNK: usize = 16;
    let mut reps: Vec<PathResult> = representatives
        .par_chunks(CHUNK)
        .map(|chunk| {
            let mut tracker = Tracker::new(homotopy, options.clone());
            let mut prediction = vec![C64::new(0.0, 0.0); homotopy.dimension()];
            chunk
                .iter()
                .map(|&i| {
                    // At most JUMP_HISTORY known values, on the stack.
                    let mut nodes: [Node<'_>; JUMP_HISTORY] = [(0.0, &[]); JUMP_HISTORY];
                    let depth = history.len().min(JUMP_HISTORY);
                    for (k, (node, set)) in nodes.iter_mut().zip(history).enumerate() {
                        *node = (-(k as f64), set[i].as_slice());
                    }
                    let nodes = &nodes[..depth];
                    correct_predicted(&mut tracker, nodes, 1.0, &mut prediction, i)
                })
                .collect::<Vec<_>>()
        })
        .flatten()
        .collect();
    let mut tracked = reps.len();
    // Newton limits that failed or coincide: continued in sub-steps along the straight
    // real route, else tracked (short paths through the complex midpoint).
    let redo = |which: &[usize], substeps: bool| -> Vec<PathResult> {
        which
            .par_chunks(4)
            .map(|chunk| {
                let mut newton = Tracker::new(straight, options.clone());
                let mut paths = Tracker::new(homotopy, options.clone());
                chunk
                    .iter()
                    .map(|&i| {
                        let known: Vec<&[C64]> =
                            history.iter().map(|set| set[i].as_slice()).collect();
                        substeps
                            .then(|| substep_to_pose(&mut newton, &known, i))
                            .flatten()
                            .unwrap_or_else(|| paths.track_between(&latest[i], 0.0, 1.0, i))
                    })
                    .collect::<Vec<_>>()
            })
            .flatten()
            .collect()
    };
    let crossed = crossings(&reps);
    let which: Vec<usize> = (0..reps.len())
        .filter(|&r| !simple_endpoint(&reps[r]) || crossed[r])
        .collect();
    let indices: Vec<usize> = which.iter().map(|&r| reps[r].path_index).collect();
    for (r, result) in which.iter().zip(redo(&indices, true)) {
        reps[*r] = result;
    }
    tracked += which.len();
    let mut paths: Vec<Option<PathResult>> = vec![None; latest.len()];
    for result in reps {
        let i = result.path_index;
        if let Some(j) = partner[i].filter(|&j| j != i) {
            let mut conjugate_result = result.clone();
            conjugate_result.solution = conjugate(&result.solution);
            conjugate_result.path_index = j;
            paths[j] = Some(conjugate_result);
        }
        paths[i] = Some(result);
    }
    let mut paths = paths.into_iter().collect::<Option<Vec<PathResult>>>()?;
    // A pair whose continuation became real (two real critical points), or a path
    // crossing between pairs: those critical points are tracked one by one, by paths
    // through the complex midpoint only. Newton sub-steps along the real route cannot
    // separate them: the iterates from a point and from its conjugate stay conjugate,
    // so a pair that turned real between the poses lands twice on one real point.
    let crossed = crossings(&paths);
    let which: Vec<usize> = (0..paths.len())
        .filter(|&i| !simple_endpoint(&paths[i]) || crossed[i])
        .collect();
    for (&i, result) in which.iter().zip(redo(&which, false)) {
        paths[i] = result;
    }
    tracked += which.len();
    let complete = paths.iter().all(simple_endpoint)
        && !crossings(&paths).contains(&true)
        && paths.len() == expected;
    complete.then(|| (paths.into_iter().map(|p| p.solution).collect(), tracked))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The predictors are exact on their model functions at any nodes: a quadratic
    /// per coordinate for [`extrapolate`], a Möbius function (a simple pole at
    /// `s = 2.5` and `s = −4`) for [`extrapolate_moebius`], which the quadratic misses.
    #[test]
    fn predictors_reproduce_their_model_functions() {
        let quadratic = |s: f64| {
            [
                C64::new(1.0 - 2.0 * s + 0.5 * s * s, s),
                C64::new(3.0, -s * s),
            ]
        };
        let moebius = |s: f64| {
            [
                C64::new(2.0 + 3.0 * s, 1.0) / (1.0 - 0.4 * s),
                C64::new(-1.0, 0.5 * s) / C64::new(1.0 + 0.25 * s, 0.1 * s),
            ]
        };
        // The prediction at `s` from the model's values at the nodes `at`.
        let predict = |predictor: Predictor, model: &dyn Fn(f64) -> [C64; 2], at: [f64; 3], s| {
            let owned: Vec<(f64, Vec<C64>)> = at.iter().map(|&t| (t, model(t).to_vec())).collect();
            let nodes: Vec<Node<'_>> = owned.iter().map(|(t, v)| (*t, &v[..])).collect();
            let mut out = [C64::new(0.0, 0.0); 2];
            predictor(&nodes, s, &mut out);
            out
        };
        let error = |out: [C64; 2], exact: [C64; 2]| {
            (out[0] - exact[0]).norm().max((out[1] - exact[1]).norm())
        };
        for at in [[0.0, -1.0, -2.0], [0.5, 0.0, -1.0], [0.75, 0.5, 0.0]] {
            for s in [1.0, 0.875] {
                let out = predict(extrapolate, &quadratic, at, s);
                assert!(error(out, quadratic(s)) < 1e-12, "{out:?} at {s}");
                let out = predict(extrapolate_moebius, &moebius, at, s);
                assert!(error(out, moebius(s)) < 1e-10, "{out:?} at {s}");
                let out = predict(extrapolate, &moebius, at, s);
                assert!(
                    (out[0] - moebius(s)[0]).norm() > 1e-3,
                    "the quadratic should miss the pole"
                );
            }
        }
    }
}

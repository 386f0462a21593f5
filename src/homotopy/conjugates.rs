//! Completion of a run's roots by complex conjugation.
//!
//! The complex conjugate `x̄` of a root `x` of a system with real coefficients is a
//! root too, with the same condition number. A run whose paths reached `x` but not
//! `x̄` lost a path on the way to `x̄`: one of its paths that are not accounted for
//! (failed, jumped onto another path's root, or sent to infinity by the norm cap alone
//! without confirmation in a projective chart). The start system's root count bounds
//! the number of isolated roots (Bézout, multihomogeneous Bézout, or the BKK bound of
//! a polyhedral start system: Bernstein, "The number of roots of a system of
//! equations", 1975), and every isolated root is the endpoint of some path, so `x̄`
//! belongs to such a path; which one cannot be told, and none of them is needed to
//! report `x̄`. Each missing conjugate that Newton's method confirms as a nonsingular
//! root in place is therefore recorded at one of those paths, which is then accounted
//! for (the recorded steps remain those of the lost path).
//!
//! No assumption on the coefficients is made: for a system that is not real, `x̄` is
//! no root, Newton's method moves away from it or does not converge, and nothing is
//! added.

use super::homotopies::Homotopy;
use super::newton::max_norm;
use super::refine::{contains_point, newton_refine, same_point};
use super::solve::TargetSystem;
use super::tracker::{PathResult, PathStatus};
use crate::C64;

/// Relative Newton tolerance of the check of a conjugate.
const CONJUGATE_NEWTON_TOLERANCE: f64 = 1e-13;

/// Newton iterations of the check: from a root's conjugate, which is as accurate as
/// the root, quadratic convergence needs one or two.
const CONJUGATE_NEWTON_ITERATIONS: usize = 8;

/// Largest distance, relative to `1 + ‖x̄‖∞`, by which Newton's method may move a
/// conjugate `x̄` and still confirm it as a root in place: `x` is accurate to about
/// `κ·ε` relative (κ ≤ 10¹⁰ for a nonsingular root, so 10⁻⁶ at worst), while a
/// conjugate that is no root converges, if at all, to a root at an O(1) distance.
const CONJUGATE_MOVE: f64 = 1e-5;

/// Which roots completion added, and where.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ConjugateCompletion {
    /// The paths that now hold a conjugate root (from `doubtful`, in its order).
    pub paths: Vec<usize>,
}

/// For each nonsingular endpoint of `paths` that is not real (some
/// `|Im x_i| > real_tolerance · (1 + ‖x‖∞)`) and whose conjugate no finite endpoint
/// matches (`cluster_tolerance`), Newton's method on `H(·, 1)` from the conjugate; a
/// nonsingular root (condition below `max_condition`) within [`CONJUGATE_MOVE`] of the
/// conjugate is recorded at the next path of `doubtful` (paths not accounted for),
/// until they run out. See the module documentation.
pub(crate) fn complete_conjugate_roots<H: Homotopy + ?Sized>(
    homotopy: &H,
    paths: &mut [PathResult],
    doubtful: &[usize],
    (real_tolerance, cluster_tolerance, max_condition): (f64, f64, f64),
) -> ConjugateCompletion {
    let mut completion = ConjugateCompletion::default();
    if doubtful.is_empty() {
        return completion;
    }
    let target = TargetSystem { homotopy };
    let mut known: Vec<Vec<C64>> = paths
        .iter()
        .filter(|p| p.status.is_finite())
        .map(|p| p.solution.clone())
        .collect();
    let roots: Vec<Vec<C64>> = paths
        .iter()
        .filter(|p| p.status == PathStatus::Nonsingular && !p.is_real(real_tolerance))
        .map(|p| p.solution.clone())
        .collect();
    for root in roots {
        let Some(&index) = doubtful.get(completion.paths.len()) else {
            break;
        };
        let conjugate: Vec<C64> = root.iter().map(|v| v.conj()).collect();
        if contains_point(&known, &conjugate, cluster_tolerance) {
            continue;
        }
        let refined = newton_refine(
            &target,
            &conjugate,
            &[],
            CONJUGATE_NEWTON_TOLERANCE,
            CONJUGATE_NEWTON_ITERATIONS,
        );
        let in_place = same_point(&refined.point, &conjugate, CONJUGATE_MOVE)
            && max_norm(&refined.point).is_finite();
        if !refined.is_nonsingular(max_condition)
            || !in_place
            || contains_point(&known, &refined.point, cluster_tolerance)
        {
            continue;
        }
        let path = &mut paths[index];
        path.record_nonsingular_root(&refined);
        path.multiplicity = 1;
        path.last_t = C64::new(1.0, 0.0);
        known.push(refined.point);
        completion.paths.push(index);
    }
    completion
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::test_support::{path_result as path, read_xy as read};
    use crate::homotopy::{FailureReason, StraightLineHomotopy};

    fn c(re: f64, im: f64) -> C64 {
        C64::new(re, im)
    }

    /// A run of `target` (from a start system in the same unknowns) whose path 0 reached
    /// `(x, 2)` and whose path 1 failed.
    fn completed(
        target: &str,
        x: C64,
        doubtful: &[usize],
    ) -> (Vec<PathResult>, ConjugateCompletion) {
        let start = read("f = x^2 - 1;\ng = y - 1;");
        let target = read(target);
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], c(0.6, 0.8));
        let mut paths = vec![
            path(0, PathStatus::Nonsingular, vec![x, c(2.0, 0.0)]),
            path(
                1,
                PathStatus::Failed(FailureReason::TooManySteps),
                vec![c(9.0, 9.0); 2],
            ),
        ];
        let completion =
            complete_conjugate_roots(&homotopy, &mut paths, doubtful, (1e-8, 1e-6, 1e10));
        (paths, completion)
    }

    #[test]
    fn a_missing_conjugate_of_a_real_system_is_recorded_at_a_lost_path() {
        let (paths, completion) = completed("f = x^2 + 1;\ng = y - 2;", c(0.0, 1.0), &[1]);
        assert_eq!(completion.paths, vec![1]);
        assert_eq!(paths[1].status, PathStatus::Nonsingular);
        assert!((paths[1].solution[0] - c(0.0, -1.0)).norm() < 1e-12);
        assert!((paths[1].solution[1] - c(2.0, 0.0)).norm() < 1e-12);
        assert_eq!(paths[0].solution[0], c(0.0, 1.0));
    }

    #[test]
    fn nothing_is_added_without_a_lost_path_or_for_a_complex_system() {
        let (paths, completion) = completed("f = x^2 + 1;\ng = y - 2;", c(0.0, 1.0), &[]);
        assert!(completion.paths.is_empty());
        assert_eq!(
            paths[1].status,
            PathStatus::Failed(FailureReason::TooManySteps)
        );
        // Roots 1 + i and 1 − 0.9i: Newton's method from the conjugate 1 − i of the first
        // converges to the second, 0.1 away, which is no conjugate.
        let system = "f = x^2 - (2 + 0.1*I)*x + 1.9 + 0.1*I;\ng = y - 2;";
        let (paths, completion) = completed(system, c(1.0, 1.0), &[1]);
        assert!(completion.paths.is_empty());
        assert_eq!(
            paths[1].status,
            PathStatus::Failed(FailureReason::TooManySteps)
        );
    }

    #[test]
    fn a_real_root_or_one_whose_conjugate_is_known_adds_nothing() {
        let (_, completion) = completed("f = x^2 - 4;\ng = y - 2;", c(2.0, 0.0), &[1]);
        assert!(completion.paths.is_empty());
        let start = read("f = x^2 - 1;\ng = y - 1;");
        let target = read("f = x^2 + 1;\ng = y - 2;");
        let homotopy = StraightLineHomotopy::new(&start, &target, vec![], c(0.6, 0.8));
        let mut paths = vec![
            path(0, PathStatus::Nonsingular, vec![c(0.0, 1.0), c(2.0, 0.0)]),
            path(1, PathStatus::Nonsingular, vec![c(0.0, -1.0), c(2.0, 0.0)]),
            path(
                2,
                PathStatus::Failed(FailureReason::TooManySteps),
                vec![c(9.0, 9.0); 2],
            ),
        ];
        let completion = complete_conjugate_roots(&homotopy, &mut paths, &[2], (1e-8, 1e-6, 1e10));
        assert!(completion.paths.is_empty());
    }
}

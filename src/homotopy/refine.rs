//! Newton refinement of an approximate root against the target system, and the test
//! that decides whether two approximate roots are the same root.
//!
//! Newton's method `x ← x − J(x)⁻¹ F(x)` with the residual `F(x)` evaluated in
//! double-double arithmetic (so the limiting accuracy is `κ·ε·‖x‖` rather than the
//! rounding error of `F`), stopped when the correction falls below
//! `tolerance · (1 + ‖x‖∞)`. A root is *nonsingular* when Newton converges
//! quadratically (each correction at most the square of the previous one, up to the
//! noise floor) to a point whose Jacobian has a condition number below a threshold:
//! Smale's α-theory (Blum, Cucker, Shub, Smale, "Complexity and Real Computation",
//! 1998) guarantees such a point is in the quadratic basin of exactly one root.
//!
//! Two approximate roots are the same root when Newton started from each converges to
//! the same limit ("Newton-cluster test"), compared at an accuracy: a fixed distance
//! tolerance either merges distinct close roots or splits one ill-conditioned root in
//! two. Two accuracies serve: that of the problem, `10·κ·ε` at condition κ (how far a
//! root moves when the coefficients are rounded, [`accuracy_at_condition`]), for
//! systems given to rounding; and that of the limit, for a system that is exactly
//! what it is (a random start system): a converged limit is accurate to about its last
//! correction (in the quadratic regime the error after a correction Δ is O(‖Δ‖²)),
//! [`Refinement::accuracy`].

use super::linalg::LuWorkspace;
use super::newton::{NewtonBuffers, NewtonOptions, max_norm, newton};
use crate::C64;
use crate::system::Evaluator;

/// Outcome of [`newton_refine`].
#[derive(Clone, Debug, PartialEq)]
pub struct Refinement {
    /// The last iterate.
    pub point: Vec<C64>,
    /// Whether the last correction fell below the tolerance.
    pub converged: bool,
    /// Size of the last correction, relative to `1 + ‖x‖∞`.
    pub last_correction: f64,
    /// `‖F(x)‖∞` at the last iterate (double-double evaluation, rounded).
    pub residual: f64,
    /// 1-norm condition estimate of `∂F/∂x` at the last iterate (∞ if singular).
    pub condition: f64,
    /// Newton iterations done.
    pub iterations: usize,
}

impl Refinement {
    /// Converged to a root with a condition number below `max_condition`.
    pub fn is_nonsingular(&self, max_condition: f64) -> bool {
        self.converged && self.condition < max_condition
    }

    /// Accuracy of the last iterate relative to `1 + ‖x‖∞`, for [`group_roots`]: ten
    /// times the last correction (plus rounding) when Newton converged, else
    /// [`accuracy_at_condition`] of its condition number.
    pub fn accuracy(&self) -> f64 {
        if self.converged {
            10.0 * self.last_correction + 4.0 * f64::EPSILON
        } else {
            accuracy_at_condition(self.condition)
        }
    }
}

/// Accuracy `10·κ·ε` (κ capped at 10¹²) relative to `1 + ‖x‖∞` of an approximate root
/// at condition number `κ = condition` that Newton's method has not been seen to
/// converge to.
pub fn accuracy_at_condition(condition: f64) -> f64 {
    10.0 * condition.min(1e12) * f64::EPSILON
}

/// Refines `x` by at most `max_iterations` Newton steps on `F(·; p) = 0`
/// ([`super::newton::newton`]); stops when a correction is below
/// `tolerance · (1 + ‖x‖∞)`, or when the corrections stop decreasing (no
/// convergence); then evaluates the residual and condition at the last iterate.
pub fn newton_refine<F: Evaluator + ?Sized>(
    system: &F,
    x: &[C64],
    parameters: &[C64],
    tolerance: f64,
    max_iterations: usize,
) -> Refinement {
    let n = system.num_variables();
    let zero = C64::new(0.0, 0.0);
    let mut point = x.to_vec();
    let mut work = vec![zero; system.workspace_len()];
    let mut f = vec![zero; system.num_equations()];
    let mut jac = vec![zero; system.num_equations() * n];
    let mut lu = LuWorkspace::new(n);
    let options = NewtonOptions {
        tolerance,
        max_iterations,
        stop_when_growing: true,
    };
    let buffers = NewtonBuffers {
        work: &mut work,
        f: &mut f,
        jac: &mut jac,
        lu: &mut lu,
    };
    let outcome = newton(system, &mut point, parameters, &options, buffers);
    let mut result = Refinement {
        point: Vec::new(),
        converged: outcome.converged(),
        last_correction: outcome.last_correction,
        residual: f64::INFINITY,
        condition: f64::INFINITY,
        iterations: outcome.iterations,
    };
    system.evaluate_with_jacobian(&point, parameters, &mut work, &mut f, &mut jac);
    system.evaluate_extended(&point, parameters, &mut work, &mut f);
    result.residual = max_norm(&f);
    result.condition = if lu.factor(&jac) {
        lu.condition_estimate()
    } else {
        f64::INFINITY
    };
    if !result.residual.is_finite() {
        result.converged = false;
    }
    result.point = point;
    result
}

/// Whether two refined roots `a` and `b` (limits of [`newton_refine`]) are the same
/// root: their distance is below `(tolerance + accuracy) · (1 + ‖a‖∞)`, `accuracy` the
/// larger relative accuracy of the two ([`accuracy_at_condition`] or
/// [`Refinement::accuracy`]).
pub fn same_root(a: &[C64], b: &[C64], accuracy: f64, tolerance: f64) -> bool {
    let scale = 1.0 + max_norm(a).max(max_norm(b));
    let bound = tolerance + accuracy;
    a.iter()
        .zip(b)
        .all(|(u, v)| (u - v).norm() <= bound * scale)
}

/// Whether `b` is within `tolerance · (1 + ‖a‖∞)` of `a` in every coordinate: the
/// fixed relative distance test for points known far more accurately than they are
/// apart (the Newton-limit test [`same_root`] is for points of unknown conditioning).
pub fn same_point(a: &[C64], b: &[C64], tolerance: f64) -> bool {
    // Squared moduli: this runs for every pair of endpoints of every run.
    let bound = (tolerance * (1.0 + max_norm(a))).powi(2);
    a.iter().zip(b).all(|(u, v)| (u - v).norm_sqr() <= bound)
}

/// Whether some point of `set` is the [`same_point`] as `x` (distance relative to `x`).
pub fn contains_point(set: &[Vec<C64>], x: &[C64], tolerance: f64) -> bool {
    set.iter().any(|y| same_point(x, y, tolerance))
}

/// The distinct nonsingular roots among approximate solutions `points` of
/// `F(·; p) = 0` (no parameters): each refined by [`newton_refine`] (corrections below
/// 1e-13 relative, at most 40 steps), kept if its condition number is below 1e11, and
/// grouped by [`group_roots`] (tolerance 1e-10, at the accuracy of the problem
/// [`accuracy_at_condition`]); one representative per root, in the
/// order of `points`. The independent count the demo-suite tests compare with.
pub fn distinct_nonsingular_roots<F: Evaluator + ?Sized>(
    system: &F,
    points: &[Vec<C64>],
) -> Vec<Vec<C64>> {
    let refined: Vec<(Vec<C64>, f64)> = points
        .iter()
        .map(|x| newton_refine(system, x, &[], 1e-13, 40))
        .filter(|r| r.is_nonsingular(1e11))
        .map(|r| {
            let accuracy = accuracy_at_condition(r.condition);
            (r.point, accuracy)
        })
        .collect();
    let groups = group_roots(&refined, 1e-10);
    (0..refined.len())
        .filter(|&i| groups[i] == i)
        .map(|i| refined[i].0.clone())
        .collect()
}

/// Groups refined nonsingular roots into distinct roots: `roots[i]` is a point with its
/// relative accuracy ([`accuracy_at_condition`] or [`Refinement::accuracy`]); two are
/// one root when [`same_root`] at the larger accuracy. Returns for every root the index
/// of its group's first member.
/// Sorting by the real part of the first coordinate keeps the comparison near-linear.
pub fn group_roots(roots: &[(Vec<C64>, f64)], tolerance: f64) -> Vec<usize> {
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut order: Vec<usize> = (0..roots.len()).collect();
    let key = |i: usize| roots[i].0.first().map_or(0.0, |v| v.re);
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
    let mut parent: Vec<usize> = (0..roots.len()).collect();
    // The largest bound of `same_root` bounds the gap of the real parts.
    let widest = tolerance + roots.iter().map(|r| r.1).fold(0.0, f64::max);
    for (position, &i) in order.iter().enumerate() {
        let (a, ka) = (&roots[i].0, roots[i].1);
        for &j in order[position + 1..].iter() {
            let (b, kb) = (&roots[j].0, roots[j].1);
            if key(j) - key(i) > widest * (1.0 + max_norm(a) + max_norm(b)) {
                break;
            }
            if same_root(a, b, ka.max(kb), tolerance) {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                parent[ri.max(rj)] = ri.min(rj);
            }
        }
    }
    (0..roots.len()).map(|i| find(&mut parent, i)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::bertini;

    fn system(text: &str) -> crate::system::CompiledSystem {
        bertini::read(text).unwrap().compile()
    }

    /// Newton converges to the nonsingular root √2 and stalls at the double root of x².
    #[test]
    fn classifies_nonsingular_and_singular_roots() {
        let f = system("variable_group x;\nfunction f;\nf = x^2 - 2;\n");
        let r = newton_refine(&f, &[C64::new(1.5, 0.1)], &[], 1e-14, 30);
        assert!(r.is_nonsingular(1e8), "{r:?}");
        assert!((r.point[0] - C64::new(2f64.sqrt(), 0.0)).norm() < 1e-14);
        let g = system("variable_group x;\nfunction f;\nf = x^2;\n");
        let r = newton_refine(&g, &[C64::new(0.1, 0.0)], &[], 1e-14, 30);
        assert!(!r.is_nonsingular(1e8), "{r:?}");
    }

    /// Two roots that differ only in a coordinate far smaller than the others, at a
    /// condition number of 10¹⁰ (`1e-8·(x² − 9·10⁻⁶) = 0, y = 2000`: x = ±0.003): the
    /// limits are accurate to their last Newton correction, so they stay two roots,
    /// while two approximations of one of them group together. A slack of `10·κ·ε`
    /// relative to `1 + ‖x‖∞` (0.07 here) merged them.
    #[test]
    fn converged_limits_of_an_ill_conditioned_pair_are_two_roots() {
        let f =
            system("variable_group x, y;\nfunction f, g;\nf = 1e-8*(x^2 - 9e-6);\ng = y - 2000;\n");
        let refine = |x: f64, y: f64| {
            let r = newton_refine(&f, &[C64::new(x, 0.0), C64::new(y, 0.0)], &[], 1e-13, 40);
            assert!(r.converged && r.condition > 1e9, "{r:?}");
            let accuracy = r.accuracy();
            assert!(accuracy < 1e-12, "{accuracy}");
            (r.point, accuracy)
        };
        let roots = vec![
            refine(0.0031, 2000.1),
            refine(-0.0029, 1999.9),
            refine(0.00299, 2000.0),
        ];
        let groups = group_roots(&roots, 1e-10);
        assert_ne!(groups[0], groups[1]);
        assert_eq!(groups[0], groups[2]);
        // The same two points without the evidence of convergence are one root.
        let unconverged: Vec<_> = roots
            .iter()
            .map(|(x, _)| (x.clone(), accuracy_at_condition(1e10)))
            .collect();
        assert_eq!(group_roots(&unconverged, 1e-10)[1], 0);
    }

    /// Two approximations of one root group together, a distinct close root does not.
    #[test]
    fn groups_by_refined_limits() {
        let roots = vec![
            (vec![C64::new(1.0, 0.0)], 1e-14),
            (vec![C64::new(1.0 + 1e-15, 0.0)], 1e-14),
            (vec![C64::new(1.0 + 1e-9, 0.0)], 1e-14),
            (vec![C64::new(-3.0, 0.0)], 1e-14),
        ];
        let groups = group_roots(&roots, 1e-12);
        assert_eq!(groups[0], groups[1]);
        assert_ne!(groups[0], groups[2]);
        assert_ne!(groups[0], groups[3]);
    }
}

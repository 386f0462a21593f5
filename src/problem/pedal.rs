//! Closed-form solution of the collinear sub-problems of a `bars` part whose other
//! part is deformable (`bars/plate`, `bars/bars`, and symmetrically `plate/bars`,
//! `bars/bars` for the base).
//!
//! The pedal-point theorems of Kapilavai and Nawratil ("Singularity distance computations
//! for 3-RPR manipulators using extrinsic metrics", Thms 1 and 2; docs/theory.md §5.5)
//! state that the
//! closest configuration on the collinear-platform variety has platform points equal
//! to the orthogonal projections (pedal points) of `b₁, b₂, b₃` onto their
//! total-least-squares line: the line through the centroid `c` along the eigenvector
//! of the larger eigenvalue of the scatter matrix `Σ (b_i − c)(b_i − c)ᵀ`. The
//! constraint `C_p(K′) = 0` involves the platform points only, so once they are
//! fixed the base points `a′` minimise a positive definite quadratic: `D²` is
//! `Q(d_x) + Q(d_y)` for the displacements `d = K′ − K` of the six points (the
//! segment and triangle distances couple x with x and y with y only), and
//! `∂Q/∂d_a = 0` is the 3×3 linear system `Q_aa d_a = −Q_ab d_b` per coordinate.
//!
//! When the two eigenvalues coincide (an equilateral platform: its scatter matrix
//! is isotropic) every line through the centroid is a total-least-squares line and
//! the critical points form a circle, a positive-dimensional component that path
//! tracking cannot resolve into isolated points. The closed form still gives the
//! distance and one closest configuration on that circle; [`PedalSolution::degenerate`]
//! says that the closest configuration is not unique.

use super::{ProblemId, SubProblem};
use crate::metric::{Metric, Part};

/// One closest configuration of a pedal-point sub-problem.
#[derive(Clone, Debug, PartialEq)]
pub struct PedalSolution {
    /// `K′` (twelve coordinates, `a1x … b3y`).
    pub closest: [f64; 12],
    /// Whether the scatter matrix is isotropic to rounding (every line through the
    /// centroid is optimal: the closest configurations form a circle).
    pub degenerate: bool,
}

/// Whether sub-problem `id` has the closed form of this module: the collinear
/// platform of a `bars` platform over a `plate` or `bars` base, or the collinear base
/// of a `bars` base under a `plate` or `bars` platform (not with a rigid other part,
/// where the theorem fails: Kapilavai and Nawratil, Counter example 1).
pub fn has_closed_form(id: ProblemId) -> bool {
    let deformable = |p: Part| p != Part::Rigid;
    match id.subproblem {
        SubProblem::CollinearPlatform => {
            id.metric.platform == Part::Bars && deformable(id.metric.base)
        }
        SubProblem::CollinearBase => id.metric.base == Part::Bars && deformable(id.metric.platform),
        _ => false,
    }
}

/// Relative gap between the scatter matrix's eigenvalues below which they count as
/// equal ([`PedalSolution::degenerate`]).
const ISOTROPY_TOLERANCE: f64 = 1e-9;

/// The closest configuration of sub-problem `id` ([`has_closed_form`]) to the real
/// configuration `k`; `None` for any other sub-problem.
pub fn closest_by_pedal_points(id: ProblemId, k: &[f64; 12]) -> Option<PedalSolution> {
    let axes = scatter_axes(id, k)?;
    Some(PedalSolution {
        closest: on_line(id, k, axes.major)?,
        degenerate: axes.degenerate,
    })
}

/// Both critical points of sub-problem `id` ([`has_closed_form`]) at the real
/// configuration `k`: the pedal points on the line through the centroid along the
/// major axis of the scatter matrix (the minimiser, paper Thms 1–2) and along the minor
/// axis, each with the free part's best displacement. For a generic `k` these are all
/// the critical points of the sub-problem's Lagrangian (its generic count is 2); with
/// an isotropic scatter ([`PedalSolution::degenerate`]) they lie on a circle of
/// critical points. `None` for any other sub-problem.
pub fn critical_points(id: ProblemId, k: &[f64; 12]) -> Option<[[f64; 12]; 2]> {
    let axes = scatter_axes(id, k)?;
    Some([on_line(id, k, axes.major)?, on_line(id, k, axes.minor)?])
}

/// Points 0..3 are the base, 3..6 the platform: the three points on the line and the
/// three free ones.
fn point_roles(id: ProblemId) -> ([usize; 3], [usize; 3]) {
    match id.subproblem {
        SubProblem::CollinearPlatform => ([3, 4, 5], [0, 1, 2]),
        _ => ([0, 1, 2], [3, 4, 5]),
    }
}

/// The principal axes (through the centroid) of the scatter matrix of the points that
/// are to be collinear.
struct ScatterAxes {
    major: ([f64; 2], [f64; 2]),
    minor: ([f64; 2], [f64; 2]),
    degenerate: bool,
}

fn scatter_axes(id: ProblemId, k: &[f64; 12]) -> Option<ScatterAxes> {
    if !has_closed_form(id) {
        return None;
    }
    let (line_points, _) = point_roles(id);
    let line = total_least_squares_line(line_points.map(|i| [k[2 * i], k[2 * i + 1]]));
    let (c, w) = (line.centroid, line.direction);
    Some(ScatterAxes {
        major: (c, w),
        minor: (c, [-w[1], w[0]]),
        degenerate: line.eigenvalue_gap <= ISOTROPY_TOLERANCE * line.spread,
    })
}

/// The total-least-squares line of three points (Kapilavai and Nawratil, Thm 1): the
/// line through their centroid along the major axis of their scatter matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TotalLeastSquaresLine {
    /// The centroid `c` of the points.
    pub centroid: [f64; 2],
    /// The unit direction `w` of the major axis.
    pub direction: [f64; 2],
    /// The difference of the scatter matrix's eigenvalues (0: every line through `c`
    /// fits equally well).
    pub eigenvalue_gap: f64,
    /// The trace `sxx + syy` of the scatter matrix.
    pub spread: f64,
}

/// The [`TotalLeastSquaresLine`] of `points`.
pub fn total_least_squares_line(points: [[f64; 2]; 3]) -> TotalLeastSquaresLine {
    let c = points
        .iter()
        .fold([0.0; 2], |c, p| [c[0] + p[0] / 3.0, c[1] + p[1] / 3.0]);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    // Major axis of [[sxx, sxy], [sxy, syy]]: θ = ½ atan2(2 sxy, sxx − syy).
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    TotalLeastSquaresLine {
        centroid: c,
        direction: [theta.cos(), theta.sin()],
        eigenvalue_gap: ((sxx - syy).powi(2) + 4.0 * sxy * sxy).sqrt(),
        spread: sxx + syy,
    }
}

/// The configuration whose collinear points are the pedal points of `k`'s on the line
/// `c + t w` and whose free points minimise `D²` given those.
fn on_line(id: ProblemId, k: &[f64; 12], (c, w): ([f64; 2], [f64; 2])) -> Option<[f64; 12]> {
    let (line_points, free_points) = point_roles(id);
    let point = |i: usize| [k[2 * i], k[2 * i + 1]];
    let mut closest = *k;
    for &i in &line_points {
        let p = point(i);
        let t = (p[0] - c[0]) * w[0] + (p[1] - c[1]) * w[1];
        closest[2 * i] = c[0] + t * w[0];
        closest[2 * i + 1] = c[1] + t * w[1];
    }
    let q = quadratic_form(id.metric);
    for axis in 0..2 {
        // Q_aa d_a = −Q_ab d_b for the free points' displacements along `axis`.
        let fixed: [f64; 3] = line_points.map(|i| closest[2 * i + axis] - k[2 * i + axis]);
        let matrix = nalgebra::Matrix3::from_fn(|r, s| q[free_points[r]][free_points[s]]);
        let rhs = nalgebra::Vector3::from_fn(|r, _| {
            -(0..3)
                .map(|s| q[free_points[r]][line_points[s]] * fixed[s])
                .sum::<f64>()
        });
        // Q_aa is positive definite: the legs alone give it a positive diagonal part.
        let d = matrix.cholesky()?.solve(&rhs);
        for (r, &i) in free_points.iter().enumerate() {
            closest[2 * i + axis] = k[2 * i + axis] + d[r];
        }
    }
    Some(closest)
}

/// The 6×6 matrix `Q` of `D²(K, K + d) = Σ_ij Q_ij (d_ix d_jx + d_iy d_jy)` over the six
/// points' displacements `d_i` ([`Metric::distance_sq`] is a quadratic form in the
/// displacements and does not depend on `K`), from its values at unit displacements:
/// `Q_ii = D²(e_i)`, `Q_ij = (D²(e_i + e_j) − Q_ii − Q_jj) / 2` (exact: small rationals).
pub(super) fn quadratic_form(metric: Metric) -> [[f64; 6]; 6] {
    let origin = [0.0; 12];
    let displaced = |points: &[usize]| {
        let mut k = origin;
        for &i in points {
            k[2 * i] += 1.0;
        }
        metric.distance_sq(&origin, &k)
    };
    let diagonal: [f64; 6] = std::array::from_fn(|i| displaced(&[i]));
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                diagonal[i]
            } else {
                0.5 * (displaced(&[i, j]) - diagonal[i] - diagonal[j])
            }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rpr::collinearity_platform;

    fn id(name: &str) -> ProblemId {
        name.parse().expect("a problem name")
    }

    #[test]
    fn quadratic_form_reproduces_the_metric() {
        let metric: Metric = "bars/plate".parse().unwrap();
        let q = quadratic_form(metric);
        let k = [0.3, -1.0, 2.0, 0.5, 1.0, 3.0, 0.2, 0.1, 1.5, -0.7, 0.9, 2.2];
        let d = [
            0.1, 0.2, -0.3, 0.4, 0.05, -0.6, 0.7, 0.8, -0.9, 0.15, 0.25, -0.35,
        ];
        let k_prime: [f64; 12] = std::array::from_fn(|i| k[i] + d[i]);
        let by_form: f64 = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .map(|(i, j)| q[i][j] * (d[2 * i] * d[2 * j] + d[2 * i + 1] * d[2 * j + 1]))
            .sum();
        let direct = metric.distance_sq(&k, &k_prime);
        assert!(
            (by_form - direct).abs() <= 1e-14 * direct,
            "{by_form} vs {direct}"
        );
    }

    #[test]
    fn closest_configuration_is_collinear_and_stationary() {
        let k = [
            0.0, 0.0, 10.0, 0.0, 4.0, 8.0, 4.0, 3.0, 6.87, 3.89, 4.36, 5.21,
        ];
        for name in [
            "bars/plate:collinear-platform",
            "bars/bars:collinear-platform",
        ] {
            let id = id(name);
            let solution = closest_by_pedal_points(id, &k).expect("closed form");
            let kp = solution.closest;
            assert!(
                collinearity_platform(&kp).abs() < 1e-12,
                "{name}: collinear"
            );
            assert!(!solution.degenerate);
            // Moving any free (base) coordinate can only increase D².
            let d0 = id.metric.distance_sq(&k, &kp);
            for i in 0..6 {
                let mut moved = kp;
                moved[i] += 1e-4;
                assert!(
                    id.metric.distance_sq(&k, &moved) > d0,
                    "{name}: coordinate {i}"
                );
            }
        }
        assert!(closest_by_pedal_points(id("bars/rigid:collinear-platform"), &k).is_none());
        assert!(closest_by_pedal_points(id("bars/bars:singularity"), &k).is_none());
    }

    #[test]
    fn equilateral_platform_is_degenerate_and_every_line_is_as_close() {
        let h = 3f64.sqrt() / 2.0;
        let k = [
            0.0,
            0.0,
            10.0,
            0.0,
            4.0,
            8.0,
            4.0,
            3.0,
            5.0,
            3.0,
            4.5,
            3.0 + h,
        ];
        let id = id("bars/bars:collinear-platform");
        let solution = closest_by_pedal_points(id, &k).expect("closed form");
        assert!(solution.degenerate);
        let best = id.metric.distance_sq(&k, &solution.closest);
        // The same construction on other lines through the centroid: same D².
        for theta in [0.3, 1.1, 2.0] {
            let w = [f64::cos(theta), f64::sin(theta)];
            let c = [(4.0 + 5.0 + 4.5) / 3.0, (9.0 + h) / 3.0];
            let mut kp = k;
            for i in 3..6 {
                let t = (k[2 * i] - c[0]) * w[0] + (k[2 * i + 1] - c[1]) * w[1];
                kp[2 * i] = c[0] + t * w[0];
                kp[2 * i + 1] = c[1] + t * w[1];
            }
            let q = quadratic_form(id.metric);
            for axis in 0..2 {
                let m = nalgebra::Matrix3::from_fn(|r, s| q[r][s]);
                let rhs = nalgebra::Vector3::from_fn(|r, _| {
                    -(3..6)
                        .map(|s| q[r][s] * (kp[2 * s + axis] - k[2 * s + axis]))
                        .sum::<f64>()
                });
                let d = m.cholesky().unwrap().solve(&rhs);
                for r in 0..3 {
                    kp[2 * r + axis] = k[2 * r + axis] + d[r];
                }
            }
            let other = id.metric.distance_sq(&k, &kp);
            assert!(
                (other - best).abs() <= 1e-12 * best,
                "θ = {theta}: {other} vs {best}"
            );
        }
    }
}

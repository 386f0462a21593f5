//! The collinear sub-problem of a `bars` part under a rigid other part when both are
//! equilateral with the same orientation (`bars/rigid:collinear-platform`,
//! `rigid/bars:collinear-base`): a circle of critical points.
//!
//! With the line direction `w(α)` fixed, the collinear part's points are
//! `p_i′ = h n + s_i w` (`n ⊥ w`) and the rigid part moves by a rotation `θ` about its
//! centroid and a translation `t`. `D²` is a quadratic form in the displacements
//! ([`super::pedal`]), affine in `z = (s₁, s₂, s₃, h, t_x, t_y)` for fixed `θ`, so
//! `G(α, θ) = min_z D²` is one 6×6 linear solve. Where both triangles are equilateral
//! with the same orientation, the second moments of both parts are isotropic and
//! their cross moment `Σ (a_i − c_a)(b_i − c_b)ᵀ` is a rotation times a scale, so every
//! term of `D²` is invariant under turning the line about the centroid: `G` does not
//! depend on `α` and the critical points form a circle that path tracking cannot
//! resolve into isolated points. The distance is then `min_θ G(0, θ)`, found on a
//! grid of [`ANGLE_SAMPLES`] rotations and refined by golden-section search.

use super::pedal::quadratic_form;
use super::{ProblemId, SubProblem};
use crate::metric::{Metric, Part};

/// Rotations sampled before refinement (0.5° apart).
pub const ANGLE_SAMPLES: usize = 720;

/// Relative tolerance of "equilateral": edge lengths equal to `1e-9` of the longest.
const EQUILATERAL_TOLERANCE: f64 = 1e-9;

/// `(collinear part, rigid part)` as point indices (0–2 base, 3–5 platform), if `id`
/// is one of the two sub-problems of this module.
fn parts(id: ProblemId) -> Option<([usize; 3], [usize; 3])> {
    let (platform, base) = (id.metric.platform, id.metric.base);
    match id.subproblem {
        SubProblem::CollinearPlatform if platform == Part::Bars && base == Part::Rigid => {
            Some(([3, 4, 5], [0, 1, 2]))
        }
        SubProblem::CollinearBase if base == Part::Bars && platform == Part::Rigid => {
            Some(([0, 1, 2], [3, 4, 5]))
        }
        _ => None,
    }
}

fn point(k: &[f64; 12], i: usize) -> [f64; 2] {
    [k[2 * i], k[2 * i + 1]]
}

/// Twice the signed area of the triangle of points `idx` of `k`, and whether its
/// three edges are equal to [`EQUILATERAL_TOLERANCE`].
fn equilateral(k: &[f64; 12], idx: [usize; 3]) -> (f64, bool) {
    let p = idx.map(|i| point(k, i));
    let edge = |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let e = [edge(p[0], p[1]), edge(p[1], p[2]), edge(p[2], p[0])];
    let longest = e.iter().fold(0.0f64, |m, &v| m.max(v));
    let shortest = e.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    let area2 =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    (
        area2,
        longest > 0.0 && longest - shortest <= EQUILATERAL_TOLERANCE * longest,
    )
}

/// Whether sub-problem `id` at configuration `k` (any pose of a design: the shapes do
/// not change along a motion) has the circle of critical points of this module.
pub fn on_circle(id: ProblemId, k: &[f64; 12]) -> bool {
    let Some((line, rigid)) = parts(id) else {
        return false;
    };
    let (area_line, line_equilateral) = equilateral(k, line);
    let (area_rigid, rigid_equilateral) = equilateral(k, rigid);
    line_equilateral && rigid_equilateral && area_line * area_rigid > 0.0
}

/// `G(α, θ)` and its minimiser `K′` (see the module documentation).
fn reduced(
    metric: Metric,
    k: &[f64; 12],
    (line, rigid): ([usize; 3], [usize; 3]),
    alpha: f64,
    theta: f64,
) -> (f64, [f64; 12]) {
    let q = quadratic_form(metric);
    let (w, n) = ([alpha.cos(), alpha.sin()], [-alpha.sin(), alpha.cos()]);
    let c = rigid.iter().fold([0.0; 2], |c, &i| {
        [c[0] + k[2 * i] / 3.0, c[1] + k[2 * i + 1] / 3.0]
    });
    let (cos, sin) = (theta.cos(), theta.sin());
    // K′(z) = base + Σ_m z_m column_m.
    let mut base = *k;
    let mut columns = [[0.0f64; 12]; 6];
    for &i in &rigid {
        let (dx, dy) = (k[2 * i] - c[0], k[2 * i + 1] - c[1]);
        base[2 * i] = c[0] + cos * dx - sin * dy;
        base[2 * i + 1] = c[1] + sin * dx + cos * dy;
        columns[4][2 * i] = 1.0;
        columns[5][2 * i + 1] = 1.0;
    }
    for (m, &i) in line.iter().enumerate() {
        base[2 * i] = 0.0;
        base[2 * i + 1] = 0.0;
        columns[m][2 * i] = w[0];
        columns[m][2 * i + 1] = w[1];
        columns[3][2 * i] = n[0];
        columns[3][2 * i + 1] = n[1];
    }
    // D² = Σ_ij Q_ij (d_i · d_j), d = K′ − K: the bilinear form of two 12-vectors.
    let form = |u: &[f64; 12], v: &[f64; 12]| -> f64 {
        let mut sum = 0.0;
        for i in 0..6 {
            for j in 0..6 {
                sum += q[i][j] * (u[2 * i] * v[2 * j] + u[2 * i + 1] * v[2 * j + 1]);
            }
        }
        sum
    };
    let offset: [f64; 12] = std::array::from_fn(|i| base[i] - k[i]);
    let matrix = nalgebra::Matrix6::from_fn(|r, s| form(&columns[r], &columns[s]));
    let rhs = nalgebra::Vector6::from_fn(|r, _| -form(&columns[r], &offset));
    let z = match matrix.cholesky() {
        Some(c) => c.solve(&rhs),
        None => return (f64::INFINITY, *k),
    };
    let mut closest = base;
    for (m, column) in columns.iter().enumerate() {
        for i in 0..12 {
            closest[i] += z[m] * column[i];
        }
    }
    (metric.distance_sq(k, &closest), closest)
}

/// The closest configuration of sub-problem `id` at `k` where [`on_circle`] holds
/// (one point of the circle: the line direction `α = 0`); `None` otherwise.
pub fn closest_on_circle(id: ProblemId, k: &[f64; 12]) -> Option<[f64; 12]> {
    if !on_circle(id, k) {
        return None;
    }
    Some(minimise_over_rotation(id.metric, k, parts(id)?, 0.0).1)
}

/// `min_θ G(α, θ)` and its `K′`: the best of the sampled local minima, each refined by
/// golden-section search on its bracket.
fn minimise_over_rotation(
    metric: Metric,
    k: &[f64; 12],
    split: ([usize; 3], [usize; 3]),
    alpha: f64,
) -> (f64, [f64; 12]) {
    let g = |theta: f64| reduced(metric, k, split, alpha, theta);
    let step = 2.0 * std::f64::consts::PI / ANGLE_SAMPLES as f64;
    let values: Vec<f64> = (0..ANGLE_SAMPLES).map(|j| g(j as f64 * step).0).collect();
    let mut best = (f64::INFINITY, *k);
    for j in 0..ANGLE_SAMPLES {
        let before = values[(j + ANGLE_SAMPLES - 1) % ANGLE_SAMPLES];
        let after = values[(j + 1) % ANGLE_SAMPLES];
        if values[j] > before || values[j] > after {
            continue;
        }
        let (mut lo, mut hi) = ((j as f64 - 1.0) * step, (j as f64 + 1.0) * step);
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..80 {
            let a = hi - ratio * (hi - lo);
            let b = lo + ratio * (hi - lo);
            if g(a).0 <= g(b).0 {
                hi = b;
            } else {
                lo = a;
            }
        }
        let candidate = g(0.5 * (lo + hi));
        if candidate.0 < best.0 {
            best = candidate;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rpr::{Design, Pose, collinearity_base, collinearity_platform};

    fn id(name: &str) -> ProblemId {
        name.parse().unwrap()
    }

    fn equilateral_design(flip_platform: bool) -> Design {
        let h = 3f64.sqrt() / 2.0;
        let top = if flip_platform { -3.0 * h } else { 3.0 * h };
        Design::new(
            [[0.0, 0.0], [10.0, 0.0], [5.0, 10.0 * h]],
            [[0.0, 0.0], [3.0, 0.0], [1.5, top]],
        )
        .unwrap()
    }

    #[test]
    fn the_minimum_does_not_depend_on_the_line_direction() {
        let design = equilateral_design(false);
        let k = design.configuration(Pose::new(4.0, 3.0, 0.7)).to_array();
        for (name, line_platform) in [
            ("bars/rigid:collinear-platform", true),
            ("rigid/bars:collinear-base", false),
        ] {
            let id = id(name);
            assert!(on_circle(id, &k), "{name}");
            let split = parts(id).unwrap();
            let (a, _) = minimise_over_rotation(id.metric, &k, split, 0.0);
            let (b, _) = minimise_over_rotation(id.metric, &k, split, 1.1);
            assert!((a - b).abs() <= 1e-10 * a, "{name}: {a} vs {b}");
            let closest = closest_on_circle(id, &k).unwrap();
            let c = if line_platform {
                collinearity_platform(&closest)
            } else {
                collinearity_base(&closest)
            };
            assert!(c.abs() < 1e-9, "{name}: collinear");
            assert!(id.metric.distance_sq(&k, &closest) <= a * (1.0 + 1e-12));
        }
    }

    #[test]
    fn only_equilateral_pairs_of_one_orientation_are_on_a_circle() {
        let k = equilateral_design(true)
            .configuration(Pose::new(4.0, 3.0, 0.7))
            .to_array();
        assert!(!on_circle(id("bars/rigid:collinear-platform"), &k));
        let example = crate::mechanism::rpr::example_design()
            .configuration(Pose::new(4.0, 3.0, 0.3))
            .to_array();
        assert!(!on_circle(id("bars/rigid:collinear-platform"), &example));
        let k = equilateral_design(false)
            .configuration(Pose::new(4.0, 3.0, 0.7))
            .to_array();
        assert!(!on_circle(id("bars/bars:collinear-platform"), &k));
        assert!(!on_circle(id("bars/rigid:singularity"), &k));
    }
}

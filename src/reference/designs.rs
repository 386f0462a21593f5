//! A matrix of 3-RPR test designs of every class a user builds, each with an analytic
//! motion that crosses the singularity hypersurface `S = 0` and a scattered pose list.
//!
//! Classes: generic random designs at coordinate scales 10⁻², 1, 10²; equilateral
//! base, platform, or both (aligned and rotated against each other); isosceles; a
//! platform similar to, or congruent with, the base; exactly and nearly (10⁻³)
//! collinear anchors of base or platform; each pair of anchors close (10⁻⁴ apart) in
//! base or platform; two coincident anchors; a platform 100 times smaller or larger
//! than the base. Everything is deterministic for a given seed (ChaCha8 streams).
//!
//! Designs with coincident anchors are legitimate robots ([`Design::new`] accepts
//! them; only a part collapsed to a point is rejected).

use crate::algebra::Point;
use crate::mechanism::rpr::{
    AnalyticMotion, CosineTerm, Design, Motion, MotionCoordinate, Pose, PoseList, RprError,
    singularity_polynomial,
};
use crate::pipeline::bisection::bisect_sign_change;
use crate::random;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// One test design with its motions.
#[derive(Clone, Debug, PartialEq)]
pub struct DesignCase {
    /// Class name, e.g. `random-scale-1e-2`, `close-base-12`.
    pub name: String,
    /// Base anchors `A_i`.
    pub base: [Point<f64>; 3],
    /// Platform anchors `P_i`.
    pub platform: [Point<f64>; 3],
    /// `x = x_0 + r sin τ`, `y = y_0 − r′ cos τ`, `φ = φ_0 + ω τ` on its τ range,
    /// chosen so that `S` changes sign along it.
    pub motion: AnalyticMotion,
    /// τ of the sign changes of `S` along [`DesignCase::motion`] (sampled at 4001
    /// points, bisected to `10⁻¹²`).
    pub crossings: Vec<f64>,
    /// Random poses in the workspace (platform centre within half the base size of
    /// the base centroid, any orientation).
    pub scattered: Vec<Pose>,
}

impl DesignCase {
    /// The validated design.
    pub fn design(&self) -> Result<Design, RprError> {
        Design::new(self.base, self.platform)
    }

    /// [`DesignCase::motion`] as a [`Motion`].
    pub fn analytic_motion(&self) -> Motion {
        Motion::Analytic(self.motion.clone())
    }

    /// [`DesignCase::scattered`] as a pose-list [`Motion`].
    pub fn scattered_motion(&self) -> Motion {
        Motion::Poses(PoseList {
            poses: self.scattered.clone(),
        })
    }
}

/// Number of scattered poses per case.
pub const SCATTERED_POSES: usize = 8;

fn scale_points(p: [Point<f64>; 3], s: f64) -> [Point<f64>; 3] {
    p.map(|q| [s * q[0], s * q[1]])
}

fn centroid(p: &[Point<f64>; 3]) -> Point<f64> {
    [
        (p[0][0] + p[1][0] + p[2][0]) / 3.0,
        (p[0][1] + p[1][1] + p[2][1]) / 3.0,
    ]
}

fn size(p: &[Point<f64>; 3]) -> f64 {
    let c = centroid(p);
    (p.iter()
        .map(|q| (q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2))
        .sum::<f64>()
        / 3.0)
        .sqrt()
}

/// Three points at angles `θ_0 + 2πk/3 + noise` and radii `radius·(1 + noise)`.
fn random_triangle(rng: &mut random::SeededRng, radius: f64) -> [Point<f64>; 3] {
    let theta0 = random::uniform(rng, 0.0, TAU);
    [0, 1, 2].map(|k| {
        let angle = theta0 + TAU * k as f64 / 3.0 + random::uniform(rng, -0.6, 0.6);
        let r = radius * (1.0 + random::uniform(rng, -0.35, 0.35));
        [r * angle.cos(), r * angle.sin()]
    })
}

fn regular(radius: f64, rotation: f64) -> [Point<f64>; 3] {
    [0, 1, 2].map(|k| {
        let angle = rotation + FRAC_PI_2 + TAU * k as f64 / 3.0;
        [radius * angle.cos(), radius * angle.sin()]
    })
}

/// [`regular`] with its first vertex moved `offset·radius` along the circle and
/// `offset·radius` outwards: an equilateral part as a workshop builds it.
fn nearly_regular(radius: f64, rotation: f64, offset: f64) -> [Point<f64>; 3] {
    let mut p = regular(radius, rotation);
    let angle = rotation + FRAC_PI_2 + offset;
    let r = radius * (1.0 + offset);
    p[0] = [r * angle.cos(), r * angle.sin()];
    p
}

fn isosceles(radius: f64, apex_angle: f64) -> [Point<f64>; 3] {
    // Apex on the y axis, base symmetric about it; legs of length 1.4·radius.
    let leg = 1.4 * radius;
    let half = 0.5 * apex_angle;
    [
        [0.0, radius],
        [-leg * half.sin(), radius - leg * half.cos()],
        [leg * half.sin(), radius - leg * half.cos()],
    ]
}

/// Moves anchor `j` to `1e-4·size` (or 0) from anchor `i` in a random direction.
fn pull_together(
    p: [Point<f64>; 3],
    i: usize,
    j: usize,
    gap: f64,
    rng: &mut random::SeededRng,
) -> [Point<f64>; 3] {
    let mut out = p;
    let angle = random::uniform(rng, 0.0, TAU);
    let d = gap * size(&p);
    out[j] = [p[i][0] + d * angle.cos(), p[i][1] + d * angle.sin()];
    out
}

/// Anchors exactly collinear in binary floating point (the cross product of their
/// differences is exactly 0): `(−1, −½), (¼, ⅛), (1, ½)` times a power of two.
fn exactly_collinear(power_of_two: f64) -> [Point<f64>; 3] {
    scale_points([[-1.0, -0.5], [0.25, 0.125], [1.0, 0.5]], power_of_two)
}

/// [`exactly_collinear`] with the middle anchor moved `offset·size` off the line.
fn nearly_collinear(power_of_two: f64, offset: f64) -> [Point<f64>; 3] {
    let mut p = exactly_collinear(power_of_two);
    let s = size(&p);
    // Unit normal of the line (direction (2, 1)/√5).
    let n = [-1.0 / 5f64.sqrt(), 2.0 / 5f64.sqrt()];
    p[1] = [p[1][0] + offset * s * n[0], p[1][1] + offset * s * n[1]];
    p
}

fn sign_changes(
    base: &[Point<f64>; 3],
    platform: &[Point<f64>; 3],
    m: &AnalyticMotion,
) -> Vec<f64> {
    let motion = Motion::Analytic(m.clone());
    let s_of = |tau: f64| {
        let pose = motion.pose(tau).unwrap_or(Pose::new(0.0, 0.0, 0.0));
        let (s, c) = pose.phi.sin_cos();
        let mut k = [0.0; 12];
        for (i, (a, &[px, py])) in base.iter().zip(platform).enumerate() {
            k[2 * i] = a[0];
            k[2 * i + 1] = a[1];
            k[6 + 2 * i] = pose.x + c * px - s * py;
            k[6 + 2 * i + 1] = pose.y + s * px + c * py;
        }
        singularity_polynomial(&k)
    };
    let [lo, hi] = m.tau_range;
    let n = 4000;
    let mut out = Vec::new();
    let mut previous = (lo, s_of(lo));
    for j in 1..=n {
        let tau = lo + (hi - lo) * j as f64 / n as f64;
        let s = s_of(tau);
        if previous.1 != 0.0 && s != 0.0 && (previous.1 < 0.0) != (s < 0.0) {
            out.push(bisect_sign_change((previous.0, tau), previous.1, |mid| {
                Some(s_of(mid))
            }));
        }
        previous = (tau, s);
    }
    out
}

/// An analytic motion around the base centroid that crosses `S = 0` (the first of
/// up to 64 seeded candidates with a sign change; the last candidate otherwise, with
/// no crossings recorded).
fn crossing_motion(
    base: &[Point<f64>; 3],
    platform: &[Point<f64>; 3],
    rng: &mut random::SeededRng,
) -> (AnalyticMotion, Vec<f64>) {
    let c = centroid(base);
    let r = size(base).max(size(platform));
    let mut last = None;
    for _ in 0..64 {
        let x0 = c[0] + 0.2 * r * random::normal(rng);
        let y0 = c[1] + 0.2 * r * random::normal(rng);
        let rx = r * random::uniform(rng, 0.1, 0.4);
        let ry = r * random::uniform(rng, 0.1, 0.4);
        let phi0 = random::uniform(rng, -PI, PI);
        let omega = random::uniform(rng, 0.6, 1.2)
            * if random::uniform(rng, 0.0, 1.0) < 0.5 {
                -1.0
            } else {
                1.0
            };
        let motion = AnalyticMotion {
            tau_range: [-1.0, 4.5],
            x: MotionCoordinate {
                polynomial: vec![x0],
                cosines: vec![CosineTerm {
                    amplitude: rx,
                    frequency: 1.0,
                    phase: -FRAC_PI_2,
                }],
            },
            y: MotionCoordinate {
                polynomial: vec![y0],
                cosines: vec![CosineTerm {
                    amplitude: -ry,
                    frequency: 1.0,
                    phase: 0.0,
                }],
            },
            phi: MotionCoordinate::polynomial(vec![phi0, omega]),
        };
        let crossings = sign_changes(base, platform, &motion);
        if !crossings.is_empty() {
            return (motion, crossings);
        }
        last = Some(motion);
    }
    (last.expect("at least one candidate"), Vec::new())
}

fn scattered_poses(
    base: &[Point<f64>; 3],
    platform: &[Point<f64>; 3],
    rng: &mut random::SeededRng,
) -> Vec<Pose> {
    let c = centroid(base);
    let r = 0.5 * size(base).max(size(platform));
    (0..SCATTERED_POSES)
        .map(|_| {
            let radius = r * random::uniform(rng, 0.0, 1.0).sqrt();
            let angle = random::uniform(rng, 0.0, TAU);
            Pose::new(
                c[0] + radius * angle.cos(),
                c[1] + radius * angle.sin(),
                random::uniform(rng, -PI, PI),
            )
        })
        .collect()
}

/// Every class of [`design_matrix`], by name, in order.
pub const CLASS_NAMES: [&str; 27] = [
    "random-scale-1e-2",
    "random-scale-1",
    "random-scale-1e2",
    "equilateral-base",
    "equilateral-platform",
    "equilateral-both-aligned",
    "equilateral-both-rotated",
    "isosceles",
    "similar",
    "congruent",
    "collinear-base",
    "collinear-platform",
    "nearly-collinear-base",
    "nearly-collinear-platform",
    "close-base-12",
    "close-base-23",
    "close-base-13",
    "close-platform-12",
    "close-platform-23",
    "close-platform-13",
    "coincident-base-12",
    "coincident-platform-23",
    "tiny-platform",
    "large-platform",
    "nearly-equilateral-base",
    "nearly-equilateral-both-aligned",
    "nearly-equilateral-platform-1e-3",
];

/// Base and platform anchors.
type Anchors = ([Point<f64>; 3], [Point<f64>; 3]);

/// The anchors of class `name` (drawn from `rng`); `None` for an unknown name.
fn anchors(name: &str, rng: &mut random::SeededRng) -> Option<Anchors> {
    let base = random_triangle(rng, 1.0);
    let platform = random_triangle(rng, 0.4);
    let close = |p: [Point<f64>; 3], pair: &str, gap: f64, rng: &mut random::SeededRng| {
        let (i, j) = match pair {
            "12" => (0, 1),
            "23" => (1, 2),
            _ => (0, 2),
        };
        pull_together(p, i, j, gap, rng)
    };
    Some(match name {
        "random-scale-1e-2" => (scale_points(base, 1e-2), scale_points(platform, 1e-2)),
        "random-scale-1" => (base, platform),
        "random-scale-1e2" => (scale_points(base, 1e2), scale_points(platform, 1e2)),
        "equilateral-base" => (regular(1.0, 0.1), platform),
        "equilateral-platform" => (base, regular(0.4, -0.2)),
        "equilateral-both-aligned" => (regular(1.0, 0.0), regular(0.4, 0.0)),
        "equilateral-both-rotated" => (regular(1.0, 0.0), regular(0.4, 0.7)),
        "isosceles" => (isosceles(1.0, 0.9), isosceles(0.4, 1.3)),
        "similar" => {
            let c = centroid(&base);
            (
                base,
                base.map(|q| [0.4 * (q[0] - c[0]), 0.4 * (q[1] - c[1])]),
            )
        }
        "congruent" => {
            let c = centroid(&base);
            (base, base.map(|q| [q[0] - c[0], q[1] - c[1]]))
        }
        "collinear-base" => (exactly_collinear(1.0), platform),
        "collinear-platform" => (base, exactly_collinear(0.5)),
        "nearly-collinear-base" => (nearly_collinear(1.0, 1e-3), platform),
        "nearly-collinear-platform" => (base, nearly_collinear(0.5, 1e-3)),
        "tiny-platform" => (base, scale_points(platform, 1.0 / 40.0)),
        "large-platform" => (base, scale_points(platform, 250.0)),
        "nearly-equilateral-base" => (nearly_regular(1.0, 0.1, 1e-6), platform),
        "nearly-equilateral-both-aligned" => (
            nearly_regular(1.0, 0.0, 1e-6),
            nearly_regular(0.4, 0.0, 1e-6),
        ),
        "nearly-equilateral-platform-1e-3" => (base, nearly_regular(0.4, -0.2, 1e-3)),
        _ => {
            let (part, pair) = name.rsplit_once('-')?;
            match part {
                "close-base" => (close(base, pair, 1e-4, rng), platform),
                "close-platform" => (base, close(platform, pair, 1e-4, rng)),
                "coincident-base" => (close(base, pair, 0.0, rng), platform),
                "coincident-platform" => (base, close(platform, pair, 0.0, rng)),
                _ => return None,
            }
        }
    })
}

/// The test case of class `name` (one of [`CLASS_NAMES`]) for `seed`; `None` for an
/// unknown name. Each class draws from its own stream, so a case does not depend on
/// which other classes are generated.
pub fn design_case(name: &str, seed: u64) -> Option<DesignCase> {
    let index = CLASS_NAMES.iter().position(|&c| c == name)?;
    // The generic random base and platform are the same stream for every class.
    let mut shapes = random::stream(seed, 0);
    let (base, platform) = anchors(name, &mut shapes)?;
    let mut rng = random::stream(seed, 1 + index as u64);
    let (motion, crossings) = crossing_motion(&base, &platform, &mut rng);
    let scattered = scattered_poses(&base, &platform, &mut rng);
    Some(DesignCase {
        name: name.to_string(),
        base,
        platform,
        motion,
        crossings,
        scattered,
    })
}

/// Every class of [`CLASS_NAMES`] for `seed`.
pub fn design_matrix(seed: u64) -> Vec<DesignCase> {
    CLASS_NAMES
        .iter()
        .filter_map(|name| design_case(name, seed))
        .collect()
}

//! The planar 3-RRR parallel manipulator: design, pose, inverse kinematics with an explicit
//! working mode per leg, and the configuration of its nine joint points (docs/theory.md
//! §10, §11.1, §11.5; Ramana Babu et al. §II).
//!
//! # Model
//!
//! Leg `i` (0-based in code, 1-based in docs/theory.md and the papers) is the chain
//! `O_i —(proximal link)— B_i —(distal link)— C_i`:
//! - `O_i`: base revolute joint, fixed frame;
//! - `B_i`: elbow (middle revolute joint), `|B_i − O_i| = proximal_i`;
//! - `C_i`: platform revolute joint, `|C_i − B_i| = distal_i`.
//!
//! The platform joints are given in the moving frame, whose origin is the operation point
//! `P`; at pose `(x, y, φ)` they are `C_i = P + R(φ)·c_i^moving`, `P = (x, y)`.
//!
//! Joint angles (Ramana Babu et al. Eqs. 2–3): `θ_i = atan2(B_i − O_i)` (absolute direction of the
//! proximal link) and `ψ_i = atan2(C_i − B_i)` (absolute direction of the distal link), both
//! measured from the x-axis.
//!
//! # Working modes
//!
//! Each leg reaches a platform joint `C_i` with two elbow postures, mirror images about the
//! line `O_iC_i`. [`ElbowMode::Positive`] (σ_i = +1) is the posture with
//! `(B_i − O_i) × (C_i − B_i) > 0` (the distal link turns counter-clockwise from the proximal
//! link), [`ElbowMode::Negative`] (σ_i = −1) the other one. The "positive working
//! modes" of Ramana Babu et al. are taken to be σ = (+1, +1, +1).
//!
//! # Symmetric family of Ramana Babu et al.
//!
//! Ramana Babu et al. write the loop closure (their Eqs. 2–3) as
//! `x_p = b cos θ_i + c cos ψ_i + a cos(φ + γ_i) + x_oi`, so in their notation
//! **`a` = distance from P to each platform joint C_i (platform circumradius), `b` = |O_iB_i|
//! (proximal link), `c` = |B_iC_i| (distal link)**; their design vector `[a b c]` is
//! optimised under `a + b + c ≤ λ`. [`RrrDesign::symmetric`] maps `(R, a, b, c)` to: base
//! joints on the circle of radius `R` about the origin at angles 90°, 210°, 330°;
//! platform joints on the circle of radius `a` about P at the same angles in the moving
//! frame (so at φ = 0 every leg points radially); every proximal link `b`, every distal
//! link `c`. The base radius `R` is not given by Ramana Babu et al. and is a free choice
//! of the example geometry.

use crate::C64;
use crate::algebra::{
    Point as RingPoint, Ring, cross as algebra_cross, difference as algebra_difference,
};
use crate::mechanism::rpr::{self, AnalyticMotion, CosineTerm, MotionCoordinate};
use crate::mechanism::rrr_reach;
use crate::mechanism::{InputNumberError, check_input_number};
use crate::metric::{segment_distance_sq, triangle_distance_sq};
use nalgebra::Vector2;
use std::f64::consts::PI;
use thiserror::Error;

/// Plane point or vector in the design's length unit.
pub type Point = Vector2<f64>;

/// Errors of the 3-RRR model; each names the offending field.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RrrError {
    /// A number is NaN, infinite or beyond ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE).
    #[error(transparent)]
    Number(#[from] InputNumberError),
    /// A length that must be positive is zero or negative.
    #[error("{field} must be positive, got {value}")]
    NonPositive {
        /// Field path, e.g. `proximal[0]`.
        field: String,
        /// The offending value.
        value: f64,
    },
    /// Two joints that must be distinct coincide.
    #[error("{first} and {second} coincide (distance {distance:e})")]
    CoincidentJoints {
        /// First joint, e.g. `base[0]`.
        first: String,
        /// Second joint, e.g. `base[2]`.
        second: String,
        /// Their distance.
        distance: f64,
    },
    /// The platform joint of a leg is out of the leg's annulus `| |b|−|c| | ≤ |C_i − O_i| ≤ |b|+|c|`.
    #[error(
        "pose unreachable: leg {leg} needs |C-O| = {distance} but reaches only [{min_reach}, {max_reach}]"
    )]
    Unreachable {
        /// Leg index (0-based).
        leg: usize,
        /// `|C_i − O_i|` at the requested pose.
        distance: f64,
        /// `|proximal − distal|`.
        min_reach: f64,
        /// `proximal + distal`.
        max_reach: f64,
    },
    /// The motion has no pose at this parameter (outside an explicit pose list).
    #[error("tau = {tau}: no pose of the motion at this parameter")]
    NoPose {
        /// The parameter value.
        tau: f64,
    },
    /// `C_i = O_i` with equal link lengths: the elbow angle is undetermined.
    #[error("pose degenerate: platform joint {leg} coincides with its base joint")]
    DegenerateLeg {
        /// Leg index (0-based).
        leg: usize,
    },
}

/// Relative tolerance under which two joints count as coincident (scaled by the design size).
const COINCIDENCE_TOLERANCE: f64 = 1e-12;

/// Working mode (elbow posture) of one leg; see the module documentation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ElbowMode {
    /// σ = +1: `(B − O) × (C − B) > 0`.
    Positive,
    /// σ = −1: `(B − O) × (C − B) < 0`.
    Negative,
}

impl ElbowMode {
    /// The sign σ ∈ {+1, −1}.
    pub fn sign(self) -> f64 {
        match self {
            ElbowMode::Positive => 1.0,
            ElbowMode::Negative => -1.0,
        }
    }

    /// The other posture.
    pub fn flipped(self) -> Self {
        match self {
            ElbowMode::Positive => ElbowMode::Negative,
            ElbowMode::Negative => ElbowMode::Positive,
        }
    }
}

/// Working modes of the three legs.
pub type WorkingModes = [ElbowMode; 3];

/// The "positive working modes" of Ramana Babu et al.: σ = (+1, +1, +1).
pub const POSITIVE_MODES: WorkingModes = [ElbowMode::Positive; 3];

/// Pose of the platform: operation point `P = (x, y)` and orientation `φ` (radians) of the
/// moving frame with respect to the fixed frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RrrPose {
    /// x of the operation point P.
    pub x: f64,
    /// y of the operation point P.
    pub y: f64,
    /// Platform orientation φ, radians, counter-clockwise from the x-axis.
    pub phi: f64,
}

impl RrrPose {
    /// Pose from its three coordinates.
    pub fn new(x: f64, y: f64, phi: f64) -> Self {
        Self { x, y, phi }
    }

    /// The operation point P.
    pub fn point(&self) -> Point {
        Point::new(self.x, self.y)
    }

    fn check_finite(&self) -> Result<(), RrrError> {
        for (field, value) in [
            ("pose.x", self.x),
            ("pose.y", self.y),
            ("pose.phi", self.phi),
        ] {
            check_number(field, value)?;
        }
        Ok(())
    }
}

/// `value` finite and within ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE); errors name `field`.
fn check_number(field: &str, value: f64) -> Result<(), RrrError> {
    Ok(check_input_number(|| field.to_string(), value)?)
}

/// A validated general planar 3-RRR design (docs/theory.md §10, §11.5).
#[derive(Debug, Clone, PartialEq)]
pub struct RrrDesign {
    base: [Point; 3],
    proximal: [f64; 3],
    distal: [f64; 3],
    platform: [Point; 3],
}

fn check_point(field: &str, p: Point) -> Result<(), RrrError> {
    for (axis, value) in [("x", p.x), ("y", p.y)] {
        check_number(&format!("{field}.{axis}"), value)?;
    }
    Ok(())
}

fn check_length(field: &str, value: f64) -> Result<(), RrrError> {
    check_number(field, value)?;
    if value <= 0.0 {
        return Err(RrrError::NonPositive {
            field: field.to_string(),
            value,
        });
    }
    Ok(())
}

fn check_distinct(name: &str, points: &[Point; 3], scale: f64) -> Result<(), RrrError> {
    for i in 0..3 {
        for j in (i + 1)..3 {
            let distance = (points[i] - points[j]).norm();
            if distance <= COINCIDENCE_TOLERANCE * scale {
                return Err(RrrError::CoincidentJoints {
                    first: format!("{name}[{i}]"),
                    second: format!("{name}[{j}]"),
                    distance,
                });
            }
        }
    }
    Ok(())
}

impl RrrDesign {
    /// General design: base joints `O_i` (fixed frame), proximal lengths `|O_iB_i|`, distal
    /// lengths `|B_iC_i|`, platform joints `C_i` in the moving frame (origin = operation point).
    ///
    /// Errors: any non-finite number or one beyond ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE), a non-positive length, or two coincident base (or
    /// platform) joints, naming the field (`base[i].x`, `proximal[i]`, `distal[i]`,
    /// `platform[i].y`, …).
    pub fn new(
        base: [Point; 3],
        proximal: [f64; 3],
        distal: [f64; 3],
        platform: [Point; 3],
    ) -> Result<Self, RrrError> {
        for i in 0..3 {
            check_point(&format!("base[{i}]"), base[i])?;
            check_point(&format!("platform[{i}]"), platform[i])?;
            check_length(&format!("proximal[{i}]"), proximal[i])?;
            check_length(&format!("distal[{i}]"), distal[i])?;
        }
        let scale = base
            .iter()
            .chain(platform.iter())
            .map(|p| p.norm())
            .chain(proximal.iter().copied())
            .chain(distal.iter().copied())
            .fold(0.0_f64, f64::max);
        check_distinct("base", &base, scale)?;
        check_distinct("platform", &platform, scale)?;
        Ok(Self {
            base,
            proximal,
            distal,
            platform,
        })
    }

    /// Symmetric design in the style of Ramana Babu et al. (see the module
    /// documentation): base joints on the circle of radius `base_radius` at 90°, 210°,
    /// 330°; platform joints at distance `platform_radius` (`a` of Ramana Babu et al.)
    /// from P at the same angles in the moving frame; proximal links `proximal` (`b`),
    /// distal links `distal` (`c`).
    pub fn symmetric(
        base_radius: f64,
        platform_radius: f64,
        proximal: f64,
        distal: f64,
    ) -> Result<Self, RrrError> {
        check_length("base_radius", base_radius)?;
        check_length("platform_radius", platform_radius)?;
        check_length("proximal", proximal)?;
        check_length("distal", distal)?;
        let angle = |i: usize| PI / 2.0 + 2.0 * PI * i as f64 / 3.0;
        let on_circle = |r: f64, i: usize| Point::new(r * angle(i).cos(), r * angle(i).sin());
        Self::new(
            [0, 1, 2].map(|i| on_circle(base_radius, i)),
            [proximal; 3],
            [distal; 3],
            [0, 1, 2].map(|i| on_circle(platform_radius, i)),
        )
    }

    /// Base joints `O_i`, fixed frame.
    pub fn base(&self) -> &[Point; 3] {
        &self.base
    }

    /// Proximal link lengths `|O_iB_i|`.
    pub fn proximal(&self) -> &[f64; 3] {
        &self.proximal
    }

    /// Distal link lengths `|B_iC_i|`.
    pub fn distal(&self) -> &[f64; 3] {
        &self.distal
    }

    /// Platform joints in the moving frame (origin = operation point P).
    pub fn platform(&self) -> &[Point; 3] {
        &self.platform
    }

    /// Characteristic platform length `max_i |c_i^moving|` (> 0 since the joints are
    /// distinct); used to make moment columns and determinants dimensionless.
    pub fn platform_length(&self) -> f64 {
        self.platform.iter().map(|p| p.norm()).fold(0.0, f64::max)
    }

    /// Platform joints `C_i = P + R(φ) c_i^moving` in the fixed frame.
    pub fn platform_joints(&self, pose: &RrrPose) -> [Point; 3] {
        let (s, c) = pose.phi.sin_cos();
        let p = pose.point();
        self.platform
            .map(|q| p + Point::new(c * q.x - s * q.y, s * q.x + c * q.y))
    }

    /// Inverse kinematics of one leg: elbow `B_i` for platform joint `c_joint` in working mode
    /// `mode`. With `d = C − O`, `L = |d|`, the law of cosines gives the angle α at `O_i`
    /// between `d` and the proximal link, `cos α = (L² + b² − c²)/(2 b L)`, and
    /// `θ_i = atan2(d) − σ_i α` (so `b_i × c_i = σ_i·b·L·sin α ≥ 0·σ_i`).
    /// Unreachable (cos α outside [−1, 1] beyond rounding) is an error, never NaN.
    pub fn leg_elbow(
        &self,
        leg: usize,
        c_joint: Point,
        mode: ElbowMode,
    ) -> Result<Point, RrrError> {
        let o = self.base[leg];
        let (b, c) = (self.proximal[leg], self.distal[leg]);
        let d = c_joint - o;
        let length = d.norm();
        let min_reach = (b - c).abs();
        let max_reach = b + c;
        let slack = 1e-12 * max_reach;
        if !length.is_finite() || length > max_reach + slack || length < min_reach - slack {
            return Err(RrrError::Unreachable {
                leg,
                distance: length,
                min_reach,
                max_reach,
            });
        }
        if length <= COINCIDENCE_TOLERANCE * max_reach {
            return Err(RrrError::DegenerateLeg { leg });
        }
        let cos_alpha = ((length * length + b * b - c * c) / (2.0 * b * length)).clamp(-1.0, 1.0);
        let theta = d.y.atan2(d.x) - mode.sign() * cos_alpha.acos();
        Ok(o + b * Point::new(theta.cos(), theta.sin()))
    }

    /// Inverse kinematics: the configuration of the nine points at `pose` with working modes
    /// `modes`. Errors name the first unreachable leg.
    pub fn inverse_kinematics(
        &self,
        pose: &RrrPose,
        modes: &WorkingModes,
    ) -> Result<RrrConfiguration, RrrError> {
        pose.check_finite()?;
        let platform = self.platform_joints(pose);
        let mut elbow = [Point::zeros(); 3];
        for leg in 0..3 {
            elbow[leg] = self.leg_elbow(leg, platform[leg], modes[leg])?;
        }
        Ok(RrrConfiguration {
            operation_point: pose.point(),
            base: self.base,
            elbow,
            platform,
        })
    }

    /// Like [`inverse_kinematics`](Self::inverse_kinematics) but `None` when unreachable.
    pub fn try_inverse_kinematics(
        &self,
        pose: &RrrPose,
        modes: &WorkingModes,
    ) -> Option<RrrConfiguration> {
        self.inverse_kinematics(pose, modes).ok()
    }
}

/// Configuration of a 3-RRR: the nine joint points in the fixed frame and the operation point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RrrConfiguration {
    /// Operation point P (platform reference point).
    pub operation_point: Point,
    /// Base joints `O_i`.
    pub base: [Point; 3],
    /// Elbows `B_i`.
    pub elbow: [Point; 3],
    /// Platform joints `C_i`.
    pub platform: [Point; 3],
}

fn cross(u: Point, v: Point) -> f64 {
    u.x * v.y - u.y * v.x
}

impl RrrConfiguration {
    /// The nine points in the order `O_1, O_2, O_3, B_1, B_2, B_3, C_1, C_2, C_3`
    /// (docs/theory.md §10).
    pub fn points(&self) -> [Point; 9] {
        let mut out = [Point::zeros(); 9];
        out[..3].copy_from_slice(&self.base);
        out[3..6].copy_from_slice(&self.elbow);
        out[6..].copy_from_slice(&self.platform);
        out
    }

    /// Proximal vector `b_i = B_i − O_i` (Ramana Babu et al. notation).
    pub fn proximal_vector(&self, leg: usize) -> Point {
        self.elbow[leg] - self.base[leg]
    }

    /// Distal vector `c_i = C_i − B_i` (Ramana Babu et al. notation).
    pub fn distal_vector(&self, leg: usize) -> Point {
        self.platform[leg] - self.elbow[leg]
    }

    /// Platform vector `a_i = P − C_i` (Ramana Babu et al. notation).
    pub fn platform_vector(&self, leg: usize) -> Point {
        self.operation_point - self.platform[leg]
    }

    /// Absolute proximal angle `θ_i = atan2(B_i − O_i)`.
    pub fn theta(&self, leg: usize) -> f64 {
        let b = self.proximal_vector(leg);
        b.y.atan2(b.x)
    }

    /// Absolute distal angle `ψ_i = atan2(C_i − B_i)`.
    pub fn psi(&self, leg: usize) -> f64 {
        let c = self.distal_vector(leg);
        c.y.atan2(c.x)
    }

    /// Leg-singularity determinant `det[[O_i,1],[B_i,1],[C_i,1]] = b_i × c_i`
    /// (docs/theory.md §10): zero iff `O_i, B_i, C_i` are collinear (Type I of Ramana
    /// Babu et al.), sign = working mode.
    pub fn leg_determinant(&self, leg: usize) -> f64 {
        cross(self.proximal_vector(leg), self.distal_vector(leg))
    }

    /// Parallel-singularity polynomial of docs/theory.md §10: `S` of docs/theory.md §1.3
    /// with `(a_i, b_i) → (B_i, C_i)`, `det [ C_i − B_i , B_i × C_i ]_{i=1..3}`; zero iff
    /// the lines `B_iC_i` are concurrent or parallel.
    pub fn parallel_determinant(&self) -> f64 {
        let rows = [0, 1, 2].map(|i| {
            let c = self.distal_vector(i);
            [c.x, c.y, cross(self.elbow[i], self.platform[i])]
        });
        det3(&rows)
    }
}

/// Determinant of a 3×3 matrix given by rows.
pub(crate) fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

// ---------------------------------------------------------------------------------
// Polynomial formulas on the 18-vector of the nine points (docs/theory.md §10)
// ---------------------------------------------------------------------------------

/// Number of coordinates of a 3-RRR configuration: nine points in the plane.
pub const CONFIGURATION_LEN: usize = 18;

/// Names of the 18 coordinates, in the order `O_1, O_2, O_3, B_1, B_2, B_3, C_1, C_2, C_3`
/// (x before y), as used by [`RrrConfiguration::to_array`].
pub const COORDINATE_NAMES: [&str; CONFIGURATION_LEN] = [
    "O1x", "O1y", "O2x", "O2y", "O3x", "O3y", "B1x", "B1y", "B2x", "B2y", "B3x", "B3y", "C1x",
    "C1y", "C2x", "C2y", "C3x", "C3y",
];

fn ring_point<T: Ring>(k: &[T; CONFIGURATION_LEN], index: usize) -> RingPoint<T> {
    [k[2 * index].clone(), k[2 * index + 1].clone()]
}

/// Parallel-singularity polynomial of docs/theory.md §10 on the 18-vector `k`: the
/// singularity polynomial S of docs/theory.md §1.3 (Kapilavai and Nawratil, Eq. 6) with
/// `(a_i, b_i) → (B_i, C_i)`, `det[ C_i − B_i | B_i × C_i ]_{i=1..3}` (degree 4). Zero
/// iff the lines `B_iC_i` are concurrent or parallel. Generic over [`Ring`] (numbers and
/// symbolic Lagrangians).
pub fn parallel_polynomial<T: Ring>(k: &[T; CONFIGURATION_LEN]) -> T {
    let lines: [T; 12] = std::array::from_fn(|j| k[6 + j].clone());
    rpr::singularity_polynomial(&lines)
}

/// Leg-singularity polynomial of leg `leg` (0-based) on the 18-vector `k` (docs/theory.md
/// §10): `det[[O_i, 1], [B_i, 1], [C_i, 1]] = (B_i − O_i) × (C_i − B_i)` (quadratic);
/// zero iff `O_i, B_i, C_i` are collinear.
pub fn leg_polynomial<T: Ring>(k: &[T; CONFIGURATION_LEN], leg: usize) -> T {
    let o = ring_point(k, leg);
    let b = ring_point(k, 3 + leg);
    let c = ring_point(k, 6 + leg);
    algebra_cross(&algebra_difference(&o, &b), &algebra_difference(&b, &c))
}

/// The all-deformable metric of docs/theory.md §10 (Kapilavai and Nawratil, §6.3): base
/// plate, platform plate and six deformable bars,
///
/// `D²(K, K′) = (tri²(O) + tri²(C) + Σ_i seg²(O_iB_i) + Σ_i seg²(B_iC_i)) / 8`
///
/// with `seg²`, `tri²` of docs/theory.md §2 ([`crate::metric`]). Generic over [`Ring`].
pub fn distance_sq<T: Ring>(k: &[T; CONFIGURATION_LEN], k_prime: &[T; CONFIGURATION_LEN]) -> T {
    let p: [RingPoint<T>; 9] = std::array::from_fn(|j| ring_point(k, j));
    let q: [RingPoint<T>; 9] = std::array::from_fn(|j| ring_point(k_prime, j));
    let mut total = triangle_distance_sq([&p[0], &p[1], &p[2]], [&q[0], &q[1], &q[2]])
        + triangle_distance_sq([&p[6], &p[7], &p[8]], [&q[6], &q[7], &q[8]]);
    for leg in 0..3 {
        total = total
            + segment_distance_sq([&p[leg], &p[3 + leg]], [&q[leg], &q[3 + leg]])
            + segment_distance_sq([&p[3 + leg], &p[6 + leg]], [&q[3 + leg], &q[6 + leg]]);
    }
    total * T::from_f64(1.0 / 8.0)
}

/// `D(K, K′)`: square root of [`distance_sq`] (docs/theory.md §10).
pub fn distance(k: &[f64; CONFIGURATION_LEN], k_prime: &[f64; CONFIGURATION_LEN]) -> f64 {
    distance_sq(k, k_prime).max(0.0).sqrt()
}

impl RrrConfiguration {
    /// The 18-vector `(O1x, O1y, …, B1x, …, C3y)` of [`COORDINATE_NAMES`].
    pub fn to_array(&self) -> [f64; CONFIGURATION_LEN] {
        let points = self.points();
        std::array::from_fn(|j| points[j / 2][j % 2])
    }

    /// Inverse of [`to_array`](Self::to_array); the operation point is not part of the
    /// 18-vector and is given separately.
    pub fn from_array(k: &[f64; CONFIGURATION_LEN], operation_point: Point) -> Self {
        let p = |j: usize| Point::new(k[2 * j], k[2 * j + 1]);
        RrrConfiguration {
            operation_point,
            base: [p(0), p(1), p(2)],
            elbow: [p(3), p(4), p(5)],
            platform: [p(6), p(7), p(8)],
        }
    }
}

impl RrrDesign {
    /// Configuration at a complex pose `(x, y, φ)` with working modes `modes`, as the
    /// 18-vector of [`COORDINATE_NAMES`] (the seed configuration of the parameter
    /// homotopy, docs/theory.md §8.2). With `d = C − O`, `L² = d·d`,
    /// `k = (L² + b² − c²)/(2L²)`, `h = √(b²/L² − k²)` (principal branch), the elbow is
    /// `B = O + k d − σ h E d`, which for a real reachable pose equals
    /// [`leg_elbow`](Self::leg_elbow) (`k = (b/L) cos α`, `h = (b/L) sin α`).
    pub fn configuration_complex(
        &self,
        x: C64,
        y: C64,
        phi: C64,
        modes: &WorkingModes,
    ) -> [C64; CONFIGURATION_LEN] {
        let (s, c) = (phi.sin(), phi.cos());
        let mut out = [C64::new(0.0, 0.0); CONFIGURATION_LEN];
        for leg in 0..3 {
            let o = self.base[leg];
            let q = self.platform[leg];
            let cx = x + c * q.x - s * q.y;
            let cy = y + s * q.x + c * q.y;
            let (dx, dy) = (cx - o.x, cy - o.y);
            let l2 = dx * dx + dy * dy;
            let (b, cl) = (self.proximal[leg], self.distal[leg]);
            let k = (l2 + b * b - cl * cl) / (l2 * 2.0);
            let h = (C64::new(b * b, 0.0) / l2 - k * k).sqrt();
            let sigma = modes[leg].sign();
            out[2 * leg] = C64::new(o.x, 0.0);
            out[2 * leg + 1] = C64::new(o.y, 0.0);
            out[6 + 2 * leg] = o.x + k * dx + sigma * h * dy;
            out[6 + 2 * leg + 1] = o.y + k * dy - sigma * h * dx;
            out[12 + 2 * leg] = cx;
            out[12 + 2 * leg + 1] = cy;
        }
        out
    }

    /// [`configuration_complex`](Self::configuration_complex) along a branch: the
    /// signed elbow heights `g_i = σ_i h_i` (`B = O + k d + g (d_y, −d_x)`) are the
    /// square roots of `h_i² = b²/L² − k²` nearest `reference`, so that a caller can
    /// follow one branch continuously along a complex motion. With the pose's
    /// derivative `velocity` (`dx, dy, dφ` per unit of the motion parameter) also
    /// returns the configuration's derivative (`k′ = −(b² − c²) L²′/(2L⁴)`,
    /// `(h²)′ = −b² L²′/L⁴ − 2k k′`, `g′ = (h²)′/(2g)`), and the heights `g`.
    pub fn configuration_complex_on_branch(
        &self,
        [x, y, phi]: [C64; 3],
        [vx, vy, vphi]: [C64; 3],
        reference: &[C64; 3],
    ) -> ([C64; CONFIGURATION_LEN], [C64; CONFIGURATION_LEN], [C64; 3]) {
        let (s, c) = (phi.sin(), phi.cos());
        let zero = C64::new(0.0, 0.0);
        let (mut out, mut velocity, mut heights) = (
            [zero; CONFIGURATION_LEN],
            [zero; CONFIGURATION_LEN],
            [zero; 3],
        );
        for leg in 0..3 {
            let o = self.base[leg];
            let q = self.platform[leg];
            let cx = x + c * q.x - s * q.y;
            let cy = y + s * q.x + c * q.y;
            let vcx = vx + vphi * (-s * q.x - c * q.y);
            let vcy = vy + vphi * (c * q.x - s * q.y);
            let (dx, dy) = (cx - o.x, cy - o.y);
            let l2 = dx * dx + dy * dy;
            let vl2 = (dx * vcx + dy * vcy) * 2.0;
            let (b, cl) = (self.proximal[leg], self.distal[leg]);
            let k = (l2 + b * b - cl * cl) / (l2 * 2.0);
            let vk = -vl2 * (b * b - cl * cl) / (l2 * l2 * 2.0);
            let h2 = C64::new(b * b, 0.0) / l2 - k * k;
            let vh2 = -vl2 * (b * b) / (l2 * l2) - k * vk * 2.0;
            let root = h2.sqrt();
            let g = if (root - reference[leg]).norm() <= (root + reference[leg]).norm() {
                root
            } else {
                -root
            };
            let vg = vh2 / (g * 2.0);
            heights[leg] = g;
            out[2 * leg] = C64::new(o.x, 0.0);
            out[2 * leg + 1] = C64::new(o.y, 0.0);
            out[6 + 2 * leg] = o.x + k * dx + g * dy;
            out[6 + 2 * leg + 1] = o.y + k * dy - g * dx;
            out[12 + 2 * leg] = cx;
            out[12 + 2 * leg + 1] = cy;
            velocity[6 + 2 * leg] = vk * dx + k * vcx + vg * dy + g * vcy;
            velocity[6 + 2 * leg + 1] = vk * dy + k * vcy - vg * dx - g * vcx;
            velocity[12 + 2 * leg] = vcx;
            velocity[12 + 2 * leg + 1] = vcy;
        }
        (out, velocity, heights)
    }
}

// ---------------------------------------------------------------------------------
// Motions and the working modes along them
// ---------------------------------------------------------------------------------

/// Motions of the 3-RRR platform: the same type as the 3-RPR's (Kapilavai and Nawratil,
/// §5.2, Eq. 64; docs/theory.md §1.2): an explicit list of poses `[x, y, φ]` or an
/// analytic motion (polynomial plus cosine terms per coordinate), evaluable at complex τ.
pub type RrrMotion = rpr::Motion;

/// Circular translation of the operation point, `x = x_c + r cos τ`, `y = y_c + r sin τ`,
/// `φ` fixed, on `tau_range` (docs/theory.md §10 example motion).
pub fn circular_translation(
    center: Point,
    radius: f64,
    phi: f64,
    tau_range: [f64; 2],
) -> RrrMotion {
    rpr::Motion::Analytic(AnalyticMotion {
        tau_range,
        x: MotionCoordinate {
            polynomial: vec![center.x],
            cosines: vec![CosineTerm {
                amplitude: radius,
                frequency: 1.0,
                phase: 0.0,
            }],
        },
        y: MotionCoordinate {
            polynomial: vec![center.y],
            cosines: vec![CosineTerm {
                amplitude: radius,
                frequency: 1.0,
                phase: -PI / 2.0,
            }],
        },
        phi: MotionCoordinate::polynomial(vec![phi]),
    })
}

/// Errors of a 3-RRR moving along a motion.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TrajectoryError {
    /// The motion itself is invalid (names the field).
    #[error("motion: {0}")]
    Motion(String),
    /// Inverse kinematics fails at some τ of the motion.
    #[error("motion leaves the workspace at tau = {tau}: {reason}")]
    OutsideWorkspace {
        /// The parameter value.
        tau: f64,
        /// The IK error (names the leg).
        reason: RrrError,
    },
}

/// Grid intervals of the inverse-kinematics check of an analytic motion (after the exact
/// reach check of [`rrr_reach::leg_reach`]).
const CHECK_INTERVALS: usize = 4096;

/// A 3-RRR design moving along a motion, with the working modes continued along it.
///
/// The working modes `initial_modes` hold at the start of the motion. With a fixed
/// working mode the leg determinant `(B_i − O_i) × (C_i − B_i) = σ_i b L sin α` never
/// changes sign; a leg meets its leg singularity only where `L = |C_i − O_i|` touches a
/// boundary of its ring `[|b − c|, b + c]` (stretched, folded, or `C_i` through `O_i`
/// when `b = c`). The configuration is continued analytically along the motion: the mode
/// of leg i flips exactly where its determinant changes sign, i.e. at a zero of odd
/// `m` of the ring factors (order `2m`, [`rrr_reach`]); a leg that only comes close to
/// the boundary, or touches it with even `m` (e.g. `L = (b + c) − a(τ − τ₀)⁴`), keeps its
/// mode. The reach is checked exactly on the whole motion ([`rrr_reach::leg_reach`]).
/// Explicit pose lists keep the given modes (no continuation is possible between
/// isolated poses), as does a trajectory built with [`RrrTrajectory::holding_modes`].
#[derive(Debug, Clone, PartialEq)]
pub struct RrrTrajectory {
    design: RrrDesign,
    initial_modes: WorkingModes,
    motion: RrrMotion,
    switches: [Vec<f64>; 3],
}

impl RrrTrajectory {
    /// Validates the motion, checks the reach of every leg on the whole motion (analytic:
    /// exactly, [`rrr_reach::leg_reach`]; pose list: at every pose), finds the τ where a
    /// working mode flips (type documentation) and checks the inverse kinematics (on a
    /// grid of analytic motions).
    pub fn new(
        design: RrrDesign,
        initial_modes: WorkingModes,
        motion: RrrMotion,
    ) -> Result<Self, TrajectoryError> {
        motion
            .validate()
            .map_err(|e| TrajectoryError::Motion(e.to_string()))?;
        let mut switches: [Vec<f64>; 3] = Default::default();
        if let rpr::Motion::Analytic(analytic) = &motion {
            for (leg, leg_switches) in switches.iter_mut().enumerate() {
                let geometry = rrr_reach::LegGeometry {
                    base: [design.base[leg].x, design.base[leg].y],
                    platform: [design.platform[leg].x, design.platform[leg].y],
                    proximal: design.proximal[leg],
                    distal: design.distal[leg],
                };
                match rrr_reach::leg_reach(&geometry, analytic) {
                    Ok(touches) => {
                        *leg_switches = touches
                            .iter()
                            .filter(|t| t.flips())
                            .map(|t| t.tau)
                            .collect();
                    }
                    Err(violation) => {
                        let tau = violation.tau;
                        let pose = motion.pose(tau).unwrap_or(rpr::Pose::new(0.0, 0.0, 0.0));
                        let joint =
                            design.platform_joints(&RrrPose::new(pose.x, pose.y, pose.phi))[leg];
                        let (b, c) = (design.proximal[leg], design.distal[leg]);
                        return Err(TrajectoryError::OutsideWorkspace {
                            tau,
                            reason: RrrError::Unreachable {
                                leg,
                                distance: (joint - design.base[leg]).norm(),
                                min_reach: (b - c).abs(),
                                max_reach: b + c,
                            },
                        });
                    }
                }
            }
        }
        let trajectory = RrrTrajectory {
            design,
            initial_modes,
            motion,
            switches,
        };
        let taus: Vec<f64> = match &trajectory.motion {
            rpr::Motion::Analytic(_) => {
                let [lo, hi] = trajectory.motion.tau_range();
                (0..=CHECK_INTERVALS)
                    .map(|j| lo + (hi - lo) * j as f64 / CHECK_INTERVALS as f64)
                    .collect()
            }
            rpr::Motion::Poses(list) => (0..list.poses.len()).map(|j| j as f64).collect(),
        };
        for tau in taus {
            if let Err(reason) = trajectory.configuration(tau) {
                return Err(TrajectoryError::OutsideWorkspace { tau, reason });
            }
        }
        Ok(trajectory)
    }

    /// The same trajectory with the initial working modes held along the whole motion
    /// (no flip at leg singularities).
    pub fn holding_modes(mut self) -> Self {
        self.switches = Default::default();
        self
    }

    /// The design.
    pub fn design(&self) -> &RrrDesign {
        &self.design
    }

    /// The motion.
    pub fn motion(&self) -> &RrrMotion {
        &self.motion
    }

    /// Working modes at the start of the motion.
    pub fn initial_modes(&self) -> WorkingModes {
        self.initial_modes
    }

    /// Per leg, the τ where it passes through a leg singularity (its mode flips there).
    pub fn leg_crossings(&self) -> &[Vec<f64>; 3] {
        &self.switches
    }

    /// Working modes at τ: the initial mode of leg i, flipped once per crossing `≤ τ`.
    pub fn modes_at(&self, tau: f64) -> WorkingModes {
        std::array::from_fn(|leg| {
            let flips = self.switches[leg].iter().filter(|&&t| t <= tau).count();
            if flips % 2 == 0 {
                self.initial_modes[leg]
            } else {
                self.initial_modes[leg].flipped()
            }
        })
    }

    /// Pose at τ (see [`rpr::Motion::pose`]); `None` outside a pose list.
    pub fn pose(&self, tau: f64) -> Option<RrrPose> {
        self.motion.pose(tau).map(|p| RrrPose::new(p.x, p.y, p.phi))
    }

    /// Configuration of the nine points at τ with the continued working modes. Where a
    /// platform joint coincides with its base joint (`b = c`, [`RrrError::DegenerateLeg`])
    /// the elbow of an analytic motion is the limit of the continued configuration from
    /// the left (from the right at the start of the motion): `θ = atan2(u) − σ·π/2` with
    /// `u` the direction of `C_i − O_i` as it tends to 0 (`∓(C_i − O_i)′`, computed by a
    /// complex step) and σ the mode on that side.
    pub fn configuration(&self, tau: f64) -> Result<RrrConfiguration, RrrError> {
        let pose = self.pose(tau).ok_or(RrrError::NoPose { tau })?;
        match self.design.inverse_kinematics(&pose, &self.modes_at(tau)) {
            Err(RrrError::DegenerateLeg { leg }) => self.configuration_on_fold(tau, &pose, leg),
            other => other,
        }
    }

    /// [`configuration`](Self::configuration) where leg `leg` is degenerate.
    fn configuration_on_fold(
        &self,
        tau: f64,
        pose: &RrrPose,
        degenerate: usize,
    ) -> Result<RrrConfiguration, RrrError> {
        let rpr::Motion::Analytic(_) = &self.motion else {
            return Err(RrrError::DegenerateLeg { leg: degenerate });
        };
        let [lo, hi] = self.motion.tau_range();
        let eta = 1e-7 * (hi - lo);
        // From the left, except at the start of the motion.
        let side = if tau - eta >= lo { -1.0 } else { 1.0 };
        let modes = self.modes_at(tau + side * eta);
        let platform = self.design.platform_joints(pose);
        let mut elbow = [Point::zeros(); 3];
        for leg in 0..3 {
            if leg != degenerate {
                elbow[leg] = self.design.leg_elbow(leg, platform[leg], modes[leg])?;
                continue;
            }
            let joint = |t: C64| -> Option<[C64; 2]> {
                let [x, y, phi] = self.motion.pose_complex(t)?;
                let q = self.design.platform[leg];
                let (s, c) = (phi.sin(), phi.cos());
                Some([x + c * q.x - s * q.y, y + s * q.x + c * q.y])
            };
            let step = 1e-20;
            let derivative = joint(C64::new(tau, step))
                .map(|[x, y]| Point::new(x.im / step, y.im / step))
                .unwrap_or_else(Point::zeros);
            let scale = self.design.proximal[leg] + self.design.distal[leg];
            let direction = if derivative.norm() > 1e-9 * scale / (hi - lo) {
                derivative * side
            } else {
                // A zero of higher order: the direction at a small distance.
                let t = tau + side * 1e-4 * (hi - lo);
                let p = self.pose(t).ok_or(RrrError::NoPose { tau: t })?;
                self.design.platform_joints(&p)[leg] - self.design.base[leg]
            };
            let theta =
                direction.y.atan2(direction.x) - modes[leg].sign() * std::f64::consts::FRAC_PI_2;
            elbow[leg] = self.design.base[leg]
                + self.design.proximal[leg] * Point::new(theta.cos(), theta.sin());
        }
        Ok(RrrConfiguration {
            operation_point: pose.point(),
            base: self.design.base,
            elbow,
            platform,
        })
    }

    /// Configuration at complex τ (analytic motions; `None` for pose lists) with the modes
    /// at `Re τ`, see [`RrrDesign::configuration_complex`].
    pub fn configuration_complex(&self, tau: C64) -> Option<[C64; CONFIGURATION_LEN]> {
        let [x, y, phi] = self.motion.pose_complex(tau)?;
        Some(
            self.design
                .configuration_complex(x, y, phi, &self.modes_at(tau.re)),
        )
    }
}

// ---------------------------------------------------------------------------------
// Built-in example (systems/rrr_example_*.json)
// ---------------------------------------------------------------------------------

/// The built-in example design (also `systems/rrr_example_design.json`): the symmetric
/// design of [`RrrDesign::symmetric`] with base radius 1, platform radius 0.4 and all
/// links 0.8 (proximal = distal, so leg 1 can fold through its base joint).
pub fn example_design() -> RrrDesign {
    RrrDesign::symmetric(1.0, 0.4, 0.8, 0.8)
        .unwrap_or_else(|_| unreachable!("the example design is valid"))
}

/// Working modes of the example at τ = 0: all positive.
pub const EXAMPLE_MODES: WorkingModes = POSITIVE_MODES;

/// The built-in example motion (also `systems/rrr_example_motion.json`): the circular
/// translation `x = 0.15 + 0.25 cos τ`, `y = 0.4 + 0.25 sin τ`, `φ = 0`, τ ∈ [0, 2π].
/// Platform joint C_1 runs on the circle of radius 0.25 about `(0.15, 0.8)`, which passes
/// through `O_1 = (0, 1)` at `τ₁ = atan2(0.8, −0.6) ≈ 2.2143` (leg-1 singularity, folded
/// leg); the parallel determinant changes sign near τ ≈ 0.111 and τ ≈ 5.52
/// (`systems/rrr_example_README.md`, checked by the tests).
pub fn example_motion() -> RrrMotion {
    circular_translation(Point::new(0.15, 0.4), 0.25, 0.0, [0.0, 2.0 * PI])
}

/// The example trajectory: [`example_design`], [`EXAMPLE_MODES`], [`example_motion`].
pub fn example_trajectory() -> RrrTrajectory {
    RrrTrajectory::new(example_design(), EXAMPLE_MODES, example_motion())
        .unwrap_or_else(|e| unreachable!("the example motion stays in the workspace: {e}"))
}

//! The planar 3-RRR parallel manipulator: design, pose, inverse kinematics with an explicit
//! working mode per leg, and the configuration of its nine joint points (SPEC Part C, D.1, D.5;
//! seed 003 §II).
//!
//! # Model
//!
//! Leg `i` (0-based in code, 1-based in the SPEC and the seeds) is the chain
//! `O_i —(proximal link)— B_i —(distal link)— C_i`:
//! - `O_i`: base revolute joint, fixed frame;
//! - `B_i`: elbow (middle revolute joint), `|B_i − O_i| = proximal_i`;
//! - `C_i`: platform revolute joint, `|C_i − B_i| = distal_i`.
//!
//! The platform joints are given in the moving frame, whose origin is the operation point
//! `P`; at pose `(x, y, φ)` they are `C_i = P + R(φ)·c_i^moving`, `P = (x, y)`.
//!
//! Joint angles (seed 003 Eqs. 2–3): `θ_i = atan2(B_i − O_i)` (absolute direction of the
//! proximal link) and `ψ_i = atan2(C_i − B_i)` (absolute direction of the distal link), both
//! measured from the x-axis.
//!
//! # Working modes
//!
//! Each leg reaches a platform joint `C_i` with two elbow postures, mirror images about the
//! line `O_iC_i`. [`ElbowMode::Positive`] (σ_i = +1) is the posture with
//! `(B_i − O_i) × (C_i − B_i) > 0` (the distal link turns counter-clockwise from the proximal
//! link), [`ElbowMode::Negative`] (σ_i = −1) the other one. The seed's "positive working
//! modes" are taken to be σ = (+1, +1, +1).
//!
//! # Symmetric family of seed 003
//!
//! Seed 003 writes the loop closure (its Eqs. 2–3) as
//! `x_p = b cos θ_i + c cos ψ_i + a cos(φ + γ_i) + x_oi`, so in its notation
//! **`a` = distance from P to each platform joint C_i (platform circumradius), `b` = |O_iB_i|
//! (proximal link), `c` = |B_iC_i| (distal link)**; its design vector `[a b c]` is optimised
//! under `a + b + c ≤ λ`. [`RrrDesign::symmetric`] maps `(R, a, b, c)` to: base joints on the
//! circle of radius `R` about the origin at angles 90°, 210°, 330°; platform joints on the circle
//! of radius `a` about P at the same angles in the moving frame (so at φ = 0 every leg points
//! radially); every proximal link `b`, every distal link `c`. The base radius `R` is not given
//! by the seed and is a free choice of the example geometry.

use nalgebra::Vector2;
use std::f64::consts::PI;
use thiserror::Error;

/// Plane point or vector in the design's length unit.
pub type Point = Vector2<f64>;

/// Errors of the 3-RRR model; each names the offending field.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RrrError {
    /// A number that must be finite is NaN or infinite.
    #[error("{field} must be finite, got {value}")]
    NonFinite {
        /// Field path, e.g. `base[1].x` or `pose.phi`.
        field: String,
        /// The offending value.
        value: f64,
    },
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

/// The seed's "positive working modes": σ = (+1, +1, +1).
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
            if !value.is_finite() {
                return Err(RrrError::NonFinite {
                    field: field.to_string(),
                    value,
                });
            }
        }
        Ok(())
    }
}

/// A validated general planar 3-RRR design (SPEC Part C / D.5).
#[derive(Debug, Clone, PartialEq)]
pub struct RrrDesign {
    base: [Point; 3],
    proximal: [f64; 3],
    distal: [f64; 3],
    platform: [Point; 3],
}

fn check_point(field: &str, p: Point) -> Result<(), RrrError> {
    for (axis, value) in [("x", p.x), ("y", p.y)] {
        if !value.is_finite() {
            return Err(RrrError::NonFinite {
                field: format!("{field}.{axis}"),
                value,
            });
        }
    }
    Ok(())
}

fn check_length(field: &str, value: f64) -> Result<(), RrrError> {
    if !value.is_finite() {
        return Err(RrrError::NonFinite {
            field: field.to_string(),
            value,
        });
    }
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
    /// Errors: any non-finite number, a non-positive length, or two coincident base (or
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

    /// Seed-003 style symmetric design (see the module documentation): base joints on the
    /// circle of radius `base_radius` at 90°, 210°, 330°; platform joints at distance
    /// `platform_radius` (seed `a`) from P at the same angles in the moving frame; proximal
    /// links `proximal` (seed `b`), distal links `distal` (seed `c`).
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
    /// The nine points in the order `O_1, O_2, O_3, B_1, B_2, B_3, C_1, C_2, C_3` (SPEC Part C).
    pub fn points(&self) -> [Point; 9] {
        let mut out = [Point::zeros(); 9];
        out[..3].copy_from_slice(&self.base);
        out[3..6].copy_from_slice(&self.elbow);
        out[6..].copy_from_slice(&self.platform);
        out
    }

    /// Proximal vector `b_i = B_i − O_i` (seed 003 notation).
    pub fn proximal_vector(&self, leg: usize) -> Point {
        self.elbow[leg] - self.base[leg]
    }

    /// Distal vector `c_i = C_i − B_i` (seed 003 notation).
    pub fn distal_vector(&self, leg: usize) -> Point {
        self.platform[leg] - self.elbow[leg]
    }

    /// Platform vector `a_i = P − C_i` (seed 003 notation).
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

    /// Leg-singularity determinant `det[[O_i,1],[B_i,1],[C_i,1]] = b_i × c_i` (SPEC Part C):
    /// zero iff `O_i, B_i, C_i` are collinear (Type I of seed 003), sign = working mode.
    pub fn leg_determinant(&self, leg: usize) -> f64 {
        cross(self.proximal_vector(leg), self.distal_vector(leg))
    }

    /// Parallel-singularity polynomial of SPEC Part C: `S` of A.2 with `(a_i, b_i) → (B_i, C_i)`,
    /// `det [ C_i − B_i , B_i × C_i ]_{i=1..3}`; zero iff the lines `B_iC_i` are concurrent or
    /// parallel.
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

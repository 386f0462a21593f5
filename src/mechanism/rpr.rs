//! The 3-RPR planar parallel manipulator (docs/theory.md §1.1, §1.3, §4).
//!
//! A design is three base anchors `A_i` (fixed frame) and three platform anchors `P_i`
//! (moving frame). A pose `(x, y, φ)` places the platform anchors at
//! `b_i = (x, y) + R(φ) P_i`; the configuration `K = (a_1, a_2, a_3, b_1, b_2, b_3) ∈ R¹²`
//! collects all six points in the fixed frame (`a_i = A_i`).
//!
//! The polynomial formulas ([`singularity_polynomial`], [`collinearity_platform`],
//! [`collinearity_base`], [`reconstruct_third_point`]) are generic over
//! [`Ring`], so the same code evaluates numbers (`f64`, [`C64`]) and builds the
//! symbolic Lagrangians of the distance problems.
//!
//! Motions (Kapilavai and Nawratil, §5.2, Eq. 64; docs/theory.md §1.2) are either an
//! explicit list of poses or an analytic motion `τ ↦ (x(τ), y(τ), φ(τ))` on an interval,
//! each coordinate a polynomial plus cosine terms, which can be evaluated at complex τ
//! (the seed of the parameter homotopy is the motion at a random complex τ*).

use crate::C64;
use crate::algebra::{Cartesian, Plane, Point, Ring, difference, dot};
use crate::mechanism::InputNumberError;
pub use crate::mechanism::check_input_number;
use num_complex::ComplexFloat;
use serde::{Deserialize, Serialize};
use std::iter::Sum;
use std::ops::{Add, Mul};
use thiserror::Error;

/// Errors of 3-RPR designs and motions; every message names the offending field.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RprError {
    /// A number is NaN, infinite or beyond ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE).
    #[error(transparent)]
    Number(#[from] InputNumberError),
    /// All three anchors of a part coincide: `S ≡ 0` (architecture singular), and no
    /// labelling gives the rigid-part representation two distinct reference anchors.
    #[error(
        "{part}: collapsed to a point (all three anchors coincide): the design is singular at every pose"
    )]
    Collapsed {
        /// `base` or `platform`.
        part: &'static str,
    },
    /// A field of a motion is invalid.
    #[error("{field}: {reason}")]
    InvalidMotion {
        /// The field, e.g. `tau_range` or `poses[3][2]`.
        field: String,
        /// What is wrong.
        reason: String,
    },
}

/// Relative tolerance below which two anchors count as coincident: distance
/// `≤ COINCIDENCE_TOLERANCE · max(1, largest |coordinate| of the design)`.
pub const COINCIDENCE_TOLERANCE: f64 = 1e-9;

/// A 3-RPR design: base anchors `A_i` (fixed frame) and platform anchors `P_i`
/// (moving frame), docs/theory.md §1.1.
///
/// Invariants: all coordinates finite, and neither part collapsed to a point. Two
/// coincident anchors of one part are a legitimate robot (Kapilavai and
/// Nawratil, Lemma 2: a pair of distinct anchors always exists); the
/// sub-problems of a rigid part take their reference pair from
/// [`Design::conditioned_labelling`], not from the user's labels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "DesignFields", into = "DesignFields")]
pub struct Design {
    base: [Point<f64>; 3],
    platform: [Point<f64>; 3],
}

/// Plain serde form of a [`Design`]: `{"base": [[x,y],…], "platform": [[x,y],…]}`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct DesignFields {
    /// Base anchors `A_1, A_2, A_3` in the fixed frame.
    pub base: [Point<f64>; 3],
    /// Platform anchors `P_1, P_2, P_3` in the moving frame.
    pub platform: [Point<f64>; 3],
}

impl TryFrom<DesignFields> for Design {
    type Error = RprError;
    fn try_from(fields: DesignFields) -> Result<Self, Self::Error> {
        Design::new(fields.base, fields.platform)
    }
}

impl From<Design> for DesignFields {
    fn from(design: Design) -> Self {
        DesignFields {
            base: design.base,
            platform: design.platform,
        }
    }
}

/// Every anchor coordinate finite and within ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE) (checked before
/// anything else, so a huge coordinate is never mistaken for coincident anchors).
fn check_anchor_numbers(
    base: &[Point<f64>; 3],
    platform: &[Point<f64>; 3],
) -> Result<(), RprError> {
    for (part, points) in [("base", base), ("platform", platform)] {
        for (i, point) in points.iter().enumerate() {
            for (axis, value) in ["x", "y"].iter().zip(point) {
                check_input_number(|| format!("{part}[{i}].{axis}"), *value)?;
            }
        }
    }
    Ok(())
}

/// Checks one pose: `x`, `y`, `φ` finite and within ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE); errors
/// name `{field}[k]` (k = 0, 1, 2 for x, y, φ).
pub fn check_pose(field: &str, pose: Pose) -> Result<(), RprError> {
    for (k, v) in <[f64; 3]>::from(pose).iter().enumerate() {
        check_input_number(|| format!("{field}[{k}]"), *v)?;
    }
    Ok(())
}

fn check_part(part: &'static str, points: &[Point<f64>; 3], scale: f64) -> Result<(), RprError> {
    for (i, point) in points.iter().enumerate() {
        for (axis, value) in ["x", "y"].iter().zip(point) {
            if !value.is_finite() {
                return Err(InputNumberError::NotFinite {
                    field: format!("{part}[{i}].{axis}"),
                    value: *value,
                }
                .into());
            }
        }
    }
    let longest = edges(points).into_iter().fold(0.0f64, f64::max);
    if longest <= COINCIDENCE_TOLERANCE * scale {
        return Err(RprError::Collapsed { part });
    }
    Ok(())
}

/// Edge lengths `|p_2 − p_1|, |p_3 − p_2|, |p_1 − p_3|` of a part.
fn edges(points: &[Point<f64>; 3]) -> [f64; 3] {
    std::array::from_fn(|i| {
        let d = difference(&points[i], &points[(i + 1) % 3]);
        dot(&d, &d).sqrt()
    })
}

/// The six leg labellings, identity first: internal leg `i` is leg `labels[i]`.
const LABELLINGS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [1, 0, 2],
    [2, 1, 0],
];

impl Design {
    /// Validated design from base anchors `A_i` and platform anchors `P_i`.
    ///
    /// Errors name the field: `base[2].x: not a finite number (NaN)`,
    /// `base[1].x: 1e308 is outside ±1e12` (checked first),
    /// `platform: collapsed to a point …`.
    pub fn new(base: [Point<f64>; 3], platform: [Point<f64>; 3]) -> Result<Self, RprError> {
        check_anchor_numbers(&base, &platform)?;
        let scale = base
            .iter()
            .chain(platform.iter())
            .flatten()
            .filter(|v| v.is_finite())
            .fold(1.0_f64, |m, v| m.max(v.abs()));
        check_part("base", &base, scale)?;
        check_part("platform", &platform, scale)?;
        Ok(Design { base, platform })
    }

    /// The leg labelling under which the rigid parts' reference anchors (internal
    /// legs 1 and 2 of the point-based representation, docs/theory.md §4) are best
    /// conditioned: the largest `min` over the rigid parts of `|e| / longest edge`,
    /// `e` the reference edge (ties: the first of identity, the cyclic shifts, the
    /// transpositions). With a tiny `e` the shape constants `u, v` grow like `1/|e|`
    /// and the systems become ill-conditioned; a coincident pair gives no
    /// representation at all. Any triangle has two edges of at least half its
    /// longest, so some labelling gives both parts a ratio `≥ 1/2`. Internal leg `i`
    /// is the user's leg `labels[i]`; the identity when no part is rigid.
    pub fn conditioned_labelling(&self, rigid_base: bool, rigid_platform: bool) -> [usize; 3] {
        let ratio = |points: &[Point<f64>; 3], labels: &[usize; 3]| {
            let d = difference(&points[labels[0]], &points[labels[1]]);
            let longest = edges(points).into_iter().fold(0.0f64, f64::max);
            dot(&d, &d).sqrt() / longest
        };
        let quality = |labels: &[usize; 3]| {
            let mut q = f64::INFINITY;
            if rigid_base {
                q = q.min(ratio(&self.base, labels));
            }
            if rigid_platform {
                q = q.min(ratio(&self.platform, labels));
            }
            q
        };
        let mut best = LABELLINGS[0];
        for labels in LABELLINGS {
            // Strictly better by more than rounding, so that near-ties keep the
            // earlier (the user's own labelling first).
            if quality(&labels) > quality(&best) * (1.0 + 1e-12) {
                best = labels;
            }
        }
        best
    }

    /// The same robot with its legs relabelled: internal leg `i` is leg `labels[i]`.
    pub fn relabelled(&self, labels: [usize; 3]) -> Design {
        Design {
            base: labels.map(|i| self.base[i]),
            platform: labels.map(|i| self.platform[i]),
        }
    }

    /// The shortest edge of the base triangle (`platform == false`) or of the
    /// platform triangle over its longest: 0 where two anchors coincide, at least
    /// about 1/2 for a well-shaped triangle.
    pub fn edge_ratio(&self, platform: bool) -> f64 {
        let lengths = edges(if platform { &self.platform } else { &self.base });
        let longest = lengths.into_iter().fold(0.0f64, f64::max);
        lengths.into_iter().fold(f64::INFINITY, f64::min) / longest
    }

    /// Base anchors `A_1, A_2, A_3` (fixed frame).
    pub fn base(&self) -> &[Point<f64>; 3] {
        &self.base
    }

    /// Platform anchors `P_1, P_2, P_3` (moving frame).
    pub fn platform(&self) -> &[Point<f64>; 3] {
        &self.platform
    }

    /// The same manipulator seen from the platform: base and platform exchanged
    /// (`A_i ↔ P_i`). Used for viewpoint-free indices (MTI, MDS).
    pub fn exchanged(&self) -> Design {
        Design {
            base: self.platform,
            platform: self.base,
        }
    }

    /// Largest absolute anchor coordinate, at least 1: a length scale of the design.
    pub fn length_scale(&self) -> f64 {
        self.base
            .iter()
            .chain(self.platform.iter())
            .flatten()
            .fold(1.0_f64, |m, v| m.max(v.abs()))
    }

    /// Configuration at a pose: `a_i = A_i`, `b_i = (x, y) + R(φ) P_i` (docs/theory.md
    /// §1.1).
    pub fn configuration(&self, pose: Pose) -> Configuration {
        let (s, c) = pose.phi.sin_cos();
        let b = self
            .platform
            .map(|p| [pose.x + c * p[0] - s * p[1], pose.y + s * p[0] + c * p[1]]);
        Configuration { a: self.base, b }
    }

    /// Configuration at a complex pose, as the 12-vector
    /// `(a1x, a1y, a2x, a2y, a3x, a3y, b1x, b1y, b2x, b2y, b3x, b3y)`, with complex
    /// `cos φ`, `sin φ` (the seed configurations of the parameter homotopy,
    /// docs/theory.md §8).
    pub fn configuration_complex(&self, x: C64, y: C64, phi: C64) -> [C64; 12] {
        let (c, s) = (phi.cos(), phi.sin());
        let mut k = [C64::new(0.0, 0.0); 12];
        for i in 0..3 {
            k[2 * i] = C64::new(self.base[i][0], 0.0);
            k[2 * i + 1] = C64::new(self.base[i][1], 0.0);
            let [px, py] = self.platform[i];
            k[6 + 2 * i] = x + c * px - s * py;
            k[6 + 2 * i + 1] = y + s * px + c * py;
        }
        k
    }

    /// Shape constants `(u, v, |e|²)` of the rigid base (docs/theory.md §4).
    pub fn base_shape(&self) -> RigidShape {
        rigid_shape(&self.base[0], &self.base[1], &self.base[2])
    }

    /// Shape constants `(u, v, |e|²)` of the rigid platform (docs/theory.md §4); they do
    /// not change along a motion.
    pub fn platform_shape(&self) -> RigidShape {
        rigid_shape(&self.platform[0], &self.platform[1], &self.platform[2])
    }
}

/// A pose of the platform: translation `(x, y)` and rotation angle `φ` (radians).
///
/// Serialised as the array `[x, y, phi]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "[f64; 3]", into = "[f64; 3]")]
pub struct Pose {
    /// x of the platform frame origin.
    pub x: f64,
    /// y of the platform frame origin.
    pub y: f64,
    /// Rotation angle φ of the platform (radians).
    pub phi: f64,
}

impl Pose {
    /// Pose `(x, y, φ)`.
    pub fn new(x: f64, y: f64, phi: f64) -> Self {
        Pose { x, y, phi }
    }
}

impl From<[f64; 3]> for Pose {
    fn from(v: [f64; 3]) -> Self {
        Pose::new(v[0], v[1], v[2])
    }
}

impl From<Pose> for [f64; 3] {
    fn from(p: Pose) -> Self {
        [p.x, p.y, p.phi]
    }
}

/// A configuration `K = (a_1, a_2, a_3, b_1, b_2, b_3)`: all six anchor points in the
/// fixed frame (docs/theory.md §1.1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Configuration {
    /// Base anchors `a_i`.
    pub a: [Point<f64>; 3],
    /// Platform anchors `b_i`.
    pub b: [Point<f64>; 3],
}

impl Configuration {
    /// `(a1x, a1y, a2x, a2y, a3x, a3y, b1x, b1y, b2x, b2y, b3x, b3y)`.
    pub fn to_array(&self) -> [f64; 12] {
        let mut k = [0.0; 12];
        for i in 0..3 {
            k[2 * i] = self.a[i][0];
            k[2 * i + 1] = self.a[i][1];
            k[6 + 2 * i] = self.b[i][0];
            k[6 + 2 * i + 1] = self.b[i][1];
        }
        k
    }

    /// Inverse of [`Configuration::to_array`].
    pub fn from_array(k: &[f64; 12]) -> Self {
        let p = |j: usize| [k[j], k[j + 1]];
        Configuration {
            a: [p(0), p(2), p(4)],
            b: [p(6), p(8), p(10)],
        }
    }

    /// The singularity polynomial S(K) (Kapilavai and Nawratil, Eq. 6; docs/theory.md
    /// §1.3).
    pub fn singularity(&self) -> f64 {
        singularity_polynomial(&self.to_array())
    }
}

fn point<T: Ring>(k: &[T; 12], j: usize) -> Point<T> {
    [k[j].clone(), k[j + 1].clone()]
}

/// The singularity polynomial (Kapilavai and Nawratil, Eq. 6; docs/theory.md §1.3),
/// degree 4:
///
/// `S(K) = det[ b_i − a_i | a_i × b_i ]_{i=1..3}` (rows: non-normalised Plücker
/// coordinates of the leg lines). `S = 0` iff the three leg lines are concurrent or
/// parallel; `S = l_1 l_2 l_3 det J` with J the inverse Jacobian of unit leg lines.
pub fn singularity_polynomial<T: Ring>(k: &[T; 12]) -> T {
    singularity_polynomial_in::<Cartesian, T>(k)
}

/// [`singularity_polynomial`] with the six points in the coordinates `P` (e.g.
/// [`crate::algebra::Isotropic`]), expanded along the last column:
/// `S = m_1 (d_2 × d_3) − m_2 (d_1 × d_3) + m_3 (d_1 × d_2)` with `d_i = b_i − a_i`,
/// `m_i = a_i × b_i`.
pub fn singularity_polynomial_in<P: Plane<T>, T: Ring>(k: &[T; 12]) -> T {
    let leg = |i: usize| {
        let a = point(k, 2 * i);
        let b = point(k, 6 + 2 * i);
        (difference(&a, &b), P::cross(&a, &b))
    };
    let [(d1, m1), (d2, m2), (d3, m3)] = [leg(0), leg(1), leg(2)];
    m1 * P::cross(&d2, &d3) - m2 * P::cross(&d1, &d3) + m3 * P::cross(&d1, &d2)
}

fn collinearity<P: Plane<T>, T: Ring>(p: [Point<T>; 3]) -> T {
    let [p1, p2, p3] = p;
    P::cross(&difference(&p1, &p2), &difference(&p1, &p3))
}

/// Collinearity polynomial of the platform (Kapilavai and Nawratil, Eq. 31;
/// docs/theory.md §1.4): `C_p(K) = det[[b_1x, b_1y, 1], [b_2x, b_2y, 1], [b_3x, b_3y, 1]]
/// = (b_2 − b_1) × (b_3 − b_1)` (twice the signed area of the platform triangle).
pub fn collinearity_platform<T: Ring>(k: &[T; 12]) -> T {
    collinearity_platform_in::<Cartesian, T>(k)
}

/// [`collinearity_platform`] with the points in the coordinates `P`.
pub fn collinearity_platform_in<P: Plane<T>, T: Ring>(k: &[T; 12]) -> T {
    collinearity::<P, T>([point(k, 6), point(k, 8), point(k, 10)])
}

/// Collinearity polynomial of the base (Kapilavai and Nawratil, Eq. 31; docs/theory.md
/// §1.4): `C_b(K) = det[[a_1x, a_1y, 1], [a_2x, a_2y, 1], [a_3x, a_3y, 1]]
/// = (a_2 − a_1) × (a_3 − a_1)`.
pub fn collinearity_base<T: Ring>(k: &[T; 12]) -> T {
    collinearity_base_in::<Cartesian, T>(k)
}

/// [`collinearity_base`] with the points in the coordinates `P`.
pub fn collinearity_base_in<P: Plane<T>, T: Ring>(k: &[T; 12]) -> T {
    collinearity::<P, T>([point(k, 0), point(k, 2), point(k, 4)])
}

/// Shape constants of a rigid triangle `p_1 p_2 p_3` (Kapilavai and Nawratil, Eqs. 23–26;
/// docs/theory.md §4): with `e = p_2 − p_1`, `u = ((p_3 − p_1)·e)/|e|²`,
/// `v = ((p_3 − p_1)·Ee)/|e|²`, `r2 = |e|²`, so that `p_3 = p_1 + u e + v E e`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RigidShape {
    /// Dimensionless coordinate of `p_3 − p_1` along `e`.
    pub u: f64,
    /// Dimensionless coordinate of `p_3 − p_1` along `E e`.
    pub v: f64,
    /// `|e|² = |p_2 − p_1|²`.
    pub r2: f64,
}

/// The rigid shape constants of docs/theory.md §4. Requires `p_1 ≠ p_2` (guaranteed for the
/// anchors of a validated [`Design`]); for `p_1 = p_2` the result is not finite.
pub fn rigid_shape(p1: &Point<f64>, p2: &Point<f64>, p3: &Point<f64>) -> RigidShape {
    let e = difference(p1, p2);
    let r2 = dot(&e, &e);
    let w = difference(p1, p3);
    let ee = rotate_quarter(&e);
    RigidShape {
        u: dot(&w, &e) / r2,
        v: dot(&w, &ee) / r2,
        r2,
    }
}

/// `E u`: rotation by +90°, `E = [[0, −1], [1, 0]]`.
pub fn rotate_quarter<T: Ring>(u: &Point<T>) -> Point<T> {
    Cartesian::rotate_quarter(u)
}

/// Third point of a rigid triangle from the first two (docs/theory.md §4):
/// `p_3 = p_1 + u (p_2 − p_1) + v E (p_2 − p_1)`.
pub fn reconstruct_third_point<T: Ring>(p1: &Point<T>, p2: &Point<T>, u: T, v: T) -> Point<T> {
    reconstruct_third_point_in::<Cartesian, T>(p1, p2, u, v)
}

/// [`reconstruct_third_point`] with the points in the coordinates `P`.
pub fn reconstruct_third_point_in<P: Plane<T>, T: Ring>(
    p1: &Point<T>,
    p2: &Point<T>,
    u: T,
    v: T,
) -> Point<T> {
    let e = difference(p1, p2);
    let ee = P::rotate_quarter(&e);
    [
        p1[0].clone() + u.clone() * e[0].clone() + v.clone() * ee[0].clone(),
        p1[1].clone() + u * e[1].clone() + v * ee[1].clone(),
    ]
}

/// Rigidity constraint of docs/theory.md §4: `g(p_1, p_2) = |p_2 − p_1|² − r2`.
pub fn rigidity_constraint<T: Ring>(p1: &Point<T>, p2: &Point<T>, r2: T) -> T {
    rigidity_constraint_in::<Cartesian, T>(p1, p2, r2)
}

/// [`rigidity_constraint`] with the points in the coordinates `P`.
pub fn rigidity_constraint_in<P: Plane<T>, T: Ring>(p1: &Point<T>, p2: &Point<T>, r2: T) -> T {
    let e = difference(p1, p2);
    P::dot(&e, &e) - r2
}

// ---------------------------------------------------------------------------------
// Motions
// ---------------------------------------------------------------------------------

/// One cosine term `amplitude · cos(frequency · τ + phase)` of a motion coordinate.
///
/// Serialised as `[amplitude, frequency, phase]`; a sine is the phase `−π/2`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "[f64; 3]", into = "[f64; 3]")]
pub struct CosineTerm {
    /// Amplitude A.
    pub amplitude: f64,
    /// Angular frequency ω.
    pub frequency: f64,
    /// Phase θ (radians).
    pub phase: f64,
}

impl From<[f64; 3]> for CosineTerm {
    fn from(v: [f64; 3]) -> Self {
        CosineTerm {
            amplitude: v[0],
            frequency: v[1],
            phase: v[2],
        }
    }
}

impl From<CosineTerm> for [f64; 3] {
    fn from(t: CosineTerm) -> Self {
        [t.amplitude, t.frequency, t.phase]
    }
}

/// One coordinate of an analytic motion (entire in τ, so evaluable at complex τ):
///
/// `f(τ) = Σ_k polynomial[k] τ^k + Σ_j A_j cos(ω_j τ + θ_j)`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionCoordinate {
    /// Polynomial coefficients in ascending powers of τ (may be empty).
    #[serde(default)]
    pub polynomial: Vec<f64>,
    /// Cosine terms `[A, ω, θ]` (may be empty).
    #[serde(default)]
    pub cosines: Vec<CosineTerm>,
}

impl MotionCoordinate {
    /// The coordinate `c_0 + c_1 τ + …` (no cosine terms).
    pub fn polynomial(coefficients: Vec<f64>) -> Self {
        MotionCoordinate {
            polynomial: coefficients,
            cosines: Vec::new(),
        }
    }

    /// Value at real τ.
    pub fn value(&self, tau: f64) -> f64 {
        self.value_at(tau)
    }

    /// Value at complex τ (complex cosine).
    pub fn value_complex(&self, tau: C64) -> C64 {
        self.value_at(tau)
    }

    /// `f(τ)` in the scalar type of τ: Horner's scheme for the polynomial, then the
    /// cosine terms.
    fn value_at<T>(&self, tau: T) -> T
    where
        T: ComplexFloat + Add<f64, Output = T> + Sum,
        f64: Mul<T, Output = T>,
    {
        let poly = self
            .polynomial
            .iter()
            .rev()
            .fold(T::zero(), |acc, &c| acc * tau + c);
        let trig: T = self
            .cosines
            .iter()
            .map(|t| t.amplitude * (t.frequency * tau + t.phase).cos())
            .sum();
        poly + trig
    }

    /// Derivative `f′(τ) = Σ_k k·polynomial[k] τ^{k−1} − Σ_j A_j ω_j sin(ω_j τ + θ_j)`
    /// at complex τ.
    pub fn derivative_complex(&self, tau: C64) -> C64 {
        let poly = self
            .polynomial
            .iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(C64::new(0.0, 0.0), |acc, (k, c)| acc * tau + c * k as f64);
        let trig: C64 = self
            .cosines
            .iter()
            .map(|t| -t.amplitude * t.frequency * (t.frequency * tau + t.phase).sin())
            .sum();
        poly + trig
    }

    fn validate(&self, field: &str) -> Result<(), RprError> {
        for (k, c) in self.polynomial.iter().enumerate() {
            check_input_number(|| format!("{field}.polynomial[{k}]"), *c)?;
        }
        for (j, t) in self.cosines.iter().enumerate() {
            for (k, v) in <[f64; 3]>::from(*t).iter().enumerate() {
                check_input_number(|| format!("{field}.cosines[{j}][{k}]"), *v)?;
            }
        }
        Ok(())
    }
}

/// An analytic 1-parametric motion `τ ↦ (x(τ), y(τ), φ(τ))` on `tau_range`
/// (Kapilavai and Nawratil, Eq. 64; docs/theory.md §1.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalyticMotion {
    /// `[τ_start, τ_end]`, `τ_start < τ_end`.
    pub tau_range: [f64; 2],
    /// x(τ).
    pub x: MotionCoordinate,
    /// y(τ).
    pub y: MotionCoordinate,
    /// φ(τ) in radians.
    pub phi: MotionCoordinate,
}

/// An explicit list of poses (`{"poses": [[x, y, phi], …]}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseList {
    /// The poses, used as given; pose `j` has parameter `τ = j`.
    pub poses: Vec<Pose>,
}

/// A 1-parametric motion of the platform (docs/theory.md §1.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Motion {
    /// Explicit list of poses.
    Poses(PoseList),
    /// Analytic motion, evaluable at complex τ.
    Analytic(AnalyticMotion),
}

/// A pose of a sampled motion together with its parameter value τ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledPose {
    /// Motion parameter τ (the index for explicit pose lists).
    pub tau: f64,
    /// The pose.
    pub pose: Pose,
}

impl Motion {
    /// Checks that every number is finite and within ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE), a
    /// non-empty pose list and `τ_start < τ_end`; errors name the field.
    pub fn validate(&self) -> Result<(), RprError> {
        match self {
            Motion::Poses(list) => {
                if list.poses.is_empty() {
                    return Err(RprError::InvalidMotion {
                        field: "poses".into(),
                        reason: "the pose list is empty".into(),
                    });
                }
                for (j, pose) in list.poses.iter().enumerate() {
                    check_pose(&format!("poses[{j}]"), *pose)?;
                }
                Ok(())
            }
            Motion::Analytic(m) => {
                let [lo, hi] = m.tau_range;
                check_input_number(|| "tau_range[0]".into(), lo)?;
                check_input_number(|| "tau_range[1]".into(), hi)?;
                if lo >= hi {
                    return Err(RprError::InvalidMotion {
                        field: "tau_range".into(),
                        reason: format!(
                            "must be two finite numbers with start < end, got [{lo}, {hi}]"
                        ),
                    });
                }
                m.x.validate("x")?;
                m.y.validate("y")?;
                m.phi.validate("phi")
            }
        }
    }

    /// Pose at real τ for an analytic motion; for a pose list, the pose with index
    /// `round(τ)` if that is in range.
    pub fn pose(&self, tau: f64) -> Option<Pose> {
        match self {
            Motion::Analytic(m) => {
                Some(Pose::new(m.x.value(tau), m.y.value(tau), m.phi.value(tau)))
            }
            Motion::Poses(list) => {
                let j = tau.round();
                if j >= 0.0 && (j as usize) < list.poses.len() {
                    Some(list.poses[j as usize])
                } else {
                    None
                }
            }
        }
    }

    /// Complex pose `(x(τ), y(τ), φ(τ))` at complex τ; `None` for explicit pose lists,
    /// which have no analytic continuation (callers then interpolate in parameter
    /// space instead).
    pub fn pose_complex(&self, tau: C64) -> Option<[C64; 3]> {
        self.each_coordinate(|c| c.value_complex(tau))
    }

    /// `d(x, y, φ)/dτ` at complex τ (analytic motions only).
    pub fn pose_derivative_complex(&self, tau: C64) -> Option<[C64; 3]> {
        self.each_coordinate(|c| c.derivative_complex(tau))
    }

    /// `f` of the coordinates `x, y, φ` of an analytic motion; `None` for pose lists.
    fn each_coordinate(&self, f: impl Fn(&MotionCoordinate) -> C64) -> Option<[C64; 3]> {
        match self {
            Motion::Analytic(m) => Some([f(&m.x), f(&m.y), f(&m.phi)]),
            Motion::Poses(_) => None,
        }
    }

    /// The parameter interval: `tau_range`, or `[0, N−1]` for a list of N poses.
    pub fn tau_range(&self) -> [f64; 2] {
        match self {
            Motion::Analytic(m) => m.tau_range,
            Motion::Poses(list) => [0.0, list.poses.len().saturating_sub(1) as f64],
        }
    }

    /// `n` poses evenly spaced in τ over `tau_range` (both ends included; `n = 1` gives
    /// the start). Explicit pose lists are returned as given (`n` is ignored).
    pub fn sample(&self, n: usize) -> Vec<SampledPose> {
        match self {
            Motion::Poses(list) => list
                .poses
                .iter()
                .enumerate()
                .map(|(j, &pose)| SampledPose {
                    tau: j as f64,
                    pose,
                })
                .collect(),
            Motion::Analytic(m) => {
                let [lo, hi] = m.tau_range;
                (0..n)
                    .map(|j| {
                        let tau = if n <= 1 {
                            lo
                        } else {
                            lo + (hi - lo) * j as f64 / (n - 1) as f64
                        };
                        SampledPose {
                            tau,
                            pose: Pose::new(m.x.value(tau), m.y.value(tau), m.phi.value(tau)),
                        }
                    })
                    .collect()
            }
        }
    }
}

/// Checks the poses of a sampled analytic motion (finite coefficients can still give
/// huge or overflowing values at some τ): each `x`, `y`, `φ` finite and within
/// ±[`MAX_INPUT_MAGNITUDE`](super::MAX_INPUT_MAGNITUDE); errors name the coordinate and τ (`y(tau = 3.5)`).
pub fn check_sampled_poses(samples: &[SampledPose]) -> Result<(), RprError> {
    for s in samples {
        for (name, v) in ["x", "y", "phi"].iter().zip(<[f64; 3]>::from(s.pose)) {
            check_input_number(|| format!("{name}(tau = {})", s.tau), v)?;
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------
// Built-in example
// ---------------------------------------------------------------------------------

/// The built-in example design (also `systems/rpr_example_design.json`):
/// `A = (0,0), (10,0), (4,8)`, `P = (0,0), (3,0), (1,2)` (the design of the test vector of
/// docs/theory.md §9). The example design of Kapilavai and Nawratil (their Eq. 67) is not
/// given in the text available to us, so this one is ours.
pub fn example_design() -> Design {
    Design {
        base: [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]],
        platform: [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    }
}

/// The built-in example motion (also `systems/rpr_example_motion.json`), τ ∈ [−1, 4.5]:
///
/// `x = 4 + sin τ`, `y = 3.8 − 0.8 cos τ`, `φ = τ` (the rotation angle is the motion
/// parameter, as in the example of Kapilavai and Nawratil, §6, whose Eq. 68 is not given in
/// the text available to us). Along it S changes sign exactly twice, near τ ≈ −0.086 and
/// τ ≈ 3.107 (checked in the tests), like their motion with its two singular poses.
pub fn example_motion() -> Motion {
    Motion::Analytic(AnalyticMotion {
        tau_range: [-1.0, 4.5],
        x: MotionCoordinate {
            polynomial: vec![4.0],
            cosines: vec![CosineTerm {
                amplitude: 1.0,
                frequency: 1.0,
                phase: -std::f64::consts::FRAC_PI_2,
            }],
        },
        y: MotionCoordinate {
            polynomial: vec![3.8],
            cosines: vec![CosineTerm {
                amplitude: -0.8,
                frequency: 1.0,
                phase: 0.0,
            }],
        },
        phi: MotionCoordinate::polynomial(vec![0.0, 1.0]),
    })
}

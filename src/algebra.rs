//! The arithmetic shared by numbers and symbolic expressions.
//!
//! Formulas that appear both numerically and inside Lagrangians (the singularity
//! polynomial S of docs/theory.md §1.3, the collinearity polynomials, the segment and
//! triangle distances of docs/theory.md §2) are written once, generic over [`Ring`], and
//! instantiated with `f64`, [`crate::C64`] or the symbolic expression type of
//! [`crate::system`].

use crate::C64;
use std::ops::{Add, Mul, Neg, Sub};

/// A commutative ring with constants: what a polynomial formula needs.
pub trait Ring:
    Clone + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// The constant `value` in this ring.
    fn from_f64(value: f64) -> Self;
}

impl Ring for f64 {
    fn from_f64(value: f64) -> Self {
        value
    }
}

impl Ring for C64 {
    fn from_f64(value: f64) -> Self {
        C64::new(value, 0.0)
    }
}

/// A ring containing the imaginary unit (complex numbers, complex expressions): what
/// isotropic coordinates need.
pub trait ComplexRing: Ring {
    /// `i`, with `i² = −1`.
    fn imaginary_unit() -> Self;
}

impl ComplexRing for C64 {
    fn imaginary_unit() -> Self {
        C64::new(0.0, 1.0)
    }
}

/// A point of the plane with coordinates in a ring.
pub type Point<T> = [T; 2];

/// The coordinates in which a formula's points are written: the dot and cross products
/// and the quarter turn `E` are the only operations on points that depend on them (sums,
/// differences and scalar multiples are the same in every linear coordinate system).
pub trait Plane<T: Ring> {
    /// `p · q`.
    fn dot(p: &Point<T>, q: &Point<T>) -> T;
    /// `p × q` (the 2D cross product `p_x q_y − p_y q_x`).
    fn cross(p: &Point<T>, q: &Point<T>) -> T;
    /// `E p`, the rotation by +90°.
    fn rotate_quarter(p: &Point<T>) -> Point<T>;
    /// These coordinates of the point with Cartesian coordinates `p`.
    fn from_cartesian(p: &Point<T>) -> Point<T>;
    /// The Cartesian coordinates of the point `p` given in these coordinates.
    fn to_cartesian(p: &Point<T>) -> Point<T>;
}

/// Cartesian coordinates `(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cartesian;

impl<T: Ring> Plane<T> for Cartesian {
    fn dot(p: &Point<T>, q: &Point<T>) -> T {
        dot(p, q)
    }
    fn cross(p: &Point<T>, q: &Point<T>) -> T {
        cross(p, q)
    }
    fn rotate_quarter(p: &Point<T>) -> Point<T> {
        [-p[1].clone(), p[0].clone()]
    }
    fn from_cartesian(p: &Point<T>) -> Point<T> {
        p.clone()
    }
    fn to_cartesian(p: &Point<T>) -> Point<T> {
        p.clone()
    }
}

/// Isotropic (minimal) coordinates `(u, v) = ((x + i y)/√2, (x − i y)/√2)` of the
/// complexified plane (a unitary change of coordinates): `p · q = p_u q_v + p_v q_u`,
/// `p × q = i (p_u q_v − p_v q_u)`, `E (u, v) = (i u, −i v)`, so `|p|² = 2 p_u p_v`.
///
/// Why: critical points of the rigid metrics' Lagrangians escape to infinity along
/// isotropic lines (`y ≈ ∓ i x`, `|p|²` bounded). In Cartesian coordinates the products
/// `x² + y²` then cancel catastrophically (rounding `ε |x|²` in a value of size `|x|`)
/// and the Jacobian is ill-conditioned in every diagonal scaling; in isotropic
/// coordinates one coordinate is large and the other bounded, nothing cancels, and the
/// Jacobian is well-conditioned after scaling its rows and columns (measured on the
/// built-in example's `rigid/rigid` seed solutions: κ ≈ 10¹³ Cartesian, 4·10⁴
/// isotropic and equilibrated). The factor `1/√2` keeps the map unitary and the dot
/// product free of constants (shorter tapes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Isotropic;

impl<T: ComplexRing> Plane<T> for Isotropic {
    fn dot(p: &Point<T>, q: &Point<T>) -> T {
        p[0].clone() * q[1].clone() + p[1].clone() * q[0].clone()
    }
    fn cross(p: &Point<T>, q: &Point<T>) -> T {
        T::imaginary_unit() * (p[0].clone() * q[1].clone() - p[1].clone() * q[0].clone())
    }
    fn rotate_quarter(p: &Point<T>) -> Point<T> {
        [
            T::imaginary_unit() * p[0].clone(),
            -(T::imaginary_unit() * p[1].clone()),
        ]
    }
    fn from_cartesian(p: &Point<T>) -> Point<T> {
        to_isotropic(p)
    }
    fn to_cartesian(p: &Point<T>) -> Point<T> {
        to_cartesian(p)
    }
}

/// Isotropic coordinates `((x + i y)/√2, (x − i y)/√2)` of the Cartesian point `(x, y)`.
pub fn to_isotropic<T: ComplexRing>(p: &Point<T>) -> Point<T> {
    let (x, iy) = (
        p[0].clone() * T::from_f64(std::f64::consts::FRAC_1_SQRT_2),
        T::imaginary_unit() * p[1].clone() * T::from_f64(std::f64::consts::FRAC_1_SQRT_2),
    );
    [x.clone() + iy.clone(), x - iy]
}

/// Cartesian coordinates `((u + v)/√2, −i (u − v)/√2)` of the isotropic point `(u, v)`.
pub fn to_cartesian<T: ComplexRing>(p: &Point<T>) -> Point<T> {
    let scale = T::from_f64(std::f64::consts::FRAC_1_SQRT_2);
    [
        (p[0].clone() + p[1].clone()) * scale.clone(),
        (p[0].clone() - p[1].clone()) * (T::imaginary_unit() * -scale),
    ]
}

/// `u × v = u_x v_y − u_y v_x` (the notation of docs/theory.md).
pub fn cross<T: Ring>(u: &Point<T>, v: &Point<T>) -> T {
    u[0].clone() * v[1].clone() - u[1].clone() * v[0].clone()
}

/// `u · v`.
pub fn dot<T: Ring>(u: &Point<T>, v: &Point<T>) -> T {
    u[0].clone() * v[0].clone() + u[1].clone() * v[1].clone()
}

/// `v − u`.
pub fn difference<T: Ring>(u: &Point<T>, v: &Point<T>) -> Point<T> {
    [v[0].clone() - u[0].clone(), v[1].clone() - u[1].clone()]
}

/// Determinant of a 3×3 matrix given by rows.
pub fn det3<T: Ring>(m: &[[T; 3]; 3]) -> T {
    let minor = |r1: usize, r2: usize, c1: usize, c2: usize| {
        m[r1][c1].clone() * m[r2][c2].clone() - m[r1][c2].clone() * m[r2][c1].clone()
    };
    m[0][0].clone() * minor(1, 2, 1, 2) - m[0][1].clone() * minor(1, 2, 0, 2)
        + m[0][2].clone() * minor(1, 2, 0, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotropic_products_match_cartesian_ones() {
        let p = [C64::new(0.3, -1.2), C64::new(2.1, 0.4)];
        let q = [C64::new(-0.7, 0.5), C64::new(1.1, -2.3)];
        let (pi, qi) = (to_isotropic(&p), to_isotropic(&q));
        let close = |a: C64, b: C64| (a - b).norm() < 1e-14 * (1.0 + a.norm());
        assert!(close(Isotropic::dot(&pi, &qi), Cartesian::dot(&p, &q)));
        assert!(close(Isotropic::cross(&pi, &qi), Cartesian::cross(&p, &q)));
        let turned = to_cartesian(&Isotropic::rotate_quarter(&pi));
        let expected = Cartesian::rotate_quarter(&p);
        assert!(close(turned[0], expected[0]) && close(turned[1], expected[1]));
        let back = to_cartesian(&pi);
        assert!(close(back[0], p[0]) && close(back[1], p[1]));
        // |p|² = u v: an isotropic direction (y = −i x) has zero length.
        let isotropic_line = to_isotropic(&[C64::new(1e6, 0.0), C64::new(0.0, -1e6)]);
        assert!(isotropic_line[1].norm() == 0.0);
    }

    #[test]
    fn det3_matches_expansion_and_is_alternating() {
        let m = [[2.0, -1.0, 3.0], [0.5, 4.0, -2.0], [1.0, 1.0, 1.0]];
        // Rule of Sarrus by hand.
        // Products along the three diagonals minus the three anti-diagonals.
        let diagonals = [2.0 * 4.0 * 1.0, -1.0 * -2.0 * 1.0, 3.0 * 0.5 * 1.0];
        let anti_diagonals = [3.0 * 4.0 * 1.0, -0.5, 2.0 * -2.0 * 1.0];
        let sarrus: f64 = diagonals.iter().sum::<f64>() - anti_diagonals.iter().sum::<f64>();
        assert!((det3(&m) - sarrus).abs() < 1e-14);
        let swapped = [m[1], m[0], m[2]];
        assert!((det3(&swapped) + sarrus).abs() < 1e-14);
        assert_eq!(cross(&[1.0, 0.0], &[0.0, 1.0]), 1.0);
    }
}

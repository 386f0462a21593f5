//! The arithmetic shared by numbers and symbolic expressions.
//!
//! Formulas that appear both numerically and inside Lagrangians (the singularity
//! polynomial S of SPEC A.2, the collinearity polynomials, the segment and triangle
//! distances of SPEC A.3) are written once, generic over [`Ring`], and instantiated
//! with `f64`, [`crate::C64`] or the symbolic expression type of [`crate::system`].

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

/// A point of the plane with coordinates in a ring.
pub type Point<T> = [T; 2];

/// `u × v = u_x v_y − u_y v_x` (SPEC notation).
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

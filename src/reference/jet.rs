//! Second-order forward-mode automatic differentiation: a [`Jet`] carries a value,
//! its gradient and its (symmetric, packed) Hessian with respect to up to
//! [`MAX_VARIABLES`] variables.
//!
//! Jets implement [`crate::algebra::Ring`], so every polynomial formula of the crate
//! that is generic over the ring (the singularity polynomial, the collinearity
//! polynomials, the nine metrics' `D²`) evaluates its exact first and second
//! derivatives without any hand-written derivative code. The product rule
//! `∇²(ab) = a∇²b + b∇²a + ∇a∇bᵀ + ∇b∇aᵀ` and the chain rule
//! `∇²g(u) = g′(u)∇²u + g″(u)∇u∇uᵀ` are the whole method (Griewank and Walther,
//! *Evaluating Derivatives*, SIAM 2008, ch. 13).

use crate::algebra::Ring;
use std::ops::{Add, Mul, Neg, Sub};

/// Largest number of variables a jet differentiates with respect to.
pub const MAX_VARIABLES: usize = 12;

/// Number of packed entries of a symmetric `MAX_VARIABLES × MAX_VARIABLES` matrix.
const PACKED: usize = MAX_VARIABLES * (MAX_VARIABLES + 1) / 2;

/// Row and column of every packed Hessian entry (`k ↦ (i, j)` with `i ≤ j`,
/// column-major upper triangle).
const INDEX: ([usize; PACKED], [usize; PACKED]) = {
    let mut rows = [0; PACKED];
    let mut columns = [0; PACKED];
    let mut k = 0;
    let mut j = 0;
    while j < MAX_VARIABLES {
        let mut i = 0;
        while i <= j {
            rows[k] = i;
            columns[k] = j;
            k += 1;
            i += 1;
        }
        j += 1;
    }
    (rows, columns)
};

/// Packed position of the Hessian entry `(i, j)`.
pub fn packed_index(i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    j * (j + 1) / 2 + i
}

/// A value with its gradient and Hessian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet {
    /// The value.
    pub value: f64,
    /// `∂/∂x_i`.
    pub gradient: [f64; MAX_VARIABLES],
    /// `∂²/∂x_i∂x_j`, packed upper triangle (see [`packed_index`]).
    pub hessian: [f64; PACKED],
}

impl Jet {
    /// A constant (zero derivatives).
    pub fn constant(value: f64) -> Self {
        Jet {
            value,
            gradient: [0.0; MAX_VARIABLES],
            hessian: [0.0; PACKED],
        }
    }

    /// The variable `x_index` at `value` (unit gradient, zero Hessian).
    pub fn variable(value: f64, index: usize) -> Self {
        let mut jet = Jet::constant(value);
        jet.gradient[index] = 1.0;
        jet
    }

    /// `∂²/∂x_i∂x_j`.
    pub fn hessian_entry(&self, i: usize, j: usize) -> f64 {
        self.hessian[packed_index(i, j)]
    }

    /// `g(self)` for a scalar function with `g(u), g′(u), g″(u)` given.
    fn compose(&self, g: f64, dg: f64, ddg: f64) -> Self {
        let mut out = Jet::constant(g);
        for (o, s) in out.gradient.iter_mut().zip(&self.gradient) {
            *o = dg * s;
        }
        for (k, o) in out.hessian.iter_mut().enumerate() {
            let (i, j) = (INDEX.0[k], INDEX.1[k]);
            *o = dg * self.hessian[k] + ddg * self.gradient[i] * self.gradient[j];
        }
        out
    }
}

/// Scalars the parametrisations of constrained configurations are written in: a ring
/// with sine and cosine (`f64` for values, [`Jet`] for derivatives).
pub trait Real: Ring + Copy {
    /// `sin self`.
    fn sin(self) -> Self;
    /// `cos self`.
    fn cos(self) -> Self;
    /// The value (drops derivatives).
    fn value(self) -> f64;
}

impl Real for f64 {
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn value(self) -> f64 {
        self
    }
}

impl Real for Jet {
    fn sin(self) -> Self {
        let (s, c) = self.value.sin_cos();
        self.compose(s, c, -s)
    }
    fn cos(self) -> Self {
        let (s, c) = self.value.sin_cos();
        self.compose(c, -s, -c)
    }
    fn value(self) -> f64 {
        self.value
    }
}

impl Ring for Jet {
    fn from_f64(value: f64) -> Self {
        Jet::constant(value)
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(mut self, other: Jet) -> Jet {
        self.value += other.value;
        for (s, o) in self.gradient.iter_mut().zip(&other.gradient) {
            *s += o;
        }
        for (s, o) in self.hessian.iter_mut().zip(&other.hessian) {
            *s += o;
        }
        self
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(mut self, other: Jet) -> Jet {
        self.value -= other.value;
        for (s, o) in self.gradient.iter_mut().zip(&other.gradient) {
            *s -= o;
        }
        for (s, o) in self.hessian.iter_mut().zip(&other.hessian) {
            *s -= o;
        }
        self
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(mut self) -> Jet {
        self.value = -self.value;
        for g in &mut self.gradient {
            *g = -*g;
        }
        for h in &mut self.hessian {
            *h = -*h;
        }
        self
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, other: Jet) -> Jet {
        let (a, b) = (self.value, other.value);
        let mut out = Jet::constant(a * b);
        for (o, (p, q)) in out
            .gradient
            .iter_mut()
            .zip(self.gradient.iter().zip(&other.gradient))
        {
            *o = a * q + b * p;
        }
        for (k, o) in out.hessian.iter_mut().enumerate() {
            let (i, j) = (INDEX.0[k], INDEX.1[k]);
            *o = a * other.hessian[k]
                + b * self.hessian[k]
                + self.gradient[i] * other.gradient[j]
                + self.gradient[j] * other.gradient[i];
        }
        out
    }
}

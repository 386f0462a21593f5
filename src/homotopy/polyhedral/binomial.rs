//! Binomial systems `y^{v_i} = b_i` (i = 1..n, `v_i ∈ Z^n` the rows of a nonsingular
//! integer matrix V, `b_i ≠ 0`), solved exactly: they are the start systems of the
//! polyhedral homotopy, one per mixed cell.
//!
//! Unimodular row operations `U V = H` bring V to upper triangular (Hermite) form with
//! positive diagonal, by extended-Euclid combinations of two rows
//! `[[s, t], [−y/g, x/g]]` (`sx + ty = g = gcd(x, y)`, determinant 1). Since
//! `y^{(UV)_k} = Π_i (y^{v_i})^{U_ki}`, the system is equivalent to `y^{h_k} = b'_k`
//! with `log b'_k = Σ_i U_ki log b_i` (any branch: U is integral). Back substitution
//! then gives, for `k_j = 0..h_jj − 1`,
//! `log y_j = (log b'_j − Σ_{l>j} h_jl log y_l + 2πi k_j) / h_jj`, so there are
//! exactly `Π h_jj = |det V|` solutions, all distinct and in `(C*)^n` (Huber and
//! Sturmfels, "A polyhedral method for solving sparse polynomial systems", Math.
//! Comp. 1995, §3; Li, "Numerical solution of polynomial systems by homotopy
//! continuation methods", Handbook of Numerical Analysis XI, 2003, §4.2). Working with
//! logarithms (real part ln|·|, imaginary part reduced to `(−π, π]`) keeps large
//! exponents from overflowing. Solution `index` is decoded in mixed radix over the
//! diagonal, so any subset of solutions is generated independently.

use crate::C64;
use std::f64::consts::{PI, TAU};

/// The triangular form of a binomial system.
#[derive(Clone, Debug)]
pub struct BinomialSystem {
    n: usize,
    /// Upper triangular H (row-major), positive diagonal.
    triangular: Vec<i64>,
    /// `log b'`.
    log_rhs: Vec<C64>,
}

/// Errors of [`BinomialSystem::new`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BinomialError {
    /// V is singular.
    #[error("the exponent matrix is singular")]
    Singular,
    /// A right-hand side is zero or not finite.
    #[error("a right-hand side is zero or not finite")]
    BadRightHandSide,
    /// An entry overflowed during the reduction.
    #[error("the Hermite reduction overflowed")]
    Overflow,
}

/// `log z` with the imaginary part in `(−π, π]`.
fn reduce(z: C64) -> C64 {
    let mut im = z.im % TAU;
    if im > PI {
        im -= TAU;
    } else if im <= -PI {
        im += TAU;
    }
    C64::new(z.re, im)
}

/// `(g, s, t)` with `s a + t b = g = gcd(a, b) ≥ 0`.
fn extended_gcd(a: i64, b: i64) -> (i64, i64, i64) {
    let (mut r0, mut r1) = (a, b);
    let (mut s0, mut s1) = (1i64, 0i64);
    let (mut t0, mut t1) = (0i64, 1i64);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if r0 < 0 {
        (-r0, -s0, -t0)
    } else {
        (r0, s0, t0)
    }
}

impl BinomialSystem {
    /// The system `y^{v_i} = b_i` with `exponents` the rows `v_i` (row-major n × n).
    pub fn new(n: usize, exponents: &[i64], rhs: &[C64]) -> Result<Self, BinomialError> {
        assert_eq!(exponents.len(), n * n);
        assert_eq!(rhs.len(), n);
        if rhs
            .iter()
            .any(|b| !(b.norm() > 0.0 && b.norm().is_finite()))
        {
            return Err(BinomialError::BadRightHandSide);
        }
        let mut h = exponents.to_vec();
        let mut log_rhs: Vec<C64> = rhs.iter().map(|b| b.ln()).collect();
        for k in 0..n {
            for r in k + 1..n {
                let (x, y) = (h[k * n + k], h[r * n + k]);
                if y == 0 {
                    continue;
                }
                let (g, s, t) = extended_gcd(x, y);
                let (xg, yg) = (x / g, y / g);
                for j in 0..n {
                    let (a, b) = (h[k * n + j], h[r * n + j]);
                    let top = s
                        .checked_mul(a)
                        .zip(t.checked_mul(b))
                        .and_then(|(u, v)| u.checked_add(v));
                    let bottom = xg
                        .checked_mul(b)
                        .zip(yg.checked_mul(a))
                        .and_then(|(u, v)| u.checked_sub(v));
                    let (Some(top), Some(bottom)) = (top, bottom) else {
                        return Err(BinomialError::Overflow);
                    };
                    h[k * n + j] = top;
                    h[r * n + j] = bottom;
                }
                let (la, lb) = (log_rhs[k], log_rhs[r]);
                log_rhs[k] = reduce(la * s as f64 + lb * t as f64);
                log_rhs[r] = reduce(lb * xg as f64 - la * yg as f64);
            }
            if h[k * n + k] == 0 {
                return Err(BinomialError::Singular);
            }
            if h[k * n + k] < 0 {
                h[k * n..(k + 1) * n].iter_mut().for_each(|v| *v = -*v);
                log_rhs[k] = reduce(-log_rhs[k]);
            }
        }
        Ok(BinomialSystem {
            n,
            triangular: h,
            log_rhs,
        })
    }

    /// Number of solutions `|det V| = Π h_jj` (`None` on overflow).
    pub fn solution_count(&self) -> Option<u64> {
        (0..self.n).try_fold(1u64, |acc, j| {
            acc.checked_mul(self.triangular[j * self.n + j] as u64)
        })
    }

    /// Writes `log y` of solution `index` (mixed radix over `h_11, …, h_nn`, the last
    /// unknown varying fastest) into `log_y`.
    pub fn log_solution(&self, index: u64, log_y: &mut [C64]) {
        let n = self.n;
        let mut rest = index;
        for j in (0..n).rev() {
            let d = self.triangular[j * n + j];
            let k = rest % d as u64;
            rest /= d as u64;
            let mut v = self.log_rhs[j] + C64::new(0.0, TAU * k as f64);
            for (l, y) in log_y.iter().enumerate().skip(j + 1) {
                v -= *y * self.triangular[j * n + l] as f64;
            }
            log_y[j] = reduce(v / d as f64);
        }
    }

    /// Writes solution `index` into `y`.
    pub fn solution(&self, index: u64, y: &mut [C64]) {
        self.log_solution(index, y);
        y.iter_mut().for_each(|v| *v = v.exp());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn residual(v: &[i64], b: &[C64], y: &[C64]) -> f64 {
        let n = y.len();
        (0..n)
            .map(|i| {
                let mut p = C64::new(1.0, 0.0);
                for j in 0..n {
                    p *= y[j].powi(v[i * n + j] as i32);
                }
                (p - b[i]).norm() / b[i].norm()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn binomial_solutions_satisfy_the_system_and_are_distinct() {
        let v = [3, 1, 0, 1, -2, 1, 2, 0, -1];
        let b = [C64::new(0.3, -1.2), C64::new(-2.0, 0.5), C64::new(0.1, 0.9)];
        let system = BinomialSystem::new(3, &v, &b).unwrap();
        // det = 3·(2 − 0) − 1·(−1 − 2) + 0 = 9.
        assert_eq!(system.solution_count(), Some(9));
        let mut solutions: Vec<Vec<C64>> = Vec::new();
        for k in 0..9 {
            let mut y = vec![C64::new(0.0, 0.0); 3];
            system.solution(k, &mut y);
            assert!(residual(&v, &b, &y) < 1e-12, "solution {k}: {y:?}");
            for s in &solutions {
                let d: f64 = s.iter().zip(&y).map(|(a, c)| (a - c).norm()).sum();
                assert!(d > 1e-6);
            }
            solutions.push(y);
        }
        assert!(BinomialSystem::new(2, &[1, 2, 2, 4], &b[..2]).is_err());
    }
}

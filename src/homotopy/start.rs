//! Start systems.
//!
//! The total-degree start system `G_i(x) = x_i^{d_i} − 1` (d_i = degree of equation i)
//! has exactly `D = Π d_i` (the Bézout number) nonsingular solutions, the products of
//! roots of unity `x_i = exp(2πi k_i / d_i)`, `0 ≤ k_i < d_i`. With a random γ the
//! straight-line homotopy `(1 − t)γG + tF` then reaches every isolated solution of `F`
//! (Sommese & Wampler, Thm 8.4.1). Solution `index` is decoded in mixed radix
//! `(d_1, …, d_n)`, so any subset of paths can be generated independently.

use crate::C64;
use crate::system::PlainSystem;

/// `G_i(x) = x_i^{d_i} − 1`, i = 1..n.
#[derive(Clone, Debug)]
pub struct TotalDegreeStartSystem {
    degrees: Vec<u32>,
}

impl TotalDegreeStartSystem {
    /// Start system for equation degrees `degrees` (each ≥ 1).
    pub fn new(degrees: Vec<u32>) -> Self {
        TotalDegreeStartSystem { degrees }
    }

    /// The degrees d_i.
    pub fn degrees(&self) -> &[u32] {
        &self.degrees
    }

    /// Bézout number `Π d_i` (`None` on overflow of u64).
    pub fn path_count(&self) -> Option<u64> {
        self.degrees
            .iter()
            .try_fold(1u64, |acc, &d| acc.checked_mul(d as u64))
    }

    /// Writes start solution number `index` (mixed radix over the degrees) into `x`.
    pub fn start_solution(&self, index: u64, x: &mut [C64]) {
        let mut rest = index;
        for (xi, &d) in x.iter_mut().zip(&self.degrees) {
            let d = d.max(1) as u64;
            let k = rest % d;
            rest /= d;
            *xi = C64::from_polar(1.0, std::f64::consts::TAU * k as f64 / d as f64);
        }
    }
}

impl PlainSystem for TotalDegreeStartSystem {
    fn num_variables(&self) -> usize {
        self.degrees.len()
    }
    fn workspace_len(&self) -> usize {
        0
    }

    fn evaluate(&self, x: &[C64], _work: &mut [C64], f: &mut [C64]) {
        for ((fi, xi), &d) in f.iter_mut().zip(x).zip(&self.degrees) {
            *fi = xi.powu(d) - 1.0;
        }
    }

    fn evaluate_with_jacobian(&self, x: &[C64], _work: &mut [C64], f: &mut [C64], jac: &mut [C64]) {
        let n = self.degrees.len();
        jac.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        for i in 0..n {
            let d = self.degrees[i];
            let lower = if d >= 1 {
                x[i].powu(d - 1)
            } else {
                C64::new(0.0, 0.0)
            };
            f[i] = lower * x[i] - 1.0;
            jac[i * n + i] = lower * d as f64;
        }
    }
}

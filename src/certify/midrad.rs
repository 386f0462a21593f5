//! `I − Y·B` for a point matrix `Y` and an interval matrix `B`, in midpoint–radius
//! form: one floating-point product and an error bound instead of `n³` interval
//! products (Rump, "Fast and parallel interval arithmetic", BIT 1999).
//!
//! Write every entry of `B` as `C + Δ` with `C = Cᵣ + iCᵢ` its midpoint and
//! `|Re Δ| ≤ Rᵣ`, `|Im Δ| ≤ Rᵢ` (radii rounded up). Then for every `Δ`
//!
//! `Re (Y·B) ∈ Yᵣ·Cᵣ − Yᵢ·Cᵢ ± (|Yᵣ|·Rᵣ + |Yᵢ|·Rᵢ)`,
//! `Im (Y·B) ∈ Yᵣ·Cᵢ + Yᵢ·Cᵣ ± (|Yᵣ|·Rᵢ + |Yᵢ|·Rᵣ)`,
//!
//! exactly (the rectangle of a point times a rectangle). Each midpoint is a real dot
//! product of length `2n`, computed in round-to-nearest with error at most
//! `γ₂ₙ·(|Yᵣ|·|Cᵣ| + |Yᵢ|·|Cᵢ|)` (resp. `γ₂ₙ·(|Yᵣ|·|Cᵢ| + |Yᵢ|·|Cᵣ|)`),
//! `γₖ = k·u/(1 − k·u)`, `u = 2⁻⁵³` (Higham, "Accuracy and Stability of Numerical
//! Algorithms", 2002, §3.1), plus at most `2⁻¹⁰⁷⁵` per product from underflow. Both
//! bounds together are `|Yᵣ|·Wᵣ + |Yᵢ|·Wᵢ` (resp. `|Yᵣ|·Wᵢ + |Yᵢ|·Wᵣ`) with the
//! weights `W = γ₂ₙ·|C| + R`. These sums, of at most `2n + 3` roundings per term, are
//! enlarged by the factor `1 + 2γ₄ₙ₊₄` and by `(8n + 8)` times the smallest normal number, which
//! covers their own rounding and every underflow; the subtraction from `I` adds
//! `2u·|m|` for its rounded result `m`. The interval `m ± r` is then rounded outwards.

use crate::C64;
use crate::system::interval::{ComplexInterval, Interval};

/// Scratch space for `n × n` products.
pub struct MidpointRadius {
    n: usize,
    /// Midpoints `C` of `B` and the weights `γ₂ₙ·|C| + R`, real and imaginary parts.
    mid: [Vec<f64>; 2],
    rad: [Vec<f64>; 2],
    /// Per row: midpoint sums and radius sums (re, im).
    center: [Vec<f64>; 2],
    spread: [Vec<f64>; 2],
}

const U: f64 = f64::EPSILON / 2.0;

fn gamma(k: usize) -> f64 {
    let ku = k as f64 * U;
    ku / (1.0 - ku)
}

impl MidpointRadius {
    /// Scratch space for `n × n` matrices.
    pub fn new(n: usize) -> Self {
        let square = || [vec![0.0; n * n], vec![0.0; n * n]];
        let row = || [vec![0.0; n], vec![0.0; n]];
        MidpointRadius {
            n,
            mid: square(),
            rad: square(),
            center: row(),
            spread: row(),
        }
    }

    /// `out = I − Y·B` (row-major `n × n`) enclosed; `false` (and `out` unspecified)
    /// if an entry of `B` is unbounded.
    pub fn identity_minus(
        &mut self,
        y: &[C64],
        b: &[ComplexInterval],
        out: &mut [ComplexInterval],
    ) -> bool {
        let n = self.n;
        assert!(y.len() == n * n && b.len() == n * n && out.len() == n * n);
        let gamma_dot = gamma(2 * n);
        for (k, e) in b.iter().enumerate() {
            if !e.is_bounded() {
                return false;
            }
            for (part, v) in [e.re, e.im].into_iter().enumerate() {
                let m = 0.5 * v.lo + 0.5 * v.hi;
                self.mid[part][k] = m;
                // The weight γ₂ₙ·|m| + radius of |Y| in both bounds.
                let radius = (v.hi - m).max(m - v.lo).next_up();
                self.rad[part][k] = gamma_dot * m.abs() + radius;
            }
        }
        let enlarge = 1.0 + 2.0 * gamma(4 * n + 4);
        let floor = (8 * n + 8) as f64 * f64::MIN_POSITIVE;
        for i in 0..n {
            for part in 0..2 {
                self.center[part].fill(0.0);
                self.spread[part].fill(0.0);
            }
            for l in 0..n {
                let (yr, yi) = (y[i * n + l].re, y[i * n + l].im);
                let (ar, ai) = (yr.abs(), yi.abs());
                let row = l * n..(l + 1) * n;
                let (cr, ci) = (&self.mid[0][row.clone()], &self.mid[1][row.clone()]);
                let (wr, wi) = (&self.rad[0][row.clone()], &self.rad[1][row]);
                let [center_re, center_im] = &mut self.center;
                let [spread_re, spread_im] = &mut self.spread;
                for j in 0..n {
                    center_re[j] += yr * cr[j] - yi * ci[j];
                    center_im[j] += yr * ci[j] + yi * cr[j];
                    spread_re[j] += ar * wr[j] + ai * wi[j];
                    spread_im[j] += ar * wi[j] + ai * wr[j];
                }
            }
            for j in 0..n {
                let identity = if i == j { 1.0 } else { 0.0 };
                let part = |p: usize| {
                    let m = if p == 0 { identity } else { 0.0 } - self.center[p][j];
                    let r = (self.spread[p][j] + 2.0 * U * m.abs()) * enlarge + floor;
                    Interval::centered(m, r)
                };
                out[i * n + j] = ComplexInterval {
                    re: part(0),
                    im: part(1),
                };
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random;

    /// Random products enclose every sampled exact product `I − Y·B₀` (B₀ ∈ B), and
    /// the enclosure is not much wider than the entrywise interval product.
    #[test]
    fn encloses_sampled_products() {
        let mut rng = random::stream(7, 3);
        let n = 5;
        let mut unit = || random::uniform(&mut rng, -1.0, 1.0);
        for _ in 0..20 {
            let y: Vec<C64> = (0..n * n).map(|_| C64::new(unit(), unit())).collect();
            let centers: Vec<C64> = (0..n * n).map(|_| C64::new(unit(), unit())).collect();
            let width = 1e-6 * unit().abs();
            let b: Vec<ComplexInterval> = centers
                .iter()
                .map(|&c| ComplexInterval::centered(c, width))
                .collect();
            let mut out = vec![ComplexInterval::default(); n * n];
            let mut product = MidpointRadius::new(n);
            assert!(product.identity_minus(&y, &b, &mut out));
            for _ in 0..10 {
                // A sample of B and the product in interval arithmetic on points (an
                // enclosure of the exact value).
                let sample: Vec<C64> = centers
                    .iter()
                    .map(|&c| c + C64::new(unit(), unit()) * (width * 0.7))
                    .collect();
                for i in 0..n {
                    for j in 0..n {
                        let mut sum = ComplexInterval::default();
                        for l in 0..n {
                            sum = sum
                                + ComplexInterval::point(y[i * n + l])
                                    * ComplexInterval::point(sample[l * n + j]);
                        }
                        let identity = if i == j { 1.0 } else { 0.0 };
                        let exact = ComplexInterval::point(C64::new(identity, 0.0)) - sum;
                        let got = out[i * n + j];
                        assert!(
                            got.re.lo <= exact.re.lo && exact.re.hi <= got.re.hi,
                            "re {got:?} ∌ {exact:?}"
                        );
                        assert!(
                            got.im.lo <= exact.im.lo && exact.im.hi <= got.im.hi,
                            "im {got:?} ∌ {exact:?}"
                        );
                        assert!(got.re.width() < 20.0 * width * n as f64 + 1e-12);
                    }
                }
            }
        }
        // An unbounded entry is refused.
        let mut b = vec![ComplexInterval::default(); 4];
        b[3].re = Interval::ENTIRE;
        let y = vec![C64::new(1.0, 0.0); 4];
        let mut out = vec![ComplexInterval::default(); 4];
        assert!(!MidpointRadius::new(2).identity_minus(&y, &b, &mut out));
    }
}

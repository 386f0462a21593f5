//! Componentwise bounds of `|(I − Y·B)·E|` for a point matrix `Y`, an interval
//! matrix `B` and an interval vector `E`, in midpoint–radius form: one floating-point
//! product `Y·mid B` and matrix–vector products of absolute values, instead of `n³`
//! interval products and `n²` more for the product with `E` (Rump, "Fast and parallel
//! interval arithmetic", BIT 39 (1999) 534–554).
//!
//! Write every entry of `B` as `C + Δ` with `C = Cᵣ + iCᵢ` its midpoint and
//! `|Re Δ| ≤ Rᵣ`, `|Im Δ| ≤ Rᵢ` (radii rounded up). Then for every `Δ`
//!
//! `|Re (Y·Δ)| ≤ |Yᵣ|·Rᵣ + |Yᵢ|·Rᵢ`, `|Im (Y·Δ)| ≤ |Yᵣ|·Rᵢ + |Yᵢ|·Rᵣ`
//!
//! (the rectangle of a point times a rectangle). The product `Y·C` is computed in
//! round-to-nearest as `Ĉ`; each part is a real dot product of length `2n`, with error
//! at most `γ₂ₙ·(|Yᵣ|·|Cᵣ| + |Yᵢ|·|Cᵢ|)` (resp. `γ₂ₙ·(|Yᵣ|·|Cᵢ| + |Yᵢ|·|Cᵣ|)`),
//! `γₖ = k·u/(1 − k·u)`, `u = 2⁻⁵³` (Higham, "Accuracy and Stability of Numerical
//! Algorithms", SIAM 2002, §3.1), plus at most `2⁻¹⁰⁷⁵` per product from underflow.
//! With the weights `W = γ₂ₙ·|C| + R` and `m̂ = fl(I − Ĉ)` (`|m̂ − (I − Ĉ)| ≤ 2u·|m̂|`)
//! every matrix `M = I − Y·B₀`, `B₀ ∈ B`, satisfies
//!
//! `|Re M| ≤ (1 + 2u)·|Re m̂| + |Yᵣ|·Wᵣ + |Yᵢ|·Wᵢ`, `|Im M| ≤ (1 + 2u)·|Im m̂| + |Yᵣ|·Wᵢ + |Yᵢ|·Wᵣ`,
//!
//! and for `e ∈ E` with `ēᵣ = mag Re E`, `ēᵢ = mag Im E` (exact)
//!
//! `|Re (M·e)| ≤ |Re M|·ēᵣ + |Im M|·ēᵢ`, `|Im (M·e)| ≤ |Re M|·ēᵢ + |Im M|·ēᵣ`.
//!
//! The radius part is evaluated as `|Y|·(W·ē)`: first `a = Wᵣ·ēᵣ + Wᵢ·ēᵢ`,
//! `b = Wᵢ·ēᵣ + Wᵣ·ēᵢ` (a vector), then `|Yᵣ|·a + |Yᵢ|·b` and `|Yᵣ|·b + |Yᵢ|·a`, which
//! is the same sum of non-negative terms in another order. Every quantity summed is
//! non-negative, so a computed sum whose terms went through at most `k` roundings is
//! at least `(1 − u)ᵏ` times the exact one, less `2⁻¹⁰⁷⁵` per underflowing product;
//! `upper` turns it into an upper bound. (A weight loses nothing to underflow: its
//! radius, rounded up by `next_up`, exceeds the exact one by at least `2⁻¹⁰⁷⁵`.) The
//! underflow in `Ĉ`, at most `n·2⁻¹⁰⁷⁴` per entry, adds `n·2⁻¹⁰⁷⁴·Σⱼ (ēᵣⱼ + ēᵢⱼ)`.

use crate::C64;
use crate::system::interval::{ComplexInterval, Interval};

/// Scratch space for `n × n` products.
pub struct MidpointRadius {
    n: usize,
    /// Midpoints `C` of `B`, real and imaginary parts (row-major).
    mid: [Vec<f64>; 2],
    /// Weights `W = γ₂ₙ·|C| + R`, real and imaginary parts (row-major).
    weight: [Vec<f64>; 2],
    /// One row of `Ĉ = fl(Y·C)` (re, im).
    center: [Vec<f64>; 2],
    /// Upper bounds of `W·ē`: the vectors `a` and `b`.
    spread: [Vec<f64>; 2],
}

const U: f64 = f64::EPSILON / 2.0;

/// An upper bound of `γₖ = k·u/(1 − k·u)`: `k·u` and `1 − k·u` are exact for the
/// small `k` used here, and the quotient is rounded up.
fn gamma(k: usize) -> f64 {
    let ku = k as f64 * U;
    (ku / (1.0 - ku)).next_up()
}

/// An upper bound of an exact sum `s ≥ 0` of non-negative terms from its computed value
/// `computed`, when every term went through at most `roundings` roundings (products,
/// sums, and factors `1 + 2u` counted as two) and at most `products` products may have
/// underflowed: `s ≤ computed/(1 − γₖ) + products·2⁻¹⁰⁷⁴`. The factor `1 + 2γₖ₊₂`
/// covers `1/(1 − γₖ)` and the two roundings of this function; the smallest normal
/// number per product, added last, covers every underflow.
fn upper(computed: f64, roundings: usize, products: usize) -> f64 {
    computed * (1.0 + 2.0 * gamma(roundings + 2)) + (products + 1) as f64 * f64::MIN_POSITIVE
}

/// The midpoint `m` of a bounded interval and the weight `γ·|m| + r` for a radius `r`
/// rounded up (at least `2⁻¹⁰⁷⁴` above the exact one).
#[inline]
fn split(v: Interval, gamma: f64) -> (f64, f64) {
    let m = 0.5 * v.lo + 0.5 * v.hi;
    let radius = (v.hi - m).max(m - v.lo).next_up();
    (m, gamma * m.abs() + radius)
}

/// `−Y·f` enclosed, for a point matrix `Y` (row-major `n × n`) and an interval vector
/// `f` with midpoint `m` and radius `R`: midpoint `−fl(Y·m)` and radius
/// `|Yᵣ|·Wᵣ + |Yᵢ|·Wᵢ` (imaginary part `|Yᵣ|·Wᵢ + |Yᵢ|·Wᵣ`) with `W = γ₂ₙ·|m| + R`,
/// bounded by `upper` (whose floor also covers the underflow in `fl(Y·m)`, at most
/// `n·2⁻¹⁰⁷⁴`), rounded outwards (the matrix case of the module documentation with
/// one column). `false` if an entry of `f` is unbounded.
pub fn negated_product(y: &[C64], f: &[ComplexInterval], out: &mut [ComplexInterval]) -> bool {
    let n = f.len();
    assert!(y.len() == n * n && out.len() == n);
    if !f.iter().all(|v| v.is_bounded()) {
        return false;
    }
    let gamma_dot = gamma(2 * n);
    // Midpoints and weights of `f`, once for all rows.
    let splits: Vec<((f64, f64), (f64, f64))> = f
        .iter()
        .map(|v| (split(v.re, gamma_dot), split(v.im, gamma_dot)))
        .collect();
    for (row, z) in y.chunks_exact(n).zip(out.iter_mut()) {
        let (mut c_re, mut c_im, mut r_re, mut r_im) = (0.0, 0.0, 0.0, 0.0);
        for (&yv, &((m_re, w_re), (m_im, w_im))) in row.iter().zip(&splits) {
            c_re += yv.re * m_re - yv.im * m_im;
            c_im += yv.re * m_im + yv.im * m_re;
            let (ar, ai) = (yv.re.abs(), yv.im.abs());
            r_re += ar * w_re + ai * w_im;
            r_im += ar * w_im + ai * w_re;
        }
        // Per radius term: two roundings of its weight, one product, at most 2n sums.
        *z = ComplexInterval {
            re: Interval::centered(-c_re, upper(r_re, 2 * n + 3, 2 * n)),
            im: Interval::centered(-c_im, upper(r_im, 2 * n + 3, 2 * n)),
        };
    }
    out.iter().all(|z| z.is_bounded())
}

impl MidpointRadius {
    /// Scratch space for `n × n` matrices.
    pub fn new(n: usize) -> Self {
        let square = || [vec![0.0; n * n], vec![0.0; n * n]];
        let row = || [vec![0.0; n], vec![0.0; n]];
        MidpointRadius {
            n,
            mid: square(),
            weight: square(),
            center: row(),
            spread: row(),
        }
    }

    /// `out[i] = [tᵣ, tᵢ]` with `|Re ((I − Y·B₀)·e)ᵢ| ≤ tᵣ` and `|Im ((I − Y·B₀)·e)ᵢ| ≤ tᵢ`
    /// for every `B₀ ∈ B` and `e ∈ E` (`Y`, `B` row-major `n × n`). `false` (and `out`
    /// unspecified) if an entry of `B` or `E` is unbounded or a bound is not finite.
    pub fn product_bound(
        &mut self,
        y: &[C64],
        b: &[ComplexInterval],
        e: &[ComplexInterval],
        out: &mut [[f64; 2]],
    ) -> bool {
        let n = self.n;
        assert!(y.len() == n * n && b.len() == n * n && e.len() == n && out.len() == n);
        if !e.iter().all(|v| v.is_bounded()) {
            return false;
        }
        let gamma_dot = gamma(2 * n);
        for (k, entry) in b.iter().enumerate() {
            if !entry.is_bounded() {
                return false;
            }
            for (part, v) in [entry.re, entry.im].into_iter().enumerate() {
                (self.mid[part][k], self.weight[part][k]) = split(v, gamma_dot);
            }
        }
        // a = Wᵣ·ēᵣ + Wᵢ·ēᵢ, b = Wᵢ·ēᵣ + Wᵣ·ēᵢ: per term the two roundings of its
        // weight, one product and at most 2n sums.
        for l in 0..n {
            let row = l * n..(l + 1) * n;
            let (wr, wi) = (&self.weight[0][row.clone()], &self.weight[1][row]);
            let (mut a, mut b) = (0.0, 0.0);
            for ((&wr, &wi), v) in wr.iter().zip(wi).zip(e) {
                let (er, ei) = (v.re.magnitude(), v.im.magnitude());
                a += wr * er + wi * ei;
                b += wi * er + wr * ei;
            }
            self.spread[0][l] = upper(a, 2 * n + 3, 2 * n);
            self.spread[1][l] = upper(b, 2 * n + 3, 2 * n);
        }
        // Underflow in Ĉ: at most n·2⁻¹⁰⁷⁴ per entry, times Σⱼ (ēᵣ + ēᵢ).
        let magnitudes = e
            .iter()
            .fold(0.0, |s, v| s + v.re.magnitude() + v.im.magnitude());
        let underflow = (n as f64 * f64::from_bits(1) * upper(magnitudes, 2 * n, 0)).next_up();
        for (i, bound) in out.iter_mut().enumerate() {
            let [center_re, center_im] = &mut self.center;
            center_re.fill(0.0);
            center_im.fill(0.0);
            // |Y|·(a, b): one product and at most 2n sums per term.
            let (mut radius_re, mut radius_im) = (0.0, 0.0);
            for l in 0..n {
                let (yr, yi) = (y[i * n + l].re, y[i * n + l].im);
                let (ar, ai) = (yr.abs(), yi.abs());
                let (a, b) = (self.spread[0][l], self.spread[1][l]);
                radius_re += ar * a + ai * b;
                radius_im += ar * b + ai * a;
                let row = l * n..(l + 1) * n;
                let (cr, ci) = (&self.mid[0][row.clone()], &self.mid[1][row]);
                for (((c_re, c_im), &cr), &ci) in center_re
                    .iter_mut()
                    .zip(center_im.iter_mut())
                    .zip(cr)
                    .zip(ci)
                {
                    *c_re += yr * cr - yi * ci;
                    *c_im += yr * ci + yi * cr;
                }
            }
            // |m̂|·ē: the factor 1 + 2u (two roundings), one product, at most 2n sums.
            let (mut mid_re, mut mid_im) = (0.0, 0.0);
            for (j, ((&c_re, &c_im), v)) in
                center_re.iter().zip(center_im.iter()).zip(e).enumerate()
            {
                let identity = if i == j { 1.0 } else { 0.0 };
                let (mr, mi) = ((identity - c_re).abs(), c_im.abs());
                let (er, ei) = (v.re.magnitude(), v.im.magnitude());
                mid_re += mr * er + mi * ei;
                mid_im += mr * ei + mi * er;
            }
            let part = |mid: f64, radius: f64| {
                let mid = upper(mid * (1.0 + 2.0 * U), 2 * n + 3, 2 * n);
                let radius = upper(radius, 2 * n + 1, 2 * n);
                ((mid + radius).next_up() + underflow).next_up()
            };
            *bound = [part(mid_re, radius_re), part(mid_im, radius_im)];
            if !bound.iter().all(|t| t.is_finite()) {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random;

    /// `(I − Y·B₀)·e₀` in interval arithmetic on points (an enclosure of the exact
    /// value), row `i`.
    fn exact_row(y: &[C64], b0: &[C64], e0: &[C64], i: usize) -> ComplexInterval {
        let n = e0.len();
        let point = ComplexInterval::point;
        (0..n).fold(ComplexInterval::default(), |sum, j| {
            let yb = (0..n).fold(ComplexInterval::default(), |s, l| {
                s + point(y[i * n + l]) * point(b0[l * n + j])
            });
            let identity = point(C64::new(if i == j { 1.0 } else { 0.0 }, 0.0));
            sum + (identity - yb) * point(e0[j])
        })
    }

    /// Uniform draws in `[−1, 1]` from stream `stream` of `seed`.
    fn unit_draws(seed: u64, stream: u64) -> impl FnMut() -> f64 {
        let mut rng = random::stream(seed, stream);
        move || random::uniform(&mut rng, -1.0, 1.0)
    }

    /// `len` complex numbers with real and imaginary parts drawn from `unit`, in turn.
    fn random_complex(unit: &mut impl FnMut() -> f64, len: usize) -> Vec<C64> {
        (0..len).map(|_| C64::new(unit(), unit())).collect()
    }

    fn assert_bounded(got: [f64; 2], exact: ComplexInterval) {
        assert!(
            exact.re.magnitude() <= got[0] && exact.im.magnitude() <= got[1],
            "{got:?} does not bound {exact:?}"
        );
    }

    /// Random complex matrices and boxes: the bound holds at sampled points of `B` and
    /// `E`, and is not much larger than `|I − Y·C|·ē` plus the radius term.
    #[test]
    fn bounds_sampled_products() {
        let mut unit = unit_draws(7, 3);
        let n = 5;
        for _ in 0..20 {
            let y = random_complex(&mut unit, n * n);
            let centers = random_complex(&mut unit, n * n);
            let offsets = random_complex(&mut unit, n);
            let width = 1e-6 * unit().abs();
            let b = ComplexInterval::boxes(&centers, width);
            let e = ComplexInterval::boxes(&offsets, 0.3);
            let mut out = vec![[0.0; 2]; n];
            let mut product = MidpointRadius::new(n);
            assert!(product.product_bound(&y, &b, &e, &mut out));
            for _ in 0..10 {
                let b0: Vec<C64> = centers
                    .iter()
                    .map(|&c| c + C64::new(unit(), unit()) * width)
                    .collect();
                let e0: Vec<C64> = offsets
                    .iter()
                    .map(|&c| c + C64::new(unit(), unit()) * 0.3)
                    .collect();
                for (i, &got) in out.iter().enumerate() {
                    assert_bounded(got, exact_row(&y, &b0, &e0, i));
                }
            }
            // Not loose: at most |I − Y·C|·ē·(1 + 1e-12) + the radius term.
            for (i, got) in out.iter().enumerate() {
                let mut crude = 0.0;
                for j in 0..n {
                    let c: C64 = (0..n).map(|l| y[i * n + l] * centers[l * n + j]).sum();
                    let m = C64::new(if i == j { 1.0 } else { 0.0 }, 0.0) - c;
                    let e = offsets[j].re.abs() + offsets[j].im.abs() + 0.6;
                    crude += (m.re.abs() + m.im.abs()) * e;
                }
                let radius_term = 10.0 * (n * n) as f64 * width + 1e-12;
                assert!(got[0] <= crude * (1.0 + 1e-12) + radius_term);
            }
        }
    }

    /// With `Y ≈ C⁻¹` the centre term vanishes and the bound is the radius term
    /// `|Y|·R·ē`, which the worst corner of `B` and `E` attains: the bound must hold
    /// there, and it is tight to rounding.
    #[test]
    fn the_radius_term_is_attained_at_the_worst_corner() {
        let n = 4;
        let mut unit = unit_draws(11, 5);
        // C = 2I + small (real), Y = C⁻¹ by Gauss–Jordan in double.
        let mut c: Vec<f64> = (0..n * n).map(|_| 0.3 * unit()).collect();
        for i in 0..n {
            c[i * n + i] += 2.0;
        }
        let y = invert(&c, n);
        let radius = 1e-3;
        let b: Vec<ComplexInterval> = c
            .iter()
            .map(|&v| ComplexInterval {
                re: Interval::centered(v, radius),
                im: Interval::point(0.0),
            })
            .collect();
        let e: Vec<ComplexInterval> = (0..n)
            .map(|_| ComplexInterval {
                re: Interval::centered(0.0, 0.5),
                im: Interval::point(0.0),
            })
            .collect();
        let y_complex: Vec<C64> = y.iter().map(|&v| C64::new(v, 0.0)).collect();
        let mut out = vec![[0.0; 2]; n];
        assert!(MidpointRadius::new(n).product_bound(&y_complex, &b, &e, &mut out));
        for i in 0..n {
            // Δ_lj = −R·sign(Y_il) makes every term of (−Y·Δ)_ij equal to +|Y_il|·R;
            // e_j = 0.5 adds them all.
            let b0: Vec<C64> = (0..n * n)
                .map(|k| {
                    let l = k / n;
                    C64::new(c[k] - radius * y[i * n + l].signum(), 0.0)
                })
                .collect();
            let e0 = vec![C64::new(0.5, 0.0); n];
            let exact = exact_row(&y_complex, &b0, &e0, i);
            assert_bounded(out[i], exact);
            assert!(
                out[i][0] <= exact.re.magnitude() * 1.001,
                "{:?} {exact:?}",
                out[i]
            );
        }
    }

    fn invert(c: &[f64], n: usize) -> Vec<f64> {
        let mut a = c.to_vec();
        let mut inv: Vec<f64> = (0..n * n)
            .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
            .collect();
        for p in 0..n {
            let pivot = a[p * n + p];
            for j in 0..n {
                a[p * n + j] /= pivot;
                inv[p * n + j] /= pivot;
            }
            for i in (0..n).filter(|&i| i != p) {
                let f = a[i * n + p];
                for j in 0..n {
                    a[i * n + j] -= f * a[p * n + j];
                    inv[i * n + j] -= f * inv[p * n + j];
                }
            }
        }
        inv
    }

    /// `−Y·f₀` at corners of the boxes `f` (interval arithmetic on points) lies in the
    /// enclosure, which is about as wide as the interval product's.
    #[test]
    fn negated_product_encloses_corners() {
        let mut unit = unit_draws(13, 2);
        let n = 6;
        for _ in 0..20 {
            let y = random_complex(&mut unit, n * n);
            let centers: Vec<C64> = random_complex(&mut unit, n)
                .into_iter()
                .map(|c| c * 1e-3)
                .collect();
            let width = 1e-9 * unit().abs();
            let f = ComplexInterval::boxes(&centers, width);
            let mut out = vec![ComplexInterval::default(); n];
            assert!(negated_product(&y, &f, &mut out));
            for i in 0..n {
                let interval: ComplexInterval = -(0..n).fold(ComplexInterval::default(), |s, l| {
                    s + ComplexInterval::point(y[i * n + l]) * f[l]
                });
                assert!(out[i].re.width() <= interval.re.width() * (1.0 + 1e-6) + 1e-18);
                for _ in 0..8 {
                    let corner = |v: f64| if v > 0.0 { 1.0 } else { -1.0 };
                    let f0: Vec<C64> = centers
                        .iter()
                        .map(|&c| c + C64::new(corner(unit()), corner(unit())) * width)
                        .collect();
                    let exact = -(0..n).fold(ComplexInterval::default(), |s, l| {
                        s + ComplexInterval::point(y[i * n + l]) * ComplexInterval::point(f0[l])
                    });
                    let got = out[i];
                    assert!(
                        got.re.lo <= exact.re.lo && exact.re.hi <= got.re.hi,
                        "{got:?} ∌ {exact:?}"
                    );
                    assert!(
                        got.im.lo <= exact.im.lo && exact.im.hi <= got.im.hi,
                        "{got:?} ∌ {exact:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn unbounded_entries_are_refused() {
        let mut b = vec![ComplexInterval::default(); 4];
        let y = vec![C64::new(1.0, 0.0); 4];
        let e = vec![ComplexInterval::default(); 2];
        let mut out = vec![[0.0; 2]; 2];
        b[3].re = Interval::ENTIRE;
        assert!(!MidpointRadius::new(2).product_bound(&y, &b, &e, &mut out));
        let mut e = e;
        e[1].im = Interval::ENTIRE;
        let b = vec![ComplexInterval::default(); 4];
        assert!(!MidpointRadius::new(2).product_bound(&y, &b, &e, &mut out));
    }
}

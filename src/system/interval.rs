//! Real and complex interval arithmetic with outward rounding.
//!
//! An [`Interval`] `[lo, hi]` encloses a set of reals. Every operation computes its
//! endpoints in round-to-nearest double arithmetic and then moves each one ulp outwards
//! (`next_down`, `next_up`): a correctly rounded result is within half an ulp of the
//! exact one, so the widened interval contains every exact result (Moore, Kearfott,
//! Cloud, "Introduction to Interval Analysis", SIAM 2009, §3). Results with a NaN
//! endpoint become the whole line, so an overflow can only make a test fail, never
//! pass.
//!
//! A [`ComplexInterval`] is a rectangle `re + i·im` of two real intervals; its product
//! `(a + ib)(c + id) = (ac − bd) + i(ad + bc)` is evaluated in real interval
//! arithmetic (a rectangle enclosing the exact product set).

use crate::C64;
use crate::algebra::Ring;
use std::ops::{Add, Mul, Neg, Sub};

/// A closed real interval `[lo, hi]` (`lo ≤ hi`), possibly unbounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Interval {
    /// The whole real line (what an undefined result is widened to).
    pub const ENTIRE: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// `[lo, hi]` from already-rounded ends (a NaN end gives [`Interval::ENTIRE`]).
    #[inline]
    fn from_rounded(lo: f64, hi: f64) -> Interval {
        if lo.is_nan() | hi.is_nan() {
            Interval::ENTIRE
        } else {
            Interval {
                lo: next_down(lo),
                hi: next_up(hi),
            }
        }
    }

    /// The degenerate interval `[v, v]` (exact: no rounding happened).
    #[inline]
    pub fn point(v: f64) -> Interval {
        if v.is_nan() {
            Interval::ENTIRE
        } else {
            Interval { lo: v, hi: v }
        }
    }

    /// `[c − r, c + r]`, rounded outwards.
    pub fn centered(c: f64, r: f64) -> Interval {
        Interval::from_rounded(c - r, c + r)
    }

    /// `[lo, hi]` with both ends moved one ulp outwards.
    pub fn widened(self) -> Interval {
        Interval::from_rounded(self.lo, self.hi)
    }

    /// `hi − lo` (rounded up).
    pub fn width(&self) -> f64 {
        (self.hi - self.lo).next_up()
    }

    /// `max(|lo|, |hi|)`.
    pub fn magnitude(&self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// Whether `0 ∈ self`.
    pub fn contains_zero(&self) -> bool {
        self.lo <= 0.0 && 0.0 <= self.hi
    }

    /// Whether `self` lies in the interior of `other` (`other.lo < lo`, `hi < other.hi`).
    pub fn strictly_inside(&self, other: &Interval) -> bool {
        other.lo < self.lo && self.hi < other.hi
    }

    /// Whether the two intervals share a point.
    pub fn meets(&self, other: &Interval) -> bool {
        self.lo <= other.hi && other.lo <= self.hi
    }

    /// Whether both ends are finite.
    pub fn is_bounded(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }

    /// `1/self` for an interval that excludes zero (`None` otherwise).
    pub fn recip(&self) -> Option<Interval> {
        if self.contains_zero() || !self.lo.is_finite() || !self.hi.is_finite() {
            return None;
        }
        Some(Interval::from_rounded(1.0 / self.hi, 1.0 / self.lo))
    }

    /// `sqrt` of the non-negative part (`None` if the interval is entirely negative).
    pub fn sqrt(&self) -> Option<Interval> {
        if self.hi < 0.0 {
            return None;
        }
        let lo = self.lo.max(0.0).sqrt().next_down().max(0.0);
        Some(Interval {
            lo,
            hi: self.hi.sqrt().next_up(),
        })
    }
}

/// `x.next_up()` for a non-NaN `x`, without branches: the bit pattern moves one step
/// away from zero for `x > 0` (and `−0`, `+0` go to the smallest positive number),
/// towards zero for `x < 0`; `+∞` stays.
#[inline]
fn next_up(x: f64) -> f64 {
    let bits = x.to_bits();
    let step = (((bits as i64) >> 63) | 1) as u64;
    let next = if bits & !(1 << 63) == 0 {
        1
    } else {
        bits.wrapping_add(step)
    };
    f64::from_bits(if x == f64::INFINITY { bits } else { next })
}

/// `x.next_down()` for a non-NaN `x`.
#[inline]
fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// The smaller of two non-NaN numbers (either zero when they are `±0`).
#[inline]
fn min(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// The larger of two non-NaN numbers (either zero when they are `±0`).
#[inline]
fn max(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

impl Add for Interval {
    type Output = Interval;
    #[inline]
    fn add(self, o: Interval) -> Interval {
        Interval::from_rounded(self.lo + o.lo, self.hi + o.hi)
    }
}

impl Sub for Interval {
    type Output = Interval;
    #[inline]
    fn sub(self, o: Interval) -> Interval {
        Interval::from_rounded(self.lo - o.hi, self.hi - o.lo)
    }
}

impl Mul for Interval {
    type Output = Interval;
    #[inline]
    fn mul(self, o: Interval) -> Interval {
        let (a, b, c, d) = (
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        );
        if a.is_nan() | b.is_nan() | c.is_nan() | d.is_nan() {
            return Interval::ENTIRE;
        }
        // A factor that is exactly zero gives an exact zero (0·x = 0 in floating point
        // too); otherwise widen, also where a product underflowed to zero. (The sign
        // of a zero end does not matter: both zeros round to the same neighbours.)
        if (self.lo == 0.0 && self.hi == 0.0) || (o.lo == 0.0 && o.hi == 0.0) {
            return Interval::point(0.0);
        }
        Interval {
            lo: next_down(min(min(a, b), min(c, d))),
            hi: next_up(max(max(a, b), max(c, d))),
        }
    }
}

impl Neg for Interval {
    type Output = Interval;
    #[inline]
    fn neg(self) -> Interval {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

/// A complex rectangle `re + i·im`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ComplexInterval {
    /// Real part.
    pub re: Interval,
    /// Imaginary part.
    pub im: Interval,
}

impl Default for ComplexInterval {
    fn default() -> Self {
        ComplexInterval::point(C64::new(0.0, 0.0))
    }
}

impl ComplexInterval {
    /// The rectangles of half-width `radius` (outward rounded) around each of
    /// `centers`: a box of points as an interval vector.
    pub fn boxes(centers: &[C64], radius: f64) -> Vec<ComplexInterval> {
        centers
            .iter()
            .map(|&c| ComplexInterval::centered(c, radius))
            .collect()
    }

    /// The degenerate rectangle `{z}`.
    #[inline]
    pub fn point(z: C64) -> ComplexInterval {
        ComplexInterval {
            re: Interval::point(z.re),
            im: Interval::point(z.im),
        }
    }

    /// The square `z + [−r, r] + i[−r, r]`.
    pub fn centered(z: C64, r: f64) -> ComplexInterval {
        ComplexInterval {
            re: Interval::centered(z.re, r),
            im: Interval::centered(z.im, r),
        }
    }

    /// The midpoint (rounded).
    pub fn midpoint(&self) -> C64 {
        C64::new(
            0.5 * self.re.lo + 0.5 * self.re.hi,
            0.5 * self.im.lo + 0.5 * self.im.hi,
        )
    }

    /// `max` of the real and imaginary magnitudes (an upper bound of `|z|/√2`… `|z|`
    /// up to √2: the ∞-norm of the rectangle).
    pub fn magnitude(&self) -> f64 {
        self.re.magnitude().max(self.im.magnitude())
    }

    /// `self · s` for a real scalar `s` (exact when `s = ±1`).
    pub fn scale(&self, s: Interval) -> ComplexInterval {
        ComplexInterval {
            re: self.re * s,
            im: self.im * s,
        }
    }

    /// Whether both parts lie in the interiors of `other`'s.
    pub fn strictly_inside(&self, other: &ComplexInterval) -> bool {
        self.re.strictly_inside(&other.re) && self.im.strictly_inside(&other.im)
    }

    /// Whether the two rectangles share a point.
    pub fn meets(&self, other: &ComplexInterval) -> bool {
        self.re.meets(&other.re) && self.im.meets(&other.im)
    }

    /// Whether both parts are bounded.
    pub fn is_bounded(&self) -> bool {
        self.re.is_bounded() && self.im.is_bounded()
    }
}

complex_add_sub_neg!(ComplexInterval);

impl Mul for ComplexInterval {
    type Output = ComplexInterval;
    #[inline]
    fn mul(self, o: ComplexInterval) -> ComplexInterval {
        ComplexInterval {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
}

/// A complex rectangle in midpoint–radius form: real part in `[re − rad_re, re + rad_re]`,
/// imaginary part in `[im − rad_im, im + rad_im]` (radii non-negative; a NaN or an
/// infinity anywhere means "unbounded"). The arithmetic of the interval tapes
/// ([`crate::system::compile`]): a product costs one floating-point complex product for
/// the midpoint and a few real products of absolute values for the radius, with no
/// branches and no change of rounding mode, where the inf–sup [`ComplexInterval`]
/// product takes sixteen real products, their minima and maxima and outward steps
/// (Rump, "Fast and parallel interval arithmetic", BIT 39 (1999) 534–554; midpoint–
/// radius arithmetic in round-to-nearest as in Rump, "Fast interval matrix
/// multiplication", Numer. Algorithms 61 (2012) 1–34).
///
/// **Enclosure.** With `u = 2⁻⁵³`, `η = 2⁻¹⁰⁷⁴` and round-to-nearest, a product
/// rounds as `fl(xy) = xy(1 + δ) + ε` with `|δ| ≤ u`, `|ε| ≤ η/2`, and a sum as
/// `fl(x ± y) = (x ± y)/(1 + δ)` (exact if subnormal) (Higham, "Accuracy and Stability
/// of Numerical Algorithms", SIAM 2002, §2.2). Hence
/// - a sum's midpoint `m = fl(a ± c)` is off by at most `u·|m|`, and the exact set lies
///   in `m ± (r_a + r_c + u·|m|)`;
/// - for `z = (a + ib) ± (r_a, r_b)`, `w = (c + id) ± (r_c, r_d)`:
///   `Re zw ∈ ac − bd ± (|a|r_c + r_a(|c| + r_c) + |b|r_d + r_b(|d| + r_d))` and
///   `Im zw ∈ ad + bc ± (|a|r_d + r_a(|d| + r_d) + |b|r_c + r_b(|c| + r_c))`, and the
///   computed midpoint `fl(fl(ac) − fl(bd))` is off by at most
///   `(2u + u²)(|ac| + |bd|) + 2η ≤ γ₂(|a||c| + |b||d|) + 2η`, `γ₂ = 2u/(1 − 2u)`
///   (similarly for `Im`);
/// - a product by a real `s ± r_s`: `m = fl(a·s)`, `a·s` off by `u·|m| + η/2`, the set
///   in `m ± (|s|·r_a + r_s(|a| + r_a) + u·|m|)`.
///
/// Every radius is a sum of non-negative terms computed in round-to-nearest; each term
/// goes through at most 8 roundings (products, sums), so the computed sum is at least
/// `(1 − u)⁸` times the exact one less `η/2` per product that underflowed (at most 12;
/// an underflowed product is never multiplied by a factor above 1 afterwards).
/// `upper_radius` returns `fl(fl(s·(1 + 10⁻¹⁴)) + 2⁻¹⁰¹⁸)`, which exceeds
/// `s/(1 − u)⁸ + 12·η/2 + 2η` (the midpoint's underflow) with room to spare: `1 + 10⁻¹⁴`
/// is above `(1 − u)⁻¹⁰` (its own two roundings included), and `2⁻¹⁰¹⁸·(1 − u)` above
/// `14η`, also where `s·(1 + 10⁻¹⁴)` is absorbed by the sum or is subnormal (error `η/2`).
/// NaN and ∞ propagate through `+ − ×` and `abs` (∞·0 is NaN, ∞ − ∞ is NaN), so an
/// overflow can only produce an unbounded result ([`MidRad::to_interval`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MidRad {
    /// Midpoint, real part.
    pub re: f64,
    /// Midpoint, imaginary part.
    pub im: f64,
    /// Radius of the real part.
    pub rad_re: f64,
    /// Radius of the imaginary part.
    pub rad_im: f64,
}

/// `u = 2⁻⁵³`.
const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;
/// An upper bound of `γ₂ = 2u/(1 − 2u)` (`2.2204460492503136e-16`).
const GAMMA_2: f64 = 2.3e-16;

/// An upper bound of the exact value of a radius computed as `s` (see [`MidRad`]).
#[inline(always)]
fn upper_radius(s: f64) -> f64 {
    s * (1.0 + 1e-14) + f64::from_bits(4 << 52)
}

/// Midpoint and radius (rounded up) of one part of a rectangle; NaN for an unbounded
/// part.
#[inline]
fn mid_rad(v: Interval) -> (f64, f64) {
    if !v.is_bounded() {
        return (f64::NAN, f64::NAN);
    }
    let m = 0.5 * v.lo + 0.5 * v.hi;
    // `hi − m` and `m − lo` are rounded to nearest: within `u` of the exact values
    // (exact if subnormal); the next float above covers that.
    (m, next_up((v.hi - m).max(m - v.lo)))
}

impl MidRad {
    /// The rectangle `v` (its midpoint and a radius rounded up).
    #[inline]
    pub fn from_interval(v: &ComplexInterval) -> MidRad {
        let (re, rad_re) = mid_rad(v.re);
        let (im, rad_im) = mid_rad(v.im);
        MidRad {
            re,
            im,
            rad_re,
            rad_im,
        }
    }

    /// The point `z` (radius zero).
    #[inline]
    pub fn point(z: C64) -> MidRad {
        MidRad {
            re: z.re,
            im: z.im,
            rad_re: 0.0,
            rad_im: 0.0,
        }
    }

    /// The rectangle as inf–sup intervals, rounded outwards ([`Interval::ENTIRE`] parts
    /// where a value is not finite).
    #[inline]
    pub fn to_interval(&self) -> ComplexInterval {
        let part = |m: f64, r: f64| {
            if m.is_finite() && r.is_finite() {
                Interval::centered(m, r)
            } else {
                Interval::ENTIRE
            }
        };
        ComplexInterval {
            re: part(self.re, self.rad_re),
            im: part(self.im, self.rad_im),
        }
    }

    /// `self · Re(s)` (the real part of `s` with its radius).
    #[inline(always)]
    pub fn scale_by_real_part(self, s: MidRad) -> MidRad {
        let (re, im) = (self.re * s.re, self.im * s.re);
        let sa = s.re.abs();
        MidRad {
            re,
            im,
            rad_re: upper_radius(
                sa * self.rad_re
                    + s.rad_re * (self.re.abs() + self.rad_re)
                    + UNIT_ROUNDOFF * re.abs(),
            ),
            rad_im: upper_radius(
                sa * self.rad_im
                    + s.rad_re * (self.im.abs() + self.rad_im)
                    + UNIT_ROUNDOFF * im.abs(),
            ),
        }
    }
}

impl MidRad {
    /// The box of `self ± o` with the rounded midpoint `(re, im)`: the radii add, plus
    /// one rounding error `u·|mid|` per part (Rump, *Fast and parallel interval
    /// arithmetic*, BIT 39, 1999).
    #[inline(always)]
    fn sum_with(self, (re, im): (f64, f64), o: MidRad) -> MidRad {
        MidRad {
            re,
            im,
            rad_re: upper_radius(self.rad_re + o.rad_re + UNIT_ROUNDOFF * re.abs()),
            rad_im: upper_radius(self.rad_im + o.rad_im + UNIT_ROUNDOFF * im.abs()),
        }
    }
}

impl Add for MidRad {
    type Output = MidRad;
    #[inline(always)]
    fn add(self, o: MidRad) -> MidRad {
        self.sum_with((self.re + o.re, self.im + o.im), o)
    }
}

impl Sub for MidRad {
    type Output = MidRad;
    #[inline(always)]
    fn sub(self, o: MidRad) -> MidRad {
        self.sum_with((self.re - o.re, self.im - o.im), o)
    }
}

impl Mul for MidRad {
    type Output = MidRad;
    #[inline(always)]
    fn mul(self, o: MidRad) -> MidRad {
        let (a, b, c, d) = (self.re, self.im, o.re, o.im);
        let (ra, rb, rc, rd) = (self.rad_re, self.rad_im, o.rad_re, o.rad_im);
        let (aa, ab, ac, ad) = (a.abs(), b.abs(), c.abs(), d.abs());
        MidRad {
            re: a * c - b * d,
            im: a * d + b * c,
            rad_re: upper_radius(
                aa * rc + ra * (ac + rc) + ab * rd + rb * (ad + rd) + GAMMA_2 * (aa * ac + ab * ad),
            ),
            rad_im: upper_radius(
                aa * rd + ra * (ad + rd) + ab * rc + rb * (ac + rc) + GAMMA_2 * (aa * ad + ab * ac),
            ),
        }
    }
}

impl Neg for MidRad {
    type Output = MidRad;
    #[inline(always)]
    fn neg(self) -> MidRad {
        MidRad {
            re: -self.re,
            im: -self.im,
            ..self
        }
    }
}

/// A constant `v` of a formula as an interval: exact for integers, otherwise widened by
/// an ulp on each side, since a constant such as `1/3` was itself rounded once.
fn constant(v: f64) -> Interval {
    if v.fract() == 0.0 && v.abs() < 9.0e15 {
        Interval::point(v)
    } else {
        Interval::from_rounded(v, v)
    }
}

impl Ring for Interval {
    fn from_f64(value: f64) -> Self {
        constant(value)
    }
}

impl Ring for ComplexInterval {
    fn from_f64(value: f64) -> Self {
        ComplexInterval {
            re: constant(value),
            im: Interval::point(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tenth_times_ten_encloses_one() {
        // 0.1 is not representable; [0.1] · 10 must contain the exact product of the
        // rounded 0.1 and 10, and a sum of ten must contain 1.
        let tenth = Interval::from_f64(0.1);
        assert!(tenth.lo < 0.1 && 0.1 < tenth.hi);
        let mut sum = Interval::point(0.0);
        for _ in 0..10 {
            sum = sum + tenth;
        }
        assert!(sum.lo <= 1.0 && 1.0 <= sum.hi, "{sum:?}");
        assert!(sum.width() < 1e-14);
    }

    #[test]
    fn products_take_every_corner() {
        let a = Interval { lo: -2.0, hi: 3.0 };
        let b = Interval { lo: -5.0, hi: 4.0 };
        let p = a * b;
        assert!(p.lo <= -15.0 && p.hi >= 12.0 && p.hi < 12.0 + 1e-12);
        assert_eq!(a * Interval::point(0.0), Interval::point(0.0));
    }

    #[test]
    fn overflow_and_nan_become_entire() {
        let huge = Interval::point(f64::MAX);
        assert!(!(huge * huge).is_bounded());
        let inf = Interval::point(f64::INFINITY);
        let nan = inf - inf;
        assert_eq!(nan, Interval::ENTIRE);
        assert!(!nan.strictly_inside(&Interval::ENTIRE));
    }

    /// Ends and intervals for the bit-for-bit tests: zeros, subnormals, extremes,
    /// infinities, and random values of many magnitudes.
    fn test_values() -> Vec<f64> {
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            5e-324,
            -5e-324,
            1e-310,
            -1e-310,
            f64::MIN_POSITIVE,
            f64::MAX,
            -f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut rng = crate::random::stream(5, 2);
        for _ in 0..40 {
            let exponent = crate::random::uniform(&mut rng, -300.0, 300.0).round() as i32;
            values.push(crate::random::uniform(&mut rng, -1.0, 1.0) * 10f64.powi(exponent));
        }
        values
    }

    #[test]
    fn branchless_neighbours_are_the_standard_ones() {
        for x in test_values() {
            assert_eq!(next_up(x).to_bits(), x.next_up().to_bits(), "{x:e}");
            assert_eq!(next_down(x).to_bits(), x.next_down().to_bits(), "{x:e}");
        }
    }

    /// The product is the hull of the four corner products, rounded outwards, with the
    /// exact zero and NaN rules (the textbook form, bit for bit).
    #[test]
    fn products_are_the_rounded_corner_hull() {
        let reference = |x: Interval, y: Interval| {
            let p = [x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi];
            if p.iter().any(|v| v.is_nan()) {
                return Interval::ENTIRE;
            }
            if x == Interval::point(0.0) || y == Interval::point(0.0) {
                return Interval::point(0.0);
            }
            let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            Interval {
                lo: lo.next_down(),
                hi: hi.next_up(),
            }
        };
        let values = test_values();
        let mut boxes = vec![Interval::ENTIRE];
        for &a in &values {
            for &b in &values {
                if a <= b {
                    boxes.push(Interval { lo: a, hi: b });
                }
            }
        }
        let bits = |v: Interval| (v.lo.to_bits(), v.hi.to_bits());
        for &x in &boxes {
            for &y in &boxes {
                assert_eq!(bits(x * y), bits(reference(x, y)), "{x:?} × {y:?}");
            }
        }
    }

    #[test]
    fn complex_product_encloses_i_squared() {
        let i = ComplexInterval::point(C64::new(0.0, 1.0));
        let minus_one = i * i;
        assert!(minus_one.re.lo <= -1.0 && minus_one.re.hi >= -1.0);
        assert!(minus_one.im.contains_zero());
        let z = ComplexInterval::centered(C64::new(1.0, 2.0), 0.5);
        let w = z * z;
        // Every corner product of the square lies in the rectangle.
        for (dx, dy) in [(-0.5, -0.5), (0.5, 0.5), (-0.5, 0.5), (0.5, -0.5)] {
            let c = C64::new(1.0 + dx, 2.0 + dy);
            let c2 = c * c;
            assert!(w.re.lo <= c2.re && c2.re <= w.re.hi);
            assert!(w.im.lo <= c2.im && c2.im <= w.im.hi);
        }
    }

    /// Random rectangles of many magnitudes and widths (some points, some subnormal).
    fn random_rectangles(count: usize) -> Vec<ComplexInterval> {
        let mut rng = crate::random::stream(17, 4);
        let mut draw = |lo: f64, hi: f64| crate::random::uniform(&mut rng, lo, hi);
        (0..count)
            .map(|k| {
                let mut part = || {
                    let exponent = if k % 7 == 0 {
                        -310.0
                    } else {
                        draw(-30.0, 30.0).round()
                    };
                    let m = draw(-1.0, 1.0) * 10f64.powf(exponent);
                    let width = match k % 4 {
                        0 => 0.0,
                        1 => m.abs() * 1e-15,
                        2 => m.abs() * draw(0.0, 1e-6),
                        _ => m.abs() * draw(0.0, 2.0),
                    };
                    Interval::centered(m, width)
                };
                ComplexInterval {
                    re: part(),
                    im: part(),
                }
            })
            .collect()
    }

    fn corners(z: &ComplexInterval) -> [C64; 4] {
        [
            C64::new(z.re.lo, z.im.lo),
            C64::new(z.re.lo, z.im.hi),
            C64::new(z.re.hi, z.im.lo),
            C64::new(z.re.hi, z.im.hi),
        ]
    }

    /// Whether the double-double `v` (the number `v.hi + v.lo`) lies in `g`.
    fn dd_inside(v: crate::system::double_double::DoubleDouble, g: Interval) -> bool {
        (v.hi > g.lo || (v.hi == g.lo && v.lo >= 0.0))
            && (v.hi < g.hi || (v.hi == g.hi && v.lo <= 0.0))
    }

    fn inside(exact: &ComplexInterval, got: &ComplexInterval) -> bool {
        got.re.lo <= exact.re.lo
            && exact.re.hi <= got.re.hi
            && got.im.lo <= exact.im.lo
            && exact.im.hi <= got.im.hi
    }

    /// Every part of `zw`, `z ± w` and `z·Re w` is multilinear in the real and
    /// imaginary parts of `z` and `w`, so its extremes over two rectangles are at
    /// corners: the midpoint–radius results must contain the inf–sup enclosures of the
    /// exact corner results (this fails if a radius term or a rounding error is left
    /// out), and must not be much wider than the inf–sup results on the rectangles.
    #[test]
    fn midpoint_radius_operations_enclose_every_corner() {
        use crate::system::double_double::ComplexDd as Dd;
        let boxes = random_rectangles(60);
        for z in &boxes {
            for w in &boxes {
                let (mz, mw) = (MidRad::from_interval(z), MidRad::from_interval(w));
                let results = [
                    ((mz * mw).to_interval(), *z * *w),
                    ((mz + mw).to_interval(), *z + *w),
                    ((mz - mw).to_interval(), *z - *w),
                    ((mz.scale_by_real_part(mw)).to_interval(), z.scale(w.re)),
                ];
                for a in corners(z) {
                    for b in corners(w) {
                        // The exact corner results to about 2⁻¹⁰⁵ relative (products
                        // of doubles are exact in double-double).
                        let (x, y) = (Dd::from_c64(a), Dd::from_c64(b));
                        let exact = [x * y, x + y, x - y, x.scale_by_real_part(y)];
                        for (op, (got, _)) in results.iter().enumerate() {
                            assert!(
                                dd_inside(exact[op].re, got.re) && dd_inside(exact[op].im, got.im),
                                "op {op}: {a} and {b} of {z:?}, {w:?}: {:?} not in {got:?}",
                                exact[op]
                            );
                        }
                    }
                }
                for (op, (got, reference)) in results.iter().enumerate() {
                    let slack = |r: Interval, g: Interval| {
                        g.width() <= 3.0 * r.width() + 1e-300 + 1e-13 * r.magnitude()
                    };
                    assert!(
                        slack(reference.re, got.re) && slack(reference.im, got.im),
                        "op {op}: {got:?} much wider than {reference:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn midpoint_radius_overflow_and_unbounded_inputs_become_entire() {
        let huge = MidRad::point(C64::new(f64::MAX, 0.0));
        assert!(!(huge * huge).to_interval().is_bounded());
        assert!(!(huge + huge).to_interval().is_bounded());
        // ∞ − ∞ and ∞·0 are NaN, which no later operation turns finite.
        let zero = MidRad::point(C64::new(0.0, 0.0));
        let nan = (huge * huge - huge * huge) * zero + zero;
        assert_eq!(nan.to_interval().re, Interval::ENTIRE);
        let entire = ComplexInterval {
            re: Interval::ENTIRE,
            im: Interval::point(0.0),
        };
        let product = MidRad::from_interval(&entire) * zero;
        assert_eq!(product.to_interval().re, Interval::ENTIRE);
        // Radii are rounded up: [1, 1 + 2⁻⁵²] keeps both ends.
        let one = ComplexInterval {
            re: Interval {
                lo: 1.0,
                hi: 1.0 + f64::EPSILON,
            },
            im: Interval::point(0.0),
        };
        assert!(inside(&one, &MidRad::from_interval(&one).to_interval()));
    }
}

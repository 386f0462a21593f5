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
}

//! Midpoint–radius intervals with double-double midpoints: enclosures of a system's
//! values at a point known to about 32 significant digits, for Krawczyk's test on
//! critical points too ill-conditioned for double precision
//! ([`crate::certify::krawczyk`]).
//!
//! A [`RealDd`] is the set `mid ± rad` with a double-double midpoint `mid` (an
//! unevaluated sum `hi + lo` of two doubles, [`DoubleDouble`]) and a double radius; a
//! [`MidRadDd`] is a complex rectangle of two of them.
//!
//! **Enclosure.** The midpoints are computed by [`DoubleDouble`]'s own operations.
//! With `u = 2⁻⁵³` and no underflow, its sum (Algorithm 6, "AccurateDWPlusDW", of
//! Joldes, Muller, Popescu, "Tight and rigorous error bounds for basic building blocks
//! of double-word arithmetic", ACM Trans. Math. Softw. 44 (2017)) is within
//! `3u²/(1 − 4u)` of the exact sum relative to it, and its product (their
//! Algorithm 10, "DWTimesDW1", with an exact `TwoProduct`) within `7u²`; the bounds
//! used here are `8u²` (`ADD_ERROR`) and `16u²` (`MUL_ERROR`), and a complex
//! product's part `ac − bd` is within `(16 + 8·(1 + 16u²))u² ≤ 32u²` of
//! `|a||c| + |b||d|` (`COMPLEX_MUL_ERROR`). Each operation adds `TINY` (`2⁻⁹⁹⁰`)
//! for underflow, which exceeds the few `2⁻¹⁰⁷⁴` an underflowing error term can lose.
//! The radius of a result is the exact set's deviation from the exact result of the
//! midpoints (as for [`crate::system::interval::MidRad`]) plus that rounding error, a
//! sum of non-negative terms computed in round-to-nearest, each term through fewer
//! than 100 roundings: `upper` multiplies it by `1 + 10⁻¹³` (more than
//! `(1 − u)⁻¹⁰⁰`) and adds `TINY`. Magnitudes `|hi + lo|` are bounded by `magnitude`.
//! A NaN or an infinity anywhere makes the enclosure the whole line
//! ([`RealDd::to_interval`]).

use super::double_double::{ComplexDd, DoubleDouble};
use super::interval::{ComplexInterval, Interval, MidRad};
use crate::C64;
use std::ops::{Add, Mul, Neg, Sub};

/// `u²`, `u = 2⁻⁵³`.
const U2: f64 = (f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);
/// Bound of a double-double sum's relative error (see the module documentation).
const ADD_ERROR: f64 = 8.0 * U2;
/// Bound of a double-double product's relative error.
const MUL_ERROR: f64 = 16.0 * U2;
/// Bound of the error of a complex product's part relative to `|a||c| + |b||d|`.
const COMPLEX_MUL_ERROR: f64 = 32.0 * U2;
/// `2⁻⁹⁹⁰`: added to every radius for underflow.
const TINY: f64 = f64::from_bits(33 << 52);

/// An upper bound of the exact value of a sum of non-negative terms computed as `s`
/// (see the module documentation).
#[inline]
fn upper(s: f64) -> f64 {
    s * (1.0 + 1e-13) + TINY
}

/// An upper bound of `|hi + lo|`: `fl(|hi| + |lo|)` loses at most `u` relative, and
/// the factor `1 + 10⁻¹⁵` (rounded) more than makes up for it and its own rounding.
#[inline]
fn magnitude(x: DoubleDouble) -> f64 {
    (x.hi.abs() + x.lo.abs()) * (1.0 + 1e-15)
}

/// A real interval `mid ± rad` with a double-double midpoint.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RealDd {
    /// Midpoint.
    pub mid: DoubleDouble,
    /// Radius (non-negative).
    pub rad: f64,
}

impl RealDd {
    /// The double `v` exactly.
    pub fn exact(v: f64) -> RealDd {
        RealDd {
            mid: DoubleDouble::from_f64(v),
            rad: 0.0,
        }
    }

    /// An upper bound of `|x|` over the interval.
    pub fn magnitude(&self) -> f64 {
        upper(magnitude(self.mid) + self.rad)
    }

    /// The interval as an inf–sup [`Interval`] of doubles, rounded outwards
    /// ([`Interval::ENTIRE`] if anything is not finite).
    pub fn to_interval(&self) -> Interval {
        let RealDd { mid, rad } = *self;
        if !(mid.hi.is_finite() && mid.lo.is_finite() && rad.is_finite()) {
            return Interval::ENTIRE;
        }
        Interval::point(mid.hi) + Interval::centered(mid.lo, rad)
    }

    /// `1/x` over the interval, if it excludes zero. With `q ≈ 1/m` (the double-double
    /// reciprocal of the midpoint `m`), `|1/x − q| ≤ |x − m|/(|x||m|) + |1 − m q|/|m|`,
    /// and `1 − m q` is enclosed in this arithmetic.
    pub fn recip(self) -> Option<RealDd> {
        let m = self.mid;
        // A lower bound of |m|: |lo| ≤ u|hi|, so |hi| − 2|lo| (rounded) is below it.
        let low = (m.hi.abs() - 2.0 * m.lo.abs()) * (1.0 - 1e-15);
        if !(low > 2.0 * self.rad && low.is_finite()) {
            return None;
        }
        let q = m.recip();
        let residual = RealDd::exact(1.0) - RealDd { mid: m, rad: 0.0 } * RealDd::exact_dd(q);
        let spread = self.rad / ((low - self.rad) * low);
        let rounding = residual.magnitude() / low;
        let rad = upper(spread * (1.0 + 1e-13) + rounding * (1.0 + 1e-13));
        rad.is_finite().then_some(RealDd { mid: q, rad })
    }

    /// `√x` over the interval, if it is positive. With `s ≈ √m` (one Newton step in
    /// double-double from the double square root), `|√x − s| = |x − s²|/(√x + s) ≤
    /// (|m − s²| + rad)/s`, and `m − s²` is enclosed in this arithmetic.
    pub fn sqrt(self) -> Option<RealDd> {
        let m = self.mid;
        if !(m.hi > 0.0 && m.hi.is_finite()) {
            return None;
        }
        let s0 = m.hi.sqrt();
        let correction =
            (m - DoubleDouble::from_f64(s0) * DoubleDouble::from_f64(s0)).value() / (2.0 * s0);
        let s = DoubleDouble::from_f64(s0) + DoubleDouble::from_f64(correction);
        let residual = RealDd { mid: m, rad: 0.0 } - RealDd::exact_dd(s) * RealDd::exact_dd(s);
        let low = (s.hi - 2.0 * s.lo.abs()) * (1.0 - 1e-15);
        if low.is_nan() || low <= 0.0 {
            return None;
        }
        let rad = upper((residual.magnitude() + self.rad) / low * (1.0 + 1e-13));
        rad.is_finite().then_some(RealDd { mid: s, rad })
    }

    /// The double-double `v` exactly.
    fn exact_dd(v: DoubleDouble) -> RealDd {
        RealDd { mid: v, rad: 0.0 }
    }
}

impl Add for RealDd {
    type Output = RealDd;
    #[inline]
    fn add(self, o: RealDd) -> RealDd {
        let mid = self.mid + o.mid;
        RealDd {
            mid,
            rad: upper(self.rad + o.rad + ADD_ERROR * magnitude(mid)),
        }
    }
}

impl Neg for RealDd {
    type Output = RealDd;
    #[inline]
    fn neg(self) -> RealDd {
        RealDd {
            mid: -self.mid,
            rad: self.rad,
        }
    }
}

/// `a − b = a + (−b)`: negation is exact, so the sum's enclosure is the difference's.
impl Sub for RealDd {
    type Output = RealDd;
    #[inline]
    fn sub(self, o: RealDd) -> RealDd {
        self + -o
    }
}

impl Mul for RealDd {
    type Output = RealDd;
    #[inline]
    fn mul(self, o: RealDd) -> RealDd {
        let (a, c) = (magnitude(self.mid), magnitude(o.mid));
        RealDd {
            mid: self.mid * o.mid,
            rad: upper(a * o.rad + self.rad * (c + o.rad) + MUL_ERROR * a * c),
        }
    }
}

/// A complex rectangle `re + i·im` of two [`RealDd`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MidRadDd {
    /// Real part.
    pub re: RealDd,
    /// Imaginary part.
    pub im: RealDd,
}

impl MidRadDd {
    /// The complex double-double `z` exactly.
    pub fn point(z: ComplexDd) -> MidRadDd {
        MidRadDd {
            re: RealDd {
                mid: z.re,
                rad: 0.0,
            },
            im: RealDd {
                mid: z.im,
                rad: 0.0,
            },
        }
    }

    /// The real interval `x` as a rectangle.
    pub fn real(x: RealDd) -> MidRadDd {
        MidRadDd {
            re: x,
            im: RealDd::exact(0.0),
        }
    }

    /// The midpoint (a complex double-double).
    pub fn midpoint(&self) -> ComplexDd {
        ComplexDd {
            re: self.re.mid,
            im: self.im.mid,
        }
    }

    /// The rectangle as inf–sup intervals of doubles, rounded outwards.
    pub fn to_interval(&self) -> ComplexInterval {
        ComplexInterval {
            re: self.re.to_interval(),
            im: self.im.to_interval(),
        }
    }
}

// Sums, differences, negations and `z · Re(w)` part by part (`RealDd`'s enclosures,
// the radius of `Re(w)` included).
complex_add_sub_neg!(MidRadDd, scale_by_real_part);

impl Mul for MidRadDd {
    type Output = MidRadDd;
    /// `(a + ib)(c + id)`: midpoint parts `ac − bd`, `ad + bc` in double-double; the
    /// radius of `Re` is `|a| r_c + r_a(|c| + r_c) + |b| r_d + r_b(|d| + r_d)` plus the
    /// rounding error `32u²(|a||c| + |b||d|)` (and symmetrically for `Im`).
    #[inline]
    fn mul(self, o: MidRadDd) -> MidRadDd {
        let (a, b) = (magnitude(self.re.mid), magnitude(self.im.mid));
        let (c, d) = (magnitude(o.re.mid), magnitude(o.im.mid));
        let (ra, rb, rc, rd) = (self.re.rad, self.im.rad, o.re.rad, o.im.rad);
        let re = self.re.mid * o.re.mid + -(self.im.mid * o.im.mid);
        let im = self.re.mid * o.im.mid + self.im.mid * o.re.mid;
        // The part `p·q + r·t` (midpoint `mid`) of boxes `p ± r_p`, … .
        let part = |mid, (p, rp): (f64, f64), (q, rq): (f64, f64), (r, rr), (t, rt)| RealDd {
            mid,
            rad: upper(
                p * rq
                    + rp * (q + rq)
                    + r * rt
                    + rr * (t + rt)
                    + COMPLEX_MUL_ERROR * (p * q + r * t),
            ),
        };
        MidRadDd {
            re: part(re, (a, ra), (c, rc), (b, rb), (d, rd)),
            im: part(im, (a, ra), (d, rd), (b, rb), (c, rc)),
        }
    }
}

/// `1/√2` as a double-double (`hi + lo` within `2.1·10⁻³³` of it).
const FRAC_1_SQRT_2_DD: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::FRAC_1_SQRT_2,
    lo: -4.833646656726457e-17,
};

/// Largest denominator and numerator of a coefficient read as a fraction
/// ([`coefficient`]).
const FRACTION_DENOMINATOR: u32 = 64;
const FRACTION_NUMERATOR: f64 = 1_048_576.0;

/// The exact number a double coefficient of a system stands for, enclosed: the
/// systems are built from rational coefficients (centroids, moments: `1/3`, `2/9`,
/// `1/42`, …) and `1/√2` (isotropic coordinates, [`crate::algebra::Isotropic`]),
/// which the compiled tapes hold rounded to doubles. A part `v` is read as the
/// integer it is, as `±1/√2` when it is that constant rounded, or as the fraction
/// `p/q` (`q ≤ 64`, `|p| ≤ 2²⁰`, smallest `q`) whose rounding it is; for the fraction,
/// `e = p − v·q` is exact (one fused multiply-add: `|e| ≤ q·ulp(v)/2` is a multiple of
/// `ulp(v)/2` with few bits) and `p/q = v + e/q`, so `lo = fl(e/q)` is within
/// `u·|lo|` of the rest. `None` for a part that is none of these (the double-double
/// test then does not apply).
pub fn coefficient(c: C64) -> Option<MidRadDd> {
    Some(MidRadDd {
        re: coefficient_part(c.re)?,
        im: coefficient_part(c.im)?,
    })
}

/// [`coefficient`] as a double midpoint–radius rectangle ([`MidRad`], the arithmetic
/// of the double interval tapes): `hi ± (|lo| + rad)` per part, the radius rounded up;
/// the point `c` itself where it is not recognised.
pub fn coefficient_enclosure(c: C64) -> MidRad {
    let Some(exact) = coefficient(c) else {
        return MidRad::point(c);
    };
    let radius = |part: RealDd| {
        if part.mid.lo == 0.0 && part.rad == 0.0 {
            0.0
        } else {
            (part.mid.lo.abs() + part.rad) * (1.0 + 1e-15) + f64::MIN_POSITIVE
        }
    };
    MidRad {
        re: exact.re.mid.hi,
        im: exact.im.mid.hi,
        rad_re: radius(exact.re),
        rad_im: radius(exact.im),
    }
}

fn coefficient_part(v: f64) -> Option<RealDd> {
    if !v.is_finite() {
        return None;
    }
    if v.fract() == 0.0 {
        return Some(RealDd::exact(v));
    }
    if v.abs() == std::f64::consts::FRAC_1_SQRT_2 {
        let mid = if v > 0.0 {
            FRAC_1_SQRT_2_DD
        } else {
            -FRAC_1_SQRT_2_DD
        };
        return Some(RealDd { mid, rad: 1e-32 });
    }
    (2..=FRACTION_DENOMINATOR).find_map(|q| {
        let q = q as f64;
        let p = (v * q).round();
        if p.abs() > FRACTION_NUMERATOR || p / q != v {
            return None;
        }
        let e = (-v).mul_add(q, p);
        if e == 0.0 {
            // A dyadic fraction: the double is exact.
            return Some(RealDd::exact(v));
        }
        let lo = e / q;
        Some(RealDd {
            mid: DoubleDouble { hi: v, lo },
            rad: upper(lo.abs() * (f64::EPSILON / 2.0)),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dd(hi: f64, lo: f64) -> RealDd {
        RealDd {
            mid: DoubleDouble { hi, lo },
            rad: 0.0,
        }
    }

    /// The enclosure `[lo, hi]` as exact rationals is out of reach without big
    /// numbers; instead identities whose exact value is known: `(1/3)·3 = 1` with the
    /// fraction `1/3` read from its double, `(1/√2)² = 1/2`, `√2·√2 = 2`, and
    /// `(1/7)·7 = 1` from the reciprocal. Each enclosure must contain the exact value
    /// and be far narrower than a double's ulp.
    #[test]
    fn enclosures_of_known_values_contain_them_and_are_tight() {
        let contains = |x: RealDd, value: f64, width: f64| {
            let i = x.to_interval();
            assert!(i.lo <= value && value <= i.hi, "{x:?} misses {value}");
            // The midpoint's deviation from the value (exact: both are near `value`).
            let deviation = (x.mid.hi - value) + x.mid.lo;
            assert!(
                deviation.abs() <= x.rad,
                "{x:?} misses {value} by {deviation:e}"
            );
            assert!(x.rad <= width, "{x:?} too wide");
        };
        let third = coefficient_part(1.0 / 3.0).unwrap();
        contains(third * RealDd::exact(3.0), 1.0, 1e-29);
        let root = coefficient_part(std::f64::consts::FRAC_1_SQRT_2).unwrap();
        contains(root * root, 0.5, 1e-29);
        let two = RealDd::exact(2.0).sqrt().unwrap();
        contains(two * two, 2.0, 1e-29);
        let seventh = RealDd::exact(7.0).recip().unwrap();
        contains(seventh * RealDd::exact(7.0), 1.0, 1e-29);
        let ninth = coefficient_part(1.0 / 9.0).unwrap();
        contains(ninth * RealDd::exact(9.0), 1.0, 1e-29);
        // A radius on the input carries over: 1/(4 ± 2⁻⁴⁰) is 1/4 ± 2⁻⁴⁴ to first order.
        let wide = RealDd {
            mid: DoubleDouble::from_f64(4.0),
            rad: 2f64.powi(-40),
        }
        .recip()
        .unwrap();
        assert!(
            wide.rad >= 2f64.powi(-44) && wide.rad < 2f64.powi(-43),
            "{wide:?}"
        );
    }

    /// Every `x` in the operands' rectangles gives a product in the result's: checked
    /// on the corners, with the products formed in double-double of the corners
    /// (error far below the radii, which are at least 2⁻³⁰ here).
    #[test]
    fn complex_products_enclose_the_products_of_the_corners() {
        let z = MidRadDd {
            re: dd(0.3, 1e-18),
            im: dd(-1.7, 0.0),
        };
        let mut a = z;
        a.re.rad = 2f64.powi(-30);
        a.im.rad = 2f64.powi(-31);
        let mut b = MidRadDd {
            re: dd(2.5, -3e-17),
            im: dd(0.125, 0.0),
        };
        b.im.rad = 2f64.powi(-29);
        let product = (a * b).to_interval();
        for (sa, sb, sc, sd) in itertools_corners() {
            let x = ComplexDd {
                re: a.re.mid + DoubleDouble::from_f64(sa * a.re.rad),
                im: a.im.mid + DoubleDouble::from_f64(sb * a.im.rad),
            };
            let y = ComplexDd {
                re: b.re.mid + DoubleDouble::from_f64(sc * b.re.rad),
                im: b.im.mid + DoubleDouble::from_f64(sd * b.im.rad),
            };
            let p = (x * y).to_c64();
            assert!(product.re.lo <= p.re && p.re <= product.re.hi);
            assert!(product.im.lo <= p.im && p.im <= product.im.hi);
        }
        // A point times a point is as narrow as the rounding error.
        let narrow = z * MidRadDd::point(b.midpoint());
        assert!(narrow.re.rad < 1e-29 && narrow.im.rad < 1e-29, "{narrow:?}");
    }

    fn itertools_corners() -> Vec<(f64, f64, f64, f64)> {
        let s = [-1.0, 1.0];
        let mut out = Vec::new();
        for a in s {
            for b in s {
                for c in s {
                    for d in s {
                        out.push((a, b, c, d));
                    }
                }
            }
        }
        out
    }

    #[test]
    fn coefficients_are_read_as_the_fractions_they_round() {
        // 1/42 and 2/9 (coefficients of the plate metrics) are fractions too.
        assert!(coefficient_part(1.0 / 42.0).unwrap().mid.lo != 0.0);
        assert!(coefficient_part(2.0 / 9.0).unwrap().mid.lo != 0.0);
        assert_eq!(coefficient_part(0.25).unwrap().mid.lo, 0.0);
        assert_eq!(coefficient_part(-3.0).unwrap(), RealDd::exact(-3.0));
        // π is no fraction of a small denominator.
        assert!(coefficient_part(std::f64::consts::PI).is_none());
        // As double rectangles: 1/3 gets a radius covering 1/3 − fl(1/3), 2 and i/2
        // none, and π (not recognised) stands for itself.
        let third = coefficient_enclosure(C64::new(1.0 / 3.0, 0.0));
        let rest = coefficient_part(1.0 / 3.0).unwrap().mid.lo;
        assert!(
            third.rad_re >= rest.abs() && third.rad_re < 1e-16,
            "{third:?}"
        );
        let exact = coefficient_enclosure(C64::new(2.0, 0.5));
        assert_eq!((exact.rad_re, exact.rad_im), (0.0, 0.0));
        let pi = coefficient_enclosure(C64::new(std::f64::consts::PI, 0.0));
        assert_eq!(pi, MidRad::point(C64::new(std::f64::consts::PI, 0.0)));
    }
}

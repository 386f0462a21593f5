//! Double-double ("DD") complex arithmetic for evaluations and linear solves beyond
//! double precision: a value is an unevaluated sum `hi + lo` with `|lo| ≤ ulp(hi)/2`,
//! about 106 significant bits (Dekker 1971; Hida, Li & Bailey, *Algorithms for
//! quad-double precision floating point arithmetic*, 2001: `two_sum`, `two_prod` by
//! FMA or by Dekker's splitting).
//!
//! Used by the tracker's extended-precision mode: residuals, Jacobians and `∂H/∂t` from
//! the compiled tapes run in DD ([`super::Evaluator::evaluate_extended`],
//! [`super::Evaluator::evaluate_with_jacobian_extended`]) and the DD LU
//! ([`crate::homotopy::linalg::DdLuWorkspace`]). A double-precision residual stalls at
//! a relative noise floor of about `κ(J)·ε·Σ|terms|/|F|`, and a Jacobian or LU in
//! double costs `κ(J)·ε` of relative accuracy in every velocity and Newton update.

use crate::C64;
use std::ops::{Add, Mul, Neg, Sub};

/// A real double-double number `hi + lo`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DoubleDouble {
    /// Leading part (the double nearest the value).
    pub hi: f64,
    /// Trailing part.
    pub lo: f64,
}

#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// The result of `detect`, computed once and cached in `state` (0 unknown, 1 no,
/// 2 yes).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn detected_once(state: &std::sync::atomic::AtomicU8, detect: fn() -> bool) -> bool {
    use std::sync::atomic::Ordering;
    match state.load(Ordering::Relaxed) {
        2 => true,
        1 => false,
        _ => {
            let yes = detect();
            state.store(if yes { 2 } else { 1 }, Ordering::Relaxed);
            yes
        }
    }
}

/// Whether this CPU has fused multiply-add (x86-64: checked once at run time; other
/// architectures: whether the crate was compiled with the feature).
#[inline(always)]
pub fn has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        static STATE: std::sync::atomic::AtomicU8 = std::sync::atomic::AtomicU8::new(0);
        detected_once(&STATE, || std::arch::is_x86_feature_detected!("fma"))
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        cfg!(target_feature = "fma")
    }
}

/// Whether this CPU has AVX2 and FMA (x86-64, checked once at run time; other
/// architectures: never). Kernels compiled a second time with these target features
/// are chosen by it; without explicit `mul_add` the compiler does not fuse, so they
/// round exactly as the baseline copies.
#[inline(always)]
pub fn has_avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        static STATE: std::sync::atomic::AtomicU8 = std::sync::atomic::AtomicU8::new(0);
        detected_once(&STATE, || {
            std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("fma")
        })
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `(p, e)` with `p = fl(a·b)` and `p + e = a·b` exactly (`TwoProduct`). With a
/// hardware FMA one fused multiply-add: inside the double-double kernels compiled with
/// the `fma` target feature ([`Tape`](super::compile) extended runs, the
/// double-double LU) it is one instruction. Without FMA, Dekker's splitting into 26-bit
/// halves (Veltkamp), in ordinary double arithmetic — `f64::mul_add` on a CPU without
/// FMA is a software emulation, several times slower.
#[inline(always)]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    if cfg!(target_feature = "fma") || has_fma() {
        let p = a * b;
        (p, a.mul_add(b, -p))
    } else {
        two_prod_split(a, b)
    }
}

/// [`two_prod`] without FMA: Dekker's product of Veltkamp-split 26-bit halves.
#[inline(always)]
fn two_prod_split(a: f64, b: f64) -> (f64, f64) {
    #[inline(always)]
    fn split(x: f64) -> (f64, f64) {
        const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
        let t = SPLITTER * x;
        let hi = t - (t - x);
        (hi, x - hi)
    }
    let p = a * b;
    let (a_hi, a_lo) = split(a);
    let (b_hi, b_lo) = split(b);
    let e = ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
    (p, e)
}

#[inline(always)]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

impl DoubleDouble {
    /// The exact value of a double.
    #[inline(always)]
    pub fn from_f64(value: f64) -> Self {
        DoubleDouble { hi: value, lo: 0.0 }
    }

    /// `self ← self + a·b` for doubles `a, b`: the product formed exactly by a fused
    /// multiply-add (`TwoProduct`), the sum by Knuth's `TwoSum` (dot products of
    /// mixed-precision iterative refinement).
    #[inline(always)]
    pub fn add_product(&mut self, a: f64, b: f64) {
        let (product, product_error) = two_prod(a, b);
        let (sum, sum_error) = two_sum(self.hi, product);
        let lo = self.lo + sum_error + product_error;
        let (hi, lo) = quick_two_sum(sum, lo);
        self.hi = hi;
        self.lo = lo;
    }

    /// `1 / self` to about 106 bits (one Newton correction of the double reciprocal).
    #[inline(always)]
    pub fn recip(self) -> Self {
        let q1 = 1.0 / self.hi;
        // r = 1 − q1·self, exactly enough: q1·self is within ε of 1.
        let r = DoubleDouble::from_f64(1.0) + -(self * DoubleDouble::from_f64(q1));
        let q2 = r.hi * q1;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo }
    }

    /// `self − x·y`, the product's trailing terms folded into one renormalisation (the
    /// inner update of the double-double LU: about half the work of `self + -(x * y)`).
    #[inline(always)]
    pub fn minus_product(self, x: Self, y: Self) -> Self {
        let (p, e) = two_prod(x.hi, y.hi);
        let e = e + (x.hi * y.lo + x.lo * y.hi);
        let (s, s_error) = two_sum(self.hi, -p);
        let (hi, lo) = quick_two_sum(s, s_error + (self.lo - e));
        DoubleDouble { hi, lo }
    }

    /// Rounded to the nearest double.
    #[inline(always)]
    pub fn value(self) -> f64 {
        self.hi + self.lo
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    /// Sum, correctly rounded to about 106 bits.
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        let (s, e) = two_sum(self.hi, other.hi);
        let (t, f) = two_sum(self.lo, other.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DoubleDouble { hi, lo }
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    /// Difference `a + (−b)` (negation is exact).
    #[inline(always)]
    fn sub(self, other: Self) -> Self {
        self + -other
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    /// Product (FMA for the exact error of `hi·hi`).
    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        let (p, e) = two_prod(self.hi, other.hi);
        let e = e + (self.hi * other.lo + self.lo * other.hi);
        let (hi, lo) = quick_two_sum(p, e);
        DoubleDouble { hi, lo }
    }
}

/// A complex double-double number.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ComplexDd {
    /// Real part.
    pub re: DoubleDouble,
    /// Imaginary part.
    pub im: DoubleDouble,
}

impl ComplexDd {
    /// The exact value of a complex double.
    #[inline(always)]
    pub fn from_c64(value: C64) -> Self {
        ComplexDd {
            re: DoubleDouble::from_f64(value.re),
            im: DoubleDouble::from_f64(value.im),
        }
    }

    /// `hi + lo` for complex doubles (a value known beyond double precision as a
    /// rounded part and its trailing part).
    #[inline(always)]
    pub fn from_parts(hi: C64, lo: C64) -> Self {
        ComplexDd::from_c64(hi) + ComplexDd::from_c64(lo)
    }

    /// `1 / self = conj(self) / |self|²`.
    #[inline(always)]
    pub fn recip(self) -> Self {
        let inverse_norm = (self.re * self.re + self.im * self.im).recip();
        ComplexDd {
            re: self.re * inverse_norm,
            im: -(self.im * inverse_norm),
        }
    }

    /// `self − x·y` for complex double-double numbers
    /// (`(a − Re(xy)) + i(b − Im(xy))` with [`DoubleDouble::minus_product`]).
    #[inline(always)]
    pub fn minus_product(self, x: Self, y: Self) -> Self {
        ComplexDd {
            re: self.re.minus_product(x.re, y.re).minus_product(-x.im, y.im),
            im: self.im.minus_product(x.re, y.im).minus_product(x.im, y.re),
        }
    }

    /// Rounded to the nearest complex double.
    #[inline(always)]
    pub fn to_c64(self) -> C64 {
        C64::new(self.re.hi + self.re.lo, self.im.hi + self.im.lo)
    }
}

complex_add_sub_neg!(ComplexDd, scale_by_real_part);

impl Mul for ComplexDd {
    type Output = Self;
    /// `(a + ib)(c + id) = (ac − bd) + i(ad + bc)`.
    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        ComplexDd {
            re: self.re * other.re + -(self.im * other.im),
            im: self.re * other.im + self.im * other.re,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(1 + 2⁻⁶⁰) − 1` is lost in double precision but exact in double-double, and
    /// `(1 + 2⁻³⁰)²` keeps its `2⁻⁶⁰` term.
    #[test]
    fn keeps_the_bits_double_precision_loses() {
        let tiny = 2f64.powi(-60);
        let one = DoubleDouble::from_f64(1.0);
        let sum = one + DoubleDouble::from_f64(tiny);
        let back = sum + -one;
        assert_eq!(back.hi + back.lo, tiny);
        let x = DoubleDouble::from_f64(1.0 + 2f64.powi(-30));
        let square = x * x;
        let rest = square + DoubleDouble::from_f64(-1.0 - 2f64.powi(-29));
        assert_eq!(rest.hi + rest.lo, tiny);
        let z =
            ComplexDd::from_c64(C64::new(1.0, 2.0)).mul(ComplexDd::from_c64(C64::new(3.0, -1.0)));
        assert_eq!(z.to_c64(), C64::new(5.0, 5.0));
    }

    /// `two_prod` is exact (both branches agree with exact integer arithmetic on
    /// 40-bit operands), and `minus_product` and `recip` keep about 32 digits.
    #[test]
    fn products_differences_and_reciprocals_are_double_double_accurate() {
        let a = (1u64 << 40) as f64 + 12345.0;
        let b = (1u64 << 39) as f64 + 6789.0;
        let exact = ((1u128 << 40) + 12345) * ((1u128 << 39) + 6789);
        // Both the dispatched product and the FMA-free split product are exact.
        for (p, e) in [two_prod(a, b), two_prod_split(a, b)] {
            assert_eq!(p as u128 as i128 + e as i128, exact as i128);
        }
        let (x, y) = (0.1f64, 3.0f64.sqrt());
        let (p1, e1) = two_prod_split(x, y);
        let (p2, e2) = (x * y, x.mul_add(y, -(x * y)));
        assert_eq!((p1, e1), (p2, e2), "split and fused products agree");
        // (1 + 2⁻³⁰)(1 − 2⁻³⁰) = 1 − 2⁻⁶⁰; minus 1 leaves −2⁻⁶⁰ only in DD.
        let x = DoubleDouble::from_f64(1.0 + 2f64.powi(-30));
        let y = DoubleDouble::from_f64(1.0 - 2f64.powi(-30));
        let d = DoubleDouble::from_f64(1.0).minus_product(x, y);
        assert_eq!(d.value(), 2f64.powi(-60));
        let three = DoubleDouble::from_f64(3.0);
        let third = three.recip();
        let back = DoubleDouble::from_f64(1.0).minus_product(three, third);
        assert!(back.value().abs() < 1e-31, "{:e}", back.value());
        let z = ComplexDd::from_c64(C64::new(3.0, -4.0));
        let w = ComplexDd::from_c64(C64::new(1.0, 0.0)).minus_product(z, z.recip());
        assert!(w.to_c64().norm() < 1e-31, "{}", w.to_c64());
    }
}

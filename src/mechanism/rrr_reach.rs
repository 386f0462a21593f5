//! Reach of the legs of a 3-RRR along an analytic motion: where each leg is in its
//! workspace, and where it really passes through its leg singularity (its working mode
//! flips).
//!
//! Leg `i` with proximal length `b`, distal length `c` reaches its platform joint `C_i`
//! iff `L = |C_i − O_i|` lies in the ring `[|b − c|, b + c]`, i.e. iff both factors
//!
//! `g_out(τ) = ((b + c)² − L²)/(b + c)²`, `g_in(τ) = (L² − (b − c)²)/(b + c)²`
//!
//! are non-negative. Both are analytic in τ (polynomials in `x(τ)`, `y(τ)`, `cos φ(τ)`,
//! `sin φ(τ)`), and the leg determinant satisfies (Heron's formula for the triangle
//! `O_iB_iC_i`)
//!
//! `det_i² = ((B_i − O_i) × (C_i − B_i))² = (b + c)⁴ g_out g_in / 4`.
//!
//! **Reachability** is checked exactly per leg and factor: on a grid fine enough for the
//! motion's frequencies, every local minimum of the factor (a sign change of its
//! derivative, computed exactly by the complex-step formula `g′(τ) = Im g(τ + iε)/ε`,
//! Squire and Trapp, *Using complex variables to estimate derivatives of real functions*,
//! SIAM Rev. 40, 1998) is located by bisection on `g′`; the motion is refused if a minimum
//! (or an end point) is below `−REACH_TOLERANCE`.
//!
//! **Crossings**: a leg meets its singularity where a factor has a zero, necessarily of
//! even order `2m` (the factor is non-negative), so `g ≈ a (τ − τ₀)^{2m}` and the
//! analytic continuation of the configuration has `det_i ∝ (τ − τ₀)^m`: the determinant
//! changes sign, and the working mode flips, iff `m` is odd. A minimum counts as a zero
//! when it is within `REACH_TOLERANCE` of 0 (a leg that only comes close to full reach
//! keeps its mode); `2m` is measured from `g(τ₀ + h) + g(τ₀ − h) ≈ 2a h^{2m}` at two
//! step sizes.

use crate::C64;
use crate::mechanism::rpr::{AnalyticMotion, MotionCoordinate};

/// A factor within this (relative to `(b + c)²`) of zero counts as zero: the leg is on
/// the boundary of its ring.
pub const REACH_TOLERANCE: f64 = 1e-12;

/// Smallest number of grid intervals of the scan.
const MIN_INTERVALS: usize = 4096;

/// Largest number of grid intervals of the scan.
const MAX_INTERVALS: usize = 1 << 18;

/// Complex step of the derivative.
const COMPLEX_STEP: f64 = 1e-20;

/// One leg: base joint, platform joint in the moving frame, link lengths.
#[derive(Clone, Copy, Debug)]
pub struct LegGeometry {
    /// Base joint `O_i`.
    pub base: [f64; 2],
    /// Platform joint in the moving frame.
    pub platform: [f64; 2],
    /// `|O_iB_i|`.
    pub proximal: f64,
    /// `|B_iC_i|`.
    pub distal: f64,
}

/// Which boundary of the ring.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// `L = b + c` (leg stretched).
    Outer,
    /// `L = |b − c|` (leg folded).
    Inner,
}

/// Where a leg leaves its ring.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Violation {
    /// τ of the deepest point found.
    pub tau: f64,
    /// The boundary crossed.
    pub boundary: Boundary,
}

/// A zero of a factor in the interior of the motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Touch {
    /// τ₀.
    pub tau: f64,
    /// The boundary touched.
    pub boundary: Boundary,
    /// The order `2m` of the zero.
    pub order: u32,
}

impl Touch {
    /// Whether the leg determinant changes sign there (`m` odd).
    pub fn flips(&self) -> bool {
        (self.order / 2) % 2 == 1
    }
}

impl LegGeometry {
    /// `L²(τ)` at complex τ.
    fn reach_sq(&self, motion: &AnalyticMotion, tau: C64) -> C64 {
        let (x, y, phi) = (
            motion.x.value_complex(tau),
            motion.y.value_complex(tau),
            motion.phi.value_complex(tau),
        );
        let (s, c) = (phi.sin(), phi.cos());
        let [qx, qy] = self.platform;
        let dx = x + c * qx - s * qy - self.base[0];
        let dy = y + s * qx + c * qy - self.base[1];
        dx * dx + dy * dy
    }

    /// The factor of `boundary` at complex τ (module documentation).
    fn factor_complex(&self, motion: &AnalyticMotion, boundary: Boundary, tau: C64) -> C64 {
        let outer = (self.proximal + self.distal).powi(2);
        let inner = (self.proximal - self.distal).powi(2);
        let l2 = self.reach_sq(motion, tau);
        match boundary {
            Boundary::Outer => (C64::new(outer, 0.0) - l2) / outer,
            Boundary::Inner => (l2 - inner) / outer,
        }
    }

    /// The factor and its derivative at real τ.
    fn factor(&self, motion: &AnalyticMotion, boundary: Boundary, tau: f64) -> (f64, f64) {
        let v = self.factor_complex(motion, boundary, C64::new(tau, COMPLEX_STEP));
        (v.re, v.im / COMPLEX_STEP)
    }
}

/// Bound on `|d/dτ|` of a coordinate on `[lo, hi]` (polynomial part) plus its cosine
/// frequencies weighted by amplitude, and its largest frequency.
fn rate(c: &MotionCoordinate, lo: f64, hi: f64) -> (f64, f64) {
    let r = lo.abs().max(hi.abs()).max(1.0);
    let polynomial: f64 = c
        .polynomial
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, a)| k as f64 * a.abs() * r.powi(k as i32 - 1))
        .sum();
    let cosine: f64 = c
        .cosines
        .iter()
        .map(|t| t.amplitude.abs() * t.frequency.abs())
        .sum();
    let frequency = c
        .cosines
        .iter()
        .map(|t| t.frequency.abs())
        .fold(0.0, f64::max);
    (polynomial + cosine, frequency)
}

/// Grid intervals for `motion`: enough for 32 per period of its fastest cosine and of the
/// platform's rotation, and per polynomial degree, between 4096 and 2¹⁸.
pub fn scan_intervals(motion: &AnalyticMotion) -> usize {
    let [lo, hi] = motion.tau_range;
    let width = hi - lo;
    let (phi_rate, phi_frequency) = rate(&motion.phi, lo, hi);
    let frequency = [&motion.x, &motion.y]
        .iter()
        .map(|c| rate(c, lo, hi).1)
        .fold(phi_frequency, f64::max)
        + phi_rate;
    let degree = [&motion.x, &motion.y, &motion.phi]
        .iter()
        .map(|c| c.polynomial.len())
        .max()
        .unwrap_or(0);
    let wanted = 32.0 * frequency * width / (2.0 * std::f64::consts::PI) + 64.0 * degree as f64;
    if !wanted.is_finite() {
        return MAX_INTERVALS;
    }
    (wanted.ceil() as usize).clamp(MIN_INTERVALS, MAX_INTERVALS)
}

/// Bisection on the derivative between `lo` (`g′ < 0`) and `hi` (`g′ > 0`).
fn minimum_between(f: impl Fn(f64) -> (f64, f64), mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid).1 < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The order `2m` of the zero of `f` at `tau` (see the module documentation): from
/// `s(h) = g(τ₀ + h) + g(τ₀ − h)` at `h` and `h/2`, with the smallest `h` (from
/// `width/100` down) at which `s(h/2)` is well above rounding.
fn zero_order(f: impl Fn(f64) -> f64, tau: f64, width: f64) -> u32 {
    let s = |h: f64| f(tau + h) + f(tau - h);
    let mut h = 0.01 * width;
    let mut order = 2;
    for _ in 0..12 {
        let (big, small) = (s(h), s(0.5 * h));
        if small.is_nan() || small <= 1e-9 {
            break;
        }
        let estimate = (big / small).log2();
        if estimate.is_finite() {
            order = (2.0 * (estimate / 2.0).round()).max(2.0) as u32;
        }
        h *= 0.25;
    }
    order
}

/// The reach of one leg along `motion`: the first point outside the ring (if any) and
/// the zeros of the factors in the open τ-range (module documentation).
pub fn leg_reach(leg: &LegGeometry, motion: &AnalyticMotion) -> Result<Vec<Touch>, Violation> {
    let [lo, hi] = motion.tau_range;
    let intervals = scan_intervals(motion);
    let tau_at = |j: usize| lo + (hi - lo) * j as f64 / intervals as f64;
    let mut touches = Vec::new();
    for boundary in [Boundary::Outer, Boundary::Inner] {
        let f = |tau: f64| leg.factor(motion, boundary, tau);
        let values: Vec<(f64, f64)> = (0..=intervals).map(|j| f(tau_at(j))).collect();
        let mut candidates: Vec<(f64, bool)> = Vec::new();
        if values[0].1 >= 0.0 {
            candidates.push((lo, false));
        }
        if values[intervals].1 <= 0.0 {
            candidates.push((hi, false));
        }
        for j in 0..intervals {
            let (a, b) = (values[j], values[j + 1]);
            if a.0 < -REACH_TOLERANCE {
                return Err(Violation {
                    tau: tau_at(j),
                    boundary,
                });
            }
            if a.1 < 0.0 && b.1 >= 0.0 {
                candidates.push((minimum_between(f, tau_at(j), tau_at(j + 1)), true));
            }
        }
        for (tau, interior) in candidates {
            let value = f(tau).0;
            if value < -REACH_TOLERANCE {
                return Err(Violation { tau, boundary });
            }
            let known = touches
                .iter()
                .any(|t: &Touch| (t.tau - tau).abs() <= 1e-9 * (hi - lo));
            if interior && value <= REACH_TOLERANCE && tau > lo && tau < hi && !known {
                touches.push(Touch {
                    tau,
                    boundary,
                    order: zero_order(|t| f(t).0, tau, hi - lo),
                });
            }
        }
    }
    touches.sort_by(|a, b| a.tau.total_cmp(&b.tau));
    Ok(touches)
}

//! Planar parallel manipulators: 3-RPR, 3-RRR and 3-PRRR designs, poses, motions, configurations, inverse kinematics and Jacobians.

pub mod rpr;

pub mod prrr;
pub mod rrr;
pub mod rrr_reach;

/// Largest magnitude accepted for any number of a design, motion or pose (coordinates,
/// lengths, angles, motion coefficients, τ range): `|v| ≤ 1e12`.
///
/// The distance problems square coordinates and multiply up to four of them (the
/// singularity polynomial has degree 4), so inputs of 1e12 keep every intermediate
/// below 1e48, far from overflow, while a coordinate near `f64::MAX` (e.g. 1e308)
/// overflows to infinity on the first product and poisons the run with NaN. Angles
/// beyond 1e12 rad are not representable to better than 1e-4 rad.
pub const MAX_INPUT_MAGNITUDE: f64 = 1e12;

/// Whether a finite or non-finite input number lies within ±[`MAX_INPUT_MAGNITUDE`]
/// (NaN and infinities do not).
pub fn within_input_range(value: f64) -> bool {
    value.abs() <= MAX_INPUT_MAGNITUDE
}

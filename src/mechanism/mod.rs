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

/// An input number (of a design, motion or pose) that is rejected; the message names
/// the field.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum InputNumberError {
    /// The number is NaN or infinite.
    #[error("{field}: not a finite number ({value})")]
    NotFinite {
        /// The field, e.g. `base[1].y`.
        field: String,
        /// The offending value.
        value: f64,
    },
    /// The number is finite but beyond ±[`MAX_INPUT_MAGNITUDE`].
    #[error("{field}: {value:e} is outside ±{max:e}", max = MAX_INPUT_MAGNITUDE)]
    OutOfRange {
        /// The field, e.g. `base[1].x` or `poses[0][0]`.
        field: String,
        /// The offending value.
        value: f64,
    },
}

/// Checks that `value` is finite and within ±[`MAX_INPUT_MAGNITUDE`]; the error names
/// `field()`.
pub fn check_input_number(
    field: impl FnOnce() -> String,
    value: f64,
) -> Result<(), InputNumberError> {
    if !value.is_finite() {
        return Err(InputNumberError::NotFinite {
            field: field(),
            value,
        });
    }
    if !within_input_range(value) {
        return Err(InputNumberError::OutOfRange {
            field: field(),
            value,
        });
    }
    Ok(())
}

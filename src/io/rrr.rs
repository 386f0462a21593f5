//! 3-RRR design files (docs/theory.md §10):
//!
//! ```json
//! {"base": [[x, y], [x, y], [x, y]],
//!  "proximal": [b1, b2, b3], "distal": [c1, c2, c3],
//!  "platform": [[x, y], [x, y], [x, y]],
//!  "working_modes": [1, 1, -1]}
//! ```
//!
//! Base joints `O_i` in the fixed frame, link lengths `|O_iB_i|` and `|B_iC_i|`, platform
//! joints `C_i` in the moving frame (origin = operation point), and the working mode
//! σ_i ∈ {+1, −1} of each leg at the start of the motion (optional, default all +1; see
//! [`crate::mechanism::rrr::ElbowMode`]). Motions use the 3-RPR motion format
//! ([`super::rpr::load_motion`]). Every error names the file and the field.

use super::rpr::{FieldError, FileError, fixed_numbers, read_json};
use crate::mechanism::rrr::{ElbowMode, POSITIVE_MODES, Point, RrrDesign, RrrError, WorkingModes};
use serde_json::Value;
use std::path::Path;

/// Errors of reading a 3-RRR design file: the 3-RPR loaders' error type (read, JSON,
/// field, and [`FileError::InvalidRrr`] for a well-formed but invalid design).
pub type RrrFileError = FileError;

/// A field-level error without the file name.
#[derive(Debug, Clone, PartialEq)]
pub enum RrrParseError {
    /// Missing field, wrong type or length (field, reason).
    Field(String, String),
    /// The numbers are fine but the design is invalid.
    Invalid(RrrError),
}

fn field(name: &str, reason: impl Into<String>) -> RrrParseError {
    RrrParseError::Field(name.to_string(), reason.into())
}

impl From<FieldError> for RrrParseError {
    fn from(error: FieldError) -> Self {
        RrrParseError::Field(error.field, error.reason)
    }
}

fn points(value: &Value, name: &str) -> Result<[Point; 3], RrrParseError> {
    let items = value
        .as_array()
        .ok_or_else(|| field(name, format!("expected 3 points [x, y], got {value}")))?;
    if items.len() != 3 {
        return Err(field(
            name,
            format!("expected 3 points [x, y], got {} elements", items.len()),
        ));
    }
    let mut out = [Point::zeros(); 3];
    for (i, item) in items.iter().enumerate() {
        let [x, y] = fixed_numbers::<2>(item, &format!("{name}[{i}]"))?;
        out[i] = Point::new(x, y);
    }
    Ok(out)
}

/// Design and initial working modes from a parsed JSON tree (module documentation).
pub fn rrr_design_from_json(value: &Value) -> Result<(RrrDesign, WorkingModes), RrrParseError> {
    const KEYS: [&str; 5] = ["base", "proximal", "distal", "platform", "working_modes"];
    let map = value
        .as_object()
        .ok_or_else(|| field("(top level)", format!("expected an object, got {value}")))?;
    if let Some(unknown) = map.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(field(
            unknown,
            format!("unknown field (expected one of {})", KEYS.join(", ")),
        ));
    }
    let required = |key: &str| map.get(key).ok_or_else(|| field(key, "missing field"));
    let base = points(required("base")?, "base")?;
    let platform = points(required("platform")?, "platform")?;
    let proximal = fixed_numbers::<3>(required("proximal")?, "proximal")?;
    let distal = fixed_numbers::<3>(required("distal")?, "distal")?;
    let mut modes = POSITIVE_MODES;
    if let Some(list) = map.get("working_modes") {
        let values = fixed_numbers::<3>(list, "working_modes")?;
        for (leg, v) in values.iter().enumerate() {
            modes[leg] = match *v {
                1.0 => ElbowMode::Positive,
                -1.0 => ElbowMode::Negative,
                other => {
                    return Err(field(
                        &format!("working_modes[{leg}]"),
                        format!("expected 1 or -1, got {other}"),
                    ));
                }
            };
        }
    }
    let design =
        RrrDesign::new(base, proximal, distal, platform).map_err(RrrParseError::Invalid)?;
    Ok((design, modes))
}

/// Loads and validates a 3-RRR design file.
pub fn load_rrr_design(path: impl AsRef<Path>) -> Result<(RrrDesign, WorkingModes), RrrFileError> {
    let path = path.as_ref();
    let value = read_json(path)?;
    rrr_design_from_json(&value).map_err(|e| match e {
        RrrParseError::Field(field, reason) => RrrFileError::Field {
            path: path.to_path_buf(),
            field,
            reason,
        },
        RrrParseError::Invalid(error) => RrrFileError::InvalidRrr {
            path: path.to_path_buf(),
            error,
        },
    })
}

//! 3-RPR design and motion files (docs/theory.md §1.1).
//!
//! - Design: `{"base": [[x, y], [x, y], [x, y]], "platform": [[x, y], [x, y], [x, y]]}`
//!   (base anchors in the fixed frame, platform anchors in the moving frame).
//! - Motion, either an explicit pose list `{"poses": [[x, y, phi], …]}` or an analytic
//!   motion `{"tau_range": [t0, t1], "x": C, "y": C, "phi": C}` where each coordinate
//!   `C = {"polynomial": [c0, c1, …], "cosines": [[A, ω, θ], …]}` means
//!   `Σ c_k τ^k + Σ A cos(ω τ + θ)` (both lists optional). Angles in radians.
//!
//! Loading reads JSON into a tree first and then walks it field by field, so every
//! error names the file and the field (`design.json: platform[1]: expected an array
//! of 2 numbers, got 3 elements`).

use crate::mechanism::rpr::{
    AnalyticMotion, CosineTerm, Design, Motion, MotionCoordinate, Pose, PoseList, RprError,
};
use serde_json::Value;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Errors of reading design and motion files; each names the file and the field.
#[derive(Debug, Error)]
pub enum FileError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not valid JSON.
    #[error("{path}: malformed JSON: {source}")]
    Json {
        /// The file.
        path: PathBuf,
        /// The parser's error (with line and column).
        source: serde_json::Error,
    },
    /// A field is missing or has the wrong shape.
    #[error("{path}: {field}: {reason}")]
    Field {
        /// The file.
        path: PathBuf,
        /// The field, e.g. `base[2]`.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// The values are well-formed but the design or motion is invalid. The validation
    /// error is part of the message and deliberately not an error source, so that a
    /// printed error chain states it once.
    #[error("{path}: {error}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The validation error (names the field).
        error: RprError,
    },
    /// The values are well-formed but the 3-RRR design is invalid (the validation error
    /// is part of the message, not an error source, as for [`FileError::Invalid`]).
    #[error("{path}: {error}")]
    InvalidRrr {
        /// The file.
        path: PathBuf,
        /// The validation error (names the field).
        error: crate::mechanism::rrr::RrrError,
    },
}

/// A field-level error without the file name (attached by the loaders).
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// The field path.
    pub field: String,
    /// What is wrong.
    pub reason: String,
}

fn field_error(field: &str, reason: impl Into<String>) -> FieldError {
    FieldError {
        field: field.to_string(),
        reason: reason.into(),
    }
}

fn describe(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn number(value: &Value, field: &str) -> Result<f64, FieldError> {
    match value.as_f64() {
        Some(v) if v.is_finite() => Ok(v),
        Some(v) => Err(field_error(field, format!("not a finite number ({v})"))),
        None => Err(field_error(
            field,
            format!("expected a number, got {}", describe(value)),
        )),
    }
}

fn array<'a>(value: &'a Value, field: &str) -> Result<&'a Vec<Value>, FieldError> {
    value
        .as_array()
        .ok_or_else(|| field_error(field, format!("expected an array, got {}", describe(value))))
}

/// An array of exactly `N` finite numbers (the 3-RPR and 3-RRR loaders' shared reader).
pub(super) fn fixed_numbers<const N: usize>(
    value: &Value,
    field: &str,
) -> Result<[f64; N], FieldError> {
    let items = array(value, field)?;
    if items.len() != N {
        return Err(field_error(
            field,
            format!(
                "expected an array of {N} numbers, got {} elements",
                items.len()
            ),
        ));
    }
    let mut out = [0.0; N];
    for (k, item) in items.iter().enumerate() {
        out[k] = number(item, &format!("{field}[{k}]"))?;
    }
    Ok(out)
}

fn object<'a>(
    value: &'a Value,
    field: &str,
    allowed: &[&str],
) -> Result<&'a serde_json::Map<String, Value>, FieldError> {
    let map = value.as_object().ok_or_else(|| {
        field_error(
            field,
            format!("expected an object, got {}", describe(value)),
        )
    })?;
    for key in map.keys() {
        if !allowed.contains(&key.as_str()) {
            let name = if field.is_empty() {
                key.clone()
            } else {
                format!("{field}.{key}")
            };
            return Err(field_error(
                &name,
                format!("unknown field (expected one of: {})", allowed.join(", ")),
            ));
        }
    }
    Ok(map)
}

fn required<'a>(
    map: &'a serde_json::Map<String, Value>,
    parent: &str,
    key: &str,
) -> Result<&'a Value, FieldError> {
    let name = if parent.is_empty() {
        key.to_string()
    } else {
        format!("{parent}.{key}")
    };
    map.get(key)
        .ok_or_else(|| field_error(&name, "missing field"))
}

/// Reads the three anchors of `key` from a design object.
fn anchors(map: &serde_json::Map<String, Value>, key: &str) -> Result<[[f64; 2]; 3], FieldError> {
    let value = required(map, "", key)?;
    let items = array(value, key)?;
    if items.len() != 3 {
        return Err(field_error(
            key,
            format!("expected 3 anchors [x, y], got {}", items.len()),
        ));
    }
    let mut out = [[0.0; 2]; 3];
    for (i, item) in items.iter().enumerate() {
        out[i] = fixed_numbers::<2>(item, &format!("{key}[{i}]"))?;
    }
    Ok(out)
}

/// Either a field-level error or a validation error.
#[derive(Debug, Clone, PartialEq)]
pub enum ParseError {
    /// Missing field, wrong type or length, non-finite number.
    Field(FieldError),
    /// The numbers are fine but the design or motion is invalid.
    Invalid(RprError),
}

impl From<FieldError> for ParseError {
    fn from(e: FieldError) -> Self {
        ParseError::Field(e)
    }
}

/// Design from a parsed JSON tree (see the module documentation for the format).
pub fn design_from_json(value: &Value) -> Result<Design, ParseError> {
    let map = object(value, "", &["base", "platform"])?;
    let base = anchors(map, "base")?;
    let platform = anchors(map, "platform")?;
    Design::new(base, platform).map_err(ParseError::Invalid)
}

fn coordinate(value: &Value, field: &str) -> Result<MotionCoordinate, FieldError> {
    let map = object(value, field, &["polynomial", "cosines"])?;
    let mut out = MotionCoordinate::default();
    if let Some(poly) = map.get("polynomial") {
        let name = format!("{field}.polynomial");
        for (k, c) in array(poly, &name)?.iter().enumerate() {
            out.polynomial.push(number(c, &format!("{name}[{k}]"))?);
        }
    }
    if let Some(cosines) = map.get("cosines") {
        let name = format!("{field}.cosines");
        for (j, t) in array(cosines, &name)?.iter().enumerate() {
            out.cosines.push(CosineTerm::from(fixed_numbers::<3>(
                t,
                &format!("{name}[{j}]"),
            )?));
        }
    }
    Ok(out)
}

/// Motion from a parsed JSON tree (see the module documentation for the formats).
pub fn motion_from_json(value: &Value) -> Result<Motion, ParseError> {
    let map = value.as_object().ok_or_else(|| {
        field_error(
            "",
            format!(
                "expected an object with `poses` or `tau_range`, got {}",
                describe(value)
            ),
        )
    })?;
    let motion = if map.contains_key("poses") {
        object(value, "", &["poses"])?;
        let items = array(&map["poses"], "poses")?;
        let mut poses = Vec::with_capacity(items.len());
        for (j, item) in items.iter().enumerate() {
            poses.push(Pose::from(fixed_numbers::<3>(
                item,
                &format!("poses[{j}]"),
            )?));
        }
        Motion::Poses(PoseList { poses })
    } else if map.contains_key("tau_range") {
        object(value, "", &["tau_range", "x", "y", "phi"])?;
        Motion::Analytic(AnalyticMotion {
            tau_range: fixed_numbers::<2>(&map["tau_range"], "tau_range")?,
            x: coordinate(required(map, "", "x")?, "x")?,
            y: coordinate(required(map, "", "y")?, "y")?,
            phi: coordinate(required(map, "", "phi")?, "phi")?,
        })
    } else {
        return Err(ParseError::Field(field_error(
            "poses",
            "missing field (a motion has either `poses` or `tau_range`, `x`, `y`, `phi`)",
        )));
    };
    motion.validate().map_err(ParseError::Invalid)?;
    Ok(motion)
}

/// Reads a JSON file into a tree (errors name the file, with line and column).
pub(crate) fn read_json(path: &Path) -> Result<Value, FileError> {
    let text = std::fs::read_to_string(path).map_err(|source| FileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| FileError::Json {
        path: path.to_path_buf(),
        source,
    })
}

fn attach(path: &Path, error: ParseError) -> FileError {
    match error {
        ParseError::Field(FieldError { field, reason }) => FileError::Field {
            path: path.to_path_buf(),
            field: if field.is_empty() {
                "(top level)".into()
            } else {
                field
            },
            reason,
        },
        ParseError::Invalid(error) => FileError::Invalid {
            path: path.to_path_buf(),
            error,
        },
    }
}

/// Loads and validates a design file.
pub fn load_design(path: impl AsRef<Path>) -> Result<Design, FileError> {
    let path = path.as_ref();
    design_from_json(&read_json(path)?).map_err(|e| attach(path, e))
}

/// Loads and validates a motion file.
pub fn load_motion(path: impl AsRef<Path>) -> Result<Motion, FileError> {
    let path = path.as_ref();
    motion_from_json(&read_json(path)?).map_err(|e| attach(path, e))
}

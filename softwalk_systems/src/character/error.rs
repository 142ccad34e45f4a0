//! Typed errors raised when building a character or its path.

use thiserror::Error;

/// Why a character description, balance setting or walk path was refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CharacterError {
    /// A field of a description was NaN, infinite or out of its allowed range.
    #[error("invalid character field `{field}`: {reason}")]
    InvalidField {
        /// The field's name, as written in a scene file.
        field: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// A walk path parameter was refused.
    #[error("invalid walk path `{field}`: {reason}")]
    InvalidPath {
        /// The parameter's name.
        field: &'static str,
        /// Why it was refused.
        reason: String,
    },
}

/// Checks that `value` is finite and inside `[min, max]`, naming `field` otherwise.
pub(crate) fn check_range(
    field: &'static str,
    value: f32,
    min: f32,
    max: f32,
) -> Result<f32, CharacterError> {
    if !value.is_finite() || value < min || value > max {
        return Err(CharacterError::InvalidField {
            field,
            reason: format!("{value} is not a finite number in [{min}, {max}]"),
        });
    }
    Ok(value)
}

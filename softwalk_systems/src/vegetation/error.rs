//! Errors of the vegetation module.

use thiserror::Error;

/// Why a grass patch could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum VegetationError {
    /// A grass setting is out of its valid range.
    #[error("grass setting `{field}` = {value} is invalid: {reason}")]
    BadSetting {
        /// Name of the field in `GrassSettings` or `PlatformSettings`.
        field: &'static str,
        /// The offending value.
        value: f64,
        /// What the field must satisfy.
        reason: &'static str,
    },
    /// The patch area is empty, inverted or not finite.
    #[error("grass patch area {min:?}..{max:?} is empty or not finite")]
    BadArea {
        /// Requested minimum corner (x, z).
        min: [f32; 2],
        /// Requested maximum corner (x, z).
        max: [f32; 2],
    },
    /// Density times area asks for more blades than a patch may hold.
    #[error("grass patch would hold {requested} blades, more than the limit of {limit}")]
    TooManyBlades {
        /// Blades asked for (density x area).
        requested: f64,
        /// The limit.
        limit: usize,
    },
    /// No ground (or a non-finite height) under a blade root.
    #[error("no ground under grass blade root at x = {x}, z = {z}")]
    NoGround {
        /// World X of the root.
        x: f32,
        /// World Z of the root.
        z: f32,
    },
}

/// Fails with [`VegetationError::BadSetting`] unless `value` is finite and `ok`.
pub(crate) fn check(
    field: &'static str,
    value: f32,
    reason: &'static str,
    ok: impl Fn(f32) -> bool,
) -> Result<(), VegetationError> {
    if value.is_finite() && ok(value) {
        Ok(())
    } else {
        Err(VegetationError::BadSetting {
            field,
            value: value as f64,
            reason,
        })
    }
}

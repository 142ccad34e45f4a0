//! Typed errors of the terrain module.

use engine::geom::GeomError;
use thiserror::Error;

/// Why a terrain, a material or a carving input was refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum TerrainError {
    /// A construction or step parameter was NaN, infinite, negative or out of range.
    #[error("invalid terrain parameter `{name}`: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// A material field is out of range.
    #[error("material `{material}`: invalid field `{field}`: {reason}")]
    InvalidMaterial {
        /// The material's name.
        material: String,
        /// The offending field.
        field: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// No material of that name is in the table.
    #[error("unknown material `{name}` (known: {known})")]
    UnknownMaterial {
        /// The name asked for.
        name: String,
        /// The names in the table, comma separated.
        known: String,
    },
    /// A material id does not index the table.
    #[error("material id {id} is not in the table ({len} materials)")]
    UnknownMaterialId {
        /// The id asked for.
        id: u8,
        /// How many materials the table holds.
        len: usize,
    },
    /// A second material with the same name was added.
    #[error("material `{0}` is already in the table")]
    DuplicateMaterial(String),
    /// The table already holds 256 materials (ids are bytes).
    #[error("the material table is full (256 materials)")]
    TooManyMaterials,
    /// The underlying height grid refused its parameters.
    #[error(transparent)]
    Grid(#[from] GeomError),
}

/// Refuses a non-finite value or one below `min`, naming the parameter.
pub(crate) fn check_at_least(name: &'static str, value: f32, min: f32) -> Result<(), TerrainError> {
    if value.is_finite() && value >= min {
        Ok(())
    } else {
        Err(TerrainError::InvalidParameter {
            name,
            reason: format!("{value} must be finite and >= {min}"),
        })
    }
}

/// Refuses a non-finite value, naming the parameter.
pub(crate) fn check_finite(name: &'static str, value: f32) -> Result<(), TerrainError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(TerrainError::InvalidParameter {
            name,
            reason: format!("{value} is not finite"),
        })
    }
}

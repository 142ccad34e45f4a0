use thiserror::Error;

/// Errors raised by geometry construction and queries.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GeomError {
    /// A parameter was NaN, infinite, zero or negative where that is not allowed.
    #[error("invalid parameter `{name}`: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// A grid would need more samples than [`crate::geom::MAX_GRID_SAMPLES`]; refused before allocating.
    #[error("grid of {nx} x {nz} samples is too large (limit {limit} samples)")]
    GridTooLarge {
        /// Samples along X.
        nx: usize,
        /// Samples along Z.
        nz: usize,
        /// The maximum number of samples.
        limit: usize,
    },
}

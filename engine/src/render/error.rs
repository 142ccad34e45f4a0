use thiserror::Error;

/// Errors raised when building cameras, renderers or terrain renderers.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RenderError {
    /// A parameter was NaN, infinite, zero, negative or out of range.
    #[error("invalid render parameter `{name}`: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The renderer's own rayon thread pool could not be built.
    #[error("cannot build a render thread pool of {threads} threads: {reason}")]
    ThreadPool {
        /// Requested number of threads.
        threads: usize,
        /// The reason given by rayon.
        reason: String,
    },
}

/// Refuses a non-finite or non-positive value, naming the parameter.
pub(crate) fn positive(name: &'static str, value: f32) -> Result<f32, RenderError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(RenderError::InvalidParameter {
            name,
            reason: format!("{value} must be finite and > 0"),
        })
    }
}

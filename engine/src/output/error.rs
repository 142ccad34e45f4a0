//! The error type of image and animation output.

use std::io;
use std::path::PathBuf;

use thiserror::Error;

use crate::io::WriteError;

/// An image or animation could not be written. Every variant names the file.
#[derive(Debug, Error)]
pub enum OutputError {
    /// Writing a whole file atomically failed (I/O or encoding).
    #[error(transparent)]
    Write(#[from] WriteError),
    /// An I/O operation on a streaming writer's file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The target file.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: io::Error,
    },
    /// The encoder rejected the data.
    #[error("cannot encode {path}: {message}")]
    Encode {
        /// The target file.
        path: PathBuf,
        /// What the encoder reported.
        message: String,
    },
    /// A frame's size differs from the first frame of the animation.
    #[error(
        "frame {index} of {path} is {found_width}x{found_height}, expected {expected_width}x{expected_height}"
    )]
    FrameSize {
        /// The target file.
        path: PathBuf,
        /// Zero-based index of the offending frame.
        index: usize,
        /// Width of the first frame.
        expected_width: u32,
        /// Height of the first frame.
        expected_height: u32,
        /// Width of the offending frame.
        found_width: u32,
        /// Height of the offending frame.
        found_height: u32,
    },
    /// A parameter is out of range for the format.
    #[error("invalid {parameter} for {path}: {reason}")]
    InvalidParameter {
        /// The target file.
        path: PathBuf,
        /// The parameter's name.
        parameter: &'static str,
        /// Why it was rejected.
        reason: String,
    },
    /// An animation was finished without any frame.
    #[error("no frames were pushed to {path}")]
    NoFrames {
        /// The target file.
        path: PathBuf,
    },
}

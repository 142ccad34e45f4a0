use std::path::PathBuf;

use thiserror::Error;

use crate::anim::AnimError;

/// Why a BVH file was refused. Each variant names the file.
#[derive(Debug, Error)]
pub enum BvhError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file is larger than the loader accepts; refused before reading.
    #[error("{path}: {bytes} bytes, over the limit of {limit}")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// A word other than the grammar allows, or the file ends early.
    #[error("{path}:{line}: expected {expected}, found {found}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// What the grammar allows there.
        expected: String,
        /// What was there (`end of file` at the end).
        found: String,
    },
    /// A channel name other than `X/Y/Z` + `position/rotation`.
    #[error("{path}:{line}: unknown channel {name:?}")]
    BadChannel {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The name found.
        name: String,
    },
    /// More joints, deeper nesting or more channels than the loader accepts.
    #[error("{path}:{line}: {what} over the limit of {limit}")]
    Limit {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// What is too many.
        what: String,
        /// The limit.
        limit: usize,
    },
    /// The motion holds a different number of values than frames times channels.
    #[error("{path}: {frames} frames of {channels} channels need {needed} values, found {found}")]
    FrameData {
        /// The file.
        path: PathBuf,
        /// Frames declared.
        frames: usize,
        /// Channels per frame.
        channels: usize,
        /// Values needed.
        needed: usize,
        /// Values found (counting stops one past `needed`).
        found: usize,
    },
    /// A number is NaN or infinite, or the frame time is not positive.
    #[error("{path}:{line}: bad number: {what}")]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// Which value and what is wrong with it.
        what: String,
    },
    /// The skeleton or clip built from the file was refused.
    #[error("{path}: {source}")]
    Anim {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: AnimError,
    },
}

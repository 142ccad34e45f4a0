use std::path::PathBuf;

use thiserror::Error;

use crate::geom::GeomError;
use crate::io::WriteError;

/// Why an asset could not be loaded or saved. Each variant names the file.
#[derive(Debug, Error)]
pub enum AssetError {
    /// The file does not exist.
    #[error("{path}: file not found")]
    Missing {
        /// The file.
        path: PathBuf,
    },
    /// The file exists but could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The OBJ text could not be parsed.
    #[error("{path}: malformed OBJ: {reason}")]
    MalformedObj {
        /// The file.
        path: PathBuf,
        /// What was wrong.
        reason: String,
    },
    /// A face refers to a vertex, normal or texture coordinate that does not exist.
    #[error("{path}: face index out of range: {reason}")]
    IndexOutOfRange {
        /// The file.
        path: PathBuf,
        /// Which kind of index.
        reason: String,
    },
    /// The file holds no triangle.
    #[error("{path}: the mesh has no triangles")]
    EmptyMesh {
        /// The file.
        path: PathBuf,
    },
    /// A coordinate is NaN or infinite.
    #[error("{path}: {what} is not finite")]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Which value, e.g. `vertex 3 of object "hip"`.
        what: String,
    },
    /// The PNG is not single-channel grayscale.
    #[error("{path}: not a grayscale PNG (colour type {found})")]
    NotGrayscale {
        /// The file.
        path: PathBuf,
        /// The colour type found.
        found: String,
    },
    /// The PNG's bit depth is neither 8 nor 16.
    #[error("{path}: unsupported bit depth {depth} (need 8 or 16)")]
    UnsupportedBitDepth {
        /// The file.
        path: PathBuf,
        /// The bit depth found.
        depth: u8,
    },
    /// The PNG is truncated or corrupt.
    #[error("{path}: truncated or corrupt PNG: {reason}")]
    CorruptPng {
        /// The file.
        path: PathBuf,
        /// The decoder's message.
        reason: String,
    },
    /// The image has more pixels than a height grid may hold; refused before decoding.
    #[error(
        "{path}: {width} x {height} pixels is too large for a height grid (limit {limit} samples)"
    )]
    GridTooLarge {
        /// The file.
        path: PathBuf,
        /// Image width in pixels.
        width: u32,
        /// Image height in pixels.
        height: u32,
        /// The maximum number of samples.
        limit: usize,
    },
    /// A parameter or the resulting grid was refused.
    #[error("{path}: {source}")]
    Geometry {
        /// The file.
        path: PathBuf,
        /// The geometry error.
        #[source]
        source: GeomError,
    },
    /// The output file could not be written (nothing was left half-written).
    #[error(transparent)]
    Write(#[from] WriteError),
}

impl AssetError {
    /// The error for a file that could not be opened or read: [`AssetError::Missing`]
    /// when it does not exist, [`AssetError::Read`] otherwise.
    pub(crate) fn reading(path: &std::path::Path, source: std::io::Error) -> AssetError {
        if source.kind() == std::io::ErrorKind::NotFound {
            AssetError::Missing {
                path: path.to_path_buf(),
            }
        } else {
            AssetError::Read {
                path: path.to_path_buf(),
                source,
            }
        }
    }
}

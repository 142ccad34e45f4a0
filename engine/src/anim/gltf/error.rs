use std::path::PathBuf;

use thiserror::Error;

use crate::anim::AnimError;

/// Why a glTF file was refused. Each variant names the file, and the part of it
/// at fault (e.g. `mesh 0 primitive 1 WEIGHTS_0`, `animation "walk" channel 3`).
#[derive(Debug, Error)]
pub enum GltfError {
    /// The file, or a buffer file it names, could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file or a buffer is larger than the loader accepts; refused before reading.
    #[error("{path}: {part} is {bytes} bytes, over the limit of {limit}")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Which part.
        part: String,
        /// Its size.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// Not glTF 2.0 JSON or GLB, or it breaks the glTF schema.
    #[error("{path}: not a valid glTF 2.0 file: {reason}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// The parser's or validator's message.
        reason: String,
    },
    /// A feature this loader does not read (sparse accessors, non-triangle
    /// primitives, remote URIs, ...).
    #[error("{path}: {part}: unsupported: {reason}")]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// Which part.
        part: String,
        /// What is not supported.
        reason: String,
    },
    /// No node has both a mesh and a skin, or the skinned mesh lacks joints or weights.
    #[error("{path}: missing skin: {reason}")]
    MissingSkin {
        /// The file.
        path: PathBuf,
        /// What is missing.
        reason: String,
    },
    /// A vertex's weights do not sum to about 1.
    #[error("{path}: {part}: vertex {vertex}'s weights sum to {sum}, not 1")]
    WeightSum {
        /// The file.
        path: PathBuf,
        /// Which part.
        part: String,
        /// The vertex.
        vertex: usize,
        /// The sum.
        sum: f32,
    },
    /// A vertex names a joint past the end of the skin's joint list.
    #[error("{path}: {part}: vertex {vertex} uses joint {joint}, but the skin has {joints}")]
    JointOutOfRange {
        /// The file.
        path: PathBuf,
        /// Which part.
        part: String,
        /// The vertex.
        vertex: usize,
        /// The joint index.
        joint: usize,
        /// The skin's joint count.
        joints: usize,
    },
    /// An animation none of whose channels animates a joint of the skin.
    #[error("{path}: {part}: the clip targets no joint of the skin")]
    ClipTargetsNoJoint {
        /// The file.
        path: PathBuf,
        /// Which animation.
        part: String,
    },
    /// A number is NaN or infinite.
    #[error("{path}: {part}: element {index} is not finite")]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Which accessor or node.
        part: String,
        /// The element.
        index: usize,
    },
    /// An accessor or buffer view reaches past the end of its data.
    #[error("{path}: {part}: needs {needed} bytes, but only {available} are there")]
    BufferTooShort {
        /// The file.
        path: PathBuf,
        /// Which accessor, view or buffer.
        part: String,
        /// Bytes needed.
        needed: u64,
        /// Bytes available.
        available: u64,
    },
    /// Anything else that makes the file unusable (wrong accessor type, node
    /// cycle, keys out of order, ...).
    #[error("{path}: {part}: {reason}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// Which part.
        part: String,
        /// What is wrong.
        reason: String,
    },
}

impl GltfError {
    /// The [`GltfError`] for an [`AnimError`] found while building `part`.
    pub(super) fn from_anim(path: &std::path::Path, part: &str, error: AnimError) -> GltfError {
        let path = path.to_path_buf();
        let part = part.to_string();
        match error {
            AnimError::WeightSum { vertex, sum } => GltfError::WeightSum {
                path,
                part,
                vertex,
                sum,
            },
            AnimError::JointOutOfRange {
                vertex,
                joint,
                joints,
            } => GltfError::JointOutOfRange {
                path,
                part,
                vertex,
                joint,
                joints,
            },
            other => GltfError::Invalid {
                path,
                part,
                reason: other.to_string(),
            },
        }
    }
}

//! Why a character model could not be loaded or driven.

use std::path::PathBuf;

use engine::anim::gltf::GltfError;
use engine::anim::{AnimError, RigError};
use thiserror::Error;

/// Why a rigged model was refused as a character.
#[derive(Debug, Error)]
pub enum ModelError {
    /// The file could not be read or is not a valid rigged glTF.
    #[error("{}: {source}", path.display())]
    Load {
        /// The file.
        path: PathBuf,
        /// The loader's error (it names the part of the file).
        #[source]
        source: Box<GltfError>,
    },
    /// The legs, spine or head are not found through the bone map.
    #[error("{0}")]
    Rig(#[from] RigError),
    /// The rest pose could not be skinned.
    #[error("the rest pose: {0}")]
    Skin(#[from] AnimError),
    /// The rest pose is not a standing character (e.g. hips below the soles).
    #[error("the rest pose is not a standing character: {reason}")]
    Shape {
        /// What is wrong with it.
        reason: String,
    },
}

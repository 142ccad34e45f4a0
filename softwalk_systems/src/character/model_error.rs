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
    /// The standing figure's height fits no length unit (metres, centimetres,
    /// millimetres) for a 0.5 to 3 m tall character.
    #[error(
        "the model stands {height:.2} units tall: not 0.5-3 m in metres, centimetres or millimetres; \
         scale it to metres (or put a scale on its armature's root node)"
    )]
    Units {
        /// The rest pose's height in file units.
        height: f32,
    },
    /// The rest pose lies down: wider than tall, as a Z-up model whose root
    /// does not turn it to Y up.
    #[error(
        "the rest pose lies down ({width:.2} wide, {height:.2} tall along +Y): glTF is Y-up; \
         rotate the armature's root node -90 degrees about X if the model is Z-up"
    )]
    LyingDown {
        /// The rest pose's largest horizontal extent, file units.
        width: f32,
        /// The rest pose's vertical extent, file units.
        height: f32,
    },
    /// The rest pose is not a standing character (e.g. hips below the soles).
    #[error("the rest pose is not a standing character: {reason}")]
    Shape {
        /// What is wrong with it.
        reason: String,
    },
}

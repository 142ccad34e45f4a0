use super::{Clip, Skeleton, SkinnedMesh};

/// A rigged, skinned character as a glTF file holds it.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The skin's joints and their ancestors, parents first.
    pub skeleton: Skeleton,
    /// The skinned mesh, in its bind pose, with joint indices into `skeleton`.
    pub mesh: SkinnedMesh,
    /// The animation clips that animate at least one joint.
    pub clips: Vec<Clip>,
}

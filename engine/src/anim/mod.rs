//! Character animation: skeletons, skinned meshes, clips, poses, CPU skinning,
//! and their import from glTF 2.0 and BVH mocap.
//!
//! The data model, one concept per file:
//! - [`Transform`]: translation, rotation, scale of one joint;
//! - [`Skeleton`] of [`Joint`]s (names, parents before children, rest local
//!   transforms, inverse bind matrices);
//! - [`Pose`]: local transforms of every joint, and their global matrices;
//! - [`Clip`] of [`Channel`]s, each sampled with an [`Interpolation`];
//! - [`SkinnedMesh`]: positions, normals, triangles, 4 joints and 4 weights per vertex,
//!   and its coarse copy for figures seen from afar ([`SkinnedMesh::clustered`]);
//! - [`skin`]: linear blend skinning on the CPU, parallel over vertices;
//! - [`Model`]: what a glTF file holds (skeleton, mesh, clips).
//!
//! Import: [`gltf::load_gltf`] and [`bvh::load_bvh`]. Rigs: a [`BoneMap`] names the
//! bones a rig uses for each [`BoneRole`]; [`RigChains`] are the legs and spine found
//! through it, and [`retarget`] moves a clip from one rig onto another by bone name.
//! [`WalkCycle`] reads a walk clip's period, duty factor, stride and phase from its
//! foot contacts.

#![forbid(unsafe_code)]

mod bone_map;
pub mod bvh;
mod channel;
mod clip;
mod error;
pub mod gltf;
mod interpolation;
mod model;
mod model_scale;
mod pose;
mod retarget;
mod rig;
mod skeleton;
mod skinned_lod;
mod skinned_mesh;
mod skinning;
mod transform;
mod walk_cycle;

pub use bone_map::{BoneMap, BoneRole, RigPreset};
pub use channel::{Channel, Property};
pub use clip::{Clip, Playback};
pub use error::AnimError;
pub use interpolation::Interpolation;
pub use model::Model;
pub use pose::Pose;
pub use retarget::{RetargetError, retarget};
pub use rig::{LegChain, RigChains, RigError};
pub use skeleton::{Joint, Skeleton};
pub use skinned_mesh::SkinnedMesh;
pub use skinning::{SkinnedVertices, skin, skin_matrices, skin_serial};
pub use transform::Transform;
pub use walk_cycle::{WalkCycle, WalkCycleError};

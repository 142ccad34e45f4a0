//! BVH motion-capture import: the hierarchy becomes a [`Skeleton`] (rest
//! rotations identity, rest translations the joint offsets) and the motion a
//! [`Clip`] sampled linearly between frames. A small parser of our own: the
//! format is a few keywords, and the `bvh_anim` crate has seen no release since 2020.

mod error;
mod hierarchy;
mod motion;
mod tokens;

use std::io::Read;
use std::path::Path;

use glam::Mat4;

pub use error::BvhError;

use crate::anim::{Clip, Joint, Skeleton, Transform};
use tokens::Tokens;

/// The largest BVH file the loader reads (256 MiB).
pub const MAX_BVH_BYTES: u64 = 256 << 20;

/// A BVH file's skeleton and motion.
#[derive(Debug, Clone, PartialEq)]
pub struct BvhClip {
    /// The hierarchy's joints (End Sites dropped), in file order.
    pub skeleton: Skeleton,
    /// The motion, named after the file's stem.
    pub clip: Clip,
    /// Seconds per frame.
    pub frame_time: f32,
    /// How many frames the file holds.
    pub frames: usize,
}

/// Loads a `.bvh` file.
pub fn load_bvh(path: &Path) -> Result<BvhClip, BvhError> {
    let read_error = |source| BvhError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(read_error)?;
    let bytes = file.metadata().map_err(read_error)?.len();
    if bytes > MAX_BVH_BYTES {
        return Err(BvhError::TooLarge {
            path: path.to_path_buf(),
            bytes,
            limit: MAX_BVH_BYTES,
        });
    }
    let mut text = String::with_capacity(bytes as usize);
    file.take(MAX_BVH_BYTES)
        .read_to_string(&mut text)
        .map_err(read_error)?;
    load_bvh_from_str(&text, path)
}

/// The hierarchy as a skeleton whose bind pose is its rest pose.
fn bind_skeleton(joints: &[hierarchy::BvhJoint]) -> Result<Skeleton, crate::anim::AnimError> {
    let unbound = Skeleton::new(
        joints
            .iter()
            .map(|j| Joint {
                name: j.name.clone(),
                parent: j.parent,
                rest: Transform::from_translation(j.offset),
                inverse_bind: Mat4::IDENTITY,
            })
            .collect(),
    )?;
    let globals = unbound.rest_globals();
    let bound = unbound
        .joints()
        .iter()
        .zip(globals)
        .map(|(j, global)| Joint {
            inverse_bind: global.inverse(),
            ..j.clone()
        })
        .collect();
    Skeleton::new(bound)
}

/// Like [`load_bvh`] on BVH text held in memory; `path` names it in errors and
/// its stem names the clip.
pub fn load_bvh_from_str(text: &str, path: &Path) -> Result<BvhClip, BvhError> {
    let mut tokens = Tokens::new(text, path);
    let joints = hierarchy::parse_hierarchy(&mut tokens)?;
    let channels: usize = joints.iter().map(|j| j.channels.len()).sum();
    let motion = motion::parse_motion(&mut tokens, channels, text.len())?;
    let anim_error = |source| BvhError::Anim {
        path: path.to_path_buf(),
        source,
    };
    let skeleton = bind_skeleton(&joints).map_err(anim_error)?;
    let clip_channels = motion::clip_channels(&joints, &motion).map_err(anim_error)?;
    let name = path
        .file_stem()
        .map_or_else(|| "bvh".to_string(), |s| s.to_string_lossy().into_owned());
    let clip = Clip::new(name, clip_channels, skeleton.len()).map_err(anim_error)?;
    Ok(BvhClip {
        skeleton,
        clip,
        frame_time: motion.frame_time,
        frames: motion.frames,
    })
}

//! [`ClipScratch`]: the buffers a [`super::ClipWalk`] samples its clip into,
//! kept by whoever plays it frame after frame so a frame allocates nothing.

use glam::Mat4;

/// The clip's local pose and global matrices, reused from call to call.
#[derive(Debug, Clone, Default)]
pub struct ClipScratch {
    /// The clip's local transforms at the played time.
    pub(super) pose: engine::anim::Pose,
    /// Their global matrices.
    pub(super) globals: Vec<Mat4>,
}

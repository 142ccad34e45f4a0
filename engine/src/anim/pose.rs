use glam::Mat4;

use super::{Skeleton, Transform};

/// The local transform of every joint of a skeleton, in the skeleton's order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pose {
    /// One local transform per joint.
    pub locals: Vec<Transform>,
}

impl Pose {
    /// Writes each joint's global matrix (parent's global times its local) into
    /// `out`, one per joint of `skeleton`. A joint missing from the pose keeps its
    /// rest transform.
    pub fn globals(&self, skeleton: &Skeleton, out: &mut Vec<Mat4>) {
        out.clear();
        out.reserve(skeleton.len());
        for (k, joint) in skeleton.joints().iter().enumerate() {
            let local = self.locals.get(k).unwrap_or(&joint.rest).to_mat4();
            let global = match joint.parent {
                // Parents come first, so out[parent] exists.
                Some(parent) => out[parent] * local,
                None => local,
            };
            out.push(global);
        }
    }
}
